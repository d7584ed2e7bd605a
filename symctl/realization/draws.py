r"""Realizations of :math:`G_2` at random section values: the realizations a circuit simulates.

The epsilons are drawn on the grid :math:`k/1000`, :math:`|k| \le 899` (:math:`C_k = 1`),
then the realizer's own choices from the same generator.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.validate import MAX_CIRCUITS, as_generator, bounded_int
from symctl.design.tf import DiscreteTF
from symctl.realization.factorization import Factorization, factor
from symctl.realization.realizers import RealizerResult, get_realizer

__all__ = ["EPS_GRID", "EPS_MAX", "Draw", "draw_eps", "draw_realizations"]

EPS_GRID = 1000
"""The epsilons are ``k / EPS_GRID``..."""
EPS_MAX = 899
"""... with ``|k| <= EPS_MAX``: the open interval (-0.9, 0.9)."""


@dataclass(frozen=True)
class Draw:
    """One realization of :math:`G_2` at drawn values: the epsilons drawn (``values``, the C are
    1), the :class:`Factorization` built at them and the :class:`RealizerResult` of its G2."""

    values: Mapping
    factors: Factorization
    result: RealizerResult

    def __post_init__(self) -> None:
        object.__setattr__(self, "values", MappingProxyType(dict(self.values)))

    def __hash__(self) -> int:
        return hash((tuple(self.values.items()), self.factors, self.result))


def draw_eps(eps, gen: np.random.Generator) -> dict:
    """Each epsilon drawn uniformly from the grid ``k / EPS_GRID``, ``|k| <= EPS_MAX`` (exact)."""
    return {e: sp.Rational(int(gen.integers(-EPS_MAX, EPS_MAX + 1)), EPS_GRID) for e in eps}


def draw_realizations(
    G: DiscreteTF, sensor_delay: int, actuator_delay: int, name: str, count: int, rng=None
) -> tuple[Draw, ...]:
    """``count`` (1 to ``MAX_CIRCUITS``) realizations by the realizer ``name`` of the :math:`G_2`
    of the numeric ``G`` at section values drawn from ``rng`` (which then seeds the realizer);
    ParameterError for an unknown realizer, a bad ``count`` or ``rng``."""
    realizer = get_realizer(name, "name")
    count = bounded_int(count, "count", 1, MAX_CIRCUITS)
    gen = as_generator(rng, "rng")
    f0 = factor(G, sensor_delay, actuator_delay)  # the section symbols, per channel
    eps = (*f0.sensor_eps, *f0.actuator_eps)
    out = []
    for _ in range(count):
        drawn = draw_eps(eps, gen)
        # the factors built at the drawn values: exact and cheap (no substitution into G2)
        fs = factor(G, sensor_delay, actuator_delay, eps=list(drawn.values()), C=1)
        out.append(Draw(drawn, fs, realizer(fs.G2, rng=gen)))
    return tuple(out)
