r"""Where a circuit's neurons, inputs, outputs and synapse arcs go: numbers, no matplotlib.

The layout of :meth:`Circuit.draw <symctl.neural.circuit.Circuit.draw>`, apart from
its rendering (:mod:`symctl.plotting.circuit`), as networkx keeps ``drawing/layout.py``
apart from ``nx_pylab.py``. One unit is one inch.

* **Columns**: the inputs in column 0; each neuron one column right of its
  furthest predecessor along forward synapses (a depth-first search from the
  inputs; the edges it finds closing a cycle are feedback); the outputs in one
  last column.
* **Rows**: each node at the mean row of its placed predecessors (two sweeps),
  the nodes of a column spread one row apart around their mean.
* **Arcs**: a synapse between neighbouring columns is straight; one that skips
  a column bulges when its straight line would pass within a quarter inch of a
  circle there, by the largest such radius plus a margin (alternately above and
  below, or the other way or further when its label would come that close to a
  circle); a feedback synapse (to the same or an earlier column) runs below;
  parallel synapses between the same two neurons fan out 0.4 inch apart. An
  arc's weight label sits at its middle.

>>> from symctl import Circuit, ifp_structure
>>> from symctl.plotting.circuit_layout import circuit_layout
>>> lay = circuit_layout(Circuit.from_structure(ifp_structure(2)))
>>> lay.column
{'x': 0, 'mu': 1, ('out', 'u'): 2}
>>> lay.pos["mu"], [(a.source, a.target, a.height) for a in lay.arcs]
((2.6, 0.0), [('x', 'mu', 0.0), ('mu', ('out', 'u'), 0.0)])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import networkx as nx
import numpy as np

from symctl.compatibility.signalgraph import back_edges

if TYPE_CHECKING:
    from symctl.neural.circuit import Circuit
    from symctl.neural.neuron import Synapse

__all__ = ["MIN_RADIUS", "XSTEP", "YSTEP", "Arc", "CircuitLayout", "circuit_layout", "grid"]

XSTEP = 2.6
"""Inches between columns."""
YSTEP = 1.5
"""Inches between rows."""
MIN_RADIUS = 0.32
"""The smallest neuron circle [in] (the radius when none is given)."""
_CLEAR = 0.25  # a straight arc or a label closer than this to a circle [in] moves away


@dataclass(frozen=True)
class Arc:
    """One drawn arrow: a synapse, or the path from a neuron (or input) to a circuit output.

    Attributes
    ----------
    source, target : str or tuple
        Node keys of :attr:`CircuitLayout.pos` (an output is ``("out", name)``).
    synapse : Synapse or None
        What the arc carries; None for a plain wire to an output (weight 1, no delay).
    height : float
        How far the arc bulges from the straight line [in]; > 0 above it.
    rad : float
        The same as a curvature relative to the arc's length (matplotlib's ``arc3``).
    label : (float, float) or None
        Where the weight label goes (None: no label).
    """

    source: str | tuple
    target: str | tuple
    synapse: Synapse | None
    height: float
    rad: float
    label: tuple[float, float] | None


@dataclass(frozen=True, eq=False)
class CircuitLayout:
    """The positions of a circuit drawing (see the module text for the rules).

    Attributes
    ----------
    column, row : mapping
        Each node's column and row (nodes: inputs and neurons by name, outputs as
        ``("out", name)``).
    pos : mapping
        Each node's centre ``(x, y)`` [in].
    radius : mapping of str to float
        Each neuron's circle [in].
    arcs : tuple of Arc
        Synapses (shortest span first, parallel ones together), then the outputs.
    bounds : (float, float, float, float)
        ``(x_lo, x_hi, y_lo, y_hi)``: every node, circle and label inside, with margins.
    """

    column: Mapping
    row: Mapping
    pos: Mapping
    radius: Mapping[str, float]
    arcs: tuple[Arc, ...]
    bounds: tuple[float, float, float, float]


def grid(c: Circuit) -> tuple[dict, dict]:
    """Columns (inputs 0, neurons by longest forward path, outputs last) and rows.

    Examples
    --------
    >>> from symctl import Circuit, controllable_canonical, controller_tf, factor, Structure
    >>> from symctl.plotting.circuit_layout import grid
    >>> f = factor(controller_tf(2))
    >>> col, row = grid(Circuit.from_structure(Structure.from_realization(
    ...     controllable_canonical(f.G2))))
    >>> col
    {'u': 0, 'x2': 1, 'y': 2, ('out', 'y'): 3}
    """
    nodes = [*c.inputs, *(n.name for n in c.neurons)]
    edges = [s for n in c.neurons for s in n.synapses]
    successors: dict = {node: [] for node in nodes}
    for s in edges:
        if s.source != s.target and s.target not in successors[s.source]:
            successors[s.source].append(s.target)
    feedback = set(back_edges(successors, [*c.inputs, *nodes]))  # the one DFS (signalgraph)
    dag = nx.DiGraph()
    dag.add_nodes_from(nodes)
    dag.add_edges_from((a, b) for a in nodes for b in successors[a] if (a, b) not in feedback)
    col: dict = {}
    for node in nx.topological_sort(dag):
        if node in c.inputs:
            col[node] = 0
        else:
            col[node] = max((col[p] + 1 for p in dag.predecessors(node)), default=1)
    last = max(col.values(), default=0) + 1
    columns: dict[int, list] = {}
    for node in nodes:
        columns.setdefault(col[node], []).append(node)
    for o in c.outputs:
        col[("out", o.target)] = last
        columns.setdefault(last, []).append(("out", o.target))
    # rows: barycenters of the already placed neighbours, two sweeps
    preds: dict = {n: [] for n in col}
    for s in edges:
        preds[s.target].append(s.source)
    for o in c.outputs:
        preds[("out", o.target)].append(o.source)
    row: dict = {}
    for _ in range(2):
        for k in sorted(columns):
            items = columns[k]
            want = {
                n: (
                    np.mean([row[p] for p in preds.get(n, []) if p in row and p != n])
                    if any(p in row and p != n for p in preds.get(n, []))
                    else row.get(n, 0.0)
                )
                for n in items
            }
            items.sort(key=lambda n, w=want: -w[n])
            mean = np.mean(list(want.values()))
            for i, n in enumerate(items):
                row[n] = float(mean + (len(items) - 1) / 2 - i)
    return col, row


def _distance(p, a, b) -> float:
    """The distance from the point ``p`` to the segment from ``a`` to ``b``."""
    p, a, b = (np.asarray(v, dtype=float) for v in (p, a, b))
    d = b - a
    t = float(np.clip(np.dot(p - a, d) / max(float(np.dot(d, d)), 1e-18), 0.0, 1.0))
    return float(np.hypot(*(p - a - t * d)))


def _rad(pos, a, b, h: float) -> float:
    """The ``arc3`` curvature of an arc from ``a`` to ``b`` that bulges by ``h``."""
    (x0, y0), (x1, y1) = pos[a], pos[b]
    length = max(np.hypot(x1 - x0, y1 - y0), 1e-9)
    return float(-2 * h / length * (1 if x1 >= x0 else -1))


def _middle(pos, a, b, h: float) -> tuple[float, float]:
    """The middle of the arc from ``a`` to ``b`` that bulges by ``h``: where its label goes."""
    (x0, y0), (x1, y1), rad = pos[a], pos[b], _rad(pos, a, b, h)
    return ((x0 + x1) / 2 + 0.5 * rad * (y1 - y0), (y0 + y1) / 2 - 0.5 * rad * (x1 - x0))


def _clear_bulge(pos, a, b, h: float, radius: Mapping[str, float]) -> float:
    """``h``, or the nearest bulge (the other way, then 0.4 inch further) whose label is on no circle."""
    side = 1.0 if h >= 0 else -1.0
    for t in (h, -h, *(s * (abs(h) + 0.4 * i) for i in (1, 2, 3) for s in (side, -side))):
        x, y = _middle(pos, a, b, t)
        if all(np.hypot(x - pos[n][0], y - pos[n][1]) >= r + _CLEAR for n, r in radius.items()):
            return t
    return h


def _arc(pos, a, b, s: Synapse | None, h: float) -> Arc:
    label = _middle(pos, a, b, h) if s is not None else None
    return Arc(a, b, s, float(h), _rad(pos, a, b, h), label)


def circuit_layout(c: Circuit, radius: Mapping[str, float] | None = None) -> CircuitLayout:
    """The positions, arcs and extent of the drawing of ``c``.

    Parameters
    ----------
    c : Circuit
    radius : mapping of str to float, optional
        Each neuron's circle [in], e.g. measured from its label; default
        :data:`MIN_RADIUS` for every neuron.

    Returns
    -------
    CircuitLayout

    Examples
    --------
    >>> from symctl import Circuit, controllable_canonical, controller_tf, factor, Structure
    >>> from symctl.plotting.circuit_layout import circuit_layout
    >>> f = factor(controller_tf(2))
    >>> c = Circuit.from_structure(Structure.from_realization(controllable_canonical(f.G2)))
    >>> lay = circuit_layout(c)
    >>> [(a.source, a.target, round(a.height, 2)) for a in lay.arcs]   # u -> y skips x2
    [('u', 'x2', 0.0), ('x2', 'y', -0.2), ('x2', 'y', 0.2), ('u', 'y', 0.82), ('y', ('out', 'y'), 0.0)]
    """
    if radius is None:
        radius = {n.name: MIN_RADIUS for n in c.neurons}
    col, row = grid(c)
    pos = {n: (XSTEP * col[n], YSTEP * row[n]) for n in col}
    # group parallel synapses (same pair of ends) and give each its own curvature
    pairs: dict[tuple, list[Synapse]] = {}
    for n in c.neurons:
        for s in n.synapses:
            pairs.setdefault((s.source, s.target), []).append(s)
    # each arc bulges by a height h (inches; > 0 above): skipping arcs alternate above and
    # below, feedback arcs run below, parallel synapses fan out; longer arcs bulge more
    arcs = []
    up = 1
    for (a, b), group in sorted(pairs.items(), key=lambda kv: abs(col[kv[0][1]] - col[kv[0][0]])):
        span = abs(col[b] - col[a])
        between = [
            radius.get(n, 0.1)
            for n in col
            if min(col[a], col[b]) < col[n] < max(col[a], col[b])
            and _distance(pos[n], pos[a], pos[b]) < radius.get(n, 0.1) + _CLEAR
        ]
        skips = bool(between)
        if col[b] <= col[a]:
            base = -(0.55 + 0.4 * max(span - 1, 0))
        elif skips:
            base, up = up * (max(between) + 0.5 + 0.4 * (span - 2)), -up
            base = _clear_bulge(pos, a, b, base, radius)
        else:
            base = 0.0
        for k, s in enumerate(group):
            arcs.append(_arc(pos, a, b, s, base + (k - (len(group) - 1) / 2) * 0.4))
    for o in c.outputs:
        if o.source in pos:
            wire = o if (o.weight != 1 or o.delay) else None
            arcs.append(_arc(pos, o.source, ("out", o.target), wire, 0.0))
    xs = [p[0] for p in pos.values()]
    ys = [p[1] for p in pos.values()]
    labels = [a.label[1] for a in arcs if a.label is not None]
    big = max(radius.values(), default=0.3)
    bounds = (
        min(xs) - 0.9,
        max(xs) + 0.9,
        min([min(ys) - big - 0.5] + [y - 0.35 for y in labels]),
        max([max(ys) + big + 0.45] + [y + 0.35 for y in labels]),
    )
    return CircuitLayout(col, row, pos, dict(radius), tuple(arcs), bounds)
