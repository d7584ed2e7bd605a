"""Compatible structures built along the paths of a delay graph (the theorems'
constructions, :mod:`symctl.compatibility.controller`)."""

from __future__ import annotations

import itertools
import math
import numbers
from collections.abc import Sequence
from dataclasses import dataclass

import networkx as nx
import sympy as sp

from symctl.compatibility.csp import build_problem, solve_chain
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.structure import Structure
from symctl.design.tf import DiscreteTF
from symctl.errors import ParameterError
from symctl.realization.factorization import factor
from symctl.realization.realization import controllable_canonical, controller_realization
from symctl.realization.realizers import get_realizer
from symctl.symbols import z

__all__ = ["MAX_PATHS", "PathPart", "along_path", "fastest_path", "markov_split", "slowest_path"]

MAX_PATHS = 10_000
"""The most simple paths :func:`slowest_path` enumerates before it asks for ``paths=``."""


@dataclass(frozen=True)
class PathPart:
    """One part of a construction: a transfer function factored along one path.

    Attributes
    ----------
    G : sympy expression
        The part's transfer function.
    path : tuple of int
        The vertices of the path, from 1.
    delays : tuple of int
        The steps of the path's edges.
    structure : Structure
        The sections (axons on edges of several steps) and :math:`G_2`, in series.
    vertex_of : dict
        Each signal's vertex, on the path.
    realization : Realization or None
        The series realization when every edge has at most one step (else None); beyond
        :data:`~symctl.realization.factorization.EXPANDED_ZEROS_MAX` sections its :math:`G_2`
        is abbreviated (substitute ``sigma_values()``).
    label : str
        Which part it is, e.g. ``"G[1,2]"`` for an entry of a MIMO controller.

    Examples
    --------
    >>> from symctl import DelayGraph, controller_compatibility, controller_tf
    >>> (part,) = controller_compatibility(controller_tf(2), DelayGraph.chain([2])).parts
    >>> part.path, part.delays, part.delay
    ((1, 2), (2,), 2)
    """

    G: sp.Expr
    path: tuple[int, ...]
    delays: tuple[int, ...]
    structure: Structure
    vertex_of: dict
    realization: object = None
    label: str = ""

    @property
    def delay(self) -> int:
        """The path's total delay."""
        return sum(self.delays)


def _digraph(graph: DelayGraph, max_wire_delay: int | None) -> nx.DiGraph:
    """The graph's edges of at most ``max_wire_delay`` steps (vertices from 0), the least delay
    of parallel edges."""
    g = nx.DiGraph()
    g.add_nodes_from(range(graph.n))
    for i, j, d in graph.edges:
        if i != j and (max_wire_delay is None or d <= max_wire_delay):
            if not g.has_edge(i - 1, j - 1) or g.edges[i - 1, j - 1]["delay"] > d:
                g.add_edge(i - 1, j - 1, delay=d)
    return g


def _distances(g: nx.DiGraph, source: int) -> list[float]:
    found = nx.single_source_dijkstra_path_length(g, source, weight="delay")
    return [found.get(v, math.inf) for v in range(len(g))]


def fastest_path(
    graph: DelayGraph, max_wire_delay: int | None = None, ends: tuple[int, int] | None = None
):
    """The fastest path ``(delay, vertices, edge delays)`` from the sensor to the actuator (or
    ``ends``) over edges of at most ``max_wire_delay`` steps, through the most vertices; or None.
    """
    n = graph.n
    if ends is None:
        (src,), (dst,) = ((v - 1 for v in end) for end in graph.pins(1, 1))
    else:
        src, dst = ends[0] - 1, ends[1] - 1
    g = _digraph(graph, max_wire_delay)
    ahead = _distances(g, src)
    behind = _distances(g.reverse(copy=False), dst)
    total = ahead[dst]
    if math.isinf(total):
        return None
    tight = nx.DiGraph()
    tight.add_nodes_from(range(n))
    for i, j, d in g.edges(data="delay"):
        if ahead[i] + d + behind[j] == total and ahead[i] + d == ahead[j]:
            tight.add_edge(i, j, delay=d)
    if nx.is_directed_acyclic_graph(tight):
        best = {src: (0, None)}
        for v in nx.topological_sort(tight):
            if v not in best:
                continue
            for w in tight.successors(v):
                if w not in best or best[w][0] < best[v][0] + 1:
                    best[w] = (best[v][0] + 1, v)
        vertices = [dst]
        while vertices[-1] != src:
            vertices.append(best[vertices[-1]][1])
        vertices.reverse()
    else:
        vertices = nx.shortest_path(tight, src, dst)
    delays = tuple(int(tight.edges[a, b]["delay"]) for a, b in itertools.pairwise(vertices))
    return int(total), tuple(v + 1 for v in vertices), delays


def slowest_path(graph: DelayGraph, max_wire_delay: int | None = None):
    """The slowest simple path from the sensor to the actuator (as :func:`fastest_path`);
    ParameterError past :data:`MAX_PATHS`."""
    g = _digraph(graph, max_wire_delay)
    (src,), (dst,) = graph.pins(1, 1)
    best = None
    for count, path in enumerate(nx.all_simple_paths(g, src - 1, dst - 1)):
        if count >= MAX_PATHS:
            raise ParameterError(
                f"paths: the graph has more than {MAX_PATHS} simple paths from v{src} to "
                f"v{dst}; give the paths of the decomposition explicitly"
            )
        delays = tuple(int(g.edges[a, b]["delay"]) for a, b in itertools.pairwise(path))
        key = (sum(delays), len(path))
        if best is None or key > best[0]:
            best = (key, tuple(v + 1 for v in path), delays)
    return None if best is None else (best[0][0], best[1], best[2])


def path_delays(graph: DelayGraph, path, max_wire_delay: int | None, argname: str):
    """The edge delays along a user's ``path`` (vertices from 1), checked against the graph."""
    n = graph.n
    (src,), (dst,) = graph.pins(1, 1)
    if isinstance(path, str) or not hasattr(path, "__iter__"):
        raise ParameterError(f"{argname}: expected a sequence of vertices 1..{n}, got {path!r}")
    vertices = tuple(itertools.islice(path, n + 1))
    for v in vertices:
        if isinstance(v, bool) or not isinstance(v, numbers.Integral) or not 1 <= v <= n:
            raise ParameterError(f"{argname}: expected a sequence of vertices 1..{n}, got {v!r}")
    vertices = tuple(int(v) for v in vertices)
    if len(vertices) < 2 or vertices[0] != src or vertices[-1] != dst:
        raise ParameterError(f"{argname}: a path runs from v{src} to v{dst}, got {list(vertices)}")
    if len(set(vertices)) != len(vertices):
        raise ParameterError(f"{argname}: a path visits each vertex once, got {list(vertices)}")
    g, delays = _digraph(graph, None), []
    for a, b in itertools.pairwise(vertices):
        if not g.has_edge(a - 1, b - 1):
            raise ParameterError(f"{argname}: v{a} -> v{b} is not an edge of the graph")
        delays.append(g.edges[a - 1, b - 1]["delay"])
        if max_wire_delay is not None and delays[-1] > max_wire_delay:
            raise ParameterError(
                f"{argname}: the edge v{a} -> v{b} has {delays[-1]} steps, more than "
                f"max_wire_delay = {max_wire_delay}"
            )
    return vertices, tuple(delays)


def along_path(
    G,
    path: Sequence[int],
    delays: Sequence[int],
    *,
    base: str = "controllable",
    structure: str = "branch",
) -> PathPart:
    r"""``G`` (SISO, of relative degree at least ``sum(delays)``) factored along the path
    ``path`` whose edges have ``delays`` steps, every signal placed on it (Theorem 1's
    construction): one section :math:`C z^{1-e}/(z - \epsilon)` per edge of :math:`e \ge 1`
    steps, half on the sensor side, and :math:`G_2` between, realized by ``base`` with the
    ``structure`` convention; the signals placed by the exact chain solver."""
    tf = DiscreteTF.from_expr(G)
    steps = [int(e) for e in delays]
    crossing = [e for e in steps if e > 0]
    ms = len(crossing) // 2
    ma = len(crossing) - ms
    f = factor(tf, ms, ma)
    extra = sum(crossing) - len(crossing)
    G2 = f.G2_symbolic  # beyond EXPANDED_ZEROS_MAX sections its zeros are sigma_k
    G2 = G2 if not extra else DiscreteTF.from_expr(sp.cancel(G2.expr * z**extra))
    realizer = get_realizer(base, "base", where=lambda r: r.keeps_symbols)
    n = G2.order
    options = {"P": sp.eye(n) + sp.ones(n, n)} if realizer.takes_transform else {}
    R2 = realizer(G2, **options).realization
    S = Structure.from_factorization(f, R2, structure, axons=crossing)
    chain = DelayGraph.chain(steps)
    place, _ = solve_chain(build_problem(S, chain), *chain.chain_order)
    if place is None:  # pragma: no cover - the construction's theorem
        raise RuntimeError("the path construction found no placement on its own path")
    vertex_of = {name: path[p] for name, p in zip(S.signal_graph.names, place, strict=True)}
    realization = controller_realization(f, R2) if extra == 0 else None
    return PathPart(tf.expr, tuple(path), tuple(steps), S, vertex_of, realization)


def markov_split(G, delays: Sequence[int]) -> list[sp.Expr]:
    r""":math:`G = G_1 + \dots + G_k` with :math:`G_i` of relative degree at least ``delays[i]``.

    :math:`G_i = \sum_{L_i \le j < L_{i+1}} h_j z^{-j}` for :math:`i < k`, :math:`G_k` the rest
    (Theorem 2 of :mod:`symctl.compatibility.controller`).

    Parameters
    ----------
    G : DiscreteTF or sympy expression in z
        SISO and proper.
    delays : sequence of int
        :math:`L_1 < L_2 < \dots < L_k`.

    Returns
    -------
    list of sympy expressions
        :math:`G_1, \dots, G_k`, summing to :math:`G` exactly (zero parts kept).

    Raises
    ------
    ParameterError
        ``delays`` not increasing.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import z
    >>> from symctl.compatibility.construction import markov_split
    >>> markov_split(1 / (z - sp.Rational(1, 2)), [1, 3])
    [(2*z + 1)/(2*z**2), 1/(4*z**3 - 2*z**2)]
    """
    tf = DiscreteTF.from_expr(G)
    Ls = [int(d) for d in delays]
    if any(b <= a for a, b in itertools.pairwise(Ls)):
        raise ParameterError(f"delays: must increase, got {Ls}")
    h = controllable_canonical(tf).markov(Ls[-1]) if Ls[-1] > 0 else []
    parts, rest = [], tf.expr
    for lo, hi in itertools.pairwise(Ls):
        part = sp.Add(*(sp.cancel(h[j][0, 0]) * z**-j for j in range(lo, hi)))
        part = sp.cancel(sp.together(part))
        parts.append(part)
        rest = rest - part
    parts.append(sp.cancel(sp.together(rest)))
    return parts
