"""Time the MIMO controller G(z) = adj D(z) K_0 / det D(z) and its proof (issue 13).

Rows (n, m, T) = (3, 4, 2) and (3, 6, 3): a random plant with n states and m
inputs, delays (T // 2, T - T // 2). Columns: ``controller_tf`` with numeric
gains (from ``lqr_gains``), with symbolic gain blocks, and ``prove_controller_tf``
of the symbolic one; each beside the method symctl used before issue 13
(SymPy's generic ``Matrix.adjugate`` and ``det`` of D(z), expanded, the numeric
controller by substituting the gains into the symbolic one, and the proof by
``sp.expand`` of every entry of (zI - F_c) W - H_c det D), measured in the same
run. Every measurement runs in a subprocess capped at --cap seconds ("> cap")
and 4 GB of address space ("mem").

Run:  python benchmarks/mimo.py [--cap SECONDS]
"""

from __future__ import annotations

import argparse
import resource
import time

import numpy as np
import sympy as sp
from capped import capped

from symctl import DiscreteTF, augment, controller_tf, lqr_gains, prove_controller_tf
from symctl.design.controller import ifp_state_space
from symctl.symbols import gain_matrix_symbols, z

CASES = [(3, 4, 2), (3, 6, 3)]


def system(n: int, m: int, T: int):
    rng = np.random.default_rng(n + 10 * m + 100 * T)
    A = rng.normal(size=(n, n)) / np.sqrt(n)
    B = rng.normal(size=(n, m))
    return augment((A, B), T // 2, T - T // 2)


# ---------------------------------------------------------------- before issue 13
def _baseline_controller(aug, gains=None) -> DiscreteTF:
    T, m, n = aug.T, aug.m, aug.n
    blocks = gain_matrix_symbols(T, m, n)
    D = z**T * sp.eye(m)
    for k in range(1, T + 1):
        D = D - blocks[k] * z ** (T - k)
    num, den = (D.adjugate() * blocks[0]).applyfunc(sp.expand), sp.expand(D.det())
    G = DiscreteTF(num, den, aug.plant.Ts)
    if G.relative_degree != T:
        raise AssertionError("relative degree")
    return G if gains is None else G.subs(gains.substitutions())


def _baseline_proof(aug, G) -> bool:
    T = aug.T
    K = sp.Matrix.hstack(*gain_matrix_symbols(T, aug.m, aug.n))
    F, H, M, _ = ifp_state_space(sp.Matrix(aug.A), sp.Matrix(aug.B), K, aug.n, aug.m, T)
    M, N = sp.Matrix(M), G.num_matrix
    W = sp.Matrix.vstack(*(N * z ** (T - k) for k in range(1, T + 1)))
    lhs = (z * sp.eye(F.shape[0]) - F) * W - H * G.den
    return all(sp.expand(e) == 0 for e in (*lhs, *(M * W - N)))


def old_numeric(n, m, T):
    aug = system(n, m, T)
    _baseline_controller(aug, lqr_gains(aug))


def old_symbolic(n, m, T):
    _baseline_controller(system(n, m, T))


def old_proof(n, m, T):  # G by the new method (untimed), proved the old way
    aug = system(n, m, T)
    G = controller_tf(aug)
    start = time.perf_counter()
    assert _baseline_proof(aug, G)
    return time.perf_counter() - start


# ---------------------------------------------------------------- symctl now
def new_numeric(n, m, T):
    aug = system(n, m, T)
    controller_tf(lqr_gains(aug))


def new_symbolic(n, m, T):
    controller_tf(system(n, m, T))


def new_proof(n, m, T):
    aug = system(n, m, T)
    G = controller_tf(aug)
    start = time.perf_counter()
    assert prove_controller_tf(aug, G)
    return time.perf_counter() - start


MEMORY = 4 << 30  # bytes of address space per measurement ("mem" beyond)


def guarded(job, args):
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))
    try:
        return job(*args)
    except MemoryError:
        return "mem"


def cell(job, args, cap: float) -> str:
    out = capped(guarded, (job, args), cap)
    if out is None:
        return f"> {cap:g}"
    seconds, inner = out
    if inner == "mem":
        return "mem"
    return f"{inner if isinstance(inner, float) else seconds:.2f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cap", type=float, default=60.0, help="seconds per measurement")
    cap = parser.parse_args().cap
    head = ("n", "m", "T", "numeric", "(before)", "symbolic", "(before)", "proof", "(before)")
    print("controller_tf / prove_controller_tf, seconds (before: the pre-issue-13 method)")
    print(" ".join(f"{h:>9}" for h in head))
    for n, m, T in CASES:
        args = (n, m, T)
        row = [n, m, T]
        for new, old in (
            (new_numeric, old_numeric),
            (new_symbolic, old_symbolic),
            (new_proof, old_proof),
        ):
            row += [cell(new, args, cap), cell(old, args, cap)]
        print(" ".join(f"{c:>9}" for c in row), flush=True)


if __name__ == "__main__":
    main()
