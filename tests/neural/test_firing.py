"""Firing patterns: same behaviour in every realization, different firing of G2's neurons."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure

from symctl import (
    DimensionError,
    MuscleModel,
    ParameterError,
    SymctlTypeError,
    augment,
    controller_tf,
    factor,
    lqr_gains,
)
from symctl.neural.firing import FiringPatterns, circuit_firing
from symctl.neural.simulate import closed_loop_response, simulate_realization
from symctl.realization.realization import controller_realization
from symctl.symbols import C_1, C_3

MODEL = MuscleModel()
GAINS = lqr_gains(augment(MODEL, 1, 1))
NO_DELAY = lqr_gains(augment(MODEL, 0, 0))


@pytest.fixture(scope="module")
def general() -> FiringPatterns:
    return circuit_firing("general", GAINS, count=3, rng=7)


def test_force_and_rate_are_identical_across_realizations_and_optimal(general):
    ref = closed_loop_response(GAINS)
    scale = np.abs(ref.delta_r).max()
    assert np.abs(general.delta_r - ref.delta_r[:, 0]).max() <= 1e-9 * scale
    assert np.abs(general.delta_f - ref.delta_f[:, 0]).max() <= 1e-9 * np.abs(ref.delta_f).max()
    assert general.max_deviation <= 1e-9
    assert general.summary().behaviour_spread < 1e-12


def test_state_neurons_fire_differently_across_realizations(general):
    for name in ("G2.x1", "G2.x2"):
        assert np.ptp(general.firing[name], axis=0).max() > 1e-2
    s = general.summary()
    assert s.neurons == general.neurons
    assert np.all(s.spread[:2] > 1e-2)
    assert "spread" in s.table()


def test_shapes_and_names(general):
    assert general.neurons == ("G2.x1", "G2.x2", "G2.y")
    assert general.t.shape == (50,)
    assert general.delta_f.shape == general.delta_r.shape == (3, 50)
    assert all(tr.shape == (3, 50) for tr in general.firing.values())
    assert all({"epsilon_1", "epsilon_3", "P"} == set(map(str, p)) for p in general.params)
    assert all(-0.9 < float(v) < 0.9 for p in general.params for k, v in p.items() if k != "P")
    assert circuit_firing("controllable", GAINS, count=2).neurons == ("G2.x2", "G2.y")


def test_neuron_traces_equal_the_realization_states_of_an_independent_simulation(general):
    """G2's state neurons are the series realization's G2 states; y = M x + N (G1 output)."""
    f = factor(controller_tf(GAINS))
    for i, R2 in enumerate(general.realizations):
        eps = {k: v for k, v in general.params[i].items() if str(k) != "P"}
        fs = f.subs({**eps, C_1: 1, C_3: 1})
        res = simulate_realization(MODEL, controller_realization(fs, R2))
        M, N = R2.numeric()[2:]
        x, g1 = res.states[:, 1:3], res.states[:, 0]
        np.testing.assert_allclose(general.firing["G2.x1"][i], x[:, 0], atol=1e-12)
        np.testing.assert_allclose(general.firing["G2.x2"][i], x[:, 1], atol=1e-12)
        np.testing.assert_allclose(general.firing["G2.y"][i], x @ M[0] + N[0, 0] * g1, atol=1e-12)


def test_observable_and_ifp_neurons():
    ocr = circuit_firing("observable", GAINS, count=2, rng=3)
    assert ocr.neurons == ("G2.x1", "G2.x2", "G2.y")
    ifp = circuit_firing("ifp", GAINS)
    assert ifp.count == 1 and ifp.neurons == ("mu",)
    # mu(t) is delta_r(t + 2): mu -> gamma -> u over two unit delays
    np.testing.assert_allclose(ifp.firing["mu"][0, :-2], ifp.delta_r[0, 2:], atol=1e-14)


def test_same_seed_same_draws_other_seed_other_draws():
    a = circuit_firing("controllable", GAINS, count=2, rng=5)
    b = circuit_firing("controllable", GAINS, count=2, rng=np.random.default_rng(5))
    c = circuit_firing("controllable", GAINS, count=2, rng=6)
    assert a.params == b.params != c.params
    np.testing.assert_array_equal(a.firing["G2.x2"], b.firing["G2.x2"])


def test_plot_returns_a_figure_with_one_panel_per_neuron_and_the_force(general):
    fig = general.plot()
    assert isinstance(fig, Figure)
    titles = [ax.get_title() for ax in fig.axes]
    assert titles == ["", "neuron $x_{1}$", "neuron $x_{2}$", "neuron $y$"]
    assert fig.axes[0].get_title(loc="left").startswith("muscle force $f$ in every realization")
    grid = fig.axes[1].figure  # the neuron panels share their axis labels
    assert grid.get_supylabel() == "firing-rate change [spikes/s]"
    assert grid.get_supxlabel() == "time [s]"
    legend = fig.legends[0]
    assert len(legend.get_texts()) == general.count + 1  # the realizations and the optimal one
    assert "epsilon_{1}" in legend.get_texts()[0].get_text()


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"kind": "diagonal"}, ParameterError, "kind: must be one of"),
        ({"kind": 3}, SymctlTypeError, "kind:"),
        ({"count": 0}, ParameterError, "count: must be an integer >= 1, got 0"),
        ({"count": 2.0}, SymctlTypeError, "count: expected an integer"),
        ({"kind": "ifp", "count": 2}, ParameterError, "count: the IFP controller"),
        ({"gains": "K"}, SymctlTypeError, "gains: expected Gains"),
        ({"rng": "x"}, SymctlTypeError, "rng:"),
        ({"rtol": 0}, ParameterError, "rtol:"),
        ({"plant": ([[0.5]], [[4.6]])}, ParameterError, "plant: realization 0"),
        (
            {"plant": ([[0.5, 0], [0, 0.5]], [[1], [1]])},
            DimensionError,
            "plant: has 2 states and 1 input",
        ),
        ({"plant": "muscle"}, SymctlTypeError, "plant: expected"),
        ({"kind": "ifp", "gains": NO_DELAY}, ParameterError, "gains: the IFP controller"),
    ],
)
def test_bad_arguments_are_refused_by_name(kwargs, error, match):
    args = {"kind": "controllable", "gains": GAINS, "count": 1, **kwargs}
    kind, gains = args.pop("kind"), args.pop("gains")
    with pytest.raises(error, match=match):
        circuit_firing(kind, gains, **args)


def test_time_axis_is_labelled_in_the_plants_time_unit():
    steps = circuit_firing("controllable", lqr_gains(augment(([[0.6]], [[4.6]]), 1, 1)), count=1)
    assert steps.reference.time_unit == "steps"
    fig = steps.plot()
    assert fig.axes[0].get_xlabel() == fig.axes[1].figure.get_supxlabel() == "time [steps]"


def test_plot_refuses_a_bad_ncols_by_name(general):
    with pytest.raises(ParameterError, match="ncols: must be an integer >= 1"):
        general.plot(0)
    for ncols in (2.5, "3"):
        with pytest.raises(SymctlTypeError, match="ncols: expected an integer"):
            general.plot(ncols)


def test_circuits_without_neurons_give_empty_firing_and_summary():
    fp = circuit_firing("controllable", NO_DELAY, count=2)
    assert fp.neurons == () and fp.max_deviation <= 1e-9
    s = fp.summary()
    assert s.peak.shape == (2, 0) and s.spread.shape == (0,)


def test_summary_table_columns_line_up_for_long_neuron_names():
    from symctl.neural.firing import FiringSummary

    summary = FiringSummary(("G2.x1", "G2.x10_long_name"), np.ones((2, 2)), np.zeros(2), 0.0)
    lines = summary.table().splitlines()
    bars = {tuple(i for i, ch in enumerate(line) if ch == "|") for line in lines[:1] + lines[2:-1]}
    assert len(bars) == 1  # every row has its bars in the same columns


def test_firing_patterns_and_summary_are_read_only(general):
    for arr in (general.t, general.delta_f, general.delta_r, *general.firing.values()):
        assert not arr.flags.writeable
    with pytest.raises(TypeError):
        general.firing["G2.x1"] = np.zeros((3, 50))
    with pytest.raises(TypeError):
        general.params[0]["epsilon_1"] = 0
    s = general.summary()
    with pytest.raises(ValueError, match="read-only"):
        s.peak[0, 0] = 0.0
    assert not s.spread.flags.writeable


def test_trace_spread_sees_differing_traces_whose_peaks_are_equal():
    """G2.y starts at N * x1(G1) in every realization, so its peaks agree; its traces do not."""
    fp = circuit_firing("general", lqr_gains(augment(MuscleModel(), 1, 1)), count=4)
    s = fp.summary()
    y = s.neurons.index("G2.y")
    tr = fp.firing["G2.y"]
    assert s.trace_spread[y] == pytest.approx(float(np.max(tr.max(0) - tr.min(0))))
    assert s.trace_spread[y] > 1e-3 and s.trace_spread[y] > 10 * s.spread[y]
