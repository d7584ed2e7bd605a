"""Dale's law within its ``timeout``: one deadline for the whole call, and every stage stops at it.

Before, ``timeout`` bounded each z3 query only: the paper's muscle at T = 6 (general circuit,
``timeout=5``) took 517 s, in the symbolic equations (180 s), their z3 encoding (30 s) and z3
queries that ran on for up to a minute past their timeout. Each stage is checked here with a
deadline that has already passed, or that passes after a given number of clock readings (a
clock of the test's own, so nothing depends on the machine's speed).
"""

from __future__ import annotations

import functools
import threading

import pytest
import sympy as sp
import z3
from helpers import bounded

import symctl
from symctl import MuscleModel, ParameterError, augment, check_realization, lqr_gains, z
from symctl._util.deadline import Deadline, OutOfTime, Unfinished
from symctl.dalelaw import dale_atlas as dale_atlas_module
from symctl.dalelaw import witness
from symctl.dalelaw.dale import controller_of, poles_of, templates_of
from symctl.dalelaw.signs import (
    Encoding,
    check,
    decide,
    encode,
    full_pattern,
    idle,
    refine,
    template,
)
from symctl.realization.factorization import factor

R = sp.Rational
G_POS = -R(1, 20) / (z**2 + R(1, 2) * z + R(1, 3))


def passes_after(readings: int):
    """A clock at 0 for its first reading (a deadline's start) and ``readings`` more, then at
    10^6: a deadline on it passes after ``readings`` looks."""
    count = [0]

    def clock() -> float:
        count[0] += 1
        return 0.0 if count[0] <= readings + 1 else 1e6

    return clock


@functools.cache
def muscle(delay: int):
    """The paper's muscle with sensor and actuator delay ``delay`` each (T = 2 delay)."""
    gains = lqr_gains(augment(MuscleModel(), delay, delay))
    G, ds, da = controller_of(gains, None, None)
    return gains, G, factor(G, ds, da)


@functools.cache
def general_template(delay: int):
    _, G, fs = muscle(delay)
    return G, templates_of(fs, "general")[1][0]


# ---------------------------------------------------------------- each stage
def test_encoding_the_general_circuit_at_T6_stops_at_a_passed_deadline():
    G, t = general_template(3)
    with pytest.raises(Unfinished, match="out of time"):
        encode(t, poles_of(G), Deadline.passed())


def test_encoding_stops_at_whichever_look_at_the_clock_finds_the_deadline_passed():
    fs = factor(G_POS, 1, 1)
    t = template(fs, full_pattern(2))
    poles = poles_of(fs.G)
    looks = [0]

    def counting() -> float:
        looks[0] += 1
        return 0.0

    encode(t, poles, Deadline(5.0, clock=counting))
    n = looks[0] - 1  # the first reading is the deadline's start
    assert n >= 3  # the minors, each equation, the whole formula
    for k in range(n):
        with pytest.raises(OutOfTime):
            encode(t, poles, Deadline(5.0, clock=passes_after(k)))
    encode(t, poles, Deadline(5.0, clock=passes_after(n)))  # just enough: no error


class Solver:
    """A stand-in for a z3 solver: records its timeouts; ``check`` returns at once or blocks."""

    def __init__(self, answer=z3.unknown, block: bool = False):
        self.answer, self.timeouts, self.calls = answer, [], 0
        self.release, self.block, self.interrupted = threading.Event(), block, False
        self.ctx = self

    def set(self, key, value):
        assert key == "timeout"
        self.timeouts.append(value)

    def check(self, *assume):
        self.calls += 1
        if self.block:
            self.release.wait()
        return self.answer

    def interrupt(self):
        self.interrupted = True


def test_each_z3_call_gets_the_time_left_at_most_its_cap():
    clock = [0.0]
    d = Deadline(10.0, clock=lambda: clock[0])
    enc = Encoding({}, Solver(z3.unsat), {}, {})
    clock[0] = 7.5
    assert check(enc, [], d) == z3.unsat
    assert check(enc, [], d, cap=0.5) == z3.unsat
    assert enc.solver.timeouts == [2500, 500]


def test_decide_asks_z3_nothing_once_the_deadline_has_passed():
    enc = Encoding({}, Solver(z3.sat), {}, {})
    assert decide(enc, deadline=Deadline.passed()) == ("unknown", [])
    assert enc.solver.calls == 0


def test_a_z3_call_that_overruns_is_left_running_and_its_formula_untouched():
    """z3's nonlinear core can run a minute past its timeout: check returns, decide stops."""
    solver = Solver(z3.sat, block=True)
    enc = Encoding({}, solver, {}, {})
    assert check(enc, [], Deadline.passed(), grace=0.01) == z3.unknown
    assert solver.interrupted and len(enc.running) == 1 and enc.running[0].is_alive()
    assert not idle(enc, Deadline.passed())
    assert decide(enc, deadline=Deadline.passed()) == ("unknown", [])
    assert solver.calls == 1  # nothing asked while the first call runs
    solver.release.set()
    assert idle(enc, Deadline(60.0)) and enc.running == []
    solver.block = False
    assert decide(enc, deadline=Deadline(60.0)) == ("sat", [])


def test_refine_stops_at_a_passed_deadline_rather_than_verify_an_algebraic_value():
    ctx = z3.Context()
    x = sp.Symbol("x")
    X = z3.Real("x", ctx)
    solver = z3.SolverFor("QF_NRA", ctx=ctx)
    solver.add(X * X == 2, X > 0)
    enc = Encoding({x: X}, solver, {}, {})
    assert solver.check() == z3.sat
    with pytest.raises(Unfinished, match="pinning the witness's x to a rational: out of time"):
        refine(enc, [x], deadline=Deadline.passed())
    values = refine(enc, [x], deadline=Deadline(60.0))["values"]  # no rational fits: sqrt(2)
    assert sp.simplify(values[x] - sp.sqrt(2)) == 0


def test_the_numeric_search_stops_inside_a_run_when_the_deadline_passes(monkeypatch):
    runs = []
    real = witness.minimize

    def spy(*args, **kwargs):
        runs.append(real(*args, **kwargs))
        return runs[-1]

    monkeypatch.setattr(witness, "minimize", spy)
    fs = factor(G_POS, 1, 1)
    t = template(fs, "general")
    assert witness.search_general(fs.G, t, deadline=Deadline.passed()) is None
    assert runs == []
    found = witness.search_general(fs.G, t, deadline=Deadline(60.0, clock=passes_after(20)))
    assert found is None and len(runs) == 1
    assert runs[0].nit <= 21 and "StopIteration" in runs[0].message  # 400 * 6 allowed


# ---------------------------------------------------------------- whole calls
@pytest.mark.parametrize("circuit", ["general", "controllable", "observable"])
def test_dale_with_a_passed_deadline_is_not_decided_and_says_why(circuit):
    r = symctl.dale(
        G_POS,
        sensor_delay=1,
        actuator_delay=1,
        circuit=circuit,
        timeout=Deadline(5.0, clock=passes_after(0)),
    )
    assert r.feasible is None and r.witness is None and r.realization is None
    assert "not decided within timeout = 5 s" in r.reason and "out of time" in r.reason


@pytest.mark.parametrize("readings", [2, 5, 10, 20, 40, 80, 160])
@pytest.mark.parametrize("circuit", ["controllable", "observable"])
def test_dale_whenever_the_deadline_passes_is_not_decided_or_exact(circuit, readings):
    """Cut at any point, a call returns: "not decided", or a verdict with its evidence."""
    r = symctl.dale(
        G_POS,
        sensor_delay=1,
        actuator_delay=1,
        circuit=circuit,
        timeout=Deadline(5.0, clock=passes_after(readings)),
    )
    want = {"controllable": True, "observable": False}[circuit]
    assert r.feasible in (None, want)
    if r.feasible is None:
        assert "not decided" in r.reason
    elif r.feasible:
        assert check_realization(r.realization, G_POS, method="exact").ok
    else:
        assert "unsat" in r.reason


def test_dale_T6_general_circuit_stops_at_its_timeout():
    """The paper's muscle at T = 6 took 517 s with timeout=5; now it is not decided in time.

    The deadline passes after 20 looks at its clock (the real clock would make the
    work depend on the machine's load), and the work until the verdict is counted:
    about half a million calls, where deciding the circuit runs for minutes.
    """
    gains, _, _ = muscle(3)
    with bounded(10_000_000):
        r = symctl.dale(gains, circuit="general", timeout=Deadline(2.0, clock=passes_after(20)))
    assert r.feasible is None and r.realizes is None
    assert r.reason.startswith("not decided within timeout = 2 s")


def test_dale_refuses_the_general_circuit_beyond_the_largest_pattern():
    G = R(1, 10) / (z - R(1, 2)) ** 7
    with pytest.raises(ParameterError, match=r"^circuit: the general circuit is decided up to"):
        symctl.dale(G, sensor_delay=0, actuator_delay=0, circuit="general", timeout=1)


def test_ei_circuit_with_a_passed_deadline_decides_nothing():
    with pytest.raises(ParameterError, match="none was decided within the timeout"):
        symctl.ei_circuit(
            G_POS,
            sensor_delay=1,
            actuator_delay=1,
            circuits=["controllable", "observable"],
            timeout=Deadline(5.0, clock=passes_after(0)),
        )


def test_dale_atlas_gives_each_search_its_deadline(monkeypatch):
    made = []

    def passed(seconds):
        made.append(seconds)
        return Deadline(seconds, clock=passes_after(0))

    monkeypatch.setattr(dale_atlas_module, "Deadline", passed)
    T = symctl.dale_atlas(2, samples=2, classes=["A1"], timeout=4)
    (row,) = T.rows
    assert row.verdict is None and row.sampled == (0, 0, 0, 2) and row.exists == "unknown"
    assert made == [4, 4, 12]  # two samples, then the generic controller (three times)
