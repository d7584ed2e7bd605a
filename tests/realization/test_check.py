"""check_realization: exact proofs and randomized tests of M (zI - F)^-1 H + N = G."""

from __future__ import annotations

import random
from fractions import Fraction

import control
import numpy as np
import pytest
import sympy as sp
from helpers import bounded
from hypothesis import assume, given
from hypothesis import strategies as st

from symctl import DimensionError, DiscreteTF, ParameterError, SymctlTypeError, z
from symctl.realization.check import RealizationCheck, check_realization
from symctl.realization.realization import Realization, controllable_canonical, observable_canonical
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3, gain_symbols

METHODS = ("exact", "randomized")
K0, K1, K2, K3 = gain_symbols(3)
G2 = K0 / (C_1 * C_3) * (z**2 - (epsilon_1 + epsilon_3) * z + epsilon_1 * epsilon_3)
G2 = G2 / (z**2 - K1 * z - K2)
G3 = K0 / (C_1 * C_3) * (z - epsilon_1) * (z - epsilon_3) / (z**3 - K1 * z**2 - K2 * z - K3)
t = sp.Symbol("t")  # a symbol foreign to both sides, for perturbations


def symbolic_P(n: int) -> sp.Matrix:
    return sp.Matrix(n, n, lambda i, j: sp.Symbol(f"p_{i}{j}"))


def side_values(R: Realization, G, values: dict) -> tuple[sp.Matrix, sp.Matrix]:
    """Both sides at ``values`` (symbols and z), evaluated independently with sympy subs."""
    Rv, tf = R.subs(values), DiscreteTF.from_expr(G)
    lhs = Rv.N + (Rv.M * (values[z] * sp.eye(R.n) - Rv.F).inv() * Rv.H if R.n else 0 * Rv.N)
    return sp.Matrix(lhs), sp.Matrix(tf.num_matrix.subs(values)) / tf.den.subs(values)


def assert_rejected_with_real_counterexample(R: Realization, G, result: RealizationCheck):
    assert not result and result.ok is False
    cex = result.counterexample
    assert cex is not None, result
    free = R.free_symbols | DiscreteTF.from_expr(G).free_symbols | {z}
    assert set(cex["values"]) == free
    assert all(isinstance(v, sp.Rational) for v in cex["values"].values())
    lhs, rhs = side_values(R, G, cex["values"])
    assert lhs != rhs
    as_matrix = sp.Matrix if R.shape != (1, 1) else lambda v: sp.Matrix([[v]])
    assert lhs == as_matrix(cex["realization"]) and rhs == as_matrix(cex["G"])


def perturbation_sites(R: Realization) -> list[tuple[str, int, int, str]]:
    """Every one-entry change of F, H, M, N: + 1, + t, and * t where the entry is nonzero."""
    sites = []
    for name in "FHMN":
        mat = getattr(R, name)
        for i in range(mat.rows):
            for j in range(mat.cols):
                changes = ("+1", "+t", "*t") if mat[i, j] != 0 else ("+1", "+t")
                sites += [(name, i, j, change) for change in changes]
    return sites


def perturbed(R: Realization, site: tuple[str, int, int, str]) -> Realization:
    name, i, j, change = site
    mat = getattr(R, name).as_mutable()
    mat[i, j] = {"+1": mat[i, j] + 1, "+t": mat[i, j] + t, "*t": mat[i, j] * t}[change]
    return Realization(**{**{k: getattr(R, k) for k in "FHMN"}, name: mat})


# ---------------------------------------------------------------- the paper's G2 and G3
@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("canonical", [controllable_canonical, observable_canonical])
def test_canonical_realizations_of_G2_pass_both_methods(canonical, method):
    result = check_realization(canonical(G2), G2, method, rng=1)
    assert result.ok and bool(result) and result.counterexample is None
    assert result.method == method and result.markov_count == 5


@pytest.mark.parametrize("method", METHODS)
def test_G2_realization_similar_by_symbolic_2x2_P_passes(method):
    R = controllable_canonical(G2).similar(symbolic_P(2))
    assert check_realization(R, DiscreteTF.from_expr(G2), method, rng=2).ok


@pytest.mark.parametrize("canonical", [controllable_canonical, observable_canonical])
def test_G3_realization_similar_by_symbolic_3x3_P_passes_both_methods(canonical):
    R = canonical(G3).similar(symbolic_P(3))
    exact = check_realization(R, G3)
    assert exact.ok and exact.error_bound == 0 and exact.method == "exact"
    randomized = check_realization(R, G3, "randomized", rng=3)
    assert randomized.ok and 0 < randomized.error_bound < Fraction(1, 2**64)
    assert randomized.rounds >= 1 and randomized.degree_bound > 0


CALL_BUDGET = 1_500_000  # about 120,000 calls


def test_G4_similar_by_fully_symbolic_4x4_P_is_proved_within_a_bounded_work():
    K = gain_symbols(4)
    eps = [
        epsilon_1,
        epsilon_3,
        sp.Symbol("epsilon_5", real=True),
        sp.Symbol("epsilon_7", real=True),
    ]
    G4 = K[0] / (C_1 * C_3) * sp.Mul(*(z - e for e in eps))
    G4 = DiscreteTF.from_expr(G4 / (z**4 - K[1] * z**3 - K[2] * z**2 - K[3] * z - K[4]))
    R = controllable_canonical(G4).similar(symbolic_P(4))
    with bounded(CALL_BUDGET):
        result = check_realization(R, G4)
    assert result.ok
    assert len(R.free_symbols | G4.free_symbols) == 16 + 5 + 2 + 4


@pytest.mark.slow
def test_every_single_entry_perturbation_of_a_symbolic_similar_G2_fails_both_methods():
    R = observable_canonical(G2).similar(symbolic_P(2))
    for site in perturbation_sites(R):
        bad = perturbed(R, site)
        for method in METHODS:
            result = check_realization(bad, G2, method, rng=4)
            assert result.method == method, site
            assert_rejected_with_real_counterexample(bad, G2, result)


@pytest.mark.slow
def test_perturbed_symbolic_3x3_similar_G3_fails_with_a_counterexample():
    R = controllable_canonical(G3).similar(symbolic_P(3))
    F = R.F.as_mutable()
    F[1, 2] = F[1, 2] * t
    bad = Realization(F, R.H, R.M, R.N)
    for method in METHODS:
        assert_rejected_with_real_counterexample(bad, G3, check_realization(bad, G3, method, rng=5))


def test_a_non_minimal_realization_is_proved_without_assuming_how_it_was_built():
    # an extra state that the output never sees: n = 3 > order 2
    R = controllable_canonical(G2)
    F = sp.diag(R.F, sp.Matrix([[t]]))
    R3 = Realization(F, sp.Matrix([*R.H, 1]), sp.Matrix([[*R.M, 0]]), R.N)
    for method in METHODS:
        result = check_realization(R3, G2, method, rng=6)
        assert result.ok and result.markov_count == 3 + 2 + 1


def test_a_difference_in_a_late_markov_parameter_is_found():
    R = controllable_canonical(1 / (z - 1))
    G = 1 / (z - 1) + 1 / z**5  # agrees on h_0 .. h_4
    for method in METHODS:
        result = check_realization(R, G, method, rng=7)
        assert "h_5" in result.details
        assert_rejected_with_real_counterexample(R, G, result)


def test_the_last_markov_parameter_n_plus_d_is_needed_and_checked():
    # T_R - G = 1/(chi d): e_0 .. e_{n+d-1} vanish, only e_{n+d} differs (the theorem is tight)
    chi, d = (z - 1) * (z - 2), (z - 3) * (z - 4)
    p = sp.invert(d, chi, z)  # p d = 1 mod chi
    R = controllable_canonical(p / chi)
    G = sp.cancel(p / chi - 1 / (chi * d))
    assert DiscreteTF.from_expr(G).order == 2
    for method in METHODS:
        result = check_realization(R, G, method, rng=18)
        assert "h_4" in result.details
        assert_rejected_with_real_counterexample(R, G, result)


@pytest.mark.slow
def test_rational_entries_not_from_a_similarity_are_cancelled_by_gcd():
    a, b = sp.symbols("a b")
    F = sp.Matrix([[1 / a, 1], [b / (a + 1), a / (b - 1)]])
    H, M = sp.Matrix([1 / b, 1]), sp.Matrix([[a, 1 / (a + b)]])
    G = sp.cancel((M * (z * sp.eye(2) - F).inv() * H)[0, 0])
    R = Realization(F, H, M, 0)
    for method in METHODS:
        assert check_realization(R, G, method, rng=19).ok
        bad = Realization(F, H, M, 1 / a)
        assert_rejected_with_real_counterexample(bad, G, check_realization(bad, G, method, rng=19))


# ---------------------------------------------------------------- MIMO
@pytest.mark.slow
def test_mimo_realization_passes_and_a_perturbed_one_fails():
    a, b = sp.symbols("a b")
    F = sp.Matrix([[a, 1, 0], [0, b, 1], [1, 0, 2]])
    H = sp.Matrix([[1, 0], [0, a], [1, 1]])
    M = sp.Matrix([[1, 0, b], [0, 1, 0]])
    N = sp.Matrix([[0, 1], [a, 0]])
    R = Realization(F, H, M, N)
    G = (M * (z * sp.eye(3) - F).inv() * H + N).applyfunc(sp.cancel)
    for method in METHODS:
        assert check_realization(R, G, method, rng=8).ok
    bad = Realization(F, H, M, N + sp.Matrix([[0, 0], [0, t]]))
    for method in METHODS:
        assert_rejected_with_real_counterexample(bad, G, check_realization(bad, G, method, rng=9))


def test_mimo_counterexample_sides_are_matrices():
    R = Realization([[0]], [[1, 0]], [[1], [1]], [[0, 0], [0, 0]])
    G = sp.Matrix([[1 / z, 0], [1 / z, 1 / z]])
    result = check_realization(R, G, rng=10)
    assert isinstance(result.counterexample["G"], sp.MatrixBase)
    assert_rejected_with_real_counterexample(R, G, result)


# ---------------------------------------------------------------- property test
coefficient = st.fractions(min_value=-4, max_value=4, max_denominator=3)


@st.composite
def similar_realizations(draw):
    n = draw(st.integers(1, 6))
    symbolic = draw(st.booleans())
    a = sp.symbols(f"a:{n}") if symbolic else [sp.Rational(draw(coefficient)) for _ in range(n)]
    c = [sp.Rational(draw(coefficient)) for _ in range(n + 1)]
    G = sum(c[i] * z**i for i in range(n + 1)) / (z**n - sum(a[i] * z**i for i in range(n)))
    canonical = draw(st.sampled_from([controllable_canonical, observable_canonical]))(G)
    assume(canonical.n > 0)  # numeric coefficients may cancel down to a constant
    P = sp.Matrix(canonical.n, canonical.n, lambda i, j: draw(st.integers(-3, 3)))
    assume(P.det() != 0)
    return G, canonical.similar(P)


@pytest.mark.slow
@given(similar_realizations(), st.integers(0, 2**32))
def test_property_similar_realizations_pass_and_perturbed_ones_fail(case, seed):
    G, R = case
    for method in METHODS:
        assert check_realization(R, G, method, rng=seed).ok
    sites = perturbation_sites(R)
    site = sites[seed % len(sites)]
    bad = perturbed(R, site)
    for method in METHODS:
        result = check_realization(bad, G, method, rng=seed)
        assert not result.ok, site
        assert_rejected_with_real_counterexample(bad, G, result)


# ---------------------------------------------------------------- python-control cross-check
def test_verdicts_agree_with_python_control_on_numeric_systems():
    rng = np.random.default_rng(0)
    points = [0.3 + 0.7j, -1.1 + 0.2j, 2.5]
    for n in (1, 3, 5):
        num = sum(int(v) * z**i for i, v in enumerate(rng.integers(-3, 4, n + 1)))
        den = z**n + sum(
            sp.Rational(int(v), 4) * z**i for i, v in enumerate(rng.integers(-3, 4, n))
        )
        G = DiscreteTF.from_expr(num / den)
        R0 = controllable_canonical(G)
        P = sp.Matrix(R0.n, R0.n, lambda i, j: int(rng.integers(-3, 4)) + (5 if i == j else 0))
        R = R0.similar(P)
        bad = perturbed(R, ("F", 0, 0, "+1"))  # still numeric
        for Rx, expected in ((R, True), (bad, False)):
            sys = control.ss2tf(Rx.to_control())
            close = all(
                np.allclose(sys(p), complex(G.expr.subs(z, p)), rtol=1e-9, atol=1e-12)
                for p in points
            )
            assert close is expected
            for method in METHODS:
                assert check_realization(Rx, G, method, rng=11).ok is expected


# ---------------------------------------------------------------- the result object
def test_error_bound_is_zero_for_exact_and_below_2_to_the_minus_64_for_randomized():
    R = controllable_canonical(G2)
    assert check_realization(R, G2, "exact").error_bound == 0
    result = check_realization(R, G2, "randomized", rng=12)
    assert 0 < result.error_bound < 2**-64
    assert result.sample_bits >= 62
    per_round = Fraction(result.degree_bound, 2 ** (result.sample_bits - 1))
    assert result.error_bound <= per_round**result.rounds


def test_randomized_without_symbols_is_exact():
    G = (z + 2) / (z**2 - z / 2)
    result = check_realization(controllable_canonical(G), G, "randomized")
    assert result.ok and result.error_bound == 0 and result.rounds == 1


def test_auto_proves_small_problems_and_rejects_with_a_counterexample():
    R = controllable_canonical(G2).similar(symbolic_P(2))
    assert check_realization(R, G2, "auto", rng=13).method == "exact"
    bad = check_realization(R, G2 * 2, "auto", rng=13)
    assert bad.method == "randomized" and not bad.ok and bad.counterexample


def test_seeds_make_the_randomized_test_reproducible():
    R = controllable_canonical(G2).similar(symbolic_P(2))
    bad = Realization(R.F, R.H, R.M * 2, R.N)
    runs = [check_realization(bad, G2, "randomized", rng=s) for s in (14, 14, random.Random(14))]
    assert runs[0].counterexample == runs[1].counterexample == runs[2].counterexample
    generator = check_realization(bad, G2, "randomized", rng=np.random.default_rng(14))
    assert not generator.ok


def test_result_displays_as_text_and_latex():
    R = controllable_canonical(G2)
    good = check_realization(R, G2)
    assert str(good).startswith("realizes G: proved exactly")
    assert good._repr_latex_().startswith("$\\displaystyle M(zI-F)^{-1}H + N = G(z)")
    rand = check_realization(R, G2, "randomized", rng=15)
    assert "error probability <= 2^-" in str(rand) and "randomized" in rand.latex()
    bad = check_realization(R, G2 + 1, rng=16)
    assert "feed-through" in bad.details and "z = " in str(bad)
    assert r"\ne" in bad.latex() and r"\epsilon_{1}" in bad.latex()


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "args, kwargs, error, name",
    [
        (("R", G2), {}, SymctlTypeError, "R:"),
        ((None, G2), {}, SymctlTypeError, "R:"),
        ((controllable_canonical(G2), "1/z"), {}, SymctlTypeError, "G:"),
        ((controllable_canonical(G2), sp.Matrix([[1 / z, 1 / z]])), {}, DimensionError, "G:"),
        ((controllable_canonical(G2), G2, "fast"), {}, ParameterError, "method:"),
        ((controllable_canonical(G2), G2, 3), {}, ParameterError, "method:"),
        ((controllable_canonical(G2), z**3 / (z - 1)), {}, ParameterError, "G:"),
        ((controllable_canonical(G2), G2), {"rng": "seed"}, SymctlTypeError, "rng:"),
        ((Realization([[sp.sqrt(2)]], [[1]], [[1]], 0), 1 / z), {}, ParameterError, "R: F[0, 0]"),
        (
            (Realization([[1]], [[sp.pi]], [[1]], 0), 1 / z),
            {"method": "randomized"},
            ParameterError,
            "R: H[0, 0]",
        ),
        ((Realization([[z]], [[1]], [[1]], 0), 1 / z), {}, ParameterError, "R:"),
        ((Realization([[1]], [[1]], [[1]], 0), 1 / (z - sp.exp(t))), {}, ParameterError, "G:"),
    ],
)
def test_bad_input_raises_symctl_errors_naming_the_argument(args, kwargs, error, name):
    with pytest.raises(error, match=name.replace("[", r"\[").replace("]", r"\]")):
        check_realization(*args, **kwargs)


def test_a_denominator_that_is_identically_zero_is_refused():
    zero = sp.Add(t * (t + 1), -(t**2), -t, evaluate=False)
    R = Realization([[1 / zero]], [[1]], [[1]], 0)
    for method in METHODS:
        with pytest.raises(ParameterError, match="R, G"):
            check_realization(R, 1 / (z - 1), method, rng=17)


def test_floats_are_taken_as_exact_binary_rationals():
    R = Realization([[0.5]], [[1]], [[2.0]], 0)
    assert check_realization(R, 2 / (z - sp.Rational(1, 2))).ok
    inexact = check_realization(Realization([[0.1]], [[1]], [[1]], 0), 1 / (z - sp.Rational(1, 10)))
    assert not inexact.ok and inexact.floating  # exactly, 0.1 is not 1/10
    assert inexact and inexact.max_relative_difference < 1e-16  # numerically it is
