"""Delay graphs: closure, validation, chains, values, a light import."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from symctl import ParameterError
from symctl.compatibility.delaygraph import DelayGraph
from symctl.errors import DimensionError

INF = math.inf
PAPER_E = [[0, 1, 2], [INF, 0, 1], [INF, INF, 0]]


def test_chain_is_the_papers_neuromuscular_graph():
    g = DelayGraph.chain([1, 1])
    assert g.E.tolist() == PAPER_E
    assert g.n == 3 and g.is_chain and g.chain_delays == (1, 1)
    assert g.edges == ((1, 2, 1), (2, 3, 1))
    assert r"\infty" in g.latex()


def test_matrix_and_edges_give_the_same_closure():
    from_matrix = DelayGraph(PAPER_E)
    assert from_matrix.edges == ((1, 2, 1), (2, 3, 1))
    g = DelayGraph.from_edges(3, [(1, 2, 1), (2, 3, 1), (1, 3, 5), (1, 2, 3)])
    assert g.E.tolist() == PAPER_E
    assert DelayGraph(np.array(PAPER_E)).E.tolist() == PAPER_E
    assert DelayGraph([[0, 1], [sp.oo, 0]]).E.tolist() == [[0, 1], [INF, 0]]


def test_chain_detection_allows_zero_steps_and_relabelled_vertices():
    assert DelayGraph.chain([1, 0, 2]).chain_delays == (1, 0, 2)
    g = DelayGraph.from_edges(4, [(1, 3, 1), (3, 2, 2), (2, 4, 1)])
    assert g.chain_order == ((1, 3, 2, 4), (0, 1, 3, 4))
    diamond = DelayGraph.from_edges(4, [(1, 2, 1), (1, 3, 1), (2, 4, 1), (3, 4, 1)])
    assert not diamond.is_chain and diamond.chain_delays is None


@pytest.mark.parametrize(
    ("E", "match"),
    [
        ([[0, -1], [INF, 0]], "integers"),
        ([[0, 1.5], [INF, 0]], "integers"),
        ([[0, True], [INF, 0]], "integers"),
        ([[1, 1], [INF, 0]], "diagonal"),
        ([[0, 1, 5], [INF, 0, 1], [INF, INF, 0]], "closure"),
        ([[0, INF, 1], [INF, 0, 1], [INF, INF, 0]], "source"),
        ([[0, 1, 1], [INF, 0, INF], [INF, INF, 0]], "sink"),
        ([[0]], "N >= 2"),
    ],
)
def test_bad_matrices_are_refused_with_the_reason(E, match):
    with pytest.raises(ParameterError, match=match):
        DelayGraph(E)


def test_bad_edges_and_shapes_are_refused():
    with pytest.raises(DimensionError, match="square"):
        DelayGraph([[0, 1], [0]])
    with pytest.raises(ParameterError, match="self-loop"):
        DelayGraph.from_edges(2, [(1, 1, 0), (1, 2, 1)])
    with pytest.raises(ParameterError, match="vertex"):
        DelayGraph.from_edges(2, [(1, 3, 1)])
    with pytest.raises(ParameterError, match="delay"):
        DelayGraph.from_edges(2, [(1, 2, -1)])
    with pytest.raises(ParameterError, match="n"):
        DelayGraph.from_edges(1, [])
    with pytest.raises(ParameterError, match="delays"):
        DelayGraph.chain([])
    with pytest.raises(ParameterError, match="edges"):
        DelayGraph.from_edges(2, [(1, 2)])


def test_delay_graph_import_loads_no_sympy_scipy_or_networkx():
    import subprocess
    import sys

    code = (
        "import sys, symctl.compatibility.delaygraph as d; d.DelayGraph.chain([1, 1]); "
        "print(sorted({m.split('.')[0] for m in sys.modules} & {'sympy', 'scipy', 'networkx'}))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_sympy_infinity_is_read_once_sympy_is_loaded():
    assert DelayGraph([[0, sp.Integer(1)], [sp.oo, 0]]).E.tolist() == [[0, 1], [INF, 0]]
    with pytest.raises(ParameterError, match="integers"):
        DelayGraph([[0, sp.Rational(1, 2)], [sp.oo, 0]])


def test_delay_graphs_are_values():
    a, b = DelayGraph.chain([1]), DelayGraph.chain([1])
    assert a == b and hash(a) == hash(b) and len({a, b}) == 1
    assert DelayGraph.chain([1, 1]) == DelayGraph(PAPER_E)
    assert DelayGraph.chain([1]) != DelayGraph.chain([2])
    assert DelayGraph.chain([1, 1]) != "E"
    with_extra_edge = DelayGraph.from_edges(3, [(1, 2, 1), (2, 3, 1), (1, 3, 5)])
    assert np.array_equal(with_extra_edge.E, DelayGraph(PAPER_E).E)
    assert with_extra_edge != DelayGraph(PAPER_E)  # the direct edges are part of the value
    with pytest.raises(ValueError, match="read-only"):
        a.E[0, 1] = 5
    with pytest.raises(AttributeError):
        a.E = np.zeros((2, 2))
