r"""The real points of a fibre that is a curve: critical points of the distance to a point.

A pattern of :math:`2n + 1` unknowns (:math:`3n + 1` entries) has a fibre of dimension 1 over a
generic target: ``k`` unknowns :math:`x`, ``k - 1`` equations :math:`g(x) = (a, c)`. For a
rational point :math:`p`, the system :math:`g = (a, c)`, :math:`\det [J_g; x - p] = 0` holds at
every critical point of :math:`\|x - p\|^2` on the fibre and at every singular point of it.

**Existence.** A real solution with every entry nonzero is a real realization.

**Refutation.** Every nonempty closed real set has a point nearest to :math:`p`, a real
solution of the system. Suppose at a target :math:`\tau_0` the system has :math:`D` solutions,
the number at a random target (over a large prime field: with high probability the generic
number, so none went to infinity), all simple (a squarefree eliminant), none real. For :math:`\tau` near
:math:`\tau_0` the :math:`D` solutions move continuously and stay non-real; off a proper
algebraic set of targets (where the system has more than :math:`D` solutions or infinitely
many) they are all the solutions. So an open set of targets has no real realization at all.

>>> from symctl.circuitatlas.pattern import Pattern
>>> from symctl.circuitatlas.critical import critical_degree
>>> critical_degree(Pattern.from_matrices([[0, 1], [1, 1]], [1, 1], [1, 1]))
7
"""

from __future__ import annotations

import random
from functools import cache

import sympy as sp
from sympy.polys.groebnertools import groebner

from symctl.circuitatlas.fibre import _det, _fibre_ring, _standard_monomials, count_ideal
from symctl.circuitatlas.pattern import Pattern

__all__ = ["count_critical", "critical_degree", "curve_target"]


@cache
def _critical_parts(pattern: Pattern):
    """(ring, coefficient polynomials, signed cofactors C_i): det [J; v] = sum v_i C_i."""
    ring, polys = _fibre_ring(pattern)
    k = ring.ngens
    if len(polys) != k - 1:
        return None
    J = [[p.diff(x) for x in ring.gens] for p in polys]
    cofactors = []
    for i in range(k):
        minor = _det([[row[j] for j in range(k) if j != i] for row in J], ring, None, pattern.n)
        cofactors.append(-minor if (k - 1 + i) % 2 else minor)
    return ring, polys, cofactors


def count_critical(pattern: Pattern, a, c, point, rng, tries: int = 3) -> dict | None:
    """:func:`~symctl.circuitatlas.fibre.count_real` of the critical system at ``(a, c)`` and
    ``point``; None when not finite and reduced, or not a curve."""
    parts = _critical_parts(pattern)
    if parts is None:
        return None
    ring, polys, cofactors = parts
    eqs = [p - v for p, v in zip(polys, (*a, *c), strict=True)]
    eqs.append(sum((x - q) * C for x, q, C in zip(ring.gens, point, cofactors, strict=True)))
    return count_ideal(eqs, ring, rng, tries)


def _point(rng, k: int) -> list[sp.Rational]:
    return [sp.Rational(rng.randint(-9, 9), rng.randint(1, 5)) for _ in range(k)]


PRIME = 2**31 - 1


@cache
def critical_degree(pattern: Pattern) -> int | None:
    """The critical system's solution count at a random target and point over GF(PRIME) (the
    generic count over Q with high probability); None if not a curve or not finite."""
    parts = _critical_parts(pattern)
    if parts is None:
        return None
    ring, polys, cofactors = parts
    field = sp.ring([str(x) for x in ring.gens], sp.GF(PRIME), order="grevlex")[0]

    def mod(p):
        return field(
            {m: int(q.numerator) * pow(int(q.denominator), -1, PRIME) for m, q in p.items()}
        )

    rng = random.Random(pattern.mask)
    eqs = [mod(p) - rng.randrange(PRIME) for p in polys]
    point = [rng.randrange(PRIME) for _ in field.gens]  # the distance point
    terms = [(x - q) * mod(C) for x, q, C in zip(field.gens, point, cofactors, strict=True)]
    eqs.append(sum(terms, field.zero))
    basis = groebner(eqs, field)
    if basis == [field.one]:
        return 0
    monos = _standard_monomials([g.LM for g in basis], field.ngens)
    return None if monos is None else len(monos)


def curve_target(pattern: Pattern, a, c, rng) -> dict | None:
    """One target at a random distance point: ``{"real": True, ...}`` (an exact real
    realization), ``{"real": False, ...}`` (generic, none real: a refutation), or None."""
    degree = critical_degree(pattern)
    if not degree:
        return None
    point = _point(rng, _critical_parts(pattern)[0].ngens)
    got = count_critical(pattern, a, c, point, rng)
    if got is None or got["degree"] != degree or (got["real"] and got["zero_entry"]):
        return None
    return {
        "real": bool(got["real"]),
        "a": [str(v) for v in a],
        "c": [str(v) for v in c],
        "point": [str(v) for v in point],
        "degree": degree,
        "eliminant": got["eliminant"],
    }
