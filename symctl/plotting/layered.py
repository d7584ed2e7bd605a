r"""A layered graph layout: layers, long edges through bends, order, rows and curves, as numbers.

The one core of the structure, circuit and delay-graph drawings
(:mod:`~symctl.plotting.structure_layout`, :mod:`~symctl.plotting.circuit_layout`,
:mod:`~symctl.plotting.delaygraph_layout`), in the manner of Sugiyama, Tagawa and Toda
(1981); each drawing adds its own shapes (boxes and orthogonal wires, circles and bridges,
boxes and S-curves). Everything is numbers; nothing here imports matplotlib, as networkx
keeps ``drawing/layout.py`` apart from ``nx_pylab.py``.

* **Layers** (:func:`longest_path`): the first nodes in layer 0, every other node one
  layer right of its furthest predecessor, the last nodes together in one last layer.
* **Bends** (:func:`split`): an edge across several layers passes one bend node in each
  layer between, so that every edge joins two neighbouring layers.
* **Order** (:func:`order`): barycentre sweeps down and up; the order with the fewest
  crossings (:func:`crossings`, inversions counted with a Fenwick tree) is kept.
* **Rows**: heights as near their neighbours as the order and the gaps allow, a
  least-squares fit under order constraints (:func:`isotonic`: the pool-adjacent-violators
  algorithm of :func:`scipy.optimize.isotonic_regression`). The block diagrams and
  circuits take :func:`rows` (each sweep re-sorts a column by its barycentres, then fits
  integer or half rows: straight orthogonal wires); the delay graph takes :func:`order`
  then :func:`positions` (the order kept, measured gaps, bends pulling hardest).
* **Curves** (:func:`bezier_points`, :func:`at_x`): piecewise cubic Bézier curves
  (``p0, c, c, p1, c, c, p2, ...``: matplotlib's ``Path.CURVE4``) sampled, or met at an
  abscissa.

References
----------
K. Sugiyama, S. Tagawa and M. Toda, "Methods for visual understanding of hierarchical
system structures", IEEE Trans. Syst. Man Cybern. 11(2), 1981.

Examples
--------
>>> from symctl.plotting.layered import longest_path, order, split
>>> preds = {"a": [], "b": ["a"], "c": ["a", "b"]}
>>> layer = longest_path(["a", "b", "c"], preds, first={"a"})
>>> layer
{'a': 0, 'b': 1, 'c': 2}
>>> chains, node_layer, up, down = split([("a", "b"), ("b", "c"), ("a", "c")], layer)
>>> chains[2]
['a', (2, 1), 'c']
>>> order([["a"], ["b", (2, 1)], ["c"]], up, down)
[['a'], ['b', (2, 1)], ['c']]
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Hashable, Iterable, Mapping, Sequence

import numpy as np

__all__ = [
    "at_x",
    "bezier_points",
    "crossings",
    "fit_rows",
    "isotonic",
    "line",
    "longest_path",
    "order",
    "positions",
    "rows",
    "split",
]


def longest_path(
    nodes: Iterable[Hashable],
    preds: Mapping,
    *,
    first: Iterable = (),
    last: Iterable = (),
    floor: int = 0,
    layer: dict | None = None,
) -> dict:
    """Layers by longest path: ``first`` in layer 0, the others one right of their furthest
    predecessor (at least ``floor``), ``last`` together in one layer right of all others.

    Parameters
    ----------
    nodes : iterable
        In a topological order of the edges kept (the feedback edges left out).
    preds : mapping
        Each node's predecessors; those not laid out yet are ignored.
    first, last : iterable, optional
        The nodes of the first layer (the inputs) and of the last (the outputs).
    floor : int
        The least layer of a node not in ``first``.
    layer : dict, optional
        Layers already given (of earlier nodes); updated and returned.

    Returns
    -------
    dict
        Each node's layer.

    Examples
    --------
    >>> from symctl.plotting.layered import longest_path
    >>> longest_path("abc", {"a": [], "b": "a", "c": "a"}, first="a", last="bc")
    {'a': 0, 'b': 1, 'c': 1}
    """
    layer = {} if layer is None else layer
    first, last, nodes = set(first), set(last), list(nodes)
    for v in nodes:
        if v in first:
            layer[v] = 0
        else:
            layer[v] = max([floor, *(layer[p] + 1 for p in preds[v] if p in layer)])
    ends = [v for v in nodes if v in last]
    if ends:
        inner = [layer[v] + 1 for v in nodes if v not in last]
        at = max([*(layer[v] for v in ends), *inner])
        for v in ends:
            layer[v] = at
    return layer


def split(edges: Sequence[tuple], layer: Mapping) -> tuple[list[list], dict, dict, dict]:
    """Each edge ``(a, b, ...)`` as a chain ``[a, bends..., b]`` with one bend per layer between.

    The bend of edge ``k`` in layer ``l`` is the node ``(k, l)``. Returns the chains, every
    node's layer (bends included), and each node's neighbours up (left) and down (right).

    Examples
    --------
    >>> from symctl.plotting.layered import split
    >>> chains, node_layer, up, down = split([("a", "b")], {"a": 0, "b": 2})
    >>> chains, node_layer[(0, 1)], down["a"], up["b"]
    ([['a', (0, 1), 'b']], 1, [(0, 1)], [(0, 1)])
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
    """Edge crossings between neighbouring layers (inversions, counted with a Fenwick tree).

    Examples
    --------
    >>> from symctl.plotting.layered import crossings
    >>> crossings([["a", "b"], ["c", "d"]], {"a": ["d"], "b": ["c"]})
    1
    """
    total = 0
    for upper, lower in itertools.pairwise(layers):
        at = {node: k for k, node in enumerate(lower)}
        ends = sorted((k, at[m]) for k, node in enumerate(upper) for m in down[node])
        tree = [0] * (len(lower) + 1)
        for seen, (_, b) in enumerate(ends):
            i, below = b + 1, 0  # how many earlier ends are at or left of b
            while i > 0:
                below += tree[i]
                i -= i & -i
            total += seen - below
            i = b + 1
            while i <= len(lower):
                tree[i] += 1
                i += i & -i
    return total


def order(layers: Sequence[Sequence], up: Mapping, down: Mapping, sweeps: int = 8) -> list[list]:
    """Barycentre sweeps down and up (``sweeps`` each); the order with the fewest crossings.

    Examples
    --------
    >>> from symctl.plotting.layered import order
    >>> order([["a", "b"], ["c", "d"]], {"c": ["b"], "d": ["a"]}, {"a": ["d"], "b": ["c"]})
    [['a', 'b'], ['d', 'c']]
    """
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
    r"""Least squares :math:`\sum_k w_k (d_k - t_k)^2` under :math:`d_{k+1} \ge d_k + g_k`.

    With :math:`d = e + o`, :math:`o` the running sum of the gaps, this is an isotonic
    regression of :math:`t - o` (:func:`scipy.optimize.isotonic_regression`).

    Examples
    --------
    >>> from symctl.plotting.layered import isotonic
    >>> isotonic([0.0, 0.0], [1.0, 1.0], [1.0]).tolist()
    [-0.5, 0.5]
    """
    target = np.asarray(target, float)
    offset = np.concatenate(([0.0], np.cumsum(gaps)))[: len(target)]
    free = target - offset
    if np.all(free[1:] >= free[:-1]):  # most calls of a sweep: nothing to pool
        return free + offset
    from scipy.optimize import isotonic_regression  # ~0.5 s to import: only when drawing

    return isotonic_regression(free, weights=np.asarray(weight, float)).x + offset


def positions(
    layers: Sequence[Sequence],
    up: Mapping,
    down: Mapping,
    gaps: Sequence[Sequence[float]],
    weight: Callable[[Hashable, Hashable], float],
    sweeps: int = 8,
) -> dict:
    """Each node's position across its layer, the order kept: as near the weighted mean of its
    neighbours as the ``gaps`` between neighbours in the layer allow (:func:`isotonic`).

    Sweeps from the left (on ``up``), from the right (on ``down``) and on both, ``sweeps``
    times; ``weight(node, neighbour)`` is how hard a neighbour pulls (a node without
    neighbours keeps its place, with weight 1/2).

    Examples
    --------
    >>> from symctl.plotting.layered import positions
    >>> up, down = {"a": [], "b": [], "c": ["a", "b"]}, {"a": ["c"], "b": ["c"], "c": []}
    >>> at = positions([["a", "b"], ["c"]], up, down, [[1.0], []], lambda n, m: 1.0)
    >>> float(at["b"] - at["a"]), float(at["c"] - (at["a"] + at["b"]) / 2)
    (1.0, 0.0)
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
                if w:
                    target.append(sum(a * at[m] for a, m in zip(w, nbrs, strict=True)) / sum(w))
                    pull.append(sum(w))
                else:
                    target.append(at[node])
                    pull.append(0.5)
            at.update(zip(layers[k], isotonic(target, pull, gaps[k]), strict=True))
    return at


def fit_rows(desired: Sequence[float], integer: bool = True) -> list:
    """Rows, top first and one apart at least, nearest ``desired`` in least squares
    (:func:`isotonic`); when ``integer``, rounded half up and pushed one apart.

    Examples
    --------
    >>> from symctl.plotting.layered import fit_rows
    >>> fit_rows([0.0, 0.0]), fit_rows([0.0, 0.0], integer=False)
    ([1, 0], [0.5, -0.5])
    """
    n = len(desired)
    fit = [-float(y) for y in isotonic([-d for d in desired], [1.0] * n, [1.0] * (n - 1))]
    if not integer:
        return fit
    rows = [math.floor(round(y, 9) + 0.5) for y in fit]  # the last bits' noise rounded away
    for i in range(1, n):
        rows[i] = min(rows[i], rows[i - 1] - 1)
    return rows


def rows(columns: Mapping[int, list], preds: Mapping, succs: Mapping, integer: bool = True) -> dict:
    """Rows (top first, one apart at least) in each layer: barycentre sweeps, each column
    fitted by :func:`fit_rows` (integer rows, or half rows allowed).

    Sweeps left to right on the predecessors, back on the successors, and again (five);
    ``columns`` maps each layer to its nodes, sorted in place top first.

    Examples
    --------
    >>> from symctl.plotting.layered import rows
    >>> columns = {0: ["a"], 1: ["b", "c"], 2: ["d"]}
    >>> preds = {"a": [], "b": ["a"], "c": ["a"], "d": ["b", "c"]}
    >>> succs = {"a": ["b", "c"], "b": ["d"], "c": ["d"], "d": []}
    >>> row = rows(columns, preds, succs)
    >>> row["b"] - row["c"], columns[1]
    (1, ['b', 'c'])
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
            fit = fit_rows([desired[n] for n in nodes], integer)
            row.update(zip(nodes, fit, strict=True))
    return row


def line(p, q) -> list[tuple[float, float]]:
    """A straight segment from ``p`` to ``q`` as cubic Bézier control points ``c, c, q``."""
    (x0, y0), (x1, y1) = p, q
    return [
        (x0 + (x1 - x0) / 3, y0 + (y1 - y0) / 3),
        (x0 + 2 * (x1 - x0) / 3, y0 + 2 * (y1 - y0) / 3),
        q,
    ]


def bezier_points(bezier, t) -> np.ndarray:
    """The points of a piecewise cubic Bézier curve (``3k + 1`` control points) at the
    parameters ``t`` of each segment, segment after segment (``k len(t) x 2``).

    Examples
    --------
    >>> from symctl.plotting.layered import bezier_points
    >>> bezier_points([(0, 0), (1, 0), (2, 0), (3, 0)], [0.0, 0.5, 1.0])[:, 0].tolist()
    [0.0, 1.5, 3.0]
    """
    ctrl = np.asarray(bezier, dtype=float)
    t = np.asarray(t, dtype=float)[:, None]
    s = 1 - t
    out = []
    for k in range(0, len(ctrl) - 1, 3):
        p0, c1, c2, p1 = ctrl[k : k + 4]
        out.append(s**3 * p0 + 3 * s * s * t * c1 + 3 * s * t * t * c2 + t**3 * p1)
    return out[0] if len(out) == 1 else np.vstack(out)


def at_x(bezier, x: float) -> tuple[float, float]:
    """The point of the curve at abscissa ``x`` (each segment x-monotone; clamped to the ends).

    Examples
    --------
    >>> from symctl.plotting.layered import at_x
    >>> [round(v, 6) for v in at_x([(0, 0), (1, 0), (2, 2), (3, 2)], 1.5)]
    [1.5, 1.0]
    """
    ctrl = [(float(px), float(py)) for px, py in bezier]  # plain floats: a fast bisection
    segments = [ctrl[k : k + 4] for k in range(0, len(ctrl) - 1, 3)]
    for k, (p0, c1, c2, p1) in enumerate(segments):
        lo, hi = sorted((p0[0], p1[0]))
        if not (lo - 1e-9 <= x <= hi + 1e-9 or k == len(segments) - 1):
            continue
        rising = p1[0] >= p0[0]
        a, b = 0.0, 1.0
        for _ in range(40):  # bisection on the segment's parameter
            t = (a + b) / 2
            px = (1 - t) ** 3 * p0[0] + 3 * (1 - t) ** 2 * t * c1[0]
            px += 3 * (1 - t) * t**2 * c2[0] + t**3 * p1[0]
            a, b = (t, b) if (px < x) == rising else (a, t)
        t = (a + b) / 2
        return tuple(
            (1 - t) ** 3 * p0[i]
            + 3 * (1 - t) ** 2 * t * c1[i]
            + 3 * (1 - t) * t**2 * c2[i]
            + t**3 * p1[i]
            for i in (0, 1)
        )
    return ctrl[-1]  # pragma: no cover - no segments
