"""Where a delay graph's vertices and edges go, in inches; no matplotlib.

Edges into a sensor, out of an actuator or closing a cycle are laid out turned around;
sensors in the first layer, actuators in the last; bends pull hardest in
:func:`~symctl.plotting.layered.positions` (long edges run straight). An edge runs level
across a column and as an S-shaped Bézier between columns; the edges of a two-cycle, and
a lone back edge between neighbours, bulge apart. A label sits on its curve in its middle
gap, off other labels and curves; gaps are as wide as their labels.
"""

from __future__ import annotations

import itertools
from collections import Counter
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from symctl.compatibility.delaygraph import DelayGraph
from symctl.errors import ParameterError, SymctlTypeError
from symctl.plotting import layered

__all__ = ["MAX_BENDS", "MAX_DRAWN_VERTICES", "DelayGraphLayout", "EdgeRoute", "delay_graph_layout"]

MAX_DRAWN_VERTICES = 200  # most vertices a drawing takes (beyond, a picture says nothing)
MAX_BENDS = 40000  # most bend points (k - 1 for an edge across k layers): bounds the time
BOX, LABEL = (0.6, 0.35), (0.4, 0.13)  # a vertex box's and a label's size when none is given

_ROW_GAP = 0.25  # between two boxes of a layer [in]
_BEND_GAP = 0.2  # between a bend and anything else of its layer
_BEND_HEIGHT = 0.1
_MIN_GAP = 0.55  # between two columns, at least
_STEEP = 0.4  # a gap at least this part of the largest fall of an edge across it [in/in]
_MAX_GAP = 1.4  # ... up to this width [in]
_LABEL_MARGIN = 0.11  # either side of the widest label of a gap
_SHIFTS = (0.0, -0.15, 0.15, -0.3, 0.3, -0.45, 0.45, -0.6, 0.6, -0.75, 0.75)  # along its gap
_LABEL_CLEAR = 0.06  # a label keeps this far from the gap's ends (the columns)
_BULGE = 0.22  # of a two-cycle's edges, and of a lone back edge between neighbouring layers
_CLIP = 0.03  # arrow tips stop this far from a box
_PORT_STEP = 0.08  # between the ends of two edges on one side of a box
_PORT_MARGIN = 0.06  # from the box's corners
_T = np.linspace(0, 1, 12)  # where a curve's segments are sampled
_WEIGHT = {(False, False): 1.0, (False, True): 30.0, (True, False): 30.0, (True, True): 60.0}


@dataclass(frozen=True)
class EdgeRoute:
    """One drawn edge ``(source, target, delay)``: ``back`` when laid out right to left; ``points``
    on the boxes' borders and the bends; ``bezier`` its cubic segments; ``label`` its centre.
    """

    source: int
    target: int
    delay: int
    back: bool
    points: tuple[tuple[float, float], ...]
    bezier: tuple[tuple[float, float], ...]
    label: tuple[float, float]


@dataclass(frozen=True, eq=False)
class DelayGraphLayout:
    """Each vertex's ``layer``, centre ``pos`` and box ``size`` [in]; the ``routes``, one per edge of
    :attr:`DelayGraph.edges`; ``bounds`` ``(x_lo, x_hi, y_lo, y_hi)`` with margins.
    """

    layer: Mapping[int, int]
    pos: Mapping[int, tuple[float, float]]
    size: Mapping[int, tuple[float, float]]
    routes: tuple[EdgeRoute, ...]
    bounds: tuple[float, float, float, float]


def _depths(order, up, down, height) -> dict:
    """Each node's depth (minus its height), near its neighbours."""
    bend = {node: not isinstance(node, int) for o in order for node in o}
    gaps = [
        [
            (height[a] + height[b]) / 2 + (_ROW_GAP if not (bend[a] or bend[b]) else _BEND_GAP)
            for a, b in itertools.pairwise(o)
        ]
        for o in order
    ]
    return layered.positions(order, up, down, gaps, lambda a, b: _WEIGHT[bend[a], bend[b]])


def _across(p, q, bulge: float) -> list[tuple[float, float]]:
    """From ``p`` to ``q`` across a gap: an S (level at both ends), or a hump of ``bulge`` [in]."""
    (x0, y0), (x1, y1) = p, q
    dx = x1 - x0
    if not bulge:
        return [(x0 + dx / 2, y0), (x1 - dx / 2, y1), q]
    mx, my = (x0 + x1) / 2, (y0 + y1) / 2 + bulge
    return [(x0 + dx / 4, y0), (mx - dx / 4, my), (mx, my), (mx + dx / 4, my), (x1 - dx / 4, y1), q]


def _ports(chains, flow, at, size) -> tuple[list[float], list[float]]:
    """The height of each chain at its two ends, spread over the box's side."""
    starts: dict[int, list[int]] = {}
    ends: dict[int, list[int]] = {}
    for k, chain in enumerate(chains):
        starts.setdefault(chain[0], []).append(k)
        ends.setdefault(chain[-1], []).append(k)
    out = ([0.0] * len(chains), [0.0] * len(chains))
    for side, (where, other) in enumerate(((starts, 1), (ends, -2))):
        for v, ks in where.items():
            # top first; of a two-cycle, the edge kept forward above the one turned around
            ks.sort(key=lambda k: (-at[chains[k][other]][1], flow[k][2]))
            step = min(_PORT_STEP, (size[v][1] - 2 * _PORT_MARGIN) / max(len(ks) - 1, 1))
            for k, dy in zip(ks, layered.spread(len(ks), (len(ks) - 1) / 2 * step), strict=True):
                out[side][k] = at[v][1] + dy
    return out


def _route(chain, ys, at, size, left, right, bulge: float) -> list[tuple[float, float]]:
    """Cubic Bézier control points of one chain at heights ``ys``."""
    a, b = chain[0], chain[-1]
    x = at[a][0] + size[a][0] / 2 + _CLIP
    ctrl = [(x, ys[0])]
    for k, node in enumerate(chain):
        hi = right[node] if node != b else at[b][0] - size[b][0] / 2 - _CLIP
        lo = x if not k else min(left[node], hi)  # the chain's extent in the node's column
        if k:
            ctrl += _across(ctrl[-1], (lo, ys[k]), bulge)
        if hi > max(lo, ctrl[-1][0]) + 1e-9:
            ctrl += layered.line(ctrl[-1], (hi, ys[k]))
    return [(float(px), float(py)) for px, py in ctrl]


def _place_labels(curves, gaps, sizes) -> tuple[list[tuple[float, float]], list[int]]:
    """Each label's centre on its curve in its gap ``(lo, hi)``, off other labels and curves
    (three rounds), and the labels still covering another."""
    samples = [layered.bezier_points(bez, _T) for bez in curves]
    owner = np.concatenate([np.full(len(p), k) for k, p in enumerate(samples)])
    points = np.vstack(samples)
    options = []  # per label: candidate centres and what each costs besides other labels
    for k, (bez, (lo, hi), (w, h)) in enumerate(zip(curves, gaps, sizes, strict=True)):
        near = (points[:, 0] > lo - w) & (points[:, 0] < hi + w) & (owner != k)
        others = points[near]
        room = max((hi - lo - w) / 2 - _LABEL_CLEAR, 0.0)
        spots = []
        for shift in _SHIFTS:
            x, y = layered.at_x(bez, (lo + hi) / 2 + shift * room)
            crossed = np.count_nonzero(
                (np.abs(others[:, 0] - x) < w / 2 + 0.02)
                & (np.abs(others[:, 1] - y) < h / 2 + 0.02)
            )
            spots.append((x, y, crossed + abs(shift) / 4))
        options.append(spots)
    by_gap: dict[tuple, list[int]] = {}
    for k, g in enumerate(gaps):
        by_gap.setdefault(g, []).append(k)
    at: dict[int, tuple[float, float]] = {}

    def covers(k, x, y) -> int:
        w, h = sizes[k]
        return sum(
            abs(at[m][0] - x) < (w + sizes[m][0]) / 2 + 0.02
            and abs(at[m][1] - y) < (h + sizes[m][1]) / 2 + 0.02
            for m in by_gap[gaps[k]]
            if m != k and m in at
        )

    def place(k) -> int:
        x, y, _ = min(options[k], key=lambda o: 1000 * covers(k, o[0], o[1]) + o[2])
        at[k] = (x, y)
        return covers(k, x, y)

    clashes = [k for k in range(len(curves)) if place(k)]
    for _ in range(3):
        clashes = [k for k in range(len(curves)) if covers(k, *at[k]) and place(k)]
        if not clashes:
            break
    return [at[k] for k in range(len(curves))], clashes


def _edges(flow, chains, node_layer, depth, size, width, gap, where, label):
    """Positions, curves (as laid out, left to right) and labels for given column gaps."""
    column = [0.0]
    for k, g in enumerate(gap):
        column.append(column[-1] + width[k] / 2 + g + width[k + 1] / 2)
    at = {node: (column[node_layer[node]], float(depth[1] - depth[node])) for node in depth}
    left = {node: column[node_layer[node]] - width[node_layer[node]] / 2 for node in at}
    right = {node: column[node_layer[node]] + width[node_layer[node]] / 2 for node in at}
    pairs = Counter((a, b) for a, b, _ in flow)
    first, last = _ports(chains, flow, at, size)
    curves = []
    for k, ((a, b, back), chain) in enumerate(zip(flow, chains, strict=True)):
        ys = [first[k], *(at[node][1] for node in chain[1:-1]), last[k]]
        bulge = 0.0
        if len(chain) == 2 and (back or pairs[a, b] > 1):
            bulge = -_BULGE if back else _BULGE  # turned around: below; its partner above
        curves.append(_route(chain, ys, at, size, left, right, bulge))
    gaps = [(column[g] + width[g] / 2, column[g + 1] - width[g + 1] / 2) for g in where]
    placed, clashes = _place_labels(curves, gaps, label)
    return at, curves, placed, clashes


def delay_graph_layout(
    graph: DelayGraph,
    sizes: Mapping[int, tuple[float, float]] | None = None,
    label_sizes: Mapping[tuple[int, int], tuple[float, float]] | None = None,
) -> DelayGraphLayout:
    """The positions, routes and extent of the drawing of ``graph``; ``sizes`` of the vertex boxes
    and ``label_sizes`` of the edges' labels by ``(i, j)`` [in] (default :data:`BOX`, :data:`LABEL`).

    Raises SymctlTypeError (not a DelayGraph) or ParameterError (more than
    :data:`MAX_DRAWN_VERTICES` vertices, or more than :data:`MAX_BENDS` bends).

    Two pathways from the sensor to the actuator, through v2 and v3, lie in two rows:

    >>> from symctl import DelayGraph
    >>> from symctl.plotting.delaygraph_layout import delay_graph_layout
    >>> lay = delay_graph_layout(DelayGraph.from_edges(4, [(1, 2, 1), (2, 4, 1), (1, 3, 1), (3, 4, 1)]))
    >>> lay.layer[2] == lay.layer[3], lay.pos[2][1] != lay.pos[3][1]
    (True, True)
    """
    if not isinstance(graph, DelayGraph):
        raise SymctlTypeError(f"graph: expected a DelayGraph, got {type(graph).__name__}")
    n = graph.n
    if n > MAX_DRAWN_VERTICES:
        raise ParameterError(f"graph: at most {MAX_DRAWN_VERTICES} vertices are drawn, got {n}")
    size = {v: tuple(map(float, (sizes or {}).get(v, BOX))) for v in range(1, n + 1)}
    sensors, actuators = graph.sensors, graph.actuators
    edges = [(i, j) for i, j, _ in graph.edges]
    against = [(i, j) for i, j in edges if j in sensors or i in actuators]
    flow, layer = layered.layering(
        range(1, n + 1), edges, sensors, against=against, first=sensors, last=actuators, floor=1
    )
    if sum(abs(layer[b] - layer[a]) - 1 for a, b, _ in flow) > MAX_BENDS:
        raise ParameterError(
            f"graph: its {len(flow)} edges cross too many layers to be drawn (more than "
            f"{MAX_BENDS} bends)"
        )
    chains, node_layer, up, down = layered.split(flow, layer)
    order: list[list] = [[] for _ in range(layer[n] + 1)]
    for node in sorted(node_layer, key=lambda v: (isinstance(v, tuple), v)):
        order[node_layer[node]].append(node)
    order = layered.order(order, up, down)
    height = {node: size[node][1] if isinstance(node, int) else _BEND_HEIGHT for node in up}
    depth = _depths(order, up, down, height)
    # columns: each as wide as its widest box, the gaps as wide as their widest label
    label_sizes = label_sizes or {}
    label = [tuple(map(float, label_sizes.get((i, j), LABEL))) for i, j, _ in graph.edges]
    where = [layer[a] + (layer[b] - layer[a] - 1) // 2 for a, b, _ in flow]  # a label's gap
    width = [max([size[v][0] for v in o if isinstance(v, int)], default=0.0) for o in order]
    gap = [_MIN_GAP] * (len(order) - 1)
    for g, (w, _) in zip(where, label, strict=True):
        gap[g] = max(gap[g], w + 2 * _LABEL_MARGIN)
    for chain in chains:  # a steep S is hard to follow: wider gaps where edges fall far
        for u, w in itertools.pairwise(chain):
            fall = abs(depth[u] - depth[w])
            gap[node_layer[u]] = max(gap[node_layer[u]], min(_STEEP * fall, _MAX_GAP))
    for _ in range(3):  # labels that cannot help covering one another get a wider gap
        at, curves, placed, clashes = _edges(
            flow, chains, node_layer, depth, size, width, gap, where, label
        )
        if not clashes:
            break
        for k in clashes:
            gap[where[k]] += label[k][0] / len(clashes)
    pos = {v: at[v] for v in range(1, n + 1)}
    routes = []
    for (i, j, d), (_, _, back), bez, centre in zip(graph.edges, flow, curves, placed, strict=True):
        if back:
            bez = bez[::-1]
        routes.append(EdgeRoute(i, j, d, back, tuple(bez[::3]), tuple(bez), centre))
    boxes = [(*pos[v], *size[v]) for v in pos]
    boxes += [(*xy, *wh) for xy, wh in zip(placed, label, strict=True)]
    corners = [layered.box(x, y, (w, h)) for x, y, w, h in boxes]
    bounds = layered.extent([p for r in routes for p in r.bezier], corners, 0.3)
    return DelayGraphLayout(layer, pos, size, tuple(routes), bounds)
