r"""Universality over the reals: proved, refuted, or conjectured from witnesses region by region.

Write an order-:math:`n` :math:`G_2 = N + b(z)/a(z)`, :math:`a(z) = z^n +
\sum_{i<n} a_i z^i`, :math:`b(z) = \sum_{i<n} c_i z^i`
(:func:`~symctl.realization.realization.split_proper`). A pattern
(:mod:`symctl.circuitatlas.pattern`) is **universal** when almost every real
:math:`(a, c)` has a real realization with exactly that support. After the
torus normalization (the spanning-tree entries set to 1) the unknowns are the
other entries, and the conditions are the :math:`2n` polynomial equations
:math:`\det(zI - F) = a(z)`, :math:`M \operatorname{adj}(zI - F) H = b(z)`.
The verdicts, each with its method (:class:`Evidence`):

``"rank"`` (refuted)
    The generic rank is below :math:`2n` (:mod:`symctl.circuitatlas.rank`): the
    reachable :math:`G_2` form a set of lower dimension.
``"real eigenvalues"`` (refuted)
    ``F``'s graph has strongly connected components of sizes :math:`s_1, ..`;
    after a permutation ``F`` is block triangular with those diagonal blocks,
    so :math:`a = \prod a_k` with real :math:`a_k` of degree :math:`s_k`, and
    each odd :math:`s_k` gives a real pole. When more blocks are odd than
    :math:`n \bmod 2`, no :math:`G_2` with only :math:`n \bmod 2` real poles
    (an open set: complex poles) is reachable. A triangular ``F`` is the
    case :math:`s = (1, .., 1)`.
``"real zeros"`` (refuted)
    :math:`M \operatorname{adj}(zI - F) H`, factored over :math:`\mathbb{Q}` as a
    polynomial in :math:`z` and the entries, has irreducible factors of odd degree in
    :math:`z`, each with a real root for every real realization; when they force more
    than :math:`(n - 1) \bmod 2` real zeros, no :math:`G_2` whose numerator has complex
    zeros (an open set) is reachable (:func:`forced_real_zeros`). Example:
    ``F = [[f11, f12, f13], [f21, f22, 0], [f31, 0, f33]]``, :math:`H = e_1`,
    :math:`M = e_1^T` gives :math:`m_1 h_1 (z - f_{22})(z - f_{33})`.
``"closed form"`` (proved)
    The equations are solved one unknown at a time, each linear in it with
    the earlier ones substituted: the entries are rational functions of
    :math:`(a, c)`, real wherever defined, and none is identically zero. The
    realization built from them is proved to equal the symbolic :math:`G_2`
    by :func:`~symctl.check_realization` (exact).
``"lifted"`` (proved when its source is)
    The pattern contains a universal pattern :math:`S'`. For almost every
    :math:`G_2`, a realization :math:`x_0` with support :math:`S'` is a
    regular point of the bigger map (its :math:`S'`-columns already have rank
    :math:`2n`), so near :math:`x_0` the fibre is a manifold of dimension
    :math:`k - 2n` on which each added entry has a nonzero derivative (solve
    the kernel equation with that entry set to 1); it leaves every
    coordinate hyperplane, so a nearby point of the fibre has every entry of
    the bigger pattern nonzero.
``"conjectured"`` (evidence, not a proof; :attr:`Evidence.universal` is None)
    For a sampled :math:`G_2` in every region of poles and zeros (every number
    of complex pole pairs, every sign pattern of the real poles, and from order
    3 a numerator with complex zeros or only real ones) a real realization is
    found exactly: a lex Groebner basis over :math:`\mathbb{Q}` in shape
    position (:math:`x_i = g_i(t)`, :math:`e(t) = 0`, :math:`t` a random
    linear form), a real root of :math:`e` isolated in a rational interval,
    and every entry :math:`g_i(t)` shown nonzero on it. A handful of samples per
    region cannot rule out an open sub-region they missed, so this is a
    conjecture, counted apart from the proofs. A pattern that contains a
    conjectured one (and no proved one) is conjectured too.
``"counterexample"`` (refuted)
    A sampled :math:`G_2` whose fibre has :math:`d` simple points, none real
    (same certificate). Or, tried before any witness search (witnesses for a
    few sampled :math:`G_2` cannot rule out an unreachable sub-region), the
    poles alone: when ``F``'s own torus leaves :math:`n` free entries,
    :math:`\det(zI - F) = a(z)` is square, and a sampled :math:`a` with no
    real solution refutes every pattern with that ``F``. With :math:`d` the fibre degree, the points move
    continuously and stay non-real nearby, so an open set of controllers of
    that region has no realization. The sampled target must be generic: its
    fibre has the degree :math:`d` seen at a random target (:func:`generic_degree`)
    with simple points, else a solution went to infinity there and the target
    refutes nothing. (That :math:`d` is the generic degree holds with probability
    1, not by proof.)
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
from symctl.circuitatlas.evidence import CONJECTURED, Evidence, _evidence
from symctl.circuitatlas.fibre import (
    _equations,
    _system,
    coefficient_symbols,
    real_solutions,
    solve_at,
)
from symctl.circuitatlas.pattern import Pattern, slot_names
from symctl.circuitatlas.rank import generic_rank
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

SAMPLES_PER_REGION = 2
"""Sampled controllers per pole region of :func:`sample_targets`."""

FIXINGS = 6
"""Random values tried for the entries beyond a square system (patterns above 3n entries)."""

DRAWS_PER_REGION = 4
"""Sampled controllers drawn per region before the region counts as failed."""

WITNESSES_PER_REGION = 1
"""Witnesses the search asks for in each region of poles and zeros (signs of the real poles,
complex or real zeros; :func:`_search_regions`)."""

POLE_DRAWS = 8
"""Sampled pole polynomials per region of the poles-alone refutation."""

EXACT_SOLVE_MAX_ORDER = 3
"""Highest order whose failed witness searches fall back to the exact Groebner-basis solve
(a refutation). Above it that solve has no useful bound (eight unknowns at order 4), so a
region without a certified real root leaves the pattern not decided."""
"""Random values tried for the entries beyond a square system (patterns above 3n entries)."""


def _linear_pair(eqs, left):
    """Two equations linear in the same two unknowns (and free of the others): their solution."""
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
                rows.append(
                    (poly.coeff_monomial(x), poly.coeff_monomial(y), poly.coeff_monomial(1))
                )
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
    """The entries as rational functions of :math:`(a, c)`, by linear steps; or None.

    A step solves one equation linear in one unknown, or two equations linear in the
    same two unknowns (Cramer), with the earlier solutions substituted.
    """
    unknowns, _slots, values, _, _ = _system(pattern)
    a, c = coefficient_symbols(pattern.n)
    eqs = [e for e in _equations(pattern, a, c) if e != 0]
    solved: dict[sp.Symbol, sp.Expr] = {}
    left = set(unknowns)

    def substitute(rule, used):
        out = [sp.expand(sp.numer(sp.together(q.xreplace(rule)))) for q in eqs if q not in used]
        return [q for q in out if q != 0]

    while left:
        for e in eqs:
            free = e.free_symbols & left
            if len(free) != 1:
                continue
            (x,) = free
            poly = sp.Poly(e, x)
            if poly.degree() != 1:
                continue
            c1, c0 = poly.all_coeffs()
            value = sp.cancel(-c0 / c1)
            if value == 0:
                return None
            solved[x] = value
            left.discard(x)
            eqs = [sp.numer(sp.together(q.subs(x, value))) for q in eqs if q is not e]
            eqs = [sp.expand(q) for q in eqs]
            eqs = [q for q in eqs if q != 0]
            break
        else:
            step = _linear_pair(eqs, left)
            if step is None:
                return None
            rule, used = step
            if any(v == 0 for v in rule.values()):
                return None
            solved = {k: sp.cancel(v.xreplace(rule)) for k, v in solved.items()}
            solved.update(rule)
            left -= set(rule)
            eqs = substitute(rule, used)
    if eqs:
        return None
    return MappingProxyType({k: solved.get(values[k], values[k]) for k in pattern.indices})


def _poles(n: int, pairs: int, signs, rng) -> sp.Expr:
    """A monic a(z) with ``pairs`` complex pole pairs and real poles of the given signs."""
    a = sp.Integer(1)
    for _ in range(pairs):
        re = sp.Rational(rng.choice([-1, 1]) * rng.randint(1, 7), 8)
        im = sp.Rational(rng.randint(1, 7), 8)
        a *= z**2 - 2 * re * z + re**2 + im**2
    used = set()
    for s in signs:
        p = sp.Rational(rng.randint(1, 15), 16) * s
        while p in used:
            p += sp.Rational(1, 32) * s
        used.add(p)
        a *= z - p
    return sp.expand(a)


def _regions(n: int) -> list[tuple[str, int]]:
    out = []
    for pairs in range(n // 2, -1, -1):  # complex poles first: where patterns fail
        real = n - 2 * pairs
        name = (
            f"{pairs} complex pair{'s' * (pairs > 1)}, {real} real pole{'s' * (real != 1)}"
            if pairs
            else f"{real} real poles"
        )
        out.append((name, pairs))
    return out


def _sample(n: int, pairs: int, s: int, rng):
    real = n - 2 * pairs
    signs = [1 if (i + s) % 2 else -1 for i in range(real)]
    a = sp.Poly(_poles(n, pairs, signs, rng), z).all_coeffs()[::-1][:n]
    c = [sp.Rational(rng.choice([-1, 1]) * rng.randint(1, 9), rng.randint(1, 4)) for _ in range(n)]
    return [sp.Rational(v) for v in a], c


def _search_regions(n: int) -> list[tuple[str, int, tuple[int, ...], bool]]:
    """The regions of the witness search: ``(name, pairs, real pole signs, complex zeros)``.

    Every number of complex pole pairs, every sign pattern of the real poles, and (from
    order 3, where the numerator has two zeros or more) complex or only real zeros.
    """
    out = []
    for pairs in range(n // 2, -1, -1):  # complex poles first: where patterns fail
        real = n - 2 * pairs
        for plus in range(real, -1, -1):
            signs = (1,) * plus + (-1,) * (real - plus)
            poles = (f"{pairs} complex pair{'s' * (pairs > 1)}" if pairs else "") + (
                (", " if pairs else "") + "real poles " + "".join("+-"[x < 0] for x in signs)
                if real
                else ""
            )
            for complex_zeros in (True, False) if n >= 3 else (None,):
                zeros = {True: ", complex zeros", False: ", real zeros", None: ""}[complex_zeros]
                out.append((poles + zeros, pairs, signs, complex_zeros))
    return out


def _search_sample(n: int, pairs: int, signs, complex_zeros, rng):
    """A target of one search region: its poles, and a numerator with the region's zeros."""
    a = sp.Poly(_poles(n, pairs, signs, rng), z).all_coeffs()[::-1][:n]
    if complex_zeros is None:
        c = [
            sp.Rational(rng.choice([-1, 1]) * rng.randint(1, 9), rng.randint(1, 4))
            for _ in range(n)
        ]
        return [sp.Rational(v) for v in a], c
    zpairs = (n - 1) // 2 if complex_zeros else 0
    zsigns = [rng.choice([-1, 1]) for _ in range(n - 1 - 2 * zpairs)]
    gain = sp.Rational(rng.choice([-1, 1]) * rng.randint(1, 9), rng.randint(1, 4))
    b = sp.Poly(gain * _poles(n - 1, zpairs, zsigns, rng), z).all_coeffs()[::-1]
    return [sp.Rational(v) for v in a], [sp.Rational(v) for v in b]


def sample_targets(n: int, rng=None, per_region: int = SAMPLES_PER_REGION):
    """Sampled targets ``(region, a, c)``: every number of complex pole pairs, real poles of both signs.

    Examples
    --------
    >>> from symctl.circuitatlas.universality import sample_targets
    >>> sorted({r for r, _, _ in sample_targets(3)})
    ['1 complex pair, 1 real pole', '3 real poles']
    """
    rng = rng or random.Random(n)
    return [
        (region, *_sample(n, pairs, s, rng))
        for region, pairs in _regions(n)
        for s in range(per_region)
    ]


ATTEMPTS = 16
"""Choices of fixed entries tried for a pattern above 3n entries."""


def fixings(slots, extra: int, rng, attempts: int = ATTEMPTS):
    """Entries to fix and their values: small ones first.

    By the lifting argument (module text, ``"lifted"``), when the
    other entries contain a universal pattern, small enough fixed values leave
    a real solution near that pattern's realization.
    """
    if extra <= 0:
        yield {}
        return
    combos = list(itertools.islice(itertools.combinations(slots, extra), 2000))
    rng.shuffle(combos)
    scales = (sp.Rational(1, 8), sp.Rational(1, 64), sp.Rational(1, 512), sp.Integer(1))
    for i, combo in enumerate(combos[:attempts]):
        scale = scales[i % len(scales)]
        yield {k: scale * rng.choice([-1, 1]) * rng.randint(1, 3) for k in combo}


def _no_real_point(sol, generic: int | None = None) -> bool:
    """A solve_at / real_solutions result that is a finite fibre without a real point.

    With ``generic`` (the fibre degree at a generic target), only a fibre of that degree
    counts: a smaller one lost solutions to infinity and refutes nothing.
    """
    if sol is None or sol["degree"] == 0 or sol["real"]:
        return False
    return generic is None or sol["degree"] == generic


def _generic_rationals(rng, k: int) -> list[sp.Rational]:
    return [sp.Rational(rng.randint(-(10**6), 10**6), rng.randint(1, 10**6)) for _ in range(k)]


@cache
def generic_degree(pattern: Pattern) -> int | None:
    """The number of complex realizations (torus-normalized) of a random rational target.

    With probability 1 it is the fibre degree of almost every target; a target with fewer
    (simple) points is not generic. None when that fibre is not finite and reduced.
    """
    rng = random.Random(pattern.mask)
    n = pattern.n
    sol = solve_at(pattern, _generic_rationals(rng, n), _generic_rationals(rng, n), rng=rng)
    return None if sol is None else sol["degree"]


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
    """F's entries after F's own torus normalization, and det(zI - F)'s coefficients; or None.

    None unless the free entries are exactly ``n`` (a square system for the poles).
    """
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


@cache
def _pole_verdict(n: int, fmask: int, seed: int) -> Evidence | None:
    """:func:`_pole_obstruction` for every pattern with this ``F`` (cached: many share it)."""
    return _pole_obstruction(Pattern(n, fmask), random.Random(seed * 104729 + fmask))


def _pole_obstruction(pattern: Pattern, rng) -> Evidence | None:
    r"""A refutation from the poles alone: no real ``F`` with this support has the sampled poles.

    ``F``'s own torus (diagonal similarities) sets a spanning forest of its graph to 1; when
    :math:`n` entries remain, :math:`\det(zI - F) = a(z)` is square, and a sampled
    :math:`a` whose solutions are all non-real (exactly, :func:`real_solutions`) refutes
    every pattern with this ``F``, whatever ``H`` and ``M``.
    """
    n = pattern.n
    system = _pole_system(n, pattern.mask & ((1 << (n * n)) - 1))
    if system is None:
        return None
    free, charpoly = system
    for region, pairs in _regions(n):
        for s in range(POLE_DRAWS):
            a, _c = _sample(n, pairs, s, rng)
            eqs = [sp.expand(p - v) for p, v in zip(charpoly, a, strict=True)]
            sol = real_solutions(eqs, free, rng)
            if _no_real_point(sol) and _no_real_point(
                sol, _generic_pole_degree(n, pattern.mask & ((1 << (n * n)) - 1))
            ):
                return _evidence(
                    False,
                    "counterexample",
                    True,
                    f"no real F with this support has the poles of the sampled a = "
                    f"{[str(v) for v in a]} ({region}): det(zI - F) = a(z) has {sol['degree']} "
                    "complex solutions and no real one, so no H, M helps",
                    region=region,
                    a=[str(v) for v in a],
                    degree=sol["degree"],
                    eliminant=sol["eliminant"],
                    poles_only=True,
                )
    return None


def _witness(pattern: Pattern, rng, extra: int, region: str, a, c, exact: bool = True):
    """(witness, None), (None, refutation) or (None, None) for one sampled target."""
    unknowns, slots, values, _, _ = _system(pattern)
    found = None
    for attempt, fixed in enumerate(fixings(slots, extra, rng, FIXINGS)):
        rule = {values[k]: v for k, v in fixed.items()}
        eqs = [sp.expand(e.xreplace(rule)) for e in _equations(pattern, a, c)]
        free = [x for x in unknowns if x not in rule]
        root = certified_real_root(eqs, free, seed=rng.randrange(2**32))
        if root is not None and root.nonzero:
            found = {
                "a": [str(v) for v in a],
                "c": [str(v) for v in c],
                "fixed": {slot_names(pattern.n)[k]: str(v) for k, v in fixed.items()},
                "entries": {str(x): v for x, v in zip(free, root.values, strict=True)},
                "radius": max(root.radii),
                "attempt": attempt + 1,
            }
            break
    if found is None and not extra and exact:
        sol = solve_at(pattern, a, c, rng=rng)
        good = [r for r in sol["real"] if r["entries_nonzero"]] if sol else []
        if good:
            found = {
                "a": [str(v) for v in a],
                "c": [str(v) for v in c],
                "fixed": {},
                "eliminant": sol["eliminant"],
                "interval": good[0]["interval"],
            }
        elif _no_real_point(sol) and _no_real_point(sol, generic_degree(pattern)):
            return None, _evidence(
                False,
                "counterexample",
                True,
                f"the sampled G2 with a = {[str(v) for v in a]}, c = {[str(v) for v in c]} "
                f"({region}) has {sol['degree']} complex realizations with this pattern (the "
                "generic number, all simple) and no real one",
                region=region,
                a=[str(v) for v in a],
                c=[str(v) for v in c],
                degree=sol["degree"],
                eliminant=sol["eliminant"],
            )
    return found, None


def _witness_search(pattern: Pattern, rng, extra: int, exact: bool = True) -> Evidence:
    witnessed: dict[str, list] = {}
    failed = []
    for region, pairs, signs, complex_zeros in _search_regions(pattern.n):
        for _ in range(DRAWS_PER_REGION):
            if len(witnessed.get(region, ())) >= WITNESSES_PER_REGION:
                break
            a, c = _search_sample(pattern.n, pairs, signs, complex_zeros, rng)
            found, refuted = _witness(pattern, rng, extra, region, a, c, exact)
            if refuted is not None:
                return refuted
            if found is not None:
                witnessed.setdefault(region, []).append(found)
        if region not in witnessed:
            failed.append(region)
    if not failed:
        return _evidence(
            None,
            CONJECTURED,
            False,
            "conjectured universal, not proved: real realizations with every entry nonzero, "
            "proved (Krawczyk test or exact Groebner basis), for "
            f"{sum(map(len, witnessed.values()))} sampled G2, one in each region of poles and "
            f"zeros ({', '.join(witnessed)}); samples cannot rule out a sub-region they missed",
            witnesses=witnessed,
        )
    return _evidence(
        None,
        "not decided",
        False,
        f"no real realization found for sampled G2 in {sorted(set(failed))}"
        + (f" with {FIXINGS} random values of the {extra} extra entries" if extra else "")
        + "; neither proved nor refuted",
        failed_regions=sorted(set(failed)),
        witnesses=witnessed,
    )


def decide(
    pattern: Pattern, universal_below=(), *, seed: int = 0, exact: bool | None = None
) -> Evidence:
    """Decide whether ``pattern`` is universal (see the module text for the methods).

    Parameters
    ----------
    pattern : Pattern
    universal_below : iterable of (Pattern, Evidence)
        Patterns already found universal (proved or conjectured); one contained
        in ``pattern`` decides it by lifting, a proof only when the source's
        verdict is one.
    seed : int
        Seeds the sampled targets and linear forms.
    exact : bool, optional
        Fall back to the exact solve (and its counterexamples) when the
        certified numeric search finds no witness; by default up to
        :data:`EXACT_SOLVE_MAX_ORDER`.

    Returns
    -------
    Evidence

    Examples
    --------
    >>> from symctl.circuitatlas.pattern import Pattern
    >>> from symctl.circuitatlas.universality import decide
    >>> decide(Pattern.from_matrices([[1, 0], [0, 1]], [1, 1], [1, 1])).universal
    False
    """
    n = pattern.n
    rank = generic_rank(pattern, seed)
    if not rank.minimal:
        return _evidence(
            False,
            "not minimal",
            rank.exact,
            "no realization with this pattern is minimal",
            rank=rank.rank,
        )
    if rank.rank < 2 * n:
        return _evidence(
            False,
            "rank",
            rank.exact,
            f"generic rank {rank.rank} < {2 * n}: the G2 it realizes form a set of dimension "
            f"{rank.rank} in the {2 * n}-dimensional space of order-{n} G2",
            rank=rank.rank,
        )
    blocked = structural_refutation(pattern)
    if blocked is not None:
        return blocked
    below = [(sub, ev) for sub, ev in universal_below if pattern.contains(sub)]
    for sub, ev in below:
        if ev.universal and ev.proved:
            return _evidence(
                True,
                "lifted",
                True,
                f"contains the universal pattern {sub.text} ({ev.method}); every added entry can "
                "be made nonzero along the fibre",
                source=sub.text,
                source_method=ev.method,
            )
    if pattern.size == 3 * n:
        form = closed_form(pattern)
        if form is not None:
            return _closed_form_evidence(pattern, form)
    # an exact refutation first: witnesses for a few sampled G2 per region do not rule out
    # an unreachable sub-region (n unknowns of degree <= n: bounded at every order here)
    blocked = _pole_verdict(n, pattern.mask & ((1 << (n * n)) - 1), seed)
    if blocked is not None:
        return blocked
    for sub, ev in below:
        if ev.conjectured:  # a lift is a proof only when its source is one
            return _evidence(
                None,
                CONJECTURED,
                False,
                f"contains the conjectured pattern {sub.text}: universal if that one is (a lift), "
                "not proved",
                source=sub.text,
                source_method=ev.method,
                lifted=True,
            )
    rng = random.Random(seed * 7919 + pattern.mask)
    if exact is None:
        exact = n <= EXACT_SOLVE_MAX_ORDER
    return _witness_search(pattern, rng, pattern.size - 3 * n, exact)


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
    names = pattern.slots
    return _evidence(
        True,
        "closed form",
        True,
        "the entries are rational functions of G2's coefficients (torus-normalized), "
        f"proved exactly against the symbolic G2 ({check.method})",
        entries={name: str(form[k]) for name, k in zip(names, pattern.indices, strict=True)},
    )
