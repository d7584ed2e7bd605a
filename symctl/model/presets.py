"""The paper's muscle as a model file: ``symctl paper`` is ``symctl derive`` on this preset.

:func:`muscle` reads the packaged ``presets/muscle.toml`` (a copy of
``examples/muscle.toml``; a test keeps them identical) with the muscle's
parameters, the delays and the circuits' seed and count replaced, so that
``derive_paper(tau=...)`` and ``symctl derive examples/muscle.toml`` run one
pipeline on one description.

>>> from symctl.model.presets import muscle
>>> m = muscle(tau=0.05)
>>> m.name, [float(v) for v in m.ode.params.values()]
('muscle', [0.05, 60.0, 1.0])
"""

from __future__ import annotations

import copy
from functools import cache
from importlib import resources

from symctl.model.modelfile import Model, _Reader
from symctl.model.source import Source

__all__ = ["MUSCLE_FILE", "muscle", "muscle_text"]

MUSCLE_FILE = "presets/muscle.toml"
"""The preset's file inside the package ``symctl.model``."""


@cache
def muscle_text() -> str:
    """The text of the muscle preset (``examples/muscle.toml``)."""
    return resources.files("symctl.model").joinpath(MUSCLE_FILE).read_text(encoding="utf-8")


@cache
def _source() -> Source:
    return Source.from_text(muscle_text(), "muscle preset (examples/muscle.toml)")


def muscle(
    *,
    tau: float | None = None,
    f_max: float | None = None,
    r_bar: float | None = None,
    Ts: float | None = None,
    sensor_delay: int | None = None,
    actuator_delay: int | None = None,
    seed: int | None = None,
    realizations: int | None = None,
) -> Model:
    """The muscle preset, with the values given replacing the file's (validated by the caller).

    Parameters
    ----------
    tau, f_max, r_bar, Ts : float, optional
        The muscle's parameters and the sampling time.
    sensor_delay, actuator_delay : int, optional
        The delays in steps.
    seed, realizations : int, optional
        Of the random realizations.

    Returns
    -------
    Model
    """
    src = _source()
    data = copy.deepcopy(src.data)
    for key, value in (("tau", tau), ("f_max", f_max), ("r_bar", r_bar)):
        if value is not None:
            data["parameters"][key]["value"] = value
    if Ts is not None:
        data["sampling"]["Ts"] = {"value": Ts, "unit": "s"}
    for key, value in (("sensor", sensor_delay), ("actuator", actuator_delay)):
        if value is not None:
            data["delays"][key] = value
    for key, value in (("seed", seed), ("realizations", realizations)):
        if value is not None:
            data["circuits"][key] = value
    return _Reader(Source(data, src.path, src.lines, src.text)).model()
