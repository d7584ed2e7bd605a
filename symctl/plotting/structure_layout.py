r"""Layout of a structure's block diagram: positions, wire routes, lanes and sizes, as numbers.

The drawing of :meth:`Structure.draw <symctl.compatibility.structure.Structure.draw>`
in two steps, as networkx splits ``drawing/layout.py`` from ``nx_pylab.py``: this
module computes where everything goes (in inches, one data unit is one inch of
the figure) and never imports matplotlib; :mod:`symctl.plotting.structure`
renders the result. Text is measured by a function passed in, ``measure(text,
points) -> (width, height)`` in inches (the renderer passes
:func:`symctl.plotting.common.text_size`).

The steps: feedback wires (the back edges of a depth-first search from the
inputs) are routed on arcs below or above the rows, carrying the gains and
delays that feed them; the remaining forward graph is layered by longest path
from the inputs (outputs last); rows inside each layer follow barycenter sweeps
made integer and one apart by an isotonic fit (PAVA); columns widen where an arc
must hold its blocks; arcs take lanes so that arcs in one lane do not overlap.

>>> from symctl import ifp_structure
>>> from symctl.plotting.structure_layout import structure_layout
>>> def measure(text, points):  # a crude measure: 0.6 em per character
...     return 0.6 * points / 72 * len(text), points / 72
>>> layout = structure_layout(ifp_structure(2), measure)
>>> layout.layers["x"] < layout.layers["mu"] < layout.layers["u"]
True
>>> sorted((w.source, w.target) for w in layout.wires if w.feedback)
[('K1', 'mu'), ('K2', 'mu'), ('gamma', 'K1'), ('u', 'K2')]
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import NamedTuple

import networkx as nx

from symctl._util.display import latex
from symctl._util.texnames import signal_tex
from symctl.compatibility.signalgraph import back_edges
from symctl.compatibility.structure import Block, Structure

__all__ = ["Geometry", "Route", "StructureLayout", "Wire", "structure_layout"]

Measure = Callable[[str, float], tuple[float, float]]
"""``measure(text, points) -> (width, height)`` in inches; :class:`ValueError` for bad mathtext."""

# Drawing coordinates are inches (one data unit is one inch of the figure), so
# text measured in points fits its box whatever the size of the structure.
FONT = 9  # points: gain values and adders
NAME_FONT = 8  # points: signal names
GAP = 0.55  # horizontal gap between layers
ROW = 0.72  # vertical pitch of the rows inside a layer
SUM_R = 0.12  # adder radius
DOT_R = 0.03  # dot of a named signal (input, delayed signal)
PAD = 0.07  # padding around a gain value inside its box
MAX_LABEL = 25  # gain values with more visible characters are shown by block name


class Route(NamedTuple):
    """A feedback wire drawn below (or above) the rows: ``source -> *chain -> target``."""

    source: str
    chain: tuple[str, ...]
    target: str


def gain_label(block: Block, name: str, measure: Measure) -> str:
    """The gain value as mathtext, or the block name when it is long or not renderable.

    ``measure`` raises :class:`ValueError` for text it cannot set (bad mathtext).
    """
    if block.gain is None:
        return name
    text = latex(block.gain)
    visible = re.sub(r"\\(left|right|frac|dfrac)\b", "", text)
    visible = re.sub(r"\\[a-zA-Z]+", "m", visible)
    if len(re.sub(r"[{}_^\s]", "", visible)) > MAX_LABEL:
        return name
    try:
        measure(f"${text}$", FONT)
    except ValueError:
        return name
    return f"${text}$"


def signal_label(name: str) -> str:
    """``gamma2`` -> ``$\\gamma_{2}$``, ``G2.x1`` -> ``$x_{1}$`` (the part is labelled apart)."""
    return f"${signal_tex(name, part=False)}$"


def feedback_edges(S: Structure) -> list[tuple[str, str]]:
    """Wires closing a cycle, found by a depth-first search from the inputs (in order)."""
    sg = S.signal_graph
    successors = [list(dict.fromkeys(out)) for out in sg.successors]
    return [(sg.names[a], sg.names[b]) for a, b in back_edges(successors, sg.inputs)]


def feedback_routes(S: Structure, g: nx.DiGraph) -> list[Route]:
    """Each feedback wire with the single-input, single-output gains and delays before it.

    Those blocks (e.g. the IFP's :math:`K_1, K_2`, a state's self-gain :math:`F_{ii}`) are
    drawn on the feedback arc itself, as the paper does, and take no place in the rows.
    """
    ends = set(S.inputs) | set(S.outputs)
    taken: set[str] = set()
    routes = []
    for tail, head in feedback_edges(S):
        chain: list[str] = []
        node = tail
        while (
            node not in ends
            and node != head
            and node not in taken
            and g.nodes[node]["kind"] in ("gain", "delay")
            and g.in_degree(node) == 1
            and g.out_degree(node) == 1
        ):
            chain.insert(0, node)
            taken.add(node)
            node = next(iter(g.predecessors(node)))
        routes.append(Route(node, tuple(chain), head))
    return routes


def layering(S: Structure, g: nx.DiGraph, routes: list[Route]) -> tuple[nx.DiGraph, dict]:
    """The forward graph (feedback removed) and its layers: longest path from the inputs."""
    on_arcs = {n for r in routes for n in r.chain}
    index = {n: k for k, n in enumerate(S.blocks)}
    dag = nx.DiGraph()
    dag.add_nodes_from(n for n in S.blocks if n not in on_arcs)
    skip = {(r.chain[-1] if r.chain else r.source, r.target) for r in routes}
    dag.add_edges_from((a, b) for a, b in g.edges if a in dag and b in dag and (a, b) not in skip)
    layer: dict[str, int] = {}
    for node in nx.lexicographical_topological_sort(dag, key=index.__getitem__):
        layer[node] = max((layer[p] + 1 for p in dag.predecessors(node)), default=0)
    last = max(layer.values(), default=0)
    if any(layer[n] == last for n in dag if n not in S.outputs):
        last += 1
    for n in S.outputs:
        if n not in S.inputs and n in layer:
            layer[n] = last
    return dag, layer


def pava_rows(desired: list[float]) -> list[int]:
    """Integer rows, top first, one apart at least, closest to ``desired`` (isotonic fit)."""
    blocks: list[list[float]] = []  # [mean, weight] of pooled z_i = y_i + i, non-increasing
    for i, d in enumerate(desired):
        blocks.append([d + i, 1.0])
        while len(blocks) > 1 and blocks[-2][0] < blocks[-1][0]:
            mean, weight = blocks.pop()
            blocks[-1][0] = (blocks[-1][0] * blocks[-1][1] + mean * weight) / (
                blocks[-1][1] + weight
            )
            blocks[-1][1] += weight
    z = [mean for mean, weight in blocks for _ in range(int(weight))]
    rows = [math.floor(zi - i + 0.5) for i, zi in enumerate(z)]
    for i in range(1, len(rows)):
        rows[i] = min(rows[i], rows[i - 1] - 1)
    return rows


def order_rows(columns: dict[int, list], preds: dict, succs: dict) -> dict:
    """Rows inside each layer: barycenter sweeps (left to right, back, and again)."""
    row: dict = {}
    for neighbours in (preds, succs, preds, succs, preds):
        cols = sorted(columns, reverse=neighbours is succs)
        for c in cols:
            nodes = columns[c]
            desired = {}
            for n in nodes:
                ys = [row[m] for m in neighbours[n] if m in row]
                desired[n] = sum(ys) / len(ys) if ys else row.get(n, 0.0)
            nodes.sort(key=lambda n, d=desired: -d[n])
            row.update(zip(nodes, pava_rows([desired[n] for n in nodes]), strict=True))
    return row


class Geometry:
    """Sizes of the drawn blocks (inches) and where a wire meets them."""

    def __init__(self, S: Structure, measure: Measure):
        self.S = S
        self.label: dict[str, str] = {}
        self.size: dict[str, tuple[float, float]] = {}
        self.name: dict[str, tuple[str, float]] = {}
        for name, block in S.blocks.items():
            if block.kind == "gain":
                label = gain_label(block, name, measure)
                w, h = measure(label, FONT)
                self.label[name] = label
                self.size[name] = (max(w + 2 * PAD, 0.3), max(h + 2 * PAD, 0.26))
            elif block.kind == "sum":
                self.size[name] = (2 * SUM_R, 2 * SUM_R)
            else:
                self.size[name] = (2 * DOT_R, 2 * DOT_R)
            if block.kind != "gain" and not name.rpartition(".")[2].startswith("z^-"):
                text = signal_label(name)
                self.name[name] = (text, measure(text, NAME_FONT)[0])

    def kind(self, name) -> str:
        return self.S.blocks[name].kind if name in self.S.blocks else "dummy"

    def half(self, name) -> float:
        """Half the width a node needs in its column, its name included."""
        if name not in self.size:
            return 0.05
        w = self.size[name][0] / 2
        if name in self.name:
            w = max(w, w + 0.03 + self.name[name][1])
        return w

    def reach(self, name, offset: float, axis: int) -> float:
        """Distance from the centre to the edge along ``axis`` (0 = x) at ``offset`` across."""
        if name not in self.size:
            return 0.0
        if self.kind(name) == "sum":
            return math.sqrt(max(SUM_R**2 - offset**2, 0.0))
        return self.size[name][axis] / 2


def spread(count: int, half: float) -> list[float]:
    """``count`` offsets from ``+half`` to ``-half`` (0 for one)."""
    if count <= 1:
        return [0.0] * count
    return [half - 2 * half * k / (count - 1) for k in range(count)]


def assign_lanes(side, drop, rise, boxes, span) -> dict[int, int]:
    """Lane 1, 2, ... (away from the rows) of each feedback arc, narrowest arcs first.

    Arcs in one lane must not overlap; the vertical legs of an outer arc must not pass
    through a block on an inner arc. If no lane avoids every clash, the least bad one.
    """
    lane: dict[int, int] = {}

    def clashes(k, level):
        count = 0
        for q, lq in lane.items():
            if side[q] != side[k]:
                continue
            if lq == level:
                (lo, hi), (qlo, qhi) = span(k), span(q)
                count += lo < qhi and qlo < hi
            else:
                inner, outer = (q, k) if lq < level else (k, q)
                count += any(
                    lo - 0.12 < v < hi + 0.12
                    for v in (drop[outer], rise[outer])
                    for lo, hi in boxes(inner)
                )
        return count

    for k in sorted(side, key=lambda k: (span(k)[1] - span(k)[0], k)):
        levels = range(1, len(lane) + 2)
        lane[k] = min(levels, key=lambda level, k=k: (clashes(k, level) > 0, clashes(k, level)))
    return lane


class Wire(NamedTuple):
    """One drawn wire: a polyline from ``source`` to ``target`` (None: from outside / to outside).

    ``delay`` is 1 for a one-step delay (drawn dashed); ``feedback`` marks the
    wires on a feedback arc.
    """

    points: tuple[tuple[float, float], ...]
    delay: int
    source: str | None
    target: str | None
    feedback: bool


@dataclass(frozen=True)
class StructureLayout:
    """Where every piece of a structure drawing goes, in inches.

    Attributes
    ----------
    positions : mapping of signal name to (x, y)
        The centre of each block (gains on feedback arcs included).
    sizes : mapping of signal name to (width, height)
        Gain boxes, adder circles (diameter) and signal dots.
    labels : mapping of gain name to str
        The text in each gain box (mathtext, or the block name).
    names : mapping of signal name to str
        The name written next to an input, adder or delayed signal.
    layers : mapping of signal name to int
        The column of each block in the rows (blocks on feedback arcs have none).
    wires : tuple of Wire
        Every wire of the structure, as drawn.
    arrows_in, arrows_out : tuple of Wire
        The arrows into the inputs and out of the outputs.
    parts : tuple of (name, x_left, x_right, y)
        The bars naming the parts of a series connection (none for one part).
    bounds : (x_lo, x_hi, y_lo, y_hi)
        The extent of the drawing (heading and key not included).
    """

    positions: Mapping[str, tuple[float, float]]
    sizes: Mapping[str, tuple[float, float]]
    labels: Mapping[str, str]
    names: Mapping[str, str]
    layers: Mapping[str, int]
    wires: tuple[Wire, ...]
    arrows_in: tuple[Wire, ...]
    arrows_out: tuple[Wire, ...]
    parts: tuple[tuple[str, float, float, float], ...]
    bounds: tuple[float, float, float, float]


def structure_layout(S: Structure, measure: Measure) -> StructureLayout:
    """The layout of the block diagram of ``S`` (see the module text).

    Parameters
    ----------
    S : Structure
    measure : callable
        ``measure(text, points) -> (width, height)`` in inches.

    Returns
    -------
    StructureLayout
    """
    g = S.graph
    geo = Geometry(S, measure)
    routes = feedback_routes(S, g)
    dag, layer = layering(S, g, routes)

    # forward wires spanning several layers pass through one dummy slot per layer
    columns: dict[int, list] = {}
    for node in dag:
        columns.setdefault(layer[node], []).append(node)
    preds: dict = {n: [] for n in dag}
    succs: dict = {n: [] for n in dag}
    paths: dict[tuple[str, str], list] = {}
    for a, b in dag.edges:
        path = [a, *(("~", a, b, k) for k in range(layer[a] + 1, layer[b])), b]
        for k, node in enumerate(path[1:-1], start=layer[a] + 1):
            columns[k].append(node)
            preds[node], succs[node] = [], []
        for p, q in itertools.pairwise(path):
            succs[p].append(q)
            preds[q].append(p)
        paths[(a, b)] = path
    row = order_rows(columns, preds, succs)
    col = {n: c for c, nodes in columns.items() for n in nodes}
    y = {n: ROW * r for n, r in row.items()}

    # column widths, then widen where a feedback arc must hold its blocks
    ncol = max(columns) + 1
    hw = [max(geo.half(n) for n in columns[c]) for c in range(ncol)]
    gaps = [GAP] * (ncol + 1)  # gaps[c] lies left of column c
    item_width = {n: geo.size[n][0] for r in routes for n in r.chain}
    for r in routes:
        need = sum(item_width[n] for n in r.chain) + 0.3 * len(r.chain) + 0.2
        a, b = col[r.source], col[r.target]
        if a == b:
            hw[a] = max(hw[a], (need - GAP) / 2)
    x = [0.0] * ncol
    for c in range(1, ncol):
        x[c] = x[c - 1] + hw[c - 1] + gaps[c] + hw[c]
    for r in routes:
        need = sum(item_width[n] for n in r.chain) + 0.3 * len(r.chain) + 0.2
        a, b = col[r.source], col[r.target]
        if a > b and x[a] - x[b] < need:
            for c in range(b + 1, a + 1):
                gaps[c] += (need - (x[a] - x[b])) / (a - b)
    for c in range(1, ncol):
        x[c] = x[c - 1] + hw[c - 1] + gaps[c] + hw[c]
    pos = {n: (x[col[n]], y[n]) for n in col}

    # feedback arcs: side (below unless more is in the way there), legs, blocks, lane
    lowest = {c: min(y[n] for n in columns[c]) for c in columns}
    highest = {c: max(y[n] for n in columns[c]) for c in columns}
    # a leg straight down (up) from a node unless something is below (above) it in its
    # column or a self-loop hangs there
    looped = {r.source for r in routes if r.source == r.target}
    # legs in a gap: drops left of rises, the longest arcs outermost (they take outer lanes)
    legs: dict[int, list] = {}  # gap index -> [(order, route id, "drop" | "rise")]
    side, drop, rise, straight = {}, {}, {}, {}
    for k, r in enumerate(routes):
        ends = ((r.source, col[r.source]), (r.target, col[r.target]))
        above = sum(y[n] > y[e] for e, c in ends for n in columns[c])
        below = sum(y[n] < y[e] for e, c in ends for n in columns[c])
        sign = 1 if below > above else -1
        side[k] = sign
        edge = highest if sign > 0 else lowest
        s_col, t_col = col[r.source], col[r.target]
        straight[k] = (
            r.source not in looped and y[r.source] == edge[s_col],
            r.target not in looped and y[r.target] == edge[t_col],
        )
        if straight[k][0]:
            drop[k] = pos[r.source][0]
        else:
            legs.setdefault(s_col + 1, []).append((0, s_col - t_col, k, "drop"))
        if straight[k][1]:
            rise[k] = pos[r.target][0]
        else:
            legs.setdefault(t_col, []).append((1, t_col - s_col, k, "rise"))
    for gap, entries in legs.items():
        left = x[gap - 1] + hw[gap - 1] if gap > 0 else x[0] - hw[0] - gaps[0]
        right = x[gap] - hw[gap] if gap < ncol else left + gaps[gap]
        for j, (*_, k, what) in enumerate(sorted(entries)):
            xj = left + (right - left) * (j + 1) / (len(entries) + 1)
            (drop if what == "drop" else rise)[k] = xj

    items: dict[int, list[tuple[str, float]]] = {}
    for k, r in enumerate(routes):
        widths = [item_width[n] for n in r.chain]
        total = sum(widths) + 0.3 * max(len(widths) - 1, 0)
        cursor = (drop[k] + rise[k]) / 2 + total / 2
        placed = []
        for n, w in zip(r.chain, widths, strict=True):
            placed.append((n, cursor - w / 2))
            cursor -= w + 0.3
        items[k] = placed

    def boxes(k):
        return [(cx - item_width[n] / 2, cx + item_width[n] / 2) for n, cx in items[k]]

    def span(k):
        ends = [drop[k], rise[k], *itertools.chain.from_iterable(boxes(k))]
        return min(ends) - 0.1, max(ends) + 0.1

    lane = assign_lanes(side, drop, rise, boxes, span)

    pitch = max([0.42] + [geo.size[n][1] + 0.16 for r in routes for n in r.chain])

    def extent(n, sign):
        reach = geo.size[n][1] / 2 if n in geo.size else 0.0
        if sign > 0:
            return y[n] + reach + (0.25 if n in geo.name else 0.08)
        return y[n] - reach - 0.12

    # an arc runs just clear of the columns it spans, outside every inner arc it overlaps
    heights: dict[int, float] = {}
    for k in sorted(lane, key=lambda k: (lane[k], k)):
        sign, r = side[k], routes[k]
        spanned = [n for c in range(col[r.target], col[r.source] + 1) for n in columns[c]]
        level = sign * max(sign * extent(n, sign) for n in spanned) + sign * pitch / 2
        for q, hq in heights.items():
            if side[q] == sign and lane[q] < lane[k]:
                (lo, hi), (qlo, qhi) = span(k), span(q)
                if lo < qhi and qlo < hi:
                    level = sign * max(sign * level, sign * (hq + sign * pitch))
        heights[k] = level
    bottom = min([extent(n, -1) for n in y] + [h - pitch / 2 for h in heights.values()])
    top = max([extent(n, 1) for n in y] + [h + pitch / 2 for h in heights.values()])

    # where wires enter a node: from the left (spread across), from below or above
    enter_left: dict[str, list] = {}
    enter_vert: dict[tuple[str, int], list] = {}
    for a, b in dag.edges:
        last = paths[(a, b)][-2]
        enter_left.setdefault(b, []).append((-y[last], ("wire", a)))
    for k, r in enumerate(routes):
        if straight[k][1]:
            enter_vert.setdefault((r.target, side[k]), []).append((-lane[k], k))
        else:
            enter_left.setdefault(r.target, []).append((-side[k] * 1e6 - lane[k], ("arc", k)))
    offset: dict = {}
    for b, entries in enter_left.items():
        half = 0.7 * (SUM_R if geo.kind(b) == "sum" else geo.size[b][1] / 2)
        for (_, key), off in zip(sorted(entries), spread(len(entries), half), strict=True):
            offset[(b, key)] = off
    for (b, _), entries in enter_vert.items():
        half = 0.55 * (SUM_R if geo.kind(b) == "sum" else geo.size[b][0] / 2)
        # outer lanes enter on the left so that arcs do not cross
        for (_, k), off in zip(sorted(entries), spread(len(entries), half)[::-1], strict=True):
            rise[k] = pos[b][0] + off

    wires: list[Wire] = []

    def out_point(a):
        xa, ya = pos[a]
        return (xa + geo.reach(a, 0, 0), ya)

    def in_points(b, off):
        xb, yb = pos[b]
        return [(xb - hw[col[b]], yb + off), (xb - geo.reach(b, off, 0), yb + off)]

    for a, b in dag.edges:
        path = paths[(a, b)]
        pts = [out_point(a), (pos[a][0] + hw[col[a]], pos[a][1])]
        for d in path[1:-1]:
            pts += [(pos[d][0] - hw[col[d]], pos[d][1]), (pos[d][0] + hw[col[d]], pos[d][1])]
        pts += in_points(b, offset[(b, ("wire", a))])
        wires.append(Wire(tuple(pts), g.edges[a, b]["delay"], a, b, False))
    for k, r in enumerate(routes):
        sign, ly = side[k], heights[k]
        xs, ys = pos[r.source]
        if straight[k][0]:
            pts = [(xs, ys + sign * geo.reach(r.source, 0, 1)), (xs, ly)]
        else:
            pts = [out_point(r.source), (drop[k], ys), (drop[k], ly)]
        prev = r.source
        for n, cx in items[k]:
            pts.append((cx + item_width[n] / 2, ly))
            wires.append(Wire(tuple(pts), g.edges[prev, n]["delay"], prev, n, True))
            pos[n] = (cx, ly)
            pts, prev = [(cx - item_width[n] / 2, ly)], n
        xt, yt = pos[r.target]
        if straight[k][1]:
            off = rise[k] - xt
            pts += [(rise[k], ly), (rise[k], yt - sign * geo.reach(r.target, off, 1))]
        else:
            off = offset[(r.target, ("arc", k))]
            pts += [(rise[k], ly), *in_points(r.target, off)]
            pts[-2] = (rise[k], yt + off)
        wires.append(Wire(tuple(pts), g.edges[prev, r.target]["delay"], prev, r.target, True))

    # input and output arrows
    arrows_in = tuple(
        Wire(((xa - hw[col[n]] - 0.35, ya), (xa - geo.reach(n, 0, 0), ya)), 0, None, n, False)
        for n in S.inputs
        for xa, ya in [pos[n]]
    )
    arrows_out = tuple(
        Wire((out_point(n), (pos[n][0] + hw[col[n]] + 0.45, pos[n][1])), 0, n, None, False)
        for n in S.outputs
    )

    # extent, parts, title and legend
    xs_all = [p[0] for p in pos.values()]
    x_lo = min(x[0] - hw[0] - gaps[0], min(xs_all)) - 0.15
    x_hi = x[-1] + hw[-1] + 0.6
    y_lo, y_hi = bottom, top
    parts: dict[str, list[float]] = {}
    for n in dag:
        part = S.blocks[n].part.partition(".")[0]
        if part:
            parts.setdefault(part, []).append(pos[n][0])
    bars = []
    if len(parts) > 1:
        y_hi += 0.05
        for part, xs in parts.items():
            bars.append((part, min(xs) - 0.1, max(xs) + 0.1, y_hi))
        y_hi += 0.25
    signals = set(S.blocks)
    return StructureLayout(
        positions=MappingProxyType({n: p for n, p in pos.items() if n in signals}),
        sizes=MappingProxyType(dict(geo.size)),
        labels=MappingProxyType(dict(geo.label)),
        names=MappingProxyType({n: text for n, (text, _) in geo.name.items()}),
        layers=MappingProxyType({n: col[n] for n in dag}),
        wires=tuple(wires),
        arrows_in=arrows_in,
        arrows_out=arrows_out,
        parts=tuple(bars),
        bounds=(x_lo, x_hi, y_lo, y_hi),
    )
