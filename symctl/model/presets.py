"""The paper's muscle as a model file: ``symctl paper`` is ``symctl derive`` on this preset.

:func:`muscle` reads the packaged ``presets/muscle.toml`` (a copy of
``examples/muscle.toml``; a test keeps them identical) with the muscle's
values given replaced (:meth:`Model.replace <symctl.model.model.Model.replace>`),
so that ``derive_paper(tau=...)`` and ``symctl derive examples/muscle.toml`` run one
pipeline on one description.

>>> from symctl.model.presets import muscle
>>> m = muscle(tau=0.05)
>>> m.name, [float(v) for v in m.ode.params.values()]
('muscle', [0.05, 60.0, 1.0])
"""

from __future__ import annotations

from functools import cache
from importlib import resources

from symctl.model.modelfile import Model, read_model

__all__ = ["MUSCLE_FILE", "muscle", "muscle_text"]

MUSCLE_FILE = "presets/muscle.toml"
"""The preset's file inside the package ``symctl.model``."""


@cache
def muscle_text() -> str:
    """The text of the muscle preset (``examples/muscle.toml``)."""
    return resources.files("symctl.model").joinpath(MUSCLE_FILE).read_text(encoding="utf-8")


@cache
def _preset() -> Model:
    return read_model(muscle_text(), "muscle preset (examples/muscle.toml)")


def muscle(**values) -> Model:
    """The muscle preset, with the values given replacing the file's.

    Parameters
    ----------
    **values
        As :meth:`Model.replace <symctl.model.model.Model.replace>` takes them: the
        muscle's ``tau``, ``f_max``, ``r_bar``, the sampling time ``Ts``, the delays
        ``sensor_delay``, ``actuator_delay`` in steps, ``Q``, ``R``, ``seed`` and
        ``realizations``; a value None keeps the file's.

    Returns
    -------
    Model
    """
    given = {k: v for k, v in values.items() if v is not None}
    return _preset().replace(**given) if given else _preset()
