"""Simulation: open/closed loop, every realization gives the same loop, nonlinear muscle, batch."""

from __future__ import annotations

import control
import matplotlib
import numpy as np
import pytest
import sympy as sp

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
from symctl.neural.batch import _CHUNK, _schur_stable, simulate_batch
from symctl.neural.nonlinear import nonlinear_check
from symctl.neural.simulate import (
    closed_loop_response,
    ifp_realization,
    open_loop_response,
    pulse,
    simulate_realization,
)
from symctl.realization.realization import controller_realization
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3

MODEL = MuscleModel()
GAINS = lqr_gains(augment(MODEL, 1, 1))
REF = closed_loop_response(GAINS)
FACT = factor(controller_tf(2))
K_VALUES = GAINS.substitutions()


def rel_err(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def paper_controllers(seed: int, count: int = 3) -> dict[str, list[Realization]]:
    """IFP and G3 G2 G1 with general, controllable and observable G2: random eps, C, P (seeded)."""
    gen = np.random.default_rng(seed)
    out: dict[str, list[Realization]] = {"IFP": [ifp_realization(GAINS)]}
    for kind in ("general", "controllable", "observable"):
        out[kind] = []
        for i in range(count):
            eps = [sp.Rational(int(gen.integers(-900, 901)), 1000) for _ in range(2)]
            cs = [sp.Integer(1), sp.Integer(1)] if i == 0 else [
                sp.Rational(int(gen.choice([-1, 1]) * gen.integers(200, 3000)), 1000)
                for _ in range(2)
            ]  # fmt: skip
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


def test_batch_equals_single_runs_for_lambdified_realizations():
    a, b = sp.symbols("a b")
    P = sp.Matrix([[1, a], [b, 2]])
    f = FACT.subs({**K_VALUES, epsilon_1: sp.Rational(1, 3), epsilon_3: -sp.Rational(1, 2)})
    f = f.subs({C_1: 1, C_3: 2})
    R = controller_realization(f, controllable_canonical(f.G2).similar(P))
    gen = np.random.default_rng(3)
    av, bv = gen.uniform(-1, 1, 40), gen.uniform(3, 4, 40)  # det P = 2 - a b != 0
    F, H, M, N = R.lambdify([a, b])(av, bv)
    out = simulate_batch(MODEL, F, H, M, N, states=True)
    assert out.delta_f.shape == (40, 50, 1) and out.states.shape == (40, 50, 4)
    for i in (0, 17, 39):
        one = simulate_realization(MODEL, R.subs({a: av[i], b: bv[i]}))
        np.testing.assert_allclose(out.states[i], one.states, rtol=1e-9, atol=1e-12)
        assert rel_err(out.delta_r[i], REF.delta_r) < 1e-9
    assert np.max(np.abs(out.states[0] - out.states[1])) > 1e-4


def test_batch_accepts_one_disturbance_per_realization():
    F, H, M, N = (
        np.zeros((2, 1, 1)),
        np.full((2, 1, 1), -0.05),
        np.ones((2, 1, 1)),
        np.zeros((2, 1, 1)),
    )
    w = np.stack([pulse(30, 1.0), pulse(30, 2.0)])
    out = simulate_batch(MODEL, F, H, M, N, w)
    np.testing.assert_allclose(out.delta_f[1], 2 * out.delta_f[0], rtol=1e-12)


def test_batch_across_chunk_boundaries_equals_single_loops():
    count = _CHUNK + 3
    gain = np.linspace(-0.02, -0.08, count).reshape(count, 1, 1)
    F, H, M, N = np.zeros((count, 1, 1)), gain, np.ones((count, 1, 1)), np.zeros((count, 1, 1))
    scale = np.linspace(0.5, 2.0, count)
    w = scale[:, None, None] * pulse(12, 1.0)[None]
    out = simulate_batch(MODEL, F, H, M, N, w, states=True)
    for i in (0, _CHUNK - 1, _CHUNK, count - 1):
        one = simulate_batch(
            MODEL, F[i : i + 1], H[i : i + 1], M[i : i + 1], N[i : i + 1], w[i][None]
        )
        np.testing.assert_allclose(out.delta_f[i], one.delta_f[0], rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(out.delta_r[i], one.delta_r[0], rtol=1e-12, atol=1e-15)


def test_schur_cohn_agrees_with_eigenvalues():
    gen = np.random.default_rng(7)
    A = gen.normal(size=(3000, 5, 5)) * gen.uniform(0.1, 0.8, size=(3000, 1, 1))
    radii = np.max(np.abs(np.linalg.eigvals(A)), axis=-1)
    clear = np.abs(radii - 1) > 1e-6
    assert 100 < np.sum(radii < 1) < 2900
    stable = _schur_stable(np.moveaxis(A, 0, -1))  # stacks are realization-last
    np.testing.assert_array_equal(stable[clear], (radii < 1)[clear])


def test_batch_refuses_an_unstable_loop_among_many():
    F = np.zeros((3000, 1, 1))
    H = np.full((3000, 1, 1), -0.05)
    H[1234] = -1.0
    with pytest.raises(ParameterError, match=r"unstable.*realization 1234 of 3000"):
        simulate_batch(MODEL, F, H, np.ones((3000, 1, 1)), np.zeros((3000, 1, 1)), steps=5)


# ---------------------------------------------------------------- nonlinear muscle
def test_nonlinear_check_departs_quadratically_and_integrates_accurately():
    chk = nonlinear_check(amplitudes=[1e-3, 1e-2, 1e-1, 1.0, 10.0], steps=40)
    assert np.all(np.diff(chk.max_deviation) > 0)
    ratio = chk.max_deviation[1:4] / chk.max_deviation[:3]
    np.testing.assert_allclose(ratio, 100, rtol=0.1)  # second order in the amplitude
    assert chk.relative_deviation[0] < 1e-4
    # the exact solution with r held constant: f_inf + (f - f_inf) exp(-Ts/tau)
    decay = np.exp(-MODEL.Ts / MODEL.tau)
    w = pulse(40)[:, 0]
    for i, amp in enumerate(chk.amplitudes):
        f_inf = MODEL.f_max / (1 + np.exp(-chk.r_nonlinear[i, :-1]))
        nxt = f_inf + (chk.f_nonlinear[i, :-1] - f_inf) * decay + amp * w[:-1]
        np.testing.assert_allclose(chk.f_nonlinear[i, 1:], nxt, rtol=1e-9)
    assert "relative" in chk.table()


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize("steps", [0, -3, 2.5, True])
def test_bad_horizon_is_refused(steps):
    with pytest.raises(ParameterError, match="steps"):
        open_loop_response(steps=steps)
    with pytest.raises(ParameterError, match="steps"):
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


def test_a_rate_that_overflows_while_the_state_stays_finite_is_refused():
    # delta_r = -1e10 delta_f overflows during the pulse; the stable loop (pole -0.5)
    # has decayed to finite rates again by the last step.
    plant = (np.array([[0.5]]), np.array([[1e-10]]))
    zero = np.zeros((1, 1, 1))
    with pytest.raises(ParameterError, match="blew up at step 6"):
        simulate_batch(plant, zero, zero, zero, np.full((1, 1, 1), -1e10), 1e300)
    N = np.zeros((_CHUNK + 1, 1, 1))
    N[-1] = -1e10  # only the last loop, in the second chunk
    zeros = np.zeros_like(N)
    with pytest.raises(ParameterError, match="blew up at step 6"):
        simulate_batch(plant, zeros, zeros, zeros, N, 1e300)


def test_a_run_whose_returned_values_are_finite_is_not_refused():
    # only the state after the horizon, which nobody sees, overflows
    plant = (np.array([[1e200]]), np.array([[1.0]]))
    zero = np.zeros((1, 1, 1))
    out = simulate_batch(plant, zero, zero, zero, zero, [1.0, 0.0, 0.0], check_stability=False)
    np.testing.assert_array_equal(out.delta_f[0, :, 0], [0.0, 1.0, 1e200])


def test_a_ragged_batch_disturbance_is_refused_by_name():
    with pytest.raises(SymctlTypeError, match="disturbance"):
        simulate_batch(MODEL, *(np.zeros((2, 1, 1)),) * 4, [[1.0], [1.0, 2.0]])


# ---------------------------------------------------------------- figures
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
        assert any(ax.get_legend() is not None for ax in fig.axes), name
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


def test_batch_response_arrays_read_only():
    F, H, M, N = (
        np.zeros((2, 1, 1)),
        np.full((2, 1, 1), -0.05),
        np.ones((2, 1, 1)),
        np.zeros((2, 1, 1)),
    )
    out = simulate_batch(MODEL, F, H, M, N, states=True)
    for arr in (out.t, out.delta_f, out.delta_r, out.states):
        assert not arr.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        out.delta_r[0, 0, 0] = 1.0
    assert F.flags.writeable


def test_nonlinear_check_arrays_read_only():
    chk = nonlinear_check(amplitudes=[0.1, 1.0], steps=12)
    for name in ("amplitudes", "t", "f_linear", "f_nonlinear", "r_nonlinear", "max_deviation"):
        assert not getattr(chk, name).flags.writeable, name
    with pytest.raises(ValueError, match="read-only"):
        chk.relative_deviation[0] = 0.0
