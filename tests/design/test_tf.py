"""DiscreteTF: Markov parameters, interop, checks, algebra, value semantics, display."""

from __future__ import annotations

import control
import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from symctl import (
    DiscreteTF,
    MuscleModel,
    ParameterError,
    SymctlTypeError,
    augment,
    controller_tf,
    lqr_gains,
    z,
)
from symctl.symbols import gain_symbols


def test_markov_parameters_of_symbolic_G():
    K0, K1, K2 = gain_symbols(2)
    h = [m[0, 0] for m in controller_tf(2).markov(5)]
    assert h[:3] == [0, 0, K0]
    assert sp.expand(h[3] - K0 * K1) == 0
    assert sp.expand(h[4] - K0 * (K1**2 + K2)) == 0


def test_control_roundtrip_keeps_dt_and_coefficients():
    G = controller_tf(lqr_gains(augment(MuscleModel(), 1, 1)))
    sys = G.to_control()
    assert isinstance(sys, control.TransferFunction) and sys.dt == pytest.approx(0.01)
    np.testing.assert_allclose(sys.den[0][0], [float(c) for c in G.den_coeffs()])
    back = DiscreteTF.from_control(sys)
    assert back.dt == pytest.approx(0.01)
    np.testing.assert_allclose(back.impulse_response(10), G.impulse_response(10), atol=1e-14)


def test_mimo_control_roundtrip():
    aug = augment(([[1.1, 0.2], [0, 0.9]], [[0, 1], [1, 0]]), 1, 1)
    G = controller_tf(lqr_gains(aug))
    back = DiscreteTF.from_control(G.to_control())
    assert back.shape == (2, 2)
    np.testing.assert_allclose(back.impulse_response(12), G.impulse_response(12), atol=1e-10)


def test_from_control_refuses_continuous_systems():
    with pytest.raises(ParameterError, match="continuous"):
        DiscreteTF.from_control(control.tf([1], [1, 1]))


def test_symbolic_G_cannot_go_to_control():
    with pytest.raises(ParameterError, match="free symbols"):
        controller_tf(2).to_control()


def test_discrete_tf_checks_its_input():
    with pytest.raises(ParameterError, match="den"):
        DiscreteTF(1, 0)
    with pytest.raises(ParameterError, match="polynomial"):
        DiscreteTF(sp.exp(z), z)
    with pytest.raises(SymctlTypeError, match="G"):
        DiscreteTF.from_expr("1/z")
    with pytest.raises(ParameterError, match="T"):
        controller_tf(-1)


def test_series_and_equality():
    a = DiscreteTF.from_expr(1 / (z - sp.Rational(1, 2)))
    b = DiscreteTF.from_expr((z - sp.Rational(1, 2)) / (z - sp.Rational(1, 3)))
    assert (a * b).equals(1 / (z - sp.Rational(1, 3)))
    assert not a.equals(b)


def test_lambdify_broadcasts_and_matches_sympy():
    G = controller_tf(2)
    K = gain_symbols(2)
    f = G.lambdify(K)
    zs = np.exp(1j * np.linspace(0, np.pi, 7))
    vals = {K[0]: 0.3, K[1]: -0.2, K[2]: 0.1}
    got = f(zs, 0.3, -0.2, 0.1)
    want = [complex(G.expr.subs(vals).subs(z, zz)) for zz in zs]
    np.testing.assert_allclose(got, want, rtol=1e-12)


def test_repr_latex_in_jupyter():
    assert controller_tf(2)._repr_latex_().startswith("$\\displaystyle \\frac{K_{0}}")
    assert str(controller_tf(2)) == "(K_0)/(z**2 - K_1*z - K_2)"


def test_discrete_tf_equal_and_hashed_by_value():
    a = DiscreteTF.from_expr(2 / (2 * z**2 - 1), dt=0.01)
    b = DiscreteTF(1, z**2 - sp.Rational(1, 2), 0.01)
    assert a == b and hash(a) == hash(b) and len({a, b}) == 1
    assert a != DiscreteTF(1, z**2 - sp.Rational(1, 2))  # dt differs
    assert a != DiscreteTF(2, z**2 - sp.Rational(1, 2), 0.01)


def test_importing_the_tf_type_does_not_load_scipy_or_the_controller():
    import subprocess
    import sys

    code = (
        "import sys, symctl.design.tf; "
        "print(sorted(m for m in ('scipy', 'symctl.design.lqr', 'symctl.design.augment') "
        "if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_floats_print_short_and_exact_numbers_exactly():
    from symctl import controller_tf, lqr_gains

    s = augment(MuscleModel(), 1, 1)
    G = controller_tf(s).subs(lqr_gains(s).substitutions())  # floats from the Riccati equation
    assert str(G) == "(-0.0459719)/(z**2 + 0.580041*z + 0.351813)"
    assert G.latex() == r"\frac{-0.0459719}{z^{2} + 0.580041 z + 0.351813}"
    assert "1.0" not in repr(G) and str(DiscreteTF(sp.Rational(1, 3), z - 1)) == "(1/3)/(z - 1)"


def test_a_transfer_function_without_a_denominator_prints_its_numerator():
    assert str(DiscreteTF(1, 1)) == "1" and DiscreteTF(1, 1).latex() == "1"
    assert str(DiscreteTF(sp.Symbol("C") * z, 1)) == "C*z"


@given(st.lists(st.fractions(max_denominator=50), min_size=3, max_size=3))
def test_subs_of_numbers_is_sympys_subs_and_a_rule_with_symbols_keeps_its_order(values):
    """Numbers go in by xreplace (fast): the same expression as SymPy's subs; a rule whose
    values hold symbols keeps subs's sequential meaning."""
    a, b, c = sp.symbols("a b c")
    G = DiscreteTF(a * z**2 + b * z - c, z**3 - a * b * z + c**2 + 1)
    rule = {
        s: sp.Rational(v.numerator, v.denominator) for s, v in zip((a, b, c), values, strict=True)
    }
    got = G.subs(rule)
    assert got.num == G.num.subs(rule) and got.den == G.den.subs(rule)
    chained = G.subs([(a, b), (b, 2)])  # sequential: a -> b -> 2
    assert chained.num == G.num.subs([(a, b), (b, 2)])
    assert not chained.free_symbols - {c}
