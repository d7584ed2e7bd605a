r"""One deadline for a whole computation, handed down: every stage asks it how long is left.

The clock is a parameter, so a test can run out of time without waiting.

>>> from symctl._util.deadline import Deadline
>>> ticks = iter(range(100))
>>> d = Deadline(2.5, clock=lambda: next(ticks))   # started at tick 0
>>> d.left(), d.expired(), d.expired()             # ticks 1, 2 and 3
(1.5, False, True)
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

from symctl._util.validate import bounded_number


class Unfinished(Exception):
    """A stage stopped before its end: out of time, or past a size limit (the caller reports
    "not decided" with the message)."""


class OutOfTime(Unfinished):
    """A stage found its :class:`Deadline` passed; ``stage`` says which."""

    def __init__(self, stage: str, seconds: float):
        self.stage, self.seconds = stage, seconds
        super().__init__(f"{stage}: out of time ({seconds:g} s)")


@dataclass(frozen=True)
class Deadline:
    """``seconds`` from its creation (``start``) on ``clock`` (default :func:`time.perf_counter`)."""

    seconds: float
    clock: Callable[[], float] = field(default=time.perf_counter, repr=False, compare=False)
    start: float | None = None

    def __post_init__(self) -> None:
        if self.start is None:
            object.__setattr__(self, "start", self.clock())

    @classmethod
    def passed(cls) -> Deadline:
        """A deadline that has already passed (every stage stops at once)."""
        return cls(0.0)

    @property
    def at(self) -> float:
        """The clock's reading when the time runs out."""
        return self.start + self.seconds

    def left(self) -> float:
        """Seconds left (0 once passed)."""
        return max(0.0, self.at - self.clock())

    def expired(self) -> bool:
        """The time has run out."""
        return self.left() <= 0.0

    def elapsed(self) -> float:
        """Seconds since the start."""
        return self.clock() - self.start

    def check(self, stage: str) -> None:
        """Raise :class:`OutOfTime` naming ``stage`` when the time has run out."""
        if self.expired():
            raise OutOfTime(stage, self.seconds)

    def within(self, seconds: float) -> Deadline:
        """A deadline at most ``seconds`` from now and never after this one (same clock)."""
        now = self.clock()
        return Deadline(max(0.0, min(seconds, self.at - now)), self.clock, now)


def deadline_of(timeout, argname: str = "timeout", high: float = 3600.0) -> Deadline:
    """``timeout`` as a :class:`Deadline`: seconds from now (in ``[0.001, high]``), or itself."""
    if isinstance(timeout, Deadline):
        return timeout
    return Deadline(bounded_number(timeout, argname, 1e-3, high))
