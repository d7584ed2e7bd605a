"""Interop: python-control, SciPy and SymPy systems to and from symctl, with the sampling time kept.

The facts protected: a python-control system is a plant wherever ``(A, B)`` is (same
gains, same controller); every conversion round-trips (exactly for exact and symbolic
objects, to the last bit or numerically for floats); the converted system responds
like the original (checked with the other library's own evaluation); ``dt`` is
carried, mismatches are refused; bad input gives symctl's errors. The SymPy tests
follow the installed SymPy: 1.14 has no discrete-time classes (``dt=`` is given
apart), a later SymPy's ``DiscreteTransferFunction`` carries it.
"""

from __future__ import annotations

import control
import numpy as np
import pytest
import sympy as sp
import sympy.physics.control as sympy_control
from hypothesis import given
from hypothesis import strategies as st
from scipy import signal

from symctl import (
    DimensionError,
    DiscretePlant,
    DiscreteTF,
    MuscleModel,
    ParameterError,
    Realization,
    SymctlError,
    SymctlTypeError,
    augment,
    circuit_firing,
    closed_loop_response,
    controllable_canonical,
    controller_tf,
    factor,
    loop_stability,
    lqr_gains,
    open_loop_response,
    simulate_batch,
    simulate_realization,
    z,
)
from symctl.design._foreign import canonical_columns
from symctl.interop import (
    ss_from_control,
    ss_from_scipy,
    ss_from_sympy,
    ss_to_control,
    ss_to_scipy,
    ss_to_sympy,
    tf_from_control,
    tf_from_scipy,
    tf_from_sympy,
    tf_to_control,
    tf_to_scipy,
    tf_to_sympy,
)
from symctl.symbols import gain_symbols

SYMPY_DISCRETE = hasattr(sympy_control, "DiscreteTransferFunction")
TF_SYMPY = sympy_control.TransferFunction
K0, K1, K2 = gain_symbols(2)
MUSCLE = MuscleModel().plant()
A_MUSCLE, B_MUSCLE = float(MUSCLE.A[0, 0]), float(MUSCLE.B[0, 0])
A2 = np.array([[1.1, 0.2], [0.0, 0.9]])
B2 = np.array([[0.0, 1.0], [1.0, 0.0]])
POINTS = np.exp(1j * np.array([0.1, 0.7, 1.9, 3.0]))  # on the unit circle


def _at(G: DiscreteTF, points=POINTS) -> np.ndarray:
    """``G`` at complex points, shape (points, outputs, inputs)."""
    f = G.lambdify()
    return np.array([np.array(f(p), dtype=complex).reshape(G.shape) for p in points])


def _control_at(sys, points=POINTS) -> np.ndarray:
    return np.array(
        [np.array(sys(p), dtype=complex).reshape(sys.noutputs, sys.ninputs) for p in points]
    )


def _ss_at(A, B, C, D, points=POINTS) -> np.ndarray:
    n = np.shape(A)[0]
    return np.array([C @ np.linalg.solve(p * np.eye(n) - A, B) + D for p in points])


def _through_sympy(dt):
    """The dt that comes back from SymPy: a later SymPy writes None as its default, 1."""
    return 1 if SYMPY_DISCRETE and dt is None else dt


def _gains_and_G(plant, ds=1, da=1):
    gains = lqr_gains(augment(plant, ds, da))
    return gains, controller_tf(gains)


# ---------------------------------------------------------------- python-control as a plant
@pytest.mark.parametrize(("A", "B"), [([[A_MUSCLE]], [[B_MUSCLE]]), (A2, B2)], ids=["siso", "mimo"])
def test_control_state_space_plant_gives_the_gains_and_controller_of_its_A_B(A, B):
    sys = control.ss(A, B, np.eye(len(A)), 0, 0.01)
    gains, G = _gains_and_G(sys)
    ref_gains, ref_G = _gains_and_G((np.asarray(A), np.asarray(B)))
    np.testing.assert_array_equal(gains.K, ref_gains.K)
    assert G.num_matrix == ref_G.num_matrix and G.den == ref_G.den
    assert G.dt == sp.Float(0.01) and ref_G.dt is None  # dt kept from the system
    assert gains.system.plant.state_names == (("x",) if len(A) == 1 else ("x_1", "x_2"))


def test_control_transfer_function_plant_is_its_controllable_canonical_form():
    tf = control.tf([B_MUSCLE], [1, -A_MUSCLE], 0.01)
    gains, G = _gains_and_G(tf)
    ccf = controllable_canonical(DiscreteTF.from_expr(B_MUSCLE / (z - A_MUSCLE)))
    ref_gains, _ = _gains_and_G((np.array(ccf.F, float), np.array(ccf.H, float)))
    np.testing.assert_array_equal(gains.K, ref_gains.K)
    assert gains.system.plant.dt == sp.Float(0.01) and G.dt == sp.Float(0.01)
    # second order: the same F, H as symctl's controllable_canonical
    tf2 = control.tf([1.0, 0.5], [1.0, -0.9, 0.2], True)
    p = augment(tf2, 0, 0).plant
    ccf2 = controllable_canonical(DiscreteTF.from_expr((z + 0.5) / (z**2 - 0.9 * z + 0.2)))
    np.testing.assert_allclose(np.array(p.A, float), np.array(ccf2.F, float), atol=0)
    np.testing.assert_allclose(np.array(p.B, float), np.array(ccf2.H, float), atol=0)
    assert p.dt is None  # dt=True, python-control's "discrete, unspecified"


def test_control_mimo_transfer_function_plant_realizes_the_same_transfer_function():
    num = [[[1.0], [2.0, 0.1]], [[0.5, 0.0], [1.0]]]
    den = [[[1.0, -0.5], [1.0, -0.2]], [[1.0, -0.5], [1.0, 0.3, 0.02]]]
    sys = control.tf(num, den, 0.1)
    F, H, M, N = canonical_columns(sys.num_array, sys.den_array, "sys")
    np.testing.assert_allclose(_ss_at(F, H, M, N), _control_at(sys), atol=1e-12)
    p = augment(sys, 1, 0).plant
    np.testing.assert_array_equal(np.array(p.A, float), F)
    np.testing.assert_array_equal(np.array(p.B, float), H)
    assert (p.n, p.m, p.dt) == (4, 2, sp.Float(0.1))  # column 0: one shared pole; column 1: two
    assert lqr_gains(augment(sys, 1, 1)).K.shape == (2, 4 + 2 * 2)


def test_control_labels_become_names_when_they_are_identifiers():
    sys = control.ss(A2, B2, np.eye(2), 0, 0.1, states=["pos", "vel"], inputs=["f1", "f2"])
    aug = augment(sys, 0, 1)
    assert aug.plant.state_names == ("pos", "vel") and aug.plant.input_names == ("f1", "f2")
    assert aug.state_names == ("pos", "vel", "f1", "f2")
    default = augment(control.ss(A2, B2, np.eye(2), 0, 0.1), 0, 0).plant  # x[0], u[0] ...
    assert default.state_names == ("x_1", "x_2") and default.input_names == ("u_1", "u_2")
    spaced = augment(control.ss(A2, B2, np.eye(2), 0, 0.1, states=["a b", "c"]), 0, 0).plant
    assert spaced.state_names == ("x_1", "x_2")


def test_every_plant_taking_function_accepts_a_control_state_space():
    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    G = controller_tf(gains)
    sys = control.ss([[A_MUSCLE]], [[B_MUSCLE]], [[1]], 0, 0.01)
    pairs = [
        (open_loop_response(sys).delta_f, open_loop_response(MuscleModel()).delta_f),
        (closed_loop_response(G, sys).delta_r, closed_loop_response(G, MuscleModel()).delta_r),
        (closed_loop_response(gains, sys).delta_r, closed_loop_response(gains).delta_r),
        (
            simulate_realization(sys, controllable_canonical(G)).delta_f,
            simulate_realization(MuscleModel(), controllable_canonical(G)).delta_f,
        ),
    ]
    for got, want in pairs:
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12)
    assert loop_stability(sys, G) and loop_stability(sys, gains)
    F, H, M, N = (np.asarray(a, float)[None] for a in controllable_canonical(G).numeric())
    batch = simulate_batch(sys, F, H, M, N)
    np.testing.assert_allclose(batch.delta_r[0], closed_loop_response(G, sys).delta_r)
    fp = circuit_firing("controllable", gains, sys, count=1)
    assert fp.t[1] == pytest.approx(0.01)


def test_a_plant_and_a_controller_with_different_sampling_times_are_refused():
    gains = lqr_gains(augment(MuscleModel(), 1, 1))  # Ts = 1/100
    G = controller_tf(gains)
    slow = control.ss([[A_MUSCLE]], [[B_MUSCLE]], [[1]], 0, 0.1)
    with pytest.raises(ParameterError, match=r"^controller: the plant is sampled with Ts = 0\.1"):
        closed_loop_response(G, slow)
    with pytest.raises(ParameterError, match=r"^plant: .* the gains' plant with dt = 1/100"):
        closed_loop_response(gains, slow)
    with pytest.raises(ParameterError, match=r"^R: "):
        simulate_realization(slow, controllable_canonical(G))
    with pytest.raises(ParameterError, match=r"^controller: "):
        loop_stability(slow, G)
    with pytest.raises(ParameterError, match=r"^plant: "):
        circuit_firing("controllable", gains, slow, count=1)
    # unspecified on either side fits; 0.01 and 1/100 agree
    unspecified = control.ss([[A_MUSCLE]], [[B_MUSCLE]], [[1]], 0, True)
    assert closed_loop_response(G, unspecified).t[1] == 1.0  # in steps: the plant has no Ts
    undated = DiscreteTF(G.num, G.den)
    assert closed_loop_response(undated, slow).t[1] == pytest.approx(0.1)
    same = control.ss([[A_MUSCLE]], [[B_MUSCLE]], [[1]], 0, 0.01)
    assert closed_loop_response(gains, same).t[1] == pytest.approx(0.01)


BAD_PLANTS = {
    "continuous state space": (control.ss([[-1]], [[1]], [[1]], 0), ParameterError, "discretize"),
    "continuous tf": (control.tf([1], [1, 1]), ParameterError, "continuous"),
    "improper tf": (control.tf([1, 0, 0], [1, -0.5], 0.1), ParameterError, "improper"),
    "static gain": (control.tf([2], [1], 0.1), DimensionError, "static gain"),
    "nan": (control.ss([[np.nan]], [[1]], [[1]], 0, 0.1), ParameterError, "finite"),
    "frequency data": (
        control.frd([1, 2], [0.1, 1.0]),
        SymctlTypeError,
        "StateSpace or TransferFunction",
    ),
    "a list": ([[1]], SymctlTypeError, "python-control StateSpace or TransferFunction, got list"),
    "text": ("[[1]], [[1]]", SymctlTypeError, "got str"),
}


@pytest.mark.parametrize(("plant", "error", "match"), BAD_PLANTS.values(), ids=BAD_PLANTS.keys())
def test_bad_plants_are_refused_with_symctl_errors(plant, error, match):
    with pytest.raises(error, match=match) as info:
        augment(plant, 1, 1)
    assert str(info.value).startswith(("plant: ", "plant[0, 0]: "))  # the argument, the entry


def test_ss_from_control_realizes_a_mimo_transfer_function_without_slycot():
    sys = control.tf([[[1.0], [0.5, 0.1]]], [[[1.0, -0.5], [1.0, 0.2, 0.01]]], 0.2)
    R = ss_from_control(sys)
    assert R.dt == sp.Float(0.2) and R.shape == (1, 2)
    np.testing.assert_allclose(_ss_at(*R.numeric()), _control_at(sys), atol=1e-12)
    np.testing.assert_allclose(_control_at(ss_to_control(R)), _control_at(sys), atol=1e-12)


# ---------------------------------------------------------------- SymPy
def _sympy_tf(num, den, var, dt):
    """A SymPy transfer function of the installed SymPy's discrete kind."""
    if SYMPY_DISCRETE:
        return sympy_control.DiscreteTransferFunction(num, den, var, dt)
    return TF_SYMPY(num, den, var)


def test_symbolic_G_round_trips_through_sympy_exactly_with_dt():
    G = controller_tf(2)
    Gdt = DiscreteTF(G.num, G.den, dt=sp.Rational(1, 100))
    sys = tf_to_sympy(Gdt)
    assert (sys.num, sys.den, sys.var) == (G.num, G.den, z)
    assert sp.cancel(sys.to_expr() - G.expr) == 0  # SymPy's own reading of it
    assert tf_from_sympy(sys, dt=sp.Rational(1, 100)) == Gdt
    assert DiscreteTF.from_sympy(Gdt.to_sympy(), sp.Rational(1, 100)) == Gdt
    if SYMPY_DISCRETE:  # the sampling time travels inside the object
        assert sys.sampling_time == sp.Rational(1, 100) and tf_from_sympy(sys) == Gdt
    else:  # SymPy 1.14's TransferFunction carries none: dt= gives it back
        assert tf_from_sympy(sys).dt is None


def test_mimo_symbolic_transfer_function_round_trips_through_a_sympy_matrix():
    a, b = sp.symbols("a b")
    G = DiscreteTF.from_expr(
        sp.Matrix([[K0 / (z - a), 1 / (z - b)], [0, (z + b) / ((z - a) * (z - b))]]), dt=a
    )
    sys = G.to_sympy()
    assert isinstance(sys, sympy_control.TransferFunctionMatrix)
    assert (sys.num_outputs, sys.num_inputs) == (2, 2)
    back = DiscreteTF.from_sympy(sys, dt=a)
    assert back == G
    # entries over different denominators: brought to the lowest common one, exactly
    mixed = sympy_control.TransferFunctionMatrix(
        [[_sympy_tf(1, z - a, z, a), _sympy_tf(K0, (z - a) * (z - b), z, a)]]
    )
    got = tf_from_sympy(mixed, dt=a)
    assert got.equals(sp.Matrix([[1 / (z - a), K0 / ((z - a) * (z - b))]]))
    assert sp.expand(got.den - (z - a) * (z - b)) == 0


def test_realization_round_trips_through_sympy_state_space_exactly():
    R = controllable_canonical(factor(controller_tf(2)).G2)
    R = Realization(R.F, R.H, R.M, R.N, dt=sp.Symbol("T_s"))
    sys = ss_to_sympy(R)
    assert (sys.A, sys.B, sys.C, sys.D) == (R.F, R.H, R.M, R.N)
    assert Realization.from_sympy(sys, dt=sp.Symbol("T_s")) == R
    assert R.to_sympy() == sys
    static = Realization(sp.zeros(0, 0), sp.zeros(0, 1), sp.zeros(1, 0), [[K0]])
    back = ss_from_sympy(ss_to_sympy(static))
    assert back == Realization(static.F, static.H, static.M, static.N, _through_sympy(None))


def test_sympy_transfer_function_to_realization_is_controllable_canonical():
    G = DiscreteTF.from_expr(K0 / (z**2 - K1 * z - K2))
    sys = tf_to_sympy(G)
    assert ss_from_sympy(sys) == controllable_canonical(
        DiscreteTF(G.num, G.den, _through_sympy(None))
    )
    assert tf_from_sympy(ss_to_sympy(controllable_canonical(G))).equals(G)
    with pytest.raises(DimensionError, match="transfer function matrix"):
        ss_from_sympy(tf_to_sympy(DiscreteTF.from_expr(sp.Matrix([[1 / z, 2 / z]]))))


@pytest.mark.skipif(SYMPY_DISCRETE, reason="a later SymPy's TransferFunction is continuous")
def test_sympy_114_transfer_function_in_another_variable_needs_var():
    q = sp.Symbol("q")
    sys = TF_SYMPY(K0, q - sp.Rational(1, 2), q)
    with pytest.raises(ParameterError, match="in q, not in z; pass var=q"):
        tf_from_sympy(sys)
    assert tf_from_sympy(sys, sp.Rational(1, 10), var=q) == DiscreteTF(
        K0, z - sp.Rational(1, 2), sp.Rational(1, 10)
    )
    with pytest.raises(ParameterError, match="var: sys is a transfer function in q, not in s"):
        tf_from_sympy(sys, var=sp.Symbol("s"))
    with pytest.raises(ParameterError, match="z as a parameter"):
        tf_from_sympy(TF_SYMPY(z, q - 1, q), var=q)


@pytest.mark.skipif(not SYMPY_DISCRETE, reason="SymPy 1.14 has no discrete-time classes")
def test_later_sympy_discrete_classes_carry_dt_and_continuous_ones_are_refused():
    q = sp.Symbol("q")
    sys = sympy_control.DiscreteTransferFunction(K0, q - 1, q, sp.Rational(1, 10))
    assert tf_from_sympy(sys) == DiscreteTF(K0, z - 1, sp.Rational(1, 10))
    with pytest.raises(ParameterError, match="dt: incompatible sampling times"):
        tf_from_sympy(sys, dt=0.2)
    with pytest.raises(ParameterError, match="continuous-time SymPy TransferFunction"):
        tf_from_sympy(TF_SYMPY(1, z - 1, z))
    ss = sympy_control.StateSpace(sp.Matrix([[1]]), sp.Matrix([[1]]), sp.Matrix([[1]]))
    with pytest.raises(ParameterError, match="continuous-time SymPy StateSpace"):
        ss_from_sympy(ss)


BAD_SYMPY = {
    "a DiscreteTF": (lambda: tf_from_sympy(controller_tf(2)), SymctlTypeError, "^sys: expected"),
    "text": (lambda: tf_from_sympy("K/(z - 1)"), SymctlTypeError, "got str"),
    "a Series": (
        lambda: tf_from_sympy(_sympy_tf(1, z, z, 1) * _sympy_tf(1, z - 1, z, 1)),
        SymctlTypeError,
        r"\.doit\(\)",
    ),
    "var text": (
        lambda: tf_from_sympy(_sympy_tf(1, z, z, 1), var="z"),
        SymctlTypeError,
        "^var: expected a sympy Symbol",
    ),
    "not rational": (
        lambda: tf_from_sympy(_sympy_tf(1, sp.exp(z), z, 1)),
        ParameterError,
        "not rational in z",
    ),
    "ss of a Realization": (lambda: ss_from_sympy(controller_tf(2)), SymctlTypeError, "^sys: "),
    "to_sympy of a tuple": (lambda: tf_to_sympy((1, 2)), SymctlTypeError, "^G: expected"),
    "ss_to_sympy of a TF": (lambda: ss_to_sympy(controller_tf(2)), SymctlTypeError, "^R: "),
    "hostile dt text": (
        lambda: tf_from_sympy(_sympy_tf(1, z, z, 1), dt="__import__('os')"),
        SymctlError,
        "dt",
    ),
}


@pytest.mark.parametrize(("call", "error", "match"), BAD_SYMPY.values(), ids=BAD_SYMPY.keys())
def test_bad_sympy_input_gives_symctl_errors(call, error, match):
    with pytest.raises(error, match=match):
        call()


# ---------------------------------------------------------------- SciPy
def test_siso_and_simo_tf_round_trip_through_scipy_with_dt():
    G = DiscreteTF.from_expr((0.5 * z + 0.2) / (z**2 - 0.3 * z + 0.02), dt=0.05)
    sys = tf_to_scipy(G)
    assert isinstance(sys, signal.dlti) and sys.dt == 0.05
    assert G.to_scipy().num.tolist() == [0.5, 0.2]
    back = tf_from_scipy(sys)
    assert back.dt == sp.Float(0.05) and back.equals(G)
    np.testing.assert_allclose(_at(back), _at(G), atol=1e-14)
    _, h = signal.dimpulse(sys, n=12)  # SciPy's own impulse response
    np.testing.assert_allclose(h[0][:, 0], G.impulse_response(12)[:, 0, 0], atol=1e-14)
    simo = DiscreteTF.from_expr(sp.Matrix([[1 / (z - 0.5)], [(z + 1) / (z - 0.5)]]))
    s2 = tf_to_scipy(simo)
    assert s2.num.shape == (2, 2) and s2.dt is True  # dt None <-> True
    back2 = DiscreteTF.from_scipy(s2)
    assert back2.dt is None and back2.shape == (2, 1)
    np.testing.assert_allclose(_at(back2), _at(simo), atol=1e-14)


def test_scipy_transfer_functions_hold_one_input_only():
    G = DiscreteTF.from_expr(sp.Matrix([[1 / (z - 0.5), 2 / (z - 0.5)]]), dt=0.1)
    with pytest.raises(DimensionError, match=r"one input.*use ss_to_scipy"):
        tf_to_scipy(G)
    R = Realization(*canonical_columns([[[1.0], [2.0]]], [[[1.0, -0.5], [1.0, -0.5]]], "G"), 0.1)
    sys = ss_to_scipy(R)
    assert sys.B.shape == (2, 2) and sys.dt == 0.1
    back = tf_from_scipy(sys)  # ss2tf input by input
    np.testing.assert_allclose(_at(back), _at(G), atol=1e-12)


def test_realization_round_trips_through_scipy_to_the_last_bit():
    rng = np.random.default_rng(3)
    F = rng.normal(size=(3, 3)) * 0.3
    R = Realization(
        F, rng.normal(size=(3, 2)), rng.normal(size=(2, 3)), rng.normal(size=(2, 2)), 0.1
    )
    back = Realization.from_scipy(R.to_scipy())
    assert back == R  # the same floats, the same dt
    static = Realization(np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0)), [[2.0]], None)
    assert ss_from_scipy(ss_to_scipy(static)) == static
    assert tf_from_scipy(ss_to_scipy(static)).expr == sp.Float(2.0)


def test_scipy_transfer_function_is_realized_in_controllable_canonical_form():
    sys = signal.dlti([1.0, 2.0], [1.0, -0.5, 0.06], dt=0.1)
    R = ss_from_scipy(sys)
    ccf = controllable_canonical(DiscreteTF.from_expr((z + 2.0) / (z**2 - 0.5 * z + 0.06)))
    np.testing.assert_array_equal(np.array(R.F, float), np.array(ccf.F, float))
    zpk = signal.ZerosPolesGain([-2.0], [0.2, 0.3], 1.0, dt=0.1)
    np.testing.assert_allclose(_at(tf_from_scipy(zpk)), _at(tf_from_scipy(sys)), atol=1e-14)
    np.testing.assert_allclose(_ss_at(*ss_from_scipy(zpk).numeric()), _at(R.to_tf()), atol=1e-14)


BAD_SCIPY = {
    "continuous tf": (lambda: tf_from_scipy(signal.lti([1], [1, 1])), ParameterError, "discretize"),
    "continuous ss": (
        lambda: ss_from_scipy(signal.StateSpace([[-1]], [[1]], [[1]], [[0]])),
        ParameterError,
        "continuous-time",
    ),
    "control tf": (lambda: tf_from_scipy(control.tf([1], [1, 0], 0.1)), SymctlTypeError, "dlti"),
    "tuple": (lambda: ss_from_scipy(([1], [1, -0.5])), SymctlTypeError, "got tuple"),
    "symbols": (lambda: tf_to_scipy(controller_tf(2)), ParameterError, "free symbols"),
    "symbolic R": (
        lambda: ss_to_scipy(controllable_canonical(controller_tf(2))),
        ParameterError,
        "symbols|numeric|substitute",
    ),
    "improper": (
        lambda: ss_from_scipy(signal.dlti([1.0, 0.0, 0.0], [1.0, -0.5], dt=0.1)),
        ParameterError,
        "improper",
    ),
}


@pytest.mark.parametrize(("call", "error", "match"), BAD_SCIPY.values(), ids=BAD_SCIPY.keys())
def test_bad_scipy_input_gives_symctl_errors(call, error, match):
    with pytest.raises(error, match=match):
        call()


# ---------------------------------------------------------------- python-control (kept working)
def test_control_conversions_agree_with_python_control_evaluation():
    G = controller_tf(lqr_gains(augment((A2, B2), 1, 1)))
    sys = tf_to_control(G)
    np.testing.assert_allclose(_control_at(sys), _at(G), rtol=1e-10)
    np.testing.assert_allclose(_at(tf_from_control(sys)), _at(G), rtol=1e-10)
    R = controllable_canonical(controller_tf(lqr_gains(augment(MuscleModel(), 1, 1))))
    np.testing.assert_allclose(_control_at(ss_to_control(R)), _at(R.to_tf()), rtol=1e-12)
    assert float(ss_from_control(ss_to_control(R)).dt) == 0.01


# ---------------------------------------------------------------- property: random stable systems
@st.composite
def stable_systems(draw):
    """A random numeric realization with spectral radius < 1 (1-4 states, 1-2 in/outputs)."""
    n = draw(st.integers(1, 4))
    p, q = draw(st.integers(1, 2)), draw(st.integers(1, 2))
    seed = draw(st.integers(0, 2**32 - 1))
    dt = draw(st.sampled_from([None, 0.01, 0.5]))
    rng = np.random.default_rng(seed)
    F = rng.normal(size=(n, n))
    F *= draw(st.floats(0.05, 0.95)) / max(np.max(np.abs(np.linalg.eigvals(F))), 1e-3)
    return Realization(
        F, rng.normal(size=(n, q)), rng.normal(size=(p, n)), rng.normal(size=(p, q)), dt
    )


@pytest.mark.slow
@given(stable_systems())
def test_random_stable_systems_round_trip_through_scipy_and_sympy(R):
    assert ss_from_scipy(ss_to_scipy(R)) == R
    sym = ss_from_sympy(ss_to_sympy(R), R.dt)
    assert sym == Realization(R.F, R.H, R.M, R.N, _through_sympy(R.dt))
    # the transfer function, through SciPy's ss2tf and back, responds like R
    G = tf_from_scipy(ss_to_scipy(R))
    want = _ss_at(*R.numeric())
    np.testing.assert_allclose(_at(G), want, atol=1e-8 * max(1.0, np.abs(want).max()))
    if R.shape[1] == 1:  # SciPy TFs hold one input
        back = tf_from_scipy(tf_to_scipy(G))
        np.testing.assert_allclose(_at(back), _at(G), atol=1e-12 * max(1.0, np.abs(want).max()))
    assert tf_from_sympy(tf_to_sympy(G), G.dt) == DiscreteTF(G.num, G.den, _through_sympy(G.dt))


@given(st.lists(st.floats(-0.9, 0.9), min_size=1, max_size=4), st.floats(0.1, 3.0))
def test_random_stable_siso_transfer_functions_round_trip(poles, gain):
    den = sp.expand(sp.prod([z - sp.Float(p) for p in poles]))
    G = DiscreteTF(gain * z ** (len(poles) - 1), den, dt=0.1)
    back = tf_from_scipy(tf_to_scipy(G))
    np.testing.assert_allclose(_at(back), _at(G), rtol=1e-12)
    R = ss_from_scipy(tf_to_scipy(G))
    np.testing.assert_allclose(_ss_at(*R.numeric()), _at(G), rtol=1e-9)
    assert tf_from_sympy(tf_to_sympy(G), dt=0.1) == G
    assert DiscretePlant(R.F, R.H).n == len(poles)
