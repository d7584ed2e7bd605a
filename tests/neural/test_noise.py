"""Noise in the simulations: the Noise value, noisy loops, and the Monte Carlo against Lyapunov."""

from __future__ import annotations

import control
import numpy as np
import pytest
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import (
    DelayGraph,
    DiscretePlant,
    MuscleModel,
    Noise,
    Realization,
    augment,
    circuit_firing,
    closed_loop_response,
    controller_compatibility,
    controller_tf,
    ifp_realization,
    load_model,
    lqr_gains,
    monte_carlo,
    simulate_batch,
    simulate_realization,
    structure_firing,
)
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.neural.noise import _factor, _parts, _sensor_inputs
from symctl.neural.simulate import _loop

GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
FOREARM = load_model("examples/forearm.toml")
FOREARM_GAINS = lqr_gains(
    augment(FOREARM.plant, FOREARM.sensor_delay, FOREARM.actuator_delay, Q=FOREARM.Q, R=FOREARM.R)
)
FOREARM_NOISE = Noise(process=[1e-6, 1e-4], motor=1e-4, sensor=[1e-6, 1e-4])


def _stack(R: Realization, count: int) -> tuple[np.ndarray, ...]:
    return tuple(np.repeat(a[None], count, axis=0) for a in R.numeric())


def test_noise_parts_are_a_number_a_diagonal_or_a_covariance():
    mats = Noise(process=2.0, motor=[3.0], sensor=[[2.0, 1.0], [1.0, 2.0]]).matrices(2, 1)
    assert np.array_equal(mats["process"], 2 * np.eye(2))
    assert np.array_equal(mats["motor"], [[3.0]])
    assert np.array_equal(mats["sensor"], [[2.0, 1.0], [1.0, 2.0]])
    assert Noise(process=1.0) == Noise(process=1.0) != Noise(process=2.0)
    assert not Noise(process=1.0).process.flags.writeable


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"process": [[1.0, 2.0], [2.0, 1.0]]}, ParameterError, "process: must be positive semi"),
        ({"sensor": [[1.0, 0.5], [0.0, 1.0]]}, ParameterError, "sensor: must be symmetric"),
        ({"motor": [1.0, -1.0]}, ParameterError, "motor: variances must be >= 0"),
        ({"motor": [[1.0, 0.0]]}, DimensionError, "motor: a covariance must be square"),
        ({"process": np.zeros((2, 2, 2))}, DimensionError, "process: expected a number"),
        ({"process": np.zeros(1001)}, DimensionError, "process: .* at most 1000"),
        ({"signal_dependent": -0.1}, ParameterError, "signal_dependent: variances must be >= 0"),
        ({"signal_dependent": np.eye(2)}, DimensionError, "signal_dependent: expected a number"),
        ({"process": np.nan}, ParameterError, "process: entries must be finite"),
        ({"process": "1e-3"}, SymctlTypeError, "process"),
    ],
)
def test_bad_noise_is_refused_naming_its_argument(kwargs, error, match):
    with pytest.raises(error, match=match):
        Noise(**kwargs)


def test_noise_of_the_wrong_size_for_the_loop_is_refused_naming_the_part():
    with pytest.raises(DimensionError, match=r"noise.sensor: expected 2 entries"):
        closed_loop_response(FOREARM_GAINS, noise=Noise(sensor=[1.0, 1.0, 1.0]))
    with pytest.raises(DimensionError, match=r"noise.motor: expected 1 entries"):
        monte_carlo(FOREARM_GAINS, noise=Noise(motor=np.eye(2)), count=2, steps=4)
    with pytest.raises(SymctlTypeError, match=r"noise: expected a symctl\.Noise"):
        closed_loop_response(GAINS, noise={"process": 1.0})


@settings(max_examples=examples(20), deadline=None)
@given(
    st.sampled_from(["process", "motor", "sensor", "signal_dependent"]),
    st.sampled_from([0.0, [0.0], [[0.0]]]),
)
def test_zero_noise_equals_the_noise_free_run_exactly(part, zero):
    noise = Noise(**{part: zero}) if part != "signal_dependent" or zero != [[0.0]] else Noise()
    assert noise.is_zero
    assert closed_loop_response(GAINS, noise=noise, rng=3) == closed_loop_response(GAINS)
    F, H, M, N = _stack(ifp_realization(GAINS), 3)
    a = simulate_batch(MuscleModel(), F, H, M, N, noise=noise, keep=("delta_f", "peak_delta_r"))
    b = simulate_batch(MuscleModel(), F, H, M, N, keep=("delta_f", "peak_delta_r"))
    assert np.array_equal(a.delta_f, b.delta_f) and np.array_equal(
        a.peaks["delta_r"], b.peaks["delta_r"]
    )


def test_the_noisy_loop_without_noise_draws_follows_the_noise_free_loop():
    tiny = Noise(process=1e-300)  # drawn, but below every trace's rounding
    a = closed_loop_response(FOREARM_GAINS, noise=tiny, draws=2, steps=80)
    b = closed_loop_response(FOREARM_GAINS, steps=80)
    assert np.allclose(a.delta_f, b.delta_f, rtol=0, atol=1e-12 * np.abs(b.delta_f).max())
    assert np.allclose(a.delta_r, b.delta_r, rtol=0, atol=1e-12 * np.abs(b.delta_r).max())
    assert np.allclose(a.states, b.states, rtol=0, atol=1e-12 * np.abs(b.states).max())


def test_a_noisy_response_is_the_mean_and_spread_of_its_draws_seeded_by_rng():
    noise = Noise(process=1e-3, sensor=1e-4)
    a = closed_loop_response(GAINS, noise=noise, draws=50, rng=4)
    assert a == closed_loop_response(GAINS, noise=noise, draws=50, rng=np.random.default_rng(4))
    assert a != closed_loop_response(GAINS, noise=noise, draws=50, rng=5)
    assert a.draws == 50 and a.delta_f_sd.shape == a.delta_f.shape
    assert a.states_sd.shape == a.states.shape and np.all(a.delta_r_sd[3:] > 0)
    # the plant around the IFP realization and the augmented loop: the same noisy behaviour
    b = closed_loop_response(GAINS, MuscleModel(), noise=noise, draws=50, rng=4)
    assert np.allclose(a.delta_f, b.delta_f, atol=1e-10) and np.allclose(a.delta_r, b.delta_r)


def test_simulate_batch_with_noise_keeps_traces_peaks_and_chunks_consistent():
    F, H, M, N = _stack(ifp_realization(GAINS), 5)
    noise = Noise(process=1e-2, motor=1e-2, sensor=1e-4)
    out = simulate_batch(
        MuscleModel(), F, H, M, N, noise=noise, rng=1, keep=("delta_f", "delta_r", "peak_delta_r")
    )
    assert np.array_equal(out.peaks["delta_r"], np.abs(out.delta_r).max(axis=1))
    assert len({float(out.delta_f[i, -1, 0]) for i in range(5)}) == 5  # each loop its own draws
    parts = list(simulate_batch(MuscleModel(), F, H, M, N, noise=noise, rng=1, chunk=2))
    assert [p.first for p in parts] == [0, 2, 4] and parts[0].delta_f.shape == (2, 50, 1)


def test_a_noisy_batch_equals_python_control_forced_response_on_the_same_draws():
    """The loops of simulate_batch and control.forced_response of the closed loop, driven by the
    documented draws (per step, normals (k, loops): process and motor as one state noise, then
    sensor), agree to 1e-9."""
    count, steps = 3, 40
    R = ifp_realization(FOREARM_GAINS)
    p = FOREARM.plant
    out = simulate_batch(p, *_stack(R, count), 0.0, steps=steps, noise=FOREARM_NOISE, rng=9)
    _, Acl, Cr, _, _ = _loop(FOREARM_GAINS, p)
    Acl, Cr = Acl[:, :, 0], Cr[:, :, 0]
    A, B = (np.asarray(M, dtype=float) for M in p.numeric())
    n, m = p.n, p.m
    Ev, Dv = _sensor_inputs(Acl, Cr, A, n)
    parts = _parts(FOREARM_NOISE, n, m)
    P, BM = parts["process"], B @ parts["motor"]
    # process and motor noise drawn as one state noise of covariance W + B W_u B^T
    S = P @ P.T + BM @ BM.T
    lam, U = np.linalg.eigh(S)
    root = U * np.sqrt(np.clip(lam, 0, None))
    z = np.random.default_rng(9).standard_normal((steps, n + n, count))
    E = np.zeros((Acl.shape[0], n + n))
    E[:n, :n], E[:, n:] = np.eye(n), Ev
    D = np.zeros((n + m, n + n))
    D[n:, n:] = Dv
    C = np.vstack([np.eye(n, Acl.shape[0]), Cr])
    loop = control.ss(Acl, E, C, D, float(p.dt))
    for r in range(count):
        noise = np.vstack([root @ z[:, :n, r].T, parts["sensor"] @ z[:, n:, r].T])
        y = control.forced_response(loop, U=noise).outputs
        assert np.allclose(out.delta_f[r], y[:n].T, rtol=0, atol=1e-9 * np.abs(y[:n]).max())
        assert np.allclose(out.delta_r[r], y[n:].T, rtol=0, atol=1e-9 * np.abs(y[n:]).max())


def test_the_draws_are_the_same_in_blocks_or_at_once():
    a = np.random.default_rng(2).standard_normal((200, 3, 7))
    gen = np.random.default_rng(2)
    b = np.concatenate([gen.standard_normal((k, 3, 7)) for k in (64, 64, 64, 8)])
    assert np.array_equal(a, b)


def test_a_covariance_factor_squares_to_the_covariance():
    cov = np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 0.0]])
    L = _factor(cov)
    assert np.allclose(L @ L.T, cov, atol=1e-14)
    assert np.array_equal(_factor(np.diag([4.0, 9.0])), np.diag([2.0, 3.0]))


SCALAR = DiscretePlant([[0.5]], [[1]], dt=0.01)


def _gain(k: float) -> Realization:
    """The static controller u = -k x."""
    return Realization([[0]], [[0]], [[0]], [[-k]], dt=0.01)


@settings(max_examples=examples(25), deadline=None)
@given(st.floats(-0.95, 0.95), st.floats(1e-3, 10.0), st.floats(0.0, 0.4), st.floats(0.0, 0.5))
def test_the_predicted_variance_of_a_scalar_ar1_loop_is_its_closed_form(a, q, k, sigma):
    """x(t+1) = a x + u (1 + sigma eps) + p, u = -k x: P = q / (1 - (a - k)^2 - sigma^2 k^2)."""
    plant = DiscretePlant([[a]], [[1]], dt=0.01)
    if abs(a - k) >= 0.99 or (a - k) ** 2 + (sigma * k) ** 2 >= 0.98:
        return
    mc = monte_carlo(
        _gain(k),
        plant,
        noise=Noise(process=q, signal_dependent=sigma),
        count=2,
        steps=3,
        burn_in=0,
        Q=1.0,
        R=2.0,
    )
    P = q / (1 - (a - k) ** 2 - (sigma * k) ** 2)
    assert mc.predicted_covariance[0, 0] == pytest.approx(P, rel=1e-9)
    assert mc.predicted_cost == pytest.approx(P + 2 * k * k * P, rel=1e-9)
    assert mc.additive_covariance[0, 0] == pytest.approx(q / (1 - (a - k) ** 2), rel=1e-9)


def test_the_measured_variance_of_a_scalar_ar1_loop_matches_within_its_standard_error():
    mc = monte_carlo(_gain(0.2), SCALAR, noise=Noise(process=1.0), count=5000, steps=200, rng=0)
    assert mc.predicted_covariance[0, 0] == pytest.approx(1 / (1 - 0.09))
    assert mc.z_score < 4


def test_the_forearm_monte_carlo_matches_the_lyapunov_covariance_and_cost():
    mc = monte_carlo(FOREARM_GAINS, noise=FOREARM_NOISE, count=10_000, steps=500, rng=0)
    assert mc.covariance.shape == (2, 2) and mc.count == 10_000 and mc.burn_in > 0
    assert mc.z_score < 4.5  # seeded: 1.3 standard errors at the largest
    assert np.all(mc.covariance_se < 0.01 * np.abs(np.diag(mc.covariance)).max())
    assert "cost per step" in mc.table()


def test_signal_dependent_noise_raises_the_variance_as_predicted():
    noise = Noise(process=[1e-6, 1e-4], signal_dependent=0.5)
    mc = monte_carlo(FOREARM_GAINS, noise=noise, count=4000, steps=400, rng=1)
    assert mc.z_score < 4.5
    assert np.all(np.diag(mc.predicted_covariance) > np.diag(mc.additive_covariance))
    assert mc.predicted_cost > mc.additive_cost
    assert mc.covariance[1, 1] - 4 * mc.covariance_se[1, 1] > mc.additive_covariance[1, 1]


def test_a_loop_unstable_in_mean_square_is_refused():
    with pytest.raises(ParameterError, match="signal_dependent: the loop is not stable in mean"):
        monte_carlo(_gain(0.9), SCALAR, noise=Noise(process=1.0, signal_dependent=2.0), count=2)


def test_monte_carlo_refuses_bad_arguments():
    with pytest.raises(ParameterError, match="noise: all zero"):
        monte_carlo(GAINS, noise=Noise(process=0.0))
    with pytest.raises(ParameterError, match="count"):
        monte_carlo(GAINS, noise=Noise(process=1.0), count=1)
    with pytest.raises(ParameterError, match="burn_in: must be below steps = 10"):
        monte_carlo(GAINS, noise=Noise(process=1.0), steps=10, burn_in=10)
    with pytest.raises(ParameterError, match="plant: needed"):
        monte_carlo(_gain(0.1), noise=Noise(process=1.0))


def test_simulate_realization_takes_noise_like_closed_loop_response():
    R = _gain(0.2)
    a = simulate_realization(SCALAR, R, noise=Noise(process=1.0), draws=300, rng=1)
    # far from the pulse the spread is the stationary standard deviation
    assert a.delta_f_sd[-1, 0] == pytest.approx((1 / (1 - 0.09)) ** 0.5, rel=0.15)


def test_noisy_firing_keeps_the_realizations_and_their_equal_behaviour():
    noise = Noise(process=1e-2, motor=1e-3, sensor=1e-4, signal_dependent=0.1)
    fp = circuit_firing("general", GAINS, count=3, rng=1, noise=noise, noise_draws=40)
    quiet = circuit_firing("general", GAINS, count=3, rng=1)
    assert fp.params == quiet.params  # the noise is drawn apart from the realizations
    assert fp.max_deviation < 1e-9 and fp.draws == 40 == fp.reference.draws
    assert set(fp.firing_sd) == set(fp.firing) and fp.firing_sd["G2.x1"].shape == (3, 50)
    assert np.ptp(fp.delta_r_sd, axis=0).max() < 1e-9 and fp.delta_r_sd[:, 10:].min() > 0
    assert np.allclose(fp.delta_r[0], fp.reference.delta_r[:, 0], atol=1e-12)
    assert fp == circuit_firing("general", GAINS, count=3, rng=1, noise=noise, noise_draws=40)
    ifp = circuit_firing("ifp", GAINS, noise=noise, noise_draws=5)
    assert ifp.firing_sd.keys() == ifp.firing.keys() and ifp.max_deviation < 1e-9


def test_noisy_structure_firing_checks_every_draw_against_the_optimal_loop():
    G = controller_tf(GAINS.system).subs(GAINS.substitutions(exact=True))
    r = controller_compatibility(G, DelayGraph.chain([2]))
    fp = structure_firing(r.structure, GAINS, count=2, noise=Noise(sensor=1e-3), noise_draws=8)
    assert fp.max_deviation < 1e-9 and fp.firing_sd is not None


def test_a_noisy_run_that_overflows_is_refused():
    one = np.ones((1, 1, 1))
    with pytest.raises(ParameterError, match="noise: the simulation blew up"):
        simulate_batch(
            MuscleModel(),
            0 * one,
            one,
            one,
            one,
            steps=500,
            check_stability=False,
            noise=Noise(process=1.0),
        )


def test_the_prediction_is_the_same_for_the_augmented_loop_and_its_realization():
    """The plant's covariance depends on the controller's transfer function only."""
    noise = Noise(process=[1e-6, 1e-4], motor=1e-4, sensor=[1e-6, 1e-4], signal_dependent=0.3)
    a = monte_carlo(FOREARM_GAINS, noise=noise, count=2, steps=3)
    b = monte_carlo(FOREARM_GAINS, FOREARM.plant, noise=noise, count=2, steps=3)
    assert np.allclose(a.predicted_covariance, b.predicted_covariance, rtol=1e-8, atol=0)
    assert a.predicted_cost == pytest.approx(b.predicted_cost, rel=1e-8)


@settings(max_examples=examples(15), deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_the_predicted_covariance_solves_python_controls_lyapunov_equation(seed):
    gen = np.random.default_rng(seed)
    A = gen.normal(size=(2, 2))
    A *= 0.9 / max(abs(np.linalg.eigvals(A)))  # stable
    W = gen.normal(size=(2, 2))
    W = W @ W.T
    mc = monte_carlo(
        Realization([[0]], [[0, 0]], [[0]], [[0, 0]], dt=1),
        DiscretePlant(A, [[1], [0]], dt=1),
        noise=Noise(process=W),
        count=2,
        steps=3,
    )
    assert np.allclose(mc.predicted_covariance, control.dlyap(A, W), rtol=1e-9, atol=1e-12)
