"""Time series are drawn as what they are and printed legibly: steps, units, keys off the data.

The figures are measured as printed (symctl.plotting.legibility: no text under 6 pt, no
two texts overlapping, none off the figure, no wider than the derivation's text, a unit
on every axis). The report's own figures, for the paper at T = 2 and T = 6 and for a
model file, are checked the same way in tests/report/test_figures.py.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.text import Text

from symctl import (
    MuscleModel,
    augment,
    circuit_firing,
    closed_loop_response,
    fit,
    lqr_gains,
    simulate_realization,
    synthetic_traces,
)
from symctl.plotting.firing import firing_plot
from symctl.plotting.fit import fit_plot
from symctl.plotting.legibility import legibility, missing_units
from symctl.plotting.response import nonlinear_plot, response_plot
from symctl.plotting.style import COLUMN, TEXT_WIDTH


def _lines(fig):
    return [ln for ax in fig.axes for ln in ax.get_lines() if len(ln.get_xdata()) > 2]


def _texts(fig):
    return [t.get_text() for t in fig.findobj(Text) if t.get_visible() and t.get_text()]


def _check(fig, name):
    """Legible at print size, a unit on every axis, no heading, one or two columns wide."""
    found = legibility(fig)
    assert found, f"{name}: {found}"
    assert not missing_units(fig), (name, missing_units(fig))
    assert fig._suptitle is None, (
        f"{name}: a figure has no heading unless asked (the caption says it)"
    )
    width = float(fig.get_size_inches()[0])
    assert width == pytest.approx(COLUMN) or width == pytest.approx(TEXT_WIDTH), (name, width)


def test_no_legend_is_clipped_with_the_whole_delay_on_the_actuator():
    # the sensor-delay 0 / actuator-delay 3 run: G1 vanishes, the realizations' keys are long
    fp = circuit_firing("general", lqr_gains(augment(MuscleModel(), 0, 3)), count=4)
    fig = firing_plot(fp)
    _check(fig, "firing_general, delays 0 + 3")
    legend = fig.legends[0]
    assert [t.get_text() for t in legend.get_texts()][:4] == [fp.legend_label(i) for i in range(4)]


def test_the_fit_figure_is_legible_and_names_what_each_panel_shows():
    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    data = synthetic_traces(gains, sensor_delay=1, actuator_delay=1, rng=3)
    res = fit(
        data.select(["G2.x1", "G2.y"]).traces,
        gains,
        sensor_delay=1,
        actuator_delay=1,
        C=1,
        starts=2,
    )
    fig = fit_plot(res)
    _check(fig, "fit")
    heads = [ax.get_title() for ax in fig.axes]
    assert sum("(recorded)" in h for h in heads) == 2 and len(heads) == len(res.predict())
    texts = [t.get_text() for t in fig.legends[0].get_texts()]
    assert texts[:2] == ["data", "fit"]
    assert all(
        ln.get_drawstyle() == "steps-post" for ln in _lines(fig) if ln.get_linestyle() == "-"
    )


def test_closed_loop_traces_are_steps_and_the_states_are_the_delay_chain():
    gains = lqr_gains(augment(MuscleModel(), 1, 2))  # T = 3: gamma_1, gamma_2, delta_r
    res = closed_loop_response(gains)
    assert res.controller_state_names == ("gamma_1", "gamma_2", "delta_r")
    fig = response_plot(res)
    assert all(ln.get_drawstyle() == "steps-post" for ln in _lines(fig))
    labels = fig.axes[-1].get_legend_handles_labels()[1]
    assert labels == [r"$\gamma_{1}$", r"$\gamma_{2}$", r"$\delta r$"]  # not x_1, x_2, x_3
    _check(fig, "closed loop, T = 3")


def test_a_panel_heading_gives_the_operating_point_and_a_key_never_sits_on_the_data():
    fig = response_plot(closed_loop_response(lqr_gains(augment(MuscleModel(), 1, 1))))
    force, rate, _ = fig.axes
    assert force.get_legend().get_title().get_text() == r"muscle force $f$ ($\bar{f}$ = 43.86 N)"
    assert rate.get_title(loc="left") == r"motor-neuron rate $r$ ($\bar{r}$ = 1 spike/s)"
    fig.canvas.draw()
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is not None:  # above the axes: its box starts where the data's ends
            assert legend.get_window_extent().y0 >= ax.get_window_extent().y1 - 1


def test_a_user_title_is_drawn_and_the_default_is_none():
    res = closed_loop_response(lqr_gains(augment(MuscleModel(), 1, 1)))
    assert response_plot(res)._suptitle is None
    assert response_plot(res, title="Closed loop")._suptitle.get_text() == "Closed loop"
    fp = circuit_firing("controllable", lqr_gains(augment(MuscleModel(), 1, 1)), count=2)
    assert firing_plot(fp, title="Firing")._suptitle.get_text() == "Firing"


def test_a_realization_closed_loop_names_its_states_x():
    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    from symctl.realization.realizers import ifp_realization

    res = simulate_realization(MuscleModel().plant(), ifp_realization(gains), 1.0)
    assert res.controller_state_names == tuple(f"x_{i + 1}" for i in range(res.states.shape[1]))
    fig = response_plot(res)
    assert fig.axes[-1].get_ylabel() == "state [arb. unit]"  # a realization's own scale


def test_mimo_chain_names_carry_the_input_index():
    from symctl.design.augment import chain_names

    assert chain_names(2, 2) == ("gamma_1[1]", "gamma_1[2]", "delta_r[1]", "delta_r[2]")
    assert chain_names(1, 1) == ("delta_r",)


def test_firing_panels_are_steps_and_the_heading_says_the_behaviour_is_the_same():
    fp = circuit_firing("general", lqr_gains(augment(MuscleModel(), 1, 1)), count=2)
    fig = firing_plot(fp)
    assert all(ln.get_drawstyle() == "steps-post" for ln in _lines(fig))
    head = fig.axes[0].get_title(loc="left")
    assert head.startswith("muscle force $f$ in every realization") and "relative" in head
    assert np.ptp(fp.delta_r, axis=0).max() <= 1e-9 * np.abs(fp.delta_r).max()
    assert "firing-rate change [spikes/s]" in _texts(fig)


def test_nonlinear_plot_draws_the_bounds_it_is_given_near_the_traces():
    from symctl import nonlinear_check

    chk = nonlinear_check(amplitudes=[1.0, 10.0], steps=30)
    fig = nonlinear_plot(chk, bounds=[(60.0, "top"), (-1000.0, "far")])
    key = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "top" in key and "far" not in key
    _check(fig, "nonlinear")


def test_legend_width_is_never_narrower_than_matplotlibs_legend():
    # the keys are placed by this measure: an underestimate would clip them or overlap
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from symctl.plotting.style import SMALL, legend_width, new_figure

    cases = [
        (["a", "bbbbbbbbb", "c"], 2),
        ([r"$\gamma_{1}$", r"$\gamma_{2}$", r"$\delta r$"], 3),
        ([r"#1: $\epsilon_{1}$ = 0.631, $\epsilon_{3}$ = 0.246"] * 4 + ["optimal controller"], 2),
        ([f"$w$ = {a} N per step" for a in (0.1, 0.3, 1, 3, 10)], 4),
    ]
    for labels, ncol in cases:
        fig = new_figure("text", 2.0)
        ax = fig.add_subplot()
        lines = [ax.plot([0, 1], [0, 1])[0] for _ in labels]
        legend = fig.legend(lines, labels, ncols=ncol, fontsize=SMALL, loc="center")
        renderer = FigureCanvasAgg(fig).get_renderer()
        fig.draw(renderer)
        drawn = legend.get_window_extent(renderer).width / fig.dpi
        assert drawn <= legend_width(labels, ncol) <= drawn + 0.3, (labels, ncol)


def test_an_axis_of_a_plant_without_units_says_so_not_dimensionless():
    from symctl import open_loop_response

    res = open_loop_response((np.array([[0.5]]), np.array([[1.0]])), steps=10)
    fig = response_plot(res)
    assert [ax.get_ylabel() for ax in fig.axes] == [
        r"$\delta x$ [arb. unit]",
        r"$\delta u$ [arb. unit]",
    ]
    assert fig.axes[-1].get_xlabel() == "time [steps]"


def test_a_noisy_loop_is_drawn_as_its_mean_in_a_band_of_two_standard_deviations():
    from matplotlib.collections import PolyCollection

    from symctl import Noise

    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    noise = Noise(process=0.01, sensor=1e-3)
    res = closed_loop_response(gains, noise=noise, draws=30, rng=1)
    fig = response_plot(res)
    bands = [c for ax in fig.axes for c in ax.collections if isinstance(c, PolyCollection)]
    assert len(bands) == res.delta_f.shape[1] + res.delta_r.shape[1] + res.states.shape[1]
    top = bands[0].get_paths()[0].vertices[:, 1]  # the band reaches mean +- 2 sd
    assert top.max() == pytest.approx(float((res.delta_f + 2 * res.delta_f_sd).max()))
    assert legibility(fig)
    quiet = response_plot(closed_loop_response(gains))
    assert not [c for ax in quiet.axes for c in ax.collections if isinstance(c, PolyCollection)]
    fp = circuit_firing("general", gains, count=2, noise=noise, noise_draws=20)
    fig = firing_plot(fp)
    per_neuron = [ax for ax in fig.axes[1:] if ax.collections]
    assert len(per_neuron) == len(fp.neurons) and "noisy runs" in fig.axes[0].get_title(loc="left")
    _check(fig, "noisy firing")
