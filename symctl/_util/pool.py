"""The dask path of every long sweep: workers here or on a dask cluster, and a JSON-lines
checkpoint from which an interrupted sweep resumes."""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path

from symctl._util.validate import bounded_int
from symctl.errors import ParameterError, SymctlTypeError

MAX_WORKERS = 512  # most worker processes one sweep may ask for


class Checkpoint:
    """The records of a sweep by ``key(record)``, in the JSON-lines file ``path`` (or none) whose
    first line is ``header``; reading stops (and cuts the file) at a line cut or not ``valid``."""

    def __init__(self, path, header: dict, key: Callable, valid: Callable[[object], bool]):
        self.path = None if path is None else Path(path)
        self.key, self.valid = key, valid
        self.done: dict = {}
        if self.path is None:
            return
        try:
            self._open(header)
        except OSError as exc:
            raise ParameterError(
                f"checkpoint: cannot use {self.path}: {exc.strerror or exc}"
            ) from None

    def _open(self, header: dict) -> None:
        if not self.path.exists():
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self.path.write_text(json.dumps(header) + "\n")
            return
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
        kept = 1
        for line in lines[1:]:
            try:
                records = json.loads(line)
            except json.JSONDecodeError:
                break  # a line cut by the interruption: redo from there
            if not isinstance(records, list) or not all(self.valid(r) for r in records):
                break  # not a record this sweep wrote: redo from there
            for rec in records:
                self.done[self.key(rec)] = rec
            kept += 1
        if kept < len(lines):  # drop the rest, so that new records follow the good ones
            self.path.write_text("".join(line + "\n" for line in lines[:kept]))

    def add(self, records: list) -> None:
        """Keep ``records`` and append them to the file, flushed to disk."""
        for rec in records:
            self.done[self.key(rec)] = rec
        if self.path is not None:
            with self.path.open("a") as fh:
                fh.write(json.dumps(records) + "\n")
                fh.flush()
                os.fsync(fh.fileno())


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
    """``workers`` and ``scheduler``, checked."""
    workers = bounded_int(workers, "workers", 1, MAX_WORKERS)
    if scheduler is not None and not isinstance(scheduler, str):
        raise SymctlTypeError(f"scheduler: expected an address string, got {scheduler!r}")
    return workers, scheduler


def open_pool(workers, scheduler):
    """This process (one worker, no scheduler) or a dask cluster, with ``map`` and ``close``."""
    workers, scheduler = pool_options(workers, scheduler)
    return _Local() if workers == 1 and scheduler is None else _Dask(scheduler, workers)
