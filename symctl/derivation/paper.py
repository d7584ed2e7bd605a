r"""The paper's inputs, stated once: :data:`PAPER`, the defaults of ``derive_paper`` and ``symctl paper``.

The muscle's parameters are not repeated here: they are read from the defaults of
:class:`~symctl.design.plant.MuscleModel` (the paper's section "Simulations":
:math:`\tau = 0.02` s, :math:`f_\text{max} = 60` N, :math:`\bar r = 1`
spike/s, :math:`T_s = 0.01` s), and the delays from those of
:func:`~symctl.design.augment.augment` (one step each), so each number lives in
one place (a test checks that the muscle preset, ``examples/muscle.toml``, agrees).

>>> from symctl.derivation.paper import PAPER
>>> PAPER.tau, PAPER.sensor_delay, PAPER.seed
(0.02, 1, 0)
"""

from __future__ import annotations

import dataclasses
import inspect
from dataclasses import dataclass

from symctl.design.augment import augment
from symctl.design.plant import MuscleModel

__all__ = ["PAPER", "PaperSpec"]

_MUSCLE = {f.name: f.default for f in dataclasses.fields(MuscleModel)}
_DELAYS = {
    name: p.default
    for name, p in inspect.signature(augment).parameters.items()
    if name in ("sensor_delay", "actuator_delay")
}


@dataclass(frozen=True)
class PaperSpec:
    r"""The inputs of the paper's derivation, defaulting to the paper's values.

    Parameters
    ----------
    tau, f_max, r_bar, Ts : float
        The muscle's time constant [s], maximum force [N], equilibrium firing
        rate [spikes/s] and the sampling time [s]; defaults are those of
        :class:`~symctl.design.plant.MuscleModel`.
    sensor_delay, actuator_delay : int
        Delays in steps; defaults are those of :func:`~symctl.design.augment.augment`.
    seed : int
        Seed of the random realizations.
    realizations : int
        Random realizations simulated per circuit (the IFP controller has one).

    Examples
    --------
    >>> from symctl.derivation.paper import PaperSpec
    >>> PaperSpec(tau=0.05).tau, PaperSpec().f_max
    (0.05, 60.0)
    """

    tau: float = _MUSCLE["tau"]
    f_max: float = _MUSCLE["f_max"]
    r_bar: float = _MUSCLE["r_bar"]
    Ts: float = _MUSCLE["dt"]
    sensor_delay: int = _DELAYS["sensor_delay"]
    actuator_delay: int = _DELAYS["actuator_delay"]
    seed: int = 0
    realizations: int = 4


PAPER = PaperSpec()
"""The paper's parameters (the defaults of ``derive_paper`` and ``symctl paper``)."""
