"""The circuit 'pathways' of plants with several states or inputs: built, proved, simulated, told."""

from __future__ import annotations

from pathlib import Path

import pytest

from symctl import check_realization, derive
from symctl.compatibility.statespace import structure_realization
from symctl.report import model_story as MS
from symctl.report.document import Text

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

_GRAPH = """
[[delay_graph.vertices]]
name = "receptor"

[[delay_graph.vertices]]
name = "spinal"

[[delay_graph.vertices]]
name = "muscle"

[[delay_graph.edges]]
from = "receptor"
to = "spinal"
steps = 2

[[delay_graph.edges]]
from = "spinal"
to = "muscle"
steps = 1
"""

TWO_INPUTS = (
    """
[model]
name = "two_inputs"

[[states]]
name = "x1"
rhs = "-x1 + u1"

[[states]]
name = "x2"
rhs = "x1 - 2 * x2 + u2"

[[inputs]]
name = "u1"

[[inputs]]
name = "u2"

[sampling]
Ts = 0.01

[delays]
sensor = 2
actuator = 1

[circuits]
build = ["controllable"]
realizations = 2

[simulation]
steps = 30

[delay_graph]
sensor = "receptor"
actuator = "muscle"
"""
    + _GRAPH
)

# an unstable plant whose optimal controller has a pole at |z| = 1.36, one receptor per state
UNSTABLE_CHANNELS = """
[model]
name = "unstable_channels"

[discrete]
A = [[1.3, 0.1], [0, 1.1]]
B = [[0], [1]]

[sampling]
Ts = 0.01

[circuits]
build = ["observable"]
realizations = 2

[simulation]
steps = 30

[delay_graph]
sensor = ["s1", "s2"]
actuator = "muscle"

[[delay_graph.vertices]]
name = "s1"

[[delay_graph.vertices]]
name = "s2"

[[delay_graph.vertices]]
name = "muscle"

[[delay_graph.edges]]
from = "s1"
to = "muscle"
steps = 2

[[delay_graph.edges]]
from = "s2"
to = "muscle"
steps = 2
"""


def _text(blocks) -> str:
    return " ".join(b.text for b in blocks if isinstance(b, Text))


def _assert_pathways_realizes_G_and_the_optimal_loop(res):
    rec = res.circuits["pathways"]
    assert rec.compatibility.ok and rec.compatibility.assignment.is_compatible()
    # G3 G2 G1 = G for every section pole: the proof the pipeline records, and again here
    assert rec.realizes.ok and rec.realizes.method == "exact"
    G = res.factors.G.subs(res.gains.substitutions(exact=True))
    assert check_realization(structure_realization(rec.structure), G, "exact").ok
    assert rec.firing.count == res.spec.realizations and rec.firing.max_deviation < 1e-9
    assert res.to_dict()["circuits"]["pathways"]["realizes"] == {"ok": True, "method": "exact"}


@pytest.fixture(scope="module")
def forearm():
    return derive(EXAMPLES / "forearm.toml")


def test_the_forearm_gets_a_compatible_pathways_circuit_equal_to_G(forearm):
    res = forearm
    assert (res.plant.n, res.plant.m, res.G.shape) == (2, 1, (1, 2))
    assert (res.spec.sensor_delay, res.spec.actuator_delay) == (4, 2)
    # unit wires cannot cross the axons of 4 and 2 steps: only the construction fits
    assert not any(c.compatibility.ok for k, c in res.circuits.items() if k != "pathways")
    _assert_pathways_realizes_G_and_the_optimal_loop(res)
    (part,) = res.pathways.parts  # one G2 for both entries, along spindle -> spinal -> muscle
    assert (part.label, part.path, part.delays) == ("G", (1, 2, 3), (4, 2))
    rec = res.circuits["pathways"]
    assert {n.vertex for n in rec.circuit.neurons if n.part == "G2"} == {2}  # in the spinal cord
    assert rec.g2_neurons == sum(1 for n in rec.circuit.neurons if n.part == "G2") > 0


def test_a_two_input_plant_gets_its_pathways_circuit_with_one_shared_G2():
    res = derive(TWO_INPUTS)
    assert res.G.shape == (2, 2) and not res.circuits["controllable"].compatibility.ok
    _assert_pathways_realizes_G_and_the_optimal_loop(res)
    assert [p.label for p in res.pathways.parts] == ["G"]
    assert res.pathways.method == "theorem 3 (MIMO) + path construction"


def test_the_document_claims_the_pathways_circuit_only_when_it_was_built(forearm):
    built = _text(MS.theorem(forearm))
    assert "symctl built such a structure" in built and "the circuit 'pathways' below" in built
    assert "proved to realize $G$ (exact" in built
    # a compatible controller whose realizations' circuits fit: the construction exists, unbuilt
    oculomotor = derive(EXAMPLES / "oculomotor.toml")
    assert "pathways" not in oculomotor.circuits and oculomotor.pathways.ok
    told = _text(MS.theorem(oculomotor))
    assert "built" not in told.replace("builds its circuits", "")
    assert "such a structure exists" in told and "fit the graph already" in told


def test_a_construction_with_hidden_unstable_copies_is_left_out_with_its_reason():
    res = derive(UNSTABLE_CHANNELS)
    assert res.pathways.ok and len(res.pathways.parts) == 2  # one per receptor
    assert max(abs(res.G.poles())) > 1
    assert "pathways" not in res.circuits
    assert "left out is the circuit 'pathways'" in res.skipped
    told = _text(MS.theorem(res))
    assert "built such" not in told and "hidden unstable mode" in told


def test_a_mimo_controller_beyond_the_theorems_order_limit_is_a_stated_skip():
    from types import SimpleNamespace

    import sympy as sp

    from symctl import z
    from symctl.derivation.pipeline import MIMO_GENERAL_MAX_ORDER, _mimo_kinds
    from symctl.design.tf import DiscreteTF

    order = MIMO_GENERAL_MAX_ORDER + 1
    G = DiscreteTF.from_expr(sp.Matrix([[1 / z**order, 2 / z**order]]))
    kinds, why = _mimo_kinds(("controllable",), G, SimpleNamespace(n=2, m=1))
    assert kinds == ("controllable",)
    assert (
        f"its circuit 'pathways' (G has order {order}; built up to {MIMO_GENERAL_MAX_ORDER})" in why
    )


def test_the_forearm_draws_its_pathways_circuit(forearm):
    names = forearm.figure_names()
    assert {"structure_pathways", "circuit_pathways", "firing_pathways"} <= set(names)
    assert type(forearm.figure("structure_pathways")).__name__ == "Figure"
