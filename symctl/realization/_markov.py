"""Both sides of a realization check as exact entries, and their Markov parameters
(the machinery of :mod:`symctl.realization.check`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import sympy as sp
from flint import fmpz_mpoly_ctx
from flint.utils.flint_exceptions import DomainError

from symctl._util.exact import IntFractions, PolyFractions, fold
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.realization._similarity import over_lcm
from symctl.realization.realization import Realization
from symctl.symbols import z


@dataclass(frozen=True)
class _Problem:
    """The entries of both sides as sympy expressions, ready to be evaluated."""

    F: tuple
    H: tuple
    M: tuple
    N: tuple
    b: tuple  # b[k][i][j]: coefficient of z**(d-k) in G's numerator (i, j), k = 0..d
    a: tuple  # a[i]: coefficient of z**(d-i) in G's monic denominator, a[0] = 1
    symbols: tuple

    @property
    def n(self) -> int:
        return len(self.F)

    @property
    def d(self) -> int:
        return len(self.a) - 1

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.N), len(self.N[0])

    def entries(self):
        """``(where, expression)`` for every entry of both sides."""
        for name in "FHMN":
            for i, row in enumerate(getattr(self, name)):
                for j, e in enumerate(row):
                    yield f"R: {name}[{i}, {j}]", e
        for k, mat in enumerate(self.b):
            for e in (e for row in mat for e in row):
                yield f"G: numerator coefficient of z**{self.d - k}", e
        for i, e in enumerate(self.a):
            yield f"G: denominator coefficient of z**{self.d - i}", e


def _rows(mat: sp.MatrixBase) -> tuple:
    return tuple(tuple(mat.row(i)) for i in range(mat.shape[0]))


def _problem(R, G) -> _Problem:
    if not isinstance(R, Realization):
        raise SymctlTypeError(f"R: expected a Realization, got {type(R).__name__}")
    if not isinstance(G, DiscreteTF | sp.Basic | sp.MatrixBase):
        raise SymctlTypeError(
            f"G: expected a DiscreteTF or a sympy expression in z, got {type(G).__name__}"
        )
    tf = DiscreteTF.from_expr(G)
    if tf.shape != R.shape:
        raise DimensionError(
            f"G: shape {tf.shape} does not match the realization's (outputs, inputs) = {R.shape}"
        )
    if tf.relative_degree < 0:
        raise ParameterError(f"G: improper (numerator degree above denominator degree): {tf}")
    own = R.free_symbols
    if z in own:
        raise ParameterError("R: the entries of F, H, M, N must not depend on z")
    d = tf.order
    p, q = tf.shape
    nums = [
        [[0] * (d + 1 - len(c)) + c for c in (tf.num_coeffs(i, j) for j in range(q))]
        for i in range(p)
    ]
    b = tuple(
        tuple(tuple(sp.sympify(nums[i][j][k]) for j in range(q)) for i in range(p))
        for k in range(d + 1)
    )
    symbols = sorted(own | tf.free_symbols, key=sp.default_sort_key)
    return _Problem(
        _rows(R.F),
        _rows(R.H),
        _rows(R.M),
        _rows(R.N),
        b,
        tuple(tf.den_coeffs()),
        tuple(symbols),
    )


class _Entries:
    """Entries as reduced ``fmpz_mpoly`` pairs: polynomials in the symbols, or with ``values``
    the constants at that point (ZeroDivisionError where a denominator vanishes)."""

    def __init__(self, symbols, values: Mapping | None = None):
        nvars = len(symbols) if values is None else 0
        self.ctx = fmpz_mpoly_ctx.get(("x", nvars), "degrevlex")
        if values is None:
            self._algebra = PolyFractions(self.ctx, symbols)
        else:
            self._algebra = IntFractions(values)
        self.zero, self.one = self.ctx.constant(0), self.ctx.constant(1)
        self._memo: dict = {}

    def entry(self, expr: sp.Expr):
        """A reduced pair (numerator, denominator)."""
        num, den = fold(expr, self._algebra, self._memo)
        if isinstance(num, int):
            g = math.gcd(num, den)
            return self.ctx.constant(num // g), self.ctx.constant(den // g)
        g = num.gcd(den)
        return (num, den) if g.is_one() else (num / g, den / g)

    def common(self, exprs) -> tuple[list, object]:
        """Numerators over one common denominator (the lcm of the entries' ones)."""
        return over_lcm([self.entry(e) for e in exprs], self.one)


def _cancel(nums: list, den, factor) -> tuple[list, object]:
    """``nums / (den * factor)`` with common factors removed, dividing by ``factor`` first."""
    if factor.is_one():
        return nums, den
    try:
        return [x / factor for x in nums], den
    except DomainError:
        pass
    g = den * factor
    for x in nums:
        if g.is_one():
            break
        g = g.gcd(x)
    return [x / g for x in nums], den * factor / g


def _markov_next(b: tuple, a: list, h: list, scale, zero) -> list:
    r"""The next :math:`\hat h_k = \delta^{k+1} h_k` of :meth:`DiscreteTF.markov`'s recurrence,
    fraction-free: :math:`\hat h_k = b_k \delta^k - \sum_i a_i \hat h_{k-i} \delta^{i-1}`.
    """
    k, d = len(h), len(a) - 1
    rows, cols = len(b[0]), len(b[0][0])
    out = []
    for i in range(rows):
        row = []
        for j in range(cols):
            acc = b[k][i][j] * scale**k if k <= d else zero
            for s in range(1, min(k, d) + 1):
                acc = acc - a[s] * h[k - s][i][j] * scale ** (s - 1)
            row.append(acc)
        out.append(row)
    return out


def _first_difference(problem: _Problem, alg: _Entries) -> tuple[int, int, int] | None:
    r"""The first :math:`(k, i, j)` with :math:`e_k[i, j] \ne 0`, or ``None`` (all agree)."""
    for k, i, j, num, den, h, scale in _markov_pairs(problem, alg):
        if num * scale != h * den:
            return k, i, j
    return None


def _markov_pairs(problem: _Problem, alg: _Entries):
    r"""``(k, i, j, num, den, h, scale)`` with :math:`(M F^{k-1} H)[i, j] = num/den` (``N`` at
    ``k = 0``), :math:`h_k[i, j] = h/scale`, ``k <= n + d``; met in the middle as :math:`(M F^a)
    (F^b H)`, cancelled at each step, the side whose numerators have fewer terms advancing."""
    n, (p, q) = problem.n, problem.shape
    Fn, Fd = alg.common(e for row in problem.F for e in row)
    Fn = [Fn[i * n : (i + 1) * n] for i in range(n)]
    FnT = [list(col) for col in zip(*Fn, strict=True)]
    N = [[alg.entry(e) for e in row] for row in problem.N]
    coeffs, delta = alg.common([*(e for mat in problem.b for row in mat for e in row), *problem.a])
    nb = (problem.d + 1) * p * q
    b = [
        [coeffs[k * p * q + i * q : k * p * q + (i + 1) * q] for i in range(p)]
        for k in range(problem.d + 1)
    ]
    a = coeffs[nb:]
    rows = [alg.common(row) for row in problem.M]  # M F^a, one per output
    cols = [alg.common(problem.H[m][j] for m in range(n)) for j in range(q)]  # F^b H
    steps = [0, 0]  # a and b
    h: list = []
    scale = delta  # delta**(k+1)
    for k in range(n + problem.d + 1):
        h.append(_markov_next(b, a, h, delta, alg.zero))
        if k >= 2 and _rows_first(rows, cols, steps):
            rows = [_step(FnT, vec, den, Fd, alg.zero) for vec, den in rows]
            steps[0] += 1
        elif k >= 2:
            cols = [_step(Fn, vec, den, Fd, alg.zero) for vec, den in cols]
            steps[1] += 1
        for i, j in ((i, j) for i in range(p) for j in range(q)):
            if k == 0:
                num, den = N[i][j]
            else:
                (row, rden), (col, cden) = rows[i], cols[j]
                num = sum((row[m] * col[m] for m in range(n)), alg.zero)
                den = rden * cden
            yield k, i, j, num, den, h[k][i][j], scale
        scale = scale * delta


def _rows_first(rows, cols, steps) -> bool:
    """Whether the rows advance next: their numerators have fewer terms (benchmarks swap this)."""
    return _size(rows) <= _size(cols)


def _size(vectors) -> int:
    """Terms in the numerators of ``vectors`` (the cost of one more step with them)."""
    return sum(len(x) for vec, _ in vectors for x in vec)


def _step(A: list, vec: list, den, Fd, zero) -> tuple[list, object]:
    """``A vec / (den Fd)``, cancelled: one step of a row (``A = F^T``) or a column (``A = F``)."""
    product = [
        sum((Ai[m] * vec[m] for m in range(len(vec)) if not vec[m].is_zero()), zero) for Ai in A
    ]
    return _cancel(product, den, Fd)
