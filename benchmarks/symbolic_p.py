"""The similarity transform: fraction-free in python-flint against SymPy's cancel (the old method).

1. A general realization of the order-n controller ``controller_tf(n)`` with a
   fully symbolic n x n ``P`` (entries ``p_ij``), n = 2..6: the build
   (``general_realization``) and the exact proof (``check_realization``). The
   old build is the former ``Realization._similar`` (copied below: SymPy's
   Berkowitz determinant and adjugate, ``cancel`` of ``P^-1``, then
   ``factor_terms(cancel(.))`` of every entry); the old proof is the checker
   with its former step rule (rows and columns of the Markov parameters
   advanced in turn, ``|a - b| <= 1``), run on the same matrices (both builds
   give the same entries).
2. ``.similar(P)`` with a numeric (rational, well conditioned) ``P`` of order
   4, 10, 20, on a realization with rational entries and on the controllable
   canonical form of ``controller_tf(n)`` (entries linear in the gains).

Every old cell runs in its own process, capped at ``--cap`` seconds ("> cap").
The new and old results are compared entry for entry where both finished.

Run:  python benchmarks/symbolic_p.py [--cap SECONDS] [--max-n N]
"""

from __future__ import annotations

import argparse
import os
import time

import sympy as sp
from capped import capped

from symctl import (
    Realization,
    check_realization,
    controllable_canonical,
    controller_tf,
    general_realization,
)
from symctl.realization import _markov
from symctl.realization.realizers import random_full_rank


# --- the old method, as it was -----------------------------------------------------------------
def _tidy(expr):
    return sp.factor_terms(sp.cancel(expr))


def old_similar(R: Realization, P) -> Realization:
    """The former ``Realization._similar``: SymPy's det, adjugate and cancel."""
    Pm = sp.Matrix(P)
    det = sp.cancel(Pm.det(method="berkowitz"))
    if det == 0:
        raise ValueError("singular")
    Pinv = (Pm.adjugate(method="berkowitz") / det).applyfunc(sp.cancel)
    return Realization(
        (Pinv * R.F * Pm).applyfunc(_tidy),
        (Pinv * R.H).applyfunc(_tidy),
        (R.M * Pm).applyfunc(_tidy),
        R.N,
        R.dt,
    )


def old_check(R, G) -> bool:
    """``check_realization`` with the former step rule (rows and columns in turn)."""
    _markov._rows_first = lambda rows, cols, steps: steps[0] <= steps[1]
    return check_realization(R, G).ok


# --- the cases ----------------------------------------------------------------------------------
def symbolic_P(n: int) -> sp.Matrix:
    return sp.Matrix(n, n, sp.symbols(f"p_1:{n + 1}(1:{n + 1})"))


def old_build(n: int) -> tuple[float, bool]:
    """Seconds of the old build, and whether it equals the new one (compared here: the
    subprocess sends back only small results)."""
    base = controllable_canonical(controller_tf(n))
    start = time.perf_counter()
    R = old_similar(base, symbolic_P(n))
    seconds = time.perf_counter() - start
    return seconds, R == base.similar(symbolic_P(n))


def old_prove(n: int) -> bool:
    G = controller_tf(n)
    R = general_realization(G, symbolic_P(n))
    start = time.perf_counter()
    ok = old_check(R, G)
    return time.perf_counter() - start, ok


def numeric_case(n: int, kind: str):
    P = random_full_rank(n, rng=n, max_cond=1e4)
    if kind == "rational":
        rat = random_full_rank(n + 2, rng=n + 1, max_cond=1e9)
        R = Realization(rat[:n, :n], rat[:n, n : n + 1], rat[n : n + 1, :n], 0)
    else:
        R = controllable_canonical(controller_tf(n))
    return R, P


def repeat(fn, *args, budget: float = 0.5) -> tuple[float, object]:
    """Mean seconds per call over as many calls as fit in ``budget`` (at least one)."""
    start, calls = time.perf_counter(), 0
    while True:
        out = fn(*args)
        calls += 1
        spent = time.perf_counter() - start
        if spent >= budget:
            return spent / calls, out


def old_numeric(n: int, kind: str):
    R, P = numeric_case(n, kind)
    seconds, out = repeat(old_similar, R, P)
    return seconds, out == R.similar(P)


def fmt(seconds) -> str:
    return f"{'> cap':>9}" if seconds is None else f"{seconds:9.3f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cap", type=float, default=60.0, help="time cap of an old cell [s]")
    parser.add_argument("--max-n", type=int, default=6, help="largest order with a symbolic P")
    args = parser.parse_args()
    load = os.getloadavg()
    print(
        f"{os.cpu_count()} cores, load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}; "
        f"cap {args.cap:g} s per old cell\n"
    )
    print("general realization of controller_tf(n) with a fully symbolic n x n P [s]")
    print(
        f"{'n':>3} | {'build new':>9} | {'build old':>9} | {'prove new':>9} | {'prove old':>9} | same"
    )
    print("-" * 62)
    for n in range(2, args.max_n + 1):
        G = controller_tf(n)
        start = time.perf_counter()
        R = general_realization(G, symbolic_P(n))  # controllable_canonical(G).similar(P)
        build = time.perf_counter() - start
        start = time.perf_counter()
        ok = check_realization(R, G).ok
        prove = time.perf_counter() - start
        assert ok
        got = capped(old_build, (n,), args.cap)
        old_b = None if got is None else got[1][0]
        same = "-" if got is None else ("yes" if got[1][1] else "NO")
        got = capped(old_prove, (n,), args.cap)
        old_p = None if got is None else got[1][0]
        print(
            f"{n:>3} | {fmt(build)} | {fmt(old_b)} | {fmt(prove)} | {fmt(old_p)} | {same}",
            flush=True,
        )
    print()
    print("R.similar(P) with a numeric P (mean per call) [s]")
    print(f"{'n':>3} | {'entries':>8} | {'new':>9} | {'old':>9} | {'speed-up':>8} | same")
    print("-" * 56)
    for n in (4, 10, 20):
        for kind in ("rational", "linear"):
            R, P = numeric_case(n, kind)
            new_t, _ = repeat(R.similar, P)
            got = capped(old_numeric, (n, kind), args.cap)
            same = "-" if got is None else ("yes" if got[1][1] else "NO")
            old_t = None if got is None else got[1][0]
            ratio = "-" if old_t is None else f"{old_t / new_t:7.0f}x"
            print(
                f"{n:>3} | {kind:>8} | {fmt(new_t)} | {fmt(old_t)} | {ratio:>8} | {same}",
                flush=True,
            )
    print(
        "\nnew: Realization.similar (symctl/realization/_similarity.py); old: the former SymPy\n"
        "path copied above. 'same': the new and old realizations are equal entry for entry\n"
        "(structurally, so the printed forms agree too). prove: check_realization(R, G), exact."
    )


if __name__ == "__main__":
    main()
