"""The layered layout core: layers, bends, order, rows and curves, on the numbers."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from symctl.plotting import layered


def random_dag(n: int, seed: int) -> tuple[list[int], dict[int, list[int]], list[tuple[int, int]]]:
    """Nodes 0..n-1 in topological order, each with one to three earlier predecessors."""
    rng = np.random.default_rng(seed)
    preds = {0: []}
    for v in range(1, n):
        preds[v] = sorted({int(p) for p in rng.integers(0, v, size=rng.integers(1, 4))})
    edges = [(p, v) for v in range(n) for p in preds[v]]
    return list(range(n)), preds, edges


def layered_graph(n: int, seed: int):
    nodes, preds, edges = random_dag(n, seed)
    layer = layered.longest_path(nodes, preds, first={0})
    chains, node_layer, up, down = layered.split(edges, layer)
    layers = [[] for _ in range(max(node_layer.values()) + 1)]
    for node in node_layer:
        layers[node_layer[node]].append(node)
    return edges, layer, chains, node_layer, up, down, layers


@pytest.mark.parametrize("seed", range(5))
def test_every_edge_runs_right_and_the_last_nodes_share_the_last_layer(seed):
    nodes, preds, edges = random_dag(12, seed)
    sinks = [v for v in nodes if not any(a == v for a, _ in edges)]
    layer = layered.longest_path(nodes, preds, first={0}, last=sinks, floor=1)
    assert layer[0] == 0 and all(layer[v] >= 1 for v in nodes[1:])
    assert all(layer[a] < layer[b] for a, b in edges)
    assert {layer[v] for v in sinks} == {max(layer.values())}


@pytest.mark.parametrize("seed", range(5))
def test_split_gives_each_edge_one_bend_in_every_layer_it_crosses(seed):
    edges, layer, chains, node_layer, _, down, _ = layered_graph(12, seed)
    for (a, b), chain in zip(edges, chains, strict=True):
        assert chain[0] == a and chain[-1] == b
        assert [node_layer[v] for v in chain] == list(range(layer[a], layer[b] + 1))
    assert all(node_layer[q] == node_layer[p] + 1 for p in down for q in down[p])


@pytest.mark.parametrize("seed", range(5))
def test_order_keeps_every_layer_and_never_adds_crossings(seed):
    *_, up, down, layers = layered_graph(15, seed)
    best = layered.order(layers, up, down)
    assert [sorted(map(str, o)) for o in best] == [sorted(map(str, o)) for o in layers]
    assert layered.crossings(best, down) <= layered.crossings(layers, down)


def test_crossings_counts_each_pair_of_edges_that_cross_once():
    down = {"a": ["d", "e"], "b": ["c"]}
    assert layered.crossings([["a", "b"], ["c", "d", "e"]], down) == 2
    assert layered.crossings([["b", "a"], ["c", "d", "e"]], down) == 0


def test_isotonic_keeps_the_gaps_and_is_the_plain_targets_when_they_allow():
    spaced = layered.isotonic([0.0, 2.0, 5.0], [1.0, 1.0, 1.0], [1.0, 1.0])
    assert spaced.tolist() == [0.0, 2.0, 5.0]
    packed = layered.isotonic([0.0, 0.0, 0.0], [1.0, 1.0, 4.0], [0.5, 0.5])
    assert np.allclose(np.diff(packed), 0.5)
    assert abs(np.average(packed, weights=[1, 1, 4])) < 1e-12  # the weighted mean stays


@pytest.mark.parametrize("integer", [True, False])
def test_rows_of_a_column_are_one_apart_at_least_top_first(integer):
    *_, up, down, layers = layered_graph(15, 3)
    columns = dict(enumerate(layers))
    row = layered.rows(columns, up, down, integer=integer)
    for nodes in columns.values():
        ys = [row[n] for n in nodes]
        assert all(a - b >= 1 - 1e-9 for a, b in itertools.pairwise(ys))
        assert all(float(y).is_integer() for y in ys) or not integer


def test_positions_keep_the_order_and_the_gaps():
    *_, up, down, layers = layered_graph(15, 4)
    gaps = [[0.3] * (len(o) - 1) for o in layers]
    at = layered.positions(layers, up, down, gaps, lambda a, b: 1.0)
    for o in layers:
        assert all(at[q] - at[p] >= 0.3 - 1e-9 for p, q in itertools.pairwise(o))


def test_at_x_finds_the_curve_at_that_abscissa_and_clamps_beyond_its_ends():
    curve = [(0.0, 0.0), *layered.line((0, 0), (1, 1)), *layered.line((1, 1), (3, 1))]
    assert np.allclose(layered.at_x(curve, 0.5), (0.5, 0.5))
    assert np.allclose(layered.at_x(curve, 2.0), (2.0, 1.0))
    assert np.allclose(layered.at_x(curve, 9.0), (3.0, 1.0))
    points = layered.bezier_points(curve, np.linspace(0, 1, 5))
    assert points.shape == (10, 2) and np.allclose(points[[0, -1]], [(0, 0), (3, 1)])


def _hits_one_by_one(points, obstacles, ends=()):
    """:func:`layered.hits` as it was written for one curve: the reference of the batched one."""
    own = np.array([k in ends for k in obstacles.keys], bool)
    keep = np.ones(len(points), bool)
    for k in np.flatnonzero(own):
        keep &= np.hypot(*(points - obstacles.centres[k]).T) > obstacles.radii[k] + 1e-9
    pts = points[keep]
    if not len(pts):
        return 0
    (x0, y0), (x1, y1) = pts.min(axis=0), pts.max(axis=0)
    bad, inside = np.zeros(len(pts), bool), 0
    if len(obstacles.radii):
        c, r = obstacles.centres, obstacles.radii + layered.CLEAR
        near = ~own & (c[:, 0] > x0 - r) & (c[:, 0] < x1 + r) & (c[:, 1] > y0 - r)
        near &= c[:, 1] < y1 + r
        if near.any():
            d = np.hypot(pts[:, None, 0] - c[None, near, 0], pts[:, None, 1] - c[None, near, 1])
            bad |= (d < r[None, near]).any(axis=1)
            inside = int((d < r[None, near] - layered.CLEAR).any(axis=1).sum())
    if len(obstacles.boxes):
        b = obstacles.boxes
        m = np.array([0.04 if k in ends else 0.015 for k in obstacles.box_keys])
        near = (b[:, 0] - m < x1) & (b[:, 2] + m > x0) & (b[:, 1] - m < y1) & (b[:, 3] + m > y0)
        if near.any():
            b, m = b[near], m[near][None, :]
            bad |= (
                (pts[:, None, 0] > b[None, :, 0] - m)
                & (pts[:, None, 0] < b[None, :, 2] + m)
                & (pts[:, None, 1] > b[None, :, 1] - m)
                & (pts[:, None, 1] < b[None, :, 3] + m)
            ).any(axis=1)
    return int(bad.sum()) + 10 * inside


@pytest.mark.parametrize("seed", range(20))
def test_hits_of_many_curves_at_once_are_each_curves_own(seed):
    rng = np.random.default_rng(seed)
    n_circles, n_boxes = int(rng.integers(0, 12)), int(rng.integers(0, 6))
    circles = [
        ((float(x), float(y)), float(r))
        for (x, y), r in zip(
            rng.uniform(-1, 1, (n_circles, 2)), rng.uniform(0.02, 0.3, n_circles), strict=True
        )
    ]
    corners = np.sort(rng.uniform(-1, 1, (n_boxes, 2, 2)), axis=1)
    boxes = [(a[0], a[1], b[0], b[1]) for a, b in corners]
    keys = list(range(n_circles))
    box_keys = [int(k) if k < n_circles else None for k in rng.integers(0, n_circles + 3, n_boxes)]
    obstacles = layered.Obstacles.of(circles, boxes, keys, box_keys)
    ends = {k for k in keys if rng.random() < 0.2}
    curves = rng.uniform(-1.2, 1.2, (int(rng.integers(1, 30)), 4, 2))
    points = layered.bezier_many(curves)
    assert np.array_equal(points, np.stack([layered.bezier_points(c) for c in curves]))
    got = layered.hits_many(points, obstacles, ends)
    want = [_hits_one_by_one(p, obstacles, ends) for p in points]
    assert got.tolist() == want
    assert [layered.hits(p, obstacles, ends) for p in points] == want


def test_hits_count_points_near_and_inside_a_circle_and_in_a_box():
    line = layered.bezier_many([[(-1, 0), (-0.3, 0), (0.3, 0), (1, 0)]])  # along y = 0
    circle = layered.Obstacles.of([((0.0, 0.0), 0.1)], [])
    box = layered.Obstacles.of([], [(-0.1, -0.1, 0.1, 0.1)])
    inside = int((np.abs(line[0, :, 0]) < 0.1).sum())
    assert layered.hits_many(line, circle)[0] > 10 * inside
    assert layered.hits_many(line, circle, ends={0})[0] == 0  # a curve may end at its own circle
    assert layered.hits_many(line, box)[0] == int((np.abs(line[0, :, 0]) < 0.1 + 0.015).sum()) > 0
