"""The layout of structure drawings, asserted on its numbers (nothing is rendered).

Block diagrams as a reviewer reads them: every wire orthogonal and ending in an arrow
head on its block, no two blocks on each other, every signal named once, each vertex's
signals in its band, each part in its frame.
"""

from __future__ import annotations

import functools
import itertools
import math

import pytest
import sympy as sp

from symctl import (
    augment,
    controllable_canonical,
    controller_tf,
    factor,
    general_realization,
    ifp_structure,
    observable_canonical,
)
from symctl.compatibility.check import check_compatibility
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.structure import Structure
from symctl.plotting.common import text_size
from symctl.plotting.structure_layout import ARROW, structure_layout
from symctl.plotting.structure_rows import structure_rows
from symctl.realization.realization import first_order_realization

F = factor(controller_tf(2))
F6 = factor(controller_tf(6), 3, 3)
G1 = first_order_realization(F.sensor_eps[0], F.sensor_C[0])
G3 = first_order_realization(F.actuator_eps[0], F.actuator_C[0])
P = sp.Matrix(2, 2, sp.symbols("p_11 p_12 p_21 p_22"))
TOL = 1e-9


def crude(text: str, points: float) -> tuple[float, float]:
    """A text measure without matplotlib: 0.6 em per character."""
    return 0.6 * points / 72 * len(text), points / 72


def _mimo():
    A = [[1, 0.01], [-0.4, 0.96]]
    B = [[0], [0.01]]
    f = factor(controller_tf(augment((A, B), 1, 1)), 1, 1)
    return Structure.from_factorization(f, observable_canonical(f.G2))


STRUCTURES = {
    "ifp1": ifp_structure(1),
    "ifp2": ifp_structure(2),
    "ifp4": ifp_structure(4),
    "ccr": Structure.from_factorization(F, controllable_canonical(F.G2)),
    "ocr": Structure.from_factorization(F, observable_canonical(F.G2)),
    "general": Structure.from_factorization(F, general_realization(F.G2, P)),
    "ocr-state": Structure.from_factorization(F, observable_canonical(F.G2), "state"),
    "general-state": Structure.from_realization(
        general_realization(F.G2, [[2, 1], [1, 1]]), delays="state"
    ),
    "ccr6": Structure.from_factorization(F6, controllable_canonical(F6.abbreviated())),
    "axon": Structure.from_realization(G1, input_delay=3),
    "parallel": Structure.parallel(Structure.series(G1, G3), G1),
    "mimo": _mimo(),
}
GRAPHS = {"ccr6": DelayGraph.chain([1] * 6), "axon": DelayGraph.chain([3])}


def _assignment(name):
    S = STRUCTURES[name]
    if name.startswith("ifp") or name in ("general-state", "parallel"):
        return None
    verdict = check_compatibility(S, GRAPHS.get(name, DelayGraph.chain([1, 1])))
    assert verdict.ok, name
    return verdict.assignment.vertex_of


ASSIGNMENTS = {name: _assignment(name) for name in STRUCTURES}
CASES = [
    pytest.param(name, m, id=f"{name}-{m.__name__}")
    for name in STRUCTURES
    for m in (crude, text_size)
]


@functools.cache
def layout_of(name, measure=text_size):
    return structure_layout(STRUCTURES[name], measure, vertex_of=ASSIGNMENTS[name])


def on_boundary(point, layout, S, name) -> bool:
    """Whether ``point`` lies on the outline of the block ``name``."""
    (x, y), (cx, cy) = point, layout.positions[name]
    w, h = layout.sizes[name]
    if S.blocks[name].kind in ("sum",) or (S.blocks[name].kind != "gain" and w < 0.1):
        return abs(math.hypot(x - cx, y - cy) - w / 2) < 1e-6
    inside = abs(x - cx) <= w / 2 + TOL and abs(y - cy) <= h / 2 + TOL
    return inside and (abs(abs(x - cx) - w / 2) < TOL or abs(abs(y - cy) - h / 2) < TOL)


def every_wire(layout):
    return (*layout.wires, *layout.arrows_in, *layout.arrows_out)


@pytest.mark.parametrize(("name", "measure"), CASES)
def test_every_wire_runs_from_its_source_block_to_its_target_block(name, measure):
    S = STRUCTURES[name]
    layout = layout_of(name, measure)
    drawn = sorted((w.source, w.target) for w in layout.wires)
    assert drawn == sorted({(a, b) for a, b, _ in S.wires()})
    delays = {(a, b): d for a, b, d in S.wires()}
    for wire in layout.wires:
        assert on_boundary(wire.points[0], layout, S, wire.source), wire
        assert on_boundary(wire.points[-1], layout, S, wire.target), wire
        assert wire.delay == delays[(wire.source, wire.target)]
    for arrow in layout.arrows_in:
        assert on_boundary(arrow.points[-1], layout, S, arrow.target)
        assert arrow.points[0][0] < arrow.points[-1][0]  # from the left
    for arrow in layout.arrows_out:
        assert on_boundary(arrow.points[0], layout, S, arrow.source)
        assert arrow.points[0][0] < arrow.points[-1][0]  # to the right


@pytest.mark.parametrize(("name", "measure"), CASES)
def test_wires_are_orthogonal_and_end_in_an_arrow_head_that_shows(name, measure):
    """No diagonal piece; the last piece of every wire is axis-parallel and longer than its head."""
    for wire in every_wire(layout_of(name, measure)):
        assert len(wire.points) >= 2, wire
        for (x0, y0), (x1, y1) in itertools.pairwise(wire.points):
            assert abs(x0 - x1) < TOL or abs(y0 - y1) < TOL, ("diagonal", wire)
        (x0, y0), (x1, y1) = wire.points[-2:]
        assert math.hypot(x1 - x0, y1 - y0) >= ARROW + 0.01, ("no room for its head", wire)


@pytest.mark.parametrize(("name", "measure"), CASES)
def test_no_two_blocks_overlap(name, measure):
    S = STRUCTURES[name]
    layout = layout_of(name, measure)
    assert set(layout.positions) == set(S.blocks)

    def box(n):
        (x, y), (w, h) = layout.positions[n], layout.sizes[n]
        return x - w / 2, x + w / 2, y - h / 2, y + h / 2

    for a, b in itertools.combinations(S.blocks, 2):
        ax0, ax1, ay0, ay1 = box(a)
        bx0, bx1, by0, by1 = box(b)
        assert ax1 <= bx0 or bx1 <= ax0 or ay1 <= by0 or by1 <= ay0, (a, b)


@pytest.mark.parametrize("name", STRUCTURES)
def test_every_signal_is_named_once_and_the_ends_are_labelled(name):
    """Three different signals were all called x1 (G1's, G2's and G3's state); the output had no label."""
    S = STRUCTURES[name]
    layout = layout_of(name)
    texts = [label.text for label in layout.names.values()] + [e.text for e in layout.ends]
    assert len(texts) == len(set(texts)), sorted(t for t in texts if texts.count(t) > 1)
    assert len(layout.ends) == len(S.inputs) + len(S.outputs)
    assert all(end.text.strip("$") for end in layout.ends)


def test_parts_get_their_superscript_in_every_name():
    layout = layout_of("ccr")
    names = {n: label.text for n, label in layout.names.items()}
    assert names["G1.x1"] == "$x^{\\mathrm{G1}}_{1}$" and names["G2.x1"] == "$x^{\\mathrm{G2}}_{1}$"


@pytest.mark.parametrize("name", [n for n in STRUCTURES if ASSIGNMENTS[n]])
def test_each_signal_sits_in_the_band_of_its_vertex(name):
    layout = layout_of(name)
    where = ASSIGNMENTS[name]
    assert {b.vertex for b in layout.bands} == set(where.values())
    for n, (x, y) in layout.positions.items():
        bands = [b for b in layout.bands if b.vertex == where[n]]
        assert any(
            b.x0 - TOL <= x <= b.x1 + TOL and b.y0 - TOL <= y <= b.y1 + TOL for b in bands
        ), n
    for a, b in itertools.combinations(layout.bands, 2):  # bands do not overlap
        assert a.x1 <= b.x0 + TOL or b.x1 <= a.x0 + TOL or a.y1 <= b.y0 or b.y1 <= a.y0


def test_vertex_bands_follow_the_delay_graph_and_the_dashed_wire_crosses_them():
    layout = layout_of("ocr")
    assert [(b.vertex, b.label) for b in layout.bands] == [
        (1, "$v_{1}$"),
        (2, "$v_{2}$"),
        (3, "$v_{3}$"),
    ]
    (w,) = [w for w in layout.wires if w.source == "G1.H"]
    v1, v2 = layout.bands[:2]
    assert w.delay == 1 and w.points[0][0] < v1.x1 <= v2.x0 + TOL < w.points[-1][0]


@pytest.mark.parametrize("name", ["ccr", "ocr", "general", "ocr-state", "mimo", "parallel"])
def test_each_part_is_framed_and_frames_do_not_overlap(name):
    S = STRUCTURES[name]
    layout = layout_of(name)
    frames = {f.part: f for f in layout.parts}
    assert set(frames) == {b.part for b in S.blocks.values()} - {""}
    shared = {n for n in S.inputs if len({b.part for b in S.blocks.values() if n in b.inputs}) > 1}
    for n, (x, y) in layout.positions.items():
        part = S.blocks[n].part
        if part and n not in shared:  # an input read by parallel pathways is no one's
            f = frames[part]
            assert f.x0 < x < f.x1 and f.y0 < y < f.y1, n
    for a, b in itertools.combinations(frames.values(), 2):
        assert a.x1 <= b.x0 or b.x1 <= a.x0 or a.y1 <= b.y0 or b.y1 <= a.y0, (a.part, b.part)


@pytest.mark.parametrize("name", STRUCTURES)
def test_layers_increase_along_forward_wires_and_the_drawing_fits_its_bounds(name):
    S = STRUCTURES[name]
    layout = layout_of(name, crude)
    forward = [w for w in layout.wires if not w.feedback]
    for wire in forward:
        assert layout.layers[wire.source] < layout.layers[wire.target], wire
    for n in S.inputs:
        assert layout.layers[n] == 0
    x_lo, x_hi, y_lo, y_hi = layout.bounds
    for wire in every_wire(layout):
        for x, y in wire.points:
            assert x_lo <= x <= x_hi and y_lo <= y <= y_hi


def test_feedback_arcs_carry_the_gains_that_feed_them():
    """The paper's IFP drawing: K1 and K2 sit on the arcs back into mu, off the rows."""
    layout = structure_layout(ifp_structure(2), crude)
    assert {"K1", "K2"}.isdisjoint(layout.layers)
    arcs = {(w.source, w.target) for w in layout.wires if w.feedback}
    assert arcs == {("gamma", "K1"), ("K1", "mu"), ("u", "K2"), ("K2", "mu")}
    y_rows = {layout.positions[n][1] for n in layout.layers}
    assert layout.positions["K1"][1] not in y_rows


def test_a_branching_signal_gets_a_junction_dot():
    layout = layout_of("ccr")
    (x, y) = layout.positions["G1.x1"]
    assert any(abs(yj - y) < TOL and xj > x for xj, yj in layout.junctions)


def test_a_long_structure_is_folded_into_rows_no_wider_than_the_page():
    """T = 6: about 30 columns, 13 inches in one row; folded between parts, each row <= 6.9 in."""
    S = STRUCTURES["ccr6"]
    one = structure_layout(S, text_size)
    assert one.bounds[1] - one.bounds[0] > 6.9
    rows = structure_rows(S, text_size, vertex_of=ASSIGNMENTS["ccr6"])
    assert rows.folded and rows.fits and len(rows.placed) >= 2
    drawn = {n for layout, _ in rows.placed for n in layout.positions}
    assert drawn == set(S.blocks)
    for layout, _ in rows.placed:
        assert layout.bounds[1] - layout.bounds[0] <= 6.9 + TOL
    # a row ends with the signal the next begins with, named alike at both ends
    for (a, _), (b, _) in itertools.pairwise(rows.placed):
        assert a.ends[-1].text in {e.text for e in b.ends}


def test_layout_is_a_frozen_value():
    a = structure_layout(ifp_structure(2), crude)
    assert a == structure_layout(ifp_structure(2), crude)
    with pytest.raises(TypeError):
        a.positions["x"] = (0.0, 0.0)


@pytest.mark.slow
def test_layout_never_imports_matplotlib():
    import subprocess
    import sys

    code = (
        "import sys; from symctl.compatibility.structure import ifp_structure; "
        "from symctl.plotting.structure_layout import structure_layout; "
        "structure_layout(ifp_structure(3), lambda t, p: (0.01 * p * len(t) / 72, p / 72)); "
        "print(sorted(m for m in sys.modules if m.startswith('matplotlib')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
