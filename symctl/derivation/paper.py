"""The paper's inputs, stated once: :data:`PAPER`, the defaults of ``derive_paper`` and
``symctl paper``, read from :class:`~symctl.design.plant.MuscleModel` and
:func:`~symctl.design.augment.augment` (a test checks that ``examples/muscle.toml`` agrees)."""

from __future__ import annotations

import dataclasses
import inspect
from dataclasses import dataclass

from symctl.design.augment import augment
from symctl.design.plant import MuscleModel

__all__ = ["PAPER", "PaperSpec"]

_MUSCLE = {f.name: f.default for f in dataclasses.fields(MuscleModel)}
_DELAYS = inspect.signature(augment).parameters


@dataclass(frozen=True)
class PaperSpec:
    r"""The inputs of the paper's derivation (as :func:`~symctl.derive_paper` takes them),
    defaulting to the paper's values.

    >>> from symctl.derivation.paper import PAPER, PaperSpec
    >>> PAPER.tau, PAPER.sensor_delay, PAPER.seed, PaperSpec(tau=0.05).tau
    (0.02, 1, 0, 0.05)
    """

    tau: float = _MUSCLE["tau"]
    f_max: float = _MUSCLE["f_max"]
    r_bar: float = _MUSCLE["r_bar"]
    Ts: float = _MUSCLE["dt"]
    sensor_delay: int = _DELAYS["sensor_delay"].default
    actuator_delay: int = _DELAYS["actuator_delay"].default
    seed: int = 0
    realizations: int = 4


PAPER = PaperSpec()  # the paper's parameters (the defaults of derive_paper and symctl paper)
