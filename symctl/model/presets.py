"""The paper's muscle as a model file: ``symctl paper`` is ``symctl derive`` on this preset
(``presets/muscle.toml``, a copy of ``examples/muscle.toml`` that a test keeps identical).

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

MUSCLE_FILE = "presets/muscle.toml"  # inside the package symctl.model


@cache
def muscle_text() -> str:
    """The text of the muscle preset (``examples/muscle.toml``)."""
    return resources.files("symctl.model").joinpath(MUSCLE_FILE).read_text(encoding="utf-8")


@cache
def _preset() -> Model:
    return read_model(muscle_text(), "muscle preset (examples/muscle.toml)")


def muscle(**values) -> Model:
    """The muscle preset with ``values`` (as :meth:`Model.replace
    <symctl.model.model.Model.replace>` takes them; None keeps the file's) replacing the file's."""
    given = {k: v for k, v in values.items() if v is not None}
    return _preset().replace(**given) if given else _preset()
