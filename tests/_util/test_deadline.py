"""The one deadline of a search: its own clock, sub-deadlines that never outlast it, the stage named."""

from __future__ import annotations

import math
import time

import pytest

from symctl import ParameterError, SymctlError
from symctl._util.deadline import Deadline, OutOfTime, Unfinished, deadline_of


class Clock:
    """A clock that reads ``now`` (seconds), set by the test."""

    def __init__(self, now: float = 0.0):
        self.now = now

    def __call__(self) -> float:
        return self.now


def test_deadline_counts_down_on_its_own_clock():
    clock = Clock(100.0)
    d = Deadline(5.0, clock=clock)
    assert (d.start, d.at, d.left(), d.expired()) == (100.0, 105.0, 5.0, False)
    clock.now = 103.5
    assert (d.left(), d.elapsed(), d.expired()) == (1.5, 3.5, False)
    clock.now = 105.0
    assert d.left() == 0.0 and d.expired()
    clock.now = 110.0
    assert d.left() == 0.0 and d.elapsed() == 10.0


def test_check_passes_before_and_names_the_stage_after():
    clock = Clock()
    d = Deadline(2.0, clock=clock)
    d.check("building the equations")  # nothing raised: time is left
    clock.now = 2.0
    with pytest.raises(OutOfTime, match=r"^building the equations: out of time \(2 s\)$") as info:
        d.check("building the equations")
    assert info.value.stage == "building the equations" and info.value.seconds == 2.0
    assert isinstance(info.value, Unfinished)


def test_within_is_a_sub_deadline_that_never_outlasts_its_parent():
    clock = Clock()
    d = Deadline(10.0, clock=clock)
    clock.now = 4.0
    short, long = d.within(3.0), d.within(30.0)
    assert (short.left(), long.left()) == (3.0, 6.0)
    assert short.clock is clock and long.at == d.at
    clock.now = 7.0
    assert short.expired() and not d.expired()
    clock.now = 20.0
    assert d.within(5.0).expired()  # a passed deadline gives passed sub-deadlines


def test_passed_is_expired_at_once():
    d = Deadline.passed()
    assert d.expired() and d.left() == 0.0
    with pytest.raises(OutOfTime):
        d.check("any stage")


def test_deadline_of_takes_seconds_or_a_running_deadline():
    shared = Deadline(60.0)
    assert deadline_of(shared) is shared
    d = deadline_of(2.5)  # a fresh deadline on the real clock, 2.5 s from its start
    assert d.seconds == 2.5 and d.clock is time.perf_counter and d.at == d.start + 2.5
    assert d.left() <= 2.5


@pytest.mark.parametrize("bad", [0, -1, 1e-4, 3601, math.nan, math.inf, True, "5", None])
def test_deadline_of_refuses_a_bad_timeout_naming_it(bad):
    with pytest.raises(SymctlError, match=r"^timeout"):
        deadline_of(bad)


def test_deadline_of_names_the_callers_argument_and_limit():
    with pytest.raises(ParameterError, match=r"^budget: must be a number in \[0.001, 10\]"):
        deadline_of(11, "budget", 10.0)
