r"""The curves of a circuit drawing's synapses: bridges that clear every neuron and label.

Geometry for :mod:`symctl.plotting.circuit_layout` (numbers, no matplotlib; one unit
is one inch). A synapse from :math:`a` to :math:`b` is a *bridge*: a cubic Bézier
curve that leaves :math:`a`, rises (or sinks) by its height :math:`h` over the
chord's middle and comes down into :math:`b`,

.. math::

    B(t) = (1-t)^3 a + 3 (1-t)^2 t\, C_1 + 3 (1-t) t^2\, C_2 + t^3 b,

with the inner control points :math:`4h/3` off the chord, crossed over its middle
(:func:`bridge`: :math:`B(1/2) = (a+b)/2 + h n`, and the ends leave at a gentle
slope), and :math:`n` the chord's normal that points up (right for a vertical
chord). A height 0 is the straight line.

* **Obstacles** (:class:`Obstacles`): the circles of the neurons (and the dots of
  the inputs and outputs) and the boxes of every text (names, vertex tags, weights
  already placed). A curve is *clear* when no point of it, outside its own two
  circles, comes within :data:`CLEAR` of a circle it does not end at, or enters a box.
* **Choice** (:func:`route`): of the candidate heights (straight first for
  neighbouring columns; growing bulges, on the preferred side first, for the others)
  the first clear one on which the weight's label fits (:func:`place_label`), away
  from the heights of the other synapses between the same two neurons.
* **Ports** (:func:`spread_ports`): where the curves meet a circle, at least
  :data:`PORT_GAP` apart along it, so no two arrow heads or bars overlap.

>>> from symctl.plotting.circuit_routes import Obstacles, bridge, clear
>>> free = Obstacles.of([((1.0, 0.0), 0.2)], [])
>>> clear(bridge((0, 0), (2, 0), 0.0), free, ends=())   # straight through the circle
False
>>> clear(bridge((0, 0), (2, 0), 0.4), free, ends=())
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from symctl.plotting import layered

__all__ = [
    "CLEAR",
    "END_MARGIN",
    "INSIDE",
    "LABEL_MARGIN",
    "PAIR",
    "PORT_GAP",
    "REACH",
    "SWING",
    "TIP",
    "Obstacles",
    "bridge",
    "chord",
    "clear",
    "end_angle",
    "heights",
    "hits",
    "normal",
    "place_label",
    "point_at",
    "route",
    "samples",
    "spread_ports",
    "trimmed",
]

CLEAR = 0.035
"""How near a curve may pass a circle it does not end at [in]."""
PORT_GAP = 0.085
"""Least distance along a circle between the ends of two curves [in] (an arrow head is
about 0.05 in wide, a bar 0.07 in)."""
_BOX_MARGIN = 0.015  # a curve keeps this far from a text box [in]
REACH = 0.7
"""How far along the chord a bridge's first inner control point lies (its share of the
chord's length); over 1/2 the two cross, and the ends flatten."""
END_MARGIN = 0.04
"""How far a curve keeps from the texts of the neuron it ends at [in] (its arrow head)."""
PAIR = 0.13
"""Least difference of the heights of two curves between the same two nodes [in]."""
TIP = 0.012
"""An arrow's tip stops this far from its circle [in]."""
SWING = 0.9
"""An end moves at most this far round its circle from where it points [rad]."""
INSIDE = 10
"""A point inside a circle counts this many times one near it or in a text (:func:`hits`)."""
LABEL_MARGIN = 0.025
"""How far a weight's label keeps from every other text [in]."""
_T = np.linspace(0.0, 1.0, 49)


def normal(a, b) -> np.ndarray:
    """The unit normal of the chord from ``a`` to ``b`` that points up (right if vertical)."""
    d = np.asarray(b, float) - np.asarray(a, float)
    n = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-12)
    if n[1] < -1e-12 or (abs(n[1]) <= 1e-12 and n[0] < 0):
        n = -n
    return n


def bridge(a, b, h: float) -> tuple[tuple[float, float], ...]:
    """The control points ``(P0, C1, C2, P3)`` of the bridge from ``a`` to ``b`` of height ``h``.

    ``C1`` and ``C2`` lie at :math:`\\tfrac43 h` off the chord, ``C1`` :data:`REACH` of the
    chord's length along it from ``a`` and ``C2`` as far back from ``b``: the curve rises
    by ``h`` over the chord's middle and leaves its ends at a slope of only
    :math:`\\tfrac43 h / (0.7 L)`, so that a tall bridge still meets its circles from the
    side, away from their names and tags.
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    up = 4.0 / 3.0 * h * normal(a, b)
    c1, c2 = a + REACH * (b - a) + up, b - REACH * (b - a) + up
    return tuple(tuple(float(v) for v in p) for p in (a, c1, c2, b))


def samples(curve, t=_T) -> np.ndarray:
    """Points of a cubic Bézier ``(P0, C1, C2, P3)`` at the parameters ``t`` (``len(t) x 2``)."""
    return layered.bezier_points(curve, t)


def point_at(curve, t: float) -> tuple[float, float]:
    """The point of ``curve`` at parameter ``t``."""
    x, y = samples(curve, [t])[0]
    return float(x), float(y)


def trimmed(curve, a, ra: float, b, rb: float, a0: float | None = None, a1: float | None = None):
    """``curve`` from the border of the circle ``(a, ra)`` to that of ``(b, rb)``, radially.

    Each end moves to its circle along the direction from the centre to the curve's
    inner control point, or to the angle ``a0``, ``a1`` [rad] when given (spread
    ports), and the curve meets the circle square on: its control point next to the
    end moves onto the radius through it (as far out as half the distance to the
    old one), so an arrow head points at the centre and a bar lies along the circle.
    """
    _, c1, c2, _ = (np.asarray(p, float) for p in curve)

    def port(centre, towards, r, angle):
        centre = np.asarray(centre, float)
        if angle is None:
            d = towards - centre
            angle = math.atan2(d[1], d[0]) if np.hypot(*d) > 1e-12 else 0.0
        out = np.array([math.cos(angle), math.sin(angle)])
        q = centre + r * out
        return q, q + out * 0.5 * float(np.hypot(*(towards - q)))

    (q0, k1), (q3, k2) = port(a, c1, ra, a0), port(b, c2, rb, a1)
    return tuple(tuple(float(v) for v in p) for p in (q0, k1, k2, q3))


def chord(a, ra: float, b, rb: float):
    """The points where the straight line between the centres ``a``, ``b`` leaves the circles."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = b - a
    u = d / max(float(np.hypot(*d)), 1e-12)
    return tuple(a + ra * u), tuple(b - rb * u)


def end_angle(curve, centre, at_start: bool) -> float:
    """The angle [rad] from an end's ``centre`` towards its inner control point."""
    _, c1, c2, _ = (np.asarray(p, float) for p in curve)
    d = (c1 if at_start else c2) - np.asarray(centre, float)
    return math.atan2(d[1], d[0])


@dataclass(frozen=True, eq=False)
class Obstacles:
    """What a curve must not run through: circles ``(centre, radius)`` and text boxes.

    Attributes
    ----------
    centres : ndarray
        ``k x 2`` circle centres.
    radii : ndarray
        ``k`` radii.
    keys : tuple
        The node each circle belongs to (a curve may enter the circles it ends at).
    boxes : ndarray
        ``m x 4`` text boxes ``(x0, y0, x1, y1)``.
    box_keys : tuple
        The node each box belongs to (None for a weight): a curve ending at that node
        keeps :data:`END_MARGIN` from it, room for its arrow head or bar.
    """

    centres: np.ndarray
    radii: np.ndarray
    keys: tuple
    boxes: np.ndarray
    box_keys: tuple = ()

    def __post_init__(self) -> None:
        if len(self.box_keys) != len(self.boxes):
            object.__setattr__(self, "box_keys", (None,) * len(self.boxes))

    @classmethod
    def of(cls, circles, boxes, keys=None, box_keys=None) -> Obstacles:
        """From ``[((x, y), r), ...]`` and ``[(x0, y0, x1, y1), ...]``."""
        centres = np.array([c for c, _ in circles], float).reshape(-1, 2)
        radii = np.array([r for _, r in circles], float)
        keys = tuple(keys) if keys is not None else tuple(range(len(radii)))
        boxes = np.array(boxes, float).reshape(-1, 4)
        box_keys = tuple(box_keys) if box_keys is not None else (None,) * len(boxes)
        return cls(centres, radii, keys, boxes, box_keys)

    def with_box(self, box) -> Obstacles:
        """These obstacles and one more text box (a weight's)."""
        return Obstacles(
            self.centres,
            self.radii,
            self.keys,
            np.vstack([self.boxes, box]),
            (*self.box_keys, None),
        )


def hits(points: np.ndarray, obstacles: Obstacles, ends=()) -> int:
    """How bad ``points`` are: how many (outside the ends' circles) are too near a circle
    or in a box, and :data:`INSIDE` times as many again for those inside a circle.

    Only the obstacles near the points' bounding box are looked at; 0 is clear.
    """
    own = np.array([k in ends for k in obstacles.keys], bool)
    keep = np.ones(len(points), bool)
    for k in np.flatnonzero(own):
        d = np.hypot(*(points - obstacles.centres[k]).T)
        keep &= d > obstacles.radii[k] + 1e-9
    pts = points[keep]
    if not len(pts):
        return 0
    (x0, y0), (x1, y1) = pts.min(axis=0), pts.max(axis=0)
    bad = np.zeros(len(pts), bool)
    inside = 0
    if len(obstacles.radii):
        c, r = obstacles.centres, obstacles.radii + CLEAR
        near = (
            ~own & (c[:, 0] > x0 - r) & (c[:, 0] < x1 + r) & (c[:, 1] > y0 - r) & (c[:, 1] < y1 + r)
        )
        if near.any():
            d = np.hypot(pts[:, None, 0] - c[None, near, 0], pts[:, None, 1] - c[None, near, 1])
            bad |= (d < r[None, near]).any(axis=1)
            inside = int((d < r[None, near] - CLEAR).any(axis=1).sum())  # in a circle, not by it
    if len(obstacles.boxes):
        b = obstacles.boxes
        m = np.array([END_MARGIN if k in ends else _BOX_MARGIN for k in obstacles.box_keys])
        near = (b[:, 0] - m < x1) & (b[:, 2] + m > x0) & (b[:, 1] - m < y1) & (b[:, 3] + m > y0)
        if near.any():
            b, m = b[near], m[near][None, :]
            inside_box = (
                (pts[:, None, 0] > b[None, :, 0] - m)
                & (pts[:, None, 0] < b[None, :, 2] + m)
                & (pts[:, None, 1] > b[None, :, 1] - m)
                & (pts[:, None, 1] < b[None, :, 3] + m)
            )
            bad |= inside_box.any(axis=1)
    return int(bad.sum()) + INSIDE * inside


def clear(curve, obstacles: Obstacles, ends=()) -> bool:
    """Whether ``curve`` passes no circle (but those of ``ends``) and enters no box."""
    return hits(samples(curve), obstacles, ends) == 0


def box_free(box, obstacles: Obstacles) -> bool:
    """Whether the box ``(x0, y0, x1, y1)`` overlaps no circle and no other box."""
    x0, y0, x1, y1 = box
    if len(obstacles.radii):
        cx = np.clip(obstacles.centres[:, 0], x0, x1)
        cy = np.clip(obstacles.centres[:, 1], y0, y1)
        d = np.hypot(cx - obstacles.centres[:, 0], cy - obstacles.centres[:, 1])
        if (d < obstacles.radii + 0.02).any():
            return False
    if len(obstacles.boxes):
        b, m = obstacles.boxes, LABEL_MARGIN
        if (
            (b[:, 0] < x1 + m) & (b[:, 2] > x0 - m) & (b[:, 1] < y1 + m) & (b[:, 3] > y0 - m)
        ).any():
            return False
    return True


_LABEL_T = (0.5, 0.42, 0.58, 0.34, 0.66, 0.27, 0.73, 0.2, 0.8)


def place_label(curve, size, obstacles: Obstacles, lines=None) -> tuple[float, float] | None:
    """Where the label of ``size`` (w, h) goes on ``curve``: its centre, or None if nowhere.

    Tried along the curve from its middle outwards; a place must overlap no circle and
    no box; of those, the one whose box the fewest points of the other curves ``lines``
    (an ``n x 2`` array) pass through, the middlemost first.
    """
    w, h = size
    best, best_cost = None, None
    pts = np.zeros((0, 2)) if lines is None else np.asarray(lines, float).reshape(-1, 2)
    for t in _LABEL_T:
        x, y = point_at(curve, t)
        box = (x - w / 2, y - h / 2, x + w / 2, y + h / 2)
        if not box_free(box, obstacles):
            continue
        cost = int(
            (
                (pts[:, 0] > box[0])
                & (pts[:, 0] < box[2])
                & (pts[:, 1] > box[1])
                & (pts[:, 1] < box[3])
            ).sum()
        )
        if cost == 0:
            return x, y
        if best_cost is None or cost < best_cost:
            best, best_cost = (x, y), cost
    return best


def heights(straight: bool, prefer: float, start: float, step: float = 0.1, count: int = 14):
    """Candidate heights of a curve: 0 first when ``straight``, then growing bulges.

    ``prefer`` is the preferred side (+1 above, -1 below); each size is tried there
    first, then on the other side. Bulges start at ``start`` and grow by ``step``.
    """
    out = [0.0] if straight else []
    for k in range(count):
        size = start + k * step
        if size <= 0:
            continue
        out += [prefer * size, -prefer * size]
    return out


def spread_ports(angles: dict, radius: float, gap: float = PORT_GAP) -> dict:
    """The angles of the curve ends on one circle, moved apart to at least ``gap`` along it.

    ``angles`` maps each end to its natural angle [rad]; the ends keep their order
    around the circle and move as little as a few sweeps of pushing apart allow (no
    more than can fit: the gap shrinks to an equal share of the circle when needed).
    """
    if len(angles) < 2:
        return dict(angles)
    keys = sorted(angles, key=lambda k: angles[k] % (2 * math.pi))
    theta = np.array([angles[k] % (2 * math.pi) for k in keys])
    need = min(gap / max(radius, 1e-9), 2 * math.pi / len(keys) * 0.9)
    for _ in range(60):
        moved = False
        for i in range(len(theta)):
            j = (i + 1) % len(theta)
            d = (theta[j] - theta[i]) % (2 * math.pi)
            if d < need - 1e-9:
                push = (need - d) / 2
                theta[i] -= push
                theta[j] += push
                moved = True
        if not moved:
            break
    return {k: float(t) for k, t in zip(keys, theta, strict=True)}


def route(arcs, pos, col, radius, labels, obstacles: Obstacles, *, search=True, dot=0.03):
    """Heights, curves and label places of arcs (see the module text).

    Parameters
    ----------
    arcs : list of (source, target, synapse or None)
        In the order they claim their places (the shortest first).
    pos, col : mapping
        Each node's centre [in] and column.
    radius : mapping
        Each neuron's circle [in] (other nodes are dots of radius ``dot``).
    labels : mapping
        Each labelled synapse's label size ``(w, h)`` [in].
    obstacles : Obstacles
        The circles and texts already there; each label placed joins them.
    search : bool
        Try growing heights and ends moved round their circles (else: one arch each,
        as high as it is long, for a circuit of hundreds of synapses).

    Returns
    -------
    (list, bool, bool)
        Per arc ``(height, curve, label)`` (the curve from circle to circle, the label's
        centre or None), whether every curve is clear, and whether every label found a
        free place.

    Examples
    --------
    >>> from symctl.plotting.circuit_routes import Obstacles, route
    >>> pos, col = {"a": (0.0, 0.0), "m": (1.0, 0.0), "b": (2.0, 0.0)}, {"a": 0, "m": 1, "b": 2}
    >>> free = Obstacles.of([(pos[k], 0.2) for k in pos], [], list(pos))
    >>> (h, curve, where), = route([("a", "b", None)], pos, col, dict.fromkeys(pos, 0.2), {},
    ...                            free)[0]
    >>> h != 0   # over (or under) the neuron between
    True
    """
    clear, labelled, up = True, True, 1.0
    chosen: list[tuple] = []
    heights_of: dict[frozenset, list[float]] = {}
    ports: dict = {}  # the angles at which curves already end at each neuron
    lines: list[np.ndarray] = []
    for a, b, s in arcs:
        pa, pb = pos[a], pos[b]
        ra, rb = radius.get(a, dot), radius.get(b, dot)
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
        apart = max(PAIR, size[1] + 0.03) if size else PAIR
        if search:  # the usual heights and ends, then (none clear) more of each
            tiers = [
                (heights(adjacent, prefer, 0.16 if forward else 0.22, 0.1, 24), SWING, 3),
                (heights(adjacent, prefer, 0.12, 0.08, 40), 2 * SWING, 8),
            ]
        else:  # a hairball: one arch each, as high as it is long
            span = abs(col[b] - col[a])
            tiers = [([0.0] if adjacent else [prefer * (0.08 + 0.06 * span)], SWING, 3)]
        used = ports.setdefault(b, []) if b in radius else []
        others = np.concatenate(lines) if lines else None
        pick, fallback = None, None
        qa, qb = chord(pa, ra, pb, rb)
        for cands, swing, count in tiers:
            cands = [h for h in cands if all(abs(h - t) >= apart for t in taken)] or [
                (max(map(abs, taken)) + apart) * prefer
            ]
            for h in cands:
                curve = bridge(qa, qb, h)
                natural = end_angle(curve, pb, False)
                angles = _end_angles(natural, used, rb, swing, count)
                for angle in angles or [natural]:
                    drawn = trimmed(curve, pa, ra, pb, rb + TIP, None, angle)
                    nh = hits(samples(drawn), obstacles, {a, b}) + (not angles)
                    if fallback is None or nh < fallback[0]:
                        fallback = (nh, h, drawn, angle)
                    if nh:
                        continue
                    where = place_label(drawn, size, obstacles, others) if size else None
                    if size is None or where is not None:
                        pick = (h, drawn, where, angle)
                        break
                if pick is not None or not search:
                    break
            if pick is not None:
                break
        if pick is None:  # the least bad, its label where it overlaps the least
            nh, h, drawn, angle = fallback
            clear = clear and nh == 0
            where = None
            if size is not None:
                where = place_label(drawn, size, obstacles, others)
                labelled = labelled and where is not None
                where = where or place_label(drawn, size, _circles(obstacles), others)
                where = where or point_at(drawn, 0.5)
            pick = (h, drawn, where, angle)
        h, drawn, where, angle = pick
        taken.append(h)
        used.append(angle)
        chosen.append((h, drawn, where))
        lines.append(samples(drawn))
        if where is not None:
            w, hh = size
            obstacles = obstacles.with_box(
                (where[0] - w / 2, where[1] - hh / 2, where[0] + w / 2, where[1] + hh / 2)
            )
    return chosen, clear, labelled


def _end_angles(
    natural: float, used: list[float], radius: float, swing: float = SWING, count: int = 3
) -> list[float]:
    """Where a curve may end on a circle: its natural angle, or the ``count`` nearest ones
    within ``swing`` of it, each :data:`PORT_GAP` clear of the ends already there (none: no
    room)."""
    need = PORT_GAP / max(radius, 1e-9)

    steps = int(swing / (need / 3))
    tries = np.array([natural + sign * k * need / 3 for k in range(steps + 1) for sign in (1, -1)])
    if used:
        d = np.abs((tries[:, None] - np.array(used)[None, :] + math.pi) % (2 * math.pi) - math.pi)
        tries = tries[(d >= need - 1e-9).all(axis=1)]
    return [float(t) for t in dict.fromkeys(tries.tolist())][:count]


def _circles(obstacles: Obstacles) -> Obstacles:
    """The circles of ``obstacles`` alone."""
    return Obstacles(obstacles.centres, obstacles.radii, obstacles.keys, np.zeros((0, 4)), ())
