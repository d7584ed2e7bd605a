"""Circuit layout: the geometry of a circuit drawing, checked on the numbers without rendering."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from symctl import (
    Circuit,
    Structure,
    controllable_canonical,
    controller_tf,
    factor,
    ifp_structure,
    observable_canonical,
)
from symctl.plotting.circuit_layout import MIN_RADIUS, XSTEP, YSTEP, circuit_layout

F = factor(controller_tf(2))


def full(kind: str) -> Circuit:
    build = controllable_canonical if kind == "controllable" else observable_canonical
    return Circuit.from_structure(Structure.from_factorization(F, build(F.G2)))


def g2(kind: str) -> Circuit:
    build = controllable_canonical if kind == "controllable" else observable_canonical
    return Circuit.from_structure(Structure.from_realization(build(F.G2)))


def test_series_circuit_runs_left_to_right_input_first_output_last():
    lay = circuit_layout(full("controllable"))
    assert lay.column == {
        "G1.u": 0,
        "G1.x1": 1,
        "G2.x2": 2,
        "G2.y": 3,
        "G3.x1": 4,
        ("out", "G3.x1"): 5,
    }
    assert all(y == 0 for _, y in lay.pos.values())  # a chain stays on one row
    assert {k: x / XSTEP for k, (x, _) in lay.pos.items()} == lay.column


def test_feedback_synapse_runs_below_and_forward_ones_go_right():
    c = g2("observable")
    lay = circuit_layout(c)
    for arc in lay.arcs:
        if arc.synapse is None:
            continue
        forward = lay.column[arc.target] > lay.column[arc.source]
        assert forward or arc.height < 0, (arc.source, arc.target)
    back = [a for a in lay.arcs if a.source == "x2" and a.target == "x1"]
    assert [a.height for a in back] == [-0.55]


def test_parallel_synapses_fan_out_symmetrically():
    lay = circuit_layout(g2("controllable"))
    heights = sorted(a.height for a in lay.arcs if (a.source, a.target) == ("x2", "y"))
    assert heights == pytest.approx([-0.2, 0.2])


@pytest.mark.parametrize("big", [MIN_RADIUS, 0.8])
def test_an_arc_that_skips_a_neuron_clears_its_circle(big):
    c = g2("controllable")  # u -> y skips the neuron x2 on the same row
    lay = circuit_layout(c, {"x2": big, "y": MIN_RADIUS})
    (skip,) = [a for a in lay.arcs if (a.source, a.target) == ("u", "y")]
    assert abs(skip.height) >= big + 0.5
    # the label sits at the top of the bulge, above the skipped circle
    x2, y2 = lay.pos["x2"]
    lx, ly = skip.label
    assert abs(lx - x2) < 1e-9 and ly - y2 > big


def test_bounds_hold_every_node_circle_and_label():
    for c in (full("controllable"), full("observable"), g2("observable")):
        lay = circuit_layout(c)
        x_lo, x_hi, y_lo, y_hi = lay.bounds
        for node, (x, y) in lay.pos.items():
            r = lay.radius.get(node, 0.0)
            assert x_lo < x - r and x + r < x_hi and y_lo < y - r and y + r < y_hi, node
        for arc in lay.arcs:
            if arc.label is not None:
                assert x_lo < arc.label[0] < x_hi and y_lo < arc.label[1] < y_hi


def test_nodes_of_one_column_are_a_row_apart():
    lay = circuit_layout(full("observable"))
    by_column: dict[int, list[float]] = {}
    for node, k in lay.column.items():
        by_column.setdefault(k, []).append(lay.pos[node][1])
    for ys in by_column.values():
        gaps = np.diff(sorted(ys))
        assert np.all(gaps >= YSTEP - 1e-12)
    assert len(set(lay.pos.values())) == len(lay.pos)


def test_output_wire_of_weight_one_has_no_label():
    lay = circuit_layout(Circuit.from_structure(ifp_structure(2)))
    out = lay.arcs[-1]
    assert out.target == ("out", "u") and out.synapse is not None and out.label is not None
    lay = circuit_layout(g2("controllable"))
    assert lay.arcs[-1].synapse is None and lay.arcs[-1].label is None


def test_layout_does_not_import_matplotlib():
    code = (
        "import sys\n"
        "from symctl import Circuit, ifp_structure\n"
        "from symctl.plotting.circuit_layout import circuit_layout\n"
        "circuit_layout(Circuit.from_structure(ifp_structure(3)))\n"
        "assert 'matplotlib' not in sys.modules, 'matplotlib was imported'\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


@pytest.mark.parametrize("realize", [controllable_canonical, observable_canonical])
def test_no_arc_of_a_mimo_circuit_runs_or_has_its_label_on_a_circle(mimo_factorization, realize):
    f = mimo_factorization
    c = Circuit.from_structure(Structure.from_factorization(f, realize(f.G2)))
    lay = circuit_layout(c)
    for arc in lay.arcs:
        for n in c.neurons:
            if n.name in (arc.source, arc.target):
                continue
            centre, r = np.array(lay.pos[n.name]), lay.radius[n.name]
            if arc.label is not None:
                assert np.hypot(*(np.array(arc.label) - centre)) >= r, (arc.source, arc.target)
            if arc.height == 0:  # a straight arc passes no circle
                a, b = np.array(lay.pos[arc.source]), np.array(lay.pos[arc.target])
                t = np.clip(np.dot(centre - a, b - a) / np.dot(b - a, b - a), 0, 1)
                assert np.hypot(*(a + t * (b - a) - centre)) >= r, (arc.source, arc.target, n.name)
