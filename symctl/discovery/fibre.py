r"""The fibre of a pattern over one :math:`G_2`: its polynomial system and its exact real points.

For a pattern (:mod:`symctl.discovery.pattern`) with its spanning-tree entries set
to 1 (the torus normalization), :func:`_system` gives the unknowns and the
coefficients of :math:`\det(zI - F)` and :math:`M \operatorname{adj}(zI - F) H` as
polynomials in them; the fibre over :math:`G_2 = N + b/a` is where they equal
:math:`a` and :math:`b`. :func:`solve_at` and :func:`real_solutions` find its real
points exactly: a grevlex Groebner basis over :math:`\mathbb{Q}`, the multiplication
matrix of a random linear form and its characteristic polynomial, and the Krylov
basis for the other coordinates (shape position).

>>> from symctl.discovery.pattern import Pattern
>>> from symctl.discovery.fibre import solve_at
>>> P = Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1])
>>> solve_at(P, [1, 0], [2, 3])["degree"]
1
"""

from __future__ import annotations

import random
from functools import cache

import sympy as sp
from flint import fmpq, fmpq_mat

from symctl.discovery.pattern import Pattern
from symctl.symbols import z

__all__ = [
    "MAX_FIBRE",
    "binary_rationals",
    "coefficient_polynomials",
    "coefficient_symbols",
    "real_solutions",
    "solve_at",
]


def binary_rationals(expr):
    """A SymPy number or expression with its floats as the exact binary rationals they are."""
    expr = sp.expand(expr)
    return expr.xreplace({v: sp.Rational(v) for v in expr.atoms(sp.Float)})


@cache
def coefficient_symbols(n: int) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Symbol, ...]]:
    """The symbols :math:`a_0..a_{n-1}` and :math:`c_0..c_{n-1}` of a generic :math:`G_2`."""
    return sp.symbols(f"a_0:{n}"), sp.symbols(f"c_0:{n}")


def coefficient_polynomials(F, H, M) -> tuple[list[sp.Expr], list[sp.Expr]]:
    r"""Ascending coefficients of :math:`\det(zI - F)` (monic term dropped) and of
    :math:`M \operatorname{adj}(zI - F) H`, ``n`` each: a realization's :math:`a` and :math:`c`."""
    n = F.shape[0]
    A = z * sp.eye(n) - F
    charpoly = sp.Poly(A.det(method="berkowitz"), z).all_coeffs()[::-1][:n]
    numer = sp.Poly(sp.expand((M * A.adjugate() * H)[0, 0]), z).all_coeffs()[::-1]
    return charpoly, numer + [sp.Integer(0)] * (n - len(numer))


@cache
def _system(pattern: Pattern):
    """(unknowns, their slots, value of every slot, coefficient polynomials of a and b)."""
    tree = set(pattern.tree_slots() or ())
    syms = pattern.symbols()
    values = {k: sp.Integer(1) if k in tree else syms[k] for k in pattern.indices}
    charpoly, numer = coefficient_polynomials(*pattern.matrices(values))
    unknown_slots = tuple(k for k in pattern.indices if k not in tree)
    return tuple(syms[k] for k in unknown_slots), unknown_slots, values, charpoly, numer


def _equations(pattern: Pattern, a, c) -> list[sp.Expr]:
    _, _, _, charpoly, numer = _system(pattern)
    return [sp.expand(p - v) for p, v in zip((*charpoly, *numer), (*a, *c), strict=True)]


def _linear_form(unknowns, rng):
    return sum(rng.randint(1, 9) * x for x in unknowns)


MAX_FIBRE = 400
"""Largest quotient-ring dimension (number of complex solutions) solve_at handles."""


def _standard_monomials(basis, gens):
    """The monomials not divisible by any leading monomial (grevlex): a basis of the quotient."""
    leads = [sp.Poly(g, *gens).monoms(order="grevlex")[0] for g in basis.exprs]
    start = (0,) * len(gens)
    seen, todo, out = {start}, [start], []
    while todo:
        m = todo.pop()
        if any(all(a >= b for a, b in zip(m, lead, strict=True)) for lead in leads):
            continue
        out.append(m)
        if len(out) > MAX_FIBRE:
            return None
        for i in range(len(gens)):
            nxt = tuple(e + (k == i) for k, e in enumerate(m))
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return sorted(out, key=lambda m: (sum(m), m))


def _normal_form(basis, expr, gens, index):
    """Coordinates of expr's normal form on the standard monomials."""
    rem = basis.reduce(sp.expand(expr))[1]
    vec = [sp.Integer(0)] * len(index)
    for m, coeff in sp.Poly(rem, *gens).terms():
        vec[index[m]] = coeff
    return vec


def _q(v):
    v = sp.Rational(v)
    return fmpq(int(v.p), int(v.q))


def _rational(q) -> sp.Rational:
    return sp.Rational(int(q.p), int(q.q))


def solve_at(pattern: Pattern, a, c, *, fixed=None, rng=None, tries: int = 3):
    r"""The real realizations of one rational target, exactly.

    A grevlex Groebner basis over :math:`\mathbb{Q}` gives the quotient ring
    of the fibre; the multiplication matrix of a random linear form
    :math:`t = \sum r_i x_i` has the characteristic polynomial :math:`e(t)`,
    squarefree when :math:`t` separates the (then simple) solutions, and each
    unknown is :math:`x_i = g_i(t)` with :math:`g_i` from the Krylov basis
    (shape position). A non-real solution has a non-real :math:`t` (its
    conjugate is another solution with the conjugate :math:`t`), so the real
    solutions are the real roots of :math:`e`, isolated in rational intervals.

    Parameters
    ----------
    pattern : Pattern
    a, c : sequences of rationals
        The target's :math:`a_0..a_{n-1}` and :math:`c_0..c_{n-1}`.
    fixed : mapping of slot to rational, optional
        Entries set to given values (to make a bigger pattern's system square).
    rng : random.Random, optional
    tries : int
        Random linear forms tried until :math:`e` is squarefree.

    Returns
    -------
    dict or None
        ``{"degree": d, "real": [...], "eliminant": str}`` with one item per
        real solution (its isolating interval, and whether every entry is
        nonzero there); None when the fibre is not finite and reduced.
    """
    rng = rng or random.Random(0)
    unknowns, _slots, values, _, _ = _system(pattern)
    fixed = dict(fixed or {})
    eqs = _equations(pattern, a, c)
    rule = {values[k]: sp.Rational(v) for k, v in fixed.items()}
    if rule:
        eqs = [sp.expand(e.xreplace(rule)) for e in eqs]
    free = [x for x in unknowns if x not in rule]
    return real_solutions(eqs, free, rng, tries)


def real_solutions(eqs, free, rng, tries: int = 3):
    """The exact real solutions of a square rational system (see :func:`solve_at`)."""
    if not free:
        return {"degree": int(all(e == 0 for e in eqs)), "real": [], "eliminant": "1"}
    basis = sp.groebner(eqs, *free, order="grevlex", domain=sp.QQ)
    if basis.exprs == [1]:
        return {"degree": 0, "real": [], "eliminant": "1"}
    if not basis.is_zero_dimensional:
        return None
    monos = _standard_monomials(basis, free)
    if monos is None:
        return None
    index = {m: i for i, m in enumerate(monos)}
    d = len(monos)
    mono_expr = [sp.Mul(*(x**e for x, e in zip(free, m, strict=True))) for m in monos]
    nfs = {x: [_q(v) for v in _normal_form(basis, x, free, index)] for x in free}
    t = sp.Symbol("t_")
    for _ in range(tries):
        form = _linear_form(free, rng)
        cols = [_normal_form(basis, form * m, free, index) for m in mono_expr]
        Mt = fmpq_mat(d, d, [_q(cols[j][i]) for i in range(d) for j in range(d)])
        e = sp.Poly([_rational(q) for q in Mt.charpoly().coeffs()[::-1]], t)
        if sp.degree(sp.gcd(e, e.diff(t)), t) > 0:
            continue
        # the Krylov basis 1, t, .., t^(d-1) of the quotient (1 is the first standard monomial)
        krylov = [fmpq_mat(d, 1, [1] + [0] * (d - 1))]
        for _ in range(d - 1):
            krylov.append(Mt * krylov[-1])
        K = fmpq_mat(d, d, [krylov[j][i, 0] for i in range(d) for j in range(d)])
        try:
            g = {}
            for x in free:
                coeffs = K.solve(fmpq_mat(d, 1, nfs[x]))
                g[x] = sp.Add(*(_rational(coeffs[k, 0]) * t**k for k in range(d)))
        except ZeroDivisionError:
            continue
        e_expr = e.as_expr()
        real = []
        for (lo, hi), _mult in e.intervals():
            nonzero = all(
                sp.Poly(sp.gcd(e_expr, gi), t).count_roots(lo, hi) == 0 for gi in g.values()
            )
            real.append({"interval": [str(lo), str(hi)], "entries_nonzero": nonzero})
        return {
            "degree": d,
            "real": real,
            "eliminant": str(e_expr),
            "_g": g,
            "_e": e_expr,
            "_t": t,
        }
    return None
