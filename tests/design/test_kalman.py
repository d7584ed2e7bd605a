"""Delayed Kalman filter and LQG compensator: third-party gains, separation, proof, limits, errors."""

from __future__ import annotations

import control
import numpy as np
import pytest
import scipy.linalg
import sympy as sp
from helpers import examples, random_plant
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import DimensionError, MuscleModel, ParameterError, SymctlTypeError, augment, lqr_gains
from symctl.design.kalman import KalmanGains, kalman_gains, lqg_state_space, lqg_tf, prove_lqg_tf
from symctl.symbols import observer_gain_symbols

DOUBLE_INTEGRATOR = (np.array([[1.0, 0.1], [0.0, 1.0]]), np.array([[0.005], [0.1]]))


def _floats(M) -> np.ndarray:
    return np.array(sp.Matrix(M).evalf(), dtype=float)


def _design(plant, ds, da, C, W, V):
    s = augment(plant, ds, da)
    return s, lqr_gains(s), kalman_gains(s, C=C, W=W, V=V)


def _loop(s, g, kf):
    """Plant and compensator in closed loop, with the compensator's (F, H, M)."""
    A, B, C = _floats(s.plant.A), _floats(s.plant.B), _floats(kf.C)
    F, H, M, _ = lqg_state_space(_floats(s.A), _floats(s.B), C, g.K, kf.L[: s.n], s.n, s.m, s.T)
    return np.block([[A, B @ M], [H @ C, F]]), (F, H, M)


def _at(G, F, H, M, points, N=0.0):
    """``max |G(z) - M (zI - F)^-1 H - N|`` over ``points``."""
    f = G.lambdify()
    return max(
        float(
            np.max(np.abs(np.atleast_2d(f(p)) - M @ np.linalg.solve(p * np.eye(len(F)) - F, H) - N))
        )
        for p in points
    )


POINTS = (1.3 + 0.4j, -0.7 + 1.1j, 2.0, 0.3 - 1.7j)


def test_kalman_gain_is_dlqe_and_the_dual_dare_with_a_zero_chain():
    s, _, kf = _design(DOUBLE_INTEGRATOR, 2, 1, [[1, 0]], np.diag([1e-3, 1e-2]), 0.04)
    L, P, _ = control.dlqe(DOUBLE_INTEGRATOR[0], np.eye(2), [[1, 0]], np.diag([1e-3, 1e-2]), 0.04)
    np.testing.assert_allclose(kf.L[:2], L, rtol=1e-9)
    np.testing.assert_allclose(kf.P[:2, :2], P, rtol=1e-9)
    assert np.all(kf.L[2:] == 0) and np.max(np.abs(kf.P[2:, :])) < 1e-12
    A, Ct = _floats(s.A), np.hstack([[[1.0, 0.0]], np.zeros((1, 3))])
    Wt = np.zeros((5, 5))
    Wt[:2, :2] = np.diag([1e-3, 1e-2])
    Pd = scipy.linalg.solve_discrete_are(A.T, Ct.T, Wt, [[0.04]])
    np.testing.assert_allclose(kf.L, A @ Pd @ Ct.T / (Ct @ Pd @ Ct.T + 0.04), atol=1e-12)


def test_motor_noise_adds_B_Wu_B_transposed_to_the_process_noise():
    s = augment(DOUBLE_INTEGRATOR, 1, 1)
    B = DOUBLE_INTEGRATOR[1]
    a = kalman_gains(s, [[1, 0]], W=np.eye(2) * 1e-3, V=1, motor=[[2.0]])
    b = kalman_gains(s, [[1, 0]], W=np.eye(2) * 1e-3 + 2.0 * B @ B.T, V=1)
    assert a == b and hash(a) == hash(b) and isinstance(a, KalmanGains)


def test_closed_loop_poles_are_the_regulators_and_the_filters():
    s, g, kf = _design(MuscleModel(), 2, 2, [[1]], 0.3, 0.1)
    cl, _ = _loop(s, g, kf)
    A, C = _floats(s.plant.A), _floats(kf.C)
    expected = np.concatenate([g.poles, np.linalg.eigvals(A - kf.L[:1] @ C)])
    np.testing.assert_allclose(np.poly(cl), np.poly(expected), atol=1e-10)


def test_symbolic_compensator_is_proved_with_relative_degree_above_T():
    for ds, da in ((0, 0), (1, 0), (1, 1), (2, 3)):
        s = augment(DOUBLE_INTEGRATOR, ds, da)
        G = lqg_tf(s, [[1, 0]])
        assert G.order == 2 + s.T and G.relative_degree >= s.T + 1
        assert set(observer_gain_symbols(2, 1)) <= G.free_symbols
        assert prove_lqg_tf(s, [[1, 0]], G)


def test_proof_refuses_a_wrong_compensator_with_evidence():
    s = augment(DOUBLE_INTEGRATOR, 1, 1)
    G = lqg_tf(s, [[1, 0]])
    wrong = G.subs(observer_gain_symbols(2, 1)[0], 0)
    proof = prove_lqg_tf(s, [[1, 0]], wrong)
    assert not proof and proof.evidence
    assert not prove_lqg_tf(s, [[1, 0], [0, 1]], G)  # shapes


def test_numeric_compensator_is_the_state_space_of_the_loop():
    s, g, kf = _design(DOUBLE_INTEGRATOR, 2, 1, [[1, 0]], np.eye(2) * 1e-2, 0.05)
    G = lqg_tf(s, gains=g, kalman=kf)
    assert not G.free_symbols and G.relative_degree == s.T + 1
    _, (F, H, M) = _loop(s, g, kf)
    assert _at(G, F, H, M, POINTS) < 1e-9


def test_two_inputs_two_outputs_compensator_is_a_proved_fraction():
    A = np.array([[0.9, 0.2], [0.0, 1.1]])
    B = np.array([[1.0, 0.0], [0.5, 1.0]])
    s = augment((A, B), 1, 0)
    C = [[1, 0], [0, 1]]
    G = lqg_tf(s, C)
    assert G.shape == (2, 2) and prove_lqg_tf(s, C, G)
    g, kf = lqr_gains(s), kalman_gains(s, C, W=np.eye(2), V=np.eye(2))
    _, (F, H, M) = _loop(s, g, kf)
    assert _at(lqg_tf(s, C, g, kf), F, H, M, POINTS) < 1e-8


def test_noise_free_full_sensor_gives_the_full_state_controller_on_the_one_step_prediction():
    """C = I, V -> 0: L -> A and G -> (I - z^-1 G0 B)^-1 z^-1 G0 A, G0 the full-state G."""
    from symctl import controller_tf

    A, B = DOUBLE_INTEGRATOR
    s = augment(DOUBLE_INTEGRATOR, 1, 2)
    g = lqr_gains(s)
    G0 = controller_tf(g).lambdify()
    for V, tol in ((1e-4, 2e-2), (1e-8, 2e-6)):
        kf = kalman_gains(s, np.eye(2), W=np.eye(2), V=np.eye(2) * V)
        assert np.max(np.abs(kf.L[:2] - A)) < tol
        G = lqg_tf(s, gains=g, kalman=kf).lambdify()
        for p in POINTS:
            g0 = np.atleast_2d(G0(p))
            limit = np.linalg.solve(np.eye(1) - g0 @ B / p, g0 @ A / p)
            assert np.max(np.abs(np.atleast_2d(G(p)) - limit)) < 50 * tol


def test_tiny_process_noise_on_a_stable_plant_turns_the_sensor_off():
    s = augment(MuscleModel(), 1, 1)
    kf = kalman_gains(s, [[1]], W=1e-12, V=1)
    assert abs(kf.L[0, 0]) < 1e-10
    G = lqg_tf(s, gains=lqr_gains(s), kalman=kf)
    assert max(abs(float(c)) for c in G.num_coeffs()) < 1e-10


@settings(max_examples=examples(15), deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 3),
    p=st.integers(1, 2),
    ds=st.integers(0, 2),
    da=st.integers(0, 2),
)
def test_random_plants_gain_separation_and_transfer_function(seed, n, p, ds, da):
    rng = np.random.default_rng(seed)
    A, B = random_plant(rng, n, 1)
    C = rng.normal(size=(min(p, n), n))
    s = augment((A, B), ds, da)
    W, V = np.eye(n) * 0.1, np.eye(len(C)) * 0.2
    g, kf = lqr_gains(s), kalman_gains(s, C, W, V)
    L, _, _ = control.dlqe(A, np.eye(n), C, W, V)
    np.testing.assert_allclose(kf.L[:n], L, rtol=1e-6, atol=1e-9)
    cl, (F, H, M) = _loop(s, g, kf)
    poles = np.concatenate([g.poles, np.linalg.eigvals(A - kf.L[:n] @ C)])
    assert np.max(np.abs(cl)) < 1e6
    np.testing.assert_allclose(np.poly(cl), np.poly(poles), atol=1e-7)
    G = lqg_tf(s, C, g, kf)
    assert G.relative_degree >= s.T + 1
    scale = max(1.0, float(np.max(np.abs(g.K))))
    assert _at(G, F, H, M, POINTS) < 1e-6 * scale
    Fc, Hc, Mc, Nc = lqg_state_space(
        _floats(s.A), _floats(s.B), C, g.K, kf.M[:n], n, 1, s.T, "current"
    )
    assert _at(lqg_tf(s, C, g, kf, form="current"), Fc, Hc, Mc, POINTS, Nc) < 1e-6 * scale


@pytest.mark.parametrize(
    ("kwargs", "error", "argname"),
    [
        ({"W": [[1, 0.5], [0, 1]]}, ParameterError, "W: must be symmetric"),
        ({"W": [[1, 0], [0, -1]]}, ParameterError, "W: must be positive semidefinite"),
        ({"V": [[0.0]]}, ParameterError, "V: singular"),
        ({"V": [[-1.0]]}, ParameterError, "V: must be positive semidefinite"),
        ({"C": [[0, 1]]}, ParameterError, "C: the outputs leave the plant undetectable"),
        ({"C": [[1, 0, 0]]}, DimensionError, "C: expected p x 2"),
        ({"W": np.eye(3)}, DimensionError, "W: expected shape (2, 2)"),
        ({"V": np.eye(2)}, DimensionError, "V: expected shape (1, 1)"),
        ({"motor": [[1, 2], [2, 1]]}, DimensionError, "motor: expected shape (1, 1)"),
        ({"W": [[sp.Symbol("w"), 0], [0, 1]]}, ParameterError, "W: needs numbers"),
    ],
)
def test_bad_input_names_the_argument(kwargs, error, argname):
    with pytest.raises(error, match=argname.replace("(", r"\(").replace(")", r"\)")):
        kalman_gains(augment(DOUBLE_INTEGRATOR, 1, 1), **{"C": [[1, 0]], **kwargs})


def test_wrong_types_and_foreign_designs_are_refused():
    s = augment(DOUBLE_INTEGRATOR, 1, 1)
    with pytest.raises(SymctlTypeError, match="system"):
        kalman_gains(DOUBLE_INTEGRATOR)
    with pytest.raises(SymctlTypeError, match="gains"):
        lqg_tf(s, [[1, 0]], gains="K")
    other = kalman_gains(augment(DOUBLE_INTEGRATOR, 2, 1), [[1, 0]])
    with pytest.raises(ParameterError, match="kalman: designed for another system"):
        lqg_tf(s, kalman=other)
    with pytest.raises(ParameterError, match="C: the filter measures"):
        lqg_tf(s, [[1, 1]], kalman=kalman_gains(s, [[1, 0]]))


def test_an_unexcited_marginal_mode_names_W():
    A, B = np.array([[1.0, 0.0], [0.0, 0.5]]), np.array([[1.0], [1.0]])
    with pytest.raises(ParameterError, match="W: "):
        kalman_gains(augment((A, B), 1, 0), [[1, 1]], W=np.diag([0.0, 1.0]))


def test_symbolic_plant_keeps_its_symbols_in_the_compensator():
    a = sp.Symbol("a", real=True)
    G = lqg_tf(augment(([[a]], [[1]]), 1, 0), [[1]])
    assert a in G.free_symbols and G.order == 2
    assert prove_lqg_tf(augment(([[a]], [[1]]), 1, 0), [[1]], G)


def test_current_form_is_proved_with_relative_degree_T_and_its_gain_is_the_innovation_gain():
    for ds, da in ((0, 0), (1, 0), (2, 1)):
        s = augment(DOUBLE_INTEGRATOR, ds, da)
        G = lqg_tf(s, [[1, 0]], form="current")
        assert G.relative_degree == s.T and G.order == 2 + s.T
        assert prove_lqg_tf(s, [[1, 0]], G, form="current")
        assert not prove_lqg_tf(s, [[1, 0]], G)  # the predictor's symbols are others
    s, g, kf = _design(DOUBLE_INTEGRATOR, 1, 1, [[1, 0]], np.eye(2) * 1e-2, 0.05)
    np.testing.assert_allclose(kf.L, _floats(s.A) @ kf.M, atol=1e-12)
    C = np.array([[1.0, 0.0]])
    F, H, M, _ = lqg_state_space(_floats(s.A), _floats(s.B), C, g.K, kf.M[:2], 2, 1, 2, "current")
    assert _at(lqg_tf(s, gains=g, kalman=kf, form="current"), F, H, M, POINTS) < 1e-9


def test_noise_free_full_sensor_current_form_is_the_full_state_controller():
    """C = I, V -> 0 in the current form: M -> I and G -> the full-state G, with an error of order V."""
    from symctl import controller_tf

    s = augment(DOUBLE_INTEGRATOR, 1, 2)
    g = lqr_gains(s)
    G0 = controller_tf(g).lambdify()
    for V in (1e-4, 1e-8):
        kf = kalman_gains(s, np.eye(2), W=np.eye(2), V=np.eye(2) * V)
        G = lqg_tf(s, gains=g, kalman=kf, form="current").lambdify()
        gap = max(float(np.max(np.abs(np.atleast_2d(G(p)) - G0(p)))) for p in POINTS)
        assert gap < 10 * V


def test_an_unknown_form_names_form():
    with pytest.raises(ParameterError, match="form: expected 'predictor' or 'current'"):
        lqg_tf(augment(DOUBLE_INTEGRATOR, 1, 1), [[1, 0]], form="filter")


def test_the_compensator_is_proved_at_the_designs_exact_gains_and_refuses_half_a_design():
    from symctl import MuscleModel, augment, kalman_gains, lqr_gains
    from symctl.design.kalman import lqg_tf, prove_lqg_tf
    from symctl.errors import SymctlTypeError

    s = augment(MuscleModel(), 2, 1)
    gains, kf = lqr_gains(s), kalman_gains(s, C=[[1]], W=1, V=1)
    exact = {**gains.substitutions(exact=True), **kf.substitutions(exact=True)}
    G = lqg_tf(s, [[1]]).subs(exact)
    assert not G.free_symbols
    assert prove_lqg_tf(s, [[1]], G, gains=gains, kalman=kf)
    assert prove_lqg_tf(s, [[1]], gains=gains, kalman=kf)  # the symbolic one, evaluated
    assert not prove_lqg_tf(s, [[1]], G * (1 + sp.Rational(1, 10**12)), gains=gains, kalman=kf)
    assert not prove_lqg_tf(s, [[1]], G)  # numbers are not the symbolic compensator
    with pytest.raises(SymctlTypeError, match="kalman"):
        prove_lqg_tf(s, [[1]], G, gains=gains)
