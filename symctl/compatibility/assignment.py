r"""Delay assignments: every signal of a structure at one vertex of a delay graph.

A **delay assignment** puts every signal at one vertex, the inputs at the sensor and the
outputs at the actuator. :math:`\tilde E_{ij}` is the delay of the fastest path from a signal
at :math:`v_i` to a signal at :math:`v_j` (:math:`\infty` if none, 0 on the diagonal); the
assignment is compatible when :math:`\tilde E \ge E`. Two readings of "fastest path"
(``reading=``): ``"fastest"`` (default, the definition's words), any path of the structure;
``"direct"`` (the matrix printed in the paper for :math:`G_3 G_2 G_1`), only paths whose
signals all sit at :math:`v_i` or :math:`v_j`.

Both give the same verdict when :math:`E` is a shortest-path closure (every
:class:`DelayGraph`): fastest is entrywise at most direct, and a direct-compatible assignment
meets :math:`E_{v(a) v(b)} \le w` on every wire (a wire is a direct path), which makes it
compatible in the fastest reading (the reduction of :mod:`~symctl.compatibility.csp`).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from types import MappingProxyType

import numpy as np

from symctl._util.display import LatexMixin
from symctl.compatibility.delaygraph import DelayGraph, matrix_latex
from symctl.compatibility.signalgraph import zero_one_bfs
from symctl.compatibility.structure import Structure
from symctl.errors import ParameterError, SymctlTypeError

__all__ = ["READINGS", "DelayAssignment"]

READINGS = ("fastest", "direct")
"""The two readings of the delay assignment matrix (see the module text)."""

INF = math.inf


@dataclass(frozen=True, eq=False)
class DelayAssignment(LatexMixin):
    r"""Every signal of a structure at one vertex of a delay graph (a frozen value).

    Parameters
    ----------
    structure : Structure
    graph : DelayGraph
    vertex_of : mapping of signal name to vertex (1..N)
        Every signal once; inputs and outputs at their sensor and actuator vertices
        (:meth:`DelayGraph.pins`).

    Raises
    ------
    SymctlTypeError
        ``structure``, ``graph`` or ``vertex_of`` of the wrong type.
    ParameterError
        A missing or unknown signal, a vertex out of range, an input or output off its vertex.
    DimensionError
        The graph's sensor or actuator vertices do not fit the structure.

    Examples
    --------
    The paper's attempt for the IFP structure: :math:`\mu` at :math:`v_3`.

    >>> from symctl import DelayAssignment, DelayGraph, ifp_structure
    >>> a = DelayAssignment(ifp_structure(2), DelayGraph.chain([1, 1]),
    ...     {"x": 1, "K0": 1, "mu": 3, "gamma": 3, "u": 3, "K1": 3, "K2": 3})
    >>> a.E_tilde.tolist(), a.is_compatible()
    ([[0.0, inf, 0.0], [inf, 0.0, inf], [inf, inf, 0.0]], False)
    """

    structure: Structure
    graph: DelayGraph
    vertex_of: Mapping[str, int]

    def __post_init__(self):
        structure, graph, vertex_of = self.structure, self.graph, self.vertex_of
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
        at_in, at_out = graph.pins(len(structure.inputs), len(structure.outputs))
        ends = [("input", structure.inputs, at_in), ("output", structure.outputs, at_out)]
        for role, names, at in ends:
            for name, v in zip(names, at, strict=True):
                if clean[name] != v:
                    raise ParameterError(
                        f"vertex_of[{name!r}]: the {role} must be at v{v}, got v{clean[name]}"
                    )
        ordered = {name: clean[name] for name in structure.blocks}  # the structure's order
        object.__setattr__(self, "vertex_of", MappingProxyType(ordered))

    def signals_at(self, vertex: int) -> tuple[str, ...]:
        """The signals assigned to ``vertex``."""
        return tuple(s for s, v in self.vertex_of.items() if v == vertex)

    @cached_property
    def E_tilde(self) -> np.ndarray:
        r""":math:`\tilde E` in the definition's reading."""
        return self.e_tilde("fastest")

    def e_tilde(self, reading: str = "fastest") -> np.ndarray:
        r""":math:`\tilde E` in one of the :data:`READINGS` (read-only float array).

        >>> from symctl import DelayAssignment, DelayGraph, ifp_structure
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
            dist = zero_one_bfs(cs, groups[i])
            for j in range(n):
                if j == i or not groups[j]:
                    continue
                if reading == "direct":  # through signals at v_i and v_j only
                    dist = zero_one_bfs(cs, groups[i], [v in (i, j) for v in where])
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
        r"""The matrix :math:`\tilde E` in LaTeX."""
        return matrix_latex(r"\tilde E", self.E_tilde)

    def __eq__(self, other) -> bool:
        if not isinstance(other, DelayAssignment):
            return NotImplemented
        return (self.structure, self.graph, self.vertex_of) == (
            other.structure,
            other.graph,
            other.vertex_of,
        )

    def __hash__(self) -> int:
        return hash((self.structure, self.graph, frozenset(self.vertex_of.items())))

    def __repr__(self) -> str:
        groups = "; ".join(
            f"v{v}: {', '.join(self.signals_at(v))}" for v in range(1, self.graph.n + 1)
        )
        return f"DelayAssignment({groups})"
