"""Tracebacks and foreign exceptions, through the API.

Every bad argument (None, text, a negative, a huge int, a wrong shape, a wrong
type) is one of symctl's errors naming the argument, never a NumPy, SciPy or
Python exception (AttributeError, LinAlgError, OverflowError, ValueError...).
"""

import math

import numpy as np
import pytest

from symctl import (
    DelayGraph,
    DiscreteTF,
    MuscleModel,
    SymctlError,
    augment,
    circuit_firing,
    closed_loop_response,
    controller_tf,
    derive_paper,
    discretize,
    lqr_gains,
    nonlinear_check,
    prove_controller_tf,
    simulate_batch,
    z,
)
from symctl.design.plant import linearize

CLASS = "5"

GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
AUG = augment(MuscleModel(), 1, 1)
G = DiscreteTF.from_expr(1 / (z - 0.5))
ONE = np.ones((1, 1, 1))

CASES = [
    ("augment_plant_none", lambda: augment(None), "plant"),
    ("augment_delay_negative", lambda: augment(MuscleModel(), -1), "sensor_delay"),
    ("augment_delay_float", lambda: augment(MuscleModel(), 1.5), "sensor_delay"),
    ("augment_Q_shape", lambda: augment(MuscleModel(), Q=[[1, 2], [3, 4]]), "Q"),
    ("augment_R_negative", lambda: augment(MuscleModel(), R=-1), "R"),
    ("augment_Q_complex", lambda: augment(MuscleModel(), Q=1j), "Q"),
    ("augment_Q_huge_int", lambda: augment(MuscleModel(), Q=10**400), "Q"),
    ("lqr_system_none", lambda: lqr_gains(None), "system"),
    ("lqr_symbolic", lambda: lqr_gains(augment(MuscleModel().discrete_symbolic())), "plant"),
    ("lqr_Q_shape", lambda: lqr_gains(AUG, Q=[[1, 0], [0, 1]]), "Q"),
    ("lqr_Q_R_zero", lambda: lqr_gains(augment(MuscleModel(), 1, 1, Q=0, R=0)), "R"),
    ("controller_tf_gains_text", lambda: controller_tf(AUG, gains="x"), "gains"),
    ("controller_tf_negative", lambda: controller_tf(-1), "T"),
    ("controller_tf_text", lambda: controller_tf("2"), "T"),
    ("controller_tf_bool", lambda: controller_tf(True), "T"),
    ("prove_system_none", lambda: prove_controller_tf(None), "system"),
    ("prove_G_text", lambda: prove_controller_tf(AUG, "x"), "G"),
    ("prove_G_number", lambda: prove_controller_tf(AUG, 5), "G"),
    ("linearize_empty", lambda: linearize([], [], [], [], []), "x"),
    ("linearize_x_int", lambda: linearize("x", 5, "u", 1, 1), "x"),
    ("linearize_point_shape", lambda: linearize(["x"], ["x"], ["u"], [[1, 2]], 1), "x_eq"),
    (
        "linearize_flag_text",
        lambda: linearize("-x + u", "x", "u", 1, 1, check_equilibrium="x"),
        "check_equilibrium",
    ),
    ("linearize_u_eq_none", lambda: linearize("-x + u", "x", "u", 1, None), "u_eq"),
    ("discretize_empty", lambda: discretize([], [], 1), "a"),
    ("discretize_not_square", lambda: discretize([[1, 2]], 1, 1), "a"),
    ("discretize_b_rows", lambda: discretize([[1]], [[1], [2]], 1), "b"),
    ("discretize_ts_negative", lambda: discretize(1, 1, -1), "dt"),
    ("discretize_ts_huge", lambda: discretize(1, 1, 10**400), "dt|a"),
    ("discretize_complex", lambda: discretize([[1j]], [[1]], 1), "a"),
    ("muscle_tau_none", lambda: MuscleModel(tau=None), "tau"),
    ("muscle_tau_text", lambda: MuscleModel(tau="0.1"), "tau"),
    ("impulse_negative", lambda: G.impulse_response(-1), "steps"),
    ("impulse_text", lambda: G.impulse_response("5"), "steps"),
    ("impulse_bool", lambda: G.impulse_response(True), "steps"),
    ("impulse_improper", lambda: DiscreteTF(z**2, z + 1).impulse_response(3), "G"),
    ("lambdify_symbols_text", lambda: G.lambdify(symbols="x"), "symbols"),
    ("lambdify_modules_os", lambda: G.lambdify(modules="os"), "modules"),
    ("delay_graph_overflow", lambda: DelayGraph([[0, 10**400], [math.inf, 0]]), r"E\[1,2\]"),
    ("delay_graph_negative", lambda: DelayGraph([[0, -1], [math.inf, 0]]), r"E\[1,2\]"),
    ("delay_graph_3d", lambda: DelayGraph(np.zeros((3, 3, 3))), "E"),
    ("delay_graph_int", lambda: DelayGraph(5), "E"),
    ("chain_text", lambda: DelayGraph.chain(["a"]), r"delays\[0\]"),
    (
        "from_edges_overflow",
        lambda: DelayGraph.from_edges(3, [(1, 2, 10**400), (2, 3, 1)]),
        "edges",
    ),
    ("from_edges_not_iterable", lambda: DelayGraph.from_edges(3, 5), "edges"),
    ("firing_rng_negative", lambda: circuit_firing("ifp", GAINS, rng=-1), "rng"),
    ("firing_rng_text", lambda: circuit_firing("general", GAINS, rng="x"), "rng"),
    ("firing_rng_float", lambda: circuit_firing("general", GAINS, rng=1.5), "rng"),
    ("firing_kind_none", lambda: circuit_firing(None, GAINS), "kind"),
    ("firing_gains_none", lambda: circuit_firing("general", None), "gains"),
    ("firing_count_text", lambda: circuit_firing("general", GAINS, count="x"), "count"),
    ("firing_rtol_negative", lambda: circuit_firing("general", GAINS, rtol=-1), "rtol"),
    ("firing_plant_text", lambda: circuit_firing("general", GAINS, plant="x"), "plant"),
    ("nonlinear_rtol_negative", lambda: nonlinear_check(rtol=-1), "rtol"),
    ("nonlinear_rtol_text", lambda: nonlinear_check(rtol="x"), "rtol"),
    ("nonlinear_model_text", lambda: nonlinear_check(model="x"), "model"),
    ("nonlinear_controller_text", lambda: nonlinear_check(controller="x"), "controller"),
    ("nonlinear_amplitudes_text", lambda: nonlinear_check(amplitudes="abc"), "amplitudes"),
    ("nonlinear_steps_zero", lambda: nonlinear_check(steps=0), "steps"),
    ("nonlinear_start_negative", lambda: nonlinear_check(start=-1), "start"),
    ("closed_loop_gains_none", lambda: closed_loop_response(None), "gains|controller"),
    ("batch_text", lambda: simulate_batch(MuscleModel(), "a", "b", "c", "d"), "F"),
    (
        "batch_steps_text",
        lambda: simulate_batch(MuscleModel(), 0 * ONE, 0 * ONE, ONE, 0 * ONE, steps="x"),
        "steps",
    ),
    ("paper_progress_text", lambda: derive_paper(progress="x"), "progress"),
    ("paper_rng_negative", lambda: derive_paper(rng=-1), "rng"),
    ("paper_rng_float", lambda: derive_paper(rng=1.5), "rng"),
    ("paper_delay_negative", lambda: derive_paper(sensor_delay=-1), "sensor_delay"),
    ("paper_delay_float", lambda: derive_paper(sensor_delay=1.5), "sensor_delay"),
    ("paper_realizations_zero", lambda: derive_paper(realizations=0), "realizations"),
    ("paper_realizations_bool", lambda: derive_paper(realizations=True), "realizations"),
    ("paper_tau_text", lambda: derive_paper(tau="x"), "tau"),
    ("paper_Q_R_zero", lambda: derive_paper(Q=0, R=0), "R"),
]


@pytest.mark.parametrize(("call", "match"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_arguments_raise_a_symctl_error_naming_them(call, match):
    with pytest.raises(SymctlError, match=match):
        call()
