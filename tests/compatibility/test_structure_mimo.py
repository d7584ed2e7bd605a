"""MIMO G3 G2 G1: structures with several inputs and outputs, grouped-vertex compatibility, circuits."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symctl import (
    Circuit,
    DelayGraph,
    Structure,
    augment,
    check_compatibility,
    closed_loop_response,
    controllable_canonical,
    controller_tf,
    lqr_gains,
    observable_canonical,
    simulate_realization,
)
from symctl.realization.factorization import factor
from symctl.realization.realization import controller_realization, section_realizations

A = [[1, 0.01, 0, 0], [-0.4, 0.96, 0.005, -0.005], [0, 0, 0.6, 0], [0, 0, 0, 0.6]]
B = [[0, 0], [0.01, -0.01], [4.6, 0], [0, 4.6]]


@pytest.fixture(scope="module")
def system():
    return augment((A, B), 1, 1)


def test_each_stage_of_a_mimo_side_is_one_diagonal_realization(system):
    f = factor(controller_tf(system), 1, 1)
    first, last = section_realizations(f)
    assert len(first) == 1 and len(last) == 1
    assert first[0].F == sp.diag(*f.sensor_eps) and first[0].H == sp.diag(*f.sensor_C)
    assert last[0].shape == (2, 2) and first[0].shape == (4, 4)


@pytest.mark.parametrize("realize", [controllable_canonical, observable_canonical])
def test_a_mimo_structure_has_the_plants_signals_and_is_compatible_on_grouped_vertices(
    system, realize
):
    f = factor(controller_tf(system), 1, 1)
    S = Structure.from_factorization(f, realize(f.G2))
    assert len(S.inputs) == 4 and len(S.outputs) == 2
    verdict = check_compatibility(S, DelayGraph.chain([1, 1]))
    assert verdict.ok
    # every input sits at the sensor vertex, every output at the actuator vertex
    placed = verdict.assignment
    assert {placed.vertex_of[s] for s in S.inputs} == {1}
    assert {placed.vertex_of[s] for s in S.outputs} == {3}
    circuit = Circuit.from_structure(S, verdict)
    assert circuit.n_neurons > 0 and all(n.vertex in (1, 2, 3) for n in circuit.neurons)


def test_a_mimo_structure_is_incompatible_with_more_delay_than_its_relative_degree(system):
    f = factor(controller_tf(system), 1, 1)  # relative degree T = 2
    S = Structure.from_factorization(f, controllable_canonical(f.G2))
    assert not check_compatibility(S, DelayGraph.chain([1, 1, 1]))


@pytest.mark.parametrize("realize", [controllable_canonical, observable_canonical])
def test_the_mimo_circuit_closes_the_loop_of_the_optimal_controller(system, realize):
    gains = lqr_gains(system)
    G = controller_tf(gains)
    rng = np.random.default_rng(1)
    f = factor(G, 1, 1, eps=list(rng.uniform(-0.9, 0.9, 6).round(4)), C=1)
    R = controller_realization(f, realize(f.G2))
    assert R.shape == (2, 4)
    res = simulate_realization(system.plant, R, 1.0)
    ref = closed_loop_response(gains)
    scale = np.max(np.abs(ref.delta_r))
    np.testing.assert_allclose(res.delta_f, ref.delta_f, atol=1e-12 * max(1, scale))
    np.testing.assert_allclose(res.delta_r, ref.delta_r, atol=1e-12 * max(1, scale))
