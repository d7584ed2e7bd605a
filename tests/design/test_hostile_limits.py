"""Hostile sizes: every size has a limit, refused before any work starts.

Each case must raise a symctl error naming the argument within a few seconds
(a count of function calls turns a hang into a failure), where before it ran for minutes or ended
in a MemoryError.
"""

import itertools

import numpy as np
import pytest
from helpers import bounded
from sympy import Symbol

from symctl import (
    DelayGraph,
    DiscreteTF,
    MuscleModel,
    ParameterError,
    augment,
    circuit_firing,
    closed_loop_response,
    controller_tf,
    derive_paper,
    discretize,
    lqr_gains,
    nonlinear_check,
    open_loop_response,
    pulse,
    z,
)
from symctl.design.plant import linearize
from symctl.errors import DimensionError

CLASS = "3"

GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
G = DiscreteTF.from_expr(1 / (z - 0.5))
SQUARE = np.zeros((1001, 1001))

CASES = [
    (
        "augment_delay_1e22",
        lambda: augment(MuscleModel(), 10**22, 0),
        "sensor_delay, actuator_delay",
    ),
    ("augment_delay_501", lambda: augment(MuscleModel(), 250, 251), "at most 500"),
    ("augment_states", lambda: augment(([[0] * 40] * 40, [[1] * 30] * 40), 40, 0), "states"),
    ("controller_tf_1e5", lambda: controller_tf(10**5), "T: must be an integer <= 500"),
    ("impulse_1e9", lambda: G.impulse_response(10**9), "steps: must be an integer <= 1000000"),
    ("chain_3000", lambda: DelayGraph.chain([1] * 3000), "delays: a delay graph has at most 1000"),
    ("chain_endless", lambda: DelayGraph.chain(itertools.count()), "at most 1000 vertices"),
    ("chain_delay_1e13", lambda: DelayGraph.chain([10**13]), r"delays\[0\]"),
    ("matrix_1001", lambda: DelayGraph(SQUARE), "E: a delay graph has at most 1000"),
    ("from_edges_1e9", lambda: DelayGraph.from_edges(10**9, []), "n: a delay graph has at most"),
    ("from_edges_endless", lambda: DelayGraph.from_edges(3, itertools.repeat((1, 2, 1))), "edges"),
    ("firing_count_1e7", lambda: circuit_firing("general", GAINS, count=10**7), "count"),
    ("firing_steps_1e9", lambda: circuit_firing("general", GAINS, steps=10**9), "steps"),
    (
        "nonlinear_steps_1e9",
        lambda: nonlinear_check(steps=10**9),
        "steps: must be an integer <= 5000",
    ),
    (
        "nonlinear_amplitudes",
        lambda: nonlinear_check(amplitudes=np.ones(20_000), steps=2),
        "amplitudes",
    ),
    ("closed_loop_steps", lambda: closed_loop_response(GAINS, steps=10**12), "steps"),
    ("open_loop_steps", lambda: open_loop_response(steps=10**12), "steps"),
    ("pulse_size", lambda: pulse(size=10**9), "size"),
    ("ts_over_tau_1e4", lambda: MuscleModel(dt=1e4), "dt, tau: dt/tau must be in"),
    ("tau_1e-8", lambda: MuscleModel(tau=1e-8), "dt/tau"),
    ("tau_1e-6", lambda: MuscleModel(tau=1e-6), "dt/tau"),
    ("tau_huge", lambda: MuscleModel(tau=1e9), "dt/tau"),
    ("r_bar_1e300", lambda: MuscleModel(r_bar=1e300), "r_bar"),
    (
        "discretize_symbolic_5",
        lambda: discretize(np.array([[z] * 4] * 4), np.ones((4, 1)), 1),
        "a, b",
    ),
    (
        "discretize_1001",
        lambda: discretize(np.eye(1001), np.ones((1001, 1)), 1),
        "a: at most 1000 rows",
    ),
    (
        "linearize_endless",
        lambda: linearize("x", (Symbol(f"x{i}") for i in itertools.count()), "u", 1, 1),
        "x",
    ),
    ("paper_sensor_delay_50", lambda: derive_paper(sensor_delay=50), "at most 20 steps"),
    ("paper_delay_1e23", lambda: derive_paper(sensor_delay=99999999999999999999999), "at most 20"),
    ("paper_realizations_1e7", lambda: derive_paper(realizations=10**7), "realizations"),
    ("paper_tau_1e-8", lambda: derive_paper(tau=1e-8), "dt/tau"),
    ("paper_ts_1e4", lambda: derive_paper(dt=1e4), "dt/tau"),
]


@pytest.mark.parametrize(("call", "match"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_sizes_beyond_their_limit_are_refused_at_once_by_name(call, match):
    with bounded(), pytest.raises((ParameterError, DimensionError), match=match):
        call()


@pytest.mark.slow
def test_the_stiff_nonlinear_check_at_the_smallest_admitted_tau_takes_seconds():
    model = MuscleModel(tau=0.01 / 700)  # Ts/tau = 700, the largest admitted
    with bounded(15_000_000):  # about 1.5 million calls
        chk = nonlinear_check(model)
    assert np.all(np.isfinite(chk.f_nonlinear))


@pytest.mark.slow
def test_a_chain_at_the_vertex_limit_is_still_fast():
    with bounded(100_000_000):  # about 24 million calls
        g = DelayGraph.chain([1] * 999)
        assert DelayGraph(g.E).edges == g.edges


@pytest.mark.slow
def test_limits_keep_valid_sizes_working():
    assert controller_tf(500).relative_degree == 500
    assert G.impulse_response(10**6).shape == (10**6, 1, 1)
    assert augment(MuscleModel(), 250, 250).T == 500
