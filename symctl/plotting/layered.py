"""The one layered layout of the structure, circuit and delay-graph drawings, as numbers.

After Sugiyama, Tagawa and Toda (IEEE Trans. Syst. Man Cybern. 11(2), 1981); inches, no
matplotlib: layers, a bend per layer an edge crosses, barycentre ordering, rows by
isotonic least squares; orthogonal routes with a slot per net in each gap (as ELK Layered:
Schulze, Spönemann and von Hanxleden, J. Vis. Lang. Comput. 25, 2014); curved routes as
Bézier bridges clear of :class:`Obstacles`, and their labels.
"""

from __future__ import annotations

import bisect
import itertools
import math
from collections.abc import Callable, Hashable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import NamedTuple

import networkx as nx
import numpy as np

from symctl.compatibility.signalgraph import back_edges

_EPS = 1e-9


def layering(nodes, edges, sources, *, against=(), first=(), last=(), floor=0):
    """``(flow, layer)``: each edge as ``(a, b, False)``, or ``(b, a, True)`` when it closes a
    cycle in a depth-first search from ``sources`` or is in ``against``; layers by
    :func:`longest_path` (``last`` may hold nodes beyond ``nodes``).
    """
    against = set(against)
    succ: dict = {v: [] for v in nodes}
    for a, b in edges:
        if a != b and (a, b) not in against and b not in succ[a]:
            succ[a].append(b)
    against.update(back_edges(succ, sources))
    flow = [(b, a, True) if (a, b) in against else (a, b, False) for a, b in edges]
    dag = nx.DiGraph()
    dag.add_nodes_from(nodes)
    dag.add_edges_from((a, b) for a, b, _ in flow if a != b)
    ends = [v for v in last if v not in dag]
    order = [*nx.topological_sort(dag), *ends]
    preds = {**dag.pred, **dict.fromkeys(ends, ())}
    return flow, longest_path(order, preds, first=first, last=last, floor=floor)


def longest_path(nodes, preds: Mapping, *, first=(), last=(), floor=0, layer=None) -> dict:
    """Layers: ``first`` at 0, others one right of their furthest laid-out predecessor (at least
    ``floor``), ``last`` together at the right; ``nodes`` topologically sorted, ``layer`` updated.
    """
    layer = {} if layer is None else layer
    first, last, nodes = set(first), set(last), list(nodes)
    for v in nodes:
        layer[v] = (
            0 if v in first else max([floor, *(layer[p] + 1 for p in preds[v] if p in layer)])
        )
    ends = [v for v in nodes if v in last]
    if ends:
        at = max([*(layer[v] for v in ends), *(layer[v] + 1 for v in nodes if v not in last)])
        layer.update(dict.fromkeys(ends, at))
    return layer


def by_layer(node_layer: Mapping, nodes=None) -> dict[int, list]:
    """The ``nodes`` (default all) of each layer, in their order."""
    out: dict[int, list] = {}
    for v in node_layer if nodes is None else nodes:
        out.setdefault(node_layer[v], []).append(v)
    return out


def spread(count: int, half: float) -> list[float]:
    """``count`` offsets evenly from ``+half`` to ``-half`` (0 for one)."""
    if count <= 1:
        return [0.0] * count
    return [half - 2 * half * k / (count - 1) for k in range(count)]


def box(x: float, y: float, size, ha="center", va="center") -> tuple[float, float, float, float]:
    """The box ``(x0, y0, x1, y1)`` of a text of ``size`` (w, h) at ``(x, y)``, aligned as matplotlib."""
    w, h = size
    x0 = x - {"left": 0.0, "center": w / 2, "right": w}[ha]
    y0 = y - {"bottom": 0.0, "center": h / 2, "top": h}[va]
    return x0, y0, x0 + w, y0 + h


def extent(points, boxes=(), margin: float = 0.0) -> tuple[float, float, float, float]:
    """``(x_lo, x_hi, y_lo, y_hi)`` around ``points`` and boxes ``(x0, y0, x1, y1)``, plus ``margin``."""
    pts = [*points, *((b[0], b[1]) for b in boxes), *((b[2], b[3]) for b in boxes)]
    (x0, y0), (x1, y1) = np.min(pts, axis=0), np.max(pts, axis=0)
    return float(x0) - margin, float(x1) + margin, float(y0) - margin, float(y1) + margin


def split(edges: Sequence[tuple], layer: Mapping) -> tuple[list[list], dict, dict, dict]:
    """Each edge ``(a, b, ...)`` as a chain ``[a, (k, l)..., b]``, a bend ``(k, l)`` per layer
    ``l`` between: the chains, every node's layer and its neighbours up and down.
    """
    node_layer = dict(layer)
    up: dict = {v: [] for v in layer}
    down: dict = {v: [] for v in layer}
    chains = []
    for k, (a, b, *_) in enumerate(edges):
        chain = [a, *((k, step) for step in range(layer[a] + 1, layer[b])), b]
        for node in chain[1:-1]:
            node_layer[node] = node[1]
            up[node], down[node] = [], []
        for p, q in itertools.pairwise(chain):
            down[p].append(q)
            up[q].append(p)
        chains.append(chain)
    return chains, node_layer, up, down


def crossings(layers: Sequence[Sequence], down: Mapping) -> int:
    """Edge crossings between neighbouring layers (inversions of the edges' lower ends)."""
    total = 0
    for upper, lower in itertools.pairwise(layers):
        at = {node: k for k, node in enumerate(lower)}
        seen: list[int] = []  # the lower ends of the edges so far, sorted
        for _, b in sorted((k, at[m]) for k, node in enumerate(upper) for m in down[node]):
            total += len(seen) - bisect.bisect_right(seen, b)
            bisect.insort(seen, b)
    return total


def order(layers: Sequence[Sequence], up: Mapping, down: Mapping, sweeps: int = 8) -> list[list]:
    """Barycentre sweeps down and up (``sweeps`` each); the order with the fewest crossings."""
    current = [list(o) for o in layers]
    best, fewest = [list(o) for o in current], crossings(current, down)
    for sweep in range(2 * sweeps):
        ks = range(1, len(current)) if sweep % 2 == 0 else range(len(current) - 2, -1, -1)
        for k in ks:
            near, nbrs = (current[k - 1], up) if sweep % 2 == 0 else (current[k + 1], down)
            at = {node: i for i, node in enumerate(near)}
            mean = {
                node: sum(at[m] for m in nbrs[node]) / len(nbrs[node]) if nbrs[node] else i
                for i, node in enumerate(current[k])
            }
            current[k] = sorted(current[k], key=lambda node, m=mean: m[node])
        count = crossings(current, down)
        if count < fewest:
            best, fewest = [list(o) for o in current], count
    return best


def isotonic(target, weight, gaps) -> np.ndarray:
    r"""Least squares :math:`\sum_k w_k (d_k - t_k)^2` under :math:`d_{k+1} \ge d_k + g_k`: with
    :math:`o` the running sum of the gaps, the isotonic regression of :math:`t - o`, plus :math:`o`.
    """
    target = np.asarray(target, float)
    offset = np.concatenate(([0.0], np.cumsum(gaps)))[: len(target)]
    free = target - offset
    if np.all(free[1:] >= free[:-1]):  # most calls of a sweep: nothing to pool
        return free + offset
    from scipy.optimize import isotonic_regression  # ~0.5 s to import: only when drawing

    return isotonic_regression(free, weights=np.asarray(weight, float)).x + offset


def positions(layers, up, down, gaps, weight: Callable[[Hashable, Hashable], float], sweeps=8):
    """Each node's place across its layer, the order kept: near the ``weight``-ed mean of its
    neighbours (left, right, both; ``sweeps`` times), ``gaps`` apart at least.
    """
    at: dict = {}
    for nodes, gap in zip(layers, gaps, strict=True):
        at.update(zip(nodes, isotonic(np.zeros(len(nodes)), np.ones(len(nodes)), gap), strict=True))
    for sweep in range(3 * sweeps):
        side = sweep % 3  # 0: from the left, 1: from the right, 2: both
        ks = range(len(layers)) if side != 1 else range(len(layers) - 1, -1, -1)
        for k in ks:
            target, pull = [], []
            for node in layers[k]:
                nbrs = (up[node], down[node], [*up[node], *down[node]])[side]
                w = [weight(node, m) for m in nbrs]
                target.append(
                    sum(a * at[m] for a, m in zip(w, nbrs, strict=True)) / sum(w) if w else at[node]
                )
                pull.append(sum(w) if w else 0.5)
            at.update(zip(layers[k], isotonic(target, pull, gaps[k]), strict=True))
    return at


def fit_rows(desired: Sequence[float], integer: bool = True) -> list:
    """Rows, top first and one apart at least, nearest ``desired`` (integer: rounded half up)."""
    n = len(desired)
    fit = [-float(y) for y in isotonic([-d for d in desired], [1.0] * n, [1.0] * (n - 1))]
    if not integer:
        return fit
    out = [math.floor(round(y, 9) + 0.5) for y in fit]  # the last bits' noise rounded away
    for i in range(1, n):
        out[i] = min(out[i], out[i - 1] - 1)
    return out


def rows(columns: Mapping[int, list], preds: Mapping, succs: Mapping, integer: bool = True) -> dict:
    """Rows in each layer (``columns``, sorted in place top first): five barycentre sweeps,
    alternately on ``preds`` and ``succs``, each column fitted by :func:`fit_rows`.
    """
    row: dict = {}
    for neighbours in (preds, succs, preds, succs, preds):
        for c in sorted(columns, reverse=neighbours is succs):
            nodes = columns[c]
            desired = {}
            for n in nodes:
                ys = [row[m] for m in neighbours[n] if m in row]
                desired[n] = sum(ys) / len(ys) if ys else row.get(n, 0.0)
            nodes.sort(key=lambda n, d=desired: -d[n])
            row.update(zip(nodes, fit_rows([desired[n] for n in nodes], integer), strict=True))
    return row


def break_cycles(graph: nx.DiGraph, key) -> nx.DiGraph:
    """``graph`` with the edge of least ``key(edge)`` removed from each cycle found, in place."""
    while True:
        try:
            cycle = nx.find_cycle(graph)
        except nx.NetworkXNoCycle:
            return graph
        graph.remove_edge(*min(cycle, key=key)[:2])


class Segment(NamedTuple):
    """The vertical piece of one net in one gap; ``attachments`` ``(y, side)`` are horizontal
    pieces at ``y`` to the gap's ``"left"`` or ``"right"`` edge.

    >>> from symctl.plotting.layered import Segment, assign_slots
    >>> a = Segment("a", ((0.0, "left"), (2.0, "right")))   # up from row 0 to row 2
    >>> b = Segment("b", ((1.0, "left"), (3.0, "right")))   # up from row 1 to row 3
    >>> assign_slots([a, b])   # a left of b would cross twice, b left of a never
    {'b': 0, 'a': 1}
    """

    net: Hashable
    attachments: tuple[tuple[float, str], ...]

    @property
    def low(self) -> float:
        return min(y for y, _ in self.attachments)

    @property
    def high(self) -> float:
        return max(y for y, _ in self.attachments)


def merge(segments: Iterable[Segment]) -> list[Segment]:
    """One segment per net: the attachments of a net's segments joined (first seen first)."""
    nets: dict = {}
    for s in segments:
        nets.setdefault(s.net, []).extend(s.attachments)
    return [Segment(net, tuple(dict.fromkeys(att))) for net, att in nets.items()]


def _segment_crossings(left: Segment, right: Segment) -> int:
    """Crossings when ``left`` runs left of ``right``; a piece along another counts three."""

    def inside(y, s):
        return s.low + _EPS < y < s.high - _EPS

    count = sum(1 for y, side in right.attachments if side == "left" and inside(y, left))
    count += sum(1 for y, side in left.attachments if side == "right" and inside(y, right))
    ends = {y for y, side in left.attachments if side == "right"}
    along = [y for y, side in right.attachments if side == "left"]
    return count + 3 * sum(1 for y in along if any(abs(y - e) <= _EPS for e in ends))


def _overlap(a: Segment, b: Segment) -> bool:
    return a.low <= b.high + _EPS and b.low <= a.high + _EPS


def assign_slots(segments: Sequence[Segment]) -> dict:
    """``net -> slot`` (0, 1, ... left to right) of each vertical segment: overlapping ones apart,
    in the order crossing fewer pieces (preference cycles broken at the weakest), first fit.
    """
    vertical = [s for s in segments if s.high - s.low > _EPS]
    prefer = nx.DiGraph()
    prefer.add_nodes_from(range(len(vertical)))
    for i, j in itertools.combinations(range(len(vertical)), 2):
        a, b = vertical[i], vertical[j]
        if _overlap(a, b):
            ab, ba = _segment_crossings(a, b), _segment_crossings(b, a)
            prefer.add_edge(*((i, j) if ab <= ba else (j, i)), weight=abs(ba - ab))
    break_cycles(prefer, lambda e: (prefer.edges[e[0], e[1]]["weight"], -e[0]))
    slot: dict[int, int] = {}
    for i in nx.lexicographical_topological_sort(prefer):
        taken = {slot[j] for j in slot if _overlap(vertical[i], vertical[j])}
        k = max([slot[j] for j in prefer.predecessors(i) if j in slot], default=-1) + 1
        while k in taken:
            k += 1
        slot[i] = k
    return {vertical[i].net: k for i, k in slot.items()}


def junctions(segment: Segment) -> list[float]:
    """Heights where three or more pieces of one net meet (up, down, left, right): a dot each."""
    out = []
    for y in sorted({y for y, _ in segment.attachments}):
        sides = {side for yy, side in segment.attachments if abs(yy - y) <= _EPS}
        if len(sides) + (y > segment.low + _EPS) + (y < segment.high - _EPS) >= 3:
            out.append(y)
    return out


class Wire(NamedTuple):
    """A drawn polyline from ``source`` to ``target`` (None: outside), arrow at its end; ``delay``
    steps of the delay it feeds, ``feedback`` on a feedback arc.
    """

    points: tuple[tuple[float, float], ...]
    delay: int
    source: str | None
    target: str | None
    feedback: bool


def _shared(p, q) -> float:
    """The length of the common start of two polylines (0 when they start apart)."""
    if math.dist(p[0], q[0]) > _EPS:
        return 0.0
    i = j = 0
    at, done = p[0], 0.0
    while i < len(p) - 1 and j < len(q) - 1:
        da = (p[i + 1][0] - at[0], p[i + 1][1] - at[1])
        db = (q[j + 1][0] - at[0], q[j + 1][1] - at[1])
        la, lb = math.hypot(*da), math.hypot(*db)
        if la < _EPS or lb < _EPS:
            i, j = i + (la < _EPS), j + (la >= _EPS)
            continue
        if abs(da[0] / la - db[0] / lb) > _EPS or abs(da[1] / la - db[1] / lb) > _EPS:
            break
        step = min(la, lb)
        at = (at[0] + da[0] / la * step, at[1] + da[1] / la * step)
        done += step
        i, j = i + (la - step < _EPS), j + (lb - step < _EPS)
    return done


def dashed_part(wire: Wire, wires) -> tuple[tuple[float, float], ...]:
    """The part of a delay wire after it leaves every undelayed wire of its signal (drawn solid).

    >>> from symctl.plotting.layered import Wire, dashed_part
    >>> solid = Wire(((0, 0), (2, 0)), 0, "a", "b", False)
    >>> delayed = Wire(((0, 0), (1, 0), (1, 1), (2, 1)), 1, "a", "c", False)
    >>> dashed_part(delayed, [solid, delayed])
    ((1.0, 0.0), (1, 1), (2, 1))
    """
    shared = [
        _shared(wire.points, w.points) for w in wires if w.source == wire.source and not w.delay
    ]
    cut = max([*shared, 0.0])
    if cut <= _EPS:
        return wire.points
    out, walked = [], 0.0
    for a, b in itertools.pairwise(wire.points):
        length = math.dist(a, b)
        if walked + length > cut + _EPS:
            if not out:
                t = (cut - walked) / length if length else 0.0
                out.append((a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t))
            out.append(b)
        walked += length
    return tuple(out)


def clean(points) -> tuple[tuple[float, float], ...]:
    """The polyline without repeated points and without corners on a straight run."""
    out: list[tuple[float, float]] = []
    for p in points:
        if out and math.dist(out[-1], p) < _EPS:
            continue
        if len(out) >= 2:
            (x0, y0), (x1, y1) = out[-2], out[-1]
            if (abs(x0 - x1) < _EPS and abs(x1 - p[0]) < _EPS) or (
                abs(y0 - y1) < _EPS and abs(y1 - p[1]) < _EPS
            ):
                out[-1] = p
                continue
        out.append(p)
    return tuple(out)


CLEAR = 0.035  # how near a curve may pass a circle it does not end at [in]
PORT_GAP = 0.085  # least distance along a circle between two curves' ends [in] (an arrow head)
TIP = 0.012  # an arrow's tip stops this far from its circle [in]
_BOX_MARGIN = 0.015  # a curve keeps this far from a text box
_END_MARGIN = 0.04  # ... and this far from the texts of a node it ends at (its arrow head)
_INSIDE = 10  # a point inside a circle counts this many times one near it (hits)
_LABEL_MARGIN = 0.025  # a label keeps this far from every other text
_T = np.linspace(0.0, 1.0, 49)


def bezier_points(bezier, t=_T) -> np.ndarray:
    """Points of a piecewise cubic Bézier (``3k + 1`` control points) at ``t`` in each segment."""
    ctrl = np.asarray(bezier, dtype=float)
    segments = [ctrl[k : k + 4] for k in range(0, len(ctrl) - 1, 3)]
    return bezier_many(segments, t).reshape(-1, 2)


def bezier_many(curves, t=_T) -> np.ndarray:
    """The points at ``t`` of cubic Béziers of 4 control points each, as curves x points x 2."""
    ctrl = np.asarray(curves, dtype=float)[:, None]
    t = np.asarray(t, dtype=float)[:, None]
    s = 1 - t
    p0, c1, c2, p1 = (ctrl[:, :, k] for k in range(4))
    return s**3 * p0 + 3 * s * s * t * c1 + 3 * s * t * t * c2 + t**3 * p1


def at_x(bezier, x: float) -> tuple[float, float]:
    """The point of the curve at abscissa ``x`` (each segment x-monotone; clamped to the ends)."""
    ctrl = [(float(px), float(py)) for px, py in bezier]  # plain floats: a fast bisection
    segments = [ctrl[k : k + 4] for k in range(0, len(ctrl) - 1, 3)]

    def point(seg, t, i):
        p0, c1, c2, p1 = seg
        return (
            (1 - t) ** 3 * p0[i]
            + 3 * (1 - t) ** 2 * t * c1[i]
            + 3 * (1 - t) * t**2 * c2[i]
            + t**3 * p1[i]
        )

    for k, seg in enumerate(segments):
        lo, hi = sorted((seg[0][0], seg[3][0]))
        if not (lo - _EPS <= x <= hi + _EPS or k == len(segments) - 1):
            continue
        rising, a, b = seg[3][0] >= seg[0][0], 0.0, 1.0
        for _ in range(40):  # bisection on the segment's parameter
            t = (a + b) / 2
            a, b = (t, b) if (point(seg, t, 0) < x) == rising else (a, t)
        return point(seg, (a + b) / 2, 0), point(seg, (a + b) / 2, 1)
    return ctrl[-1]  # pragma: no cover - no segments


def line(p, q) -> list[tuple[float, float]]:
    """A straight segment from ``p`` to ``q`` as cubic Bézier control points ``c, c, q``."""
    (x0, y0), (x1, y1) = p, q
    return [
        (x0 + (x1 - x0) / 3, y0 + (y1 - y0) / 3),
        (x0 + 2 * (x1 - x0) / 3, y0 + 2 * (y1 - y0) / 3),
        q,
    ]


def bridge(a, b, h: float) -> tuple[tuple[float, float], ...]:
    r"""The cubic Bézier ``(a, C1, C2, b)`` rising by ``h`` over the chord's middle along its
    upward normal (right for a vertical chord); inner points :math:`\tfrac43 h` off the chord,
    0.7 of it from the far ends, so a tall bridge still meets its circles from the side.
    """
    (ax, ay), (bx, by) = (float(v) for v in a), (float(v) for v in b)  # floats: fast, exact
    dx, dy = bx - ax, by - ay
    length = max(float(np.hypot(dx, dy)), 1e-12)
    nx_, ny = -dy / length, dx / length
    if ny < -1e-12 or (abs(ny) <= 1e-12 and nx_ < 0):
        nx_, ny = -nx_, -ny
    rise = 4.0 / 3.0 * h
    ux, uy = rise * nx_, rise * ny
    return (
        (ax, ay),
        (ax + 0.7 * dx + ux, ay + 0.7 * dy + uy),
        (bx - 0.7 * dx + ux, by - 0.7 * dy + uy),
        (bx, by),
    )


def trimmed(curve, a, ra: float, b, rb: float, a1: float | None = None):
    """``curve`` from the border of circle ``(a, ra)`` to that of ``(b, rb)``, each end on the
    radius towards its inner control point (or at angle ``a1`` [rad]), pointing at the centre.
    """
    return trimmed_ends(curve, a, ra, b, rb, [a1])[0]


def trimmed_ends(curve, a, ra: float, b, rb: float, angles) -> list:
    """:func:`trimmed` at each of the end ``angles`` (the start is the same for all)."""
    _, c1, c2, _ = curve
    q0, k1 = _port(a, c1, ra, None)
    return [(q0, k1, k2, q3) for q3, k2 in (_port(b, c2, rb, a1) for a1 in angles)]


def _port(centre, towards, r: float, angle: float | None):
    """The end on circle ``(centre, r)`` at ``angle`` (None: towards ``towards``), and the
    control point beside it, half-way out to ``towards``."""
    (cx, cy), (tx, ty) = (float(v) for v in centre), (float(v) for v in towards)
    if angle is None:
        dx, dy = tx - cx, ty - cy
        angle = math.atan2(dy, dx) if np.hypot(dx, dy) > 1e-12 else 0.0
    ox, oy = math.cos(angle), math.sin(angle)
    qx, qy = cx + r * ox, cy + r * oy
    reach = float(np.hypot(tx - qx, ty - qy))
    return (qx, qy), (qx + ox * 0.5 * reach, qy + oy * 0.5 * reach)


def bulges(straight: bool, prefer: float, start: float, step: float, count: int) -> list:
    """Candidate bulges: 0 first when ``straight``, then growing, on the ``prefer`` side first."""
    out = [0.0] if straight else []
    for size in (start + k * step for k in range(count)):
        if size > 0:
            out += [prefer * size, -prefer * size]
    return out


def end_angles(natural: float, used: list[float], radius: float, swing: float, count: int):
    """Up to ``count`` angles for a curve's end on a circle, nearest ``natural`` within ``swing``,
    :data:`PORT_GAP` clear of those ``used``.
    """
    need = PORT_GAP / max(radius, 1e-9)
    steps = int(swing / (need / 3))
    tries = np.array([natural + sign * k * need / 3 for k in range(steps + 1) for sign in (1, -1)])
    if used:
        d = np.abs((tries[:, None] - np.array(used)[None, :] + math.pi) % (2 * math.pi) - math.pi)
        tries = tries[(d >= need - 1e-9).all(axis=1)]
    return [float(t) for t in dict.fromkeys(tries.tolist())][:count]


@dataclass(frozen=True, eq=False)
class Obstacles:
    """What a curve must not cross: circles (``centres``, ``radii``, their node ``keys``) and text
    boxes ``(x0, y0, x1, y1)`` (``box_keys``: their node, or None).
    """

    centres: np.ndarray
    radii: np.ndarray
    keys: tuple
    boxes: np.ndarray
    box_keys: tuple

    @classmethod
    def of(cls, circles, boxes, keys=None, box_keys=None) -> Obstacles:
        """From ``[((x, y), r), ...]`` and ``[(x0, y0, x1, y1), ...]``."""
        radii = np.array([r for _, r in circles], float)
        boxes = np.array(boxes, float).reshape(-1, 4)
        return cls(
            np.array([c for c, _ in circles], float).reshape(-1, 2),
            radii,
            tuple(keys) if keys is not None else tuple(range(len(radii))),
            boxes,
            tuple(box_keys) if box_keys is not None else (None,) * len(boxes),
        )

    def with_box(self, box) -> Obstacles:
        """These obstacles and one more text box (a label's)."""
        boxes = np.vstack([self.boxes, box])
        return Obstacles(self.centres, self.radii, self.keys, boxes, (*self.box_keys, None))


def hits(points: np.ndarray, obstacles: Obstacles, ends=()) -> int:
    """How bad ``points`` are: those (outside the circles of ``ends``) near a circle or in a box,
    plus ten times those inside a circle; 0 is clear.
    """
    return int(hits_many(np.asarray(points, float)[None], obstacles, ends)[0])


def hits_many(points: np.ndarray, obstacles: Obstacles, ends=()) -> np.ndarray:
    """:func:`hits` of each curve of ``points`` (curves x points x 2) at once: a circle or a box
    counts for a curve when it is near that curve's bounding box, as in :func:`hits`."""
    own = np.array([k in ends for k in obstacles.keys], bool)
    px, py = points[..., 0], points[..., 1]
    keep = np.ones(px.shape, bool)
    for k in np.flatnonzero(own):
        cx, cy = obstacles.centres[k]
        keep &= np.hypot(px - cx, py - cy) > obstacles.radii[k] + 1e-9
    inf = np.inf
    x0, x1 = np.where(keep, px, inf).min(axis=1), np.where(keep, px, -inf).max(axis=1)
    y0, y1 = np.where(keep, py, inf).min(axis=1), np.where(keep, py, -inf).max(axis=1)
    bad = np.zeros(px.shape, bool)
    inside = np.zeros(px.shape, bool)
    if len(obstacles.radii) and (~own).any():
        c, r = obstacles.centres[~own], (obstacles.radii + CLEAR)[~own]
        near = (
            (c[None, :, 0] > x0[:, None] - r)
            & (c[None, :, 0] < x1[:, None] + r)
            & (c[None, :, 1] > y0[:, None] - r)
            & (c[None, :, 1] < y1[:, None] + r)
        )
        if near.any():
            at = near.any(axis=0)  # the circles near any curve
            c, r, near = c[at], r[at], near[:, None, at]
            d = np.hypot(px[..., None] - c[:, 0], py[..., None] - c[:, 1])
            bad |= ((d < r) & near).any(axis=2)
            inside |= ((d < r - CLEAR) & near).any(axis=2)
    if len(obstacles.boxes):
        b = obstacles.boxes
        m = np.array([_END_MARGIN if k in ends else _BOX_MARGIN for k in obstacles.box_keys])
        lo_x, hi_x, lo_y, hi_y = b[:, 0] - m, b[:, 2] + m, b[:, 1] - m, b[:, 3] + m
        near = (
            (lo_x < x1[:, None])
            & (hi_x > x0[:, None])
            & (lo_y < y1[:, None])
            & (hi_y > y0[:, None])
        )
        if near.any():
            at = near.any(axis=0)
            near, lo_x, hi_x, lo_y, hi_y = near[:, at], lo_x[at], hi_x[at], lo_y[at], hi_y[at]
            bad |= (
                (px[..., None] > lo_x)
                & (px[..., None] < hi_x)
                & (py[..., None] > lo_y)
                & (py[..., None] < hi_y)
                & near[:, None, :]
            ).any(axis=2)
    return (bad & keep).sum(axis=1) + _INSIDE * (inside & keep).sum(axis=1)


def _box_free(box, obstacles: Obstacles) -> bool:
    """Whether the box ``(x0, y0, x1, y1)`` overlaps no circle and no other box."""
    x0, y0, x1, y1 = box
    c, b, m = obstacles.centres, obstacles.boxes, _LABEL_MARGIN
    d = np.hypot(np.clip(c[:, 0], x0, x1) - c[:, 0], np.clip(c[:, 1], y0, y1) - c[:, 1])
    if (d < obstacles.radii + 0.02).any():
        return False
    return not (
        (b[:, 0] < x1 + m) & (b[:, 2] > x0 - m) & (b[:, 1] < y1 + m) & (b[:, 3] > y0 - m)
    ).any()


def place_label(curve, size, obstacles: Obstacles, lines=None) -> tuple[float, float] | None:
    """The centre of a label of ``size`` on ``curve`` (tried from the middle out) on no circle and
    no box, crossed by the fewest points of ``lines``; or None.
    """
    best, best_cost = None, None
    pts = np.zeros((0, 2)) if lines is None else np.asarray(lines, float).reshape(-1, 2)
    for t in (0.5, 0.42, 0.58, 0.34, 0.66, 0.27, 0.73, 0.2, 0.8):
        x, y = (float(v) for v in bezier_points(curve, [t])[0])
        x0, y0, x1, y1 = box(x, y, size)
        if not _box_free((x0, y0, x1, y1), obstacles):
            continue
        cost = int(
            ((pts[:, 0] > x0) & (pts[:, 0] < x1) & (pts[:, 1] > y0) & (pts[:, 1] < y1)).sum()
        )
        if cost == 0:
            return x, y
        if best_cost is None or cost < best_cost:
            best, best_cost = (x, y), cost
    return best
