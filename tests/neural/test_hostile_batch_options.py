"""Hostile ``keep=`` and ``chunk=`` of simulate_batch.

Each case is a symctl error naming the argument, raised before any work starts
(an alarm turns a hang into a failure); valid edge values keep working.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from helpers import bounded, muscle_loops

from symctl import MuscleModel, ParameterError, SymctlTypeError, simulate_batch
from symctl._util.validate import MAX_OUTPUT_BYTES
from symctl.errors import SymctlError

CLASS = "3"

MODEL = MuscleModel()


SMALL = muscle_loops(3)

CASES = [
    # keep
    ("keep_int", {"keep": 5}, SymctlTypeError, "keep"),
    ("keep_bytes", {"keep": b"delta_r"}, SymctlTypeError, "keep"),
    ("keep_unknown", {"keep": ["nope"]}, ParameterError, "keep: expected names among"),
    ("keep_unknown_str", {"keep": "delta"}, ParameterError, "keep: expected names"),
    ("keep_case", {"keep": "DELTA_R"}, ParameterError, "keep: expected names"),
    ("keep_item_int", {"keep": [1]}, SymctlTypeError, "keep: expected names"),
    ("keep_item_none", {"keep": [None]}, SymctlTypeError, "keep"),
    ("keep_item_list", {"keep": [["delta_r"]]}, SymctlTypeError, "keep"),
    ("keep_empty", {"keep": []}, ParameterError, "keep: nothing to keep"),
    ("keep_empty_str", {"keep": ""}, ParameterError, "keep: expected names"),
    ("keep_endless", {"keep": itertools.repeat("delta_r")}, ParameterError, "keep: at most 64"),
    ("keep_endless_bad", {"keep": itertools.count()}, SymctlTypeError, "keep"),
    # chunk
    ("chunk_zero", {"chunk": 0}, ParameterError, "chunk: must be an integer >= 1"),
    ("chunk_negative", {"chunk": -5}, ParameterError, "chunk: must be an integer >= 1"),
    ("chunk_bool", {"chunk": True}, SymctlTypeError, "chunk: expected an integer"),
    ("chunk_float", {"chunk": 2.0}, SymctlTypeError, "chunk: expected an integer"),
    ("chunk_nan", {"chunk": float("nan")}, SymctlTypeError, "chunk"),
    ("chunk_text", {"chunk": "10"}, SymctlTypeError, "chunk"),
    ("chunk_array", {"chunk": np.array([2, 3])}, SymctlTypeError, "chunk"),
    ("chunk_huge_negative", {"chunk": -(10**100)}, ParameterError, "chunk"),
]


@pytest.mark.parametrize(
    ("kwargs", "error", "match"), [c[1:] for c in CASES], ids=[c[0] for c in CASES]
)
def test_hostile_keep_and_chunk_are_refused_by_name(kwargs, error, match):
    with bounded(), pytest.raises(error, match=match):
        simulate_batch(MODEL, *SMALL, **kwargs)


# outputs over MAX_OUTPUT_BYTES (4 GiB): refused before any work, saying what fits
OVERSIZED = [
    ("million_x_500", muscle_loops(10**6), {"steps": 500}, r"keep: .*8 GB.*chunk=536870 or less"),
    (
        "states_300k",
        muscle_loops(300_000, nc=4),
        {"steps": 500, "states": True},
        r"keep: .*7\.2 GB",
    ),
    (
        "keep_states_300k",
        muscle_loops(300_000, nc=4),
        {"steps": 500, "keep": ("states",)},
        r"keep: keeping states of 300000",
    ),
    (
        "chunk_too_big",
        muscle_loops(10**6),
        {"steps": 500, "chunk": 600_000},
        r"chunk: .*600000 realizations",
    ),
    (
        "chunk_1e100",
        muscle_loops(10**6),
        {"steps": 500, "chunk": 10**100},
        r"chunk: .*1000000 realizations",
    ),
    (
        "one_loop_too_large",
        muscle_loops(1, nc=1000),
        {"steps": 600_000, "states": True, "chunk": 1},
        r"chunk: .* 1 realizations x 600000 steps takes 4\.81 GB.*; keep fewer",
    ),
]


@pytest.mark.parametrize(
    ("mats", "kwargs", "match"), [c[1:] for c in OVERSIZED], ids=[c[0] for c in OVERSIZED]
)
def test_outputs_over_the_memory_limit_are_refused_before_work(mats, kwargs, match):
    with bounded(), pytest.raises(ParameterError, match=match) as info:
        simulate_batch(MODEL, *mats, **kwargs)
    assert "MAX_OUTPUT_BYTES" in str(info.value)


def test_the_one_loop_message_does_not_suggest_a_chunk_that_cannot_fit():
    with pytest.raises(ParameterError, match="keep: ") as info:
        simulate_batch(MODEL, *muscle_loops(1, nc=1000), steps=600_000, states=True)
    advice = str(info.value).split(";")[1]
    assert "chunk=" not in advice and "peak_delta_r" in advice


def test_outputs_at_the_limit_are_accepted_and_the_check_is_per_chunk():
    per_loop = 8 * 500 * 2
    fit = MAX_OUTPUT_BYTES // per_loop
    parts = simulate_batch(MODEL, *muscle_loops(10**6), steps=500, chunk=fit, check_stability=False)
    assert hasattr(parts, "__next__")  # nothing simulated yet
    del parts


@pytest.mark.parametrize("chunk", [1, 2, 3, 4, 10**100, np.int64(2)])
def test_valid_edge_chunks_work(chunk):
    parts = list(simulate_batch(MODEL, *SMALL, steps=5, chunk=chunk))
    size = min(int(chunk), 3)
    assert [p.first for p in parts] == list(range(0, 3, size))
    assert sum(p.delta_r.shape[0] for p in parts) == 3


@pytest.mark.parametrize(
    "keep",
    [
        "delta_r",
        ("delta_r", "delta_r"),
        iter(["peak_states"]),
        {"delta_f": 1},
        ["states", "peak_states"],
    ],
    ids=["str", "duplicates", "iterator", "mapping", "trace_and_peak"],
)
def test_valid_keep_values_work(keep):
    out = simulate_batch(MODEL, *SMALL, steps=5, keep=keep)
    kept = [t for t in ("delta_f", "delta_r", "states") if getattr(out, t) is not None]
    assert kept or out.peaks
    assert all(getattr(out, t).shape[:2] == (3, 5) for t in kept)


def test_every_refusal_is_a_symctl_error():
    for _, kwargs, _, _ in CASES:
        with pytest.raises(SymctlError):
            simulate_batch(MODEL, *SMALL, **kwargs)
