"""Delay assignments: both readings of Ẽ, the paper's assignment and violation, values."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import paper_assignment, random_graph, random_structure

from symctl import ParameterError, controllable_canonical, controller_tf, factor
from symctl.compatibility.assignment import DelayAssignment
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.structure import Structure, ifp_structure
from symctl.errors import SymctlTypeError

INF = math.inf
PAPER_E = [[0, 1, 2], [INF, 0, 1], [INF, INF, 0]]


def paper_controller() -> Structure:
    f = factor(controller_tf(2))
    return Structure.from_factorization(f, controllable_canonical(f.G2))


def test_papers_assignment_by_the_definition_and_as_printed():
    S = paper_controller()
    a = DelayAssignment(S, DelayGraph.chain([1, 1]), paper_assignment(S))
    assert a.E_tilde.tolist() == PAPER_E  # the definition's words: v1 -> v2 -> v3 takes 2
    printed = [[0, 1, INF], [INF, 0, 1], [INF, INF, 0]]
    assert a.e_tilde("direct").tolist() == printed  # the matrix printed in the paper
    assert a.is_compatible() and a.is_compatible("direct")
    assert "G1.u" in a.signals_at(1) and "G3.x1" in a.signals_at(3)
    assert r"\tilde E" in a.latex() and "v2:" in repr(a)


def test_ifp_assignment_shows_the_papers_violation():
    S = ifp_structure(2)
    vertex = {s: 3 for s in S.signals} | {"x": 1, "K0": 1}
    a = DelayAssignment(S, DelayGraph.chain([1, 1]), vertex)
    assert (1, 3, 0.0, 2.0) in a.violations()
    assert not a.is_compatible()


def test_assignment_validation():
    S = ifp_structure(1)
    g = DelayGraph.chain([1])
    good = {"x": 1, "K0": 1, "mu": 2, "K1": 2, "u": 2}
    DelayAssignment(S, g, good)
    with pytest.raises(ParameterError, match="missing"):
        DelayAssignment(S, g, {"x": 1})
    with pytest.raises(ParameterError, match="not a signal"):
        DelayAssignment(S, g, good | {"w": 1})
    with pytest.raises(ParameterError, match="v1"):
        DelayAssignment(S, g, good | {"x": 2})
    with pytest.raises(ParameterError, match="v2"):
        DelayAssignment(S, g, good | {"u": 1})
    with pytest.raises(ParameterError, match="vertex"):
        DelayAssignment(S, g, good | {"mu": 3})
    with pytest.raises(SymctlTypeError, match="graph"):
        DelayAssignment(S, [[0, 1], [0, 0]], good)
    with pytest.raises(ParameterError, match="reading"):
        DelayAssignment(S, g, good).e_tilde("slowest")


def test_both_readings_give_the_same_verdict_on_shortest_path_closures():
    """Thousands of random assignments of random structures on random closed graphs."""
    rng = np.random.default_rng(7)
    checked = differ = 0
    while checked < 1500:
        S = random_structure(rng)
        g = random_graph(rng, chain=bool(rng.integers(2)))
        vertex = {s: int(rng.integers(1, g.n + 1)) for s in S.signals}
        vertex.update({s: 1 for s in S.inputs})
        if set(S.inputs) & set(S.outputs):
            continue
        vertex.update({s: g.n for s in S.outputs})
        a = DelayAssignment(S, g, vertex)
        assert a.is_compatible("fastest") == a.is_compatible("direct")
        differ += not np.array_equal(a.E_tilde, a.e_tilde("direct"))
        checked += 1
    assert differ > 0  # the readings do differ as matrices, only not in verdict


def test_assignments_are_values():
    S = ifp_structure(1)
    good = {"x": 1, "K0": 1, "mu": 2, "K1": 2, "u": 2}
    a = DelayAssignment(S, DelayGraph.chain([1]), good)
    b = DelayAssignment(ifp_structure(1), DelayGraph.chain([1]), dict(reversed(good.items())))
    assert a == b and hash(a) == hash(b)
    assert a != DelayAssignment(S, DelayGraph.chain([1]), good | {"mu": 1})
    assert a != DelayAssignment(S, DelayGraph.chain([2]), good)
    with pytest.raises(TypeError):
        a.vertex_of["mu"] = 1
    with pytest.raises(ValueError, match="read-only"):
        a.E_tilde[0, 1] = 0
