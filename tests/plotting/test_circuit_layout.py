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
from symctl.plotting import layered
from symctl.plotting.circuit_layout import (
    DOT,
    MIN_RADIUS,
    Measures,
    circuit_layout,
)
from symctl.realization.realization import first_order_realization

F = factor(controller_tf(2))


def full(kind: str) -> Circuit:
    build = controllable_canonical if kind == "controllable" else observable_canonical
    return Circuit.from_structure(Structure.from_factorization(F, build(F.G2)))


def g2(kind: str) -> Circuit:
    build = controllable_canonical if kind == "controllable" else observable_canonical
    return Circuit.from_structure(Structure.from_realization(build(F.G2)))


def chain(n: int) -> Circuit:
    """``n`` first-order sections in series: a chain of ``n`` neurons."""
    return Circuit.from_structure(
        Structure.series(*(first_order_realization(0.5, k + 1) for k in range(n)))
    )


def obstacles(lay, m: Measures) -> layered.Obstacles:
    texts = lay.boxes(Measures(m.radius, m.name, m.tag, {}, m.end))
    nodes = list(lay.pos)
    return layered.Obstacles.of(
        [(lay.pos[n], lay.radius.get(n, DOT)) for n in nodes],
        list(texts.values()),
        nodes,
        [key for _, key in texts],
    )


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
    ys = {y for _, y in lay.pos.values()}
    assert len(ys) == 1  # a chain stays on one row
    xs = [lay.pos[n][0] for n in sorted(lay.column, key=lay.column.get)]
    assert xs == sorted(xs) and len(set(xs)) == len(xs)


def test_feedback_synapse_runs_below_and_forward_ones_go_right():
    lay = circuit_layout(g2("observable"))
    for arc in lay.arcs:
        if arc.synapse is None:
            continue
        forward = lay.column[arc.target] > lay.column[arc.source]
        assert forward or arc.height < 0, (arc.source, arc.target)
    (back,) = [a for a in lay.arcs if (a.source, a.target) == ("x2", "x1")]
    centre = lay.pos["x1"][1]
    assert max(p[1] for p in layered.bezier_points(back.path)) <= centre + 1e-9  # under the chain


def test_parallel_synapses_run_apart():
    lay = circuit_layout(g2("controllable"))
    pair = [a for a in lay.arcs if (a.source, a.target) == ("x2", "y")]
    assert len(pair) == 2 and abs(pair[0].height - pair[1].height) >= 0.13
    a, b = (layered.bezier_points(p.path)[24] for p in pair)  # their middles
    assert np.hypot(*(a - b)) >= 0.1


@pytest.mark.parametrize("big", [MIN_RADIUS, 0.5])
def test_an_arc_that_skips_a_neuron_clears_its_circle(big):
    c = g2("controllable")  # u -> y skips the neuron x2 on the same row
    lay = circuit_layout(c, {"x2": big, "y": MIN_RADIUS})
    (skip,) = [a for a in lay.arcs if (a.source, a.target) == ("u", "y")]
    d = np.hypot(*(layered.bezier_points(skip.path) - np.array(lay.pos["x2"])).T)
    assert d.min() >= big + layered.CLEAR - 1e-9


def test_bounds_hold_every_node_circle_curve_and_label():
    for c in (full("controllable"), full("observable"), g2("observable"), chain(14)):
        m = Measures.estimate(c)
        lay = circuit_layout(c, measures=m, width=6.9)
        x_lo, x_hi, y_lo, y_hi = lay.bounds
        for node, (x, y) in lay.pos.items():
            r = lay.radius.get(node, DOT)
            assert x_lo < x - r and x + r < x_hi and y_lo < y - r and y + r < y_hi, node
        for box in lay.boxes(m).values():
            assert x_lo <= box[0] and box[2] <= x_hi and y_lo <= box[1] and box[3] <= y_hi
        for arc in lay.arcs:
            p = arc.points()
            assert (p[:, 0] >= x_lo).all() and (p[:, 0] <= x_hi).all()
            assert (p[:, 1] >= y_lo).all() and (p[:, 1] <= y_hi).all()


def test_nodes_of_one_column_are_apart():
    lay = circuit_layout(full("observable"))
    assert len(set(lay.pos.values())) == len(lay.pos)


def test_output_wire_of_weight_one_has_no_label():
    lay = circuit_layout(Circuit.from_structure(ifp_structure(2)))
    out = lay.arcs[-1]
    assert out.target == ("out", "u") and out.synapse is not None and out.label is not None
    lay = circuit_layout(g2("controllable"))
    assert lay.arcs[-1].synapse is None and lay.arcs[-1].label is None


@pytest.mark.slow
def test_layout_does_not_import_matplotlib():
    code = (
        "import sys\n"
        "from symctl import Circuit, ifp_structure\n"
        "from symctl.plotting.circuit_layout import circuit_layout\n"
        "circuit_layout(Circuit.from_structure(ifp_structure(3)))\n"
        "assert 'matplotlib' not in sys.modules, 'matplotlib was imported'\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_a_long_chain_is_cut_into_bands_that_fit_the_width():
    c = chain(16)
    lay = circuit_layout(c, width=6.9)
    assert lay.fits and lay.width <= 6.9
    assert len(set(lay.band.values())) >= 2
    # bands are cut between neighbouring columns only, crossed by a wire each
    wires = [a for a in lay.arcs if a.wire]
    assert len(wires) == len(set(lay.band.values())) - 1
    for w in wires:
        assert lay.band[w.target] == lay.band[w.source] + 1
        assert lay.column[w.target] == lay.column[w.source] + 1
    assert circuit_layout(c).width > 6.9  # without a width: one band


def test_a_band_is_never_cut_off_to_hold_only_an_output():
    lay = circuit_layout(chain(16), width=6.9)
    (out,) = [n for n in lay.pos if isinstance(n, tuple)]
    neighbours = [n for n in lay.pos if lay.band[n] == lay.band[out] and n != out]
    assert any(not isinstance(n, tuple) for n in neighbours)


@pytest.mark.parametrize("width", [None, 6.9])
@pytest.mark.parametrize("kind", ["controllable", "observable"])
def test_no_curve_runs_through_a_circle_or_a_name(kind, width):
    c = full(kind)
    m = Measures.estimate(c)
    lay = circuit_layout(c, measures=m, width=width)
    assert lay.clear and lay.labelled
    around = obstacles(lay, m)
    for arc in lay.arcs:
        assert layered.hits(arc.points(), around, {arc.source, arc.target}) == 0, arc


@pytest.mark.slow
@pytest.mark.parametrize("realize", [controllable_canonical, observable_canonical])
def test_no_arc_of_a_mimo_circuit_runs_or_has_its_label_on_a_circle(mimo_factorization, realize):
    f = mimo_factorization
    c = Circuit.from_structure(Structure.from_factorization(f, realize(f.G2)))
    m = Measures.estimate(c)
    lay = circuit_layout(c, measures=m)
    for arc in lay.arcs:
        for n in c.neurons:
            if n.name in (arc.source, arc.target):
                continue
            centre, r = np.array(lay.pos[n.name]), lay.radius[n.name]
            if arc.label is not None:
                assert np.hypot(*(np.array(arc.label) - centre)) >= r, (arc.source, arc.target)
            if lay.clear:
                d = np.hypot(*(arc.points() - centre).T)
                assert d.min() >= r, (arc.source, arc.target, n.name)


def test_arrow_ends_at_one_neuron_are_spread_apart():
    # x2 -> y twice and x1 -> y: three arrow heads or bars on one small circle
    for c in (full("controllable"), full("observable"), g2("controllable")):
        lay = circuit_layout(c)
        for n in c.neurons:
            ends = [np.array(a.path[-1]) for a in lay.arcs if a.target == n.name]
            for i, p in enumerate(ends):
                for q in ends[i + 1 :]:
                    assert np.hypot(*(p - q)) >= 0.9 * layered.PORT_GAP, n.name


def test_measures_set_the_room_between_columns():
    c = full("controllable")
    m = Measures.estimate(c)
    wide = Measures(m.radius, m.name, m.tag, {s: (1.5, 0.13) for s in m.label}, m.end)
    a, b = circuit_layout(c, measures=m), circuit_layout(c, measures=wide)
    assert b.pos["G2.y"][0] - b.pos["G2.x2"][0] >= 1.5 + a.pos["G2.y"][0] - a.pos["G2.x2"][0] - 1
