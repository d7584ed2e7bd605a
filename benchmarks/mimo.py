"""Time the MIMO controller G(z) = D(z)^-1 K_0 and its proof.

Rows (n, m, T) = (3, 4, 2) and (3, 6, 3): a random plant with n states and m
inputs, delays (T // 2, T - T // 2). Columns: ``controller_tf`` with numeric
gains (from ``lqr_gains``); with symbolic gain blocks; ``prove_controller_tf`` of
the symbolic one; and the two together (the target: "symbolic with its proof").
Each beside the method symctl used before (measured in the same run, its code
kept below as it was): the symbolic controller always expanded into
adj D(z) K_0 / det D(z) (fraction-free Laplace minors in SymPy's ZZ[z, K]), and
the proof by the identities (zI - F_c) W = H_c det D, M_c W = N_G multiplied out
in ZZ[z, K], W = [z^(T-1) N; ...; N]. Now a symbolic controller past
MAX_EXPANDED_TERMS is the left fraction D(z)^-1 K_0, proved by multiplying by D.
(The earlier method, SymPy's generic ``adjugate``, took > 30 s in every
column.) Every measurement runs in a subprocess capped at --cap seconds ("> cap")
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

from symctl import DiscreteTF, Gains, augment, controller_tf, lqr_gains, prove_controller_tf
from symctl.design.controller import ifp_state_space
from symctl.symbols import gain_matrix_symbols, z

CASES = [(3, 4, 2), (3, 6, 3)]
TARGETS = {(3, 4, 2): (2, 5), (3, 6, 3): (10, 30)}  # seconds: numeric, symbolic with proof


def system(n: int, m: int, T: int):
    rng = np.random.default_rng(n + 10 * m + 100 * T)
    A = rng.normal(size=(n, n)) / np.sqrt(n)
    B = rng.normal(size=(n, m))
    return augment((A, B), T // 2, T - T // 2)


# ---------------------------------------------------------------- before (as it was)
def _adj_det(D: list[list], zero) -> tuple[list[list], object]:
    """Adjugate and determinant of a square matrix over a polynomial ring, fraction-free.

    Laplace expansion with every minor memoized on its (rows, columns): no division,
    so the entries stay polynomials; zero entries are skipped.
    """
    m = len(D)
    memo: dict[tuple[tuple, tuple], object] = {}

    def minor(rows: tuple, cols: tuple):
        if not rows:
            return zero + 1
        key = (rows, cols)
        if key not in memo:
            r, rest = rows[0], rows[1:]
            acc = zero
            for idx, c in enumerate(cols):
                if D[r][c]:
                    term = D[r][c] * minor(rest, cols[:idx] + cols[idx + 1 :])
                    acc = acc - term if idx % 2 else acc + term
            memo[key] = acc
        return memo[key]

    every = tuple(range(m))
    adj = [
        [
            (-1) ** (i + j) * minor(every[:j] + every[j + 1 :], every[:i] + every[i + 1 :])
            for j in range(m)
        ]
        for i in range(m)
    ]
    det = zero
    for c in range(m):  # first row against its cofactors (already in adj's column 0)
        if D[0][c]:
            det += D[0][c] * adj[c][0]
    return adj, det


def _chain_matrix(ring, blocks, T: int, m: int, convert) -> list[list]:
    """``D(z) = z^T I - K_1 z^{T-1} - ... - K_T`` as a list of ring elements."""
    zz = ring.gens[0]
    return [
        [
            (zz**T if i == j else ring.zero)
            - sum((convert(blocks[k][i, j]) * zz ** (T - k) for k in range(1, T + 1)), ring.zero)
            for j in range(m)
        ]
        for i in range(m)
    ]


def _filled(rows: int, cols: int, entry) -> sp.Matrix:
    """A matrix of ring results (SymPy expressions, never text: no sympify on the way)."""
    out = sp.zeros(rows, cols)
    for i in range(rows):
        for j in range(cols):
            out[i, j] = entry(i, j)
    return out


def _symbolic_mimo(blocks, T: int, m: int):
    """``adj D(z) K_0`` and ``det D(z)`` for symbolic gain blocks, in ZZ[z, K]."""
    gens = [z, *(s for b in blocks for s in b)]
    R = sp.polys.rings.ring(gens, sp.ZZ)[0]
    sym = dict(zip(gens, R.gens, strict=True))
    D = _chain_matrix(R, blocks, T, m, sym.__getitem__)
    adj, det = _adj_det(D, R.zero)
    K0 = blocks[0]
    num_r = [
        [sum((adj[i][k] * sym[K0[k, j]] for k in range(m)), R.zero) for j in range(K0.shape[1])]
        for i in range(m)
    ]
    top = max(
        (p.degree(R.gens[0]) for row in num_r for p in row if p), default=det.degree(R.gens[0])
    )
    num = _filled(m, K0.shape[1], lambda i, j: num_r[i][j].as_expr())
    return num, det.as_expr(), det.degree(R.gens[0]) - top


def _numeric_mimo(gains: Gains, T: int, m: int, n: int, dt) -> DiscreteTF:
    """The controller for numeric gains: exact in QQ[z] from the gains' floats, rounded once."""
    R = sp.polys.rings.ring([z], sp.QQ)[0]
    vals = [np.asarray(b, dtype=float).reshape(m, -1) for b in gains.blocks]

    def q(x):
        return R(sp.QQ.from_sympy(sp.Rational(float(x))))

    D = _chain_matrix(R, vals, T, m, q)
    adj, det = _adj_det(D, R.zero)

    def floats(p) -> sp.Expr:
        return sp.Add(*(sp.Float(sp.QQ.to_sympy(c)) * z**k for (k,), c in p.terms()))

    num = _filled(
        m, n, lambda i, j: floats(sum((adj[i][k] * q(vals[0][k, j]) for k in range(m)), R.zero))
    )
    return DiscreteTF(num, floats(det), dt)


def _prove_in_ring(F, H, M, N, den, T: int, K) -> tuple[bool, str] | None:
    """Both identities of :func:`prove_controller_tf` in ``ZZ[z, K]``; None if not expressible.

    ``W = [z^{T-1} N; ...; N]`` is never formed: block ``k`` of ``(zI - F) W`` is
    ``z^{T-k} z N - sum_l F_{kl} z^{T-l} N`` with the sparse ``F`` (an entry at a time).
    """
    gens = [z, *K]
    R = sp.polys.rings.ring(gens, sp.ZZ)[0]
    try:
        Nr = [[R.from_expr(e) for e in N.row(i)] for i in range(N.rows)]
        den_r = R.from_expr(den)
        Fr = {
            (i, j): R.from_expr(F[i, j])
            for i in range(F.rows)
            for j in range(F.cols)
            if F[i, j] != 0
        }
        Hr = {
            (i, j): R.from_expr(H[i, j])
            for i in range(H.rows)
            for j in range(H.cols)
            if H[i, j] != 0
        }
    except (sp.polys.polyerrors.CoercionFailed, ValueError, TypeError):
        return None
    zz = R.gens[0]
    m, cols = N.rows, N.cols
    zpow = [zz**p for p in range(T + 1)]

    def w(row: int, col: int):  # entry of W: block row // m is z^{T-1-block} N
        block, r = divmod(row, m)
        return Nr[r][col] * zpow[T - 1 - block]

    by_row: dict[int, list[tuple[int, object]]] = {}
    for (i, j), f in Fr.items():
        by_row.setdefault(i, []).append((j, f))
    for i in range(F.rows):
        for c in range(cols):
            e = zz * w(i, c) - sum((f * w(j, c) for j, f in by_row.get(i, ())), R.zero)
            e -= Hr.get((i, c), R.zero) * den_r
            if e:
                return False, str(e.as_expr())
    for i in range(M.rows):
        for c in range(cols):
            e = sum((int(M[i, j]) * w(j, c) for j in range(M.cols) if M[i, j]), R.zero)
            e -= Nr[i][c]
            if e:
                return False, str(e.as_expr())
    return True, ""


def _before_controller(aug, gains=None) -> DiscreteTF:
    T, m, n = aug.T, aug.m, aug.n
    blocks = gain_matrix_symbols(T, m, n)
    if gains is not None:
        return _numeric_mimo(gains, T, m, n, aug.plant.dt)
    num, den, relative_degree = _symbolic_mimo(blocks, T, m)
    if relative_degree != T:
        raise AssertionError("relative degree")
    return DiscreteTF(num, den, aug.plant.dt)


def _before_proof(aug, G) -> bool:
    T = aug.T
    K = sp.Matrix.hstack(*gain_matrix_symbols(T, aug.m, aug.n))
    F, H, M, _ = ifp_state_space(sp.Matrix(aug.A), sp.Matrix(aug.B), K, aug.n, aug.m, T)
    ok, _ = _prove_in_ring(F, H, sp.Matrix(M), G.num_matrix, G.den, T, K)
    return ok


def old_numeric(n, m, T):
    aug = system(n, m, T)
    _before_controller(aug, lqr_gains(aug))


def old_symbolic(n, m, T):
    aug = system(n, m, T)
    start = time.perf_counter()
    G = _before_controller(aug)
    built = time.perf_counter()
    assert _before_proof(aug, G)
    return built - start, time.perf_counter() - built


# ---------------------------------------------------------------- symctl now
def new_numeric(n, m, T):
    aug = system(n, m, T)
    controller_tf(lqr_gains(aug))


def new_symbolic(n, m, T):
    aug = system(n, m, T)
    start = time.perf_counter()
    G = controller_tf(aug)
    built = time.perf_counter()
    assert prove_controller_tf(aug, G)
    return built - start, time.perf_counter() - built


MEMORY = 4 << 30  # bytes of address space per measurement ("mem" beyond)


def guarded(job, args):
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))
    try:
        return job(*args)
    except MemoryError:
        return "mem"


def cells(job, args, cap: float, parts: int) -> list[str]:
    """``parts`` cells: the job's seconds (1), or its (build, proof, total) seconds (3)."""
    out = capped(guarded, (job, args), cap)
    if out is None or out[1] == "mem":
        return [f"> {cap:g}" if out is None else "mem"] * parts
    seconds, inner = out
    if parts == 1:
        return [f"{seconds:.2f}"]
    return [f"{inner[0]:.2f}", f"{inner[1]:.2f}", f"{sum(inner):.2f}"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cap", type=float, default=30.0, help="seconds per measurement")
    cap = parser.parse_args().cap
    head = (
        "n",
        "m",
        "T",
        "numeric",
        "(before)",
        "symbolic",
        "(before)",
        "proof",
        "(before)",
        "sym+proof",
        "(before)",
        "target",
    )
    print("controller_tf / prove_controller_tf, seconds (before: symctl before this change)")
    print(" ".join(f"{h:>9}" for h in head))
    for n, m, T in CASES:
        args = (n, m, T)
        numeric = cells(new_numeric, args, cap, 1) + cells(old_numeric, args, cap, 1)
        new, old = cells(new_symbolic, args, cap, 3), cells(old_symbolic, args, cap, 3)
        symbolic = [c for pair in zip(new, old, strict=True) for c in pair]
        target = "<{}, <{}".format(*TARGETS[n, m, T])
        row = [n, m, T, *numeric, *symbolic, target]
        print(" ".join(f"{c:>9}" for c in row), flush=True)


if __name__ == "__main__":
    main()
