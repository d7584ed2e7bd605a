r"""Orthogonal wires between the columns of a layered drawing: the vertical segments' slots.

A layered drawing puts blocks in columns; a wire from one row to another turns twice
in the gap between two columns: horizontal, vertical, horizontal. This module decides
where in the gap each vertical segment runs (its *slot*), as the orthogonal edge router
of a layered layout does (ELK Layered's ``ORTHOGONAL`` routing: Schulze, Spönemann and
von Hanxleden, "Drawing layered graphs with port constraints", J. Vis. Lang. Comput.
25, 2014):

* the segments of one *net* (a signal that branches: one source, several wires) in one
  gap share one vertical, with a junction dot where a branch leaves it;
* two segments whose vertical extents overlap take different slots, in the order that
  crosses fewer horizontal pieces (each order's crossings are counted; cycles of
  preferences are broken by dropping the weakest);
* segments that do not overlap may share a slot, so a gap is as wide as its densest
  point needs.

Each segment is described by its *attachments*: the rows ``y`` where a horizontal piece
leaves it, to the ``"left"`` or to the ``"right"``. Everything is numbers; no
matplotlib.

>>> from symctl.plotting.structure_routing import Segment, assign_slots, crossings, junctions
>>> a = Segment("a", ((0.0, "left"), (2.0, "right")))   # up from row 0 to row 2
>>> b = Segment("b", ((1.0, "left"), (3.0, "right")))   # up from row 1 to row 3
>>> crossings(a, b), crossings(b, a)   # a left of b crosses twice, b left of a never
(2, 0)
>>> assign_slots([a, b])
{'b': 0, 'a': 1}
>>> fan = Segment("x", ((0.0, "left"), (0.0, "right"), (1.0, "right"), (-1.0, "right")))
>>> junctions(fan)
[0.0]
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Hashable, Iterable, Sequence
from typing import NamedTuple

import networkx as nx

__all__ = [
    "Segment",
    "Wire",
    "assign_slots",
    "clean",
    "crossings",
    "dashed_part",
    "junctions",
    "merge",
]

_EPS = 1e-9


class Segment(NamedTuple):
    """The vertical piece of one net in one gap, and the horizontal pieces it meets.

    ``attachments`` are ``(y, side)``: a horizontal piece at height ``y`` running from
    the vertical to the gap's ``"left"`` or ``"right"`` edge.
    """

    net: Hashable
    attachments: tuple[tuple[float, str], ...]

    @property
    def low(self) -> float:
        return min(y for y, _ in self.attachments)

    @property
    def high(self) -> float:
        return max(y for y, _ in self.attachments)

    @property
    def vertical(self) -> bool:
        """Whether it has a vertical piece (its attachments are not all at one height)."""
        return self.high - self.low > _EPS


def merge(segments: Iterable[Segment]) -> list[Segment]:
    """One segment per net: the attachments of a net's segments joined (first seen first)."""
    nets: dict = {}
    for s in segments:
        nets.setdefault(s.net, []).extend(s.attachments)
    return [Segment(net, tuple(dict.fromkeys(att))) for net, att in nets.items()]


def _inside(y: float, s: Segment) -> bool:
    return s.low + _EPS < y < s.high - _EPS


def crossings(left: Segment, right: Segment) -> int:
    """Crossings of two segments' pieces when ``left`` runs left of ``right``.

    ``right``'s horizontal pieces to the left edge pass ``left``'s vertical, and
    ``left``'s pieces to the right edge pass ``right``'s. A piece of ``right`` to the
    left at the height of a piece of ``left`` to the right would run along it, which
    reads worse than a crossing: it counts three.
    """
    count = sum(1 for y, side in right.attachments if side == "left" and _inside(y, left))
    count += sum(1 for y, side in left.attachments if side == "right" and _inside(y, right))
    ends = {y for y, side in left.attachments if side == "right"}
    return count + 3 * sum(
        1
        for y, side in right.attachments
        if side == "left" and any(abs(y - e) <= _EPS for e in ends)
    )


def _overlap(a: Segment, b: Segment) -> bool:
    """Whether two verticals would touch if they shared a slot."""
    return a.low <= b.high + _EPS and b.low <= a.high + _EPS


def assign_slots(segments: Sequence[Segment]) -> dict:
    """Slot ``0, 1, ...`` (left to right) of each segment's net that has a vertical piece.

    Overlapping verticals get different slots, ordered to cross fewer horizontal
    pieces (ties: the order given); the rest share slots, first fit.

    Parameters
    ----------
    segments : sequence of Segment
        One per net (see :func:`merge`).

    Returns
    -------
    dict
        ``net -> slot``.
    """
    vertical = [s for s in segments if s.vertical]
    prefer = nx.DiGraph()
    prefer.add_nodes_from(range(len(vertical)))
    for i, j in itertools.combinations(range(len(vertical)), 2):
        a, b = vertical[i], vertical[j]
        if not _overlap(a, b):
            continue
        ab, ba = crossings(a, b), crossings(b, a)
        if ab <= ba:
            prefer.add_edge(i, j, weight=ba - ab)
        else:
            prefer.add_edge(j, i, weight=ab - ba)
    # break cycles of preferences: drop the weakest edge of each cycle found
    while True:
        try:
            cycle = nx.find_cycle(prefer)
        except nx.NetworkXNoCycle:
            break
        weakest = min(cycle, key=lambda e: (prefer.edges[e[0], e[1]]["weight"], -e[0]))
        prefer.remove_edge(weakest[0], weakest[1])
    slot: dict[int, int] = {}
    for i in nx.lexicographical_topological_sort(prefer):
        before = [slot[j] for j in prefer.predecessors(i) if j in slot]
        taken = {
            slot[j] for j in slot if _overlap(vertical[i], vertical[j])
        }  # overlapping ones placed so far
        k = max(before, default=-1) + 1
        while k in taken:
            k += 1
        slot[i] = k
    return {vertical[i].net: k for i, k in slot.items()}


def junctions(segment: Segment) -> list[float]:
    """Heights where three or more pieces of one net meet: a junction dot each.

    A piece up, a piece down, a horizontal piece to the left, one to the right: where
    three of these meet, the wire branches.
    """
    out = []
    for y in sorted({y for y, _ in segment.attachments}):
        sides = {side for yy, side in segment.attachments if abs(yy - y) <= _EPS}
        count = len(sides) + (y > segment.low + _EPS) + (y < segment.high - _EPS)
        if count >= 3:
            out.append(y)
    return out


class Wire(NamedTuple):
    """One drawn wire: a polyline from ``source`` to ``target`` (None: from outside / to outside).

    Every wire ends in an arrow head. ``delay`` is the steps of a delay block it feeds
    (drawn dashed; :math:`z^{-k}` written for more than one); ``feedback`` marks the wires
    on a feedback arc.
    """

    points: tuple[tuple[float, float], ...]
    delay: int
    source: str | None
    target: str | None
    feedback: bool


def _shared(p, q) -> float:
    """The length of the common start of two polylines (0 when they start apart)."""
    if math.dist(p[0], q[0]) > 1e-9:
        return 0.0
    i = j = 0
    at, done = p[0], 0.0
    while i < len(p) - 1 and j < len(q) - 1:
        (ax, ay), (bx, by) = p[i + 1], q[j + 1]
        da = (ax - at[0], ay - at[1])
        db = (bx - at[0], by - at[1])
        la, lb = math.hypot(*da), math.hypot(*db)
        if la < 1e-9:
            i += 1
            continue
        if lb < 1e-9:
            j += 1
            continue
        if abs(da[0] / la - db[0] / lb) > 1e-9 or abs(da[1] / la - db[1] / lb) > 1e-9:
            break
        step = min(la, lb)
        at = (at[0] + da[0] / la * step, at[1] + da[1] / la * step)
        done += step
        if la - step < 1e-9:
            i += 1
        if lb - step < 1e-9:
            j += 1
    return done


def dashed_part(wire: Wire, wires) -> tuple[tuple[float, float], ...]:
    """The part of a delay wire drawn dashed: after it leaves every undelayed wire of its signal.

    Where a signal branches, the wires share their first pieces; the shared part is the
    undelayed signal (drawn solid), and the delay is on the branch alone.

    >>> from symctl.plotting.structure_routing import Wire, dashed_part
    >>> solid = Wire(((0, 0), (2, 0)), 0, "a", "b", False)
    >>> delayed = Wire(((0, 0), (1, 0), (1, 1), (2, 1)), 1, "a", "c", False)
    >>> dashed_part(delayed, [solid, delayed])
    ((1.0, 0.0), (1, 1), (2, 1))
    """
    cut = max(
        [_shared(wire.points, w.points) for w in wires if w.source == wire.source and not w.delay]
        + [0.0]
    )
    if cut <= 1e-9:
        return wire.points
    out, walked = [], 0.0
    for a, b in itertools.pairwise(wire.points):
        length = math.dist(a, b)
        if walked + length <= cut + 1e-9:
            walked += length
            continue
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
        if out and math.dist(out[-1], p) < 1e-9:
            continue
        if len(out) >= 2:
            (x0, y0), (x1, y1) = out[-2], out[-1]
            if (abs(x0 - x1) < 1e-9 and abs(x1 - p[0]) < 1e-9) or (
                abs(y0 - y1) < 1e-9 and abs(y1 - p[1]) < 1e-9
            ):
                out[-1] = p
                continue
        out.append(p)
    return tuple(out)
