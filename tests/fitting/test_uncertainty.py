"""Practical identifiability: confidence intervals, prediction bands, and what these data determine."""

from __future__ import annotations

import json

import numpy as np
import pytest
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import MuscleModel, augment, circuit_firing, fit, lqr_gains
from symctl.errors import ParameterError, SymctlTypeError
from symctl.fitting.uncertainty import Prediction, Uncertainty
from symctl.report.fit import report_text

GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
KW = {"sensor_delay": 1, "actuator_delay": 1, "circuit": "observable"}
PAPER = circuit_firing("observable", GAINS, count=1, rng=11)  # the paper's controller
G2 = {n: np.asarray(v)[0] for n, v in PAPER.firing.items()}


@pytest.fixture(scope="module")
def truth():
    """Every neuron's true trace: the noise-free fit of G2's neurons recovers the circuit."""
    ref = fit(G2, GAINS, **KW, C=1, bootstrap=0)
    assert dict(ref.params) == {str(k): v for k, v in PAPER.params[0].items()}
    return dict(ref.predict())


def _noisy(truth, names, noise, seed):
    gen = np.random.default_rng(seed)
    return {
        n: truth[n] + noise * np.sqrt(np.mean(truth[n] ** 2)) * gen.normal(size=truth[n].size)
        for n in names
    }


@pytest.fixture(scope="module")
def one(truth):
    """Only G2.x2 recorded, 1% noise: G2.x1 and G2.y identifiable, G1.x1 not."""
    return fit(_noisy(truth, ["G2.x2"], 0.01, 0), GAINS, **KW, starts=2, bootstrap=50)


def test_predict_is_still_the_dict_of_traces_and_carries_the_band(one):
    pred = one.predict()
    assert isinstance(pred, dict) and isinstance(pred, Prediction) and pred.level == 0.95
    assert set(pred) == set(pred.lower) == set(pred.upper) == set(one.neuron_identifiable)
    assert pred["G2.x1"].shape == one.t.shape
    for name, ok in one.neuron_identifiable.items():
        lower, upper = pred.lower[name], pred.upper[name]
        assert np.isnan(lower).all() != ok and np.isnan(upper).all() != ok
        if ok:
            assert np.all(lower <= upper) and np.all(np.isfinite(one.band()[name]))
    assert np.max(np.abs(pred.upper["G3.x1"] - pred.lower["G3.x1"])) < 1e-12  # the behaviour


def test_every_identifiable_parameter_has_an_interval_around_the_truth(one):
    true = {**{str(k): float(v) for k, v in PAPER.params[0].items()}, "C_3": 1.0}
    assert one.intervals["C_1"] is None and not one.identifiable["C_1"]
    for name, value in true.items():
        lo, hi = one.intervals[name]
        assert lo < float(one.params[name]) < hi and lo < value < hi
    assert one.uncertainty.replicates == 50 and "bootstrap" in one.uncertainty.method


def test_the_issue_reproduction_g2_y_alone_gives_no_band_to_the_state_neurons(truth):
    res = fit(_noisy(truth, ["G2.y"], 0.01, 1), GAINS, **KW, starts=2, bootstrap=20)
    pred = res.predict()
    for name in ("G1.x1", "G2.x1", "G2.x2"):
        assert not res.neuron_identifiable[name] and not res.neuron_determined[name]
        assert np.isnan(pred.lower[name]).all()
        row = next(line for line in res.table().splitlines() if line.startswith(f" {name}"))
        assert row.endswith("| not identifiable")
    assert res.intervals["epsilon_1"] is None and res.intervals["epsilon_3"] is not None


def test_a_band_wider_than_its_signal_is_not_determined_by_these_data(truth):
    res = fit(_noisy(truth, ["G2.x2"], 1.0, 2), GAINS, **KW, starts=2, bootstrap=50)
    pred = res.predict()
    width = np.sqrt(np.mean((pred.upper["G2.x1"] - pred.lower["G2.x1"]) ** 2))
    assert width > np.sqrt(np.mean(pred["G2.x1"] ** 2))
    assert res.neuron_identifiable["G2.x1"] and not res.neuron_determined["G2.x1"]
    assert res.neuron_determined["G2.x2"] and res.neuron_determined["G3.x1"]
    row = next(line for line in res.table().splitlines() if line.startswith(" G2.x1"))
    assert row.endswith("not determined by these data")
    assert res.to_dict()["neurons"]["G2.x1"] == {
        "recorded": False,
        "identifiable": True,
        "determined": False,
    }
    assert "not determined by these data" in report_text(res)
    titles = [ax.get_title() for ax in res.plot().axes]
    assert any("G2" in t and "not determined by these data" in t for t in titles)


def test_the_uncertainty_round_trips_and_fit_json_keeps_its_keys(one):
    data = one.to_dict()
    assert {"params", "stderr", "identifiable", "neurons", "identifiability", "residuals"} <= set(
        data
    )
    assert data["intervals"]["C_1"] is None and len(data["intervals"]["epsilon_1"]) == 2
    text = json.dumps(data)
    back = Uncertainty.from_dict(json.loads(text)["uncertainty"])
    assert back == one.uncertainty and back.to_dict() == data["uncertainty"]
    assert back.intervals["epsilon_1"] == one.intervals["epsilon_1"]


def test_fit_reports_each_stage_as_it_starts(truth):
    stages = []
    fit(
        _noisy(truth, ["G2.x2"], 0.01, 4),
        GAINS,
        **KW,
        starts=2,
        bootstrap=3,
        progress=stages.append,
    )
    assert stages == ["observable: 2 starts", "structural identifiability", "bootstrap: 3 refits"]


def test_without_a_bootstrap_there_are_no_intervals_and_the_verdicts_are_structural(truth):
    res = fit(_noisy(truth, ["G2.x2"], 0.01, 3), GAINS, **KW, starts=1, bootstrap=0)
    assert res.uncertainty.replicates == 0 and all(v is None for v in res.intervals.values())
    assert dict(res.neuron_determined) == dict(res.neuron_identifiable)
    assert np.isnan(res.predict().lower["G2.x1"]).all()


@pytest.mark.parametrize(
    ("options", "error", "match"),
    [
        ({"bootstrap": -1}, ParameterError, "bootstrap: must be an integer >= 0"),
        ({"bootstrap": 10**6}, ParameterError, "bootstrap: must be an integer <= 10000"),
        ({"bootstrap": 2.5}, SymctlTypeError, "bootstrap"),
        ({"level": 1.0}, ParameterError, "level: must be a number in"),
        ({"level": "high"}, SymctlTypeError, "level"),
        ({"progress": "print"}, SymctlTypeError, "progress: expected a callable"),
    ],
)
def test_bad_bootstrap_options_are_errors_naming_them(options, error, match):
    with pytest.raises(error, match=match):
        fit({"G2.x2": G2["G2.x2"]}, GAINS, **KW, **options)


@settings(max_examples=examples(4), deadline=None)
@given(
    seed=st.integers(0, 10**6),
    noise=st.sampled_from([0.0, 0.01, 0.1, 1.0]),
    recorded=st.sampled_from([["G2.y"], ["G2.x2"], ["G2.x1", "G2.y"]]),
)
def test_only_identifiable_neurons_get_bands_and_only_they_can_be_determined(
    truth, seed, noise, recorded
):
    res = fit(_noisy(truth, recorded, noise, seed), GAINS, **KW, starts=1, rng=seed, bootstrap=20)
    pred = res.predict()
    for name, ok in res.neuron_identifiable.items():
        assert res.neuron_determined[name] <= ok
        assert np.isfinite(pred.lower[name]).all() == ok
    for name, ok in res.identifiable.items():
        iv = res.intervals[name]
        assert (iv is not None) == ok and (iv is None or iv[0] <= iv[1])


@pytest.mark.slow
@pytest.mark.parametrize("noise", [0.01, 0.1])
def test_the_95_percent_bands_cover_the_truth_over_seeded_data_sets(truth, noise):
    covered = counted = 0
    for seed in range(20):
        res = fit(_noisy(truth, ["G2.x2"], noise, 100 + seed), GAINS, **KW, starts=2, rng=seed)
        pred = res.predict()
        assert not res.neuron_identifiable["G1.x1"] and not res.neuron_determined["G1.x1"]
        for name in ("G2.x1", "G2.x2", "G2.y"):
            true, busy = truth[name], truth[name] != 0
            inside = (pred.lower[name] <= true) & (true <= pred.upper[name])
            covered += int(np.sum(inside[busy]))
            counted += int(np.sum(busy))
    assert 0.85 <= covered / counted <= 0.995
