r"""Universality over the reals: proved, refuted, or conjectured from witnesses region by region.

A pattern (:mod:`~symctl.circuitatlas.pattern`) is **universal** when almost every real
:math:`G_2 = N + b/a` (:math:`a = z^n + \sum_{i<n} a_i z^i`, :math:`b = \sum_{i<n} c_i z^i`) has
a real realization with exactly that support: after the torus normalization, a real solution of
:math:`\det(zI - F) = a`, :math:`M \operatorname{adj}(zI - F) H = b` with every entry nonzero.
The methods of :func:`decide`, in order (:class:`Evidence`):

``"not minimal"``, ``"rank"`` (refuted)
    Not generically minimal, or generic rank below :math:`2n` (:mod:`~symctl.circuitatlas.rank`).
``"real eigenvalues"``, ``"real zeros"`` (refuted)
    Structural rules (:mod:`~symctl.circuitatlas.structural`).
``"lifted"`` (proved when its source is)
    The pattern contains a universal pattern :math:`S'`. For almost every :math:`G_2`, a
    realization :math:`x_0` with support :math:`S'` is a regular point of the bigger map (its
    :math:`S'`-columns already have rank :math:`2n`), so near :math:`x_0` the fibre is a
    manifold of dimension :math:`k - 2n` on which each added entry has a nonzero derivative
    (solve the kernel equation with that entry set to 1); it leaves every coordinate hyperplane,
    so a nearby point of the fibre has every entry of the bigger pattern nonzero.
``"closed form"`` (proved)
    The equations solved one unknown (or a Cramer pair) at a time, each linear with the earlier
    ones substituted: rational functions of :math:`(a, c)`, real where defined, none identically
    zero, checked exactly against the symbolic :math:`G_2`.
``"counterexample"`` (refuted)
    The poles alone: when ``F``'s own torus leaves :math:`n` free entries, :math:`\det(zI - F) =
    a` is square, and a sampled :math:`a` of the generic degree with no real solution refutes
    every pattern with that ``F`` (simple points stay non-real nearby); or the exact screen
    (:mod:`~symctl.circuitatlas.screen`); or, for :math:`3n + 1` entries (a curve), the exact
    screen of its critical points (:mod:`~symctl.circuitatlas.critical`).
``"odd degree"`` (proved)
    :mod:`~symctl.circuitatlas.odddegree`, for :math:`3n` entries or a slice of more.
``"conjectured"`` (evidence, not a proof)
    Containing a conjectured pattern; an odd degree left unproved; every target of the screen
    with real realizations; or, above :math:`3n` entries, a real realization at one sampled
    :math:`G_2` in every region, exact (a real critical point, for a curve) or Krawczyk-certified
    (samples cannot rule out an open sub-region they missed).
``"not decided"``
    None of the above settled it; the search done is stated.

>>> from symctl.circuitatlas.pattern import Pattern
>>> from symctl.circuitatlas.universality import decide
>>> decide(Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1])).method
'closed form'
>>> decide(Pattern.from_matrices([[1, 1], [0, 1]], [1, 1], [1, 0])).method
'real eigenvalues'
"""

from __future__ import annotations

import itertools
import random
from functools import cache
from types import MappingProxyType

import networkx as nx
import sympy as sp

from symctl.circuitatlas.certify import certified_real_root
from symctl.circuitatlas.critical import critical_degree, curve_target
from symctl.circuitatlas.evidence import CONJECTURED, ODD_DEGREE, Evidence, _evidence
from symctl.circuitatlas.fibre import _equations, _system, coefficient_symbols, real_solutions
from symctl.circuitatlas.odddegree import odd_degree_proof, slice_proof
from symctl.circuitatlas.pattern import Pattern, slot_names
from symctl.circuitatlas.rank import generic_rank
from symctl.circuitatlas.screen import (
    _generic_rationals,
    _region_sample,
    _search_regions,
    generic_degree,
    sample_targets,
    screen,
)
from symctl.circuitatlas.structural import forced_real_zeros, structural_refutation
from symctl.symbols import z

__all__ = [
    "CONJECTURED",
    "Evidence",
    "closed_form",
    "decide",
    "fixings",
    "forced_real_zeros",
    "generic_degree",
    "sample_targets",
]

FIXINGS = 6  # random values tried for the entries beyond a square system (above 3n entries)
DRAWS_PER_REGION = 4  # sampled controllers per region before the region counts as failed
CURVE_TARGETS_PER_REGION = {3: 1}  # by order: targets per region of a curve's exact screen
# (targets, fixings) of the witness search's passes; the second only where the first found none
EFFORTS = ((DRAWS_PER_REGION, FIXINGS), (3 * DRAWS_PER_REGION, 4 * FIXINGS))
POLE_DRAWS = 2  # sampled pole polynomials per region of the poles-alone refutation


def _linear_pair(eqs, left):
    """Two equations linear in the same two unknowns (free of the others): their solution."""
    for i, e1 in enumerate(eqs):
        pair = e1.free_symbols & left
        if len(pair) != 2:
            continue
        x, y = sorted(pair, key=str)
        for e2 in eqs[i + 1 :]:
            if e2.free_symbols & left != pair:
                continue
            rows = []
            for e in (e1, e2):
                poly = sp.Poly(e, x, y)
                if poly.total_degree() != 1:
                    break
                rows.append(tuple(poly.coeff_monomial(m) for m in (x, y, 1)))
            else:
                (p1, q1, r1), (p2, q2, r2) = rows
                det = sp.expand(p1 * q2 - p2 * q1)
                if det == 0:
                    continue
                return {
                    x: sp.cancel((q1 * r2 - q2 * r1) / det),
                    y: sp.cancel((p2 * r1 - p1 * r2) / det),
                }, (e1, e2)
    return None


@cache  # deterministic and a few tens of ms: realize and decide ask for it again and again
def closed_form(pattern: Pattern) -> MappingProxyType | None:
    """The entries as rational functions of :math:`(a, c)`, by linear steps (module text); or None."""
    unknowns, _slots, values, _, _ = _system(pattern)
    a, c = coefficient_symbols(pattern.n)
    eqs = [e for e in _equations(pattern, a, c) if e != 0]
    solved: dict[sp.Symbol, sp.Expr] = {}
    left = set(unknowns)

    def substitute(rule, used):
        out = [sp.expand(sp.numer(sp.together(q.xreplace(rule)))) for q in eqs if q not in used]
        return [q for q in out if q != 0]

    while left:
        step = None
        for e in eqs:
            free = e.free_symbols & left
            poly = sp.Poly(e, *free) if len(free) == 1 else None
            if poly is not None and poly.degree() == 1:
                c1, c0 = poly.all_coeffs()
                step = {poly.gens[0]: sp.cancel(-c0 / c1)}, (e,)
                break
        step = step or _linear_pair(eqs, left)
        if step is None:
            return None
        rule, used = step
        if any(v == 0 for v in rule.values()):
            return None
        solved.update(rule)  # in (a, c) alone: the earlier unknowns were substituted
        left -= set(rule)
        eqs = substitute(rule, used)
    if eqs:
        return None
    return MappingProxyType({k: solved.get(values[k], values[k]) for k in pattern.indices})


ATTEMPTS = 16  # choices of fixed entries tried for a pattern above 3n entries


def fixings(slots, extra: int, rng, attempts: int = ATTEMPTS):
    """Entries to fix and their values, small first (near a contained universal pattern's point)."""
    if extra <= 0:
        yield {}
        return
    combos = list(itertools.islice(itertools.combinations(slots, extra), 2000))
    rng.shuffle(combos)
    scales = (sp.Rational(1, 8), sp.Rational(1, 64), sp.Rational(1, 512), sp.Integer(1))
    for i, combo in enumerate(combos[:attempts]):
        scale = scales[i % len(scales)]
        yield {k: scale * rng.choice([-1, 1]) * rng.randint(1, 3) for k in combo}


@cache
def _generic_pole_degree(n: int, fmask: int) -> int | None:
    """:func:`generic_degree` of the poles-alone system of this ``F``."""
    free, charpoly = _pole_system(n, fmask)
    rng = random.Random(fmask)
    a = _generic_rationals(rng, n)
    sol = real_solutions([sp.expand(p - v) for p, v in zip(charpoly, a, strict=True)], free, rng)
    return None if sol is None else sol["degree"]


@cache
def _pole_system(n: int, fmask: int):
    """F's free entries after its own torus normalization and its charpoly's coefficients (None
    unless exactly ``n`` are free)."""
    graph = nx.Graph()
    graph.add_nodes_from(range(n))
    slots = [k for k in range(n * n) if fmask >> k & 1]
    for k in slots:
        i, j = divmod(k, n)
        if i != j and not graph.has_edge(i, j):
            graph.add_edge(i, j, slot=k)
    forest = {
        d["slot"] for _, _, d in nx.minimum_spanning_tree(graph, weight="slot").edges(data=True)
    }
    values = {k: sp.Integer(1) if k in forest else sp.Symbol(f"f_{k}") for k in slots}
    free = [v for v in values.values() if v != 1]
    if len(free) != n:
        return None
    F = sp.zeros(n, n)
    for k, v in values.items():
        F[k // n, k % n] = v
    charpoly = sp.Poly((z * sp.eye(n) - F).det(method="berkowitz"), z).all_coeffs()[::-1][:n]
    return free, charpoly


@cache  # many patterns share their F
def _pole_obstruction(n: int, fmask: int, seed: int) -> Evidence | None:
    """A refutation from the poles alone (module text), for every pattern with this ``F``."""
    system = _pole_system(n, fmask)
    if system is None:
        return None
    free, charpoly = system
    rng = random.Random(seed * 104729 + fmask)
    for region, pairs, signs, zeros in _search_regions(n):
        for _ in range(POLE_DRAWS):
            a, _c = _region_sample(n, pairs, signs, zeros, rng)
            eqs = [sp.expand(p - v) for p, v in zip(charpoly, a, strict=True)]
            sol = real_solutions(eqs, free, rng)
            if not sol or not sol["degree"] or sol["real"]:
                continue
            if sol["degree"] == _generic_pole_degree(n, fmask):
                shown, degree = [str(v) for v in a], sol["degree"]
                why = (
                    f"no real F with this support has the poles of the sampled a = {shown} "
                    f"({region}): det(zI - F) = a(z) has {degree} complex solutions and no "
                    "real one, so no H, M helps"
                )
                details = dict(region=region, a=shown, degree=degree, eliminant=sol["eliminant"])
                return _evidence(False, "counterexample", True, why, **details, poles_only=True)
    return None


def _witness(pattern: Pattern, rng, extra: int, a, c, tries: int = FIXINGS) -> dict | None:
    """A real realization of one target, Krawczyk-certified with every entry nonzero; or None."""
    unknowns, slots, values, _, _ = _system(pattern)
    for attempt, fixed in enumerate(fixings(slots, extra, rng, tries)):
        rule = {values[k]: v for k, v in fixed.items()}
        eqs = [sp.expand(e.xreplace(rule)) for e in _equations(pattern, a, c)]
        free = [x for x in unknowns if x not in rule]
        root = certified_real_root(eqs, free, seed=rng.randrange(2**32))
        if root is not None and root.nonzero:
            return {
                "a": [str(v) for v in a],
                "c": [str(v) for v in c],
                "fixed": {slot_names(pattern.n)[k]: str(v) for k, v in fixed.items()},
                "entries": {str(x): v for x, v in zip(free, root.values, strict=True)},
                "radius": max(root.radii),
                "attempt": attempt + 1,
            }
    return None


def _curve_screen(pattern: Pattern, rng, per_region: int) -> tuple[Evidence | None, dict]:
    """The exact screen of a curve (:mod:`~symctl.circuitatlas.critical`): a refutation, or
    the exact real realizations found per region."""
    found: dict[str, dict] = {}
    if not critical_degree(pattern):  # not a curve, or no finite critical system
        return None, found
    for region, pairs, signs, complex_zeros in _search_regions(pattern.n):
        for _ in range(per_region):
            a, c = _region_sample(pattern.n, pairs, signs, complex_zeros, rng)
            got = curve_target(pattern, a, c, rng)
            if got is None:
                continue
            if got["real"]:
                found.setdefault(region, {k: got[k] for k in ("a", "c", "point", "degree")})
                continue
            why = (
                f"the target a = {got['a']}, c = {got['c']} ({region}) has no real realization: "
                f"its fibre is a curve, and the {got['degree']} critical points of the distance "
                f"to p = {got['point']} on it (the generic number, simple) are none real; every "
                "closed real set has a nearest point, and these stay non-real nearby, so an open "
                "set of G2 has none"
            )
            details = {k: v for k, v in got.items() if k != "real"}
            return _evidence(False, "counterexample", True, why, region=region, **details), found
    return None, found


def _witness_search(pattern: Pattern, rng, extra: int, exact: bool | None = None) -> Evidence:
    witnessed: dict[str, dict] = {}
    curve_targets = CURVE_TARGETS_PER_REGION.get(pattern.n, 0) if exact is not False else 0
    if extra == 1 and curve_targets:
        refuted, witnessed = _curve_screen(pattern, rng, curve_targets)
        if refuted is not None:
            return refuted
    for draws, tries in EFFORTS:  # the second only where the first found nothing
        for region, pairs, signs, complex_zeros in _search_regions(pattern.n):
            for _ in range(draws if region not in witnessed else 0):
                a, c = _region_sample(pattern.n, pairs, signs, complex_zeros, rng)
                found = _witness(pattern, rng, extra, a, c, tries)
                if found is not None:
                    witnessed[region] = found
                    break
    failed = [r for r, *_ in _search_regions(pattern.n) if r not in witnessed]
    witnesses = {r: [w] for r, w in witnessed.items()}
    exact_found = sum("point" in w for w in witnessed.values())
    how = (
        f"exact (critical points of a distance, {curve_targets} generic targets drawn per "
        f"region, none without) in {exact_found}, Krawczyk-certified in "
        f"{len(witnessed) - exact_found}"
        if curve_targets and extra == 1
        else "proved (Krawczyk test)"
    )
    if not failed:
        why = (
            "conjectured universal, not proved: real realizations with every entry nonzero, "
            f"{how}, for sampled G2 in each region of poles and zeros ({', '.join(witnessed)}); "
            "samples cannot rule out a sub-region they missed"
        )
        return _evidence(None, CONJECTURED, False, why, witnesses=witnesses)
    why = (
        f"no real realization found for sampled G2 in {failed}"
        + (f" with {EFFORTS[-1][1]} random values of the {extra} extra entries" if extra else "")
        + "; neither proved nor refuted"
    )
    return _evidence(None, "not decided", False, why, failed_regions=failed, witnesses=witnesses)


def decide(
    pattern: Pattern, universal_below=(), *, seed: int = 0, exact: bool | None = None
) -> Evidence:
    """Decide whether ``pattern`` is universal (the methods: module text).

    ``universal_below``: ``(Pattern, Evidence)`` pairs already found universal (proved or
    conjectured); one contained in ``pattern`` decides it by lifting (a proof only when its
    source is one). ``exact=False`` skips the odd-degree proofs and the exact screen.

    >>> from symctl.circuitatlas.pattern import Pattern
    >>> from symctl.circuitatlas.universality import decide
    >>> decide(Pattern.from_matrices([[1, 0], [0, 1]], [1, 1], [1, 1])).universal
    False
    """
    n = pattern.n
    rank = generic_rank(pattern, seed)
    if not rank.minimal:
        why = "no realization with this pattern is minimal"
        return _evidence(False, "not minimal", rank.exact, why, rank=rank.rank)
    if rank.rank < 2 * n:
        why = (
            f"generic rank {rank.rank} < {2 * n}: the G2 it realizes form a set of dimension "
            f"{rank.rank} in the {2 * n}-dimensional space of order-{n} G2"
        )
        return _evidence(False, "rank", rank.exact, why, rank=rank.rank)
    blocked = structural_refutation(pattern)
    if blocked is not None:
        return blocked
    below = [(sub, ev) for sub, ev in universal_below if pattern.contains(sub)]
    for sub, ev in below:
        if ev.universal and ev.proved:
            why = (
                f"contains the universal pattern {sub.text} ({ev.method}); every added entry can "
                "be made nonzero along the fibre"
            )
            return _evidence(True, "lifted", True, why, source=sub.text, source_method=ev.method)
    if pattern.size == 3 * n:
        form = closed_form(pattern)
        if form is not None:
            return _closed_form_evidence(pattern, form)
    # exact refutations before any conjecture (n unknowns of degree <= n: a bounded solve)
    blocked = _pole_obstruction(n, pattern.mask & ((1 << (n * n)) - 1), seed)
    if blocked is not None:
        return blocked
    proof = _odd_degree(pattern, seed) if exact is not False else None
    if proof is not None and proof.get("proved"):
        fixed = ", ".join(f"{k} = {v}" for k, v in proof["fixed"].items())
        why = (
            (f"with {fixed}, " if fixed else "")
            + f"the generic fibre is in shape position over Q(a, c) with {proof['degree']} "
            "points, an odd number: almost every real G2 has a real realization, every entry "
            "nonzero (discriminant and resultants nonzero at a rational target)"
        )
        return _evidence(
            True, ODD_DEGREE, True, why, **{k: v for k, v in proof.items() if k != "proved"}
        )
    for sub, ev in below:
        if ev.conjectured:  # a lift is a proof only when its source is one
            why = (
                f"contains the conjectured pattern {sub.text}: universal if that one is (a lift), "
                "not proved"
            )
            return _evidence(
                None, CONJECTURED, False, why, source=sub.text, source_method=ev.method, lifted=True
            )
    if proof is not None:  # an odd degree without its proof: no target can refute it
        why = (
            f"conjectured universal, not proved: a random rational target has {proof['degree']} "
            f"complex realizations, an odd number, so a real one; {proof['why']} (the exact "
            "screen cannot refute an odd degree)"
        )
        return _evidence(None, CONJECTURED, False, why, degree=proof["degree"])
    screened = screen(pattern, seed=seed) if exact is not False else None
    if screened is not None:
        return screened
    rng = random.Random(seed * 7919 + pattern.mask)
    return _witness_search(pattern, rng, pattern.size - 3 * n, exact)


def _odd_degree(pattern: Pattern, seed: int) -> dict | None:
    """The odd-degree proof (or slice proof) as a dict; None when the degree is even or unknown."""
    n = pattern.n
    if pattern.size > 3 * n:
        return slice_proof(pattern, seed=seed)
    degree = generic_degree(pattern) if pattern.size == 3 * n else None
    if not degree or degree % 2 == 0:
        return None
    proof = odd_degree_proof(pattern, seed=seed) or {"proved": False, "why": "the proof failed"}
    return {"fixed": {}, **proof, "degree": degree}


def _closed_form_evidence(pattern: Pattern, form: dict) -> Evidence:
    from symctl.realization.check import check_realization
    from symctl.realization.realization import Realization

    a, c = coefficient_symbols(pattern.n)
    n = pattern.n
    F, H, M = pattern.matrices(form)
    G2 = sp.Integer(1) + sum(c[i] * z**i for i in range(n)) / (
        z**n + sum(a[i] * z**i for i in range(n))
    )
    check = check_realization(Realization(F, H, M, 1), G2, "exact")
    if not check:
        return _evidence(None, "not decided", False, "the closed form failed its exact check")
    why = (
        "the entries are rational functions of G2's coefficients (torus-normalized), "
        f"proved exactly against the symbolic G2 ({check.method})"
    )
    entries = {slot_names(n)[k]: str(form[k]) for k in pattern.indices}
    return _evidence(True, "closed form", True, why, entries=entries)
