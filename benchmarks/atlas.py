"""Time the circuit atlas: order 2 and 3 exhaustive, order 4's sparsest size, against a naive search.

symctl: every pattern reduced by state permutations, filtered by the exact
generic-rank test mod p, decided (closed form, lifting, certified witnesses,
exact counterexamples), grouped into circuit classes; on a dask LocalCluster
with one worker per core.

Naive baseline (measured in the same run): every pattern (no symmetry
reduction), each solved numerically (no rank pruning) for two sampled G2 per
pole region with scipy.optimize.least_squares from 5 random starts; timed on
a random sample of patterns and scaled to all of them.

Order 4 searches its sparsest classes (12 entries, circuits of at most 3 neurons); the
orbits it tests are those, the others are counted and skipped.

Run: python benchmarks/atlas.py [--order4]
"""

from __future__ import annotations

import os
import random
import sys
import time

import numpy as np
import sympy as sp
from scipy.optimize import least_squares

import symctl
from symctl import Pattern, z

SAMPLE = 60


def naive_seconds_per_pattern(n: int, rng: random.Random) -> float:
    """Mean time to solve sampled patterns numerically for sampled G2 in every region."""
    slots = n * n + 2 * n
    targets = []
    for pairs in range(n // 2 + 1):
        for _ in range(2):
            poles = [complex(rng.uniform(-0.9, 0.9), rng.uniform(0.1, 0.9)) for _ in range(pairs)]
            roots = [*poles, *(p.conjugate() for p in poles)]
            roots += [rng.uniform(-0.9, 0.9) for _ in range(n - 2 * pairs)]
            a = np.real(np.poly(roots))[1:][::-1]
            targets.append((a, np.array([rng.uniform(-2, 2) for _ in range(n)])))
    start = time.perf_counter()
    for _ in range(SAMPLE):
        p = Pattern(n, rng.randrange(1 << slots))
        syms = list(p.symbols().values())
        if not syms:
            continue
        F, H, M = p.matrices(p.symbols())
        A = z * sp.eye(n) - F
        a_expr = sp.Poly(A.det(), z).all_coeffs()[::-1][:n]
        b_expr = sp.Poly(sp.expand((M * A.adjugate() * H)[0]), z).all_coeffs()[::-1]
        b_expr = b_expr + [0] * (n - len(b_expr))
        f = sp.lambdify([syms], [*a_expr, *b_expr], "numpy")
        for a, c in targets:
            goal = np.concatenate([a, c])
            for _ in range(5):
                x0 = np.array([rng.gauss(0, 1) for _ in syms])
                sol = least_squares(lambda x, g=goal, f=f: np.array(f(x), dtype=float) - g, x0)
                if sol.cost < 1e-20:
                    break
    return (time.perf_counter() - start) / SAMPLE


def main() -> None:
    rng = random.Random(1)
    cores = os.cpu_count() or 1
    rows = []
    orders = [2, 3] + ([4] if "--order4" in sys.argv else [])
    for n in orders:
        start = time.perf_counter()
        A = symctl.atlas(n, workers=1 if n == 2 else cores)
        seconds = time.perf_counter() - start
        s = A.stats
        naive = naive_seconds_per_pattern(n, rng)
        total = (
            2 ** (n * n + 2 * n)
            if n <= 3
            else sum(
                __import__("math").comb(n * n + 2 * n, k) for k in range(3 * n, s["sizes"][1] + 1)
            )
        )
        rows.append(
            (
                n,
                "all" if s["complete"] else f"{s['sizes'][0]}..{s['sizes'][1]}",
                s["patterns"],
                s["canonical"] - s["skipped"],
                s["full_rank"],
                len(A.classes),
                len(A.universal_classes),
                s["undecided"],
                seconds,
                1000 * seconds / max(s["canonical"] - s["skipped"], 1),
                naive * total,
            )
        )
    head = (
        "| order | sizes | patterns | orbits tested (rank test) | full rank | classes | universal "
        "| undecided "
        "| symctl [s] | per orbit [ms] | naive (scaled) [s] |"
    )
    print(f"atlas on {cores} cores; naive baseline timed on {SAMPLE} sampled patterns\n")
    print(head)
    print("|" + "---|" * 11)
    for r in rows:
        print(
            f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} | {r[4]} | {r[5]} | {r[6]} | {r[7]} | "
            f"{r[8]:.1f} | {r[9]:.2f} | {r[10]:.0f} |"
        )


if __name__ == "__main__":
    main()
