r"""The one exact expression fold: a SymPy expression tree evaluated in an algebra.

:func:`fold` walks a rational SymPy expression bottom up (shared subtrees once) and hands
each node to an *algebra* (``number(p, q)``, ``symbol(s)``, ``add(parts)``, ``mul(parts)``,
``pow(base, value, k)``); every numerator/denominator pair in symctl is made by one:
:class:`RingFractions` (sparse SymPy polynomials over :math:`\mathbb{Q}`: :func:`z_poly`,
:func:`products_equal`), :class:`PolyFractions` (python-flint ``fmpz_mpoly``: the exact
realization check), :class:`IntFractions` (the value at a rational point) and
:class:`Degrees` (degree bounds: the Schwartz–Zippel bound of the randomized check).

>>> import sympy as sp
>>> from symctl import z
>>> from symctl._util.exact import IntFractions, fold, z_poly
>>> a = sp.Symbol("a")
>>> fold((z + a) / (z - 1) + 1 / a, IntFractions({z: 3, a: 2}))  # 6/2, not reduced
(6, 2)
>>> z_poly(a * z**2 / 2 - 1).all_coeffs()
[a/2, 0, -1]
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from fractions import Fraction
from functools import lru_cache

import sympy as sp
from sympy.polys.rings import ring

from symctl.errors import ParameterError
from symctl.symbols import z


def _mul_pairs(parts):
    """The product of fractions given as ``(numerator, denominator)`` pairs (not reduced)."""
    num, den = parts[0]
    for n2, d2 in parts[1:]:
        num, den = num * n2, den * d2
    return num, den


def _pow_pair(base, value, k: int):
    """``value ** k`` of a pair; a negative power of a vanishing numerator raises."""
    num, den = value
    if k >= 0:
        return num**k, den**k
    if num == 0:
        raise ZeroDivisionError(f"{base} vanishes")
    return den**-k, num**-k


class NotRational(Exception):
    """An expression that is not a rational function of its symbols (its first argument)."""


def fold(expr: sp.Expr, algebra, memo: dict | None = None):
    """Evaluate a rational sympy expression bottom-up in ``algebra`` (shared subtrees once).

    Floats are their exact binary rationals; any other node raises :class:`NotRational`.
    """
    memo = {} if memo is None else memo
    got = memo.get(expr)
    if got is not None:
        return got
    if expr.is_Rational or expr.is_Float:
        value = sp.Rational(expr)
        out = algebra.number(int(value.p), int(value.q))
    elif expr.is_Symbol:
        out = algebra.symbol(expr)
    elif expr.is_Add:
        out = algebra.add([fold(a, algebra, memo) for a in expr.args])
    elif expr.is_Mul:
        out = algebra.mul([fold(a, algebra, memo) for a in expr.args])
    elif expr.is_Pow and expr.exp.is_Integer:
        out = algebra.pow(expr.base, fold(expr.base, algebra, memo), int(expr.exp))
    else:
        raise NotRational(expr)
    memo[expr] = out
    return out


class _Pairs:
    """An algebra of fractions as ``(numerator, denominator)`` pairs with leaves by symbol."""

    _leaves: dict

    def symbol(self, s):
        return self._leaves[s]

    mul = staticmethod(_mul_pairs)
    pow = staticmethod(_pow_pair)


class RingFractions(_Pairs):
    """Algebra: pairs (numerator, denominator) in a sparse SymPy polynomial ring, no gcd."""

    def __init__(self, ring_, generators):
        self.ring = ring_
        self._leaves = {g: (x, ring_.one) for g, x in zip(generators, ring_.gens, strict=True)}

    def number(self, p: int, q: int):
        return self.ring(p), self.ring(q)

    @staticmethod
    def add(parts):
        num, den = parts[0]
        for n2, d2 in parts[1:]:
            num, den = (num + n2, den) if d2 == den else (num * d2 + n2 * den, den * d2)
        return num, den


class PolyFractions(_Pairs):
    """Algebra: rational functions as pairs (numerator, denominator) of ``fmpz_mpoly``."""

    def __init__(self, ctx, symbols):
        one = ctx.constant(1)
        self.ctx = ctx
        self._leaves = {s: (g, one) for s, g in zip(symbols, ctx.gens(), strict=True)}

    def number(self, p: int, q: int):
        return self.ctx.constant(p), self.ctx.constant(q)

    @staticmethod
    def add(parts):
        num, den = parts[0]
        for n2, d2 in parts[1:]:
            if d2 == den:
                num = num + n2
            elif d2.is_one():
                num = num + n2 * den
            elif den.is_one():
                num, den = num * d2 + n2, d2
            else:
                g = den.gcd(d2)
                c1, c2 = den / g, d2 / g
                num, den = num * c2 + n2 * c1, c1 * d2
        return num, den


class IntFractions(_Pairs):
    """Algebra: the value at a point, as a pair of Python ints (fast for numbers)."""

    def __init__(self, values: Mapping):
        self._leaves = {s: (v.numerator, v.denominator) for s, v in values.items()}

    @staticmethod
    def number(p: int, q: int):
        return p, q

    @staticmethod
    def add(parts):
        num, den = parts[0]
        for n2, d2 in parts[1:]:
            if d2 == den:
                num += n2
            else:
                g = math.gcd(den, d2)
                num, den = num * (d2 // g) + n2 * (den // g), den * (d2 // g)
        return num, den

    @staticmethod
    def mul(parts):
        num, den = _mul_pairs(parts)
        if den != 1:
            g = math.gcd(num, den)
            num, den = num // g, den // g
        return num, den


class Degrees:
    r"""Algebra: degree bounds of an unreduced representation :math:`p/q` of each subtree.

    A value is ``(pi, q)``: ``pi`` bounds :math:`\deg p`, and ``q`` is a dict
    ``{base: m}`` meaning :math:`q = \prod p_\text{base}^m` (the numerators of
    the bases of negative powers). Rules: a number or symbol has :math:`q = 1`;
    a product multiplies; a sum puts its terms over the lcm of their ``q``
    (maximum exponent per base); :math:`b^{-k} = q_b^{k+1}/(p_b^k q_b)`. By
    induction, wherever :math:`q(x) \ne 0` the exact evaluation at :math:`x`
    (:class:`IntFractions`) succeeds and equals :math:`p(x)/q(x)`.
    """

    def __init__(self):
        self.pi: dict = {}

    def deg(self, q: dict) -> int:
        return sum(m * self.pi[base] for base, m in q.items())

    @staticmethod
    def merge(dicts, combine) -> dict:
        out: dict = {}
        for q in dicts:
            for base, m in q.items():
                out[base] = combine(out.get(base, 0), m)
        return out

    @staticmethod
    def number(p: int, q: int):
        return 0, {}

    @staticmethod
    def symbol(s):
        return 1, {}

    def add(self, parts):
        if not any(qi for _, qi in parts):
            return max(p for p, _ in parts), {}
        q = self.merge((qi for _, qi in parts), max)
        dq = self.deg(q)
        return max(p + dq - self.deg(qi) for p, qi in parts), q

    def mul(self, parts):
        total = sum(p for p, _ in parts)
        if not any(qi for _, qi in parts):
            return total, {}
        return total, self.merge((qi for _, qi in parts), int.__add__)

    def pow(self, base, value, k: int):
        p, q = value
        if k >= 0:
            return k * p, {b: k * m for b, m in q.items()}
        self.pi[base] = p
        return (1 - k) * self.deg(q), self.merge((q, {base: -k}), int.__add__)


def _generators(exprs) -> list[sp.Symbol] | None:
    """z and the other symbols, or None for floats or other atoms (``exp(1/2) * exp(-1/2) = 1``
    would escape a polynomial ring)."""
    syms: set[sp.Symbol] = set()
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, sp.Symbol):
                syms.add(node)
            elif isinstance(node, sp.Float) or not (
                isinstance(node, sp.Add | sp.Mul | sp.Rational)
                or (isinstance(node, sp.Pow) and node.exp.is_Integer)
            ):
                return None
    return [z, *sorted(syms - {z}, key=str)]


def ring_fractions(exprs: list[sp.Expr]) -> list[tuple] | None:
    """Each expression as a pair (numerator, denominator) of sparse polynomials over QQ in z and
    its symbols (:class:`RingFractions`: no gcd, no expansion); None for floats or other atoms."""
    gens = _generators(exprs)
    if gens is None:
        return None
    R, *_ = ring(gens, sp.QQ)
    algebra, memo = RingFractions(R, gens), {}
    return [fold(e, algebra, memo) for e in exprs]


def cancel(expr: sp.Expr) -> sp.Expr:
    """``expr`` in lowest terms, ``p/q``: :func:`sympy.cancel`, done in the sparse ring when it can."""
    pairs = ring_fractions([expr])
    if pairs is None:
        return sp.cancel(expr)
    p, q = pairs[0][0].cancel(pairs[0][1])
    return p.as_expr() / q.as_expr()


def products_equal(left: list[sp.Expr], right: list[sp.Expr]) -> bool:
    """Exact test of ``prod(left) == prod(right)`` for rational expressions."""
    pairs = ring_fractions([*left, *right])
    if pairs is None:
        return sp.expand(sp.Mul(*left) - sp.Mul(*right)) == 0
    one = (pairs[0][0].ring.one,) * 2
    num_l, den_l = _mul_pairs([one, *pairs[: len(left)]])
    num_r, den_r = _mul_pairs([one, *pairs[len(left) :]])
    return num_l * den_r == num_r * den_l


class ZPoly:
    """A univariate polynomial in z read off a sparse ring element (the few views symctl needs)."""

    __slots__ = ("_coeffs",)

    def __init__(self, coeffs: dict[int, sp.Expr]):
        self._coeffs = {k: c for k, c in coeffs.items() if c != 0}

    @property
    def is_zero(self) -> bool:
        return not self._coeffs

    def degree(self) -> int:
        return max(self._coeffs) if self._coeffs else -1

    def LC(self) -> sp.Expr:
        return self.coeff(self.degree())

    def all_coeffs(self) -> list[sp.Expr]:
        return [self.coeff(k) for k in range(self.degree(), -1, -1)] or [sp.Integer(0)]

    def coeff(self, power: int) -> sp.Expr:
        return self._coeffs.get(power, sp.Integer(0))

    def terms(self) -> list[tuple[tuple[int], sp.Expr]]:
        return [((k,), self._coeffs[k]) for k in sorted(self._coeffs, reverse=True)]


def _z_fraction(expr: sp.Expr):
    """``(num, den)`` of a polynomial in z in the sparse ring (``den`` free of z), or None."""
    pairs = ring_fractions([expr])
    if pairs is not None and pairs[0][1].degree(0) > 0:
        raise ParameterError(f"num/den: {expr} is not a polynomial in z")
    return None if pairs is None else pairs[0]


@lru_cache(maxsize=4096)
def z_poly(expr: sp.Expr) -> ZPoly:
    """Coefficients of ``expr`` in z, computed with sparse ring arithmetic (no expression expansion)."""
    pair = _z_fraction(expr)
    if pair is None:
        poly = sp.Poly(expr, z)
        return ZPoly({k: c for (k,), c in poly.terms()})
    num, den = pair
    by_power: dict[int, dict] = {}
    for monom, coeff in num.items():
        by_power.setdefault(monom[0], {})[(0, *monom[1:])] = coeff
    ring_ = num.ring
    coeffs = {}
    for k, terms in by_power.items():  # lowest terms in the ring: no expression is parsed again
        p, q = ring_.from_dict(terms).cancel(den)
        coeffs[k] = p.as_expr() / q.as_expr()
    return ZPoly(coeffs)


@lru_cache(maxsize=4096)
def z_degree(expr: sp.Expr) -> int:
    """The degree of ``expr`` in z (-1 for 0), read off the sparse ring without its coefficients."""
    pair = _z_fraction(expr)
    if pair is None:
        return z_poly(expr).degree()
    return max((monom[0] for monom in pair[0].keys()), default=-1)


def from_fmpq(q) -> sp.Rational:
    """A python-flint ``fmpq`` (or ``fmpz``) as a SymPy rational."""
    return sp.Rational(int(q.p), int(q.q))


def from_fmpq_mat(M) -> sp.ImmutableMatrix:
    """A python-flint ``fmpq_mat`` as a SymPy matrix of rationals."""
    return sp.ImmutableMatrix(M.nrows(), M.ncols(), [from_fmpq(x) for x in M.entries()])


def nearest_rational(x: float, den: int) -> sp.Rational:
    """The rational nearest the float ``x`` with denominator at most ``den``.

    >>> from symctl._util.exact import nearest_rational
    >>> nearest_rational(0.3333333, 100)
    1/3
    """
    q = Fraction(float(x)).limit_denominator(den)
    return sp.Rational(q.numerator, q.denominator)
