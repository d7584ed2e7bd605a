"""report/spec: the paper's parameters come from one place."""

from __future__ import annotations

import dataclasses
import inspect

from symctl import MuscleModel, augment, derive_paper
from symctl.cli import paper
from symctl.report.spec import CIRCUIT_SPECS, CIRCUITS, PAPER


def test_the_muscle_defaults_are_muscle_models_fields():
    fields = {f.name: f.default for f in dataclasses.fields(MuscleModel)}
    assert {
        k: getattr(PAPER, {"dt": "Ts"}.get(k, k)) for k in fields
    } == fields  # Ts: the file's key
    delays = inspect.signature(augment).parameters
    assert PAPER.sensor_delay == delays["sensor_delay"].default
    assert PAPER.actuator_delay == delays["actuator_delay"].default


def test_derive_paper_and_the_cli_default_to_the_spec():
    params = inspect.signature(derive_paper).parameters
    for name, field in (("dt", "Ts"), ("rng", "seed")):
        assert params[name].default == getattr(PAPER, field), name
    for name in ("tau", "f_max", "r_bar", "sensor_delay", "actuator_delay"):
        assert params[name].default == getattr(PAPER, name), name
    assert params["realizations"].default == PAPER.realizations
    options = {opt: p.default for p in paper.params for opt in p.opts}
    for name in ("tau", "f_max", "r_bar", "sensor_delay", "actuator_delay", "seed", "realizations"):
        assert options["--" + name.replace("_", "-")] == getattr(PAPER, name), name
    assert options["--ts"] == PAPER.Ts


def test_the_circuits_are_the_specs_in_reading_order():
    assert CIRCUITS == ("ifp", "general", "controllable", "observable", "pathways")
    assert all(CIRCUIT_SPECS[name].name == name for name in CIRCUITS)
    # the paper's chain of unit steps: no circuit along pathways (it would be the controllable one)
    assert list(derive_paper(realizations=1).circuits) == list(CIRCUITS[:-1])


def test_bad_seed_and_realizations_name_themselves_before_any_work():
    import pytest

    from symctl.errors import ParameterError, SymctlTypeError

    with pytest.raises(ParameterError, match="rng: must be an integer >= 0, got -1"):
        derive_paper(rng=-1)
    with pytest.raises(SymctlTypeError, match=r"rng: expected an integer, got 1\.5"):
        derive_paper(rng=1.5)
    with pytest.raises(ParameterError, match="realizations: must be an integer >= 1, got 0"):
        derive_paper(realizations=0)
