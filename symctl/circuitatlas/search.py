r"""The pattern search behind :func:`symctl.atlas`: enumeration, workers, checkpoints.

Patterns are enumerated size by size (:func:`canonical_masks`, one per
state-permutation orbit, vectorized in NumPy). Within a size the patterns are
independent, so they go out in chunks to workers: in this process for
``workers=1``, otherwise to a dask.distributed cluster (an existing one at
``scheduler``, or a ``LocalCluster`` with one single-threaded process per
core). Between sizes the search waits, because a pattern of size
:math:`k + 1` is decided by lifting from the universal patterns of size
:math:`\le k`.

Every finished chunk is appended to a checkpoint file (JSON lines) when one
is given; a later run with the same file skips the patterns already done, so
an interrupted search resumes.

>>> from symctl.circuitatlas.search import canonical_masks
>>> len(canonical_masks(2, 6)), len(canonical_masks(3, 9))
(16, 870)
"""

from __future__ import annotations

import itertools
import json
import os
from collections.abc import Callable
from pathlib import Path

import numpy as np

from symctl._util.validate import bounded_int
from symctl.circuitatlas.pattern import Pattern, _permutation_maps, orbit_size
from symctl.errors import ParameterError, SymctlTypeError

__all__ = ["CHUNK", "MAX_WORKERS", "canonical_masks", "open_pool", "pool_options", "run"]

CHUNK = 64
"""Patterns per task sent to a worker."""

FORMAT = 3
"""Version of the checkpoint format (3: the exact screen decides patterns of 3n entries)."""

MAX_WORKERS = 512
"""Most worker processes one search may ask for."""


def canonical_masks(n: int, size: int) -> list[int]:
    """The canonical masks (smallest in their state-permutation orbit) of ``size`` nonzero slots."""
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


class _Checkpoint:
    def __init__(self, path, header: dict):
        self.path = None if path is None else Path(path)
        self.done: dict[int, dict] = {}
        if self.path is None:
            return
        try:
            self._open(header)
        except OSError as exc:
            raise ParameterError(
                f"checkpoint: cannot use {self.path}: {exc.strerror or exc}"
            ) from None

    def _open(self, header: dict) -> None:
        if self.path.exists():
            lines = self.path.read_text().splitlines()
            try:
                first = json.loads(lines[0]) if lines else None
            except json.JSONDecodeError:
                first = None
            if first != header:
                raise ParameterError(
                    f"checkpoint: {self.path} belongs to another search ({first}); remove it "
                    "or choose another file"
                )
            slots = header["order"] ** 2 + 2 * header["order"]
            for line in lines[1:]:
                try:
                    records = json.loads(line)
                except json.JSONDecodeError:
                    break  # a line cut by the interruption: redo from there
                if not isinstance(records, list) or not all(_valid(r, slots) for r in records):
                    break  # not a record this search wrote: redo from there
                for rec in records:
                    self.done[rec["mask"]] = rec
        else:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self.path.write_text(json.dumps(header) + "\n")

    def add(self, records: list[dict]) -> None:
        for rec in records:
            self.done[rec["mask"]] = rec
        if self.path is not None:
            with self.path.open("a") as fh:
                fh.write(json.dumps(records) + "\n")
                fh.flush()
                os.fsync(fh.fileno())


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


class _Local:
    def map(self, fn, chunks):
        for chunk in chunks:
            yield fn(*chunk)

    def close(self):
        pass


class _Dask:
    def __init__(self, scheduler: str | None, workers: int):
        try:
            from distributed import Client, LocalCluster
        except ImportError as exc:  # pragma: no cover - a dependency
            raise ParameterError(f"workers: dask.distributed is not installed ({exc})") from None
        self.cluster = None
        if scheduler is None:
            self.cluster = LocalCluster(
                n_workers=workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address=":0",
                silence_logs=40,
            )
            self.client = Client(self.cluster)
        else:
            try:
                self.client = Client(scheduler, timeout="5s")
            except (OSError, ValueError, TypeError) as exc:  # refused, timed out, malformed
                raise ParameterError(f"scheduler: cannot connect to {scheduler!r}: {exc}") from None

    def map(self, fn, chunks):
        from distributed import as_completed

        futures = [self.client.submit(fn, *chunk, pure=False) for chunk in chunks]
        for future in as_completed(futures):
            yield future.result()

    def close(self):
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def pool_options(workers, scheduler) -> tuple[int, str | None]:
    """``workers`` and ``scheduler`` checked as the dask path takes them."""
    workers = bounded_int(workers, "workers", 1, MAX_WORKERS)
    if scheduler is not None and not isinstance(scheduler, str):
        raise SymctlTypeError(f"scheduler: expected an address string, got {scheduler!r}")
    return workers, scheduler


def open_pool(workers, scheduler):
    """This process (one worker, no scheduler) or a dask cluster, with ``map`` and ``close``."""
    workers, scheduler = pool_options(workers, scheduler)
    return _Local() if workers == 1 and scheduler is None else _Dask(scheduler, workers)


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
    """Decide every canonical pattern of the given sizes; return the records and counts.

    With ``max_neurons``, patterns whose circuit has more neurons are counted
    (``skipped``) but not decided.
    """
    from symctl.circuitatlas.universality import CONJECTURED

    header = {"format": FORMAT, "order": n, "delays": delays, "max_neurons": max_neurons}
    pool = open_pool(workers, scheduler)
    try:
        store = _Checkpoint(checkpoint, header)  # after the cluster: a bad address writes nothing
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
