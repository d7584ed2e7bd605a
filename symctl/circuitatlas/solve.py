"""Realize one :math:`G_2` with a given pattern: closed form, or an exact polynomial solve.

:func:`realize_with` (:meth:`CircuitClass.realize`) tries each pattern of the class, proved ones
first: the closed form (symbolic ``G2`` allowed), then for numeric ``G2`` the exact solve of
:func:`~symctl.circuitatlas.fibre.solve_at` (a real root of the eliminant as a ``CRootOf``),
entries beyond :math:`3n` set to random nonzero rationals.
"""

from __future__ import annotations

import random

import sympy as sp

from symctl.circuitatlas.fibre import _system, binary_rationals, coefficient_symbols, solve_at
from symctl.circuitatlas.universality import closed_form, fixings
from symctl.errors import NotRealizableError, ParameterError
from symctl.realization.realization import Realization, _siso, split_proper

__all__ = ["realize_with", "target_of"]


def target_of(G2, order: int, argname: str = "G2"):
    """``(N, a, c)`` of a proper order-``order`` ``G2`` with ``N != 0`` (ascending coefficients)."""
    N, c, a = split_proper(_siso(G2, argname))
    if len(a) != order:
        raise ParameterError(f"{argname}: expected order {order}, got order {len(a)}")
    if N == 0:
        raise ParameterError(
            f"{argname}: N = G2(oo) must be nonzero (every realization of the atlas has N != 0)"
        )
    return N, a, c


def realize_with(cls, G2) -> Realization:
    """A realization of ``G2`` with a pattern of ``cls`` (see the module text)."""
    N, a, c = target_of(G2, cls.order)
    numeric = all(v.is_number for v in (*a, *c))
    reasons = []
    order = sorted(cls.representatives, key=lambda p: cls.pattern_evidence[p].sort_rank)
    for pattern in order:
        ev = cls.pattern_evidence[pattern]
        form = closed_form(pattern) if ev.method == "closed form" else None
        if form is not None:
            a_s, c_s = coefficient_symbols(pattern.n)
            rule = dict(zip((*a_s, *c_s), (*a, *c), strict=True))
            values = {k: sp.cancel(v.xreplace(rule)) for k, v in form.items()}
            if all(v != 0 and not v.has(sp.zoo, sp.nan) for v in values.values()):
                return _realization(pattern, values, N, "closed form")
            reasons.append(f"{pattern.text}: the closed form is singular or zero at this G2")
            continue
        if not numeric:
            reasons.append(f"{pattern.text}: no closed form, and G2 is symbolic")
            continue
        a_q, c_q = [binary_rationals(v) for v in a], [binary_rationals(v) for v in c]
        values = _solved(pattern, a_q, c_q)
        if values is not None:
            R = _realization(pattern, values, N, "exact solve")
            if not _markov_equal(R, a_q, c_q):  # pragma: no cover - a bug
                raise AssertionError(f"the solve for {pattern.text} gave a wrong realization")
            return R
        reasons.append(f"{pattern.text}: no real solution with every entry nonzero found")
    raise NotRealizableError(
        f"G2: not realizable with the circuit class {cls.label or ''} ({cls.n_neurons} neurons): "
        + "; ".join(reasons)
    )


def _solved(pattern, a, c):
    _unknowns, slots, values, _, _ = _system(pattern)
    extra = pattern.size - 3 * pattern.n
    rng = random.Random(pattern.mask)
    for fixed in fixings(slots, extra, rng):
        sol = solve_at(pattern, a, c, fixed=fixed, rng=rng)
        if sol is None or "_e" not in sol:
            continue
        e, t, g = sol["_e"], sol["_t"], sol["_g"]
        roots = sp.Poly(e, t).real_roots()
        for info, root in zip(sol["real"], roots, strict=False):
            if not info["entries_nonzero"]:
                continue
            out = {}
            for k in pattern.indices:
                sym = values[k]
                if k in fixed:
                    out[k] = fixed[k]
                elif sym in g:
                    out[k] = sp.Poly(g[sym], t).as_expr().xreplace({t: root})
                else:
                    out[k] = sym  # a tree entry (1)
            return out
    return None


def _markov_equal(R: Realization, a, c) -> bool:
    r"""Exactly :math:`M F^{k-1} H = h_k` for :math:`k \le 2n` (minimal polynomials of the
    algebraic differences)."""
    n = R.n
    h = []  # Markov parameters of c(z)/a(z): h_k = c_{n-k} - sum_{j<k} a_{n-k+j} h_j
    for k in range(1, 2 * n + 1):
        value = c[n - k] if k <= n else sp.Integer(0)
        for j in range(1, k):
            if n - k + j >= 0:
                value -= a[n - k + j] * h[j - 1]
        h.append(value)
    x = sp.Symbol("x_")
    vec = R.H
    for k in range(2 * n):
        diff = sp.expand((R.M * vec)[0, 0] - h[k])
        if diff != 0 and (diff.is_Rational or sp.minimal_polynomial(diff, x) != x):
            return False
        vec = R.F * vec
    return True


def _realization(pattern, values, N, method) -> Realization:
    F, H, M = pattern.matrices(values)
    return Realization(F, H, M, N, params={"pattern": pattern.text, "method": method})
