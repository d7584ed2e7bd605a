"""Structural identifiability: a property of the model and the recorded set, not of the data."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import MuscleModel, augment, circuit_firing, fit, identifiability, lqr_gains
from symctl.proof import Verdict

GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
KW = {"sensor_delay": 1, "actuator_delay": 1, "circuit": "observable"}
PAPER = circuit_firing("observable", GAINS, count=1, rng=11)  # the paper's controller
TRUTH = {n: np.asarray(v)[0] for n, v in PAPER.firing.items()}


def _noisy(names, noise, seed):
    gen = np.random.default_rng(seed)
    return {
        n: TRUTH[n] + noise * np.sqrt(np.mean(TRUTH[n] ** 2)) * gen.normal(size=TRUTH[n].size)
        for n in names
    }


@pytest.mark.parametrize("noise", [0.0, 0.01, 0.1])
def test_the_state_neurons_are_not_identifiable_from_G2_y_alone_at_any_noise(noise):
    (structural,) = identifiability([["G2.y"]], GAINS, **KW)
    res = fit(_noisy(["G2.y"], noise, 0), GAINS, **KW, starts=2)
    assert not res.neuron_identifiable["G2.x1"] and not res.neuron_identifiable["G2.x2"]
    assert dict(res.neuron_identifiable) == dict(structural.neurons)
    assert dict(res.identifiable) == dict(structural.params)
    assert not res.identifiable["epsilon_1"] and not res.identifiable["C_1"]
    assert res.stderr["epsilon_1"] is None and np.isnan(res.band()["G2.x1"]).all()


@pytest.mark.parametrize("noise", [0.0, 0.01, 0.1])
def test_an_identifiable_neuron_stays_identifiable_with_noise(noise):
    data = _noisy(["G2.x2"], noise, 1)
    (free,) = identifiability([["G2.x2"]], GAINS, **KW)
    res = fit(data, GAINS, **KW, starts=2)
    assert res.neuron_identifiable["G2.x1"] and res.neuron_identifiable["G2.y"]
    assert not res.neuron_identifiable["G1.x1"] and dict(free.neurons) == dict(
        res.neuron_identifiable
    )
    (fixed,) = identifiability([["G2.x2"]], GAINS, **KW, C=1)  # full rank: a proof
    assert fixed.exact and fixed.error_bound == 0 and fixed.complete
    res = fit(data, GAINS, **KW, C=1, starts=2)
    assert all(res.neuron_identifiable.values()) and all(res.identifiable.values())
    assert res.identifiability.exact


@settings(max_examples=examples(5), deadline=None)
@given(seed=st.integers(0, 10**6), noise=st.sampled_from([0.001, 0.01, 0.1, 1.0]))
def test_the_verdicts_do_not_depend_on_the_noise_seed(seed, noise):
    res = fit(_noisy(["G2.y", "G2.x2"], noise, seed), GAINS, **KW, starts=1, rng=seed)
    (structural,) = identifiability([["G2.y", "G2.x2"]], GAINS, **KW)
    assert dict(res.neuron_identifiable) == dict(structural.neurons)
    assert dict(res.identifiable) == dict(structural.params)


def test_a_deficient_rank_is_schwartz_zippel_evidence_and_a_full_rank_a_proof():
    low, full = identifiability([["G2.y"], ["G1.x1", "G2.x1", "G2.y"]], GAINS, **KW)
    assert isinstance(low, Verdict) and low.verdict is False and not low
    assert not low.exact and 0 < low.error_bound < 1e-30 and "Schwartz-Zippel" in low.evidence
    assert full.verdict is True and full.exact and "proved" in full.evidence
    assert (low.rank, full.rank, full.n_params) == (2, 4, 4)
    assert "random integer points" in low.method


@pytest.mark.parametrize("rng", [1, 2, 3])
def test_the_random_points_do_not_change_the_verdicts(rng):
    sets = [["G2.y"], ["G2.x1"], ["G1.x1", "G2.y"]]
    ref = identifiability(sets, GAINS, **{**KW, "circuit": "general"})
    got = identifiability(sets, GAINS, **{**KW, "circuit": "general"}, rng=rng)
    for a, b in zip(ref, got, strict=True):
        assert (a.rank, dict(a.params), dict(a.neurons)) == (
            b.rank,
            dict(b.params),
            dict(b.neurons),
        )


def test_a_window_too_short_to_see_the_input_identifies_nothing():
    (row,) = identifiability([["G2.y"]], GAINS, **KW, steps=6)  # the pulse starts at step 5
    assert row.rank == 0 and not any(row.params.values())
    assert all(row.neurons.values())  # every trace is zero in the window: known
