"""The integer form of a structure's signal graph and the searches run on it (pure Python)."""

from __future__ import annotations

import heapq
from collections.abc import Hashable, Iterable, Iterator, Mapping, Sequence
from types import MappingProxyType
from typing import NamedTuple

__all__ = ["SignalGraph", "back_edges", "delay_free_cycle", "zero_one_bfs"]


class SignalGraph(NamedTuple):
    """Integer form of a structure: ``succ[a]`` / ``pred[b]`` list ``(target / source, delay, wire id)``."""

    names: tuple[str, ...]
    index: Mapping[str, int]
    kinds: tuple[str, ...]
    wires: tuple[tuple[int, int, int], ...]  # (source, target, delay)
    succ: tuple[tuple[tuple[int, int, int], ...], ...]  # per signal: (target, delay, wire id)
    pred: tuple[tuple[tuple[int, int, int], ...], ...]  # per signal: (source, delay, wire id)
    inputs: tuple[int, ...]
    outputs: tuple[int, ...]

    @classmethod
    def from_wires(
        cls,
        names: Sequence[str],
        kinds: Sequence[str],
        wires: Iterable[tuple[int, int, int]],
        inputs: Sequence[int],
        outputs: Sequence[int],
    ) -> SignalGraph:
        """The signal graph of ``names`` joined by ``wires`` ``(source, target, delay)``."""
        succ: list[list] = [[] for _ in names]
        pred: list[list] = [[] for _ in names]
        wires = tuple(wires)
        for e, (a, b, w) in enumerate(wires):
            succ[a].append((b, w, e))
            pred[b].append((a, w, e))
        return cls(
            tuple(names),
            MappingProxyType({n: i for i, n in enumerate(names)}),
            tuple(kinds),
            wires,
            tuple(map(tuple, succ)),
            tuple(map(tuple, pred)),
            tuple(inputs),
            tuple(outputs),
        )

    @property
    def successors(self) -> tuple[tuple[int, ...], ...]:
        """Per signal, the targets of its wires (in wire order)."""
        return tuple(tuple(b for b, _, _ in out) for out in self.succ)


def zero_one_bfs(graph: SignalGraph, sources, allowed=None) -> list[int | None]:
    """Fewest delays from any of ``sources`` to every signal (None if unreachable; Dijkstra);
    ``allowed`` (a boolean per signal) restricts the paths."""
    dist: list[int | None] = [None] * len(graph.names)
    for s in sources:
        dist[s] = 0
    heap = [(0, s) for s in sources]
    heapq.heapify(heap)
    while heap:
        da, a = heapq.heappop(heap)
        if da != dist[a]:
            continue
        for b, w, _ in graph.succ[a]:
            if (allowed is None or allowed[b]) and (dist[b] is None or da + w < dist[b]):
                dist[b] = da + w
                heapq.heappush(heap, (da + w, b))
    return dist


def _closing(successors, roots: Iterable[Hashable]) -> Iterator[list]:
    """Depth-first search from ``roots``, then the rest; per edge closing a cycle, the stack to its
    source and its target.
    """
    nodes = successors.keys() if isinstance(successors, Mapping) else range(len(successors))
    state: dict = {}  # absent new, 1 on the stack, 2 done
    for root in (*roots, *nodes):
        if root in state:
            continue
        stack = [(root, iter(successors[root]))]
        state[root] = 1
        while stack:
            node, children = stack[-1]
            child = next(children, None)
            if child is None:
                state[node] = 2
                stack.pop()
            elif state.get(child) == 1:
                yield [n for n, _ in stack] + [child]
            elif child not in state:
                state[child] = 1
                stack.append((child, iter(successors[child])))


def back_edges(
    successors: Sequence[Iterable[int]] | Mapping[Hashable, Iterable[Hashable]],
    roots: Iterable[Hashable],
) -> list[tuple]:
    """The edges ``(a, b)`` closing a cycle in a depth-first search from ``roots``, in order (nodes
    ``0 .. n-1`` of a sequence, or a mapping's keys); without them the graph is acyclic."""
    return [(path[-2], path[-1]) for path in _closing(successors, roots)]


def delay_free_cycle(graph: SignalGraph) -> list[str] | None:
    """A cycle of delay-free wires as signal names (first name repeated at the end), or None."""
    instant = [[b for b, w, _ in out if w == 0] for out in graph.succ]
    for path in _closing(instant, graph.inputs):
        start = path.index(path[-1])
        return [graph.names[i] for i in path[start:]]
    return None
