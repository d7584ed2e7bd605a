r"""Structural refutations: what every real realization with a support forces, with proofs.

``"real eigenvalues"``
    ``F``'s graph has strongly connected components of sizes :math:`s_k`; ``F`` is block
    triangular with those blocks, so :math:`a = \prod a_k` with real :math:`a_k` of degree
    :math:`s_k`, each odd one with a real pole. When more blocks are odd than :math:`n \bmod 2`,
    the :math:`G_2` with complex poles (an open set) are out of reach.
``"real zeros"``
    :math:`M \operatorname{adj}(zI - F) H`, factored over :math:`\mathbb{Q}` in :math:`z` and
    the entries, has odd-degree factors in :math:`z`, each with a real root; when they force
    more than :math:`(n - 1) \bmod 2` real zeros, the :math:`G_2` whose numerator has complex
    zeros (an open set) are out of reach.

No rule forces a *sign* on one pole or zero: the coefficients are multilinear in the entries, so
a factor :math:`f_1 z + f_0` has coprime squarefree :math:`f_0, f_1`; unless both are constant,
one changes sign where the other does not vanish, and so does the root. Sign restrictions come
from several coefficients at once; the screen finds those.

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
    why = (
        f"F is block triangular with diagonal blocks of sizes {list(sizes)}: it has at least "
        f"{odd} real eigenvalues, so no G2 with only {pattern.n % 2} real poles "
        "(complex poles) has a realization with this pattern"
    )
    return _evidence(False, "real eigenvalues", True, why, block_sizes=list(sizes))


def _odd_factors(coeffs, gens) -> tuple[int, list[str]]:
    """Real roots in z forced by sum(coeffs[i] z^i) (odd-degree factors), and those factors."""
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
    """The refutation ``"real zeros"`` (module text), or None when the rule does not apply.

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
    why = (
        f"M adj(zI - F) H factors as {' '.join(factors)} (times entries): {forced} real zeros "
        f"for every real realization, so no G2 whose numerator has complex zeros (an open set) "
        "has a realization with this pattern"
    )
    return _evidence(
        False, "real zeros", True, why, region="complex zeros", factors=factors, forced=forced
    )
