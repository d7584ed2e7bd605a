"""Helpers shared by the tests (importable thanks to ``pythonpath = tests``)."""

from __future__ import annotations

import os
from contextlib import contextmanager

import numpy as np

from symctl import Block, DelayGraph, ParameterError, Structure


def examples(n: int) -> int:
    """``n`` hypothesis examples in the full tier (``SYMCTL_EXAMPLES`` 40), scaled down with it in
    the fast tier (``make test``: 10, a quarter)."""
    return max(1, n * int(os.environ.get("SYMCTL_EXAMPLES", "40")) // 40)


def random_plant(rng: np.random.Generator, n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """A random plant, controllable with probability one."""
    A = rng.normal(size=(n, n)) / np.sqrt(n)
    B = rng.normal(size=(n, m))
    return A, B


def paper_assignment(S) -> dict[str, int]:
    """The paper's assignment for G3 G2 G1: x and alpha1 (= C1 x) at v1, G2 at v2, G3's output at v3."""
    vertex = {}
    for name, block in S.blocks.items():
        if name in S.inputs or name == "G1.H":
            vertex[name] = 1
        elif block.part == "G3" and name != "G3.H":
            vertex[name] = 3
        else:
            vertex[name] = 2
    return vertex


def rel_err(a: np.ndarray, b: np.ndarray) -> float:
    """``max |a - b| / max |b|``."""
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def random_structure(rng, max_signals: int = 7, max_steps: int = 1) -> Structure:
    """A random well-posed SISO structure with up to ``max_signals`` signals besides u.

    Delay blocks delay by 1 .. ``max_steps`` steps.
    """
    while True:
        k = int(rng.integers(1, max_signals))
        names = ["u"] + [f"s{i}" for i in range(1, k + 1)]
        kinds = ["input"] + [
            str(rng.choice(["gain", "sum", "delay"], p=[0.35, 0.3, 0.35])) for _ in range(k)
        ]
        delays = [names[j] for j in range(1, k + 1) if kinds[j] == "delay"]
        blocks = {"u": Block("input")}
        for i in range(1, k + 1):
            pool = names[:i] + [d for d in delays if d != names[i] or kinds[i] == "delay"]
            if kinds[i] in ("gain", "delay"):
                ins = (str(rng.choice(pool)),)
            else:
                ins = tuple(dict.fromkeys(str(rng.choice(pool)) for _ in range(rng.integers(4))))
            steps = 1
            if kinds[i] == "delay" and max_steps > 1:
                steps = int(rng.integers(1, max_steps + 1))
            blocks[names[i]] = Block(kinds[i], ins, 2 if kinds[i] == "gain" else None, "", steps)
        out = str(rng.choice(names[1:])) if rng.random() > 0.03 else "u"
        try:
            return Structure(blocks, "u", out)
        except ParameterError:  # an algebraic loop: draw again
            continue


def random_graph(rng, chain: bool) -> DelayGraph:
    n = int(rng.integers(2, 5))
    if chain:
        return DelayGraph.chain([int(d) for d in rng.integers(0, 3, n - 1)])
    while True:
        edges = [
            (i, j, int(rng.integers(0, 3)))
            for i in range(1, n + 1)
            for j in range(1, n + 1)
            if i != j and rng.random() < 0.4
        ]
        try:
            return DelayGraph.from_edges(n, edges)
        except ParameterError:  # no source or no sink: draw again
            continue


CALLS = 2_000_000


class OverBudget(AssertionError):
    """The block made more function calls than its budget: unbounded or needless work."""


class WorkCount:
    """The function calls counted so far (Python and C calls), read after the block."""

    calls = 0


@contextmanager
def bounded(calls: int = CALLS):
    """Fail (instead of running on) when the block makes more than ``calls`` function calls.

    Work is counted, not timed: a profile hook counts every Python and C call made in
    the block, and raises :class:`OverBudget` at the first call over the budget, so an
    endless or needless computation fails at once and the verdict is the same on an idle
    machine and on a loaded one. Yields a :class:`WorkCount` holding the count.
    """
    import sys

    count = WorkCount()
    previous = sys.getprofile()

    def profile(frame, event, arg):
        if event == "call" or event == "c_call":
            count.calls += 1
            if count.calls > calls:
                sys.setprofile(previous)
                raise OverBudget(f"still running after {calls:,} calls")

    sys.setprofile(profile)
    try:
        yield count
    finally:
        sys.setprofile(previous)
        if os.environ.get("SYMCTL_PRINT_CALLS"):  # to set a budget: measure, then keep a margin
            print(f"\nbounded: {count.calls:,} calls of {calls:,}", file=sys.stderr)


def muscle_loops(count: int, nc: int = 1):
    """``count`` identical stable loops of the muscle, as broadcast views (no memory)."""
    one = (
        np.zeros((1, nc, nc)),
        np.full((1, nc, 1), -0.05),
        np.ones((1, 1, nc)),
        np.zeros((1, 1, 1)),
    )
    return [np.broadcast_to(a, (count, *a.shape[1:])) for a in one]


def long_sums():
    """A table of sums wider than the page, as a two-input controller's coefficients of a(z)."""
    from symctl.report.document import Table

    rows = tuple(
        (f"${k}$", "$" + " - ".join([f"K_{{{k},12}} K_{{{k + 1},21}}"] * (k + 6)) + "$", "$0.7$")
        for k in range(6)
    )
    return Table(("$k$", "$a_k$", "with the optimal gains"), rows)


def need_spiking(module: str):
    """The spiking extra's ``module`` (nengo, nest); the test module is skipped without it,
    except under SYMCTL_REQUIRE_SPIKING (make test-all), where a missing one fails."""
    import importlib

    import pytest

    if os.environ.get("SYMCTL_REQUIRE_SPIKING"):
        return importlib.import_module(module)
    return pytest.importorskip(module, reason="pip install symctl[spiking]")
