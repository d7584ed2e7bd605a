r"""Minimal realizations, exactly: the Kalman reduction in rational arithmetic.

Two exact steps (python-flint's rational row reduction): 1. **controllable part**: the
pivot columns :math:`V` of :math:`[H, FH, \dots, F^{n-1}H]` span the reachable subspace,
:math:`F`-invariant and holding :math:`H`; with a left inverse :math:`V^+`, :math:`(V^+ F V,
V^+ H, M V)` has the same Markov parameters, as :math:`F V = V F_c`, :math:`H = V H_c`;
2. **observable part**, the dual step. The result is checked: :math:`n + r` equal Markov
parameters prove one transfer function (the difference has a realization of order
:math:`n + r`).
"""

from __future__ import annotations

import sympy as sp
from flint import fmpq, fmpq_mat

from symctl._util.exact import from_fmpq_mat
from symctl.errors import ParameterError, SymctlTypeError
from symctl.realization.realization import Realization

__all__ = ["MAX_ORDER", "minimal_realization"]

MAX_ORDER = 200
"""The largest realization :func:`minimal_realization` reduces (the Krylov matrix is n x n q)."""


def _mat(M: sp.MatrixBase, name: str) -> fmpq_mat:
    rows, cols = M.shape
    out = fmpq_mat(rows, cols)
    for i in range(rows):
        for j in range(cols):
            e = sp.Rational(M[i, j]) if M[i, j].is_Float else M[i, j]  # floats: exactly
            if not e.is_Rational:
                raise ParameterError(
                    f"R: {name}[{i + 1},{j + 1}] = {M[i, j]} is not a rational number; the "
                    "exact minimal realization needs numbers (substitute values first)"
                )
            out[i, j] = fmpq(int(e.p), int(e.q))
    return out


def _pivots(M: fmpq_mat) -> list[int]:
    """The pivot columns of ``M``'s reduced row echelon form."""
    R, rank = M.rref()
    pivots, col = [], 0
    for i in range(rank):
        while R[i, col] == 0:
            col += 1
        pivots.append(col)
        col += 1
    return pivots


def _reachable(F: fmpq_mat, H: fmpq_mat, M: fmpq_mat):
    """The controllable part of (F, H, M): ``(F_c, H_c, M_c)``, exact."""
    n, q = H.nrows(), H.ncols()
    if n == 0:
        return F, H, M
    blocks, block = [], H
    for _ in range(n):
        blocks.append(block)
        block = F * block
    K = fmpq_mat(n, n * q, [blocks[c // q][i, c % q] for i in range(n) for c in range(n * q)])
    cols = _pivots(K)
    r = len(cols)
    if r == n:
        return F, H, M
    if r == 0:  # nothing is reached: a static gain
        return fmpq_mat(0, 0), fmpq_mat(0, q), fmpq_mat(M.nrows(), 0)
    V = fmpq_mat(n, r, [K[i, c] for i in range(n) for c in cols])
    rows = _pivots(V.transpose())  # r rows of V that are independent: V[rows] is invertible
    inv = fmpq_mat(r, r, [V[i, j] for i in rows for j in range(r)]).inv()
    select = fmpq_mat(r, n, [1 if j == rows[i] else 0 for i in range(r) for j in range(n)])
    left = inv * select  # a left inverse of V
    return left * F * V, left * H, M * V


def minimal_realization(R: Realization) -> Realization:
    r"""A minimal realization of the same transfer function, exactly.

    Parameters
    ----------
    R : Realization
        Numbers (floats taken exactly), any shape, at most :data:`MAX_ORDER` states.

    Returns
    -------
    Realization
        Of order the McMillan degree, proved to realize ``R.to_tf()``.

    Raises
    ------
    SymctlTypeError, ParameterError
        ``R`` not a Realization; symbolic entries or more than :data:`MAX_ORDER` states.

    Examples
    --------
    >>> from symctl import Realization
    >>> from symctl.realization.minimal import minimal_realization
    >>> R = Realization([[0.5, 0], [0, 0.5]], [[1], [1]], [[1, 2]], 0)
    >>> minimal_realization(R).n
    1
    """
    if not isinstance(R, Realization):
        raise SymctlTypeError(f"R: expected a Realization, got {type(R).__name__}")
    if R.n > MAX_ORDER:
        raise ParameterError(f"R: at most {MAX_ORDER} states, got {R.n}")
    F0, H0, M0 = _mat(R.F, "F"), _mat(R.H, "H"), _mat(R.M, "M")
    N = _mat(R.N, "N")
    F, H, M = _reachable(F0, H0, M0)
    Ft, Mt, Ht = _reachable(F.transpose(), M.transpose(), H.transpose())
    F, H, M = Ft.transpose(), Ht.transpose(), Mt.transpose()
    if not _same_markov((F0, H0, M0), (F, H, M), R.n + F.nrows()):  # pragma: no cover
        raise RuntimeError("the minimal realization does not realize the same transfer function")
    return Realization(*(from_fmpq_mat(X) for X in (F, H, M, N)), R.dt)


def _same_markov(a, b, count: int) -> bool:
    """Whether ``M F^k H`` agree for ``k < count`` (exact)."""
    (Fa, Ha, Ma), (Fb, Hb, Mb) = a, b
    ra, rb = Ma, Mb
    for _ in range(count):
        if (ra * Ha).tolist() != (rb * Hb).tolist():
            return False
        ra, rb = ra * Fa, rb * Fb
    return True
