r"""The factorization :math:`G = G_3 G_2 G_1` that fits the controller to the delays.

The paper's section "Creating a compatible delayed controller": the sensor side
:math:`G_1` and the actuator side :math:`G_3` take the delays
(relative degrees :math:`d_s` and :math:`d_a`), and :math:`G_2` keeps the rest.
Each delay step is one first-order section with its own symbols,

.. math::
    G_1(z) = \prod_{i=1}^{d_s} \frac{C_{1,i}}{z - \epsilon_{1,i}},\qquad
    G_3(z) = \prod_{i=1}^{d_a} \frac{C_{3,i}}{z - \epsilon_{3,i}},\qquad
    G_2 = \frac{G}{G_1 G_3},

named ``epsilon_1``, ``C_1`` (``epsilon_3``, ``C_3``) when a side has one
section, as in the paper, and ``epsilon_{1,i}``, ``C_{1,i}`` otherwise. For the
paper's :math:`d_s = d_a = 1` and :math:`G = K_0/(z^2 - K_1 z - K_2)`:

.. math::
    G_2 = \frac{K_0}{C_1 C_3}\,\frac{z^2 - (\epsilon_1+\epsilon_3) z + \epsilon_1\epsilon_3}
    {z^2 - K_1 z - K_2}
    = \frac{K_0}{C_1 C_3} + \frac{K_0}{C_1 C_3}\,
    \frac{(K_1 - \epsilon_1 - \epsilon_3) z + K_2 + \epsilon_1\epsilon_3}{z^2 - K_1 z - K_2}.

>>> from symctl import controller_tf, factor
>>> f = factor(controller_tf(2))
>>> f.N
K_0/(C_1*C_3)
>>> f.remainder_coeffs
[K_1 - epsilon_1 - epsilon_3, K_2 + epsilon_1*epsilon_3]
>>> bool(f.verify())
True
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from functools import cache

import sympy as sp

from symctl import symbols as S
from symctl._util.display import LatexMixin, descending_latex, latex
from symctl._util.exact import products_equal
from symctl._util.proof import Proof
from symctl._util.validate import nonneg_int, relative_tolerance, subs_rule, to_expr
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError
from symctl.symbols import z

__all__ = ["Factorization", "factor", "section_symbols"]


@cache
def section_symbols(side: int, count: int) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Symbol, ...]]:
    """The ``(epsilons, Cs)`` of the ``count`` first-order sections on side 1 or 3.

    >>> from symctl.realization.factorization import section_symbols
    >>> section_symbols(1, 1)
    ((epsilon_1,), (C_1,))
    >>> section_symbols(3, 2)
    ((epsilon_{3,1}, epsilon_{3,2}), (C_{3,1}, C_{3,2}))
    """
    if side not in (1, 3):
        raise ParameterError(f"side: must be 1 (sensor) or 3 (actuator), got {side!r}")
    if count == 1:
        return ((S.epsilon_1,), (S.C_1,)) if side == 1 else ((S.epsilon_3,), (S.C_3,))
    eps = tuple(sp.Symbol(f"epsilon_{{{side},{i}}}", real=True) for i in range(1, count + 1))
    cs = tuple(sp.Symbol(f"C_{{{side},{i}}}", real=True) for i in range(1, count + 1))
    return eps, cs


def _sections(eps, cs, dt) -> DiscreteTF:
    num = sp.Mul(*cs)
    den = sp.Mul(*(z - e for e in eps))
    return DiscreteTF(num, den, dt)


@dataclass(frozen=True)
class Factorization(LatexMixin):
    r"""The factors of :math:`G = G_3 G_2 G_1` and their symbols.

    Attributes
    ----------
    G, G1, G2, G3 : DiscreteTF
    sensor_eps, sensor_C, actuator_eps, actuator_C : tuple of sympy expressions
        Poles and gains of the first-order sections of ``G1`` and ``G3`` (symbols,
        or values after :meth:`subs`).

    Built by :func:`factor`; compares and hashes by value.

    Examples
    --------
    >>> from symctl import controller_tf, factor
    >>> f = factor(controller_tf(2))
    >>> f.sensor_eps, f.actuator_C
    ((epsilon_1,), (C_3,))
    >>> f.G2.expr
    K_0*(-epsilon_1 + z)*(-epsilon_3 + z)/(C_1*C_3*(-K_1*z - K_2 + z**2))
    >>> f == factor(controller_tf(2))
    True
    """

    G: DiscreteTF
    G1: DiscreteTF
    G2: DiscreteTF
    G3: DiscreteTF
    sensor_eps: tuple
    sensor_C: tuple
    actuator_eps: tuple
    actuator_C: tuple

    @property
    def N(self) -> sp.Expr:
        r"""Feed-through of :math:`G_2`, the same in every realization (:math:`K_0/(C_1C_3)`)."""
        from symctl.realization.realization import split_proper

        return split_proper(self.G2)[0]

    @property
    def strictly_proper(self) -> DiscreteTF:
        """:math:`G_2 - N`."""
        return DiscreteTF.from_expr(self.G2.expr - self.N, self.G2.dt)

    @property
    def remainder_coeffs(self) -> list[sp.Expr]:
        r"""Numerator of :math:`(G_2 - N)/N` in descending powers of z.

        The paper's :math:`[K_1 - \epsilon_1 - \epsilon_3,\ K_2 + \epsilon_1\epsilon_3]`;
        when :math:`N = 0` the numerator of :math:`G_2` itself.
        """
        from symctl.realization.realization import split_proper

        N, c, _ = split_proper(self.G2)
        scale = N if N != 0 else 1
        return [sp.factor_terms(sp.cancel(ci / scale)) for ci in reversed(c)]

    def verify(self, rtol: float = 1e-9) -> Proof:
        """Exact proof that ``G3 * G2 * G1 == G`` (polynomial cross-multiplication).

        Parameters
        ----------
        rtol : float, optional
            Tolerance of the numeric verdict for floating-point coefficients
            (e.g. gains substituted as floats); unused for exact ones.

        Returns
        -------
        Proof
            Truthy when the identity holds, with its method. When a coefficient
            is a floating-point number and the exact identity fails (the floats'
            binary rationals differ by rounding), the verdict is the numeric one:
            the cross-multiplied sides :math:`n_3 n_2 n_1 d` and :math:`n d_3 d_2 d_1`
            compared as polynomials in :math:`z` (with every other symbol at 8
            random points in :math:`\\pm(0, 2]`), truthy when the largest
            coefficient difference relative to the largest coefficient is at most
            ``rtol``; the method says so and states that difference and ``rtol``.

        Examples
        --------
        >>> from symctl import controller_tf, factor
        >>> bool(factor(controller_tf(3), 1, 2).verify())
        True
        >>> from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3, gain_symbols
        >>> K_0, K_1, K_2 = gain_symbols(2)
        >>> values = {K_0: -0.046, K_1: -0.58, K_2: -0.35, epsilon_1: 0.3, epsilon_3: -0.2}
        >>> f = factor(controller_tf(2)).subs({**values, C_1: 1, C_3: 1})
        >>> proof = f.verify()
        >>> bool(proof), proof.method.startswith("floating-point")
        (True, True)
        """
        rtol = relative_tolerance(rtol, "rtol")
        left = [self.G3.num, self.G2.num, self.G1.num, self.G.den]
        right = [self.G.num, self.G3.den, self.G2.den, self.G1.den]
        holds = products_equal(left, right)
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
        """Substitute values (e.g. for the epsilons and Cs); a zero C is refused.

        Arguments are checked by :func:`symctl._util.validate.subs_rule` (text is
        read by the safe parser, never by ``sympify``).
        """
        sections = (*self.sensor_eps, *self.sensor_C, *self.actuator_eps, *self.actuator_C)
        sections = [to_expr(v, "sections") for v in sections]
        symbols = set().union(
            *(g.free_symbols for g in (self.G, self.G1, self.G2, self.G3)),
            *(v.free_symbols for v in sections),
        )
        rule, flags = subs_rule(args, kwargs, symbols)

        def sub(values):
            return tuple(to_expr(v, "sections").subs(rule, **flags) for v in values)

        out = Factorization(
            self.G.subs(rule, **flags),
            self.G1.subs(rule, **flags),
            self.G2.subs(rule, **flags),
            self.G3.subs(rule, **flags),
            sub(self.sensor_eps),
            sub(self.sensor_C),
            sub(self.actuator_eps),
            sub(self.actuator_C),
        )
        _check_C(out.sensor_C + out.actuator_C)
        return out

    def latex(self) -> str:
        r"""The three factors, :math:`G_2` written as the paper does (gain times zeros over poles)."""
        zeros = sp.Mul(*(z - e for e in (*self.sensor_eps, *self.actuator_eps)))
        zeros_tex = descending_latex(sp.collect(sp.expand(zeros), z, evaluate=True))
        g2 = (
            self.G2.latex()
            if self.N == 0
            else (rf"{latex(self.N)} \frac{{{zeros_tex}}}{{{descending_latex(self.G2.den)}}}")
        )
        return rf"G_1 = {self.G1.latex()},\quad G_2 = {g2},\quad G_3 = {self.G3.latex()}"


def _check_C(values) -> None:
    for c in values:
        if to_expr(c, "C") == 0:
            raise ParameterError("C: the section gains C_1, C_3 must be nonzero, got C = 0")


def factor(G, sensor_delay: int = 1, actuator_delay: int = 1) -> Factorization:
    r"""Split ``G`` into :math:`G_3 G_2 G_1` with relative degrees ``actuator_delay``, rest, ``sensor_delay``.

    Parameters
    ----------
    G : DiscreteTF or sympy expression in ``z``
        A proper SISO controller, e.g. :func:`symctl.controller_tf`.
    sensor_delay, actuator_delay : int
        Number of first-order sections in :math:`G_1` and :math:`G_3`.

    Returns
    -------
    Factorization
        :math:`G_2` has relative degree ``reldeg(G) - sensor_delay - actuator_delay``
        (0 for the optimal delayed controller).

    Raises
    ------
    ParameterError
        Improper ``G``, relative degree of ``G`` below ``sensor_delay + actuator_delay``,
        or negative delays.
    DimensionError
        A MIMO ``G``.

    Examples
    --------
    >>> from symctl import controller_tf, factor
    >>> f = factor(controller_tf(3), sensor_delay=1, actuator_delay=2)
    >>> f.G1.expr, f.G3.relative_degree, f.G2.relative_degree
    (C_1/(-epsilon_1 + z), 2, 0)
    >>> bool(f.verify())
    True
    """
    tf = DiscreteTF.from_expr(G)
    ds = nonneg_int(sensor_delay, "sensor_delay")
    da = nonneg_int(actuator_delay, "actuator_delay")
    if not tf.is_siso:
        raise DimensionError(f"G: factor() handles SISO controllers, got shape {tf.shape}")
    rd = tf.relative_degree
    if rd < 0:
        raise ParameterError("G: improper (numerator degree above denominator degree)")
    if rd < ds + da:
        raise ParameterError(
            f"G: relative degree {rd} is below sensor_delay + actuator_delay = {ds + da}; "
            "no factorization puts the delays at the input and output"
        )
    eps1, c1 = section_symbols(1, ds) if ds else ((), ())
    eps3, c3 = section_symbols(3, da) if da else ((), ())
    G1 = _sections(eps1, c1, tf.dt)
    G3 = _sections(eps3, c3, tf.dt)
    scale = sp.Mul(*c1, *c3)
    zeros = sp.Mul(*(z - e for e in (*eps1, *eps3)))
    G2 = DiscreteTF(tf.num / scale * zeros, tf.den, tf.dt)
    return Factorization(tf, G1, G2, G3, eps1, c1, eps3, c3)


def _relative_difference(left: sp.Expr, right: sp.Expr, points: int = 8) -> float:
    r"""The largest coefficient of ``left - right`` in :math:`z` over the largest of either side.

    Floats are taken as their exact binary rationals; other symbols are set to
    ``points`` seeded random values in :math:`\pm(0, 2]` (a point where a side is
    undefined is skipped), and the worst point counts.
    """
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
