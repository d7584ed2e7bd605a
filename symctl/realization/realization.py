r"""State-space realizations :math:`(F, H, M, N)` in closed form.

:math:`x(t+1) = F x(t) + H u(t)`, :math:`y(t) = M x(t) + N u(t)` realizes :math:`G(z) = M
(zI - F)^{-1} H + N` (the paper's section "Realizations"); the canonical forms of the paper's
:math:`G_2` are exactly its matrices. Other realizers: :mod:`symctl.realization.realizers`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.display import LatexMixin, latex
from symctl._util.exact import cancel
from symctl._util.validate import (
    MAX_STEPS,
    bounded_int,
    common_dt,
    subs_rule,
    to_expr,
    to_matrix,
)
from symctl.design.tf import DiscreteTF, convertible
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.realization._similarity import similar_exact
from symctl.symbols import z

__all__ = [
    "Realization",
    "controllable_canonical",
    "controller_realization",
    "first_order_realization",
    "observable_canonical",
    "section_realizations",
    "split_proper",
]


def _tidy(expr: sp.Expr) -> sp.Expr:
    """Lowest terms with common factors pulled out (no blanket simplify)."""
    return sp.factor_terms(cancel(expr))


@convertible("ss")
@dataclass(frozen=True)
class Realization(LatexMixin):
    r"""A realization :math:`(F, H, M, N)`: :math:`G(z) = M(zI-F)^{-1}H + N` (a value; ``n = 0``,
    a static gain, allowed; similar realizations are not equal).

    Parameters
    ----------
    F : (n, n) matrix-like
    H : (n, q) matrix-like
    M : (p, n) matrix-like
    N : (p, q) matrix-like (a scalar for SISO)
    dt : sampling time, optional
    params : mapping, optional
        Values used to build it (e.g. epsilons, ``P``); read-only, not compared.

    Raises
    ------
    DimensionError, ParameterError, SymctlTypeError
        Shapes that do not fit; entries that are not numbers or sympy expressions.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import Realization
    >>> R = Realization([[sp.Rational(1, 2)]], [[1]], [[2]], 0)
    >>> R.to_tf().expr
    2/(z - 1/2)
    >>> R == Realization([[sp.Rational(1, 2)]], [[1]], [[2]], 0), R == R.similar([[2]])
    (True, False)
    """

    F: sp.ImmutableMatrix
    H: sp.ImmutableMatrix
    M: sp.ImmutableMatrix
    N: sp.ImmutableMatrix
    dt: sp.Expr | None = None
    params: Mapping = field(default=None, compare=False)

    def __post_init__(self):
        Fm = _matrix_or_empty(self.F, "F")
        n = Fm.shape[0]
        if Fm.shape != (n, n):
            raise DimensionError(f"F: must be square, got shape {Fm.shape}")
        Nm = to_matrix(self.N, "N")
        p, q = Nm.shape
        Hm = _matrix_or_empty(self.H, "H", (n, q))
        Mm = _matrix_or_empty(self.M, "M", (p, n))
        for name, mat, shape in (("H", Hm, (n, q)), ("M", Mm, (p, n))):
            if mat.shape != shape:
                raise DimensionError(
                    f"{name}: expected shape {shape} (F is {n}x{n}, N is {p}x{q}), got {mat.shape}"
                )
        for name, mat in (("F", Fm), ("H", Hm), ("M", Mm), ("N", Nm)):
            object.__setattr__(self, name, sp.ImmutableMatrix(mat))
        object.__setattr__(self, "dt", None if self.dt is None else to_expr(self.dt, "dt"))
        object.__setattr__(self, "params", MappingProxyType(dict(self.params or {})))

    @property
    def n(self) -> int:
        """Number of states."""
        return self.F.shape[0]

    @property
    def shape(self) -> tuple[int, int]:
        """``(outputs, inputs)``."""
        return self.N.shape

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        return set().union(*(m.free_symbols for m in (self.F, self.H, self.M, self.N)))

    def markov(self, count: int) -> list[sp.Matrix]:
        r"""``[N, M H, M F H, ..., M F^{count-2} H]``, :math:`M F^k` cancelled at each step."""
        count = bounded_int(count, "count", 0, MAX_STEPS)
        out = [sp.Matrix(self.N)]
        row = sp.Matrix(self.M)
        for _ in range(count - 1):
            out.append((row * self.H).applyfunc(sp.cancel))
            row = (row * self.F).applyfunc(sp.cancel)
        return out[:count]

    def to_tf(self) -> DiscreteTF:
        r"""The transfer function :math:`M \operatorname{adj}(zI-F) H / \det(zI-F) + N`, not reduced.

        :math:`\operatorname{adj}(zI - F) = \sum_{j<n} z^j \sum_{i>j} c_i F^{i-j-1}` with
        :math:`\chi(z) = \sum_i c_i z^i`: only the Markov parameters are needed.
        """
        n = self.n
        chi = self.F.charpoly(z)
        c = chi.all_coeffs()[::-1]  # c[i] multiplies z**i, c[n] = 1
        m = self.markov(n + 1)[1:]  # m[k] = M F^k H
        num = sp.Matrix(self.N) * chi.as_expr()
        for j in range(n):
            acc = sum((c[i] * m[i - j - 1] for i in range(j + 1, n + 1)), sp.zeros(*self.shape))
            num = num + acc * z**j
        return DiscreteTF(
            num.applyfunc(lambda e: sp.expand(sp.together(e))), chi.as_expr(), self.dt
        )

    def similar(self, P) -> Realization:
        r"""The similar realization :math:`(P^{-1} F P,\ P^{-1} H,\ M P,\ N)`.

        Raises
        ------
        ParameterError
            When ``P`` is singular (its determinant cancels to zero).
        """
        return self._similar(P)[0]

    def _similar(self, P) -> tuple[Realization, sp.Matrix]:
        """:meth:`similar` and its ``P^{-1}``, in python-flint (floats, ``pi``: :func:`_similar_sympy`)."""
        Pm = to_matrix(P, "P")
        if Pm.shape != (self.n, self.n):
            raise DimensionError(f"P: expected shape {(self.n, self.n)}, got {Pm.shape}")
        got = similar_exact(self.F, self.H, self.M, Pm) if self.n else None
        if got is None:
            got = _similar_sympy(self.F, self.H, self.M, Pm)
        if got == "singular" or got[0] is None:
            raise ParameterError(f"P: singular (det P = 0), got {Pm.tolist()}")
        F, H, M, Pinv = got
        params = {**self.params, "P": sp.ImmutableMatrix(Pm)}
        return Realization(F, H, M, self.N, self.dt, params), sp.ImmutableMatrix(Pinv)

    def subs(self, *args, **kwargs) -> Realization:
        """Substitute symbols in every matrix (as :meth:`sympy.Basic.subs`; text through the safe parser)."""
        dt_symbols = set() if self.dt is None else self.dt.free_symbols
        rule, flags = subs_rule(args, kwargs, self.free_symbols | dt_symbols)
        mats = [m.subs(rule, **flags) for m in (self.F, self.H, self.M, self.N)]
        dt = None if self.dt is None else self.dt.subs(rule, **flags)
        return Realization(*mats, dt, self.params)

    def transpose(self) -> Realization:
        """The dual realization :math:`(F^T, M^T, H^T, N^T)` (of :math:`G^T`)."""
        return Realization(self.F.T, self.M.T, self.H.T, self.N.T, self.dt, self.params)

    def controllability_matrix(self) -> sp.Matrix:
        return (
            sp.Matrix.hstack(*[self.F**k * self.H for k in range(self.n)])
            if self.n
            else sp.zeros(0, 0)
        )

    def observability_matrix(self) -> sp.Matrix:
        return self.transpose().controllability_matrix().T

    def is_minimal(self) -> bool:
        r"""Controllable and observable (generic rank with symbols; floats to a relative 1e-10)."""
        if self.n == 0:
            return True
        return all(
            _rank(mat) == self.n
            for mat in (self.controllability_matrix(), self.observability_matrix())
        )

    def numeric(self) -> tuple[np.ndarray, ...]:
        """``(F, H, M, N)`` as float arrays; refuses free symbols."""
        from symctl._util.validate import numeric_matrix

        return tuple(
            numeric_matrix(m, name) if m.shape[0] * m.shape[1] else np.zeros(m.shape)
            for name, m in zip("FHMN", (self.F, self.H, self.M, self.N), strict=True)
        )

    @classmethod
    def series(cls, *parts: Realization) -> Realization:
        r"""The series connection :math:`G_k \cdots G_1` of ``parts`` (the first acts first, its
        states first): :math:`F = [[F_1, 0], [H_2 M_1, F_2]]`, :math:`H = [H_1; H_2 N_1]`,
        :math:`M = [N_2 M_1,\ M_2]`, :math:`N = N_2 N_1`."""
        if not parts:
            raise ParameterError("parts: give at least one realization")
        for i, part in enumerate(parts):
            if not isinstance(part, Realization):
                raise SymctlTypeError(
                    f"parts[{i}]: expected a Realization, got {type(part).__name__}"
                )
        out = parts[0]
        for i, nxt in enumerate(parts[1:], start=1):
            if nxt.shape[1] != out.shape[0]:
                raise DimensionError(f"parts: {out.shape[0]} outputs feed {nxt.shape[1]} inputs")
            n1, n2 = out.n, nxt.n
            F = sp.zeros(n1 + n2, n1 + n2)
            F[:n1, :n1] = out.F
            F[n1:, :n1] = nxt.H * out.M
            F[n1:, n1:] = nxt.F
            H = sp.Matrix.vstack(sp.Matrix(out.H), nxt.H * out.N)
            M = sp.Matrix.hstack(nxt.N * out.M, sp.Matrix(nxt.M))
            dt = common_dt(out.dt, nxt.dt, f"parts[{i}]")
            out = Realization(F, H, M, nxt.N * out.N, dt, {**out.params, **nxt.params})
        return out

    def lambdify(self, symbols):
        """A NumPy function of the ``symbols`` returning ``(F, H, M, N)`` (broadcasts)."""
        from symctl._util.evaluate import lambdify_matrices

        return lambdify_matrices((self.F, self.H, self.M, self.N), symbols)

    def latex(self) -> str:
        return (
            rf"F = {latex(self.F)},\quad H = {latex(self.H)},\quad "
            rf"M = {latex(self.M)},\quad N = {latex(self.N)}"
        )

    def __repr__(self) -> str:
        mats = ", ".join(f"{k}={getattr(self, k).tolist()}" for k in "FHMN")
        return f"Realization({mats})"


def _similar_sympy(F, H, M, P: sp.Matrix):
    """``(P^-1 F P, P^-1 H, M P, P^-1)`` with SymPy's cancel (``F`` is None when ``P`` is singular)."""
    det = sp.cancel(P.det(method="berkowitz"))
    if det == 0:
        return None, None, None, None
    Pinv = (P.adjugate(method="berkowitz") / det).applyfunc(sp.cancel)
    return (
        (Pinv * F * P).applyfunc(_tidy),
        (Pinv * H).applyfunc(_tidy),
        (M * P).applyfunc(_tidy),
        Pinv,
    )


def _matrix_or_empty(value, name: str, shape: tuple[int, int] | None = None) -> sp.Matrix:
    if isinstance(value, sp.MatrixBase | np.ndarray) and 0 in value.shape:
        return sp.zeros(*value.shape)
    if isinstance(value, list | tuple) and len(value) == 0:
        return sp.zeros(*(shape or (0, 0)))
    return to_matrix(value, name)


def _rank(mat: sp.Matrix) -> int:
    if not mat.free_symbols and any(isinstance(e, sp.Float) for e in mat):
        arr = np.array(mat.evalf(), dtype=float)
        return int(np.linalg.matrix_rank(arr, tol=1e-10 * max(1.0, np.abs(arr).max())))
    return mat.rank(iszerofunc=lambda e: sp.cancel(e) == 0)


def _siso(G, argname: str = "G2") -> DiscreteTF:
    tf = _proper(G, argname)
    if not tf.is_siso:
        raise DimensionError(
            f"{argname}: canonical forms are built for SISO transfer functions, got {tf.shape}"
        )
    return tf


def _proper(G, argname: str = "G2") -> DiscreteTF:
    tf = DiscreteTF.from_expr(G)
    if tf.relative_degree < 0:
        raise ParameterError(f"{argname}: improper (numerator degree above denominator degree)")
    return tf


def _split(tf: DiscreteTF) -> tuple[list, sp.Matrix, list[sp.Matrix]]:
    """``(a, N, C)``: the denominator ascending (``a[n] = 1``), ``G(oo)`` and the ascending
    coefficient matrices of the numerator of :math:`G - N`."""
    p, m = tf.shape
    a = tf.den_coeffs()[::-1]
    n = len(a) - 1
    N = sp.zeros(p, m)
    C = [sp.zeros(p, m) for _ in range(n)]
    for i in range(p):
        for j in range(m):
            b = tf.num_coeffs(i, j)[::-1]
            b = b + [sp.Integer(0)] * (n + 1 - len(b))
            N[i, j] = _tidy(b[n])
            for k in range(n):
                C[k][i, j] = _tidy(b[k] - b[n] * a[k])
    return a, N, C


def split_proper(G) -> tuple[sp.Expr, list[sp.Expr], list[sp.Expr]]:
    r"""``(N, c, a)`` with :math:`G = N + \sum_i c_i z^i / (z^n + \sum_{i<n} a_i z^i)` for a proper
    SISO ``G``, ``c`` and ``a`` ascending (length ``n``)."""
    a, N, C = _split(_siso(G, "G"))
    return N[0, 0], [c[0, 0] for c in C], a[:-1]


def controllable_canonical(G2) -> Realization:
    r"""The controllable canonical realization (the paper's, for :math:`n = 2`).

    .. math::
        F = \begin{bmatrix} 0 & 1 & & \\ & \ddots & \ddots & \\ & & 0 & 1 \\
            -a_0 & -a_1 & \cdots & -a_{n-1}\end{bmatrix},\quad
        H = e_n,\quad M = [c_0\ \cdots\ c_{n-1}],\quad N = G_2(\infty),

    with :math:`G_2 = N + \sum_k c_k z^k / d(z)`. A p x m ``G2`` gets the block form (each
    entry of :math:`F`, :math:`H` times :math:`I_m`, :math:`M = [C_0\ \cdots\ C_{n-1}]`).

    Parameters
    ----------
    G2 : DiscreteTF or sympy expression in z
        Proper, exact or symbolic (else ParameterError).

    Returns
    -------
    Realization
        Of order :math:`n m`, :math:`n = \deg d`.

    Examples
    --------
    >>> from symctl import controllable_canonical, controller_tf, factor
    >>> R = controllable_canonical(factor(controller_tf(2)).G2)
    >>> R.F.tolist(), R.H.T
    ([[0, 1], [K_2, K_1]], Matrix([[0, 1]]))
    """
    tf = _proper(G2)
    p, m = tf.shape
    a, D, C = _split(tf)
    n = len(a) - 1
    F = sp.zeros(n * m, n * m)
    for k in range(n):
        for r in range(m):
            F[(n - 1) * m + r, k * m + r] = -a[k]
            if k < n - 1:
                F[k * m + r, (k + 1) * m + r] = 1
    H = sp.zeros(n * m, m)
    if n:
        H[(n - 1) * m :, :] = sp.eye(m)
    M = sp.Matrix.hstack(*C) if n else sp.zeros(p, 0)
    return Realization(F, H, M, D, tf.dt)


def observable_canonical(G2) -> Realization:
    r"""The observable canonical realization: the transpose of :func:`controllable_canonical`
    of :math:`G_2^\top` (:math:`n p` states).

    Parameters
    ----------
    G2 : DiscreteTF or sympy expression in z
        Proper, exact or symbolic (else ParameterError).

    Returns
    -------
    Realization

    Examples
    --------
    >>> from symctl import controller_tf, factor, observable_canonical
    >>> R = observable_canonical(factor(controller_tf(2)).G2)
    >>> R.F.tolist(), R.M
    ([[0, K_2], [1, K_1]], Matrix([[0, 1]]))
    """
    tf = _proper(G2)
    if not tf.is_siso:  # the dual of the block controllable form of G2^T
        tf = DiscreteTF(tf.num_matrix.T, tf.den, tf.dt)
    return controllable_canonical(tf).transpose()


def first_order_realization(eps, C, dt=None) -> Realization:
    r"""The section :math:`x(t+1) = \epsilon x(t) + C u(t)`, :math:`y = x`, of :math:`C/(z-\epsilon)`
    (one per delay step of :math:`G_1` and :math:`G_3`).

    Parameters
    ----------
    eps, C : number, sympy expression or str
        The pole and the input gain (text through the safe parser; ParseError,
        SymctlTypeError for others).
    dt : number, optional

    Returns
    -------
    Realization

    Examples
    --------
    >>> from symctl import first_order_realization
    >>> first_order_realization(2, 3).to_tf().expr
    3/(z - 2)
    """
    return Realization([[eps]], [[C]], [[1]], 0, dt)


def section_realizations(factorization) -> tuple[list[Realization], list[Realization]]:
    r"""The first-order sections of :math:`G_1` and of :math:`G_3`, each in signal-flow order
    (MIMO: one diagonal realization per stage, holding that stage's section of every channel)."""
    dt, out = factorization.G.dt, []
    for side in factorization.section_channels:  # stage k: the k-th section of every channel
        eps, cs = (zip(*part, strict=True) for part in zip(*side, strict=True))
        out.append(
            [
                Realization(sp.diag(*e), sp.diag(*c), sp.eye(len(e)), sp.zeros(len(e)), dt)
                for e, c in zip(eps, cs, strict=True)
            ]
        )
    return out[0], out[1]


def controller_realization(factorization, R2: Realization) -> Realization:
    r"""The whole controller :math:`G_3 G_2 G_1` as a series realization (states: :math:`G_1`'s
    sections, ``R2``'s, :math:`G_3`'s).

    Parameters
    ----------
    factorization : Factorization
    R2 : Realization
        A realization of ``factorization.G2``.

    Returns
    -------
    Realization

    Examples
    --------
    >>> from symctl import controller_realization, controller_tf, controllable_canonical, factor
    >>> f = factor(controller_tf(2))
    >>> R = controller_realization(f, controllable_canonical(f.G2))
    >>> R.n, R.to_tf().equals(f.G)
    (4, True)
    """
    first, last = section_realizations(factorization)
    return Realization.series(*first, R2, *last)
