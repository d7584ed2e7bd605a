"""Simulation: open/closed loop, every realization gives the same loop, nonlinear muscle, batch."""

from __future__ import annotations

import control
import matplotlib
import numpy as np
import pytest
import sympy as sp
from helpers import rel_err

from symctl import (
    DimensionError,
    MuscleModel,
    ParameterError,
    Realization,
    SymctlTypeError,
    augment,
    controllable_canonical,
    controller_tf,
    factor,
    lqr_gains,
    observable_canonical,
    random_realization,
)
from symctl.neural.batch import simulate_batch
from symctl.neural.nonlinear import nonlinear_check
from symctl.neural.simulate import (
    closed_loop_response,
    ifp_realization,
    open_loop_response,
    simulate_realization,
)
from symctl.realization.realization import controller_realization
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3

MODEL = MuscleModel()
GAINS = lqr_gains(augment(MODEL, 1, 1))
REF = closed_loop_response(GAINS)
FACT = factor(controller_tf(2))
K_VALUES = GAINS.substitutions()


def paper_controllers(seed: int, count: int = 3) -> dict[str, list[Realization]]:
    """IFP and G3 G2 G1 with general, controllable and observable G2: random eps, C, P (seeded)."""
    gen = np.random.default_rng(seed)
    out: dict[str, list[Realization]] = {"IFP": [ifp_realization(GAINS)]}
    for kind in ("general", "controllable", "observable"):
        out[kind] = []
        for i in range(count):
            eps = [sp.Rational(int(gen.integers(-900, 901)), 1000) for _ in range(2)]
            cs = (
                [sp.Integer(1), sp.Integer(1)]
                if i == 0
                else [
                    sp.Rational(int(gen.choice([-1, 1]) * gen.integers(200, 3000)), 1000)
                    for _ in range(2)
                ]
            )
            values = {**K_VALUES, epsilon_1: eps[0], epsilon_3: eps[1], C_1: cs[0], C_3: cs[1]}
            f = FACT.subs(values)
            if kind == "general":
                R2 = random_realization(f.G2, rng=gen)
            elif kind == "controllable":
                R2 = controllable_canonical(f.G2)
            else:
                R2 = observable_canonical(f.G2)
            out[kind].append(controller_realization(f, R2))
    return out


# ---------------------------------------------------------------- open and closed loop
def test_open_loop_pulse_follows_the_discrete_plant():
    res = open_loop_response(pulse=2.0, start=3, length=4, steps=20)
    A, B = (float(v) for v in (MODEL.plant().A[0, 0], MODEL.plant().B[0, 0]))
    df = np.zeros(20)
    for k in range(19):
        df[k + 1] = A * df[k] + B * (2.0 if 3 <= k < 7 else 0.0)
    np.testing.assert_allclose(res.delta_f[:, 0], df, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(res.t, 0.01 * np.arange(20))
    np.testing.assert_allclose(res.f - res.delta_f, MODEL.f_bar)
    np.testing.assert_allclose(res.r - res.delta_r, MODEL.r_bar)
    assert res.states.shape == (20, 0)


def test_closed_loop_answers_after_the_delay_and_restores_the_force():
    start = 5
    first_force = np.flatnonzero(REF.delta_f[:, 0])[0]
    first_rate = np.flatnonzero(np.abs(REF.delta_r[:, 0]) > 0)[0]
    assert first_force == start + 1  # w(t) enters f(t + 1)
    assert first_rate == first_force + 2  # net delay T = 2
    assert np.all(REF.delta_r[first_rate : start + 10, 0] < 0)  # pushes back
    assert abs(REF.delta_f[-1, 0]) < 1e-12  # back to equilibrium after the pulse


def test_closed_loop_matches_python_control_forced_response():
    A, B = (float(v) for v in (MODEL.plant().A[0, 0], MODEL.plant().B[0, 0]))
    G = controller_tf(GAINS).to_control()
    plant_w = control.tf([1], [1, -A], 0.01)  # w -> delta_f with the loop open
    loop = control.feedback(plant_w, B * G, sign=1)  # 1/(z - A - B G)
    w = REF.w[:, 0]
    f_ctrl = control.forced_response(loop, T=REF.t, U=w).outputs
    r_ctrl = control.forced_response(control.series(loop, G), T=REF.t, U=w).outputs
    assert rel_err(REF.delta_f[:, 0], f_ctrl) < 1e-9
    assert rel_err(REF.delta_r[:, 0], r_ctrl) < 1e-9


def test_gains_with_a_plant_close_the_ifp_realization_around_it():
    other = MuscleModel(tau=0.03)
    res = closed_loop_response(GAINS, other)
    ref = simulate_realization(other, ifp_realization(GAINS))
    np.testing.assert_array_equal(res.delta_f, ref.delta_f)
    assert rel_err(res.delta_f, REF.delta_f) > 1e-3  # a different plant, a different loop


def test_ifp_realization_without_delay_is_the_static_gain():
    g = lqr_gains(augment(MODEL, 0, 0))
    R = ifp_realization(g)
    assert R.n == 0
    res, ref = closed_loop_response(g), closed_loop_response(R, MODEL)
    assert rel_err(res.delta_r, ref.delta_r) < 1e-12


# ---------------------------------------------------------------- every realization, same loop
@pytest.mark.parametrize("seed", [0, 1])
def test_every_realization_gives_the_optimal_loop_while_neurons_differ(seed):
    controllers = paper_controllers(seed)
    for kind, realizations in controllers.items():
        traces = []
        for R in realizations:
            res = simulate_realization(MODEL, R)
            assert rel_err(res.delta_f, REF.delta_f) < 1e-9, kind
            assert rel_err(res.delta_r, REF.delta_r) < 1e-9, kind
            np.testing.assert_allclose(res.r, REF.r, rtol=1e-12)
            assert res.states.shape == (50, R.n)
            traces.append(res.states)
        for a in range(len(traces)):
            for b in range(a + 1, len(traces)):
                assert np.max(np.abs(traces[a] - traces[b])) > 1e-4, kind
    g2_states = {k: simulate_realization(MODEL, v[0]).states for k, v in controllers.items()}
    assert np.max(np.abs(g2_states["controllable"] - g2_states["observable"])) > 1e-4


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    ("steps", "error"),
    [(0, ParameterError), (-3, ParameterError), (2.5, SymctlTypeError), (True, SymctlTypeError)],
)
def test_bad_horizon_is_refused(steps, error):
    with pytest.raises(error, match="steps"):
        open_loop_response(steps=steps)
    with pytest.raises(error, match="steps"):
        closed_loop_response(GAINS, steps=steps)


def test_bad_disturbance_is_refused():
    with pytest.raises(DimensionError, match=r"disturbance: expected shape \(steps, 1\)"):
        closed_loop_response(GAINS, disturbance=np.ones((10, 2)))
    with pytest.raises(DimensionError, match="disturbance"):
        closed_loop_response(GAINS, disturbance=[])
    with pytest.raises(ParameterError, match="disturbance: entries must be finite"):
        closed_loop_response(GAINS, disturbance=[0.0, np.nan])
    with pytest.raises(ParameterError, match="amplitude"):
        closed_loop_response(GAINS, disturbance=np.inf)
    with pytest.raises(SymctlTypeError, match="disturbance"):
        closed_loop_response(GAINS, disturbance="big")
    with pytest.raises(DimensionError, match="disturbance"):
        simulate_batch(MODEL, *(np.zeros((2, 1, 1)),) * 4, np.ones((3, 10, 1)))


def test_unstable_and_non_finite_controllers_are_refused():
    with pytest.raises(ParameterError, match="R: the closed loop is unstable, spectral radius"):
        simulate_realization(MODEL, Realization([[0]], [[-1]], [[1]], 0))
    with pytest.raises(ParameterError, match="finite"):
        Realization([[float("nan")]], [[1]], [[1]], 0)
    F = np.full((2, 1, 1), np.inf)
    with pytest.raises(ParameterError, match="F: entries must be finite"):
        simulate_batch(MODEL, F, *(np.zeros((2, 1, 1)),) * 3)
    with pytest.raises(DimensionError, match="H: expected shape"):
        simulate_batch(MODEL, np.zeros((2, 1, 1)), np.zeros((2, 2, 1)), *(np.zeros((2, 1, 1)),) * 2)
    with pytest.raises(DimensionError, match="R: the controller maps"):
        simulate_realization(MODEL, Realization([[0]], [[1, 1]], [[1]], [[0, 0]]))
    with pytest.raises(SymctlTypeError, match="controller"):
        closed_loop_response("G", MODEL)
    with pytest.raises(ParameterError, match="plant"):
        closed_loop_response(controller_tf(GAINS))


def test_a_run_that_blows_up_says_so():
    F, H, M, N = (
        np.zeros((1, 1, 1)),
        np.full((1, 1, 1), -2.0),
        np.ones((1, 1, 1)),
        np.zeros((1, 1, 1)),
    )
    with pytest.raises(ParameterError, match="blew up"):
        simulate_batch(MODEL, F, H, M, N, steps=2000, check_stability=False)
    with pytest.raises(ParameterError, match="blew up"):
        closed_loop_response(GAINS, disturbance=1e308)


# ---------------------------------------------------------------- figures
@pytest.mark.slow
def test_figures_have_units_and_legends(tmp_path):
    matplotlib.use("Agg")
    figs = {
        "open": open_loop_response().plot(),
        "closed": REF.plot(),
        "nonlinear": nonlinear_check(amplitudes=[1.0, 10.0], steps=30).plot(),
    }
    for name, fig in figs.items():
        labels = [ax.get_ylabel() for ax in fig.axes] + [ax.get_xlabel() for ax in fig.axes]
        assert any("[s]" in lab for lab in labels), name
        assert any("[N]" in lab for lab in labels), name
        keyed = any(ax.get_legend() is not None for ax in fig.axes) or fig.legends
        assert keyed or name == "open", name  # the open loop: one trace per panel, named above it
        fig.savefig(tmp_path / f"{name}.png")
    assert any("spikes/s" in ax.get_ylabel() for ax in figs["closed"].axes)


def test_an_open_loop_that_blows_up_names_the_pulse():
    unstable = (np.array([[1e200]]), np.array([[1.0]]))
    with pytest.raises(ParameterError, match=r"^pulse: the simulation blew up"):
        open_loop_response(unstable, pulse=1e200, steps=20)


def test_time_axis_is_in_steps_without_a_sampling_time():
    res = open_loop_response((np.array([[0.5]]), np.array([[1.0]])), steps=10)
    assert res.time_unit == "steps"
    assert res.plot().axes[1].get_xlabel() == "time [steps]"
    assert open_loop_response(MODEL, steps=10).time_unit == "s"


def test_response_arrays_read_only():
    owned = np.zeros((50, 1))
    res = simulate_realization(MODEL, Realization([[0]], [[-0.05]], [[1]], 0), owned + 1.0)
    for name in ("t", "delta_f", "delta_r", "w", "states", "f_bar", "r_bar"):
        arr = getattr(res, name)
        assert not arr.flags.writeable, name
        with pytest.raises(ValueError, match="read-only"):
            arr[...] = 0.0
    assert owned.flags.writeable  # the caller's array is copied, not frozen
