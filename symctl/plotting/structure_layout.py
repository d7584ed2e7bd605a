"""Layout of a structure's block diagram at its printed size, in inches; no matplotlib.

Text is measured by ``measure(text, points) -> (width, height)`` [in]. Wires closing a
cycle are arcs below or above the rows, carrying the gains and delays that feed them (the
paper's IFP drawing). Columns by longest path, level by level of a delay assignment
(:func:`vertex_levels`); integer rows; orthogonal wires turning at a slot of their gap; an
adder takes its inputs on its left side; each part of a series connection framed.

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
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import NamedTuple

import networkx as nx

from symctl.compatibility.signalgraph import back_edges
from symctl.compatibility.structure import Structure
from symctl.plotting import layered
from symctl.plotting.layered import Segment, Wire, assign_slots, clean, junctions, merge
from symctl.plotting.layered import spread as spread
from symctl.plotting.structure_labels import StructureText, structure_text
from symctl.plotting.style import FONT_SIZE, SMALL

__all__ = ["ARROW", "Band", "Frame", "StructureLayout", "structure_layout", "vertex_levels"]

Measure = Callable[[str, float], tuple[float, float]]
"""``measure(text, points) -> (width, height)`` in inches; :class:`ValueError` for bad mathtext."""

FONT = NAME_FONT = SMALL  # points: gain values, signal names
END_FONT = FONT_SIZE  # points: the labels of the inputs and outputs
ROW = 0.4  # vertical pitch of the rows [in]
SUM_R = 0.07  # adder radius, at least
PORT = 0.045  # spacing of the inputs along an adder's side
DOT_R = 0.02  # dot of a signal (input, delayed signal)
PAD = 0.035  # padding around a gain value inside its box
ARROW = 0.055  # length of an arrow head; every wire's last piece is longer
PITCH = 0.05  # spacing of the vertical wires in a gap
GAP_IN, GAP_OUT = 0.07, 0.1  # room in a gap before its first and after its last vertical
MIN_GAP = 0.17  # narrowest gap between two columns
END = 0.24  # length of the arrows into the inputs and out of the outputs
ITEM_GAP = 0.1  # between two blocks on a feedback arc
DASH_ROOM = 0.06  # more room after the last turn of a wire into a delay, for its dashes
FRAME_PAD = 0.03  # between a part's blocks and its frame


class Route(NamedTuple):
    """A feedback wire drawn below (or above) the rows: ``source -> *chain -> target``."""

    source: str
    chain: tuple[str, ...]
    target: str


class Label(NamedTuple):
    """A text at ``(x, y)`` with its alignment; ``text`` is mathtext."""

    text: str
    x: float
    y: float
    ha: str
    va: str


@dataclass(frozen=True)
class StructureLayout:
    """Where every piece of a structure drawing goes [in]: each block's centre and size (gains
    on feedback arcs included), the text in each gain box, the ``names`` and ``ends`` written,
    each block's column in the rows (``layers``; none on a feedback arc), every wire and the
    arrows in and out, the ``junctions`` (a dot each), the frame of each part, the band of each
    delay-graph vertex, and the ``bounds`` (heading and key not included).
    """

    positions: Mapping[str, tuple[float, float]]
    sizes: Mapping[str, tuple[float, float]]
    labels: Mapping[str, str]
    names: Mapping[str, Label]
    ends: tuple[Label, ...]
    layers: Mapping[str, int]
    wires: tuple[Wire, ...]
    arrows_in: tuple[Wire, ...]
    arrows_out: tuple[Wire, ...]
    junctions: tuple[tuple[float, float], ...]
    parts: tuple[Frame, ...]
    bands: tuple[Band, ...]
    bounds: tuple[float, float, float, float]


def feedback_edges(S: Structure, level: Mapping[str, int]) -> list[tuple[str, str]]:
    """Wires closing a cycle (depth-first search from the inputs), and wires to an earlier level."""
    sg = S.signal_graph
    successors = [list(dict.fromkeys(out)) for out in sg.successors]
    back = [(sg.names[a], sg.names[b]) for a, b in back_edges(successors, sg.inputs)]
    back += [(a, b) for a, b, _ in S.wires() if level[a] > level[b] and (a, b) not in back]
    return back


def feedback_routes(S: Structure, g: nx.DiGraph, level, vertex) -> list[Route]:
    """Each feedback wire with the single-input, single-output gains and delays before it, drawn
    on its arc (with an assignment, only those at the vertex of both ends).
    """
    ends = set(S.inputs) | set(S.outputs)
    taken: set[str] = set()
    routes = []
    for tail, head in feedback_edges(S, level):
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
            node = next(iter(g.predecessors(node)))
        if vertex and any(vertex.get(n) != vertex.get(head) for n in (node, *chain)):
            chain, node = [], tail  # blocks of other vertices stay in the rows, in their band
        taken.update(chain)
        routes.append(Route(node, tuple(chain), head))
    return routes


def layering(S: Structure, g: nx.DiGraph, routes: list[Route], level) -> tuple[nx.DiGraph, dict]:
    """The forward graph (feedback removed) and its layers: longest path, level by level."""
    on_arcs = {n for r in routes for n in r.chain}
    index = {n: k for k, n in enumerate(S.blocks)}
    dag = nx.DiGraph()
    dag.add_nodes_from(n for n in S.blocks if n not in on_arcs)
    skip = {(r.chain[-1] if r.chain else r.source, r.target) for r in routes}
    dag.add_edges_from((a, b) for a, b in g.edges if a in dag and b in dag and (a, b) not in skip)
    layer: dict[str, int] = {}
    order = list(nx.lexicographical_topological_sort(dag, key=index.__getitem__))
    start = 0
    for lev in sorted({level[n] for n in dag}):
        members = [n for n in order if level[n] == lev]
        # outputs (nothing after them) close their level
        ends = [
            n for n in members if n in S.outputs and n not in S.inputs and not dag.out_degree(n)
        ]
        layered.longest_path(members, dag.pred, last=ends, floor=start, layer=layer)
        start = max(layer[n] for n in members) + 1
    return dag, layer


def arc_lanes(spans: dict[int, tuple[float, float]], side: dict[int, int]) -> dict[int, int]:
    """Lane 1, 2, ... (out from the rows) of each arc: overlapping arcs on a side differ, narrow inside."""
    lane: dict[int, int] = {}
    for k in sorted(spans, key=lambda k: (spans[k][1] - spans[k][0], k)):
        lo, hi = spans[k]
        used = {
            lane[q] for q in lane if side[q] == side[k] and lo <= spans[q][1] and spans[q][0] <= hi
        }
        lane[k] = min(set(range(1, len(lane) + 2)) - used)
    return lane


class Geometry:
    """Sizes of the drawn blocks (inches) and where a wire meets them."""

    def __init__(self, S: Structure, text: StructureText, measure: Measure):
        self.S = S
        self.size: dict[str, tuple[float, float]] = {}
        self.label: dict[str, str] = {}
        self.name: dict[str, tuple[str, float, float]] = {}
        self.left_named: set[str] = set()  # named above their left (an arc comes from above)
        for name, block in S.blocks.items():
            if block.kind == "gain":
                label = f"${text.gains[name]}$"
                w, h = measure(label, FONT)
                self.label[name] = label
                self.size[name] = (max(w + 2 * PAD, 0.22), max(h + 2 * PAD, 0.17))
            elif block.kind == "sum":
                self.size[name] = (2 * SUM_R, 2 * SUM_R)
            else:
                self.size[name] = (2 * DOT_R, 2 * DOT_R)
            if name in text.names:
                label = f"${text.names[name]}$"
                self.name[name] = (label, *measure(label, NAME_FONT))

    def kind(self, name) -> str:
        return self.S.blocks[name].kind if name in self.S.blocks else "dummy"

    def grow(self, name: str, entries: int) -> None:
        """An adder with ``entries`` inputs on one side grows to space them :data:`PORT` apart."""
        r = min(max(SUM_R, (entries - 1) * PORT / 1.2), ROW / 2 - 0.06)
        self.size[name] = (2 * r, 2 * r)

    def half(self, name) -> float:
        """Half the width a node needs in its column, its name (written above it) included."""
        if name not in self.size:
            return 0.0
        w = self.size[name][0] / 2
        if name in self.name and name in self.left_named:
            w = max(w, 0.45 * w + self.name[name][1] + 0.02)
        elif name in self.name:
            w = max(w, self.name[name][1] / 2 + 0.02)
        return w

    def reach(self, name, offset: float, axis: int) -> float:
        """Distance from the centre to the edge along ``axis`` (0 = x) at ``offset`` across."""
        if name not in self.size:
            return 0.0
        if self.kind(name) == "sum":
            r = self.size[name][0] / 2
            return math.sqrt(max(r**2 - offset**2, 0.0))
        return self.size[name][axis] / 2

    def port(self, name) -> float:
        """Half the span an adder's inputs may take along its side."""
        return 0.6 * self.size[name][0] / 2 if self.kind(name) == "sum" else 0.0


def structure_layout(
    S: Structure,
    measure: Measure,
    *,
    text: StructureText | None = None,
    vertex_of: Mapping[str, int] | None = None,
    vertex_names: Mapping[int, str] | None = None,
) -> StructureLayout:
    """The layout of the block diagram of ``S`` (see the module text): ``text`` what is written
    (default :func:`~symctl.plotting.structure_labels.structure_text`); ``vertex_of`` a delay
    assignment (each vertex's signals in one band) and ``vertex_names`` the bands' labels.
    """
    text = text or structure_text(S)
    g = S.graph
    geo = Geometry(S, text, measure)
    vertex = dict(vertex_of or {})
    level = vertex_levels(S, vertex)
    routes = feedback_routes(S, g, level, vertex)
    dag, layer = layering(S, g, routes, level)

    # forward wires spanning several layers pass through one bend per layer
    edges = list(dag.edges)
    chains, node_layer, preds, succs = layered.split(edges, layer)
    paths = dict(zip(edges, chains, strict=True))
    columns = layered.by_layer(node_layer, [*dag, *(n for chain in chains for n in chain[1:-1])])
    ncol = max(columns) + 1
    row = layered.rows(columns, preds, succs)
    col = {n: c for c, nodes in columns.items() for n in nodes}
    y = {n: ROW * r for n, r in row.items()}

    # feedback arcs: side (below unless more is in the way), straight entry into an adder
    side, straight = {}, {}
    for k, r in enumerate(routes):
        ends = ((r.source, col[r.source]), (r.target, col[r.target]))
        above = sum(y[n] > y[e] for e, c in ends for n in columns[c])
        below = sum(y[n] < y[e] for e, c in ends for n in columns[c])
        side[k] = 1 if below > above else -1
        beyond = [n for n in columns[col[r.target]] if side[k] * (y[n] - y[r.target]) > 0]
        straight[k] = geo.kind(r.target) == "sum" and not beyond
    spans = {k: (col[r.target] - 0.5, col[r.source] + 0.5) for k, r in enumerate(routes)}
    geo.left_named = {r.target for k, r in enumerate(routes) if straight[k] and side[k] > 0}
    lane = arc_lanes(spans, side)

    # where wires enter a node: its left side (spread), or from below / above
    enter_left: dict[str, list] = {}
    enter_vert: dict[tuple[str, int], list] = {}
    for a, b in dag.edges:
        enter_left.setdefault(b, []).append((-y[paths[(a, b)][-2]], ("wire", a)))
    for k, r in enumerate(routes):
        if straight[k]:
            enter_vert.setdefault((r.target, side[k]), []).append((-lane[k], k))
        else:
            enter_left.setdefault(r.target, []).append((-side[k] * 1e6 - lane[k], ("arc", k)))
    for b, entries in enter_left.items():
        if geo.kind(b) == "sum":
            vertical = [len(v) for (t, _), v in enter_vert.items() if t == b]
            geo.grow(b, max([len(entries), *vertical]))
    offset: dict = {}
    for b, entries in enter_left.items():
        for (_, key), off in zip(
            sorted(entries), layered.spread(len(entries), geo.port(b)), strict=True
        ):
            offset[(b, key)] = off
    rise_off: dict[int, float] = {}
    for (b, _), entries in enter_vert.items():
        # outer lanes enter on the left, so that arcs do not cross
        for (_, k), off in zip(
            sorted(entries), layered.spread(len(entries), geo.port(b))[::-1], strict=True
        ):
            rise_off[k] = off

    # arcs' heights: just clear of the columns they span, outside the inner arcs they overlap
    pitch = max([0.26] + [geo.size[n][1] + 0.1 for r in routes for n in r.chain])

    def extent(n, sign):
        reach = geo.size[n][1] / 2 if n in geo.size else 0.0
        if sign > 0:
            return y[n] + reach + (0.04 + geo.name[n][2] if n in geo.name else 0.04)
        return y[n] - reach - 0.04

    # a gap's vertical wires reach the rows of both its columns: an arc clears those too
    reach_y = {c: [y[n] for n in columns.get(c, [])] for c in range(-1, ncol + 1)}
    for a, b in dag.edges:
        for p, q in itertools.pairwise(paths[(a, b)]):
            reach_y[col[q]] += [y[p], y[q]]
    heights: dict[int, float] = {}
    for k in sorted(lane, key=lambda k: (lane[k], k)):
        sign, r = side[k], routes[k]
        spanned = [n for c in range(col[r.target], col[r.source] + 1) for n in columns[c]]
        level_y = sign * max(sign * extent(n, sign) for n in spanned) + sign * pitch / 2
        for c in (col[r.target], col[r.source] + 1):  # the gaps of its legs
            level_y = sign * max([sign * level_y] + [sign * v + pitch for v in reach_y.get(c, [])])
        for q, hq in heights.items():
            lo, hi = spans[k]
            if side[q] == sign and lane[q] < lane[k] and lo <= spans[q][1] and spans[q][0] <= hi:
                level_y = sign * max(sign * level_y, sign * (hq + sign * pitch))
        heights[k] = level_y

    # the vertical pieces in each gap (gap c lies left of column c), by net
    pieces: dict[int, list[Segment]] = {}
    hops: dict[tuple, tuple[int, object]] = {}  # (wire key, hop) -> (gap, net)

    def piece(gap, net, attachments, key):
        pieces.setdefault(gap, []).append(Segment(net, tuple(attachments)))
        hops[key] = (gap, net)

    for a, b in dag.edges:
        path = paths[(a, b)]
        for h, (p, q) in enumerate(itertools.pairwise(path)):
            yq = y[q] + (offset[(b, ("wire", a))] if q == b else 0.0)
            net = ("src", a) if p == a else ("hop", a, b, h)
            piece(col[q], net, [(y[p], "left"), (yq, "right")], ((a, b), h))
    for k, r in enumerate(routes):
        s_col, t_col = col[r.source], col[r.target]
        drop = [(y[r.source], "left"), (heights[k], "left")]
        piece(s_col + 1, ("src", r.source), drop, (("arc", k), "drop"))
        if not straight[k]:
            yt = y[r.target] + offset[(r.target, ("arc", k))]
            piece(t_col, ("rise", k), [(heights[k], "right"), (yt, "right")], (("arc", k), "rise"))
    for n in S.outputs:
        piece(col[n] + 1, ("src", n), [(y[n], "left"), (y[n], "right")], (("out", n), 0))
    slots = {gap: assign_slots(merge(segs)) for gap, segs in pieces.items()}

    # column widths and gaps, then room for the blocks on the arcs
    hw = [max([geo.half(n) for n in columns[c]] + [0.0]) for c in range(ncol)]
    gaps = [MIN_GAP] * (ncol + 1)
    # a delay's dashes need room after the last turn of its wire (a dot in the next column)
    delayed = {col[b] for a, b in dag.edges if g.edges[a, b]["delay"]}
    for gap, used in slots.items():
        if used:
            out = GAP_OUT + (DASH_ROOM if gap in delayed else 0.0)
            gaps[gap] = max(MIN_GAP, GAP_IN + PITCH * max(used.values()) + out)
    gaps[0] = max(gaps[0], 0.05)
    item_width = {n: geo.size[n][0] for r in routes for n in r.chain}

    def place():
        x = [0.0] * ncol
        for c in range(1, ncol):
            x[c] = x[c - 1] + hw[c - 1] + gaps[c] + hw[c]
        return x

    x = place()
    widened: set[int] = set()

    def slot_x(gap, net):
        left = x[gap - 1] + hw[gap - 1] if gap > 0 else x[0] - hw[0] - gaps[0]
        right = x[gap] - hw[gap] if gap < ncol else left + gaps[gap]
        used = slots.get(gap, {})
        n = max(used.values(), default=0) + 1
        if gap in widened:  # the slots keep to the right, where the widening put the drop
            out = GAP_OUT + (DASH_ROOM if gap in delayed else 0.0)
            return max(left + GAP_IN, right - out - PITCH * (n - 1)) + PITCH * used[net]
        return left + GAP_IN + PITCH * used[net]

    def arc_ends(k):
        r = routes[k]
        drop = slot_x(*hops[(("arc", k), "drop")])
        if straight[k]:
            return drop, x[col[r.target]] + rise_off[k]
        return drop, slot_x(*hops[(("arc", k), "rise")])

    # room on each arc for its blocks: widen the gap before its source, or for a loop on one
    # column the gap of its drop (whose slots then keep to its right)
    for k, r in enumerate(routes):
        need = sum(item_width[n] + ITEM_GAP for n in _on_arc(r, g)) + ITEM_GAP
        for _ in range(3):
            drop, rise = arc_ends(k)
            if not r.chain or drop - rise >= need - 1e-9:
                break
            gap = col[r.source] if col[r.source] > col[r.target] else col[r.source] + 1
            if gap > col[r.source]:
                widened.add(gap)
            gaps[gap] += need - (drop - rise)
            x = place()
    pos = {n: (x[col[n]], y[n]) for n in col}

    def out_point(a):
        xa, ya = pos[a]
        return (xa + geo.reach(a, 0, 0), ya)

    def turn(key, y0, y1, pts):
        """The two corners of a hop that changes rows (none when it keeps its row)."""
        gap, net = hops[key]
        if abs(y0 - y1) > 1e-9:
            xs = slot_x(gap, net)
            pts += [(xs, y0), (xs, y1)]

    wires: list[Wire] = []
    for a, b in dag.edges:
        path = paths[(a, b)]
        off = offset[(b, ("wire", a))]
        pts = [out_point(a)]
        for h, (p, q) in enumerate(itertools.pairwise(path)):
            turn(((a, b), h), y[p], y[q] + (off if q == b else 0.0), pts)
        pts.append((pos[b][0] - geo.reach(b, off, 0), y[b] + off))
        wires.append(Wire(clean(pts), g.edges[a, b]["delay"], a, b, False))

    # feedback arcs with their blocks
    for k, r in enumerate(routes):
        sign, ly = side[k], heights[k]
        ys = pos[r.source][1]
        drop, rise = arc_ends(k)
        items = _on_arc(r, g)
        widths = [item_width[n] for n in items]
        total = sum(widths) + ITEM_GAP * max(len(widths) - 1, 0)
        cursor = (drop + rise) / 2 + total / 2
        pts = [out_point(r.source), (drop, ys), (drop, ly)]
        prev = r.source
        for n, w in zip(items, widths, strict=True):
            pos[n] = (cursor - w / 2, ly)
            pts.append((cursor, ly))
            wires.append(Wire(clean(pts), g.edges[prev, n]["delay"], prev, n, True))
            pts, prev = [(cursor - w, ly)], n
            cursor -= w + ITEM_GAP
        if len(items) < len(r.chain):  # the delayed signal at the arc's corner
            n = r.chain[-1]
            pos[n] = (rise, ly)
            pts.append((rise + item_width[n] / 2, ly))
            wires.append(Wire(clean(pts), g.edges[prev, n]["delay"], prev, n, True))
            pts, prev = [(rise, ly)], n
        xt, yt = pos[r.target]
        if straight[k]:
            pts += [(rise, ly), (rise, yt - sign * geo.reach(r.target, rise - xt, 1))]
        else:
            off = offset[(r.target, ("arc", k))]
            pts += [(rise, ly), (rise, yt + off), (xt - geo.reach(r.target, off, 0), yt + off)]
        if prev in r.chain and g.nodes[prev]["kind"] == "delay":  # up from the corner dot
            pts[0] = (rise, ly - sign * item_width[prev] / 2)
        wires.append(Wire(clean(pts), g.edges[prev, r.target]["delay"], prev, r.target, True))

    # the arrows into the inputs and out of the outputs, and their labels
    arrows_in, arrows_out, ends = [], [], []
    for n in S.inputs:
        xa, ya = pos[n]
        tail = xa - hw[col[n]] - END
        arrows_in.append(Wire(((tail, ya), (xa - geo.reach(n, 0, 0), ya)), 0, None, n, False))
        ends.append(Label(f"${text.ends[n]}$", tail - 0.04, ya, "right", "center"))
    for n in S.outputs:
        c = col[n]
        head = x[c] + hw[c] + (gaps[c + 1] - GAP_OUT if slots.get(c + 1) else 0.0) + END
        arrows_out.append(Wire((out_point(n), (head, pos[n][1])), 0, n, None, False))
        ends.append(Label(f"${text.ends[n]}$", head + 0.04, pos[n][1], "left", "center"))

    dots = []
    for gap, segs in pieces.items():
        for seg in merge(segs):
            if seg.net in slots[gap]:
                dots += [(slot_x(gap, seg.net), yj) for yj in junctions(seg)]

    # names: above the signal, or above its left when an arc comes in from above
    names = {}
    for n, (label, _, _) in geo.name.items():
        xn, yn = pos[n]
        reach = geo.size[n][1] / 2 + 0.015
        if n in geo.left_named:  # above its top left, clear of the arcs coming in
            r = geo.size[n][0] / 2
            names[n] = Label(label, xn - 0.45 * r, yn + r + 0.01, "right", "bottom")
        else:
            names[n] = Label(label, xn, yn + reach, "center", "bottom")

    # extent, bands, frames
    boxes = {n: (*pos[n], *geo.size[n]) for n in S.blocks}
    xs_all = [p[0] for w in (*wires, *arrows_in, *arrows_out) for p in w.points]
    ys_all = [p[1] for w in wires for p in w.points] + [b[1] - b[3] / 2 for b in boxes.values()]
    tops = [b[1] + b[3] / 2 for b in boxes.values()]
    tops += [lab.y + geo.name[n][2] for n, lab in names.items() if lab.va == "bottom"]
    x_lo = min(xs_all + [e.x - measure(e.text, END_FONT)[0] for e in ends if e.ha == "right"])
    x_hi = max(xs_all + [e.x + measure(e.text, END_FONT)[0] for e in ends if e.ha == "left"])
    y_lo, y_hi = min(ys_all) - 0.06, max(tops + ys_all) + 0.04
    part_frames, y_hi = frames(S, boxes, names, geo.name, wires, y_hi, measure)
    band_list, y_hi = vertex_bands(
        vertex, level, boxes, x, hw, gaps, col, (y_lo, y_hi), vertex_names, measure
    )
    signals = set(S.blocks)
    return StructureLayout(
        positions=MappingProxyType({n: p for n, p in pos.items() if n in signals}),
        sizes=MappingProxyType(dict(geo.size)),
        labels=MappingProxyType(dict(geo.label)),
        names=MappingProxyType(names),
        ends=tuple(ends),
        layers=MappingProxyType({n: col[n] for n in dag}),
        wires=tuple(wires),
        arrows_in=tuple(arrows_in),
        arrows_out=tuple(arrows_out),
        junctions=tuple(dots),
        parts=part_frames,
        bands=band_list,
        bounds=(x_lo - 0.05, x_hi + 0.05, y_lo, y_hi),
    )


def _on_arc(route: Route, g: nx.DiGraph) -> tuple[str, ...]:
    """The blocks placed along an arc: its chain, less a last delay (a dot at the arc's corner)."""
    if route.chain and g.nodes[route.chain[-1]]["kind"] == "delay":
        return route.chain[:-1]
    return route.chain


class Band(NamedTuple):
    """The region of one delay-graph vertex: ``x0 .. x1`` by ``y0 .. y1``, its label above."""

    vertex: int
    label: str
    x0: float
    x1: float
    y0: float
    y1: float


class Frame(NamedTuple):
    """The frame around one part of a series connection."""

    part: str
    x0: float
    x1: float
    y0: float
    y1: float


def vertex_levels(S: Structure, vertex: Mapping[str, int]) -> dict[str, int]:
    """The level of each signal: the longest path to its vertex in the graph of the vertices the
    wires join (cycles broken at the wire going furthest back); 0 without ``vertex``.
    """
    if not vertex:
        return dict.fromkeys(S.blocks, 0)
    vg = nx.DiGraph()
    vg.add_nodes_from(sorted(set(vertex.values())))
    for a, b, _ in S.wires():
        va, vb = vertex.get(a), vertex.get(b)
        if va is not None and vb is not None and va != vb:
            vg.add_edge(va, vb)
    layered.break_cycles(vg, lambda e: (e[1] - e[0], -e[0]))
    level = layered.longest_path(nx.lexicographical_topological_sort(vg), vg.pred)
    return {n: level[vertex[n]] if n in vertex else 0 for n in S.blocks}


def vertex_label(v: int, names: Mapping[int, str] | None) -> str:
    """``$v_{2}$``, or ``spinal ($v_{2}$)`` with the model's name of the vertex."""
    name = (names or {}).get(v, "")
    tex = f"$v_{{{v}}}$"
    if not name or name == f"v{v}":
        return tex
    return f"{name.replace('_', ' ').replace('$', '')} ({tex})"


def vertex_bands(vertex, level, boxes, x, hw, gaps, col, y_range, names, measure):
    """The band of each vertex (a level's, from mid-gap before its first column to mid-gap after
    its last; the whole height when alone at its level) and the drawing's new top.
    """
    if not vertex:
        return (), y_range[1]
    y_lo, y_hi = y_range
    by_level: dict[int, set[int]] = {}
    cols: dict[int, list[int]] = {}
    for n, v in vertex.items():
        if n in boxes:
            by_level.setdefault(level[n], set()).add(v)
            if n in col:
                cols.setdefault(level[n], []).append(col[n])
    bands = []
    for lev in sorted(set(by_level) & set(cols)):
        c0, c1 = min(cols[lev]), max(cols[lev])
        x0 = x[c0] - hw[c0] - (gaps[c0] / 2 if lev > min(cols) else 0.06)
        x1 = x[c1] + hw[c1] + (gaps[c1 + 1] * (0.85 if c1 == len(x) - 1 else 0.5))
        members = sorted(by_level[lev])
        for v in members:
            y0, y1 = y_lo, y_hi
            if len(members) > 1:
                own = [b for n, b in boxes.items() if vertex.get(n) == v]
                y0 = max(y_lo, min(b[1] - b[3] / 2 for b in own) - 0.12)
                y1 = min(y_hi, max(b[1] + b[3] / 2 for b in own) + 0.12)
            bands.append(Band(v, vertex_label(v, names), x0, x1, y0, y1))
    return tuple(bands), y_hi + measure("$v_{1}$", FONT_SIZE)[1] + 0.08


def frames(S: Structure, boxes, names, name_sizes, wires, y_hi, measure):
    """The frame of each part (none for one part) and the drawing's new top (labels above frames)."""
    parts: dict[str, list[str]] = {}
    for n, block in S.blocks.items():
        parts.setdefault(block.part, []).append(n)
    parts.pop("", None)  # blocks of no part (the output adder of parallel pathways)
    for n in S.inputs:  # an input read by several parts (parallel pathways) is no one's
        readers = {b.part for b in S.blocks.values() if n in b.inputs}
        if len(readers) > 1 and n in parts.get(S.blocks[n].part, []):
            parts[S.blocks[n].part].remove(n)
    if len(parts) <= 1:
        return (), y_hi
    label_h = measure("G1", SMALL)[1]
    out = []
    for part, members in parts.items():
        inside = set(members)
        corners = [layered.box(bx, by, (bw, bh)) for bx, by, bw, bh in map(boxes.get, members)]
        for n in inside & set(names):
            lab = names[n]
            corners.append(layered.box(lab.x, lab.y, name_sizes[n][1:], lab.ha, lab.va))
        pts = [p for w in wires if w.source in inside and w.target in inside for p in w.points]
        out.append(Frame(part, *layered.extent(pts, corners, FRAME_PAD)))
        y_hi = max(y_hi, out[-1].y1 + label_h + 0.06)
    return tuple(out), y_hi
