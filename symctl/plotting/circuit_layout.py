"""Where a circuit's neurons, inputs, outputs and synapse curves go, in inches; no matplotlib.

Columns by longest forward path (inputs first, outputs last), rows by
:func:`~symctl.plotting.layered.rows`; a drawing wider than ``width`` is cut into bands
stacked top to bottom where every synapse across the cut joins neighbouring columns (a
wire out of the right of its band, into the next from the left). Each synapse is a bridge
(:func:`route`), straight when clear, else bulging just enough to pass no circle and no text.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING

import numpy as np

from symctl.plotting import layered

if TYPE_CHECKING:
    from symctl.neural.circuit import Circuit
    from symctl.neural.neuron import Synapse

MIN_RADIUS = 0.11  # the smallest neuron circle [in] (the radius when none is given)
DOT = 0.03  # the radius of an input or output dot [in]
MIN_GAP = 0.26  # the least room between two columns' circles and names [in]
MAX_RADIUS = 0.3  # a circle grows to space the ends of its synapses no larger than this
NAME_GAP = 0.06  # between a circle and its name above it or its vertex tag below it
_END_GAP = 0.04  # between a dot and its label
_ARROW = 0.11  # room for an arrow head or bar, either side of a weight on a straight synapse [in]
_ROW_GAP = 0.18  # between the texts of two rows
_ROW_STEP = 0.45  # rows of nodes not side by side stay this far apart, per row [in]
_MARGIN = 0.04  # around the drawing
_WIRE = 0.12  # a wire between bands runs this far outside the bands
_WIRE_STEP = 0.07  # between two wires at one cut
_CORNER = 0.05  # the rounding of a wire's corners
_MAX_CURVES = 150  # beyond: the curves are not searched (a hairball takes its first choice)
_PAIR = 0.13  # least difference of the heights of two curves between the same two nodes
_SWING = 0.9  # an end moves at most this far round its circle from where it points [rad]


@dataclass(frozen=True)
class Measures:
    """The sizes [in] of a circuit drawing's texts: ``radius`` of each neuron; ``name`` and ``tag``
    (w, h) above and below it; ``label`` of each weighted synapse; ``end`` of each input and output.
    """

    radius: Mapping[str, float]
    name: Mapping = field(default_factory=dict)
    tag: Mapping = field(default_factory=dict)
    label: Mapping = field(default_factory=dict)
    end: Mapping = field(default_factory=dict)

    def __post_init__(self) -> None:
        for f in ("radius", "name", "tag", "label", "end"):
            object.__setattr__(self, f, MappingProxyType(dict(getattr(self, f))))

    @classmethod
    def estimate(cls, c: Circuit, radius: Mapping[str, float] | None = None) -> Measures:
        """Sizes from character counts (0.06 in each), for a layout without a renderer."""
        radius = dict(radius) if radius is not None else {n.name: MIN_RADIUS for n in c.neurons}

        def size(text: str) -> tuple[float, float]:
            return 0.06 * len(text) + 0.04, 0.13

        labels = {s: size("w1") for n in c.neurons for s in n.synapses}
        labels.update({o: size("w1") for o in c.outputs if o.weight != 1 or o.delay})
        ends = {u: size(u) for u in c.inputs}
        ends.update({("out", o.target): size(o.target) for o in c.outputs})
        names = {n.name: size(n.name.rpartition(".")[2]) for n in c.neurons}
        tags = {n.name: size(f"v{n.vertex}") for n in c.neurons if n.vertex is not None}
        return cls(radius, names, tags, labels, ends).with_room_for_ends(c)

    def with_room_for_ends(self, c: Circuit) -> Measures:
        """These sizes, each circle large enough (up to :data:`MAX_RADIUS`) to space one more end than
        its synapses, :data:`~symctl.plotting.layered.PORT_GAP` apart.
        """
        grown = dict(self.radius)
        for n in c.neurons:
            ends = (
                min((len(n.synapses) + 1) * layered.PORT_GAP / 2.0, MAX_RADIUS) if n.synapses else 0
            )
            grown[n.name] = max(grown.get(n.name, MIN_RADIUS), ends)
        return Measures(grown, self.name, self.tag, self.label, self.end)


@dataclass(frozen=True)
class Arc:
    """One drawn synapse, or the wire to an output ``("out", name)``: ``synapse`` None for a plain
    wire; ``height`` the bulge [in] (> 0 above); ``label`` its weight's centre; ``path`` and
    ``codes`` the matplotlib ``Path``.
    """

    source: str | tuple
    target: str | tuple
    synapse: Synapse | None
    height: float
    label: tuple[float, float] | None
    path: tuple[tuple[float, float], ...] = ()
    codes: tuple[int, ...] = ()

    @property
    def wire(self) -> bool:
        """Whether the arc runs between two bands (a wire with corners)."""
        return 2 in self.codes

    def points(self) -> np.ndarray:
        """Points along the drawn path (``n x 2``)."""
        if not self.wire:
            return layered.bezier_points(self.path)
        pts = np.array(self.path)
        return np.concatenate([np.linspace(a, b, 12) for a, b in itertools.pairwise(pts)])


@dataclass(frozen=True, eq=False)
class CircuitLayout:
    """The positions of a circuit drawing: each node's ``column``, ``row``, centre ``pos`` [in] and
    ``band``; ``radius`` of each neuron; ``arcs`` (synapses, shortest span first, then outputs);
    ``bounds`` ``(x_lo, x_hi, y_lo, y_hi)``; ``narrow`` (no wider than asked), ``clear`` (no curve
    through another's circle or text) and ``labelled`` (every weight placed).
    """

    column: Mapping
    row: Mapping
    pos: Mapping
    radius: Mapping[str, float]
    arcs: tuple[Arc, ...]
    bounds: tuple[float, float, float, float]
    band: Mapping = field(default_factory=dict)
    narrow: bool = True
    clear: bool = True
    labelled: bool = True

    @property
    def fits(self) -> bool:
        """Narrow enough, every curve clear and every label placed."""
        return self.narrow and self.clear and self.labelled

    @property
    def width(self) -> float:
        """The drawing's width [in]."""
        return self.bounds[1] - self.bounds[0]

    def boxes(self, measures: Measures) -> dict:
        """The text boxes ``(x0, y0, x1, y1)`` of the drawing: names, tags, ends, labels."""
        return _text_boxes(self.pos, self.radius, measures, self.arcs)


def _grid(c: Circuit) -> tuple[dict, dict]:
    """Columns (inputs 0, neurons by longest forward path, outputs last) and rows."""
    nodes = [*c.inputs, *(n.name for n in c.neurons)]
    links = [(s.source, s.target) for n in c.neurons for s in n.synapses]
    outs = [("out", o.target) for o in c.outputs]
    _, col = layered.layering(nodes, links, [*c.inputs, *nodes], first=c.inputs, last=outs, floor=1)
    links += [(o.source, ("out", o.target)) for o in c.outputs if o.source in col]
    preds: dict = {n: [] for n in col}
    succs: dict = {n: [] for n in col}
    for a, b in links:
        if a != b:
            succs[a].append(b)
            preds[b].append(a)
    return col, layered.rows(layered.by_layer(col, [*nodes, *outs]), preds, succs, integer=False)


def _extents(node, c_inputs, m: Measures) -> tuple[float, float, float, float]:
    """``(left, right, down, up)``: how far a node's circle or dot and its texts reach [in]."""
    if node in m.radius:
        r = m.radius[node]
        nw, nh = m.name.get(node, (0.0, 0.0))
        tw, th = m.tag.get(node, (0.0, 0.0))
        half = max(r, nw / 2, tw / 2)
        return half, half, r + (NAME_GAP + th if th else 0.0), r + (NAME_GAP + nh if nh else 0.0)
    w, h = m.end.get(node, (0.0, 0.0))
    half = max(DOT, h / 2)
    if node in c_inputs:
        return DOT + _END_GAP + w, DOT, half, half
    return DOT, DOT + _END_GAP + w, half, half


def _text_boxes(pos, radius, m: Measures, arcs=()) -> dict:
    """Every text box ``(x0, y0, x1, y1)`` by ``(kind, key)``: name, tag, end and label."""
    out = {}
    for node, (x, y) in pos.items():
        if node in radius:
            r = radius[node] + NAME_GAP
            if node in m.name:
                out["name", node] = layered.box(x, y + r, m.name[node], va="bottom")
            if node in m.tag:
                out["tag", node] = layered.box(x, y - r, m.tag[node], va="top")
        elif node in m.end:  # an output's on the right
            d = DOT + _END_GAP if isinstance(node, tuple) else -DOT - _END_GAP
            out["end", node] = layered.box(x + d, y, m.end[node], "left" if d > 0 else "right")
    for k, arc in enumerate(arcs):
        if arc.label is not None and arc.synapse in m.label:
            out["label", k] = layered.box(*arc.label, m.label[arc.synapse])
    return out


def _specs(c: Circuit, col) -> list[tuple]:
    """``(source, target, synapse or None)`` of every arc: synapses, shortest first, then outputs."""
    pairs: dict[tuple, list] = {}
    for n in c.neurons:
        for s in n.synapses:
            pairs.setdefault((s.source, s.target), []).append(s)
    out = []
    for (a, b), group in sorted(
        pairs.items(),
        key=lambda kv: (abs(col[kv[0][1]] - col[kv[0][0]]), col[kv[0][1]] <= col[kv[0][0]]),
    ):
        out += [(a, b, s) for s in group]
    for o in c.outputs:
        if o.source in col:
            out.append((o.source, ("out", o.target), o if (o.weight != 1 or o.delay) else None))
    return out


def _column_x(columns: dict, specs, col, ext, m: Measures, gap: float) -> dict[int, float]:
    """Each column's x [in]: room for the circles and names, and for a weight between two."""
    x = {}
    for k in sorted(columns):
        if not x:
            x[k] = 0.0
            continue
        prev = max(x)
        right = max(ext[n][1] for n in columns[prev])
        left = max(ext[n][0] for n in columns[k])
        need = x[prev] + right + gap + left
        arrow = _ARROW * min(1.0, gap / MIN_GAP)  # a tight drawing leaves less room too
        for a, b, s in specs:
            if col[a] == prev and col[b] == k and s in m.label:
                ra, rb = m.radius.get(a, DOT), m.radius.get(b, DOT)
                need = max(need, x[prev] + ra + m.label[s][0] + 2 * arrow + rb)
        x[k] = need
    return x


def _cuts(specs, col, last: int) -> dict[int, int]:
    """Gaps ``k`` (between columns ``k`` and ``k+1``) that every synapse across joins: their counts."""
    cross: dict[int, list[bool]] = {k: [] for k in range(last)}
    for a, b, _ in specs:
        lo, hi = sorted((col[a], col[b]))
        for k in range(lo, hi):
            cross[k].append(col[a] == k and col[b] == k + 1)
    return {k: len(v) for k, v in cross.items() if v and all(v)}


def _bands(x, columns, ext, cuts, width: float | None) -> list[tuple[int, int]]:
    """Columns ``(first, last)`` of each band: the fewest bands that fit, the widest narrowest."""
    ks = sorted(columns)
    if not ks:
        return []
    lo = {k: x[k] - max(ext[n][0] for n in columns[k]) for k in ks}
    hi = {k: x[k] + max(ext[n][1] for n in columns[k]) for k in ks}

    def span(i, j):
        room = (_WIRE + cuts[i - 1] * _WIRE_STEP if i > ks[0] else 0.0) + (
            _WIRE + cuts[j] * _WIRE_STEP if j < ks[-1] else 0.0
        )
        return hi[j] - lo[i] + room + 2 * _MARGIN

    if width is None or span(ks[0], ks[-1]) <= width:
        return [(ks[0], ks[-1])]
    # best[j]: (overflow, bands, widest) of the columns up to j, cut after j
    best: dict[int, tuple] = {}
    choice: dict[int, int] = {}
    for j in ks:
        if j != ks[-1] and j not in cuts:
            continue
        for i in ks:
            if i > j or (i != ks[0] and i - 1 not in best):
                continue
            w = span(i, j)
            before = best[i - 1] if i != ks[0] else (0.0, 0, 0.0)
            cand = (max(before[0], max(w - width, 0.0)), before[1] + 1, max(before[2], w))
            if j not in best or cand < best[j]:
                best[j], choice[j] = cand, i
    out, j = [], ks[-1]
    while True:
        i = choice[j]
        out.append((i, j))
        if i == ks[0]:
            return out[::-1]
        j = i - 1


def circuit_layout(
    c: Circuit,
    radius: Mapping[str, float] | None = None,
    *,
    measures: Measures | None = None,
    width: float | None = None,
    gap: float = MIN_GAP,
) -> CircuitLayout:
    """The positions, curves and extent of the drawing of ``c``, its texts sized by ``measures``
    (default :meth:`Measures.estimate` with circles of ``radius``), cut into bands when wider
    than ``width`` [in]; ``gap`` the least room between columns (under :data:`MIN_GAP`, the room
    either side of a weight shrinks in proportion).

    >>> from symctl import Circuit, controllable_canonical, controller_tf, factor, Structure
    >>> from symctl.plotting.circuit_layout import circuit_layout
    >>> f = factor(controller_tf(2))
    >>> c = Circuit.from_structure(Structure.from_realization(controllable_canonical(f.G2)))
    >>> [(a.source, a.target, round(a.height, 2)) for a in circuit_layout(c).arcs]
    [('u', 'x2', 0.0), ('x2', 'y', 0.0), ('x2', 'y', 0.16), ('u', 'y', -0.36), ('y', ('out', 'y'), 0.0)]
    """
    m = measures if measures is not None else Measures.estimate(c, radius)
    col, row = _grid(c)
    columns = layered.by_layer(col)
    inputs = set(c.inputs)
    ext = {node: _extents(node, inputs, m) for node in col}
    specs = _specs(c, col)
    x = _column_x(columns, specs, col, ext, m, gap)
    cuts = _cuts(specs, col, max(columns, default=0))
    last_neuron = max((col[n.name] for n in c.neurons), default=0)
    first_neuron = min((col[n.name] for n in c.neurons), default=0)
    # an input and an output stay by their neurons: no band of inputs or outputs alone
    cuts = {k: v for k, v in cuts.items() if first_neuron <= k < last_neuron}
    bands = _bands(x, columns, ext, cuts, width)
    band_of = {node: b for b, (i, j) in enumerate(bands) for node in col if i <= col[node] <= j}
    search = len(specs) <= _MAX_CURVES
    pos: dict = {}
    by_spec: dict[int, Arc] = {}
    clear = labelled = True
    top = 0.0
    band_box: list[tuple[float, float, float, float]] = []
    for b, (i, _) in enumerate(bands):
        wire = _WIRE + cuts[i - 1] * _WIRE_STEP if b else 0.0
        left = x[i] - max(ext[n][0] for n in columns[i]) - wire
        mine_nodes = [n for n in col if band_of[n] == b]
        rows = _closed_up([row[n] for n in mine_nodes])
        ys = _row_heights(mine_nodes, {n: rows[row[n]] for n in mine_nodes}, x, col, ext)
        local = {n: (x[col[n]] - left + _MARGIN, ys[n]) for n in mine_nodes}
        idx = [k for k, s in enumerate(specs) if band_of[s[0]] == b and band_of[s[1]] == b]
        mine = [specs[k] for k in idx]
        texts = _text_boxes(local, m.radius, m)
        nodes = list(local)
        obstacles = layered.Obstacles.of(
            [(local[n], m.radius.get(n, DOT)) for n in nodes],
            list(texts.values()),
            nodes,
            [key for _, key in texts],
        )
        chosen, fine, written = route(mine, local, col, m.radius, m.label, obstacles, search=search)
        clear, labelled = clear and fine, labelled and written
        curves = [curve for _, curve, _ in chosen]
        # the band's extent, then moved under the one above
        ink = [
            (lx - e[0], ly - e[2], lx + e[1], ly + e[3])
            for n, (lx, ly) in local.items()
            for e in [ext[n]]
        ]
        ink += [
            layered.box(*w, m.label[s])
            for (_, _, s), (_, _, w) in zip(mine, chosen, strict=True)
            if w
        ]
        x0, x1, y0, y1 = layered.extent([p for c in curves for p in layered.bezier_points(c)], ink)
        dy = top - (0.0 if b == 0 else _band_gap(specs, band_of, b, m)) - y1
        top = y0 + dy
        band_box.append((x0, x1, y0 + dy, y1 + dy))
        for n, (lx, ly) in local.items():
            pos[n] = (lx, ly + dy)
        for k, (h, _, where), curve in zip(idx, chosen, curves, strict=True):
            a, t, s = specs[k]
            path = tuple((px, py + dy) for px, py in curve)
            label = None if where is None else (where[0], where[1] + dy)
            by_spec[k] = Arc(a, t, s, float(h), label, path, (1, 4, 4, 4))
    for b in range(1, len(bands)):
        by_spec.update(_wires(specs, band_of, b, pos, m, band_box))
    arcs = [by_spec[k] for k in sorted(by_spec)]
    boxes = [(b[0], b[2], b[1], b[3]) for b in band_box]
    boxes += _text_boxes(pos, m.radius, m, arcs).values()
    bounds = layered.extent([p for arc in arcs for p in arc.points()], boxes, _MARGIN)
    narrow = width is None or bounds[1] - bounds[0] <= width + 1e-9
    return CircuitLayout(
        col, row, pos, dict(m.radius), tuple(arcs), bounds, band_of, narrow, clear, labelled
    )


def route(arcs, pos, col, radius, labels, obstacles: layered.Obstacles, *, search=True):
    """Per arc ``(source, target, synapse or None)`` its ``(height, curve, label centre or None)``,
    and whether every curve is clear and every label placed.

    Each arc takes the first bridge (straight between neighbouring columns, then growing
    bulges, feedback below) clear of ``obstacles`` where its label fits, apart from the arcs
    between the same nodes, its end moved round the target's circle clear of the ends there;
    a placed label joins the obstacles. Without ``search``, one arch each.
    """
    clear, labelled, up = True, True, 1.0
    chosen: list[tuple] = []
    heights_of: dict[frozenset, list[float]] = {}
    ports: dict = {}  # the angles at which curves already end at each neuron
    lines: list[np.ndarray] = []
    for a, b, s in arcs:
        pa, pb = np.asarray(pos[a], float), np.asarray(pos[b], float)
        ra, rb = radius.get(a, DOT), radius.get(b, DOT)
        forward = col[b] > col[a]
        adjacent = forward and col[b] == col[a] + 1
        if adjacent:
            prefer = 1.0
        elif forward:
            prefer, up = up, -up
        else:
            prefer = -1.0
        taken = heights_of.setdefault(frozenset((a, b)), [])
        size = labels.get(s) if s is not None else None
        apart = max(_PAIR, size[1] + 0.03) if size else _PAIR
        if search:  # the usual heights and ends, then (none clear) more of each
            tiers = [
                (layered.bulges(adjacent, prefer, 0.16 if forward else 0.22, 0.1, 24), _SWING, 3),
                (layered.bulges(adjacent, prefer, 0.12, 0.08, 40), 2 * _SWING, 8),
            ]
        else:  # a hairball: one arch each, as high as it is long
            tiers = [
                ([0.0] if adjacent else [prefer * (0.08 + 0.06 * abs(col[b] - col[a]))], _SWING, 3)
            ]
        used = ports.setdefault(b, []) if b in radius else []
        others = np.concatenate(lines) if lines else None
        u = (pb - pa) / max(float(np.hypot(*(pb - pa))), 1e-12)
        qa, qb = tuple(pa + ra * u), tuple(pb - rb * u)  # where the chord leaves the circles

        tries = _tries(tiers, taken, (apart, prefer), (qa, qb), (pa, ra, pb, rb), used, search)
        pick, fallback = _first_clear(tries, obstacles, {a, b}, size, others)
        if pick is None:  # the least bad, its label where it overlaps the least
            nh, h, drawn, angle = fallback
            clear = clear and nh == 0
            where = None
            if size is not None:
                where = layered.place_label(drawn, size, obstacles, others)
                labelled = labelled and where is not None
                circles = layered.Obstacles(
                    obstacles.centres, obstacles.radii, obstacles.keys, np.zeros((0, 4)), ()
                )
                where = where or layered.place_label(drawn, size, circles, others)
                where = where or tuple(float(v) for v in layered.bezier_points(drawn, [0.5])[0])
            pick = (h, drawn, where, angle)
        h, drawn, where, angle = pick
        taken.append(h)
        used.append(angle)
        chosen.append((h, drawn, where))
        lines.append(layered.bezier_points(drawn))
        if where is not None:
            obstacles = obstacles.with_box(layered.box(*where, size))
    return chosen, clear, labelled


def _tries(tiers, taken, spacing, chord, circles, used, search: bool):
    """Each curve ``route`` tries, in order, as ``(height, end angle, curve, 1 when no end is
    clear of those ``used``)``; ``spacing`` is ``(least gap to the heights taken, side)``."""
    (apart, prefer), (qa, qb), (pa, ra, pb, rb) = spacing, chord, circles
    for cands, swing, count in tiers:
        cands = [h for h in cands if all(abs(h - t) >= apart for t in taken)] or [
            (max(map(abs, taken)) + apart) * prefer
        ]
        for h in cands:
            curve = layered.bridge(qa, qb, h)
            natural = math.atan2(curve[2][1] - pb[1], curve[2][0] - pb[0])
            angles = layered.end_angles(natural, used, rb, swing, count)
            ends = angles or [natural]
            drawn = layered.trimmed_ends(curve, pa, ra, pb, rb + layered.TIP, ends)
            for angle, curve_drawn in zip(ends, drawn, strict=True):
                yield h, angle, curve_drawn, int(not angles)
            if not search:
                return


def _first_clear(tries, obstacles, ends, size, others, first: int = 4):
    """The first of ``tries`` clear of ``obstacles`` with room for its label of ``size`` (None:
    no label) as ``(height, curve, label centre, angle)``, or None; and the least bad one tried,
    ``(hits, height, curve, angle)``. Curves are judged in batches growing fourfold from ``first``.
    """
    fallback, batch = None, first
    while chunk := list(itertools.islice(tries, batch)):
        bad = layered.hits_many(layered.bezier_many([c for _, _, c, _ in chunk]), obstacles, ends)
        for (h, angle, drawn, penalty), nh in zip(chunk, bad.tolist(), strict=True):
            nh += penalty
            if fallback is None or nh < fallback[0]:
                fallback = (nh, h, drawn, angle)
            if nh:
                continue
            where = layered.place_label(drawn, size, obstacles, others) if size else None
            if size is None or where is not None:
                return (h, drawn, where, angle), fallback
        batch *= 4
    return None, fallback


def _row_heights(nodes, row, x, col, ext) -> dict:
    """Each node's height [in]: each row as near the one above as its nodes' texts allow."""
    levels = sorted({row[n] for n in nodes}, reverse=True)
    at = {lv: [n for n in nodes if row[n] == lv] for lv in levels}
    y: dict[float, float] = {}
    for k, lv in enumerate(levels):
        if not k:
            y[lv] = 0.0
            continue
        prev = levels[k - 1]
        h = y[prev] - _ROW_STEP * (prev - lv)
        for above in levels[:k]:
            for a in at[above]:
                for b in at[lv]:
                    xa, xb = x[col[a]], x[col[b]]
                    if (
                        xa + ext[a][1] + 0.05 > xb - ext[b][0]
                        and xb + ext[b][1] + 0.05 > xa - ext[a][0]
                    ):
                        h = min(h, y[above] - ext[a][2] - ext[b][3] - _ROW_GAP)
        y[lv] = h
    return {n: y[row[n]] for n in nodes}


def _closed_up(rows: list[float]) -> dict[float, float]:
    """Rows with no gap wider than one row between neighbours."""
    levels = sorted(set(rows))
    out, at = {}, 0.0
    for k, r in enumerate(levels):
        if k:
            at += min(r - levels[k - 1], 1.0)
        out[r] = at
    return out


def _crossing(specs, band_of, b: int) -> list[int]:
    """The arcs (indices of ``specs``) from band ``b - 1`` into band ``b``."""
    return [k for k, s in enumerate(specs) if band_of[s[0]] == b - 1 and band_of[s[1]] == b]


def _band_gap(specs, band_of, b: int, m: Measures) -> float:
    """The room between bands ``b - 1`` and ``b``: the wires across and their labels."""
    gap = 0.12
    for k in _crossing(specs, band_of, b):
        s = specs[k][2]
        gap += (m.label[s][1] if s in m.label else 0.0) + 0.08
    return gap


def _wires(specs, band_of, b: int, pos, m: Measures, band_box) -> dict[int, Arc]:
    """The arcs across the cut above band ``b``: out right, back under band ``b - 1``, in left."""
    out = {}
    crossing = sorted(_crossing(specs, band_of, b), key=lambda k: -pos[specs[k][0]][1])
    n = len(crossing)
    levels = {}
    y = band_box[b - 1][2] - 0.06
    for k in reversed(range(n)):
        s = specs[crossing[k]][2]
        h = m.label[s][1] if s in m.label else 0.0
        levels[k] = y - h / 2 - 0.02
        y = levels[k] - h / 2 - 0.06
    for k, index in enumerate(crossing):
        a, t, s = specs[index]
        (xa, ya), (xt, yt) = pos[a], pos[t]
        ra, rt_ = m.radius.get(a, DOT), m.radius.get(t, DOT) + layered.TIP
        yg = levels[k]
        xr = band_box[b - 1][1] + _WIRE + (n - 1 - k) * _WIRE_STEP
        xl = band_box[b][0] - _WIRE + (n - 1 - k) * _WIRE_STEP
        xr, xl = max(xr, xa + ra + 2 * _CORNER), min(xl, xt - rt_ - 2 * _CORNER)
        corners = [(xa + ra, ya), (xr, ya), (xr, yg), (xl, yg), (xl, yt), (xt - rt_, yt)]
        pts, codes = _rounded(corners, _CORNER)
        label = ((xr + xl) / 2, yg) if s in m.label else None
        out[index] = Arc(a, t, s, 0.0, label, pts, codes)
    return out


def _rounded(corners, r: float) -> tuple[tuple, tuple]:
    """A polyline through ``corners``, inner corners rounded by ``r``: points and ``Path`` codes."""

    def toward(q, p):
        d = math.hypot(p[0] - q[0], p[1] - q[1]) or 1.0
        return (q[0] + r * (p[0] - q[0]) / d, q[1] + r * (p[1] - q[1]) / d)

    pts, codes = [corners[0]], [1]
    for p, q, nxt in zip(corners, corners[1:], corners[2:], strict=False):
        pts += [toward(q, p), q, toward(q, nxt)]
        codes += [2, 3, 3]
    return (*pts, corners[-1]), (*codes, 2)
