r"""A MIMO transfer function kept as a left matrix fraction :math:`D(z)^{-1} N(z)`.

The expanded :math:`\operatorname{adj} D\, N / \det D` of a symbolic :math:`D` is huge: for
the delayed controller's :math:`D(z) = z^T I - \sum_k K_k z^{T-k}`, :math:`\det D` has
exactly :math:`\operatorname{perm}(C)` terms (:math:`C` the term counts of :math:`D`'s
entries: every permutation and choice of terms gives a distinct monomial), 732,529 for
:math:`m = 6, T = 3`. Nothing needs them: everything but ``num``/``den`` works on :math:`D`, :math:`N`.
"""

from __future__ import annotations

import sympy as sp
from sympy.polys.rings import ring

from symctl._util.display import descending_latex, descending_str
from symctl._util.exact import RingFractions, fold, z_degree, z_poly
from symctl._util.validate import (
    MAX_EXPANDED_TERMS,
    bounded_int,
    finite_expr,
    sampling_time,
    subs_rule,
    to_expr,
)
from symctl.design.tf import DiscreteTF, _natural_key, _replaced, _z_coeffs
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.symbols import z

__all__ = ["MatrixFractionTF"]


def _adj_det(D: list[list], zero, signed: bool = True) -> tuple[list[list], object]:
    """Adjugate and determinant by memoized Laplace minors, no division (``signed=False``:
    permanents, for term-count bounds)."""
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
                    acc = acc - term if idx % 2 and signed else acc + term
            memo[key] = acc
        return memo[key]

    every = tuple(range(m))
    adj = [
        [
            (-1 if (i + j) % 2 and signed else 1)
            * minor(every[:j] + every[j + 1 :], every[:i] + every[i + 1 :])
            for j in range(m)
        ]
        for i in range(m)
    ]
    det = zero
    for c in range(m):  # first row against its cofactors (already in adj's column 0)
        if D[0][c]:
            det += D[0][c] * adj[c][0]
    return adj, det


def _term_counts(M: sp.MatrixBase) -> list[list[int]]:
    return [
        [len(sp.Add.make_args(sp.expand(e))) if e != 0 else 0 for e in row] for row in M.tolist()
    ]


class MatrixFractionTF(DiscreteTF):
    r"""``D(z)^{-1} N(z)``, ``D`` monic ``m x m`` and ``N`` ``m x p`` polynomial in ``z`` (SymPy
    matrices; else SymctlTypeError, DimensionError, ParameterError). Expands only through
    :meth:`expanded` (``num``, ``den``); ``==`` compares ``D``, ``N``, ``dt`` structurally.

    >>> import sympy as sp
    >>> from symctl import z
    >>> from symctl.design.fraction import MatrixFractionTF
    >>> a = sp.Symbol("a")
    >>> G = MatrixFractionTF(sp.Matrix([[z, -a], [0, z - 1]]), sp.Matrix([[1], [2]]))
    >>> G.shape, G.order, G.relative_degree
    ((2, 1), 2, 1)
    >>> G.expanded().num_matrix.T, G.den
    (Matrix([[2*a + z - 1, 2*z]]), z**2 - z)
    >>> G.equals(sp.Matrix([(z - 1 + 2 * a) / (z**2 - z), 2 / (z - 1)]))
    True
    """

    def __init__(self, D, N, dt=None):
        for value, name in ((D, "D"), (N, "N")):
            if not isinstance(value, sp.MatrixBase):
                raise SymctlTypeError(f"{name}: expected a sympy Matrix, got {value!r}")
        if D.rows != D.cols:
            raise DimensionError(f"D: expected a square matrix, got shape {D.shape}")
        if N.rows != D.rows:
            raise DimensionError(f"N: expected {D.rows} rows (those of D), got shape {N.shape}")
        D_m = sp.ImmutableMatrix(D.applyfunc(lambda e: to_expr(e, "D")))
        N_m = sp.ImmutableMatrix(N.applyfunc(lambda e: to_expr(e, "N")))
        for e in (*D_m, *N_m):
            if not e.is_polynomial(z):
                raise ParameterError(f"D/N: {e} is not a polynomial in z")
            finite_expr(e, "D/N")
        d = max(z_degree(e) for e in D_m)
        lead = D_m.applyfunc(lambda e: z_poly(e).coeff(d))
        if d < 0 or not all(e.is_zero is True for e in lead - sp.eye(D.rows)):
            raise ParameterError(
                f"D: expected a monic polynomial matrix (coefficient of z**{d} the "
                f"identity), got {lead.tolist()}"
            )
        object.__setattr__(self, "_D", D_m)
        object.__setattr__(self, "_N", N_m)
        object.__setattr__(self, "_degree", d)
        object.__setattr__(self, "dt", None if dt is None else sampling_time(dt, "dt"))
        object.__setattr__(self, "_cache", {})

    @property
    def D(self) -> sp.ImmutableMatrix:
        return self._D

    @property
    def N(self) -> sp.ImmutableMatrix:
        return self._N

    @property
    def shape(self) -> tuple[int, int]:
        return self._N.shape

    @property
    def order(self) -> int:
        """Degree of :math:`\\det D`: ``d m``."""
        return self._degree * self._D.rows

    @property
    def relative_degree(self) -> int:
        degrees = [z_degree(e) for e in self._N if e != 0]
        return self._degree - max(degrees) if degrees else int(1e9)

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        syms = set().union(*(e.free_symbols for e in (*self._D, *self._N)))
        return syms - {z}

    def terms_bound(self) -> int:
        r"""A bound on the terms of :math:`\operatorname{adj} D\, N` and :math:`\det D`: the permanent of
        the term counts (numbers only: ``(d m + 1)(1 + m p)``)."""
        m, p = self.shape
        if not self.free_symbols:
            return (self.order + 1) * (1 + m * p)
        adj, det = _adj_det(_term_counts(self._D), 0, signed=False)
        n_counts = _term_counts(self._N)
        return det + sum(
            adj[i][k] * n_counts[k][j] for i in range(m) for j in range(p) for k in range(m)
        )

    def expanded(self, max_terms: int = MAX_EXPANDED_TERMS) -> DiscreteTF:
        r""":math:`\operatorname{adj} D\, N / \det D` as a :class:`DiscreteTF`, fraction-free over
        :math:`\mathbb{Q}` (floats taken exactly, rounded once at the end); a ParameterError when
        symbols remain and :meth:`terms_bound` exceeds ``max_terms``."""
        max_terms = bounded_int(max_terms, "max_terms", 1, 10**9)
        got = self._cache.get("expanded")
        if got is not None:
            return got
        bound = self.terms_bound()
        if bound > max_terms and self.free_symbols:  # numbers: linear in the degree, never refused
            raise ParameterError(
                f"max_terms: expanding this {self._D.rows}x{self._D.rows} D(z)^-1 N(z) into "
                f"num/den would make up to {bound} polynomial terms, more than "
                f"max_terms = {max_terms}; work with G.D and G.N (the left fraction), "
                "substitute numbers first, or pass a larger max_terms to G.expanded()"
            )
        out = DiscreteTF(*_fraction_free(self._D, self._N), self.dt)
        self._cache["expanded"] = out
        return out

    @property
    def _num(self) -> sp.ImmutableMatrix:  # what every inherited method reads
        return self.expanded().num_matrix

    @property
    def den(self) -> sp.Expr:
        return self.expanded().den

    def __eq__(self, other) -> bool:
        if not isinstance(other, DiscreteTF):
            return NotImplemented
        if not isinstance(other, MatrixFractionTF):
            return False
        return (self._D, self._N, self.dt) == (other._D, other._N, other.dt)

    def __hash__(self) -> int:
        return hash((MatrixFractionTF, self._D, self._N, self.dt))

    def subs(self, *args, **kwargs) -> MatrixFractionTF:
        """Substitute symbols into ``D`` and ``N`` (as :meth:`DiscreteTF.subs`); stays a fraction."""
        rule, flags = subs_rule(args, kwargs, self.free_symbols | {z})
        dt = None if self.dt is None else _replaced(self.dt, rule, flags)
        return MatrixFractionTF(
            _replaced(self._D, rule, flags), _replaced(self._N, rule, flags), dt
        )

    def equals(self, other) -> bool:
        """Equality as rational functions; with the same ``D``, exactly ``N == N'`` (no expansion)."""
        if isinstance(other, MatrixFractionTF) and other.D == self._D:
            return other.shape == self.shape and all(
                sp.expand(a - b) == 0 for a, b in zip(self._N, other.N, strict=True)
            )
        return self.expanded().equals(other)

    def __mul__(self, other) -> DiscreteTF:
        """A scalar factor goes into ``N``; a product with a DiscreteTF is expanded."""
        if isinstance(other, sp.Expr | int | float) and not isinstance(other, bool):
            return MatrixFractionTF(self._D, self._N * other, self.dt)
        return DiscreteTF.__mul__(self.expanded(), other)

    __rmul__ = __mul__

    def _fraction(self) -> tuple[list, sp.MatrixBase, int]:
        d = self._degree  # D(z) G = N(z), D = sum_i D_i z^(d-i): Markov parameters unexpanded
        return [_z_coeffs(self._D, d - i) for i in range(d + 1)], self._N, d

    def latex(self) -> str:
        r"""``D(z)^{-1} N(z)``, unexpanded, each entry in descending powers of ``z``."""

        def matrix(M) -> str:  # entries in descending powers of z, as DiscreteTF prints them
            rows = r" \\ ".join(" & ".join(descending_latex(e) for e in row) for row in M.tolist())
            return rf"\left[\begin{{matrix}}{rows}\end{{matrix}}\right]"

        return rf"{matrix(self._D)}^{{-1}} {matrix(self._N)}"

    def __repr__(self) -> str:
        return f"MatrixFractionTF({self}, dt={self.dt})"

    def __str__(self) -> str:
        def rows(M):
            return ", ".join(
                "[" + ", ".join(descending_str(e) for e in row) + "]" for row in M.tolist()
            )

        return f"([{rows(self._D)}])^-1 [{rows(self._N)}]"


def _fraction_free(D: sp.MatrixBase, N: sp.MatrixBase) -> tuple[sp.Matrix, sp.Expr]:
    """``adj D N`` and ``det D`` in ``QQ[z, symbols]`` (exact; floats rounded once at the end)."""
    symbols = sorted(set().union(*(e.free_symbols for e in (*D, *N))) - {z}, key=_natural_key)
    gens = [z, *symbols]
    R = ring(gens, sp.QQ)[0]
    algebra, memo = RingFractions(R, gens), {}
    m, p = N.shape
    rows = []
    for i in range(m):  # one row of [D N], scaled by its denominators (none in z)
        pairs = [fold(e, algebra, memo) for e in (*D.row(i), *N.row(i))]
        scale = R.one
        for _, den in pairs:
            scale = scale if den.is_ground else scale.lcm(den)
        rows.append([num * scale.quo(den) for num, den in pairs])
    adj, det = _adj_det([row[:m] for row in rows], R.zero)
    num = [
        [sum((adj[i][k] * rows[k][m + j] for k in range(m)), R.zero) for j in range(p)]
        for i in range(m)
    ]
    has_float = any(e.atoms(sp.Float) for e in (*D, *N))

    def expr(poly) -> sp.Expr:
        if not has_float:
            return poly.as_expr()
        return sp.Add(
            *(
                sp.Float(sp.QQ.to_sympy(c)) * R.from_dict({mon: 1}).as_expr()
                for mon, c in poly.terms()
            )
        )

    out = sp.zeros(m, p)
    for i in range(m):
        for j in range(p):
            out[i, j] = expr(num[i][j])
    return out, expr(det)
