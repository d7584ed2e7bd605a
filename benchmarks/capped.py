"""Run a baseline in a subprocess with a time cap (shared by the benchmark scripts)."""

from __future__ import annotations

import multiprocessing as mp
import time


def _worker(job, args, queue) -> None:
    start = time.perf_counter()
    result = job(*args)
    queue.put((time.perf_counter() - start, result))


def capped(job, args: tuple, cap: float) -> tuple[float, object] | None:
    """``(seconds, result)`` of ``job(*args)`` run in a subprocess, or None past ``cap`` seconds."""
    queue = mp.Queue()
    proc = mp.Process(target=_worker, args=(job, args, queue))
    proc.start()
    proc.join(cap)
    if proc.is_alive():
        proc.terminate()
        proc.join()
        return None
    return queue.get()
