r"""Check that a realization realizes a transfer function: a proof, or a randomized test.

Both methods compare Markov parameters, never :math:`(zI - F)^{-1}`: write :math:`G =
\sum_{k \ge 0} h_k z^{-k}` and :math:`M(zI-F)^{-1}H + N = N + \sum_{k \ge 1} M F^{k-1} H z^{-k}`.

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
"""

from __future__ import annotations

import dataclasses
import math
import random
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction

import sympy as sp
from flint import fmpq, fmpq_mat

from symctl._util.display import LatexMixin, latex
from symctl._util.exact import Degrees, NotRational, fold, from_fmpq_mat
from symctl._util.validate import as_random, relative_tolerance, to_expr, to_matrix
from symctl.errors import ParameterError, SymctlTypeError
from symctl.proof import Verdict
from symctl.realization._markov import (
    _Entries,
    _first_difference,
    _markov_pairs,
    _Problem,
    _problem,
)
from symctl.realization.realization import Realization
from symctl.symbols import z

__all__ = ["RealizationCheck", "check_realization", "require_stable_sections"]

METHODS = ("exact", "randomized", "auto")
TARGET_ERROR = Fraction(1, 2**64)
_MIN_BITS = 62  # |S| >= 2**62
_MAX_RESAMPLES = 64  # consecutive points on a pole before giving up
_AUTO_EXACT_ORDER = 10  # "auto" proves exactly when n + d <= this
_SPANS = (9, 99, 10**4, 10**9, 2**62)  # counterexample values: small ones first, for reading
_TRIES = 6
RTOL = 1e-9  # default tolerance of the numeric verdict for floating-point inputs
_NUMERIC_POINTS = 8  # points of the symbols at which floating-point inputs are compared


@dataclass(frozen=True)
class RealizationCheck(Verdict, LatexMixin):
    r"""The verdict of :func:`check_realization`: truthy by :attr:`ok` for exact inputs, by
    :attr:`numeric_ok` for floating-point ones.

    Attributes
    ----------
    ok : bool
        Whether :math:`M(zI-F)^{-1}H + N = G(z)`: ``False`` is certain, ``True`` up to
        :attr:`error_bound`.
    method : str
        ``"exact"`` or ``"randomized"``.
    error_bound : fractions.Fraction
        Probability of a wrong ``True``: 0 when exact, else the Schwartz–Zippel bound.
    counterexample : dict or None
        ``{"values": {symbol: value, ..., z: value}, "realization": ..., "G": ...}``, exact
        values where the sides differ.
    details : str
        What was compared, and which Markov parameter differs.
    markov_count, rounds, resampled : int
        Markov parameters compared (:math:`n + d + 1`), random points used, and points
        discarded on a vanishing denominator.
    degree_bound, sample_bits : int or None
        :math:`D_E` and :math:`b` (:math:`|S| = 2^b`) of the randomized bound.
    floating : bool
        Whether ``R`` or ``G`` holds a float (:attr:`ok` then judges its binary rational).
    max_relative_difference, rtol : float or None
        For floats, the largest :math:`|e_k[i, j]|` over the largest Markov parameter (with
        symbols: the worst of 8 random points in :math:`\pm(0, 2]`), and its tolerance.
    numeric_ok : bool or None
        ``max_relative_difference <= rtol`` (None for exact inputs).

    Examples
    --------
    >>> from symctl import Realization, check_realization, z
    >>> result = check_realization(Realization([[2]], [[1]], [[1]], 0), 1 / (z - 3))
    >>> bool(result), result.counterexample["values"][z] != 3
    (False, True)
    >>> result.details
    'Markov parameter h_2: M F H != h_2 in entry (0, 0)'
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
    floating: bool = False
    max_relative_difference: float | None = None
    rtol: float | None = None
    numeric_ok: bool | None = None

    @property
    def verdict(self) -> bool:
        return bool(self.numeric_ok) if self.floating else self.ok

    @property
    def evidence(self):
        """The :attr:`error_bound` (0: proved) when it holds, else the :attr:`counterexample`."""
        return self.error_bound if self.verdict else self.counterexample

    def _numeric_text(self) -> str:
        relation = "<=" if self.numeric_ok else ">"
        verdict = "agree" if self.numeric_ok else "differ"
        return (
            f"floating-point inputs: numerically {verdict} at rtol = {self.rtol:g} "
            f"(largest relative difference {self.max_relative_difference:.3g} {relation} "
            f"{self.rtol:g})"
        )

    def _log2_bound(self) -> float:
        bound = self.error_bound  # exact integers: no underflow
        return math.log2(bound.numerator) - math.log2(bound.denominator)

    def __str__(self) -> str:
        if self.floating and not self.ok:
            return f"{self._numeric_text()}; exact: {self._exact_str()}"
        if self.floating:
            return f"{self._exact_str()}; {self._numeric_text()}"
        return self._exact_str()

    def _exact_str(self) -> str:
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
        if not self.floating or self.ok:
            return self._exact_latex()
        relation, rel = (r"\approx", r"\le") if self.numeric_ok else (r"\not\approx", ">")
        return (
            rf"M(zI-F)^{{-1}}H + N {relation} G(z)\quad \text{{(floating-point inputs: "
            rf"largest relative difference }} {latex(sp.Float(self.max_relative_difference, 3))}"
            rf" {rel} {latex(sp.Float(self.rtol, 3))}\text{{; not equal exactly)}}"
        )

    def _exact_latex(self) -> str:
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


def _markov_names(count: int) -> str:
    return "the Markov parameter h_0" if count == 1 else f"the Markov parameters h_0..h_{count - 1}"


def _describe(k: int, i: int, j: int) -> str:
    if k == 0:
        return f"feed-through: N != h_0 = G(oo) in entry ({i}, {j})"
    power = {1: "", 2: "F "}.get(k, f"F^{k - 1} ")
    return f"Markov parameter h_{k}: M {power}H != h_{k} in entry ({i}, {j})"


def _degree_bound(problem: _Problem) -> tuple[int, int]:
    r"""``(D_E, deg Delta)``: each entry is :math:`\hat p_e/\Delta`, :math:`\deg \hat p_e \le A`,
    so :math:`\deg e_k \le (k+1)A` and :math:`D_E = (n+d+1)A`."""
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
    M = from_fmpq_mat(value)
    return M[0, 0] if M.shape == (1, 1) else M


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


def _exact(problem: _Problem, rng: random.Random, values=None) -> RealizationCheck:
    count = problem.n + problem.d + 1
    try:
        diff = _first_difference(problem, _Entries(problem.symbols, values))
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
        return dataclasses.replace(_exact(problem, rng, {}), method="randomized", rounds=1)
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


def _relative_difference(problem: _Problem, values: Mapping) -> Fraction:
    """The normwise relative difference of the Markov parameters at ``values`` (exact)."""
    alg = _Entries(problem.symbols, values)
    worst, size = Fraction(0), Fraction(0)
    for _, _, _, num, den, h, scale in _markov_pairs(problem, alg):
        lhs = Fraction(_const(num), _const(den))
        rhs = Fraction(_const(h), _const(scale))
        worst = max(worst, abs(lhs - rhs))
        size = max(size, abs(lhs), abs(rhs))
    return worst / size if size else Fraction(0)


def _numeric(problem: _Problem, rng: random.Random) -> Fraction:
    """:attr:`RealizationCheck.max_relative_difference`, exact."""
    if not problem.symbols:
        return _relative_difference(problem, {})
    worst, found = Fraction(0), 0
    for _ in range(_NUMERIC_POINTS * _MAX_RESAMPLES):
        values = {
            s: Fraction(rng.choice((-1, 1)) * rng.randint(1, 2**10), 2**9) for s in problem.symbols
        }
        try:
            worst = max(worst, _relative_difference(problem, values))
        except ZeroDivisionError:
            continue
        found += 1
        if found == _NUMERIC_POINTS:
            break
    return worst


def _with_numeric(result: RealizationCheck, problem: _Problem, rng, rtol: float):
    if not any(e.has(sp.Float) for _, e in problem.entries()):
        return result
    worst = Fraction(0) if result.ok else _numeric(problem, rng)
    return dataclasses.replace(
        result,
        floating=True,
        max_relative_difference=float(worst),
        rtol=rtol,
        numeric_ok=worst <= Fraction(rtol),
    )


def _similarity_holds(R: Realization, base: Realization, P) -> bool:
    r"""Exactly :math:`P F = F_0 P`, :math:`P H = H_0`, :math:`M = M_0 P`, :math:`N = N_0`,
    :math:`\det P \ne 0`, multiplied out (False when an entry is not rational)."""
    from flint import fmpz_mpoly_ctx

    from symctl._util.exact import PolyFractions

    P = sp.Matrix(P)
    if P.shape != (R.n, R.n) or base.shape != R.shape or base.n != R.n:
        return False
    mats = (P, R.F, R.H, R.M, R.N, base.F, base.H, base.M, base.N)
    symbols = sorted(set().union(*(m.free_symbols for m in mats)), key=str) or [z]
    ctx = fmpz_mpoly_ctx.get(("x", len(symbols)), "degrevlex")
    alg, memo = PolyFractions(ctx, symbols), {}
    try:
        Pf, F, H, M, N, F0, H0, M0, N0 = (
            [[fold(m[i, j], alg, memo) for j in range(m.cols)] for i in range(m.rows)] for m in mats
        )
    except (NotRational, ZeroDivisionError):
        return False

    def product(A, B):  # an empty inner dimension only meets n = 0: empty columns too
        cols = len(B[0]) if B else 0
        return [
            [alg.add([alg.mul([a[k], B[k][j]]) for k in range(len(B))]) for j in range(cols)]
            for a in A
        ]

    def same(A, B):
        return all(
            a[0] * b[1] == b[0] * a[1]
            for ra, rb in zip(A, B, strict=True)
            for a, b in zip(ra, rb, strict=True)
        )

    if R.n and sp.Matrix(P).det(method="bareiss") == 0:
        return False
    return (
        same(product(Pf, F), product(F0, Pf))
        and same(product(Pf, H), H0)
        and same(M, product(M0, Pf))
        and same(N, N0)
    )


def check_realization(
    R: Realization,
    G,
    method: str = "exact",
    *,
    rng=None,
    rtol: float = RTOL,
    similar_to: tuple | None = None,
) -> RealizationCheck:
    r"""Decide whether :math:`M(zI - F)^{-1}H + N = G(z)`, exactly or by a randomized test.

    Parameters
    ----------
    R : Realization
        Entries rational functions of any symbols (floats as their exact binary rationals).
    G : DiscreteTF or sympy expression in :data:`symctl.z`
        Proper, of ``R``'s shape.
    method : {"exact", "randomized", "auto"}
        A proof; exact evaluation at random points (error probability below :math:`2^{-64}`);
        or randomized, then exact when :math:`n + d \le 10`.
    rng : None, int, random.Random or numpy.random.Generator, optional
        Source of the random points and counterexamples.
    rtol : float, optional
        Tolerance of the numeric verdict for floating-point inputs.
    similar_to : (Realization, matrix), optional
        ``(base, P)`` with ``R`` claimed ``base.similar(P)``: the similarity is checked exactly
        and ``base`` decided (much faster for a dense ``R``); else ``R`` is decided directly.

    Returns
    -------
    RealizationCheck

    Raises
    ------
    SymctlTypeError, DimensionError
        ``R``, ``G`` or ``rng`` of another type; ``G`` of another shape.
    ParameterError
        Unknown ``method``; ``rtol`` not in (0, 1); ``G`` improper; entries not rational or
        depending on ``z``.

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

    Floating-point inputs are judged exactly and numerically, side by side:

    >>> from symctl import Realization
    >>> G = 0.1 / (z - 0.3)
    >>> R = Realization([[0.3]], [[1]], [[0.1 * (1 + 2**-52)]], 0)
    >>> result = check_realization(R, G)
    >>> bool(result), result.ok, result.floating, result.max_relative_difference < 1e-15
    (True, False, True, True)
    """
    if not isinstance(method, str) or method not in METHODS:
        raise ParameterError(f"method: expected one of {', '.join(METHODS)}, got {method!r}")
    if similar_to is not None:
        base, P = _similar_to(similar_to)
        if isinstance(R, Realization) and _similarity_holds(R, base, P):
            result = check_realization(base, G, method, rng=rng, rtol=rtol)
            return dataclasses.replace(
                result,
                details=(
                    "similar to a realization (F0, H0, M0, N0) by P: P F = F0 P, P H = H0, "
                    "M = M0 P, N = N0 and det P != 0 proved exactly, so both have one transfer "
                    f"function; the base: {result.details}"
                ),
            )
    source = as_random(rng, "rng")
    rtol = relative_tolerance(rtol, "rtol")
    problem = _problem(R, G)
    degrees = _degree_bound(problem)  # also refuses entries that are not rational, naming them
    if method == "exact":
        return _with_numeric(_exact(problem, source), problem, source, rtol)
    result = _randomized(problem, degrees, source)
    small = problem.n + problem.d <= _AUTO_EXACT_ORDER
    if method == "randomized" or not result.ok or result.error_bound == 0 or not small:
        return _with_numeric(result, problem, source, rtol)
    return _with_numeric(_exact(problem, source), problem, source, rtol)


def _similar_to(value) -> tuple[Realization, sp.Matrix]:
    if not (isinstance(value, tuple) and len(value) == 2 and isinstance(value[0], Realization)):
        raise SymctlTypeError(
            f"similar_to: expected a pair (Realization, P), got {type(value).__name__}"
        )
    return value[0], to_matrix(value[1], "similar_to[1]")


def require_stable_sections(epsilons, argname: str) -> None:
    r"""Refuse (ParameterError naming ``argname``) section poles :math:`|\epsilon| \ge 1`, or
    such ends of the interval they are drawn from: hidden unstable modes, which :math:`G_2`
    cancels. Symbols pass."""
    for value in epsilons:
        e = to_expr(value, argname)
        if e.is_number and abs(complex(e)) >= 1:
            raise ParameterError(
                f"{argname}: {value!r} has |epsilon| >= 1: a section C/(z - epsilon) with it is "
                "unstable, and G3 G2 G1 hides it (G2 cancels it with a zero), so the circuit "
                "would be internally unstable although its transfer function is right"
            )
