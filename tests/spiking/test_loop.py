"""spiking_response: the loop through spiking populations, beside symctl's linear loop."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import need_spiking

from symctl import (
    DimensionError,
    ParameterError,
    SymctlTypeError,
    spiking_response,
)

nengo = need_spiking("nengo")


@pytest.fixture(scope="module")
def paper(derived_T2):
    return derived_T2.gains, {k: r.firing.circuits[0] for k, r in derived_T2.circuits.items()}


@pytest.mark.parametrize("name", ["ifp", "general", "controllable", "observable"])
def test_exact_nodes_close_the_same_loop_as_symctl(paper, name):
    gains, circuits = paper
    r = spiking_response(gains, circuits[name], n_neurons=None)
    np.testing.assert_allclose(r.delta_f, r.delta_f_linear, rtol=0, atol=1e-9)
    np.testing.assert_allclose(r.delta_r, r.delta_r_linear, rtol=0, atol=1e-9)
    for neuron, trace in r.firing_linear.items():
        np.testing.assert_allclose(r.firing[neuron], trace, rtol=0, atol=1e-9)
    assert r.n_neurons == 0 and not r.spikes and r.spikes_per_second == 0


def test_more_neurons_per_population_bring_the_force_closer_to_the_linear_loop(paper):
    gains, circuits = paper
    small, large = (
        spiking_response(gains, circuits["observable"], n_neurons=n, rng=3) for n in (10, 1000)
    )
    assert large.deviation < small.deviation
    assert large.deviation < 0.05
    assert large.spikes_per_second > small.spikes_per_second > 0


def test_a_seed_gives_the_same_spikes_and_each_population_its_radius(paper):
    gains, circuits = paper
    a, b = (spiking_response(gains, circuits["ifp"], n_neurons=20, rng=7) for _ in range(2))
    assert a == b
    assert a.spikes["mu"].shape == (50 * 10, 20) and a.spikes["mu"].dtype == np.uint8
    peak = float(np.max(np.abs(a.firing_linear["mu"])))
    assert a.radius["mu"] == pytest.approx(1.2 * peak)


def test_to_nengo_builds_one_labelled_population_per_neuron(paper):
    _, circuits = paper
    c = circuits["observable"]
    net = c.to_nengo(30, neuron_type=nengo.LIFRate(), rng=0)
    assert list(net.populations) == [n.name for n in c.neurons]
    assert all(e.n_neurons == 30 for e in net.populations.values())
    assert isinstance(net.populations["G2.x1"].neuron_type, nengo.LIFRate)


def test_bad_arguments_name_themselves(paper, derived_oculomotor):
    gains, circuits = paper
    c = circuits["ifp"]
    with pytest.raises(ParameterError, match="n_neurons"):
        spiking_response(gains, c, n_neurons=0)
    with pytest.raises(SymctlTypeError, match="gains"):
        spiking_response("gains", c)
    with pytest.raises(SymctlTypeError, match="neuron_type"):
        spiking_response(gains, c, neuron_type="LIF")
    with pytest.raises(ParameterError, match="radius"):
        c.to_nengo(10, radius={"nobody": 1.0})
    with pytest.raises(ParameterError, match="neuron_type"):
        c.to_nengo(neuron_type=nengo.LIF())
    mimo = next(r.firing.circuits[0] for r in derived_oculomotor.circuits.values() if r.firing)
    with pytest.raises(DimensionError, match="circuit"):
        spiking_response(gains, mimo)


@pytest.mark.parametrize("amplitude", [0.01, 3.0])
def test_exact_nodes_around_the_nonlinear_muscle_close_nonlinear_checks_loop(paper, amplitude):
    from symctl import MuscleModel, nonlinear_check

    gains, circuits = paper
    chk = nonlinear_check(MuscleModel(), gains, amplitudes=[amplitude], rtol=1e-10)
    r = spiking_response(
        gains, circuits["ifp"], n_neurons=None, disturbance=amplitude, nonlinear=MuscleModel()
    )
    expected = chk.x_nonlinear[0] - chk.x_nonlinear[0, 0]  # from the equilibrium
    np.testing.assert_allclose(r.delta_f, expected, rtol=0, atol=1e-7 * np.abs(expected).max())
    # the linear loop stays the reference: close for a small pulse, apart for a large one
    gap = np.abs(r.delta_f - r.delta_f_linear).max() / np.abs(r.delta_f_linear).max()
    assert (gap < 1e-2) if amplitude < 1 else (gap > 1e-3)


def test_a_nonlinear_plant_of_another_size_or_sampling_time_is_refused(paper):
    from symctl import MuscleModel

    gains, circuits = paper
    with pytest.raises(ParameterError, match="nonlinear"):
        spiking_response(gains, circuits["ifp"], n_neurons=None, nonlinear=MuscleModel(dt=0.02))
    with pytest.raises(SymctlTypeError, match="model"):
        spiking_response(gains, circuits["ifp"], n_neurons=None, nonlinear="muscle")
