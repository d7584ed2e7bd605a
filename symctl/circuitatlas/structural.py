r"""Structural refutations: what every real realization with a support forces, with one-line proofs.

Each rule reads a property off the support alone, holds for every real
realization with it, and excludes an open set of order-:math:`n` :math:`G_2`
(so the pattern is not universal). They run before any proof or sampled search.

``"real eigenvalues"``
    ``F``'s graph has strongly connected components of sizes :math:`s_1, ..`;
    after a permutation ``F`` is block triangular with those diagonal blocks,
    so :math:`a = \prod a_k` with real :math:`a_k` of degree :math:`s_k`, and
    each odd :math:`s_k` gives a real pole. When more blocks are odd than
    :math:`n \bmod 2`, the :math:`G_2` with only :math:`n \bmod 2` real poles
    (complex poles: an open set) are out of reach.
``"real zeros"``
    :math:`M \operatorname{adj}(zI - F) H`, factored over :math:`\mathbb{Q}` as a
    polynomial in :math:`z` and the entries, has irreducible factors of odd degree in
    :math:`z`, each with a real root for every real realization; when they force more
    than :math:`(n - 1) \bmod 2` real zeros, the :math:`G_2` whose numerator has complex
    zeros (an open set) are out of reach (:func:`forced_real_zeros`).

No rule forces a *sign* on a single pole or zero: the coefficients of
:math:`\det(zI - F)` and :math:`M \operatorname{adj}(zI - F) H` are multilinear in the
entries, so a factor linear in :math:`z` is :math:`f_1 z + f_0` with coprime multilinear
(hence squarefree) :math:`f_0, f_1`; unless both are constant (a fixed root: a rank
deficiency), one of them changes sign across its zero set where the other does not vanish,
and so does the root :math:`-f_0 / f_1`. Sign restrictions come from several coefficients at
once (a discriminant, for example); the exact screen (:mod:`~symctl.circuitatlas.screen`)
finds those.

>>> from symctl.circuitatlas.pattern import Pattern
>>> from symctl.circuitatlas.structural import structural_refutation
>>> structural_refutation(Pattern.from_matrices([[1, 1], [0, 1]], [1, 1], [1, 1])).method
'real eigenvalues'
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from flint import fmpz_mpoly_ctx

from symctl.circuitatlas.evidence import Evidence, _evidence
from symctl.circuitatlas.fibre import coefficient_polynomials
from symctl.circuitatlas.pattern import Pattern
from symctl.symbols import z

__all__ = ["forced_real_zeros", "structural_refutation"]


def structural_refutation(pattern: Pattern) -> Evidence | None:
    """The first structural rule that refutes ``pattern`` (see the module text), or None."""
    for rule in (_odd_blocks, forced_real_zeros):
        found = rule(pattern)
        if found is not None:  # a refutation is falsy: test for None
            return found
    return None


def _odd_blocks(pattern: Pattern) -> Evidence | None:
    sizes = pattern.component_sizes()
    odd = sum(s % 2 for s in sizes)
    if odd <= pattern.n % 2:
        return None
    return _evidence(
        False,
        "real eigenvalues",
        True,
        f"F is block triangular with diagonal blocks of sizes {list(sizes)}: it has at least "
        f"{odd} real eigenvalues, so no G2 with only {pattern.n % 2} real poles "
        "(complex poles) has a realization with this pattern",
        block_sizes=list(sizes),
    )


def _odd_factors(coeffs, gens) -> tuple[int, list[str]]:
    """Real roots in z forced by sum(coeffs[i] z^i) (its odd-degree factors over Q[gens, z],
    with multiplicity), and the factors that involve z."""
    poly = sp.Poly(sum(c * z**i for i, c in enumerate(coeffs)), *gens, z, domain=sp.ZZ)
    if poly.is_zero:
        return 0, []
    names = [str(g) for g in (*gens, z)]
    ctx = fmpz_mpoly_ctx.get(tuple(names), "lex")
    _, factors = ctx.from_dict({m: int(c) for m, c in poly.terms()}).factor()
    forced, shown = 0, []
    for f, mult in factors:
        d = f.degrees()[-1]
        if d == 0:
            continue
        forced += int(mult) * (int(d) % 2)
        shown.append(f"({f})" + (f"^{int(mult)}" if mult > 1 else ""))
    return forced, sorted(shown)


@cache
def _zero_factors(pattern: Pattern) -> tuple[int, list[str], int]:
    """:func:`_odd_factors` of the numerator over the pattern's own symbols, and its z-degree."""
    syms = pattern.symbols()
    F, H, M = pattern.matrices(syms)
    _, numer = coefficient_polynomials(F, H, M)
    degree = max((i for i, c in enumerate(numer) if c != 0), default=-1)
    return (*_odd_factors(numer, [syms[k] for k in pattern.indices]), degree)


def forced_real_zeros(pattern: Pattern) -> Evidence | None:
    r"""The refutation "real zeros" (module text): the numerator :math:`M \operatorname{adj}(zI - F)
    H` forces more real zeros than the :math:`G_2` with complex zeros have; None when the rule
    does not apply.

    Examples
    --------
    >>> from symctl.circuitatlas.pattern import Pattern
    >>> from symctl.circuitatlas.universality import forced_real_zeros
    >>> P = Pattern.from_matrices([[1, 1, 1], [1, 1, 0], [1, 0, 1]], [1, 0, 0], [1, 0, 0])
    >>> ev = forced_real_zeros(P)
    >>> ev.method, ev.details["region"], ev.details["factors"]
    ('real zeros', 'complex zeros', ['(F_22 - z)', '(F_33 - z)'])
    """
    n = pattern.n
    forced, factors, degree = _zero_factors(pattern)
    if n < 3 or degree != n - 1 or forced <= (n - 1) % 2:
        return None
    return _evidence(
        False,
        "real zeros",
        True,
        f"M adj(zI - F) H factors as {' '.join(factors)} (times entries): {forced} real zeros "
        f"for every real realization, so no G2 whose numerator has complex zeros (an open set) "
        "has a realization with this pattern",
        region="complex zeros",
        factors=factors,
        forced=forced,
    )
