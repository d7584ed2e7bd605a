r"""Check that a realization realizes a transfer function: a proof, or a randomized test.

:func:`check_realization` decides whether a realization :math:`(F, H, M, N)`
(:class:`~symctl.realization.realization.Realization`) has the transfer function
:math:`G(z)`, i.e. whether :math:`M(zI - F)^{-1}H + N = G(z)` identically in
:math:`z` and in every free symbol (gains :math:`K_i`, :math:`\epsilon_i`,
:math:`C_i`, the entries of a similarity transform :math:`P`, ...). It returns
a :class:`RealizationCheck` with the verdict, the method and the evidence: a
counterexample (values of the symbols and of :math:`z` at which the two sides
differ) when they differ, the error bound of the randomized test when they agree.

Both methods compare Markov parameters, never :math:`(zI - F)^{-1}`. Write
:math:`G = \sum_{k \ge 0} h_k z^{-k}` and
:math:`M(zI-F)^{-1}H + N = N + \sum_{k \ge 1} M F^{k-1} H z^{-k}`.

**Theorem.** Let :math:`F` be :math:`n \times n` and :math:`G = B(z)/d(z)` be
proper with a monic denominator of degree :math:`d`. Then
:math:`M(zI-F)^{-1}H + N = G` if and only if :math:`e_0 = N - h_0 = 0` and
:math:`e_k = M F^{k-1} H - h_k = 0` for :math:`k = 1, \dots, n + d`.

*Proof.* With :math:`\chi(z) = \det(zI - F)`, the difference is
:math:`E(z) = P(z)/q(z)` with :math:`q = \chi d` monic of degree
:math:`L = n + d`, and :math:`\deg P \le L` because both sides are proper. From
:math:`P = q \sum_{k \ge 0} e_k z^{-k}` the coefficient of :math:`z^{L-j}` in
:math:`P` is :math:`e_j + \sum_{i<j} q_{L-j+i} e_i` for :math:`j = 0, \dots, L`:
a unit lower triangular map of :math:`(e_0, \dots, e_L)`. So
:math:`e_0 = \dots = e_L = 0` forces every coefficient of :math:`P` to vanish,
:math:`E = 0`. The converse is immediate. :math:`\square`

* ``method="exact"`` proves it. Entries become sparse multivariate
  polynomials over :math:`\mathbb{Z}` (python-flint's ``fmpz_mpoly``), each
  rational entry a pair (numerator, denominator). :math:`M F^{k-1} H` is met
  in the middle as :math:`(M F^a)(F^b H)`, :math:`a + b = k - 1`,
  :math:`|a - b| \le 1`; the rows of :math:`M F^a` and the columns of
  :math:`F^b H` are carried with one common denominator each and cancelled at
  every step (first by exact division by the denominator of :math:`F`, else by
  a gcd), so for a similarity transform, where :math:`M F^a = M_0 F_0^a P` and
  :math:`F^b H = P^{-1} F_0^b H_0`, :math:`\det P` never piles up.
  :math:`h_k` comes fraction-free from the recurrence of
  :meth:`~symctl.design.tf.DiscreteTF.markov`. Each :math:`e_k` is tested by
  cross-multiplication: a zero polynomial, or not.
* ``method="randomized"`` evaluates every entry exactly (rationals, no floats)
  at a point :math:`x` drawn uniformly from :math:`S^v`,
  :math:`S = \{-2^{b-1}, \dots, 2^{b-1}-1\}`, :math:`b \ge 62`, and compares the
  numeric Markov parameters. A difference found is a certain disproof. If the
  two sides differ as rational functions, some :math:`e_k` is
  :math:`E_k(x)/\Delta(x)^{k+1}` with a nonzero polynomial :math:`E_k` of
  total degree at most :math:`D_E = (L+1)A` (:math:`\Delta` a common
  denominator of all entries, :math:`A` a bound on the degrees of the entries'
  numerators over :math:`\Delta`; both read off the expression trees, see
  :class:`~symctl._util.exact.Degrees`). Points where a denominator vanishes are discarded and
  resampled (such points lie in :math:`\{\Delta = 0\}`). By the
  Schwartz–Zippel lemma one round misses with probability at most
  :math:`\varepsilon = D_E / (|S| - \deg \Delta)`; rounds are repeated until
  :math:`\varepsilon^r < 2^{-64}`, and :math:`\varepsilon^r` is reported.
* ``method="auto"`` runs the randomized test and, when it passes and the
  problem is small (:math:`n + d \le 10`), the exact proof. (Without free
  symbols the randomized test is one exact evaluation, a proof already.)

>>> from symctl import check_realization, controllable_canonical, z
>>> G = (z + 2) / (z**2 - z / 2)
>>> check_realization(controllable_canonical(G), G).ok
True
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction

import sympy as sp
from flint import fmpq, fmpq_mat, fmpz_mpoly_ctx
from flint.utils.flint_exceptions import DomainError

from symctl._util.display import LatexMixin, latex
from symctl._util.exact import Degrees, IntFractions, NotRational, PolyFractions, fold
from symctl._util.validate import as_random
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.realization.realization import Realization
from symctl.symbols import z

__all__ = ["RealizationCheck", "check_realization"]

METHODS = ("exact", "randomized", "auto")
TARGET_ERROR = Fraction(1, 2**64)
_MIN_BITS = 62  # |S| >= 2**62
_MAX_RESAMPLES = 64  # consecutive points on a pole before giving up
_AUTO_EXACT_ORDER = 10  # "auto" proves exactly when n + d <= this
_SPANS = (9, 99, 10**4, 10**9, 2**62)  # counterexample values: small ones first, for reading
_TRIES = 6


# ---------------------------------------------------------------- the result
@dataclass(frozen=True)
class RealizationCheck(LatexMixin):
    r"""The verdict of :func:`check_realization`, with its method and evidence.

    Attributes
    ----------
    ok : bool
        Whether :math:`M(zI-F)^{-1}H + N = G(z)`. ``False`` is always certain
        (a counterexample is attached); ``True`` is certain for
        ``method == "exact"`` and holds up to :attr:`error_bound` otherwise.
    method : str
        ``"exact"`` or ``"randomized"`` (the method that gave the verdict).
    error_bound : fractions.Fraction
        Probability bound of a wrong ``True``: ``0`` for an exact proof (and for
        a randomized test without free symbols, which is then exact), else the
        Schwartz–Zippel bound, below :math:`2^{-64}`.
    counterexample : dict or None
        ``None`` when ``ok``. Else ``{"values": {symbol: value, ..., z: value},
        "realization": ..., "G": ...}``: exact rational values of every free
        symbol and of :math:`z`, and the two sides evaluated there (scalars for
        SISO, matrices for MIMO), which differ.
    details : str
        What was compared, and which Markov parameter differs.
    markov_count : int
        Markov parameters compared, :math:`n + d + 1`.
    rounds : int
        Random points at which they were compared (``0`` for ``"exact"``).
    resampled : int
        Random points discarded because a denominator vanished there.
    degree_bound : int or None
        :math:`D_E`, the degree bound used in :attr:`error_bound` (randomized).
    sample_bits : int or None
        :math:`b` with :math:`|S| = 2^b` (randomized).

    Examples
    --------
    >>> from symctl import Realization, check_realization, z
    >>> result = check_realization(Realization([[2]], [[1]], [[1]], 0), 1 / (z - 3))
    >>> bool(result), result.counterexample["values"][z] != 3
    (False, True)
    >>> print(result.details)
    Markov parameter h_2: M F H != h_2 in entry (0, 0)
    """

    ok: bool
    method: str
    error_bound: Fraction
    counterexample: dict | None = field(hash=False)
    details: str
    markov_count: int
    rounds: int = 0
    resampled: int = 0
    degree_bound: int | None = None
    sample_bits: int | None = None

    def __bool__(self) -> bool:
        return self.ok

    def _log2_bound(self) -> float:
        r""":math:`\log_2` of :attr:`error_bound` (exact integers, so no underflow)."""
        bound = self.error_bound
        return math.log2(bound.numerator) - math.log2(bound.denominator)

    def __str__(self) -> str:
        if self.ok and self.error_bound == 0:
            return f"realizes G: proved exactly ({self.details})"
        if self.ok:
            return (
                f"realizes G with error probability <= 2^{self._log2_bound():.1f} "
                f"(randomized: {self.details})"
            )
        text = f"does not realize G ({self.method}): {self.details}"
        if self.counterexample is not None:
            cex = self.counterexample
            values = ", ".join(f"{s} = {v}" for s, v in cex["values"].items())
            text += f"; at {values}: realization = {cex['realization']}, G = {cex['G']}"
        return text

    def latex(self) -> str:
        lhs = r"M(zI-F)^{-1}H + N"
        if self.ok and self.error_bound == 0:
            return rf"{lhs} = G(z)\quad \text{{(exact proof)}}"
        if self.ok:
            bound = rf"\Pr[\text{{error}}] \le 2^{{{self._log2_bound():.1f}}}"
            return rf"{lhs} = G(z)\quad \text{{(randomized, }} {bound} \text{{)}}"
        if self.counterexample is None:
            return rf"{lhs} \ne G(z)"
        cex = self.counterexample
        values = ",\\ ".join(f"{latex(s)} = {latex(v)}" for s, v in cex["values"].items())
        return (
            rf"{lhs} \ne G(z):\quad \text{{at }} {values}:\quad "
            rf"{latex(cex['realization'])} \ne {latex(cex['G'])}"
        )


# ---------------------------------------------------------------- the problem
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


# ---------------------------------------------------------------- expression trees
class _Entries:
    r"""The entries of a problem as reduced pairs (numerator, denominator) of ``fmpz_mpoly``.

    Without ``values``: polynomials in the free symbols (the exact method).
    With ``values`` (symbol -> Fraction): constants, the exact values at that
    point (the ring has no variables); :class:`ZeroDivisionError` when a
    denominator vanishes there. The code that compares Markov parameters is
    the same for both.
    """

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
        pairs = [self.entry(e) for e in exprs]
        den = self.one
        for _, d in pairs:
            if d != den and not d.is_one():
                den = den * (d / den.gcd(d))
        return [n * (den / d) for n, d in pairs], den


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
    r"""The next :math:`\hat h_k = \delta^{k+1} h_k` of :meth:`DiscreteTF.markov`'s recurrence.

    :math:`h_k = b_k - \sum_{i=1}^{\min(k, d)} a_i h_{k-i}` over a common
    denominator :math:`\delta` of the coefficients (``b``, ``a`` are their
    numerators): :math:`\hat h_k = b_k \delta^k - \sum_i a_i \hat h_{k-i}
    \delta^{i-1}`, fraction-free.
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
    r"""The first :math:`(k, i, j)` with :math:`e_k[i, j] \ne 0`, or ``None`` (all agree).

    ``k = 0`` is the feed-through, ``k >= 1`` compares :math:`M F^{k-1} H` with
    :math:`h_k`; ``k`` runs to :math:`n + d` (the theorem of the module).
    :math:`M F^{k-1} H` is met in the middle, :math:`(M F^a)(F^b H)` with
    :math:`a + b = k - 1` and :math:`|a - b| \le 1`: rows of :math:`M F^a` and
    columns of :math:`F^b H` are carried over common denominators and cancelled
    at each step (``_cancel``), and their degrees grow only half as far.
    """
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
    rows = [alg.common(row) for row in problem.M]  # M F^steps[0], one per output
    cols = [alg.common(problem.H[m][j] for m in range(n)) for j in range(q)]  # F^steps[1] H
    steps = [0, 0]
    h: list = []
    scale = delta  # delta**(k+1)
    for k in range(n + problem.d + 1):
        h.append(_markov_next(b, a, h, delta, alg.zero))
        if k >= 2 and steps[0] <= steps[1]:
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
            if num * scale != h[k][i][j] * den:
                return k, i, j
        scale = scale * delta
    return None


def _step(A: list, vec: list, den, Fd, zero) -> tuple[list, object]:
    """``A vec / (den Fd)``, cancelled: one step of a row (``A = F^T``) or a column (``A = F``)."""
    product = [
        sum((Ai[m] * vec[m] for m in range(len(vec)) if not vec[m].is_zero()), zero) for Ai in A
    ]
    return _cancel(product, den, Fd)


def _markov_names(count: int) -> str:
    return "the Markov parameter h_0" if count == 1 else f"the Markov parameters h_0..h_{count - 1}"


def _describe(k: int, i: int, j: int) -> str:
    if k == 0:
        return f"feed-through: N != h_0 = G(oo) in entry ({i}, {j})"
    power = {1: "", 2: "F "}.get(k, f"F^{k - 1} ")
    return f"Markov parameter h_{k}: M {power}H != h_{k} in entry ({i}, {j})"


# ---------------------------------------------------------------- degree bounds
def _degree_bound(problem: _Problem) -> tuple[int, int]:
    r"""``(D_E, deg Delta)``: the Schwartz–Zippel degree and the degree of the bad set.

    Every entry is :math:`\hat p_e/\Delta` with :math:`\Delta` the lcm of the
    entries' ``q`` and :math:`\deg \hat p_e \le A = \max(\max_e(\pi_e + \deg\Delta -
    \deg q_e), \deg \Delta)`. :math:`M F^{k-1} H` and :math:`h_k` (a sum of
    products of at most :math:`k+1` coefficients) are then polynomials of degree
    :math:`\le (k+1)A` over :math:`\Delta^{k+1}`, so :math:`D_E = (n+d+1)A`.
    """
    algebra, memo, values = Degrees(), {}, []
    for where, e in problem.entries():
        try:
            values.append(fold(e, algebra, memo))
        except NotRational as exc:
            raise ParameterError(
                f"{where}: {exc.args[0]} is not a rational function of the symbols, in {e}"
            ) from None
    delta = algebra.merge((q for _, q in values), max)
    ddelta = algebra.deg(delta)
    A = max([ddelta, *(p + ddelta - algebra.deg(q) for p, q in values)])
    return (problem.n + problem.d + 1) * A, ddelta


# ---------------------------------------------------------------- evaluation at points
def _sides_at(problem: _Problem, alg: _Entries, zval: Fraction):
    """Both sides as ``fmpq_mat`` at ``alg``'s point and ``z = zval``; ``None`` at a pole."""
    n, d, (p, q) = problem.n, problem.d, problem.shape

    def value(e):
        num, den = alg.entry(e)
        return fmpq(_const(num), _const(den))

    def mat(rows, r: int, c: int):
        return fmpq_mat(r, c, [value(e) for row in rows for e in row])

    zf = fmpq(zval.numerator, zval.denominator)
    den = sum((value(c) * zf ** (d - i) for i, c in enumerate(problem.a)), fmpq(0))
    if den == 0:
        return None
    rhs = fmpq_mat(
        p,
        q,
        [
            sum((value(problem.b[k][i][j]) * zf ** (d - k) for k in range(d + 1)), fmpq(0)) / den
            for i in range(p)
            for j in range(q)
        ],
    )
    lhs = mat(problem.N, p, q)
    if n:
        zI_F = fmpq_mat(n, n, [zf if i == j else 0 for i in range(n) for j in range(n)])
        zI_F = zI_F - mat(problem.F, n, n)
        try:
            lhs = mat(problem.M, p, n) * zI_F.solve(mat(problem.H, n, q)) + lhs
        except ZeroDivisionError:
            return None
    return lhs, rhs


def _const(poly) -> int:
    return 0 if poly.is_zero() else int(poly.leading_coefficient())


def _sympy(value: fmpq_mat):
    entries = [sp.Rational(int(x.p), int(x.q)) for x in value.entries()]
    if len(entries) == 1:
        return entries[0]
    return sp.ImmutableMatrix(value.nrows(), value.ncols(), entries)


def _counterexample(problem: _Problem, rng: random.Random) -> dict | None:
    """Exact values of the symbols and of ``z`` where the two sides differ (small ones first)."""
    for span in _SPANS:
        for _ in range(_TRIES):
            values = {s: Fraction(rng.randint(-span, span)) for s in problem.symbols}
            alg = _Entries(problem.symbols, values)
            try:
                if _first_difference(problem, alg) is None:
                    continue  # the two sides agree at these values of the symbols
            except ZeroDivisionError:
                continue
            for _ in range(_TRIES):
                zval = Fraction(rng.randint(-span, span))
                sides = _sides_at(problem, alg, zval)
                if sides is not None and sides[0] != sides[1]:
                    point = {s: sp.Rational(v.numerator, v.denominator) for s, v in values.items()}
                    point[z] = sp.Rational(zval.numerator, zval.denominator)
                    return {"values": point, "realization": _sympy(sides[0]), "G": _sympy(sides[1])}
    return None


# ---------------------------------------------------------------- the two methods
def _exact(problem: _Problem, rng: random.Random) -> RealizationCheck:
    count = problem.n + problem.d + 1
    try:
        diff = _first_difference(problem, _Entries(problem.symbols))
    except ZeroDivisionError as exc:
        raise ParameterError(
            f"R, G: division by an expression that is identically zero: {exc}"
        ) from None
    if diff is None:
        details = f"{_markov_names(count)} of both sides agree as rational functions"
        return RealizationCheck(True, "exact", Fraction(0), None, details, count)
    return RealizationCheck(
        False, "exact", Fraction(0), _counterexample(problem, rng), _describe(*diff), count
    )


def _randomized(problem: _Problem, degrees: tuple[int, int], rng: random.Random):
    count = problem.n + problem.d + 1
    if not problem.symbols:  # nothing to sample: one exact evaluation decides
        diff = _first_difference(problem, _Entries((), {}))
        cex = None if diff is None else _counterexample(problem, rng)
        details = (
            f"no free symbols: {_markov_names(count)} of both sides agree"
            if diff is None
            else _describe(*diff)
        )
        return RealizationCheck(diff is None, "randomized", Fraction(0), cex, details, count, 1)
    degree, bad = degrees
    bits = max(_MIN_BITS, (degree + bad).bit_length() + 32)
    half = 2 ** (bits - 1)
    eps = Fraction(degree, 2 * half - bad)
    rounds = 1
    while eps**rounds >= TARGET_ERROR:
        rounds += 1
    resampled = 0
    for done in range(rounds):
        for _ in range(_MAX_RESAMPLES):
            values = {s: Fraction(rng.randrange(-half, half)) for s in problem.symbols}
            try:
                diff = _first_difference(problem, _Entries(problem.symbols, values))
                break
            except ZeroDivisionError:
                resampled += 1
        else:
            raise ParameterError(
                f"R, G: a denominator vanished at {_MAX_RESAMPLES} random points in a row; "
                "is one of them identically zero?"
            )
        if diff is not None:
            return RealizationCheck(
                False,
                "randomized",
                Fraction(0),
                _counterexample(problem, rng),
                f"{_describe(*diff)} at random point {done + 1}",
                count,
                done + 1,
                resampled,
                degree,
                bits,
            )
    details = (
        f"{_markov_names(count)} agree at {rounds} random points, 2^{bits} values per "
        f"symbol ({len(problem.symbols)} symbols, degree bound {degree})"
    )
    return RealizationCheck(
        True, "randomized", eps**rounds, None, details, count, rounds, resampled, degree, bits
    )


def check_realization(R: Realization, G, method: str = "exact", *, rng=None) -> RealizationCheck:
    r"""Decide whether :math:`M(zI - F)^{-1}H + N = G(z)`, exactly or by a randomized test.

    Parameters
    ----------
    R : Realization
        :math:`(F, H, M, N)`; entries numbers or rational functions of any
        sympy symbols (floats are taken as the exact binary rationals they are).
    G : DiscreteTF or sympy expression in :data:`symctl.z`
        A proper transfer function (matrix) of the same shape as ``R``.
    method : {"exact", "randomized", "auto"}
        ``"exact"``: a proof (the difference is the zero rational function).
        ``"randomized"``: exact evaluation at random points, error probability
        below :math:`2^{-64}`. ``"auto"``: randomized, then exact when
        :math:`n + d \le 10`. See the module notes for both and for the theorem
        that :math:`n + d + 1` Markov parameters decide.
    rng : None, int, random.Random or numpy.random.Generator, optional
        Source of the random points (and of the counterexample's values);
        ``None`` uses the operating system's entropy.

    Returns
    -------
    RealizationCheck
        Truthy when ``G`` is realized; with ``.counterexample`` when not.

    Raises
    ------
    SymctlTypeError
        ``R`` is not a :class:`Realization`, ``G`` not a transfer function, or
        ``rng`` of another type.
    DimensionError
        ``G`` has another shape than ``R``.
    ParameterError
        Unknown ``method``; ``G`` improper; entries that are not rational
        functions of their symbols, or that depend on ``z`` (in ``R``).

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import check_realization, controllable_canonical, z
    >>> from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3, gain_symbols
    >>> K0, K1, K2 = gain_symbols(2)
    >>> G2 = K0 / (C_1 * C_3) * (z - epsilon_1) * (z - epsilon_3) / (z**2 - K1 * z - K2)
    >>> R = controllable_canonical(G2).similar(sp.Matrix(2, 2, sp.symbols("p:4")))
    >>> check_realization(R, G2).ok
    True
    >>> result = check_realization(R, G2, "randomized", rng=1)
    >>> result.ok, result.error_bound < 2**-64
    (True, True)
    >>> bad = check_realization(R, G2 + 1 / z)
    >>> bad.ok, sorted(bad.counterexample)
    (False, ['G', 'realization', 'values'])
    """
    if not isinstance(method, str) or method not in METHODS:
        raise ParameterError(f"method: expected one of {', '.join(METHODS)}, got {method!r}")
    source = as_random(rng, "rng")
    problem = _problem(R, G)
    degrees = _degree_bound(problem)  # also refuses entries that are not rational, naming them
    if method == "exact":
        return _exact(problem, source)
    result = _randomized(problem, degrees, source)
    small = problem.n + problem.d <= _AUTO_EXACT_ORDER
    if method == "randomized" or not result.ok or result.error_bound == 0 or not small:
        return result
    return _exact(problem, source)
