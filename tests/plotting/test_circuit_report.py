"""The report's circuit figures: every neuron at its vertex, signs read at the simulations' values."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from symctl import (
    Circuit,
    DelayGraph,
    MuscleModel,
    Structure,
    augment,
    check_compatibility,
    circuit_firing,
    controllable_canonical,
    controller_tf,
    factor,
    lqr_gains,
)
from symctl.realization import draws
from symctl.report.figures import EPS_RANGE, _placed, _signs_at

GRAPH = DelayGraph.chain([1, 1])
GAINS = lqr_gains(augment(MuscleModel(), 1, 1))


@pytest.fixture(scope="module")
def simulated() -> Circuit:
    """The first simulated realization of the general circuit (numbers, no vertices)."""
    return circuit_firing("general", GAINS, count=1).circuits[0]


def record(structure) -> SimpleNamespace:
    return SimpleNamespace(compatibility=check_compatibility(structure, GRAPH))


def test_the_simulated_circuit_is_placed_by_its_own_witness(simulated):
    placed = _placed(simulated, record(simulated.structure), GRAPH)
    assert all(n.vertex is not None for n in placed.neurons)
    assert [n.vertex for n in placed.neurons] == [2, 2, 2, 2, 3]


def test_a_witness_that_does_not_carry_over_is_replaced_by_the_drawn_structures_own(simulated):
    # the witness of another structure (the controllable circuit's) misses signals of this one
    f = factor(controller_tf(2))
    other = record(Structure.from_factorization(f, controllable_canonical(f.G2)))
    assert not set(simulated.structure.blocks) <= set(other.compatibility.assignment.vertex_of)
    placed = _placed(simulated, other, GRAPH)
    assert all(n.vertex is not None for n in placed.neurons)


def test_an_incompatible_record_leaves_the_circuit_unplaced(simulated):
    ifp = SimpleNamespace(compatibility=SimpleNamespace(ok=False, assignment=None))
    assert _placed(simulated, ifp, GRAPH) is simulated


def test_signs_are_read_at_the_gains_c_one_and_the_epsilons_simulations_draw():
    f = factor(controller_tf(2))
    c = Circuit.from_structure(Structure.from_factorization(f, controllable_canonical(f.G2)))
    values = _signs_at(SimpleNamespace(gains=GAINS), c)
    assert set(values) == c.free_symbols
    assert {str(s): v for s, v in values.items() if str(s).startswith(("C", "eps"))} == {
        "C_1": 1,
        "C_3": 1,
        "epsilon_1": EPS_RANGE,
        "epsilon_3": EPS_RANGE,
    }
    # the range holds every epsilon circuit_firing draws
    drawn = draws.EPS_MAX / draws.EPS_GRID
    assert EPS_RANGE[0] <= -drawn and drawn <= EPS_RANGE[1]
