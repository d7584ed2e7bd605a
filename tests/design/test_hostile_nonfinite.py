"""Silent NaN/inf and misleading messages.

Non-finite values are refused where they enter, a numerical failure names the
argument that caused it, and no NumPy/SciPy warning escapes (warnings are errors here).
"""

import math
import warnings

import numpy as np
import pytest
import sympy as sp

from symctl import (
    DelayGraph,
    DiscreteTF,
    MuscleModel,
    NotStabilizableError,
    ParameterError,
    augment,
    closed_loop_response,
    derive_paper,
    discretize,
    lqr_gains,
    nonlinear_check,
    open_loop_response,
    z,
)
from symctl.design.plant import linearize

CLASS = "4"

GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
AUG = augment(MuscleModel(), 1, 1)
nan, inf = math.nan, math.inf

CASES = [
    ("discretize_1e308", lambda: discretize([[1e308]], [[1]], 1.0), "a, dt: exp"),
    ("discretize_800", lambda: discretize([[800]], [[1]], 1), "a, dt: exp"),
    ("discretize_nan", lambda: discretize([[nan]], [[1]], 1), "a"),
    ("discretize_ts_nan", lambda: discretize(1, 1, nan), "dt"),
    ("tf_nan_den", lambda: DiscreteTF(1, sp.nan * z + 1), "num/den: must be finite"),
    ("tf_oo_den", lambda: DiscreteTF(1, z + sp.oo), "num/den"),
    ("tf_zoo_num", lambda: DiscreteTF(sp.zoo, z), "num/den"),
    ("tf_float_inf", lambda: DiscreteTF(1, z + sp.Float("inf")), "num/den"),
    ("tf_nan_num", lambda: DiscreteTF(sp.nan, z + 1), "num/den"),
    (
        "impulse_unstable",
        lambda: DiscreteTF.from_expr(1 / (z - 10)).impulse_response(400),
        "steps: the impulse response overflows",
    ),
    (
        "impulse_coefficient_1e400",
        lambda: DiscreteTF(1, z + 10**400).impulse_response(3),
        "G: coefficients",
    ),
    ("poles_coefficient_1e400", lambda: DiscreteTF(1, z + 10**400).poles(), "G: poles"),
    ("muscle_f_max_1e308", lambda: MuscleModel(f_max=1e308), "f_max"),
    ("muscle_f_max_1e400", lambda: MuscleModel(f_max=10**400), "f_max"),
    ("muscle_f_max_inf", lambda: MuscleModel(f_max=inf), "f_max"),
    ("muscle_tau_1e-300", lambda: MuscleModel(tau=1e-300), "tau"),
    ("muscle_tau_nan", lambda: MuscleModel(tau=nan), "tau"),
    ("muscle_ts_1e400", lambda: MuscleModel(dt=10**400), "dt"),
    ("muscle_r_bar_-1000", lambda: MuscleModel(r_bar=-1000), "r_bar"),
    (
        "augment_Q_1e300",
        lambda: augment(MuscleModel(), 1, 1, Q=1e300),
        "Q: entries must be at most",
    ),
    ("augment_R_1e300", lambda: augment(MuscleModel(), 1, 1, R=1e300), "R: entries"),
    ("augment_Q_nan", lambda: augment(MuscleModel(), Q=nan), "Q"),
    ("lqr_Q_1e300", lambda: lqr_gains(AUG, Q=1e300), "Q: entries"),
    ("lqr_R_1e400", lambda: lqr_gains(AUG, R=10**400), "R"),
    ("lqr_plant_1e200", lambda: lqr_gains(augment(([[0.5]], [[1e200]]), 1, 1)), "plant"),
    ("linearize_point_nan", lambda: linearize("-x + u", "x", "u", nan, nan), "x_eq"),
    ("delay_graph_nan", lambda: DelayGraph([[0, nan], [inf, 0]]), r"E\[1,2\]"),
    ("delay_graph_1e400", lambda: DelayGraph([[0, 10**400], [inf, 0]]), r"E\[1,2\]"),
    ("nonlinear_amplitude_nan", lambda: nonlinear_check(amplitudes=[nan]), "amplitudes"),
    ("nonlinear_rtol_nan", lambda: nonlinear_check(rtol=nan), "rtol"),
    (
        "closed_loop_disturbance_nan",
        lambda: closed_loop_response(GAINS, disturbance=[nan] * 50),
        "disturbance",
    ),
    ("open_loop_pulse_inf", lambda: open_loop_response(pulse=inf), "pulse"),
    ("paper_f_max_1e308", lambda: derive_paper(f_max=1e308), "f_max"),
    ("paper_Q_1e300", lambda: derive_paper(Q=1e300), "Q"),
    ("paper_tau_1e-300", lambda: derive_paper(tau=1e-300), "tau"),
    ("paper_Q_nan", lambda: derive_paper(Q=[[nan]]), "Q"),
]


@pytest.mark.parametrize(("call", "match"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_non_finite_values_are_refused_by_name_without_numpy_warnings(call, match):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a NumPy/SciPy RuntimeWarning fails the test
        with pytest.raises(ParameterError, match=match):
            call()


def test_q_and_r_zero_is_not_a_linalg_error_but_names_r():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(NotStabilizableError, match="R"):
            lqr_gains(augment(MuscleModel(), 1, 1, Q=0, R=0))


def test_a_stable_impulse_response_over_a_million_steps_stays_finite():
    h = DiscreteTF.from_expr(1 / (z - 0.5)).impulse_response(10**6)
    assert np.all(np.isfinite(h)) and h[1, 0, 0] == 1.0 and h[3, 0, 0] == 0.25


def test_the_impulse_response_matches_the_exact_markov_parameters():
    G = DiscreteTF.from_expr((3 * z + 1) / (z**3 - z / 2 + sp.Rational(1, 7)))
    exact = np.array([np.array(h.evalf(), dtype=float) for h in G.markov(40)])
    np.testing.assert_allclose(G.impulse_response(40), exact, rtol=1e-13, atol=1e-15)
