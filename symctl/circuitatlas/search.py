"""The pattern search behind :func:`symctl.atlas`: enumeration, workers, checkpoints.

Patterns go size by size (a pattern of size :math:`k + 1` is decided by lifting from the
universal ones below), one per state-permutation orbit, in chunks to :mod:`symctl._util.pool`'s
workers, each finished chunk appended to the checkpoint.

>>> from symctl.circuitatlas.search import canonical_masks
>>> len(canonical_masks(2, 6)), len(canonical_masks(3, 9))
(16, 870)
"""

from __future__ import annotations

import itertools
from collections.abc import Callable

import numpy as np

from symctl._util.pool import MAX_WORKERS, Checkpoint, open_pool, pool_options
from symctl.circuitatlas.pattern import Pattern, _permutation_maps, orbit_size
from symctl.errors import ParameterError

__all__ = ["CHUNK", "MAX_WORKERS", "canonical_masks", "open_pool", "pool_options", "run"]

CHUNK = 64  # patterns per task sent to a worker

FORMAT = 3  # version of the checkpoint format (3: the exact screen decides patterns of 3n entries)


def canonical_masks(n: int, size: int) -> list[int]:
    """The canonical masks (smallest in their orbit) of ``size`` nonzero slots (vectorized)."""
    slots = n * n + 2 * n
    if not 0 <= size <= slots:
        raise ParameterError(f"size: must be between 0 and {slots}, got {size}")
    out = []
    maps = _permutation_maps(n)
    combos = itertools.combinations(range(slots), size)
    weights = np.array([1 << k for k in range(slots)], dtype=np.int64)
    while True:
        block = list(itertools.islice(combos, 200_000))
        if not block:
            break
        idx = np.array(block, dtype=np.int64).reshape(len(block), size)
        masks = weights[idx].sum(axis=1) if size else np.zeros(len(block), dtype=np.int64)
        keep = np.ones(len(masks), dtype=bool)
        for image in maps[1:]:
            perm = np.zeros_like(masks)
            for k, target in enumerate(image):
                perm |= ((masks >> k) & 1) << target
            keep &= perm >= masks
        out.extend(int(m) for m in masks[keep])
    return out


def _evaluate(n: int, masks: list[int], delays: str, lifted: list) -> list[dict]:
    """Decide each pattern and read off its circuit (runs in a worker)."""
    import networkx as nx

    from symctl.circuitatlas.circuitclass import circuit_graph, circuit_of
    from symctl.circuitatlas.odddegree import proving
    from symctl.circuitatlas.universality import Evidence, decide

    below = [(Pattern(n, m), Evidence.from_dict(e)) for m, e in lifted]
    out = []
    with proving():  # one proving child for the chunk, stopped at its end
        for mask in masks:
            p = Pattern(n, mask)
            ev = decide(p, below)
            rec = {"mask": mask, "evidence": ev.to_dict()}
            if ev.method != "not minimal":
                circuit = circuit_of(p, delays)
                graph = circuit_graph(circuit)
                rec.update(
                    neurons=circuit.n_neurons,
                    synapses=len(circuit.synapses),
                    branches=sum(circuit.branches().values()),
                    graph=nx.node_link_data(graph, edges="links"),
                )
            out.append(rec)
    return out


_EVIDENCE_KEYS = {"universal": (bool, type(None)), "method": str, "proved": bool, "text": str}


def _valid(rec, slots: int) -> bool:
    """A checkpoint record as _evaluate writes it (the file may have been edited or cut)."""
    if not isinstance(rec, dict):
        return False
    mask, ev = rec.get("mask"), rec.get("evidence")
    if isinstance(mask, bool) or not isinstance(mask, int) or not 0 <= mask < 1 << slots:
        return False
    if not isinstance(ev, dict) or not isinstance(ev.get("details", {}), dict):
        return False
    if not all(isinstance(ev.get(k), t) for k, t in _EVIDENCE_KEYS.items()):
        return False
    if "graph" in rec:
        counts = [rec.get(k) for k in ("neurons", "synapses", "branches")]
        if not all(isinstance(c, int) and c >= 0 for c in counts):
            return False
        if not isinstance(rec["graph"], dict) or not isinstance(rec["graph"].get("links"), list):
            return False
    return True


def run(
    n: int,
    sizes,
    delays: str,
    *,
    workers: int,
    scheduler: str | None,
    checkpoint=None,
    progress: Callable[[int, int, int], None] | None = None,
    max_neurons: int | None = None,
) -> tuple[list[dict], dict]:
    """The records and counts of every canonical pattern of ``sizes`` (those above
    ``max_neurons`` counted as ``skipped``)."""
    from symctl.circuitatlas.universality import CONJECTURED

    header = {"format": FORMAT, "order": n, "delays": delays, "max_neurons": max_neurons}
    pool = open_pool(workers, scheduler)
    try:
        slots = n * n + 2 * n
        store = Checkpoint(  # after the cluster: a bad address writes nothing
            checkpoint, header, lambda rec: rec["mask"], lambda rec: _valid(rec, slots)
        )
    except BaseException:
        pool.close()
        raise
    counts = {"patterns": 0, "canonical": 0, "resumed": 0, "skipped": 0}
    records: list[dict] = []
    try:
        for size in sizes:
            masks = canonical_masks(n, size)
            counts["canonical"] += len(masks)
            counts["patterns"] += sum(orbit_size(n, m) for m in masks)
            if max_neurons is not None:
                kept = [m for m in masks if Pattern(n, m).n_neurons <= max_neurons]
                counts["skipped"] += len(masks) - len(kept)
                masks = kept
            lifted = [
                (r["mask"], r["evidence"])
                for r in records
                if r["evidence"]["universal"] or r["evidence"]["method"] == CONJECTURED
            ]
            todo = [m for m in masks if m not in store.done]
            counts["resumed"] += len(masks) - len(todo)
            chunks = [(n, todo[i : i + CHUNK], delays, lifted) for i in range(0, len(todo), CHUNK)]
            done = len(masks) - len(todo)
            if progress:
                progress(size, done, len(masks))
            for result in pool.map(_evaluate, chunks):
                store.add(result)
                done += len(result)
                if progress:
                    progress(size, done, len(masks))
            records.extend(store.done[m] for m in masks)
    finally:
        pool.close()
    return records, counts
