r"""The fibre of a pattern over one :math:`G_2`: its polynomial system and its exact real points.

With a pattern's spanning-tree entries set to 1 (the torus normalization), :func:`_system` gives
the unknowns and the coefficients of :math:`\det(zI - F)` and :math:`M \operatorname{adj}(zI -
F) H` as polynomials in them; the fibre over :math:`G_2 = N + b/a` is where they equal :math:`a`
and :math:`b`.

>>> from symctl.circuitatlas.pattern import Pattern
>>> from symctl.circuitatlas.fibre import solve_at
>>> P = Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1])
>>> solve_at(P, [1, 0], [2, 3])["degree"]
1
"""

from __future__ import annotations

import itertools
import random
from functools import cache

import sympy as sp
from flint import fmpq, fmpq_mat, fmpq_poly
from sympy.polys.groebnertools import groebner

from symctl._util.deadline import Unfinished
from symctl._util.exact import from_fmpq
from symctl.circuitatlas.pattern import Pattern
from symctl.symbols import z

__all__ = [
    "MAX_FIBRE",
    "MAX_TERMS",
    "binary_rationals",
    "coefficient_polynomials",
    "coefficient_polys",
    "coefficient_symbols",
    "count_ideal",
    "count_real",
    "real_root_count",
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


MAX_TERMS = 250_000  # most terms of coefficient_polys' minors at once (order 7: ~10^5, 8: ~10^6)


def coefficient_polys(F, H, M, ring, *, deadline=None) -> tuple[list, list]:
    r"""Ascending coefficients of :math:`\det(zI - F)` (monic term dropped) and of :math:`M
    \operatorname{adj}(zI - F) H = -\det\begin{bmatrix} zI - F & H \\ M & 0 \end{bmatrix}`,
    ``n`` each, in ``ring`` (generators :math:`z` and the entries), by division-free minors;
    ``deadline`` checked as they grow, :class:`Unfinished` past :data:`MAX_TERMS` terms.

    >>> import sympy as sp
    >>> from sympy.polys.rings import ring
    >>> from symctl import z
    >>> from symctl.circuitatlas.fibre import coefficient_polys
    >>> f, h, m = sp.symbols("f h m")
    >>> R, *_ = ring([f, h, m, z], sp.QQ)
    >>> coefficient_polys(sp.Matrix([[f]]), sp.Matrix([[h]]), sp.Matrix([[m]]), R)
    ([-f], [h*m])
    """
    n = F.shape[0]
    zi = ring.symbols.index(z)
    A = [[ring.from_expr(z * int(i == j) - F[i, j]) for j in range(n)] for i in range(n)]
    bordered = [[*A[i], ring.from_expr(H[i, 0])] for i in range(n)]
    bordered.append([*(ring.from_expr(M[0, j]) for j in range(n)), ring.zero])
    charpoly = _z_coefficients(_det(A, ring, deadline, n), zi, n)
    numer = _z_coefficients(-_det(bordered, ring, deadline, n), zi, n)
    return charpoly, numer


def _det(rows, ring, deadline, n):
    """The determinant of a square matrix of ring elements, by minors of the first rows."""
    size = len(rows)
    minors = {0: ring.one}  # column set (bits) -> the minor of the first k rows on it
    for k, row in enumerate(rows):
        grown = {}
        for cols, minor in minors.items():
            for j, entry in enumerate(row):
                if not entry or cols >> j & 1:
                    continue
                term = minor * entry
                key = cols | 1 << j
                grown[key] = grown.get(key, ring.zero) + (
                    -term if (cols >> j).bit_count() % 2 else term
                )
            if deadline is not None:
                deadline.check(f"the coefficient polynomials of an order-{n} realization")
        minors = {c: m for c, m in grown.items() if m}
        if sum(len(m) for m in minors.values()) > MAX_TERMS:
            raise Unfinished(
                f"the coefficient polynomials of an order-{n} realization exceed "
                f"{MAX_TERMS} terms (minors of {k + 1} rows)"
            )
    return minors.get((1 << size) - 1, ring.zero)


def _z_coefficients(poly, zi: int, n: int) -> list:
    """``poly``'s coefficients of :math:`z^0..z^{n-1}` (polynomials of the same ring)."""
    ring = poly.ring
    out = [{} for _ in range(n)]
    for monom, coeff in poly.terms():
        if monom[zi] < n:
            out[monom[zi]][(*monom[:zi], 0, *monom[zi + 1 :])] = coeff
    return [ring(terms) for terms in out]


def coefficient_polynomials(F, H, M) -> tuple[list[sp.Expr], list[sp.Expr]]:
    """:func:`coefficient_polys` as SymPy expressions (a realization's :math:`a` and :math:`c`)."""
    symbols = set().union(*(m.free_symbols for m in (F, H, M))) - {z}
    ring, *_ = sp.ring([*sorted(symbols, key=str), z], sp.QQ)
    charpoly, numer = coefficient_polys(F, H, M, ring)
    return [p.as_expr() for p in charpoly], [p.as_expr() for p in numer]


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


MAX_FIBRE = 400  # largest quotient-ring dimension (number of complex solutions) solve_at handles


def _standard_monomials(leads, k: int):
    """The monomials no leading monomial divides; None past MAX_FIBRE."""
    start = (0,) * k
    seen, todo, out = {start}, [start], []
    while todo:
        m = todo.pop()
        if any(all(a >= b for a, b in zip(m, lead, strict=True)) for lead in leads):
            continue
        out.append(m)
        if len(out) > MAX_FIBRE:
            return None
        for i in range(k):
            nxt = tuple(e + (j == i) for j, e in enumerate(m))
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return sorted(out, key=lambda m: (sum(m), m))


def _quotient(eqs, ring):
    """Standard monomials and multiplication matrices of ``eqs``'s ideal (grevlex, over Q);
    ``([], [])`` for the unit ideal, None when not finite or above MAX_FIBRE."""
    basis = groebner(eqs, ring)
    if basis == [ring.one]:
        return [], []
    monos = _standard_monomials([g.LM for g in basis], ring.ngens)
    if monos is None:
        return None
    index = {m: i for i, m in enumerate(monos)}
    d = len(monos)
    mult = []
    for x in ring.gens:
        M = fmpq_mat(d, d)
        for j, m in enumerate(monos):
            for monom, coeff in (x * ring({m: 1})).rem(basis).items():
                M[index[monom], j] = fmpq(coeff)
        mult.append(M)
    return monos, mult


def _eliminants(mult, rng, tries: int):
    """Up to ``tries`` random linear forms' multiplication matrices with squarefree charpoly."""
    for _ in range(tries):
        form = sum((M * rng.randint(1, 9) for M in mult[1:]), mult[0] * rng.randint(1, 9))
        e = form.charpoly()
        if e.gcd(e.derivative()).degree() == 0:
            yield form, e


def _sign_changes(values) -> int:
    signs = [v > 0 for v in values if v != 0]
    return sum(a != b for a, b in itertools.pairwise(signs))


def real_root_count(e: fmpq_poly) -> int:
    """The number of real roots of a squarefree ``fmpq_poly`` (Sturm's theorem, exact).

    >>> from flint import fmpq_poly
    >>> from symctl.circuitatlas.fibre import real_root_count
    >>> real_root_count(fmpq_poly([-2, 0, 1])), real_root_count(fmpq_poly([2, 0, 1]))
    (2, 0)
    """
    seq = [e, e.derivative()]
    while seq[-1].degree() > 0:
        seq.append(-(seq[-2] % seq[-1]))
    ends = [[p[p.degree()] * s ** p.degree() for p in seq] for s in (-1, 1)]
    return _sign_changes(ends[0]) - _sign_changes(ends[1])


@cache
def _fibre_ring(pattern: Pattern):
    unknowns, _, _, charpoly, numer = _system(pattern)
    ring = sp.ring(unknowns, sp.QQ, order="grevlex")[0]
    return ring, [ring.from_expr(p) for p in (*charpoly, *numer)]


def count_real(pattern: Pattern, a, c, rng, tries: int = 3) -> dict | None:
    """``{"degree", "real", "zero_entry", "eliminant"}`` of the fibre over a rational target, or
    None when not finite and reduced. A squarefree eliminant :math:`e(t)` of a random linear form
    (its multiplication matrix's charpoly) separates the simple points: the real ones are its
    real roots (Sturm); a point has an entry 0 iff that entry's multiplication matrix is singular.

    >>> import random
    >>> from symctl.circuitatlas.pattern import Pattern
    >>> from symctl.circuitatlas.fibre import count_real
    >>> P = Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1])
    >>> count_real(P, [1, 0], [2, 3], random.Random(0))["real"]
    1
    """
    ring, polys = _fibre_ring(pattern)
    return count_ideal([p - v for p, v in zip(polys, (*a, *c), strict=True)], ring, rng, tries)


def count_ideal(eqs, ring, rng, tries: int = 3) -> dict | None:
    """:func:`count_real` for any system ``eqs`` of ``ring`` (grevlex, over Q)."""
    found = _quotient(eqs, ring)
    if found is None:
        return None
    monos, mult = found
    if not monos:
        return {"degree": 0, "real": 0, "zero_entry": False, "eliminant": "1"}
    for _, e in _eliminants(mult, rng, tries):  # the first squarefree eliminant
        return {
            "degree": len(monos),
            "real": real_root_count(e),
            "zero_entry": any(M.det() == 0 for M in mult),
            "eliminant": e.str(var="t"),
        }
    return None


def solve_at(pattern: Pattern, a, c, *, fixed=None, rng=None, tries: int = 3):
    r"""The real realizations of one rational target ``(a, c)``, exactly, some entries ``fixed``.

    A grevlex Groebner basis over :math:`\mathbb{Q}`, the squarefree eliminant :math:`e(t)` of a
    random linear form, each unknown :math:`x_i = g_i(t)` (the Krylov basis: shape position). A
    non-real solution has a non-real :math:`t`, so the real solutions are the real roots of
    :math:`e`, isolated in rational intervals. Returns ``{"degree", "real": [{"interval",
    "entries_nonzero"}, ...], "eliminant"}``, or None when not finite and reduced.
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
    ring = sp.ring(free, sp.QQ, order="grevlex")[0]
    found = _quotient([ring.from_expr(e) for e in eqs], ring)
    if found is None:
        return None
    monos, mult = found
    if not monos:
        return {"degree": 0, "real": [], "eliminant": "1"}
    d = len(monos)
    t = sp.Symbol("t_")
    for Mt, ef in _eliminants(mult, rng, tries):
        e = sp.Poly([from_fmpq(q) for q in ef.coeffs()[::-1]], t)
        # the Krylov basis 1, t, .., t^(d-1) of the quotient (1 is the first standard monomial)
        krylov = [fmpq_mat(d, 1, [1] + [0] * (d - 1))]
        for _ in range(d - 1):
            krylov.append(Mt * krylov[-1])
        K = fmpq_mat(d, d, [krylov[j][i, 0] for i in range(d) for j in range(d)])
        try:
            g = {}
            for x, M in zip(free, mult, strict=True):
                coeffs = K.solve(M * krylov[0])
                g[x] = sp.Add(*(from_fmpq(coeffs[k, 0]) * t**k for k in range(d)))
        except ZeroDivisionError:
            continue
        e_expr = e.as_expr()
        real = []
        for (lo, hi), _mult in e.intervals():
            nonzero = all(
                sp.Poly(sp.gcd(e_expr, gi), t).count_roots(lo, hi) == 0 for gi in g.values()
            )
            real.append({"interval": [str(lo), str(hi)], "entries_nonzero": nonzero})
        return {"degree": d, "real": real, "eliminant": str(e_expr), "_g": g, "_e": e_expr, "_t": t}
    return None
