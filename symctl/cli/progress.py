"""The commands' live progress (a spinner with the running step, what it does, its time), drawn
only on a terminal and transient: ``--json`` output, pipes and logs are as without it."""

from __future__ import annotations

import contextlib
import time

from rich.console import Console
from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

__all__ = ["Steps", "say"]


class Steps:
    """A run's steps on ``console``: :meth:`start` a step, :meth:`part` says what it is doing.

    With ``lines``, each finished step prints ``done <step> <seconds> s`` and the run a total."""

    def __init__(self, console: Console, *, lines: bool = False) -> None:
        self._console, self._lines = console, lines
        self._bar = Progress(
            SpinnerColumn(),
            TextColumn("{task.description}"),
            TimeElapsedColumn(),
            console=console,
            transient=True,
            disable=not console.is_terminal,
        )
        self._task = self._bar.add_task("starting", total=None)
        self._name: str | None = None
        self._t0 = self._start = 0.0

    def __enter__(self) -> Steps:
        self._start = time.perf_counter()
        self._bar.__enter__()
        return self

    def start(self, name: str) -> None:
        """A new step, ``name``, starts (the one before it is done)."""
        self._done()
        self._name, self._t0 = name, time.perf_counter()
        self._bar.reset(self._task, total=None, description=f"{name} ...")
        self._bar.refresh()

    def part(self, text: str) -> None:
        """The running step is now doing ``text`` (a figure's name, a stage, a circuit)."""
        self._bar.update(self._task, description=f"{self._name}: {text} ...", refresh=True)

    def _done(self) -> None:
        if self._name is not None and self._lines:
            took = time.perf_counter() - self._t0
            self._say(f"  done  {self._name:<14} {took:6.2f} s")
        self._name = None

    def _say(self, text: str) -> None:
        self._console.print(text, markup=False, highlight=False)

    def __exit__(self, exc_type, exc, tb) -> None:
        if exc is not None and self._name is not None:
            with contextlib.suppress(AttributeError):
                exc._symctl_step = self._name  # for main's message on a foreign exception
        if exc_type is None:
            self._done()
            if self._lines:
                self._say(f"  total {'':<14} {time.perf_counter() - self._start:6.2f} s")
        self._bar.__exit__(exc_type, exc, tb)


def say(console: Console, text: str) -> None:
    """Print ``text`` as it is: no markup, no highlighting, long lines unbroken."""
    console.print(text, markup=False, soft_wrap=True, highlight=False)
