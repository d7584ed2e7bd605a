r"""Delay graphs and delay assignments (the paper's section "Structure, delay graphs, and compatibility").

A **delay graph** has vertices :math:`v_1` (the sensor, source) to :math:`v_N`
(the actuator, sink); :math:`E_{ij}` is the delay of the shortest path from
:math:`v_i` to :math:`v_j` in steps, :math:`E_{ii} = 0`, :math:`\infty` where no
path exists. The paper's neuromuscular graph is the chain
:math:`v_1 \to v_2 \to v_3` with one step per edge:

>>> g = DelayGraph.chain([1, 1])
>>> g.E.tolist()
[[0.0, 1.0, 2.0], [inf, 0.0, 1.0], [inf, inf, 0.0]]

A **delay assignment** puts every signal of a structure at one vertex, the
controller input at :math:`v_1` and the output at :math:`v_N`. Its matrix
:math:`\tilde E_{ij}` is the delay of the fastest path from a signal at
:math:`v_i` to a signal at :math:`v_j` (:math:`\infty` if none, 0 on the
diagonal); the assignment is compatible when :math:`\tilde E \ge E`.

Two readings of "fastest path" (``reading=``):

``"fastest"`` (default, the definition's words)
    any path of the structure, through signals at any vertices;
``"direct"`` (the matrix printed in the paper for :math:`G_3 G_2 G_1`)
    only paths whose signals all sit at :math:`v_i` or :math:`v_j`; the paper
    prints :math:`\tilde E_{13} = \infty` although a path of delay 2 runs from
    :math:`v_1` through :math:`v_2` to :math:`v_3`.

Both readings give the same verdict whenever :math:`E` is a shortest-path
closure (always, for a :class:`DelayGraph`): the fastest reading is entrywise
at most the direct one, so compatible-by-fastest implies compatible-by-direct;
conversely a direct-compatible assignment satisfies
:math:`E_{v(a) v(b)} \le w` on every wire :math:`a \to b` of delay :math:`w`
(a wire is a direct path), and then, summing along any path and using the
triangle inequality of :math:`E`, the fastest reading is compatible too.
"""

from __future__ import annotations

import itertools
import math
import numbers
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import cached_property
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.display import LatexMixin
from symctl.compatibility.signalgraph import zero_one_bfs
from symctl.compatibility.structure import Structure
from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["READINGS", "DelayAssignment", "DelayGraph"]

READINGS = ("fastest", "direct")
"""The two readings of the delay assignment matrix (see the module text)."""

INF = math.inf


def _delay(value, argname: str, *, allow_inf: bool) -> float:
    """A delay: an integer >= 0 (integral floats accepted), or infinity when allowed."""
    if isinstance(value, bool):
        raise ParameterError(f"{argname}: delays must be integers >= 0, got {value!r}")
    if isinstance(value, sp.Basic):
        if value in (sp.oo,) and allow_inf:
            return INF
        if value.is_Integer:
            value = int(value)
        else:
            raise ParameterError(f"{argname}: delays must be integers >= 0, got {value!r}")
    if isinstance(value, str) and allow_inf and value.strip().lower() in ("inf", "oo", "infinity"):
        return INF
    if not isinstance(value, numbers.Real):
        raise ParameterError(f"{argname}: delays must be integers >= 0, got {value!r}")
    out = float(value)
    if math.isinf(out) and out > 0 and allow_inf:
        return INF
    if math.isnan(out) or math.isinf(out) or out != int(out) or out < 0:
        what = "integers >= 0" + (" or inf" if allow_inf else "")
        raise ParameterError(f"{argname}: delays must be {what}, got {value!r}")
    return float(int(out))


def _closure(E: np.ndarray) -> np.ndarray:
    """Floyd-Warshall shortest-path closure (min-plus), vectorized."""
    E = E.copy()
    for k in range(E.shape[0]):
        np.minimum(E, E[:, k, None] + E[None, k, :], out=E)
    return E


def _fmt(value: float) -> str:
    return "inf" if math.isinf(value) else str(int(value))


@dataclass(frozen=True, eq=False)
class DelayGraph(LatexMixin):
    r"""A delay graph: vertices :math:`v_1` (sensor) .. :math:`v_N` (actuator), delays :math:`E`.

    Parameters
    ----------
    E : (N, N) matrix-like
        The shortest-path delays: integers >= 0, ``inf`` (``math.inf``,
        ``numpy.inf``, ``sympy.oo`` or ``"inf"``) where no path exists, zero
        diagonal, and closed (:math:`E_{ik} \le E_{ij} + E_{jk}`).

    Attributes
    ----------
    E : numpy.ndarray
        Read-only float array (``inf`` where no path).
    n : int
        Number of vertices :math:`N`.
    edges : tuple of (i, j, delay)
        The direct edges, vertices numbered from 1 (for :meth:`from_edges` the
        given ones; from a matrix, the entries not explained by a shorter
        two-step route).

    Raises
    ------
    ParameterError
        Negative or non-integer delays, a nonzero diagonal, a matrix that is
        not a shortest-path closure, fewer than two vertices, a vertex that
        :math:`v_1` cannot reach (no source) or that cannot reach
        :math:`v_N` (no sink).
    DimensionError
        A matrix that is not square.

    Examples
    --------
    >>> DelayGraph([[0, 1, 2], ["inf", 0, 1], ["inf", "inf", 0]]).chain_delays
    (1, 1)
    >>> DelayGraph([[0, 1, 5], [math.inf, 0, 1], [math.inf, math.inf, 0]])
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: E: not a shortest-path closure: E[1,3] = 5 but E[1,2] + E[2,3] = 2
    """

    E: np.ndarray
    edges: tuple[tuple[int, int, int], ...]

    def __init__(self, E, *, _edges=None):
        if isinstance(E, DelayGraph):
            E = E.E
        try:
            rows = [list(r) for r in (E.tolist() if hasattr(E, "tolist") else E)]
        except TypeError:
            raise SymctlTypeError(f"E: expected a square matrix, got {E!r}") from None
        n = len(rows)
        if any(len(r) != n for r in rows):
            raise DimensionError(
                f"E: expected a square matrix, got rows of lengths {[len(r) for r in rows]}"
            )
        if n < 2:
            raise ParameterError(
                f"E: a delay graph needs a source v1 and a sink vN (N >= 2), got N = {n}"
            )
        arr = np.array(
            [
                [_delay(v, f"E[{i + 1},{j + 1}]", allow_inf=True) for j, v in enumerate(r)]
                for i, r in enumerate(rows)
            ],
            dtype=float,
        )
        for i in range(n):
            if arr[i, i] != 0:
                raise ParameterError(
                    f"E: diagonal entries must be 0, got E[{i + 1},{i + 1}] = {_fmt(arr[i, i])}"
                )
        closed = _closure(arr)
        bad = np.argwhere(closed < arr)
        if len(bad):
            i, k = (int(v) for v in bad[0])
            via = int(np.argmin(arr[i, :] + arr[:, k]))
            raise ParameterError(
                f"E: not a shortest-path closure: E[{i + 1},{k + 1}] = {_fmt(arr[i, k])} but "
                f"E[{i + 1},{via + 1}] + E[{via + 1},{k + 1}] = {_fmt(arr[i, via] + arr[via, k])}"
            )
        unreached = np.flatnonzero(np.isinf(arr[0]))
        if len(unreached):
            raise ParameterError(
                f"E: v1 is not a source: there is no path from v1 to v{unreached[0] + 1}"
            )
        stranded = np.flatnonzero(np.isinf(arr[:, n - 1]))
        if len(stranded):
            raise ParameterError(
                f"E: v{n} is not a sink: there is no path from v{stranded[0] + 1} to v{n}"
            )
        arr.setflags(write=False)
        if _edges is None:
            _edges = tuple(
                (i + 1, j + 1, int(arr[i, j]))
                for i in range(n)
                for j in range(n)
                if i != j
                and not math.isinf(arr[i, j])
                and not any(
                    k not in (i, j) and arr[i, k] + arr[k, j] <= arr[i, j] for k in range(n)
                )
            )
        object.__setattr__(self, "E", arr)
        object.__setattr__(self, "edges", tuple(_edges))

    # ------------------------------------------------------------ constructors
    @classmethod
    def from_edges(cls, n: int, edges: Iterable[tuple[int, int, int]]) -> DelayGraph:
        """The delay graph of ``n`` vertices and the edges ``(i, j, delay)`` (vertices 1..n).

        Parallel edges keep the smallest delay; :attr:`E` is the shortest-path closure.

        >>> DelayGraph.from_edges(3, [(1, 2, 1), (2, 3, 1), (1, 3, 4)]).E.tolist()
        [[0.0, 1.0, 2.0], [inf, 0.0, 1.0], [inf, inf, 0.0]]
        """
        if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 2:
            raise ParameterError(f"n: the number of vertices must be an integer >= 2, got {n!r}")
        n = int(n)
        arr = np.full((n, n), INF)
        np.fill_diagonal(arr, 0)
        kept: dict[tuple[int, int], int] = {}
        if not isinstance(edges, Iterable):
            raise SymctlTypeError(f"edges: expected (i, j, delay) triples, got {edges!r}")
        for k, edge in enumerate(edges):
            if not isinstance(edge, tuple | list) or len(edge) != 3:
                raise ParameterError(f"edges[{k}]: expected (i, j, delay), got {edge!r}")
            i, j, d = edge
            for name, v in (("i", i), ("j", j)):
                if isinstance(v, bool) or not isinstance(v, numbers.Integral) or not 1 <= v <= n:
                    raise ParameterError(
                        f"edges[{k}]: vertex {name} must be an integer in 1..{n}, got {v!r}"
                    )
            if i == j:
                raise ParameterError(f"edges[{k}]: a self-loop ({i}, {j}) has no meaning")
            delay = int(_delay(d, f"edges[{k}] delay", allow_inf=False))
            key = (int(i), int(j))
            kept[key] = min(delay, kept.get(key, delay))
            arr[key[0] - 1, key[1] - 1] = kept[key]
        return cls(_closure(arr), _edges=tuple((i, j, d) for (i, j), d in kept.items()))

    @classmethod
    def chain(cls, delays: Iterable[int]) -> DelayGraph:
        """The chain :math:`v_1 \\to v_2 \\to \\dots \\to v_N` with the given step delays.

        >>> DelayGraph.chain([1, 0, 2]).E[0].tolist()
        [0.0, 1.0, 1.0, 3.0]
        """
        if isinstance(delays, str) or not isinstance(delays, Iterable):
            raise ParameterError(f"delays: expected a list of integers >= 0, got {delays!r}")
        steps = list(delays)
        if not steps:
            raise ParameterError("delays: a chain needs at least one step (two vertices)")
        D = np.concatenate(
            (
                [0.0],
                np.cumsum(
                    [_delay(d, f"delays[{k}]", allow_inf=False) for k, d in enumerate(steps)]
                ),
            )
        )
        E = np.where(np.triu(np.ones((len(D), len(D)), dtype=bool)), D[None, :] - D[:, None], INF)
        edges = tuple((k + 1, k + 2, int(D[k + 1] - D[k])) for k in range(len(steps)))
        return cls(E, _edges=edges)

    # ------------------------------------------------------------ views
    @property
    def n(self) -> int:
        """Number of vertices."""
        return self.E.shape[0]

    @cached_property
    def chain_order(self) -> tuple[tuple[int, ...], tuple[int, ...]] | None:
        """``(order, D)`` when :math:`E` is the closure of a chain, else None.

        ``order`` lists the vertices (from 1) along the chain, ``D`` the delay
        from :math:`v_1` to each: :math:`E_{ij} = D_j - D_i` when ``i`` comes no
        later than ``j``, :math:`\\infty` otherwise. Zero-delay steps are allowed.
        """
        E = self.E
        n = self.n
        reach = np.isfinite(E).sum(axis=1)
        order = sorted(range(n), key=lambda v: (-reach[v], E[0, v], v))
        if order[0] != 0 or order[-1] != n - 1:
            return None
        P = E[np.ix_(order, order)]
        D = P[0]
        upper = np.triu(np.ones((n, n), dtype=bool))
        expected = np.where(upper, D[None, :] - D[:, None], INF)
        if not np.array_equal(P, expected):
            return None
        return tuple(v + 1 for v in order), tuple(int(d) for d in D)

    @property
    def is_chain(self) -> bool:
        """Whether :math:`E` is the closure of a chain (decided in polynomial time)."""
        return self.chain_order is not None

    @property
    def chain_delays(self) -> tuple[int, ...] | None:
        """The step delays along the chain, or None when the graph is not a chain."""
        if self.chain_order is None:
            return None
        D = self.chain_order[1]
        return tuple(b - a for a, b in itertools.pairwise(D))

    def latex(self) -> str:
        rows = r" \\ ".join(
            " & ".join(r"\infty" if math.isinf(v) else str(int(v)) for v in row) for row in self.E
        )
        return r"E = \begin{bmatrix}" + rows + r"\end{bmatrix}"

    def to_networkx(self):
        """The direct edges as a :class:`networkx.DiGraph` (attribute ``delay``)."""
        import networkx as nx

        g = nx.DiGraph()
        g.add_nodes_from(range(1, self.n + 1))
        g.add_edges_from((i, j, {"delay": d}) for i, j, d in self.edges)
        return g

    def __repr__(self) -> str:
        return f"DelayGraph(n={self.n}, edges={list(self.edges)})"


@dataclass(frozen=True, eq=False)
class DelayAssignment(LatexMixin):
    r"""Every signal of a structure at one vertex of a delay graph.

    Parameters
    ----------
    structure : Structure
    graph : DelayGraph
    vertex_of : mapping of signal name to vertex (1..N)
        Every signal exactly once; inputs at :math:`v_1`, outputs at :math:`v_N`.

    Raises
    ------
    ParameterError
        A missing or unknown signal, a vertex out of range, an input not at
        :math:`v_1` or an output not at :math:`v_N`.

    Examples
    --------
    The paper's attempt for the IFP structure: :math:`\mu` at :math:`v_3`.

    >>> from symctl.compatibility.structure import ifp_structure
    >>> S = ifp_structure(2)
    >>> a = DelayAssignment(S, DelayGraph.chain([1, 1]),
    ...     {"x": 1, "K0": 1, "mu": 3, "gamma": 3, "u": 3, "K1": 3, "K2": 3})
    >>> a.E_tilde.tolist()
    [[0.0, inf, 0.0], [inf, 0.0, inf], [inf, inf, 0.0]]
    >>> a.is_compatible()
    False
    """

    structure: Structure
    graph: DelayGraph
    vertex_of: Mapping[str, int]

    def __init__(self, structure: Structure, graph: DelayGraph, vertex_of: Mapping[str, int]):
        if not isinstance(structure, Structure):
            raise SymctlTypeError(
                f"structure: expected a Structure, got {type(structure).__name__}"
            )
        if not isinstance(graph, DelayGraph):
            raise SymctlTypeError(f"graph: expected a DelayGraph, got {type(graph).__name__}")
        if not isinstance(vertex_of, Mapping):
            raise SymctlTypeError(
                f"vertex_of: expected a mapping of signal names to vertices, got {vertex_of!r}"
            )
        n = graph.n
        clean = {}
        for name, v in vertex_of.items():
            if name not in structure.blocks:
                raise ParameterError(f"vertex_of: {name!r} is not a signal of the structure")
            if isinstance(v, bool) or not isinstance(v, numbers.Integral) or not 1 <= v <= n:
                raise ParameterError(f"vertex_of[{name!r}]: must be a vertex 1..{n}, got {v!r}")
            clean[name] = int(v)
        missing = [s for s in structure.blocks if s not in clean]
        if missing:
            raise ParameterError(f"vertex_of: every signal needs a vertex; missing {missing[:5]}")
        for name in structure.inputs:
            if clean[name] != 1:
                raise ParameterError(
                    f"vertex_of[{name!r}]: the input must be at v1, got v{clean[name]}"
                )
        for name in structure.outputs:
            if clean[name] != n:
                raise ParameterError(
                    f"vertex_of[{name!r}]: the output must be at v{n}, got v{clean[name]}"
                )
        object.__setattr__(self, "structure", structure)
        object.__setattr__(self, "graph", graph)
        object.__setattr__(self, "vertex_of", MappingProxyType(clean))

    def signals_at(self, vertex: int) -> tuple[str, ...]:
        """The signals assigned to ``vertex``."""
        return tuple(s for s, v in self.vertex_of.items() if v == vertex)

    @cached_property
    def E_tilde(self) -> np.ndarray:
        """The delay assignment matrix by the definition's words (``reading="fastest"``)."""
        return self.e_tilde("fastest")

    def e_tilde(self, reading: str = "fastest") -> np.ndarray:
        r""":math:`\tilde E` in one of the :data:`READINGS` (read-only float array).

        >>> from symctl.compatibility.structure import ifp_structure
        >>> S = ifp_structure(1)
        >>> a = DelayAssignment(S, DelayGraph.chain([1]),
        ...                     {"x": 1, "K0": 1, "mu": 1, "K1": 2, "u": 2})
        >>> a.e_tilde("direct").tolist()
        [[0.0, 1.0], [0.0, 0.0]]
        """
        if reading not in READINGS:
            raise ParameterError(f"reading: must be one of {READINGS}, got {reading!r}")
        cs = self.structure.signal_graph
        n = self.graph.n
        where = [self.vertex_of[name] - 1 for name in cs.names]
        groups = [[s for s, v in enumerate(where) if v == i] for i in range(n)]
        out = np.full((n, n), INF)
        for i in range(n):
            if not groups[i]:
                continue
            if reading == "fastest":
                dist = zero_one_bfs(cs, groups[i])
                for s, d in enumerate(dist):
                    if d is not None:
                        out[i, where[s]] = min(out[i, where[s]], d)
            else:
                for j in range(n):
                    if j == i or not groups[j]:
                        continue
                    allowed = [v in (i, j) for v in where]
                    dist = zero_one_bfs(cs, groups[i], allowed)
                    found = [dist[s] for s in groups[j] if dist[s] is not None]
                    if found:
                        out[i, j] = min(found)
        np.fill_diagonal(out, 0)
        out.setflags(write=False)
        return out

    def violations(self, reading: str = "fastest") -> list[tuple[int, int, float, float]]:
        r"""The entries with :math:`\tilde E_{ij} < E_{ij}`, as ``(i, j, Ẽ_ij, E_ij)`` (from 1)."""
        Et = self.e_tilde(reading)
        E = self.graph.E
        return [
            (int(i) + 1, int(j) + 1, float(Et[i, j]), float(E[i, j]))
            for i, j in np.argwhere(Et < E)
        ]

    def is_compatible(self, reading: str = "fastest") -> bool:
        r"""Whether :math:`\tilde E_{ij} \ge E_{ij}` for all :math:`i, j`."""
        return not self.violations(reading)

    def latex(self) -> str:
        rows = r" \\ ".join(
            " & ".join(r"\infty" if math.isinf(v) else str(int(v)) for v in row)
            for row in self.E_tilde
        )
        return r"\tilde E = \begin{bmatrix}" + rows + r"\end{bmatrix}"

    def __repr__(self) -> str:
        groups = "; ".join(
            f"v{v}: {', '.join(self.signals_at(v))}" for v in range(1, self.graph.n + 1)
        )
        return f"DelayAssignment({groups})"
