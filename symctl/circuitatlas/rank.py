r"""The exact generic-rank test: how many of :math:`G_2`'s coefficients a pattern can move.

A pattern with :math:`k` nonzero slots maps its entries to the :math:`2n` coefficients of
:math:`a(z) = \det(zI - F)` and :math:`b(z) = M \operatorname{adj}(zI - F) H`. It can be
universal only if the Jacobian has generic rank :math:`2n`; otherwise the image has measure
zero.

**Evaluation at points.** The values at :math:`n` distinct points :math:`z_l` determine the
coefficients, and :math:`(a, b) \mapsto (a, g = b/a)` is invertible where :math:`a(z_l) \ne 0`,
so the Jacobian of :math:`(\log a(z_l), g(z_l))_l` has the same rank. With :math:`R = (z_l I -
F)^{-1}`: :math:`\partial \log a / \partial F_{ij} = -R_{ji}`, :math:`\partial g / \partial
F_{ij} = (MR)_i (RH)_j`, :math:`\partial g/\partial H_i = (MR)_i`, :math:`\partial g / \partial
M_j = (RH)_j`.

**Exactness.** Everything is evaluated at random points modulo :math:`p = 2^{61} - 1`. A rank
mod :math:`p` at an integer point is a lower bound of the rank over :math:`\mathbb{Q}`, so
**full rank mod p is a proof**. A smaller rank is confirmed at independent points; by
Schwartz-Zippel one point misses a nonzero :math:`2n`-minor (degree at most :math:`2n^2`) with
probability at most :math:`2n^2/p`. When :math:`k < 3n` the deficiency is exact anyway: the
torus orbits lie in the fibres with dimension :math:`n`, so the rank is at most :math:`k - n <
2n`. The same points decide **generic minimality** (controllability and observability matrices
of rank :math:`n` mod :math:`p`).

>>> from symctl.circuitatlas.pattern import Pattern
>>> from symctl.circuitatlas.rank import generic_rank
>>> generic_rank(Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1]))
GenericRank(rank=4, minimal=True, exact=True, points=1)
"""

from __future__ import annotations

import random
from typing import NamedTuple

from flint import nmod_mat

from symctl.circuitatlas.pattern import Pattern

__all__ = ["PRIME", "GenericRank", "generic_rank"]

PRIME = 2**61 - 1  # the prime modulus of the rank test

POINTS = 3  # random points tried before a deficient rank is reported


class GenericRank(NamedTuple):
    """A pattern's generic rank and minimality; ``exact`` when proved, else Schwartz-Zippel
    evidence over ``points`` points."""

    rank: int
    minimal: bool
    exact: bool
    points: int


def _point(pattern: Pattern, rng: random.Random):
    n = pattern.n
    mats = {"F": [[0] * n for _ in range(n)], "H": [[0] for _ in range(n)], "M": [[0] * n]}
    for k in pattern.indices:
        kind, i, j = pattern.where(k)
        mats[kind][i][j] = rng.randrange(1, PRIME)
    return mats["F"], [h for (h,) in mats["H"]], mats["M"][0]


def _minimal_at(n: int, F, H, M) -> bool:
    Fm = nmod_mat(F, PRIME)
    cols = [nmod_mat([[h] for h in H], PRIME)]
    rows = [nmod_mat([M], PRIME)]
    for _ in range(n - 1):
        cols.append(Fm * cols[-1])
        rows.append(rows[-1] * Fm)
    W = nmod_mat([[int(c[i, 0]) for c in cols] for i in range(n)], PRIME)
    Ob = nmod_mat([[int(r[0, j]) for j in range(n)] for r in rows], PRIME)
    return W.rank() == n and Ob.rank() == n


def _rank_at(pattern: Pattern, F, H, M, rng: random.Random) -> int:
    n = pattern.n
    rows = []
    for _ in range(n):
        zl = rng.randrange(1, PRIME)
        A = nmod_mat([[(zl if i == j else 0) - F[i][j] for j in range(n)] for i in range(n)], PRIME)
        try:
            Rm = A.inv()
        except ZeroDivisionError:  # z_l an eigenvalue mod p: a probability-1/p event
            return -1
        R = [[int(Rm[i, j]) for j in range(n)] for i in range(n)]
        MR = [sum(M[a] * R[a][i] for a in range(n)) % PRIME for i in range(n)]
        RH = [sum(R[j][a] * H[a] for a in range(n)) % PRIME for j in range(n)]
        ra, rg = [], []
        for k in pattern.indices:
            kind, i, j = pattern.where(k)
            ra.append(-R[j][i] % PRIME if kind == "F" else 0)
            rg.append({"F": MR[i] * RH[j] % PRIME, "H": MR[i], "M": RH[j]}[kind])
        rows += [ra, rg]
    return nmod_mat(rows, PRIME).rank() if pattern.size else 0


def generic_rank(pattern: Pattern, seed: int = 0) -> GenericRank:
    """The generic rank of ``pattern``'s map to :math:`G_2`'s coefficients (module text).

    >>> from symctl.circuitatlas.pattern import Pattern
    >>> from symctl.circuitatlas.rank import generic_rank
    >>> generic_rank(Pattern.from_matrices([[1, 0], [0, 1]], [1, 1], [1, 0])).minimal
    False
    """
    rng = random.Random(seed * 1_000_003 + pattern.mask)
    n = pattern.n
    best, minimal = 0, False
    tries = 0
    for tries in range(1, POINTS + 1):  # noqa: B007 (tries is reported)
        F, H, M = _point(pattern, rng)
        minimal = minimal or _minimal_at(n, F, H, M)
        best = max(best, _rank_at(pattern, F, H, M, rng))
        if best == 2 * n and minimal:
            break
    full = best == 2 * n
    exact = full or pattern.size < 3 * n
    return GenericRank(best, minimal, exact, tries)
