"""MIMO G3 G2 G1: structures with several inputs and outputs, grouped-vertex compatibility, circuits."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symctl import (
    Circuit,
    DelayGraph,
    DimensionError,
    ParameterError,
    Structure,
    augment,
    brute_force_compatibility,
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


# ---------------------------------------------------------------- one vertex per channel
def _per_channel_graph(axon: int = 1) -> DelayGraph:
    """Four receptors (one per measured state), a spinal and a cortical vertex, two muscles.

    v1..v4 receptors -> v5 spinal (1 step) -> v7, v8 muscles (1 step); beside it
    v1..v4 -> v6 cortex (1 step) -> v5 spinal (``axon`` steps).
    """
    edges = [(k, 5, 1) for k in range(1, 5)] + [(k, 6, 1) for k in range(1, 5)]
    edges += [(6, 5, axon), (5, 7, 1), (5, 8, 1)]
    return DelayGraph.from_edges(8, edges, sensors=[1, 2, 3, 4], actuators=[7, 8])


def test_one_sensor_vertex_per_measured_signal_and_one_actuator_vertex_per_input(system):
    f = factor(controller_tf(system), 1, 1)
    S = Structure.from_factorization(f, controllable_canonical(f.G2))
    g = _per_channel_graph()
    verdict = check_compatibility(S, g)
    assert verdict.ok and verdict.assignment.is_compatible()
    placed = verdict.assignment.vertex_of
    assert [placed[s] for s in S.inputs] == [1, 2, 3, 4]
    assert [placed[s] for s in S.outputs] == [7, 8]
    # the G2 neurons sit at the spinal vertex, where every channel meets
    circuit = Circuit.from_structure(S, verdict)
    assert {n.vertex for n in circuit.neurons if n.name.startswith("G2.")} == {5}
    # two measured signals on one receptor is a different graph, and no longer fits 4 inputs
    pair = DelayGraph.from_edges(4, [(1, 3, 1), (2, 3, 1), (3, 4, 1)], sensors=[1, 2])
    with pytest.raises(DimensionError, match="graph: the delay graph has 2 sensor vertices"):
        check_compatibility(S, pair)
    wrong = DelayGraph.from_edges(
        8,
        [(k, 5, 1) for k in range(1, 5)] + [(5, 7, 1), (5, 8, 1), (5, 6, 1)],
        sensors=[1, 2, 3, 4],
        actuators=[6, 7, 8],
    )
    with pytest.raises(DimensionError, match="3 actuator vertices"):
        check_compatibility(S, wrong)


def test_per_channel_pins_agree_with_brute_force_on_small_structures():
    from symctl import Realization

    R = Realization(
        [[sp.Rational(1, 2), 0], [1, 0]], [[1, 0], [0, 1]], [[1, 0], [0, 1]], [[0, 0], [0, 0]]
    )
    S = Structure.from_realization(R)
    for sensors, actuators, edges in (
        ([1, 2], [3, 4], [(1, 3, 1), (2, 4, 1), (1, 4, 1), (2, 3, 0)]),
        ([1, 2], [4], [(1, 3, 1), (2, 3, 1), (3, 4, 0)]),
        ([1], [3, 4], [(1, 2, 0), (2, 3, 1), (2, 4, 2)]),
    ):
        g = DelayGraph.from_edges(4, edges, sensors=sensors, actuators=actuators)
        fast, slow = check_compatibility(S, g), brute_force_compatibility(S, g)
        assert fast.ok == slow.ok


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"sensors": [0]}, "sensors: vertices are integers 1..3"),
        ({"sensors": [1, 1]}, "appears twice"),
        ({"actuators": "3"}, "actuators: expected vertices"),
        ({"actuators": []}, "expected 1 to"),
        ({"sensors": [2]}, "no sensor vertex reaches v1"),
        ({"actuators": [2]}, "v3 reaches no actuator vertex"),
    ],
)
def test_sensor_and_actuator_vertices_are_checked(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        DelayGraph.from_edges(3, [(1, 2, 1), (2, 3, 1)], **kwargs)
