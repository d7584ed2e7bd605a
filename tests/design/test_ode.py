"""ODEModel: any nonlinear plant, its equilibrium, its exact linearization and ZOH, the nonlinear loop."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.signal
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import (
    MuscleModel,
    ODEModel,
    ParameterError,
    SymctlTypeError,
    augment,
    lqr_gains,
    nonlinear_check,
)
from symctl.design.ode import solve_equilibrium
from symctl.model.units import parse_unit

x, v, u = sp.symbols("x v u", real=True)
k, c = sp.symbols("k c", positive=True)


def test_the_muscle_as_an_ode_model_gives_the_muscle_models_exact_plant():
    m = ODEModel.from_muscle(MuscleModel())
    ref = MuscleModel().plant()
    assert sp.simplify(m.plant().A[0, 0] - ref.A[0, 0]) == 0
    assert sp.simplify(m.plant().B[0, 0] - ref.B[0, 0]) == 0
    assert float(m.x_bar[0]) == pytest.approx(MuscleModel().f_bar, rel=1e-15)


def test_an_affine_equilibrium_is_solved_symbolically_and_proved_unique():
    rhs = sp.Matrix([v, -k * x - c * v + u])
    xe, how = solve_equilibrium(rhs, [x, v], [u], sp.Matrix([3]), {k: 2, c: 1})
    assert how.startswith("exact")
    assert list(xe) == [3 / k, 0]
    assert rhs.subs({x: xe[0], v: xe[1], u: 3}).applyfunc(sp.simplify) == sp.zeros(2, 1)


def test_a_polynomial_equilibrium_of_one_state_is_decided_exactly():
    xe, how = solve_equilibrium(sp.Matrix([-(x**3) - x + u]), [x], [u], sp.Matrix([2]), {})
    assert list(xe) == [1] and how.startswith("exact")
    with pytest.raises(ParameterError, match=r"several equilibria .* exact"):
        solve_equilibrium(sp.Matrix([-((x - 1) ** 2) * (x + 2) ** 2]), [x], [u], [0], {})
    with pytest.raises(ParameterError, match=r"no equilibrium: .* no real root"):
        solve_equilibrium(sp.Matrix([x**2 + 1 + u]), [x], [u], [0], {})
    xe, how = solve_equilibrium(sp.Matrix([-(x**3) + u]), [x], [u], sp.Matrix([2]), {})
    assert float(xe[0]) == pytest.approx(2 ** (1 / 3), rel=1e-15) and "double precision" in how


def test_a_singular_affine_system_is_refused():
    with pytest.raises(ParameterError, match="not unique"):
        solve_equilibrium(sp.Matrix([u - x + x]), [x], [u], sp.Matrix([0]), {})


def test_solve_equilibrium_never_evaluates_text():
    with pytest.raises(Exception) as info:
        solve_equilibrium(["__import__('os').getcwd()"], [x], [u], [0], {})
    assert "not allowed" in str(info.value)
    with pytest.raises(SymctlTypeError):
        ODEModel([x], [u], ["-x + u"], {}, dt=0.1)


def test_the_linearization_is_the_jacobian_and_matches_finite_differences():
    g = sp.Symbol("g", positive=True)
    m = ODEModel([x, v], [u], [v, g * sp.sin(x) - v + sp.tanh(u)], {g: 9.81}, [0, 0], dt=0.01)
    a, b = m.linearize_symbolic()
    an = np.array(a.subs(m.values).evalf(), dtype=float)
    bn = np.array(b.subs(m.values).evalf(), dtype=float)
    h = 1e-6
    x0, u0 = np.zeros((2, 1)), np.zeros((1, 1))
    fd_a = np.column_stack(
        [
            (m.rhs_numeric(x0 + h * e[:, None], u0) - m.rhs_numeric(x0 - h * e[:, None], u0))[:, 0]
            / (2 * h)
            for e in np.eye(2)
        ]
    )
    fd_b = (m.rhs_numeric(x0, u0 + h) - m.rhs_numeric(x0, u0 - h))[:, :1] / (2 * h)
    np.testing.assert_allclose(an, fd_a, atol=1e-8)
    np.testing.assert_allclose(bn, fd_b, atol=1e-8)


@pytest.mark.slow
@settings(max_examples=examples(25), deadline=None)
@given(
    st.floats(0.1, 5.0),
    st.floats(0.05, 3.0),
    st.floats(-2.0, 2.0),
    st.floats(0.001, 0.2),
)
def test_the_zero_order_hold_matches_scipy_cont2discrete(kv, cv, ue, ts):
    m = ODEModel([x, v], [u], [v, -k * x - c * v + u], {k: kv, c: cv}, u_eq=[ue], dt=ts)
    a, b = m.linearize_symbolic()
    an = np.array(a.subs(m.values).evalf(), dtype=float)
    bn = np.array(b.subs(m.values).evalf(), dtype=float)
    Ad, Bd, *_ = scipy.signal.cont2discrete((an, bn, np.eye(2), np.zeros((2, 1))), ts, "zoh")
    A, B = m.plant().numeric()
    np.testing.assert_allclose(A, Ad, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(B, Bd, rtol=1e-10, atol=1e-12)


@settings(max_examples=examples(25), deadline=None)
@given(st.floats(0.2, 5.0), st.floats(-3.0, 3.0))
def test_the_one_state_closed_form_is_exact_at_the_values(kv, ue):
    m = ODEModel([x], [u], [-k * x + u], {k: kv}, u_eq=[ue], dt=0.05)
    sym = m.discrete_symbolic()
    assert sym is not None and sym.A[0, 0] == sp.exp(-sp.Symbol("T_s", positive=True) * k)
    A, B = m.plant().numeric()
    assert A[0, 0] == pytest.approx(np.exp(-kv * 0.05), rel=1e-14)
    assert B[0, 0] == pytest.approx((1 - np.exp(-kv * 0.05)) / kv, rel=1e-12)


def test_a_numeric_equilibrium_discretizes_in_numbers_without_hanging():
    m = ODEModel([x], [u], [-(x**2) + u], {}, u_eq=[1], dt=0.01, guess=[-2.0])
    assert m.equilibrium_method.startswith("numeric")
    assert m.discrete_symbolic() is None or m.plant().n == 1
    assert m.plant().A[0, 0] == pytest.approx(np.exp(2 * 0.01))


def test_a_point_that_is_not_an_equilibrium_is_refused():
    with pytest.raises(ParameterError, match="not an equilibrium"):
        ODEModel([x], [u], [-k * x + u], {k: 2}, x_eq=[1], u_eq=[1], dt=0.1)


def test_the_nonlinear_check_of_the_muscle_is_unchanged_through_the_ode_model():
    ode = ODEModel.from_muscle(MuscleModel())
    a = nonlinear_check(MuscleModel(), amplitudes=[1.0, 3.0], steps=30)
    b = nonlinear_check(ode, amplitudes=[1.0, 3.0], steps=30)
    np.testing.assert_allclose(a.f_nonlinear, b.f_nonlinear, rtol=1e-12)
    assert a.f_nonlinear.shape == (2, 30)


def test_the_nonlinear_loop_of_a_linear_plant_is_the_linear_loop():
    m = ODEModel([x, v], [u], [v, -k * x - c * v + u], {k: 4, c: 1}, dt=0.01)
    gains = lqr_gains(augment(m.plant(), 1, 1))
    chk = nonlinear_check(m, gains, [0.5, 5.0], steps=60)
    np.testing.assert_allclose(chk.x_nonlinear, chk.x_linear, rtol=1e-7, atol=1e-9)
    assert chk.x_nonlinear.shape == (2, 60, 2) and chk.u_nonlinear.shape == (2, 60, 1)


def test_a_run_away_plant_is_marked_not_raised_when_asked():
    g = sp.Symbol("g", positive=True)
    rhs = [v, g * sp.sin(x) + 2 * sp.tanh(u / 2)]  # the torque saturates at 2
    m = ODEModel([x, v], [u], rhs, {g: 9.81}, [0, 0], dt=0.01)
    gains = lqr_gains(augment(m.plant(), 1, 1))
    chk = nonlinear_check(m, gains, [1e-3, 5.0], steps=400, fail="mark")
    assert chk.final_deviation[0] < 0.01 < chk.final_deviation[1]


@settings(max_examples=examples(40), deadline=None)
@given(
    st.lists(
        st.sampled_from(["N", "m", "s", "kg", "spikes", "rad", "ms", "Hz"]), min_size=1, max_size=4
    ),
    st.lists(st.integers(-3, 3), min_size=4, max_size=4),
)
def test_units_multiply_as_their_text_does(names, powers):
    text = "*".join(f"{n}**({p})" for n, p in zip(names, powers, strict=False))
    whole = parse_unit(text, "u")
    part = parse_unit("1", "u")
    for n, p in zip(names, powers, strict=False):
        part = part * parse_unit(n, "u") ** p
    assert whole == part
