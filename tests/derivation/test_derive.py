"""derivation/pipeline: derive is one value per model, derive_paper is derive of the preset replaced."""

from __future__ import annotations

import dataclasses

import pytest

from symctl import ParameterError, derive, derive_paper
from symctl.model.modelfile import read_model
from symctl.model.presets import muscle, muscle_text


def _fresh() -> object:
    """A model no other test derives (so that the count of steps below is this test's)."""
    return muscle().replace(seed=11, realizations=1)


def test_derive_runs_the_steps_once_per_model_value():
    model, steps, early = _fresh(), [], []
    first = derive(model, progress=steps.append, early=early.append)
    ran = len(steps)
    again = derive(muscle().replace(realizations=1).replace(seed=11), early=early.append)
    assert again is first and ran >= 10 and len(steps) == ran  # no step ran a second time
    # early: once, when computing, with the derivation as far as the circuits' simulations
    assert len(early) == 1 and steps.index("simulation") < steps.index("closed loop")
    assert steps.index("nonlinear") < steps.index("atlas")  # the atlas last: no circuit needs it
    part = early[0]
    later = ("closed_loop", "nonlinear", "atlas", "candidates", "longest", "variance")
    assert all(getattr(part, name) is None for name in later)
    assert first.atlas is not None and first.closed_loop is not None
    assert dataclasses.replace(part, **{k: getattr(first, k) for k in (*later, "spec")}) == first
    assert "closed_loop" not in part.figure_names() and "atlas_overview" not in part.figure_names()


def test_derive_paper_is_derive_of_the_preset_with_the_values_replaced(derived_T2):
    assert derive_paper() is derived_T2 is derive(muscle())
    assert derive_paper(realizations=1, rng=11) is derive(_fresh())


def test_the_realizations_run_before_the_simulation_that_closes_the_loop_with_them(derived_T2):
    steps = []
    derive(muscle().replace(seed=12, realizations=1), progress=steps.append)
    assert steps.index("realizations") < steps.index("compatibility") < steps.index("simulation")
    for name, rec in derived_T2.realizations.items():
        fp = derived_T2.circuits[name].firing
        first = {str(k): v for k, v in fp.params[0].items() if str(k).startswith("epsilon")}
        assert first == {k: v for k, v in rec.values.items() if k.startswith("epsilon")}
        assert fp.realizations[0].F == rec.numeric.F  # the first simulated is the record's


def test_replacing_a_value_is_reading_the_file_with_that_value():
    text = muscle_text()
    edited = text.replace("value = 0.02", "value = 0.05").replace("sensor = 1 ", "sensor = 2 ")
    read = read_model(edited, "muscle preset (examples/muscle.toml)")
    replaced = muscle().replace(tau=0.05, sensor_delay=2)
    for name in ("ode", "plant", "plant_symbolic", "graph", "vertices", "edges", "T"):
        assert getattr(replaced, name) == getattr(read, name), name


def test_replacing_a_value_by_the_one_the_model_has_keeps_the_model():
    m = muscle()
    assert m.replace(tau=0.02, dt=0.01, seed=0, Q=[[1]]) is m


@pytest.mark.parametrize(
    ("values", "word"),
    [
        ({"taus": 1}, "taus: not a value of the model"),
        ({"sensor_delay": 0, "actuator_delay": 0}, "net delay of 1 to"),
        ({"seed": -1}, "seed"),
        ({"Q": [[1, 0], [0, 1]]}, "Q"),
        ({"realizations": 0}, "realizations"),
    ],
)
def test_replace_refuses_bad_values_by_name(values, word):
    with pytest.raises(Exception, match=word) as info:
        muscle().replace(**values)
    assert info.type.__module__ == "symctl.errors"


def test_a_discrete_plant_keeps_its_sampling_time():
    m = read_model(
        '[model]\nname = "d"\n[discrete]\nA = [[0.5]]\nB = [[1.0]]\n[sampling]\nTs = 0.1\n'
    )
    with pytest.raises(ParameterError, match="dt: the discrete plant"):
        m.replace(dt=0.2)
    assert m.replace(seed=3).seed == 3
