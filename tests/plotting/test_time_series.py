"""Time series are drawn as what they are: discrete-time signals held over each step, named."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np

from symctl import (
    MuscleModel,
    augment,
    circuit_firing,
    closed_loop_response,
    lqr_gains,
    simulate_realization,
)
from symctl.plotting.firing import firing_plot
from symctl.plotting.response import response_plot


def _lines(fig):
    return [ln for ax in fig.axes for ln in ax.get_lines() if len(ln.get_xdata()) > 2]


def test_closed_loop_traces_are_steps_and_the_states_are_the_delay_chain():
    gains = lqr_gains(augment(MuscleModel(), 1, 2))  # T = 3: gamma_1, gamma_2, delta_r
    res = closed_loop_response(gains)
    assert res.controller_state_names == ("gamma_1", "gamma_2", "delta_r")
    fig = response_plot(res)
    assert all(ln.get_drawstyle() == "steps-post" for ln in _lines(fig))
    labels = fig.axes[-1].get_legend_handles_labels()[1]
    assert labels == [r"$\gamma_{1}$", r"$\gamma_{2}$", r"$\delta_{r}$"]  # not x_1, x_2, x_3


def test_a_realization_closed_loop_names_its_states_x():
    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    from symctl.realization.realizers import ifp_realization

    res = simulate_realization(MuscleModel().plant(), ifp_realization(gains), 1.0)
    assert res.controller_state_names == tuple(f"x_{i + 1}" for i in range(res.states.shape[1]))


def test_mimo_chain_names_carry_the_input_index():
    from symctl.design.augment import chain_names

    assert chain_names(2, 2) == ("gamma_1[1]", "gamma_1[2]", "delta_r[1]", "delta_r[2]")
    assert chain_names(1, 1) == ("delta_r",)


def test_firing_panels_are_steps_and_the_title_says_what_is_plotted():
    fp = circuit_firing("general", lqr_gains(augment(MuscleModel(), 1, 1)), count=2)
    fig = firing_plot(fp)
    assert all(ln.get_drawstyle() == "steps-post" for ln in _lines(fig))
    title = fig._suptitle.get_text()
    assert "(top)" in title and "checked to" in title
    assert np.ptp(fp.delta_r, axis=0).max() <= 1e-9 * np.abs(fp.delta_r).max()


def test_the_firing_title_fits_the_figure_even_with_two_columns():
    fp = circuit_firing("controllable", lqr_gains(augment(MuscleModel(), 1, 1)), count=2)
    fig = firing_plot(fp)
    fig.canvas.draw()
    box = fig._suptitle.get_window_extent()
    assert box.x0 >= 0 and box.x1 <= fig.bbox.width, (box, fig.bbox.width)
