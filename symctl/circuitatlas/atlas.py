"""The circuit atlas: every minimal circuit class of an order-:math:`n` :math:`G_2`, proved and ranked.

Generically minimal patterns whose circuits are isomorphic form a class
(:mod:`~symctl.circuitatlas.circuitclass`), universal when one of its patterns is proved so
(:mod:`~symctl.circuitatlas.universality`). Order 4 is searched over the sparsest patterns only
(:math:`3n` entries, the fewest a universal one can have: :mod:`~symctl.circuitatlas.rank`).

>>> import symctl
>>> A = symctl.atlas(2, workers=1)
>>> len(A.classes), len(A.universal_classes)
(37, 9)
"""

from __future__ import annotations

import functools
import os
import time
from collections import Counter, defaultdict
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import networkx as nx

from symctl._util.validate import bounded_int
from symctl.circuitatlas.circuitclass import CircuitClass, circuit_key, same_circuit
from symctl.circuitatlas.pattern import Pattern
from symctl.circuitatlas.search import pool_options, run
from symctl.circuitatlas.universality import CONJECTURED, Evidence
from symctl.errors import ParameterError, SymctlTypeError

__all__ = ["EXHAUSTIVE_MAX_ORDER", "MAX_ATLAS_ORDER", "Atlas", "atlas"]

EXHAUSTIVE_MAX_ORDER = 3  # highest order searched over every pattern

MAX_ATLAS_ORDER = 4  # highest order accepted (searched from the sparsest sizes up to max_size)

ORDER4_MAX_NEURONS = 3
"""Order 4 decides the patterns whose circuits have at most this many neurons (the sparsest)."""


@dataclass(frozen=True)
class Atlas:
    """The circuit classes of one order, ranked: universal, conjectured, undecided, refuted; then
    by neurons and synapses.

    Attributes
    ----------
    order : int
    delays : str
    classes : tuple of CircuitClass
    stats : mapping
        Pattern counts (``patterns``, ``canonical``, ``minimal``, ``full_rank``, ``universal``,
        ``conjectured``, ``undecided``), ``sizes`` searched, ``complete``, ``seconds``,
        ``workers``.

    Examples
    --------
    >>> import symctl
    >>> A = symctl.atlas(2, workers=1)
    >>> A.sparsest().n_neurons, A.stats["complete"]
    (2, True)
    """

    order: int
    delays: str
    classes: tuple
    stats: Mapping = field(compare=False)

    @property
    def universal_classes(self) -> tuple[CircuitClass, ...]:
        """The classes proved to carry almost every order-``n`` G2."""
        return tuple(c for c in self.classes if c.universal)

    @property
    def conjectured_classes(self) -> tuple[CircuitClass, ...]:
        """The classes conjectured universal (witnesses at sampled G2, no proof)."""
        return tuple(c for c in self.classes if c.conjectured)

    def sparsest(self) -> CircuitClass:
        """The universal class with the fewest neurons, then synapses (the first of the atlas)."""
        if not self.universal_classes:
            raise ParameterError(f"atlas: no universal class was found at order {self.order}")
        return self.universal_classes[0]

    def find(self, pattern: Pattern) -> CircuitClass:
        """The class of ``pattern`` (any state permutation of it); ParameterError when not in the atlas."""
        if not isinstance(pattern, Pattern):
            raise SymctlTypeError(f"pattern: expected a Pattern, got {type(pattern).__name__}")
        key = pattern.canonical()
        for c in self.classes:
            if key in c.representatives:
                return c
        raise ParameterError(
            f"pattern: {pattern.text} is not in the order-{self.order} atlas (not generically "
            "minimal, or outside the sizes searched)"
        )

    def table(self) -> list[dict]:
        """One row per class: label, neurons, synapses, branches, patterns, verdict, method."""
        return [
            {
                "class": c.label,
                "neurons": c.n_neurons,
                "synapses": c.n_synapses,
                "branches": c.n_branches,
                "patterns": len(c.representatives),
                "universal": "conjectured"
                if c.conjectured
                else {True: "yes", False: "no", None: "?"}[c.universal],
                "method": c.evidence.method,
                "proved": c.evidence.proved,
            }
            for c in self.classes
        ]

    def to_dict(self) -> dict:
        """Plain data for ``atlas.json``."""
        return {
            "order": self.order,
            "delays": self.delays,
            "stats": dict(self.stats),
            "classes": [c.to_dict() for c in self.classes],
        }

    @classmethod
    def from_dict(cls, data: dict) -> Atlas:
        """The atlas :meth:`to_dict` wrote.

        >>> import symctl
        >>> A = symctl.atlas(2, workers=1)
        >>> type(A).from_dict(A.to_dict()) == A
        True
        """
        delays = data["delays"]
        classes = tuple(CircuitClass.from_dict(c, delays) for c in data["classes"])
        return cls(data["order"], delays, classes, data["stats"])

    def __repr__(self) -> str:
        return (
            f"Atlas(order={self.order}, {len(self.classes)} classes, "
            f"{len(self.universal_classes)} universal, {len(self.conjectured_classes)} "
            f"conjectured, complete={self.stats.get('complete')})"
        )

    def draw(self, *, universal_only: bool = True, columns: int = 3):
        """An overview figure: one circuit per class (the universal ones by default)."""
        from symctl.plotting.atlas import draw_atlas

        return draw_atlas(self, universal_only=universal_only, columns=columns)


def atlas(
    order: int,
    *,
    delays: str = "branch",
    max_size: int | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    checkpoint=None,
    progress: Callable[[int, int, int], None] | None = None,
    max_neurons: int | None = None,
) -> Atlas:
    """Every minimal circuit class of order-``order`` controllers :math:`G_2`, with its evidence.

    Parameters
    ----------
    order : int
        1 to :data:`MAX_ATLAS_ORDER`.
    delays : {"branch", "state"}
        The structure convention of the circuits (:meth:`Structure.from_realization`).
    max_size : int, optional
        Largest pattern size searched (default: all for the exhaustive orders, :math:`3n` above).
    workers : int, optional
        Worker processes (default: every local core; 1 runs in this process).
    scheduler : str, optional
        Address of a running dask.distributed scheduler to use instead of a local cluster.
    checkpoint : path, optional
        A JSON-lines file of finished patterns; a rerun with the same file resumes.
    progress : callable, optional
        Called as ``progress(size, done, total)``.
    max_neurons : int, optional
        Decide only the patterns whose circuit has at most this many neurons (the others are
        counted as skipped); default all, :data:`ORDER4_MAX_NEURONS` for order 4.

    Returns
    -------
    Atlas

    Raises
    ------
    ParameterError
        ``order`` outside 1..4, ``max_size`` or ``max_neurons`` out of range, ``workers`` below
        1, or a scheduler that cannot be reached.

    Examples
    --------
    >>> import symctl
    >>> A = symctl.atlas(1, workers=1)
    >>> [(c.n_neurons, c.universal) for c in A.classes]
    [(2, True), (1, False)]
    """
    n = bounded_int(order, "order", 1, MAX_ATLAS_ORDER)
    if delays not in ("branch", "state"):
        raise ParameterError(f"delays: must be 'branch' or 'state', got {delays!r}")
    low, top = _sizes(n)
    if max_size is not None:
        top = bounded_int(max_size, "max_size", 0, n * n + 2 * n)
    if workers is None:
        workers = 1 if n <= 2 else max(1, os.cpu_count() or 1)
    workers, scheduler = pool_options(workers, scheduler)
    if max_neurons is None and n > EXHAUSTIVE_MAX_ORDER:
        max_neurons = ORDER4_MAX_NEURONS
    if max_neurons is not None:
        max_neurons = bounded_int(max_neurons, "max_neurons", 1, n + 1)
    plain = max_size is None and max_neurons is None and scheduler is None
    if plain and checkpoint is None and progress is None and workers == 1:
        return _cached(n, delays)  # a value: the same search gives the same atlas
    return _search(n, delays, low, top, workers, scheduler, checkpoint, progress, max_neurons)


def _sizes(n: int) -> tuple[int, int]:
    """The pattern sizes searched by default."""
    if n <= EXHAUSTIVE_MAX_ORDER:
        return 0, n * n + 2 * n
    return 3 * n, 3 * n


@functools.lru_cache(maxsize=8)
def _cached(n: int, delays: str) -> Atlas:
    return _search(n, delays, *_sizes(n), 1, None, None, None, None)


def _search(n, delays, low, top, workers, scheduler, checkpoint, progress, max_neurons) -> Atlas:
    slots = n * n + 2 * n
    start = time.perf_counter()
    options = dict(workers=workers, scheduler=scheduler, checkpoint=checkpoint, progress=progress)
    records, counts = run(n, range(low, top + 1), delays, **options, max_neurons=max_neurons)
    classes = _classes(n, delays, records)
    minimal = [r for r in records if r["evidence"]["method"] != "not minimal"]
    status = Counter(Evidence.from_dict(r["evidence"]).status for r in records)
    stats = {
        **counts,
        "minimal": len(minimal),
        "full_rank": sum(r["evidence"]["method"] not in ("rank", "not minimal") for r in records),
        "universal": status["universal"],
        "conjectured": status[CONJECTURED],
        "undecided": status["not decided"],
        "sizes": [low, top],
        "complete": low == 0 and top == slots and not counts["skipped"],
        "max_neurons": max_neurons,
        "seconds": round(time.perf_counter() - start, 2),
        "workers": workers if scheduler is None else scheduler,
    }
    return Atlas(n, delays, classes, MappingProxyType(stats))


def _classes(n: int, delays: str, records: list[dict]) -> tuple[CircuitClass, ...]:
    buckets: dict[str, list[list]] = defaultdict(list)  # hash -> [[graph, records...], ...]
    for rec in records:
        if "graph" not in rec:
            continue
        graph = nx.node_link_graph(rec["graph"], edges="links")
        groups = buckets[circuit_key(graph)]
        for group in groups:
            if same_circuit(group[0], graph):
                group.append(rec)
                break
        else:
            groups.append([graph, rec])
    found = []
    for groups in buckets.values():
        for _graph, *recs in groups:
            ev = {Pattern(n, r["mask"]): Evidence.from_dict(r["evidence"]) for r in recs}
            reps = tuple(
                sorted(ev, key=lambda p: (ev[p].sort_rank, not ev[p].proved, p.size, p.mask))
            )
            counts = tuple(recs[0][k] for k in ("neurons", "synapses", "branches"))
            rank = (ev[reps[0]].sort_rank, *counts, reps[0].size, reps[0].mask)
            found.append((rank, reps, ev, counts))
    found.sort(key=lambda f: f[0])
    return tuple(
        CircuitClass(n, delays, reps, ev[reps[0]], MappingProxyType(ev), *counts, f"A{i + 1}")
        for i, (_, reps, ev, counts) in enumerate(found)
    )
