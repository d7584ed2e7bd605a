"""Delay graphs (the paper's section "Structure, delay graphs, and compatibility"); NumPy only."""

from __future__ import annotations

import itertools
import math
import numbers
import sys
from collections.abc import Iterable
from dataclasses import InitVar, dataclass, field
from functools import cached_property

import numpy as np

from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["DelayGraph", "matrix_latex"]

INF = math.inf
"""No path: the delay of an unreachable vertex."""

MAX_VERTICES = 1000
"""Most vertices of a delay graph: its shortest-path closure is cubic (about 3 s at 1000)."""

PARALLEL_EDGES = 8  # entries of an edge list per ordered pair of vertices

MAX_EDGE_DELAY = 10**12
"""Largest finite delay (steps) of an entry or edge: sums along any path stay exact in a float."""


def _vertex_count(n: int, argname: str) -> None:
    if n > MAX_VERTICES:
        raise ParameterError(
            f"{argname}: a delay graph has at most {MAX_VERTICES} vertices, got {n}"
        )


def _delay(value, argname: str, *, allow_inf: bool) -> float:
    """A delay: an integer >= 0 (integral floats accepted), or infinity when allowed."""
    x = value
    sp = sys.modules.get("sympy")  # a SymPy number exists only once SymPy is loaded
    if sp is not None and isinstance(x, sp.Basic):
        x = INF if x == sp.oo else int(x) if x.is_Integer else None
    elif isinstance(x, str) and x.strip().lower() in ("inf", "oo", "infinity"):
        x = INF
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise ParameterError(f"{argname}: delays must be integers >= 0, got {value!r}")
    try:
        out = float(x)
    except OverflowError:  # an integer beyond the float range
        out = math.nan
    if out == INF and allow_inf:
        return INF
    if not 0 <= out <= MAX_EDGE_DELAY or out != int(out):  # NaN fails both
        what = "integers >= 0" + (" or inf" if allow_inf else "")
        raise ParameterError(
            f"{argname}: delays must be {what} up to {MAX_EDGE_DELAY}, got {value!r}"
        )
    return float(int(out))


def _closure(E: np.ndarray) -> np.ndarray:
    """Floyd-Warshall shortest-path closure (min-plus), vectorized."""
    E = E.copy()
    for k in range(E.shape[0]):
        np.minimum(E, E[:, k, None] + E[None, k, :], out=E)
    return E


def _direct_edges(E: np.ndarray) -> tuple[tuple[int, int, int], ...]:
    """The entries not explained by a two-step route ``i -> k -> j`` (``k`` not ``i``, ``j``)."""
    n = E.shape[0]
    out = []
    for i in range(n):
        via = E[i, :, None] + E  # via[k, j] = E[i, k] + E[k, j]
        via[i, :] = INF
        np.fill_diagonal(via, INF)
        explained = np.any(via <= E[i][None, :], axis=0)
        out += [
            (i + 1, j + 1, int(E[i, j]))
            for j in np.flatnonzero(~explained & np.isfinite(E[i]))
            if j != i
        ]
    return tuple(out)


def _ends(value, default: tuple[int, ...], n: int, argname: str) -> tuple[int, ...]:
    """Sensor or actuator vertices: distinct integers in 1..n (``default`` for None)."""
    if value is None:
        return default
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        value = (value,)
    if isinstance(value, str) or not isinstance(value, Iterable):
        raise ParameterError(f"{argname}: expected vertices 1..{n}, got {value!r}")
    out = tuple(itertools.islice(value, MAX_VERTICES + 1))
    if not out or len(out) > MAX_VERTICES:
        raise ParameterError(f"{argname}: expected 1 to {MAX_VERTICES} vertices, got {len(out)}")
    for v in out:
        if isinstance(v, bool) or not isinstance(v, numbers.Integral) or not 1 <= v <= n:
            raise ParameterError(f"{argname}: vertices are integers 1..{n}, got {v!r}")
    if len(set(out)) != len(out):
        raise ParameterError(f"{argname}: a vertex appears twice in {list(out)}")
    return tuple(int(v) for v in out)


def _fmt(value: float) -> str:
    return "inf" if math.isinf(value) else str(int(value))


def matrix_latex(name: str, E: np.ndarray) -> str:
    r"""``name = [...]`` as a LaTeX ``bmatrix`` of delays (:math:`\infty` where no path)."""
    rows = r" \\ ".join(
        " & ".join(r"\infty" if math.isinf(v) else str(int(v)) for v in row) for row in E
    )
    return name + r" = \begin{bmatrix}" + rows + r"\end{bmatrix}"


@dataclass(frozen=True, eq=False)
class DelayGraph:
    r"""A delay graph: vertices :math:`v_1` (sensor) .. :math:`v_N` (actuator), delays :math:`E`.

    :math:`E_{ij}` is the delay in steps of the shortest path from :math:`v_i` to :math:`v_j`.
    A frozen value, equal when :attr:`E`, :attr:`edges` and the ends are.

    Parameters
    ----------
    E : (N, N) matrix-like
        Integers >= 0, ``inf`` (``math.inf``, ``numpy.inf``, ``sympy.oo`` or ``"inf"``) where
        no path exists, zero diagonal, closed (:math:`E_{ik} \le E_{ij} + E_{jk}`).
    sensors, actuators : sequence of int, optional (keyword)
        The sensor (actuator) vertices from 1, default ``(1,)`` (``(N,)``): one for all the
        controller's inputs (outputs), or one per input (output).

    Attributes
    ----------
    E : numpy.ndarray
        Read-only float array.
    n : int
        Number of vertices :math:`N`.
    edges : tuple of (i, j, delay)
        The direct edges (from 1): :meth:`from_edges`'s, or the entries not explained by a
        shorter two-step route.

    Raises
    ------
    ParameterError
        Negative or non-integer delays, a nonzero diagonal, no shortest-path closure, fewer than
        two vertices, a vertex no sensor reaches or that reaches no actuator, bad ends.
    DimensionError
        A matrix that is not square.
    SymctlTypeError
        ``E`` is not a matrix.

    Examples
    --------
    >>> import math
    >>> from symctl import DelayGraph
    >>> DelayGraph([[0, 1, 2], ["inf", 0, 1], ["inf", "inf", 0]]).chain_delays
    (1, 1)
    >>> DelayGraph([[0, 1, 5], [math.inf, 0, 1], [math.inf, math.inf, 0]])
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: E: not a shortest-path closure: E[1,3] = 5 but E[1,2] + E[2,3] = 2
    """

    E: np.ndarray
    _edges: InitVar[tuple | None] = field(default=None, kw_only=True)
    edges: tuple[tuple[int, int, int], ...] = field(init=False)
    sensors: tuple[int, ...] = field(default=None, kw_only=True)
    actuators: tuple[int, ...] = field(default=None, kw_only=True)

    def __post_init__(self, _edges):
        E = self.E
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
        _vertex_count(n, "E")
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
        sensors = _ends(self.sensors, (1,), n, "sensors")
        actuators = _ends(self.actuators, (n,), n, "actuators")
        unreached = np.flatnonzero(np.isinf(arr[[v - 1 for v in sensors]]).all(axis=0)) + 1
        if len(unreached):
            raise ParameterError(
                f"E: v1 is not a source: there is no path from v1 to v{unreached[0]}"
                if sensors == (1,)
                else f"E: no sensor vertex reaches v{unreached[0]}"
            )
        stranded = np.flatnonzero(np.isinf(arr[:, [v - 1 for v in actuators]]).all(axis=1)) + 1
        if len(stranded):
            raise ParameterError(
                f"E: v{n} is not a sink: there is no path from v{stranded[0]} to v{n}"
                if actuators == (n,)
                else f"E: v{stranded[0]} reaches no actuator vertex"
            )
        object.__setattr__(self, "sensors", sensors)
        object.__setattr__(self, "actuators", actuators)
        arr.setflags(write=False)
        if _edges is None:
            _edges = _direct_edges(arr)
        object.__setattr__(self, "E", arr)
        object.__setattr__(self, "edges", tuple(_edges))

    @classmethod
    def from_edges(
        cls, n: int, edges: Iterable[tuple[int, int, int]], *, sensors=None, actuators=None
    ) -> DelayGraph:
        """The delay graph of ``n`` vertices and the edges ``(i, j, delay)`` (vertices 1..n).

        Parallel edges keep the smallest delay; at most ``PARALLEL_EDGES * n**2`` edges are read.

        >>> from symctl import DelayGraph
        >>> DelayGraph.from_edges(3, [(1, 2, 1), (2, 3, 1), (1, 3, 4)]).E.tolist()
        [[0.0, 1.0, 2.0], [inf, 0.0, 1.0], [inf, inf, 0.0]]
        """
        if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 2:
            raise ParameterError(f"n: the number of vertices must be an integer >= 2, got {n!r}")
        n = int(n)
        _vertex_count(n, "n")
        arr = np.full((n, n), INF)
        np.fill_diagonal(arr, 0)
        kept: dict[tuple[int, int], int] = {}
        if not isinstance(edges, Iterable):
            raise SymctlTypeError(f"edges: expected (i, j, delay) triples, got {edges!r}")
        limit = PARALLEL_EDGES * n * n
        for k, edge in enumerate(edges):
            if k >= limit:
                raise ParameterError(
                    f"edges: at most {limit} entries for {n} vertices "
                    f"({PARALLEL_EDGES} per ordered pair), got more"
                )
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
        return cls(
            _closure(arr),
            _edges=tuple((i, j, d) for (i, j), d in kept.items()),
            sensors=sensors,
            actuators=actuators,
        )

    @classmethod
    def chain(cls, delays: Iterable[int]) -> DelayGraph:
        """The chain :math:`v_1 \\to v_2 \\to \\dots \\to v_N` with the given step delays.

        >>> from symctl import DelayGraph
        >>> DelayGraph.chain([1, 0, 2]).E[0].tolist()
        [0.0, 1.0, 1.0, 3.0]
        """
        if isinstance(delays, str) or not isinstance(delays, Iterable):
            raise ParameterError(f"delays: expected a list of integers >= 0, got {delays!r}")
        steps = list(itertools.islice(delays, MAX_VERTICES))  # bounded: an endless iterable too
        if not steps:
            raise ParameterError("delays: a chain needs at least one step (two vertices)")
        _vertex_count(len(steps) + 1, "delays")  # MAX_VERTICES - 1 steps at most
        D = np.cumsum(
            [0.0] + [_delay(d, f"delays[{k}]", allow_inf=False) for k, d in enumerate(steps)]
        )
        E = np.where(np.triu(np.ones((len(D), len(D)), dtype=bool)), D[None, :] - D[:, None], INF)
        edges = tuple((k + 1, k + 2, int(D[k + 1] - D[k])) for k in range(len(steps)))
        return cls(E, _edges=edges)

    @property
    def n(self) -> int:
        """Number of vertices."""
        return self.E.shape[0]

    @cached_property
    def chain_order(self) -> tuple[tuple[int, ...], tuple[int, ...]] | None:
        """``(order, D)`` when :math:`E` is the closure of a chain (vertices from 1 along it, the delay
        from :math:`v_1` to each), else None.
        """
        E = self.E
        n = self.n
        reach = np.isfinite(E).sum(axis=1)
        order = sorted(range(n), key=lambda v: (-reach[v], E[0, v], v))
        if order[0] != 0 or order[-1] != n - 1:
            return None
        P = E[np.ix_(order, order)]
        D = P[0]
        if not np.isfinite(D).all():  # v1 does not reach every vertex: not a chain
            return None
        upper = np.triu(np.ones((n, n), dtype=bool))
        expected = np.where(upper, D[None, :] - D[:, None], INF)
        if not np.array_equal(P, expected):
            return None
        return tuple(v + 1 for v in order), tuple(int(d) for d in D)

    @property
    def is_chain(self) -> bool:
        """Whether :math:`E` is the closure of a chain."""
        return self.chain_order is not None

    @property
    def chain_delays(self) -> tuple[int, ...] | None:
        """The step delays along the chain, or None when the graph is not a chain."""
        if self.chain_order is None:
            return None
        D = self.chain_order[1]
        return tuple(b - a for a, b in itertools.pairwise(D))

    def draw(self, names=None, **kwargs):
        """Draw the graph (a Figure): ``names`` of the vertices; ``kwargs`` (``title``,
        ``descriptions``, ``ax``) go to :func:`symctl.plotting.delaygraph.delay_graph_plot`.

        >>> from symctl import DelayGraph
        >>> fig = DelayGraph.chain([1, 1]).draw(["Golgi tendon organ", "nervous system", "muscle"])
        >>> type(fig).__name__
        'Figure'
        """
        from symctl.plotting.delaygraph import delay_graph_plot

        return delay_graph_plot(self, names, **kwargs)

    def latex(self) -> str:
        """The matrix :math:`E` in LaTeX."""
        return matrix_latex("E", self.E)

    def _repr_latex_(self) -> str:  # LatexMixin's, without loading SymPy
        return f"$\\displaystyle {self.latex()}$"

    def __eq__(self, other) -> bool:
        if not isinstance(other, DelayGraph):
            return NotImplemented
        return (
            self.edges == other.edges
            and np.array_equal(self.E, other.E)
            and (self.sensors, self.actuators) == (other.sensors, other.actuators)
        )

    def __hash__(self) -> int:
        return hash((self.E.shape, self.E.tobytes(), self.edges, self.sensors, self.actuators))

    def __repr__(self) -> str:
        ends = ""
        if self.sensors != (1,) or self.actuators != (self.n,):
            ends = f", sensors={self.sensors}, actuators={self.actuators}"
        return f"DelayGraph(n={self.n}, edges={list(self.edges)}{ends})"

    def pins(self, inputs: int, outputs: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
        """The vertex (from 1) of each of ``inputs`` controller inputs and ``outputs`` outputs;
        DimensionError when the sensor or actuator vertices fit neither one for all nor one each.

        >>> from symctl import DelayGraph
        >>> g = DelayGraph.from_edges(4, [(1, 3, 1), (2, 3, 1), (3, 4, 1)], sensors=[1, 2])
        >>> g.pins(2, 3)
        ((1, 2), (4, 4, 4))
        """
        out = []
        for what, count, ends in (
            ("input", inputs, self.sensors),
            ("output", outputs, self.actuators),
        ):
            if len(ends) == 1:
                out.append(ends * count)
            elif len(ends) == count:
                out.append(ends)
            else:
                role = "sensor" if what == "input" else "actuator"
                raise DimensionError(
                    f"graph: the delay graph has {len(ends)} {role} vertices "
                    f"({', '.join(f'v{v}' for v in ends)}) but the controller {count} {what}s; "
                    f"give one {role} vertex for all {what}s or one per {what}"
                )
        return out[0], out[1]
