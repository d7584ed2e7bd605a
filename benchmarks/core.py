"""Time to derive the augmented system, the LQR gains and the symbolic G(z), for T = 1..20.

Baseline, measured in the same run: naive SymPy, G = cancel(M_c (zI - F_c)^-1 H_c)
on the controller's state-space matrices with symbolic gains (capped per T).

Run:  python benchmarks/core.py [--cap SECONDS] [--max-T N]
"""

from __future__ import annotations

import argparse
import time

import sympy as sp
from capped import capped

import symctl
from symctl.symbols import gain_symbols


def naive_G(T: int) -> sp.Expr:
    """Textbook route: invert zI - F_c symbolically, then cancel."""
    aug = symctl.augment(symctl.MuscleModel(), 1, T - 1)
    K = gain_symbols(T)
    n = 1
    A_c = sp.Matrix(aug.A[n:, n:])
    B_c = sp.Matrix(aug.B[n:, :])
    F = A_c + B_c * sp.Matrix([list(K[1:])])
    H = B_c * K[0]
    M = sp.zeros(1, T)
    M[0, T - 1] = 1
    return sp.cancel((M * (symctl.z * sp.eye(T) - F).inv() * H)[0, 0])


def time_naive(T: int, cap: float) -> float | None:
    got = capped(naive_G, (T,), cap)
    return None if got is None else got[0]


def time_symctl(T: int) -> tuple[float, float, float, float]:
    model = symctl.MuscleModel()
    t0 = time.perf_counter()
    aug = symctl.augment(model, 1, T - 1)
    t1 = time.perf_counter()
    gains = symctl.lqr_gains(aug)
    t2 = time.perf_counter()
    G = symctl.controller_tf(aug)
    t3 = time.perf_counter()
    assert G.relative_degree == T
    assert symctl.prove_controller_tf(aug, G)
    G.subs(gains.substitutions())
    t4 = time.perf_counter()
    return t1 - t0, t2 - t1, t3 - t2, t4 - t3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cap", type=float, default=30.0, help="time cap of the baseline [s]")
    parser.add_argument("--max-T", type=int, default=20)
    args = parser.parse_args()
    symctl.augment(symctl.MuscleModel(), 1, 1)  # warm the symbolic plant cache once
    print(
        f"{'T':>3} | {'augment':>8} | {'LQR':>8} | {'G(z)':>8} | {'proof+subs':>10} | "
        f"{'total':>8} | {'naive SymPy G':>13} | {'speed-up':>8}"
    )
    print("-" * 88)
    naive_dead = False
    for T in range(1, args.max_T + 1):
        a, g, G, p = time_symctl(T)
        total = a + g + G + p
        naive = None if naive_dead else time_naive(T, args.cap)
        naive_dead = naive_dead or naive is None
        naive_s = (
            f"{naive:13.3f}" if naive is not None else f"{'> ' + str(int(args.cap)) + ' s':>13}"
        )
        speed = f"{naive / (G + p):7.0f}x" if naive is not None else f"{'-':>8}"
        print(
            f"{T:>3} | {a:8.4f} | {g:8.4f} | {G:8.4f} | {p:10.4f} | {total:8.4f} | "
            f"{naive_s} | {speed}"
        )
    print("times in seconds; speed-up = naive SymPy G / symctl (G(z) + its proof)")


if __name__ == "__main__":
    main()
