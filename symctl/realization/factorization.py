r"""The factorization :math:`G = G_3 G_2 G_1` that fits the controller to the delays.

The paper's section "Creating a compatible delayed controller": :math:`G_1` and :math:`G_3`
take the sensor and actuator delays (relative degrees :math:`d_s`, :math:`d_a`), one
first-order section per step, and :math:`G_2` keeps the rest,

.. math::
    G_1(z) = \prod_{i=1}^{d_s} \frac{C_{1,i}}{z - \epsilon_{1,i}},\qquad
    G_3(z) = \prod_{i=1}^{d_a} \frac{C_{3,i}}{z - \epsilon_{3,i}},\qquad
    G_2 = \frac{G}{G_1 G_3},

(symbols ``epsilon_1``, ``C_1`` for one section, ``epsilon_{1,i}``, ``C_{1,i}`` for more).
For the paper's :math:`d_s = d_a = 1` and :math:`G = K_0/(z^2 - K_1 z - K_2)`:

.. math::
    G_2 = \frac{K_0}{C_1 C_3}\,\frac{z^2 - (\epsilon_1+\epsilon_3) z + \epsilon_1\epsilon_3}
    {z^2 - K_1 z - K_2}
    = \frac{K_0}{C_1 C_3} + \frac{K_0}{C_1 C_3}\,
    \frac{(K_1 - \epsilon_1 - \epsilon_3) z + K_2 + \epsilon_1\epsilon_3}{z^2 - K_1 z - K_2}.
"""

from __future__ import annotations

import dataclasses
import random
from collections import Counter
from dataclasses import dataclass
from functools import cache

import sympy as sp
from flint import fmpq, fmpq_poly, fmpz_mpoly_ctx

from symctl._util.display import LatexMixin, descending_latex, latex
from symctl._util.exact import NotRational, PolyFractions, fold, products_equal
from symctl._util.serial import DictMixin
from symctl._util.validate import nonneg_int, relative_tolerance, subs_rule, to_expr
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError
from symctl.proof import Proof
from symctl.realization.channels import channel_sections, diagonal, mimo_G2, verify_entries
from symctl.realization.channels import section_symbols as section_symbols
from symctl.symbols import z

__all__ = [
    "EXPANDED_ZEROS_MAX",
    "Factorization",
    "factor",
    "remainder",
    "section_symbols",
    "sigma_symbols",
]

EXPANDED_ZEROS_MAX = 4
r"""Sections per entry of :math:`G_2` up to which symbolic realizations take its zeros multiplied
out (:math:`2^d` monomials); beyond, as :math:`\sigma_k` (:attr:`Factorization.G2_symbolic`)."""


@cache
@cache
def sigma_symbols(count: int, entry: tuple[int, int] | None = None) -> tuple[sp.Symbol, ...]:
    r"""The abbreviations :math:`\sigma_k = e_k(\epsilon)`, :math:`\prod_{i=1}^{d} (z - \epsilon_i)
    = \sum_{k=0}^{d} (-1)^k \sigma_k z^{d-k}` (``sigma_k``; ``entry=(i, j)``: ``sigma_{i,j,k}``)."""
    at = "{},{},".format(*entry) if entry else ""
    return tuple(
        sp.Symbol(f"sigma_{{{at}{k}}}" if at else f"sigma_{k}", real=True)
        for k in range(1, count + 1)
    )


def _zeros_poly(sigma: tuple) -> sp.Expr:
    d = len(sigma)
    return sp.Add(z**d, *((-1) ** k * s * z ** (d - k) for k, s in enumerate(sigma, start=1)))


def remainder(G2) -> tuple[sp.Expr, list[sp.Expr]]:
    r"""``(N, c)``: the feed-through of ``G2`` and the numerator of :math:`(G_2 - N)/N` (of
    ``G2`` when :math:`N = 0`) in descending powers of z (:attr:`Factorization.remainder_coeffs`)."""
    from symctl.realization.realization import split_proper

    N, c, _ = split_proper(G2)
    scale = N if N != 0 else 1
    return N, [sp.factor_terms(sp.cancel(ci / scale)) for ci in reversed(c)]


def _sections(eps, cs, dt) -> DiscreteTF:
    num = sp.Mul(*cs)
    den = sp.Mul(*(z - e for e in eps))
    return DiscreteTF(num, den, dt)


@dataclass(frozen=True)
class Factorization(DictMixin, LatexMixin):
    r"""The factors of :math:`G = G_3 G_2 G_1` and their symbols (built by :func:`factor`; a value).

    Attributes
    ----------
    G, G1, G2, G3 : DiscreteTF
    sensor_eps, sensor_C, actuator_eps, actuator_C : tuple of sympy expressions
        Poles and gains of the sections of ``G1`` and ``G3``; channel-major when MIMO.
    channels : (int, int)
        The measured signals (columns of ``G``) and the outputs (rows).

    Examples
    --------
    >>> from symctl import controller_tf, factor
    >>> f = factor(controller_tf(2))
    >>> f.G2.expr
    K_0*(-epsilon_1 + z)*(-epsilon_3 + z)/(C_1*C_3*(-K_1*z - K_2 + z**2))
    """

    G: DiscreteTF
    G1: DiscreteTF
    G2: DiscreteTF
    G3: DiscreteTF
    sensor_eps: tuple
    sensor_C: tuple
    actuator_eps: tuple
    actuator_C: tuple
    channels: tuple[int, int] = (1, 1)

    @property
    def is_siso(self) -> bool:
        return self.channels == (1, 1)

    @property
    def section_channels(self) -> tuple[tuple, tuple]:
        """``(eps, Cs)`` of each channel's sections: the measured signals', then the inputs'.

        >>> from symctl import controller_tf, factor
        >>> factor(controller_tf(2)).section_channels
        ((((epsilon_1,), (C_1,)),), (((epsilon_3,), (C_3,)),))
        """
        sides = ((self.sensor_eps, self.sensor_C), (self.actuator_eps, self.actuator_C))
        return tuple(
            tuple(zip(*(channel_sections(x, len(x) // k, k) for x in side), strict=True))
            for side, k in zip(sides, self.channels, strict=True)
        )

    @property
    def sensor_sections(self) -> tuple[DiscreteTF, ...]:
        """The diagonal of ``G1``, one per measured signal."""
        return tuple(_sections(e, c, self.G.dt) for e, c in self.section_channels[0])

    @property
    def actuator_sections(self) -> tuple[DiscreteTF, ...]:
        """The diagonal of ``G3``, one per output."""
        return tuple(_sections(e, c, self.G.dt) for e, c in self.section_channels[1])

    @property
    def N(self) -> sp.Expr:
        r"""Feed-through of :math:`G_2`, the same in every realization (:math:`K_0/(C_1C_3)`)."""
        from symctl.realization.realization import split_proper

        if not self.is_siso:
            n = self.G2.order
            return sp.Matrix(
                self.G2.num_matrix.applyfunc(lambda e: sp.Poly(e, z).coeff_monomial(z**n))
            )
        return split_proper(self.G2)[0]

    @property
    def strictly_proper(self) -> DiscreteTF:
        """:math:`G_2 - N`."""
        return DiscreteTF.from_expr(self.G2.expr - self.N, self.G2.dt)

    @property
    def remainder_coeffs(self) -> list[sp.Expr]:
        """:func:`remainder`'s coefficients (SISO)."""
        if not self.is_siso:
            raise DimensionError(
                f"remainder_coeffs: defined for a SISO factorization, this one has "
                f"{self.channels[0]} measured signals and {self.channels[1]} outputs"
            )
        return remainder(self.G2)[1]

    @property
    def poles(self) -> tuple:
        """The section poles, sensor side first (the zeros of :math:`G_2`)."""
        return (*self.sensor_eps, *self.actuator_eps)

    @property
    def sigma(self) -> tuple[sp.Symbol, ...]:
        r"""The :math:`\sigma` of :meth:`abbreviated`."""
        return tuple(self.sigma_poles)

    @property
    def sigma_poles(self) -> dict:
        r"""Each :math:`\sigma` of :meth:`abbreviated` with ``(k, poles)``: :math:`e_k` of the poles
        of its entry (:attr:`entry_poles`).

        >>> from symctl import controller_tf, factor
        >>> factor(controller_tf(2)).sigma_poles
        {sigma_1: (1, (epsilon_1, epsilon_3)), sigma_2: (2, (epsilon_1, epsilon_3))}
        """
        return {
            s: (k, poles)
            for entry, poles in self.entry_poles
            for k, s in enumerate(sigma_symbols(len(poles), entry), start=1)
        }

    @property
    def entry_poles(self) -> list[tuple]:
        """``((i, j), poles)`` per entry of :attr:`G2` (from 1; ``None`` when SISO): the poles of
        measured signal :math:`j`'s sections, then input :math:`i`'s.

        >>> from symctl import controller_tf, factor
        >>> factor(controller_tf(2)).entry_poles
        [(None, (epsilon_1, epsilon_3))]
        """
        if self.is_siso:
            return [(None, self.poles)]
        s, a = self.section_channels
        return [
            ((i + 1, j + 1), (*s[j][0], *a[i][0])) for i in range(len(a)) for j in range(len(s))
        ]

    @property
    def G2_symbolic(self) -> DiscreteTF:
        """:attr:`G2` up to :data:`EXPANDED_ZEROS_MAX` sections per entry, beyond :meth:`abbreviated`."""
        long = len(self.entry_poles[0][1]) > EXPANDED_ZEROS_MAX
        return self.abbreviated() if long else self.G2

    def abbreviated(self) -> DiscreteTF:
        r""":math:`G_2` with the coefficients of its zeros written as :math:`\sigma_k`: :math:`d`
        monomials instead of :math:`2^d`, so its realizations stay small at any delay (realized
        at :math:`\sigma = e(\epsilon)`, :meth:`sigma_values`; per entry when MIMO).

        Examples
        --------
        >>> from symctl import controller_tf, factor
        >>> f = factor(controller_tf(2))
        >>> f.abbreviated().expr
        K_0*(-sigma_1*z + sigma_2 + z**2)/(C_1*C_3*(-K_1*z - K_2 + z**2))
        >>> f.abbreviated().subs(f.sigma_values()).equals(f.G2)
        True
        """
        if not self.is_siso:
            sigma = {e: sigma_symbols(len(poles), e) for e, poles in self.entry_poles}
            m, p = self.channels
            ds, da = len(self.sensor_eps) // m, len(self.actuator_eps) // p
            sides = (self.sensor_eps, self.sensor_C, self.actuator_eps, self.actuator_C)
            return mimo_G2(
                self.G, *sides, ds, da, zeros=lambda i, j: _zeros_poly(sigma[i + 1, j + 1])
            )
        scale = sp.Mul(*self.sensor_C, *self.actuator_C)
        return DiscreteTF(self.G.num / scale * _zeros_poly(self.sigma), self.G.den, self.G.dt)

    def sigma_values(self, values=None) -> dict:
        r""":math:`\sigma_k = e_k(\epsilon)` of the section poles (at ``values`` of their symbols),
        keyed by :attr:`sigma`: exact numbers when every pole is a number, else polynomials.

        >>> from symctl import controller_tf, factor
        >>> factor(controller_tf(2)).sigma_values({"epsilon_1": "1/2", "epsilon_3": "1/3"})
        {sigma_1: 5/6, sigma_2: 1/6}
        """
        poles = {p: to_expr(p, "poles") for p in self.poles}
        if values is not None:
            free = set().union(*(p.free_symbols for p in poles.values()))
            rule, flags = subs_rule((values,), {}, free)
            poles = {k: p.subs(rule, **flags) for k, p in poles.items()}
        out = {}
        for entry, group in self.entry_poles:
            coeffs = _vieta([poles[p] for p in group])
            for k, (s, c) in enumerate(
                zip(sigma_symbols(len(group), entry), coeffs[1:], strict=True), 1
            ):
                out[s] = (-1) ** k * c
        return out

    def verify(self, rtol: float = 1e-9) -> Proof:
        """Exact proof that ``G3 * G2 * G1 == G`` (polynomial cross-multiplication); with floats
        failing it by rounding, :math:`n_3 n_2 n_1 d` and :math:`n d_3 d_2 d_1` compared in
        :math:`z` (other symbols at 8 random points), truthy within ``rtol``.

        >>> from symctl import controller_tf, factor
        >>> from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3, gain_symbols
        >>> K_0, K_1, K_2 = gain_symbols(2)
        >>> values = {K_0: -0.046, K_1: -0.58, K_2: -0.35, epsilon_1: 0.3, epsilon_3: -0.2}
        >>> f = factor(controller_tf(2)).subs({**values, C_1: 1, C_3: 1})
        >>> proof = f.verify()
        >>> bool(proof), proof.method.startswith("floating-point")
        (True, True)
        """
        rtol = relative_tolerance(rtol, "rtol")
        if not self.is_siso:
            holds = verify_entries(
                self.G, self.G2, self.sensor_sections, self.actuator_sections, _products_equal
            )
            return Proof(
                holds,
                "G3 G2 G1 = G",
                "entry by entry, g3_i (G2)_ij g1_j = G_ij: cross-multiplied numerators and "
                "denominators compared as polynomials",
                "" if holds else "an entry of G3 G2 G1 differs from G's",
            )
        left = [self.G3.num, self.G2.num, self.G1.num, self.G.den]
        right = [self.G.num, self.G3.den, self.G2.den, self.G1.den]
        holds = _products_equal(left, right)
        claim = "G3 G2 G1 = G"
        method = "cross-multiplied numerators and denominators compared as polynomials"
        if holds or not any(e.has(sp.Float) for e in (*left, *right)):
            evidence = "" if holds else "num(G3 G2 G1) den(G) - num(G) den(G3 G2 G1) is not zero"
            return Proof(holds, claim, method, evidence)
        worst = _relative_difference(sp.Mul(*left), sp.Mul(*right))
        ok = worst <= rtol
        return Proof(
            ok,
            claim,
            f"floating-point coefficients: {method} numerically, largest relative "
            f"coefficient difference {worst:.3g} {'<=' if ok else '>'} rtol = {rtol:g} "
            "(not equal exactly: the floats' binary rationals differ)",
            "" if ok else "num(G3 G2 G1) den(G) - num(G) den(G3 G2 G1) exceeds rtol",
        )

    def subs(self, *args, **kwargs) -> Factorization:
        """Substitute values (e.g. epsilons and Cs; text through the safe parser); a zero C is refused."""
        tfs = ("G", "G1", "G2", "G3")
        sides = {k: [to_expr(v, "sections") for v in getattr(self, k)] for k in _SECTIONS}
        symbols = set().union(
            *(getattr(self, k).free_symbols for k in tfs),
            *(v.free_symbols for values in sides.values() for v in values),
        )
        rule, flags = subs_rule(args, kwargs, symbols)
        out = dataclasses.replace(
            self,
            **{k: getattr(self, k).subs(rule, **flags) for k in tfs},
            **{k: tuple(v.subs(rule, **flags) for v in values) for k, values in sides.items()},
        )
        _check_C(out.sensor_C + out.actuator_C)
        return out

    def latex(self) -> str:
        """The three factors, :math:`G_2` as gain times zeros over poles (the paper's)."""
        g2 = self.G2.latex()
        if self.is_siso and self.N != 0:
            zeros = sp.Mul(*(z - e for e in self.poles))
            zeros_tex = descending_latex(sp.collect(sp.expand(zeros), z, evaluate=True))
            g2 = rf"{latex(self.N)} \frac{{{zeros_tex}}}{{{descending_latex(self.G2.den)}}}"
        return rf"G_1 = {self.G1.latex()},\quad G_2 = {g2},\quad G_3 = {self.G3.latex()}"


_SECTIONS = ("sensor_eps", "sensor_C", "actuator_eps", "actuator_C")


def _vieta(poles: list) -> list:
    r"""The coefficients of :math:`\prod (z - p)`, descending (exact when the poles are numbers)."""
    if all(p.is_Rational for p in poles):
        poly = fmpq_poly([1])
        for p in poles:
            poly *= fmpq_poly([-fmpq(int(p.p), int(p.q)), 1])
        return [sp.Rational(int(c.p), int(c.q)) for c in reversed(poly.coeffs())]
    return [sp.expand(c) for c in sp.Poly(sp.Mul(*(z - p for p in poles)), z).all_coeffs()]


def _check_C(values) -> None:
    for c in values:
        if to_expr(c, "C") == 0:
            raise ParameterError("C: the section gains C_1, C_3 must be nonzero, got C = 0")


def _section_values(value, count: int, argname: str, default) -> tuple:
    """``count`` section values: the symbols ``default``, one value for all, or one each."""
    if value is None:
        return default
    if isinstance(value, str) or not hasattr(value, "__len__"):
        value = [value] * count
    if len(value) != count:
        raise DimensionError(
            f"{argname}: expected {count} values (sensor sections first), got {len(value)}"
        )
    out = tuple(to_expr(v, f"{argname}[{i}]") for i, v in enumerate(value))
    for i, v in enumerate(out):
        if v.has(z):
            raise ParameterError(f"{argname}[{i}]: a section value cannot depend on z, got {v}")
    return out


def factor(G, sensor_delay: int = 1, actuator_delay: int = 1, *, eps=None, C=None) -> Factorization:
    r"""Split ``G`` into :math:`G_3 G_2 G_1` with relative degrees ``actuator_delay``, rest, ``sensor_delay``
    (a p x m ``G`` channel by channel, :mod:`symctl.realization.channels`).

    Parameters
    ----------
    G : DiscreteTF or sympy expression in ``z``
        A proper controller, e.g. :func:`symctl.controller_tf`.
    sensor_delay, actuator_delay : int
        Number of first-order sections in :math:`G_1` and :math:`G_3`.
    eps, C : sequence or value, optional
        The section poles and gains, sensor sections first (channel-major), one for all or one
        per section (text through the safe parser); default: :func:`section_symbols`.

    Returns
    -------
    Factorization
        :math:`G_2` of relative degree ``reldeg(G) - sensor_delay - actuator_delay``.

    Raises
    ------
    ParameterError, DimensionError
        Improper ``G``, its relative degree below the delays, negative delays, a zero ``C`` or
        a value in ``z``; ``eps``/``C`` of the wrong length, over 50 inputs or outputs.

    Examples
    --------
    >>> from symctl import controller_tf, factor
    >>> f = factor(controller_tf(3), sensor_delay=1, actuator_delay=2)
    >>> f.G1.expr, f.G3.relative_degree, f.G2.relative_degree
    (C_1/(-epsilon_1 + z), 2, 0)
    >>> bool(f.verify())
    True
    >>> factor(controller_tf(2), eps=["1/2", "-1/3"], C=1).G2.expr
    K_0*(z - 1/2)*(z + 1/3)/(-K_1*z - K_2 + z**2)
    """
    tf = DiscreteTF.from_expr(G)
    ds = nonneg_int(sensor_delay, "sensor_delay")
    da = nonneg_int(actuator_delay, "actuator_delay")
    rd = tf.relative_degree
    if rd < 0:
        raise ParameterError("G: improper (numerator degree above denominator degree)")
    if rd < ds + da:
        raise ParameterError(
            f"G: relative degree {rd} is below sensor_delay + actuator_delay = {ds + da}; "
            "no factorization puts the delays at the input and output"
        )
    p, m = tf.shape
    defaults = [_default_sections(1, ds, m, tf.is_siso), _default_sections(3, da, p, tf.is_siso)]
    count = m * ds + p * da
    eps_all = _section_values(eps, count, "eps", (*defaults[0][0], *defaults[1][0]))
    c_all = _section_values(C, count, "C", (*defaults[0][1], *defaults[1][1]))
    _check_C(c_all)
    e1, e3 = eps_all[: m * ds], eps_all[m * ds :]
    c1, c3 = c_all[: m * ds], c_all[m * ds :]
    g1, g3 = (
        tuple(
            _sections(e, c, tf.dt)
            for e, c in zip(channel_sections(es, k, n), channel_sections(cs, k, n), strict=True)
        )
        for es, cs, k, n in ((e1, c1, ds, m), (e3, c3, da, p))
    )
    if tf.is_siso:
        zeros = sp.Mul(*(z - e for e in (*e1, *e3)))
        G2 = DiscreteTF(tf.num / sp.Mul(*c1, *c3) * zeros, tf.den, tf.dt)
    else:
        G2 = mimo_G2(tf, e1, c1, e3, c3, ds, da)
    return Factorization(tf, diagonal(g1, tf.dt), G2, diagonal(g3, tf.dt), e1, c1, e3, c3, (m, p))


def _default_sections(side: int, count: int, channels: int, siso: bool) -> tuple[tuple, tuple]:
    """The section symbols of one side, channel-major: ``(epsilons, Cs)``."""
    if not count:
        return (), ()
    if siso:
        return section_symbols(side, count)
    per = [section_symbols(side, count, j) for j in range(1, channels + 1)]
    return tuple(e for es, _ in per for e in es), tuple(c for _, cs in per for c in cs)


def _factors(exprs) -> Counter:
    """The product of ``exprs`` as a multiset of bases with integer exponents (numbers folded)."""
    out: Counter = Counter()
    number = sp.Integer(1)
    for e in exprs:
        for f in sp.Mul.make_args(e):
            if f.is_Number:
                number *= f
                continue
            base, exp = f.as_base_exp()
            if exp.is_Integer:
                out[base] += int(exp)
            else:
                out[f] += 1
    out[number] += 1
    return out


def _products_equal(left: list[sp.Expr], right: list[sp.Expr]) -> bool:
    """Exact ``prod(left) == prod(right)``: identical factors cancelled, the rest in python-flint."""
    zero_left, zero_right = (any(e == 0 for e in side) for side in (left, right))
    if zero_left or zero_right:  # a zero factor: cancelling the others would hide it
        return zero_left and zero_right
    lf, rf = _factors(left), _factors(right)
    net = {b: lf.get(b, 0) - rf.get(b, 0) for b in {*lf, *rf}}
    exprs = [
        sp.Mul(*(b**k for b, k in net.items() if k > 0)),
        sp.Mul(*(b ** (-k) for b, k in net.items() if k < 0)),
    ]
    symbols = sorted(set().union(*(e.free_symbols for e in exprs)), key=str) or [z]
    try:
        ctx = fmpz_mpoly_ctx.get(("x", len(symbols)), "degrevlex")
        algebra, memo = PolyFractions(ctx, symbols), {}
        (nl, dl), (nr, dr) = (fold(e, algebra, memo) for e in exprs)
    except (NotRational, ZeroDivisionError):
        return products_equal(left, right)
    return nl * dr == nr * dl


def _relative_difference(left: sp.Expr, right: sp.Expr, points: int = 8) -> float:
    r"""The largest coefficient of ``left - right`` in :math:`z` over the largest of either side,
    the worst over ``points`` seeded values of the other symbols in :math:`\pm(0, 2]`."""
    exact = {f: sp.Rational(f) for f in (left.atoms(sp.Float) | right.atoms(sp.Float))}
    left, right = left.xreplace(exact), right.xreplace(exact)
    symbols = sorted((left.free_symbols | right.free_symbols) - {z}, key=sp.default_sort_key)
    rng = random.Random(0)
    worst, found = 0.0, 0
    for _ in range(points * 8):
        values = {
            s: sp.Rational(rng.choice((-1, 1)) * rng.randint(1, 2**10), 2**9) for s in symbols
        }
        try:
            lhs = sp.Poly(sp.cancel(left.xreplace(values)), z, domain=sp.QQ).all_coeffs()
            rhs = sp.Poly(sp.cancel(right.xreplace(values)), z, domain=sp.QQ).all_coeffs()
        except (sp.PolynomialError, ZeroDivisionError, sp.polys.polyerrors.CoercionFailed):
            continue
        size = max(abs(c) for c in (*lhs, *rhs))
        width = max(len(lhs), len(rhs))
        lhs, rhs = [0] * (width - len(lhs)) + lhs, [0] * (width - len(rhs)) + rhs
        diff = max(abs(a - b) for a, b in zip(lhs, rhs, strict=True))
        worst = max(worst, float(diff / size) if size else 0.0)
        found += 1
        if found == points or not symbols:
            break
    return worst
