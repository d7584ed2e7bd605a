"""The processes that draw the report's figures, started before the derivation they draw (so that
they import matplotlib and cut the house style's fonts while the parent derives). A worker runs
the task it is given: the module knows nothing of figures."""

from __future__ import annotations

import contextlib
import functools
import gc
import multiprocessing
import os
import signal
import sys
import threading
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

from symctl._util.validate import positive_int
from symctl.errors import SymctlError

__all__ = ["FigureWorkers"]


class FigureWorkers:
    """``jobs`` processes (default the CPUs, at most 4) that draw the report's figures.

    Entering forks them (a :class:`~concurrent.futures.ProcessPoolExecutor`), and they get ready while
    the caller goes on; :meth:`submit` hands them a value (pickled once to a file) and the names to
    draw from it. With ``jobs=1``, or without ``fork``, the tasks run here. When anything stops the
    work (an error, a worker that died, a signal) every worker is stopped (SIGTERM, then SIGKILL
    after a second) and reaped before the exception goes on; the workers ignore SIGINT and, on
    Linux, die with the parent."""

    def __init__(self, jobs: int | None = None) -> None:
        self.jobs = min(4, os.cpu_count() or 1) if jobs is None else positive_int(jobs, "jobs")
        self._pool: ProcessPoolExecutor | None = None
        self._before: set = set()
        self._saved: list = []  # the values handed to the workers (temporary files)

    def __enter__(self) -> FigureWorkers:
        if self.jobs == 1 or "fork" not in multiprocessing.get_all_start_methods():
            return self
        self._before = set(multiprocessing.active_children())
        # the workers' garbage collections skip the objects they inherit (and copy no pages of them)
        frozen = gc.get_freeze_count() == 0  # not when the caller froze objects of its own
        if frozen:
            gc.freeze()
        try:
            with _signals_after():
                self._pool = ProcessPoolExecutor(
                    self.jobs,
                    mp_context=multiprocessing.get_context("fork"),
                    initializer=_worker_init,
                )
                for _ in range(self.jobs):  # forks every worker now, each getting ready
                    self._pool.submit(_warm)
        except BaseException:
            self.__exit__(*sys.exc_info())
            raise
        finally:
            if frozen:
                gc.unfreeze()
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        if self._pool is None:
            return
        if exc_type is not None:
            self._stop()
        self._pool.shutdown(wait=exc_type is None, cancel_futures=True)
        self._pool = None
        for saved in self._saved:  # also those of work never waited for (the caller failed)
            saved.close()
        self._saved.clear()

    def _stop(self) -> None:
        """SIGTERM, then SIGKILL to any worker still running after a second; reaped."""
        workers = [p for p in multiprocessing.active_children() if p not in self._before]
        for worker in workers:
            worker.terminate()
        for worker in workers:
            worker.join(1.0)
            if worker.is_alive():
                worker.kill()
                worker.join()

    def map(self, task, res, names) -> dict:
        """``{name: task(res, name)}`` for every name, in the workers (:meth:`submit`, waited)."""
        return self.submit(task, res, names)()

    def submit(self, task, res, names):
        """Start ``task(res, name)`` for every name (``task`` of module level, ``res`` picklable);
        returns a function ``result(progress=None)`` that waits and gives ``{name: value}``."""
        if self._pool is None:
            return functools.partial(_run_here, task, res, names)
        import pickle
        import tempfile

        saved = tempfile.NamedTemporaryFile(prefix="symctl-figures-", suffix=".pickle")
        self._saved.append(saved)
        pickle.dump(res, saved, protocol=pickle.HIGHEST_PROTOCOL)
        saved.flush()
        futures = {self._pool.submit(_worker, task, saved.name, n): n for n in names}

        def result(progress=None) -> dict:
            try:
                for future in as_completed(futures):
                    future.result()  # the first exception stops every worker
                    if progress:
                        progress(futures[future])
                return {name: future.result() for future, name in futures.items()}
            except BaseException as exc:
                self._stop()
                if isinstance(exc, BrokenProcessPool):
                    raise SymctlError(
                        "a figure worker died (killed by a signal or out of memory)"
                    ) from None
                raise
            finally:
                saved.close()

        return result


def _run_here(task, res, names, progress=None) -> dict:
    """The tasks of :meth:`FigureWorkers.submit` run here, one by one."""
    done = {}
    for name in names:
        done[name] = task(res, name)
        if progress:
            progress(name)
    return done


_STOPS = (signal.SIGINT, signal.SIGTERM)


@contextlib.contextmanager
def _signals_after():
    """Ctrl-C and SIGTERM noted while the block runs and acted on when it ends (an exception raised
    in a fork's own hooks is printed and ignored: the signal would be lost)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    noted: list[int] = []
    previous = {
        sig: signal.signal(sig, lambda signum, _frame: noted.append(signum)) for sig in _STOPS
    }
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        for sig in dict.fromkeys(noted):
            signal.raise_signal(sig)  # the previous handler acts now


def _worker_init() -> None:
    """Ctrl-C is the parent's to handle, SIGTERM kills, and so does the parent's death."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the terminal sends it to the whole group
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # not the parent's handler, inherited by fork
    try:  # Linux: die with the parent even when it is killed outright (no orphans)
        import ctypes

        pr_set_pdeathsig = 1
        ctypes.CDLL(None, use_errno=True).prctl(pr_set_pdeathsig, signal.SIGKILL)
    except (OSError, AttributeError):  # pragma: no cover - not Linux
        pass


def _warm() -> None:
    """Get a worker ready: a small figure with typeset text drawn as PDF and PNG."""
    import tempfile

    from symctl.plotting.png import render_pdf
    from symctl.plotting.style import axis_label, new_figure
    from symctl.plotting.vector import write_vector

    fig = new_figure("column", 1.0)
    fig.add_subplot().set_xlabel(axis_label("$x_{1}$ and $\\epsilon$", "s"))
    with tempfile.TemporaryDirectory() as out:
        render_pdf(write_vector(fig, Path(out) / "warm.pdf"), Path(out) / "warm.png", dpi=50)


_LOADED: dict = {}  # the value a worker has read: {file: value}


def _worker(task, saved: str, name: str):
    if saved not in _LOADED:
        import pickle

        _LOADED.clear()
        with open(saved, "rb") as file:
            _LOADED[saved] = pickle.load(file)
    return task(_LOADED[saved], name)
