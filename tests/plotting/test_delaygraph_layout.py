"""Delay-graph drawings: the layout's geometry on the numbers, then the rendered figure and the report."""

from __future__ import annotations

import itertools
from pathlib import Path

import matplotlib.text
import numpy as np
import pytest
from matplotlib.colors import to_hex

import symctl
from symctl import DelayGraph, load_model
from symctl.errors import ParameterError, SymctlTypeError
from symctl.plotting import style
from symctl.plotting.delaygraph import delay_graph_plot, steps_text
from symctl.plotting.delaygraph_layout import (
    LABEL,
    MAX_DRAWN_VERTICES,
    delay_graph_layout,
)
from symctl.plotting.legibility import legibility

ROOT = Path(__file__).resolve().parents[2]
SPINAL = ROOT / "examples" / "spinal_transcortical.toml"
TWO_ROUTES = DelayGraph.from_edges(
    6, [(1, 2, 1), (2, 3, 1), (3, 6, 1), (1, 4, 2), (4, 5, 1), (5, 6, 1)]
)
CYCLES = DelayGraph.from_edges(4, [(1, 2, 1), (2, 3, 1), (3, 2, 2), (3, 4, 1), (4, 1, 3)])


def random_graph(n: int, seed: int, extra: int = 6, back: int = 2) -> DelayGraph:
    """Every vertex on a path from v1 to vN, plus random forward and backward edges."""
    rng = np.random.default_rng(seed)
    edges = {}
    for v in range(2, n):
        edges[int(rng.integers(1, v)), v] = int(rng.integers(0, 4))
        edges[v, int(rng.integers(v + 1, n + 1))] = int(rng.integers(0, 4))
    for _ in range(extra):
        a, b = sorted(int(x) for x in rng.choice(np.arange(1, n + 1), 2, replace=False))
        edges[a, b] = int(rng.integers(1, 4))
    for _ in range(back if n > 3 else 0):
        a, b = sorted(int(x) for x in rng.choice(np.arange(2, n), 2, replace=False))
        edges[b, a] = int(rng.integers(1, 4))
    if n == 2:
        edges = {(1, 2): 1}
    return DelayGraph.from_edges(n, [(a, b, d) for (a, b), d in edges.items()])


def spinal():
    return load_model(SPINAL)


GRAPHS = {
    "chain": DelayGraph.chain([1, 1]),
    "spinal": spinal().graph,
    "two_routes": TWO_ROUTES,
    "cycles": CYCLES,
    "random15": random_graph(15, 1),
}


def _boxes(lay):
    return {v: (*lay.pos[v], *lay.size[v]) for v in lay.pos}


def _inside(points, box, margin=0.0) -> np.ndarray:
    x, y, w, h = box
    return (np.abs(points[:, 0] - x) < w / 2 - margin) & (np.abs(points[:, 1] - y) < h / 2 - margin)


def _curve(bezier, k: int = 30) -> np.ndarray:
    ctrl = np.asarray(bezier)
    t = np.linspace(0, 1, k)[:, None]
    return np.vstack(
        [
            (1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * c1 + 3 * (1 - t) * t**2 * c2 + t**3 * p1
            for p0, c1, c2, p1 in (ctrl[s : s + 4] for s in range(0, len(ctrl) - 1, 3))
        ]
    )


# ------------------------------------------------------------------ layout
@pytest.mark.parametrize("name", GRAPHS)
def test_sensor_is_alone_leftmost_and_actuator_alone_rightmost(name):
    g = GRAPHS[name]
    lay = delay_graph_layout(g)
    xs = {v: p[0] for v, p in lay.pos.items()}
    assert lay.layer[1] == 0 and all(lay.layer[v] > 0 for v in range(2, g.n + 1))
    assert all(lay.layer[g.n] > lay.layer[v] for v in range(1, g.n))
    assert all(xs[1] < xs[v] < xs[g.n] for v in range(2, g.n))


@pytest.mark.parametrize("name", GRAPHS)
def test_every_edge_is_drawn_once_from_its_source_box_to_its_target_box(name):
    g = GRAPHS[name]
    lay = delay_graph_layout(g)
    assert [(r.source, r.target, r.delay) for r in lay.routes] == list(g.edges)
    boxes = _boxes(lay)
    for r in lay.routes:
        (x0, y0), (x1, y1) = r.points[0], r.points[-1]
        sx, sy, sw, sh = boxes[r.source]
        tx, ty, tw, th = boxes[r.target]
        # each end on its box's border (a few hundredths of an inch off, for the arrow tip)
        assert max(abs(x0 - sx) - sw / 2, abs(y0 - sy) - sh / 2) == pytest.approx(0.03, abs=1e-9)
        assert max(abs(x1 - tx) - tw / 2, abs(y1 - ty) - th / 2) == pytest.approx(0.03, abs=1e-9)
        assert r.bezier[0] == r.points[0] and r.bezier[-1] == r.points[-1]
        assert len(r.bezier) == 3 * (len(r.points) - 1) + 1


@pytest.mark.parametrize("name", GRAPHS)
def test_no_edge_runs_through_a_vertex_and_no_boxes_overlap(name):
    g = GRAPHS[name]
    lay = delay_graph_layout(g)
    boxes = _boxes(lay)
    for r in lay.routes:
        curve = _curve(r.bezier)
        for v, box in boxes.items():
            if v not in (r.source, r.target):
                assert not _inside(curve, box).any(), (r.source, r.target, v)
    for a, b in itertools.combinations(boxes.values(), 2):
        assert abs(a[0] - b[0]) >= (a[2] + b[2]) / 2 or abs(a[1] - b[1]) >= (a[3] + b[3]) / 2


@pytest.mark.parametrize("name", GRAPHS)
def test_labels_overlap_neither_each_other_nor_a_box(name):
    g = GRAPHS[name]
    lay = delay_graph_layout(g)
    w, h = LABEL
    labels = [(*r.label, w, h) for r in lay.routes]
    for a, b in itertools.combinations(labels, 2):
        assert abs(a[0] - b[0]) >= w - 1e-9 or abs(a[1] - b[1]) >= h - 1e-9, (a, b)
    for x, y, _, _ in labels:
        for bx, by, bw, bh in _boxes(lay).values():
            assert abs(x - bx) >= (w + bw) / 2 or abs(y - by) >= (h + bh) / 2


def test_chain_is_one_straight_row():
    lay = delay_graph_layout(DelayGraph.chain([1, 2, 1]))
    assert {p[1] for p in lay.pos.values()} == {0.0}
    assert all(len(r.points) == 2 and not r.back for r in lay.routes)


def test_parallel_pathways_lie_in_different_rows():
    lay = delay_graph_layout(TWO_ROUTES)
    y = {v: p[1] for v, p in lay.pos.items()}
    assert lay.layer[2] == lay.layer[4] and lay.layer[3] == lay.layer[5]
    assert y[2] == pytest.approx(y[3]) and y[4] == pytest.approx(y[5])  # each route straight
    assert abs(y[2] - y[4]) > 0.5  # and the two apart


def test_spinal_pathway_runs_beside_the_transcortical_one():
    m = spinal()
    lay = delay_graph_layout(m.graph)
    at = {name: k for k, name in enumerate(m.vertices, start=1)}
    receptor, spinal_, cortex, muscle = (at[k] for k in ("receptor", "spinal", "cortex", "muscle"))
    assert lay.layer[cortex] < lay.layer[spinal_] < lay.layer[muscle]
    direct = next(r for r in lay.routes if (r.source, r.target) == (receptor, spinal_))
    curve = _curve(direct.bezier)
    x, y, w, h = (*lay.pos[cortex], *lay.size[cortex])
    beside = curve[np.abs(curve[:, 0] - x) <= w / 2]  # in the cortex's column: level, below it
    assert len(beside) and np.ptp(beside[:, 1]) < 1e-9 and (beside[:, 1] < y - h / 2 - 0.2).all()


def test_a_graph_with_cycles_is_laid_out_with_its_back_edges_curved():
    lay = delay_graph_layout(CYCLES)
    back = {(r.source, r.target): r for r in lay.routes if r.back}
    assert set(back) == {(3, 2), (4, 1)}  # the two-cycle's second edge, the edge into v1
    for r in back.values():
        assert r.points[0][0] > r.points[-1][0]  # right to left
    # the two-cycle between v2 and v3: one edge humps above, the other below
    mid = (lay.pos[2][0] + lay.pos[3][0]) / 2
    height = {}
    for r in lay.routes:
        if {r.source, r.target} == {2, 3}:
            curve = _curve(r.bezier)
            height[r.source, r.target] = curve[np.argmin(np.abs(curve[:, 0] - mid)), 1]
    ys = (lay.pos[2][1] + lay.pos[3][1]) / 2
    assert height[2, 3] > ys + 0.2 and height[3, 2] < ys - 0.2


def test_edges_into_one_side_of_a_box_end_at_distinct_points():
    g = DelayGraph.from_edges(5, [(1, 2, 1), (1, 3, 1), (1, 4, 1), (2, 5, 1), (3, 5, 1), (4, 5, 1)])
    lay = delay_graph_layout(g)
    tips = [r.points[-1] for r in lay.routes if r.target == 5]
    starts = [r.points[0] for r in lay.routes if r.source == 1]
    for ends in (tips, starts):
        ys = sorted(y for _, y in ends)
        assert len(ys) == 3 and min(np.diff(ys)) >= 0.07  # an arrow head is 0.06 in wide


@pytest.mark.parametrize("seed", range(12))
@pytest.mark.parametrize("n", [2, 3, 8, 15, 30])
def test_random_graphs_are_laid_out(n, seed):
    g = random_graph(n, seed, extra=n // 2, back=n // 5)
    lay = delay_graph_layout(g)
    assert len(lay.routes) == len(g.edges) and set(lay.pos) == set(range(1, n + 1))
    x_lo, x_hi, y_lo, y_hi = lay.bounds
    for r in lay.routes:
        curve = _curve(r.bezier)
        assert (curve[:, 0] >= x_lo).all() and (curve[:, 0] <= x_hi).all()
        assert (curve[:, 1] >= y_lo).all() and (curve[:, 1] <= y_hi).all()


def test_layout_refuses_what_it_cannot_draw():
    with pytest.raises(SymctlTypeError, match="graph: expected a DelayGraph"):
        delay_graph_layout([[0, 1], [np.inf, 0]])
    big = DelayGraph.chain([1] * MAX_DRAWN_VERTICES)
    with pytest.raises(ParameterError, match=f"at most {MAX_DRAWN_VERTICES} vertices"):
        delay_graph_layout(big)
    dense = DelayGraph.from_edges(
        80, [(i, j, 1) for i, j in itertools.combinations(range(1, 81), 2)]
    )
    with pytest.raises(ParameterError, match="too many layers"):
        delay_graph_layout(dense)


# ------------------------------------------------------------------ figure
def _texts(fig) -> list[str]:
    return [t.get_text() for t in fig.axes[0].texts]


@pytest.mark.parametrize(
    "graph",
    [
        DelayGraph.chain([1, 1]),
        DelayGraph.chain([1] * 6),
        DelayGraph.from_edges(
            7,
            [(k, 5, 1) for k in range(1, 5)] + [(5, 6, 1), (5, 7, 1)],
            sensors=[1, 2, 3, 4],
            actuators=[6, 7],
        ),
    ],
)
def test_delay_graph_figures_are_legible_in_print_in_the_style_colours(graph):
    fig = graph.draw(title="A delay graph with a title as long as the one the report writes")
    assert legibility(fig), legibility(fig)
    boxes = {p.get_gid(): p for p in fig.axes[0].patches if p.get_gid().startswith("vertex:")}
    sensor, actuator = boxes[f"vertex:{graph.sensors[0]}"], boxes[f"vertex:{graph.actuators[0]}"]
    assert to_hex(sensor.get_edgecolor()) == to_hex(style.SENSOR)
    assert to_hex(actuator.get_edgecolor()) == to_hex(style.ACTUATOR)


def test_chain_figure_labels_each_edge_with_its_delay_in_steps():
    fig = DelayGraph.chain([1, 2]).draw()
    texts = _texts(fig)
    assert texts.count("1 step") == 1 and texts.count("2 steps") == 1
    assert {"v1", "v2", "v3", "sensor", "actuator"} <= set(texts)
    assert [p.get_gid() for p in fig.axes[0].patches] == [
        "edge:1-2",
        "edge:2-3",
        "vertex:1",
        "vertex:2",
        "vertex:3",
    ]
    assert steps_text(0) == "0 steps"


def test_spinal_figure_names_its_vertices_and_marks_sensor_and_actuator(tmp_path):
    m = spinal()
    fig = m.graph.draw(m.vertices, descriptions=m.vertex_descriptions, title="Stretch reflex")
    texts = _texts(fig)
    assert {"receptor", "spinal", "cortex", "muscle", "Stretch reflex"} <= set(texts)
    assert {"v1, sensor", "v4, actuator", "motor cortex", "muscle spindle afferents"} <= set(texts)
    assert texts.count("1 step") == 3 and texts.count("2 steps") == 1  # the 20 ms axon
    # legible at the size it is printed: no text under 6 pt, none overlapping, within the page
    assert legibility(fig), legibility(fig)
    fig.savefig(tmp_path / "spinal.png", dpi=100)
    assert (tmp_path / "spinal.png").stat().st_size > 1000


def test_random_graph_of_15_vertices_renders_at_print_size(tmp_path):
    fig = delay_graph_plot(random_graph(15, 3), title="fifteen")
    w, h = fig.get_size_inches()
    assert w < 30 and h < 12
    fig.savefig(tmp_path / "r15.svg")
    assert "fifteen" in (tmp_path / "r15.svg").read_text()


@pytest.mark.slow
def test_a_large_graph_still_renders():
    fig = delay_graph_plot(random_graph(60, 0, extra=20, back=5))
    assert len(fig.axes[0].patches) == 60 + len(random_graph(60, 0, extra=20, back=5).edges)


def test_names_are_shown_as_they_are_written():
    fig = delay_graph_plot(DelayGraph.chain([1]), ["$x$ cost", "b_c"])
    assert r"\$x\$ cost" in _texts(fig) and "b c" in _texts(fig)


def test_figure_refuses_bad_names_and_descriptions():
    g = DelayGraph.chain([1, 1])
    with pytest.raises(ParameterError, match="names: the graph has 3 vertices, got 2"):
        delay_graph_plot(g, ["a", "b"])
    with pytest.raises(SymctlTypeError, match="names: expected a sequence"):
        delay_graph_plot(g, "abc")
    with pytest.raises(SymctlTypeError, match=r"names\[1\]: expected a string"):
        delay_graph_plot(g, ["a", 2, "c"])
    with pytest.raises(SymctlTypeError, match="descriptions: expected a mapping"):
        delay_graph_plot(g, descriptions=["a"])
    with pytest.raises(SymctlTypeError, match="graph: expected a DelayGraph"):
        delay_graph_plot(np.zeros((2, 2)))


# ------------------------------------------------------------------ report
@pytest.fixture(scope="module")
def derived():
    return symctl.derive(str(SPINAL))


def test_report_draws_the_model_graph_right_after_the_closed_loop(derived, tmp_path):
    from symctl.report.figures import save
    from symctl.report.output import _OURS

    names = derived.figure_names()
    assert names[names.index("closed_loop") + 1] == "delay_graph"
    fig = derived.figure("delay_graph")
    texts = _texts(fig)
    assert "Delay graph of spinal_transcortical; one step is 10 ms" in texts
    assert {"receptor", "cortex", "v2", "spinal cord"} <= set(texts)
    written = save(fig, tmp_path, "delay_graph")
    assert [p.name for p in written] == ["delay_graph.pdf", "delay_graph.svg", "delay_graph.png"]
    assert all(_OURS.fullmatch(p.name) for p in written)


def test_report_circuits_mark_each_neuron_with_its_vertex_by_name(derived):
    for circuit in ("general", "controllable", "observable"):
        texts = _texts(derived.figure(f"circuit_{circuit}"))
        tags = [t for t in texts if t in {"v1", "v2", "v3", "v4"}]
        neurons = derived.circuits[circuit].circuit.n_neurons
        assert len(tags) == neurons, circuit  # the general one too (its numeric realization)
        said = next(t for t in texts if t.startswith("under a neuron: its vertex"))
        used = sorted(set(tags))
        names = {"v1": "receptor", "v2": "spinal", "v3": "cortex", "v4": "muscle"}
        assert said == "under a neuron: its vertex, " + ", ".join(f"{v} {names[v]}" for v in used)
    ifp = _texts(derived.figure("circuit_ifp"))
    assert not any(t in {"v1", "v2", "v3", "v4"} for t in ifp)  # not compatible: no vertex


def test_report_story_shows_the_graph_after_describing_it(derived):
    from symctl.report.document import Graphic, Heading
    from symctl.report.story import story

    blocks = story(derived, derived.figure_names())
    at = next(k for k, b in enumerate(blocks) if isinstance(b, Heading) and "Delay graph" in b.text)
    graphic = next(
        k for k, b in enumerate(blocks) if isinstance(b, Graphic) and b.name == "delay_graph"
    )
    assert graphic == at + 2  # the heading, the paragraph on the graph, then the figure


def test_one_vertex_per_channel_puts_every_sensor_first_and_every_actuator_last():
    g = DelayGraph.from_edges(
        7,
        [(k, 5, 1) for k in range(1, 5)] + [(5, 6, 1), (5, 7, 1)],
        sensors=[1, 2, 3, 4],
        actuators=[6, 7],
    )
    lay = delay_graph_layout(g)
    assert {lay.layer[v] for v in (1, 2, 3, 4)} == {0}
    assert lay.layer[6] == lay.layer[7] == max(lay.layer.values())
    fig = g.draw()
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert texts.count("sensor") == 4 and texts.count("actuator") == 2
    assert any("one per channel" in t for t in texts)
