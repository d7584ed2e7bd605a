"""Time check_realization (exact and randomized) against naive SymPy simplify.

Rows n = 2..5: a G of order n with symbolic coefficients, its controllable
canonical realization similarity-transformed by a fully symbolic n x n P
(n^2 independent symbols p_ij). G is, by --form,

  controller: K_0/(C_1 C_3) (z - eps_1)...(z - eps_n) / (z^n - K_1 z^(n-1) - ... - K_n)
              (the paper's G2 for n = 2);
  general:    (b_n z^n + ... + b_0) / (z^n - a_(n-1) z^(n-1) - ... - a_0).

Baseline, measured in the same run in a subprocess capped at --cap seconds:
sp.simplify(M (zI - F)^-1 H + N - G).

Rows n = 6..10: a fully symbolic P is too large to build (R.similar takes ~50 s
at n = 5), so there P is a random rational matrix and G keeps its symbolic
coefficients; these rows time the methods on large n (no baseline).

Run:  python benchmarks/checker.py [--cap SECONDS] [--form controller|general]
"""

from __future__ import annotations

import argparse
import math
import random
import time

import sympy as sp
from capped import capped

from symctl import DiscreteTF, check_realization, controllable_canonical
from symctl.symbols import C_1, C_3, gain_symbols, z


def transfer_function(n: int, form: str) -> sp.Expr:
    if form == "controller":
        K = gain_symbols(n)
        eps = [sp.Symbol(f"epsilon_{i}", real=True) for i in range(1, n + 1)]
        num = K[0] / (C_1 * C_3) * sp.Mul(*(z - e for e in eps))
        return num / (z**n - sum(K[k] * z ** (n - k) for k in range(1, n + 1)))
    a, b = sp.symbols(f"a_:{n}"), sp.symbols(f"b_:{n + 1}")
    return sum(b[i] * z**i for i in range(n + 1)) / (z**n - sum(a[i] * z**i for i in range(n)))


def symbolic_P(n: int) -> sp.Matrix:
    return sp.Matrix(n, n, lambda i, j: sp.Symbol(f"p_{i}{j}"))


def rational_P(n: int, seed: int) -> sp.Matrix:
    rng = random.Random(seed)
    while True:
        P = sp.Matrix(n, n, lambda i, j: sp.Rational(rng.randint(-9, 9), rng.randint(1, 4)))
        if P.det() != 0:
            return P


def naive(R, G: sp.Expr) -> bool:
    """The textbook check: simplify the difference of the two sides."""
    diff = sp.simplify(R.M * (z * sp.eye(R.n) - R.F).inv() * R.H + R.N - sp.Matrix([[G]]))
    return diff.is_zero_matrix


def exact(R, G: DiscreteTF) -> bool:
    return check_realization(R, G, "exact").ok


def confirmed(job, args: tuple, cap: float) -> float | None:
    """Seconds of ``job(*args)`` (capped), which must confirm the realization (return True)."""
    got = capped(job, args, cap)
    if got is None:
        return None
    seconds, verdict = got
    if verdict is False:
        raise SystemExit(f"{job.__name__}: a correct realization was not confirmed")
    return seconds


def time_row(n: int, form: str, P: sp.Matrix, cap: float, baseline: bool) -> list[str]:
    """One table row: build, exact (capped), randomized, naive (capped) and the speed-up."""
    G = transfer_function(n, form)
    start = time.perf_counter()
    tf = DiscreteTF.from_expr(G)
    R = controllable_canonical(tf).similar(P)
    build = time.perf_counter() - start
    start = time.perf_counter()
    randomized = check_realization(R, tf, "randomized", rng=n)
    t_random = time.perf_counter() - start
    if not randomized:
        raise SystemExit(f"n = {n}: a correct realization was rejected: {randomized}")
    t_exact = confirmed(exact, (R, tf), cap)
    t_naive = confirmed(naive, (R, G), cap) if baseline else None
    over = f"> {cap:g}"
    if not baseline:
        speed = "-"
    elif t_exact is None:
        speed = "?"
    elif t_naive is None:
        speed = f"> {cap / t_exact:.0f}x"
    else:
        speed = f"{t_naive / t_exact:.0f}x"
    return [
        f"{n}",
        f"{len(R.free_symbols | tf.free_symbols)}",
        f"{build:.3f}",
        over if t_exact is None else f"{t_exact:.3f}",
        f"{t_random:.3f}",
        f"2^{math.log2(randomized.error_bound):.0f}" if randomized.error_bound else "0",
        ("-" if not baseline else over) if t_naive is None else f"{t_naive:.2f}",
        speed,
    ]


WIDTHS = (3, 7, 8, 8, 10, 11, 14, 9)
HEADER = (
    "n",
    "symbols",
    "build",
    "exact",
    "randomized",
    "error bound",
    "naive simplify",
    "speed-up",
)


def fmt(cells) -> str:
    return " | ".join(f"{c:>{w}}" for c, w in zip(cells, WIDTHS, strict=True))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cap", type=float, default=60.0, help="time cap of exact/naive [s]")
    parser.add_argument("--form", choices=["controller", "general"], default="controller")
    parser.add_argument("--max-n", type=int, default=5, help="largest n with a symbolic P")
    parser.add_argument("--max-n-random", type=int, default=10, help="largest n, random P")
    args = parser.parse_args()
    lines = [f"G in {args.form} form", fmt(HEADER), "-" * 98]
    lines.append(f"fully symbolic n x n P, n = 2..{args.max_n}")
    print(*lines, sep="\n", flush=True)
    for n in range(2, args.max_n + 1):
        lines.append(fmt(time_row(n, args.form, symbolic_P(n), args.cap, baseline=True)))
        print(lines[-1], flush=True)
    lines.append(f"random rational P, n = {args.max_n + 1}..{args.max_n_random} (no baseline)")
    print(lines[-1], flush=True)
    for n in range(args.max_n + 1, args.max_n_random + 1):
        lines.append(fmt(time_row(n, args.form, rational_P(n, seed=n), args.cap, baseline=False)))
        print(lines[-1], flush=True)
    lines.append(
        "times in seconds; build = DiscreteTF.from_expr(G) and controllable_canonical(G).similar(P);"
    )
    lines.append(
        f"exact and naive run in a subprocess capped at {args.cap:g} s; "
        "speed-up = naive simplify / exact"
    )
    print("\n" + "\n".join(lines))


if __name__ == "__main__":
    main()
