"""The muscle plant: linearization, exact ZOH discretization, paper's numbers."""

from __future__ import annotations

import control
import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from symctl import (
    DimensionError,
    DiscretePlant,
    MuscleModel,
    ParameterError,
    ParseError,
    SymctlTypeError,
    discretize,
    linearize,
)
from symctl.symbols import T_s, f_max, r_bar, tau


def is_zero(expr) -> bool:
    return sp.simplify(sp.expand(expr)) == 0


def test_muscle_linearization_is_the_papers():
    a, b = MuscleModel().linearize_symbolic()
    assert is_zero(a[0, 0] + 1 / tau)
    assert is_zero(b[0, 0] - (f_max / tau) * sp.exp(-r_bar) / (1 + sp.exp(-r_bar)) ** 2)


def test_muscle_discretization_closed_form_is_the_papers():
    p = MuscleModel().discrete_symbolic()
    assert p.A[0, 0] == sp.exp(-T_s / tau)
    paper_B = f_max * (1 - sp.exp(-T_s / tau)) * sp.exp(-r_bar) / (1 + sp.exp(-r_bar)) ** 2
    assert is_zero(p.B[0, 0] - paper_B)


def test_muscle_equilibrium_is_the_papers():
    m = MuscleModel()
    assert m.f_bar_symbolic == f_max / (1 + sp.exp(-r_bar))
    assert is_zero(
        m.ode.subs({sp.Symbol("f", real=True): m.f_bar_symbolic, sp.Symbol("r", real=True): r_bar})
    )


def test_paper_numbers():
    m = MuscleModel()
    p = m.plant()
    A, B = (float(v) for v in (p.A[0, 0], p.B[0, 0]))
    assert m.f_bar == pytest.approx(43.8635, abs=5e-5)
    assert A == pytest.approx(0.606531, abs=5e-7)
    assert B == pytest.approx(4.641646, abs=5e-7)
    # the paper's rounded values
    assert (round(m.f_bar, 1), round(A, 2), round(B, 2)) == (43.9, 0.61, 4.64)


@given(
    tau_=st.floats(0.005, 0.2),
    fmax=st.floats(1, 200),
    rbar=st.floats(-3, 3),
    ts=st.floats(0.001, 0.05),
)
def test_closed_form_agrees_with_control_c2d(tau_, fmax, rbar, ts):
    m = MuscleModel(tau=tau_, f_max=fmax, r_bar=rbar, dt=ts)
    a, b = m.linearize_symbolic()
    vals = m.values
    sys_c = control.ss(float(a[0, 0].subs(vals)), float(b[0, 0].subs(vals)), 1.0, 0.0)
    sys_d = control.c2d(sys_c, ts, "zoh")
    p = m.plant()
    assert float(p.A[0, 0]) == pytest.approx(sys_d.A[0, 0], rel=1e-9)
    assert float(p.B[0, 0]) == pytest.approx(sys_d.B[0, 0], rel=1e-9)


def test_linearization_matches_finite_differences():
    m = MuscleModel()
    a, b = m.linearize_symbolic()
    vals = m.values
    h = 1e-6
    fb, rb = m.f_bar, m.r_bar
    da = (m.rhs(fb + h, rb) - m.rhs(fb - h, rb)) / (2 * h)
    db = (m.rhs(fb, rb + h) - m.rhs(fb, rb - h)) / (2 * h)
    assert float(a[0, 0].subs(vals)) == pytest.approx(da, rel=1e-6)
    assert float(b[0, 0].subs(vals)) == pytest.approx(db, rel=1e-6)
    assert abs(m.rhs(fb, rb)) < 1e-9


def test_discretize_symbolic_two_state_agrees_with_scipy():
    w, ts = sp.symbols("omega T", positive=True)
    a = sp.Matrix([[0, 1], [-(w**2), 0]])
    b = sp.Matrix([0, 1])
    A, B = discretize(a, b, ts)
    vals = {w: sp.Rational(3, 2), ts: sp.Rational(1, 10)}
    sys_d = control.c2d(
        control.ss(np.array(a.subs(vals), float), np.array(b, float), np.eye(2), 0), 0.1
    )
    np.testing.assert_allclose(
        np.array(A.subs(vals).evalf(), float), sys_d.A, rtol=1e-12, atol=1e-14
    )
    np.testing.assert_allclose(
        np.array(B.subs(vals).evalf(), float), sys_d.B, rtol=1e-12, atol=1e-14
    )


def test_discretize_integrator_has_singular_a():
    ts = sp.Symbol("h", positive=True)
    A, B = discretize([[0, 1], [0, 0]], [[0], [1]], ts)
    assert A == sp.Matrix([[1, ts], [0, 1]])
    assert (B - sp.Matrix([ts**2 / 2, ts])).applyfunc(sp.simplify) == sp.zeros(2, 1)


def test_discretize_numeric_matches_c2d(rng):
    a, b = rng.normal(size=(3, 3)), rng.normal(size=(3, 2))
    A, B = discretize(a, b, 0.05)
    sys_d = control.c2d(control.ss(a, b, np.eye(3), 0), 0.05)
    np.testing.assert_allclose(np.array(A, float), sys_d.A, rtol=1e-12)
    np.testing.assert_allclose(np.array(B, float), sys_d.B, rtol=1e-12)


def test_linearize_vector_ode_and_strings():
    x1, x2, u = sp.symbols("x1 x2 u", real=True)
    a, b = linearize(["x2", "-sin(x1) + u"], [x1, x2], [u], [0, 0], [0])
    assert a == sp.Matrix([[0, 1], [-1, 0]])
    assert b == sp.Matrix([[0], [1]])


def test_linearize_refuses_non_equilibrium():
    x, u = sp.symbols("x u")
    with pytest.raises(ParameterError, match="x_eq, u_eq"):
        linearize([-x + u], [x], [u], [1], [0])


def test_linearize_refuses_code_in_strings():
    x, u = sp.symbols("x u")
    with pytest.raises(ParseError, match="f"):
        linearize(["__import__('os').system('true')"], [x], [u], [0], [0])


def test_linearize_checks_dimensions():
    x, u = sp.symbols("x u")
    with pytest.raises(DimensionError, match="f"):
        linearize([x, u], [x], [u], [0], [0])
    with pytest.raises(DimensionError, match="x_eq"):
        linearize([x], [x], [u], [0, 1], [0])


@pytest.mark.parametrize("name", ["tau", "f_max", "dt"])
@pytest.mark.parametrize("value", [0, -1.0, float("nan"), float("inf")])
def test_muscle_refuses_non_positive_parameters(name, value):
    with pytest.raises(ParameterError, match=name):
        MuscleModel(**{name: value})


def test_muscle_refuses_non_numbers():
    with pytest.raises(SymctlTypeError, match="tau"):
        MuscleModel(tau="0.02")


def test_discretize_refuses_bad_shapes_and_ts():
    with pytest.raises(DimensionError, match="a"):
        discretize([[1, 2]], [[1]], 0.1)
    with pytest.raises(DimensionError, match="b"):
        discretize([[1]], [[1], [2]], 0.1)
    with pytest.raises(ParameterError, match="dt"):
        discretize([[1]], [[1]], -0.1)


def test_discrete_plant_checks_shapes():
    with pytest.raises(DimensionError, match="B"):
        DiscretePlant([[1, 0], [0, 1]], [[1]])
    p = DiscretePlant([[1, 0], [0, 1]], [[1], [0]], dt=0.1)
    assert p.state_names == ("x_1", "x_2") and p.input_names == ("u",)
    assert p.to_control().dt == pytest.approx(0.1)


def test_plant_objects_render_latex():
    m = MuscleModel()
    assert r"f_\text{max}" in m._repr_latex_()
    assert r"\tau" in m.discrete_symbolic().latex()
    assert m.linearize_symbolic()._repr_latex_().startswith("$")
