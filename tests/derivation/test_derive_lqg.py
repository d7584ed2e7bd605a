"""derive on a model that measures some states through noise: the LQG compensator end to end."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from symctl import closed_loop_response, derive, load_results
from symctl.design.kalman import lqg_tf, prove_lqg_tf
from symctl.neural.compensator import lqg_realization

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "forearm_lqg.toml"


@pytest.fixture(scope="module")
def res():
    return derive(EXAMPLE)


def test_the_angle_only_forearm_gets_the_proved_lqg_compensator_with_K_and_L_symbolic(res):
    s, kf = res.system, res.kalman
    assert kf is not None and res.proved and res.reduction is None
    names = {str(x) for x in res.G_symbolic.free_symbols}
    assert {"L_1", "L_2"} <= names and any(n.startswith("K_") for n in names)
    assert prove_lqg_tf(s, kf.C, res.G_symbolic)
    numeric = lqg_tf(s, kf.C, res.gains, kf)
    assert res.G.shape == (1, 1) and res.G.relative_degree == s.T + 1
    assert np.allclose(res.G.impulse_response(40), numeric.impulse_response(40), atol=1e-12)


def test_its_factors_multiply_back_to_the_compensator_exactly(res):
    assert res.verified and res.factors.verify()
    assert res.factors.G == res.G_symbolic


def test_the_closed_loop_poles_are_the_regulators_and_the_estimators(res):
    s, kf = res.system, res.kalman
    A = np.array(s.plant.A.evalf(), dtype=float)
    B = np.array(s.plant.B.evalf(), dtype=float)
    C = np.array(kf.C.evalf(), dtype=float)
    F, H, M, N = lqg_realization(res.gains, kf).numeric()
    loop = np.block([[A + B @ N @ C, B @ M], [H @ C, F]])
    expected = [*res.gains.poles, *np.linalg.eigvals(A - kf.L[: s.n] @ C)]
    assert len(expected) == len(loop)
    # characteristic polynomials: the poles at 0 split by the root of the rounding error
    assert np.allclose(np.poly(loop), np.poly(expected), rtol=0, atol=1e-9)


def test_every_circuit_behaves_as_the_compensators_loop_under_the_noise(res):
    assert set(res.circuits) == {"general", "controllable", "observable", "pathways"}
    for rec in res.circuits.values():
        assert rec.firing.max_deviation <= 1e-9
        assert rec.firing.draws == 100 and rec.firing.delta_f_sd is not None
    assert "IFP circuit" in res.skipped and "atlas" in res.skipped


def test_the_noise_free_mean_is_the_compensators_loop_without_noise(res):
    kf = res.kalman
    quiet = closed_loop_response(
        lqg_realization(res.gains, kf),
        res.plant,
        disturbance=res.spec.disturbance_signal(),
        steps=res.spec.steps,
        outputs=kf.C,
    )
    se = res.closed_loop.delta_f_sd / np.sqrt(res.closed_loop.draws)
    assert np.all(np.abs(res.closed_loop.delta_f - quiet.delta_f) <= 5 * se + 1e-12)


def test_the_measured_variance_confirms_the_lyapunov_prediction(res):
    mc = res.variance
    assert mc.count == 4000 and mc.z_score < 4
    assert np.all(np.diag(mc.predicted_covariance) > 0)


def test_results_json_round_trips_with_its_estimation_entry(res, tmp_path):
    res.write(tmp_path / "out", figures=False, pdf=False)
    saved = load_results(tmp_path / "out" / "results.json")
    assert sp.expand(saved.G_symbolic.num - res.G_symbolic.num) == 0
    assert saved.G_symbolic.den == res.G_symbolic.den
    assert saved.derive() is res
    est = saved.data["estimation"]
    assert est["form"] == "predictor" and est["L_names"] == ["L_1", "L_2"]
    assert np.allclose(est["L"], res.kalman.L[:2])
    assert len(est["closed_loop_poles"]) == len(res.gains.poles) + 2
    assert set(est["variance"]) >= {"predicted", "measured", "standard_error", "cost"}


def test_the_document_says_what_the_controller_measures_and_estimates(res, tmp_path):
    res.write(tmp_path / "out", figures=False, pdf=False)
    text = (tmp_path / "out" / "report.md").read_text()
    assert "## What the controller measures and estimates" in text
    assert "Kalman gain" in text and "measured | predicted" in text


def test_the_new_keywords_refuse_bad_input_naming_the_argument(res):
    from symctl import DimensionError, ParameterError, SymctlTypeError, circuit_firing

    kf, R = res.kalman, lqg_realization(res.gains, res.kalman)
    with pytest.raises(DimensionError, match="outputs"):
        closed_loop_response(R, res.plant, outputs=[[1, 0, 0]])
    with pytest.raises(SymctlTypeError, match="controller"):
        closed_loop_response(res.gains, res.plant, outputs=kf.C)
    with pytest.raises(DimensionError, match="2 outputs"):  # a compensator of one output, fed two
        closed_loop_response(R, res.plant, outputs=[[1, 0], [0, 1]])
    from symctl import MuscleModel, augment, kalman_gains, lqr_gains

    muscle = augment(MuscleModel(), 1, 1)
    with pytest.raises(ParameterError, match="kind"):
        circuit_firing("ifp", lqr_gains(muscle), kalman=kalman_gains(muscle, [[1]]))
    with pytest.raises(SymctlTypeError, match="kalman"):
        lqg_realization(res.gains, res.gains)


def test_a_two_input_compensator_is_derived_and_proved_with_its_gains_exact_values():
    text = (EXAMPLE.parent / "antagonist.toml").read_text()
    outputs = (
        '[[outputs]]\nname = "a"\nstate = "theta"\n\n[[outputs]]\nname = "f"\nstate = "f_flex"\n\n'
    )
    text = text[: text.index("[delay_graph]")].replace("[sampling]", outputs + "[sampling]")
    res = derive(text)
    s, kf = res.system, res.kalman
    assert res.G.shape == (2, 2) and not res.G.free_symbols and res.proved and res.verified
    proof = prove_lqg_tf(s, kf.C, res.G, gains=res.gains, kalman=kf)
    assert proof and "exact gains" in proof.method
    assert not prove_lqg_tf(s, kf.C, 2 * res.G, gains=res.gains, kalman=kf)
    numeric = lqg_tf(s, kf.C, res.gains, kf)
    assert np.allclose(res.G.impulse_response(30), numeric.impulse_response(30), atol=1e-9)
    assert any("exact values" in note for note in res.spec.notes)
    assert set(res.circuits) == {"controllable", "observable"} and res.nonlinear is not None
    for rec in res.circuits.values():
        assert rec.firing.max_deviation <= 1e-9


def test_the_papers_muscle_measured_through_noise_derives_every_circuit_but_the_ifp():
    text = (EXAMPLE.parent / "muscle.toml").read_text() + "\n[noise]\nprocess = 1.0\nsensor = 0.1\n"
    res = derive(text)
    assert res.kalman is not None and res.proved and res.verified
    assert set(res.circuits) == {"general", "controllable", "observable"}
    assert all(c.firing.max_deviation <= 1e-9 for c in res.circuits.values())
    assert res.atlas is None and "IFP circuit" in res.skipped
    assert res.nonlinear is not None and res.nonlinear.relative_deviation[0] < 1e-3
