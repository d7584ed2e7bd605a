"""The layout of structure drawings, asserted on its numbers (nothing is rendered)."""

from __future__ import annotations

import itertools
import math

import pytest

from symctl import (
    controllable_canonical,
    controller_tf,
    factor,
    general_realization,
    ifp_structure,
    observable_canonical,
)
from symctl.compatibility.structure import Structure
from symctl.plotting.common import text_size
from symctl.plotting.structure_layout import SUM_R, structure_layout
from symctl.realization.realization import first_order_realization

F = factor(controller_tf(2))
G1 = first_order_realization(F.sensor_eps[0], F.sensor_C[0])
G3 = first_order_realization(F.actuator_eps[0], F.actuator_C[0])
TOL = 1e-9


def crude(text: str, points: float) -> tuple[float, float]:
    """A text measure without matplotlib: 0.6 em per character."""
    return 0.6 * points / 72 * len(text), points / 72


STRUCTURES = {
    "ifp1": ifp_structure(1),
    "ifp2": ifp_structure(2),
    "ifp4": ifp_structure(4),
    "ccr": Structure.series(G1, controllable_canonical(F.G2), G3),
    "ocr-state": Structure.from_factorization(F, observable_canonical(F.G2), "state"),
    "general": Structure.series(G1, general_realization(F.G2, [[2, 1], [1, 1]]), G3),
    "general-state": Structure.from_realization(
        general_realization(F.G2, [[2, 1], [1, 1]]), delays="state"
    ),
}
CASES = [
    pytest.param(S, m, id=f"{name}-{m.__name__}")
    for name, S in STRUCTURES.items()
    for m in (crude, text_size)
]


def on_boundary(point, layout, S, name) -> bool:
    """Whether ``point`` lies on the outline of the block ``name``."""
    (x, y), (cx, cy) = point, layout.positions[name]
    w, h = layout.sizes[name]
    if S.blocks[name].kind == "sum":
        return abs(math.hypot(x - cx, y - cy) - SUM_R) < TOL
    inside = abs(x - cx) <= w / 2 + TOL and abs(y - cy) <= h / 2 + TOL
    return inside and (abs(abs(x - cx) - w / 2) < TOL or abs(abs(y - cy) - h / 2) < TOL)


@pytest.mark.parametrize(("S", "measure"), CASES)
def test_every_wire_is_a_polyline_from_its_source_block_to_its_target_block(S, measure):
    layout = structure_layout(S, measure)
    drawn = sorted((w.source, w.target) for w in layout.wires)
    assert drawn == sorted({(a, b) for a, b, _ in S.wires()})
    delays = {(a, b): d for a, b, d in S.wires()}
    for wire in layout.wires:
        assert len(wire.points) >= 2
        assert on_boundary(wire.points[0], layout, S, wire.source), wire
        assert on_boundary(wire.points[-1], layout, S, wire.target), wire
        assert wire.delay == delays[(wire.source, wire.target)]
    for arrow in layout.arrows_in:
        assert on_boundary(arrow.points[-1], layout, S, arrow.target)
        assert arrow.points[0][0] < arrow.points[-1][0]  # from the left
    for arrow in layout.arrows_out:
        assert on_boundary(arrow.points[0], layout, S, arrow.source)
        assert arrow.points[0][0] < arrow.points[-1][0]  # to the right


@pytest.mark.parametrize(("S", "measure"), CASES)
def test_no_two_blocks_overlap(S, measure):
    layout = structure_layout(S, measure)
    assert set(layout.positions) == set(S.blocks)

    def box(n):
        (x, y), (w, h) = layout.positions[n], layout.sizes[n]
        return x - w / 2, x + w / 2, y - h / 2, y + h / 2

    for a, b in itertools.combinations(S.blocks, 2):
        ax0, ax1, ay0, ay1 = box(a)
        bx0, bx1, by0, by1 = box(b)
        assert ax1 <= bx0 or bx1 <= ax0 or ay1 <= by0 or by1 <= ay0, (a, b)


@pytest.mark.parametrize(("S", "measure"), CASES)
def test_layers_increase_along_forward_wires_and_the_drawing_fits_its_bounds(S, measure):
    layout = structure_layout(S, measure)
    forward = [w for w in layout.wires if not w.feedback]
    assert forward
    for wire in forward:
        assert layout.layers[wire.source] < layout.layers[wire.target], wire
    for n in S.inputs:
        assert layout.layers[n] == 0
    last = max(layout.layers.values())
    assert all(layout.layers[n] == last for n in S.outputs)
    x_lo, x_hi, y_lo, y_hi = layout.bounds
    for wire in (*layout.wires, *layout.arrows_in, *layout.arrows_out):
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


def test_series_parts_get_one_bar_each_in_signal_flow_order():
    layout = structure_layout(STRUCTURES["ccr"], crude)
    assert [p[0] for p in layout.parts] == ["G1", "G2", "G3"]
    assert all(x0 < x1 for _, x0, x1, _ in layout.parts)
    assert [p[1] for p in layout.parts] == sorted(p[1] for p in layout.parts)
    assert structure_layout(ifp_structure(2), crude).parts == ()


def test_layout_is_a_frozen_value():
    a = structure_layout(ifp_structure(2), crude)
    assert a == structure_layout(ifp_structure(2), crude)
    with pytest.raises(TypeError):
        a.positions["x"] = (0.0, 0.0)


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
