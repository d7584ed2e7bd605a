"""simulate_batch's bounded memory: kept traces, peaks and chunks equal the keep-all run exactly.

The time loop (each row in place, zero coefficients skipped, constant ones
as scalars) is checked against the loop it replaced (one einsum per step, copied here
from commit 43dc9c6) on random loops.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp
from helpers import muscle_loops
from hypothesis import given
from hypothesis import strategies as st

import symctl.neural.batch as batch_module
from symctl import (
    MuscleModel,
    ParameterError,
    augment,
    controller_realization,
    controller_tf,
    factor,
    general_realization,
    lqr_gains,
    pulse,
    simulate_batch,
)
from symctl.neural import timeloop
from symctl.neural.batch import KEEP, TRACES, _chunks
from symctl.neural.simulate import _run
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3

MODEL = MuscleModel()
PLANT = (np.array([[0.9, 0.1], [0.0, 0.8]]), np.array([[1.0], [0.5]]))  # n = 2, m = 1


def loops(count: int, nc: int = 3, seed: int = 0):
    """Random stable loops ``(F, H, M, N)`` around ``PLANT``, with structured zeros and constants."""
    gen = np.random.default_rng(seed)
    n, m = 2, 1
    F = 0.3 * gen.uniform(-1, 1, size=(count, nc, nc)) / max(nc, 1)
    F[:, 0, -1] = 0.0  # zero in every loop: skipped by the time loop
    H = 0.1 * gen.normal(size=(count, nc, n))
    M = np.broadcast_to(0.05 * gen.normal(size=(1, m, nc)), (count, m, nc)).copy()  # constants
    N = -0.1 * gen.uniform(size=(count, m, n))
    return F, H, M, N


def full(*args, **kwargs):
    return simulate_batch(PLANT, *args, states=True, **kwargs)


# ---------------------------------------------------------------- the old time loop
@np.errstate(over="ignore", invalid="ignore")
def old_run_chunk(A, Cr, n, w, out):
    """symctl's earlier time loop (commit 43dc9c6), verbatim but for its name."""
    steps, rows, _ = out.shape
    m = Cr.shape[0]
    states = rows > n + m
    A, Cr = np.ascontiguousarray(A), np.ascontiguousarray(Cr)
    quiet = ~np.any(w, axis=(1, 2))
    x, nxt = np.zeros(A.shape[1:]), np.empty(A.shape[1:])
    for t in range(steps):
        out[t, :n] = x[:n]
        np.einsum("mjr,jr->mr", Cr, x, out=out[t, n : n + m])
        if states:
            out[t, n + m :] = x[n:]
        np.einsum("ijr,jr->ir", A, x, out=nxt)
        if not quiet[t]:
            nxt[:n] += w[t]
        x, nxt = nxt, x
    finite = np.all(np.isfinite(out), axis=(1, 2))
    return steps if finite.all() else int(np.argmin(finite))


def random_stack(gen, n: int, m: int, nc: int, count: int, *, zeros: float):
    """A random stack ``A`` ``(n + nc, n + nc, count)`` and ``Cr`` ``(m, n + nc, count)``: entries
    zero in every loop (a fraction ``zeros`` of ``A``) or equal in every loop, as in circuits."""
    size = n + nc
    A = gen.normal(size=(size, size, count)) * 0.4 / np.sqrt(size)
    A[gen.random((size, size)) < zeros] = 0.0  # zero in every loop
    const = gen.random((size, size)) < 0.3
    A[const] = A[const][:, :1]  # equal in every loop
    Cr = gen.normal(size=(m, size, count))
    Cr[gen.random((m, size)) < 0.4] = 0.0
    return A, Cr


@given(
    st.integers(1, 3),
    st.integers(0, 3),
    st.integers(0, 4),
    st.integers(1, 40),
    st.integers(0, 2**32 - 1),
    st.booleans(),
)
def test_the_in_place_time_loop_equals_the_einsum_loop_it_replaced(n, m, nc, count, seed, shared):
    gen = np.random.default_rng(seed)
    A, Cr = random_stack(gen, n, m, nc, count, zeros=0.4)
    w = gen.normal(size=(30, n)) if shared else gen.normal(size=(count, 30, n))
    w[..., 5:9, :] = 0.0  # quiet steps
    df, dr, xc = _run(A, Cr, n, w)
    old = np.empty((30, n + m + nc, count))
    wt = w[:, :, None] if w.ndim == 2 else np.moveaxis(w, 0, -1)
    assert old_run_chunk(A, Cr, n, wt, old) == 30
    new = np.concatenate([df, dr, xc], axis=-1)
    ref = np.moveaxis(old, -1, 0)
    scale = max(float(np.max(np.abs(ref))), 1e-300)
    assert float(np.max(np.abs(new - ref))) <= 1e-12 * scale


@given(
    st.integers(1, 3),
    st.integers(0, 3),
    st.integers(0, 6),
    st.integers(1, 12),
    st.integers(0, 2**32 - 1),
    st.booleans(),
)
def test_the_grouped_and_the_row_by_row_time_loops_give_the_same_bits(n, m, nc, count, seed, peak):
    """Few loops take the grouped loop, many the row-by-row one: the same sums, the same bits."""
    gen = np.random.default_rng(seed)
    A, Cr = random_stack(gen, n, m, nc, count, zeros=0.5)
    w = gen.normal(size=(25, n, 1))
    w[3:7] = 0.0
    rows = [r for r in range(n + m + nc) if gen.random() < 0.7]
    peak_rows = tuple(r for r in range(n + m + nc) if peak and gen.random() < 0.5)
    results = []
    for run in (timeloop._run_groups, timeloop._run_rows):
        out = np.full((25, len(rows), count), np.nan)
        peaks = np.empty((len(peak_rows), count)) if peak_rows else None
        results.append((run(A, Cr, n, w, out, rows, peaks, peak_rows), out, peaks))
    (s1, o1, p1), (s2, o2, p2) = results
    assert s1 == s2
    np.testing.assert_array_equal(o1, o2)
    if peak_rows:
        np.testing.assert_array_equal(p1, p2)


def paper_loops(count: int):
    """The benchmark's loops: G3 G2 G1 with random eps1, eps3 and a random similarity of G2."""
    gains = lqr_gains(augment(MODEL, 1, 1))
    f = factor(controller_tf(2)).subs({**gains.substitutions(), C_1: 1, C_3: 1})
    P = sp.Matrix(2, 2, sp.symbols("p1:5"))
    fn = controller_realization(f, general_realization(f.G2, P)).lambdify(
        [epsilon_1, epsilon_3, *P]
    )
    gen = np.random.default_rng(0)
    p = gen.normal(size=(4, count)) + 2.0 * np.array([1, 0, 0, 1])[:, None]
    return fn(*gen.uniform(-0.9, 0.9, size=(2, count)), *p)


def test_the_paper_loop_is_identical_to_the_einsum_loop():
    F, H, M, N = paper_loops(300)
    out = simulate_batch(MODEL, F, H, M, N, steps=60, states=True)
    n, m, nc = 1, 1, 4
    A, B = MODEL.plant().numeric()
    Acl = np.empty((n + nc, n + nc, 300))
    Acl[:n, :n] = A[:, :, None] + np.einsum("ij,rjk->ikr", B, N)
    Acl[:n, n:] = np.einsum("ij,rjk->ikr", B, M)
    Acl[n:, :n] = np.moveaxis(H, 0, -1)
    Acl[n:, n:] = np.moveaxis(F, 0, -1)
    Cr = np.moveaxis(np.concatenate([N, M], axis=2), 0, -1)
    old = np.empty((60, n + m + nc, 300))
    old_run_chunk(Acl, Cr, n, pulse(60)[:, :, None], old)
    old = np.moveaxis(old, -1, 0)
    np.testing.assert_array_equal(out.delta_f, old[..., :1])
    np.testing.assert_array_equal(out.delta_r, old[..., 1:2])
    np.testing.assert_array_equal(out.states, old[..., 2:])


# ---------------------------------------------------------------- keep
SUBSETS = [c for k in range(1, 4) for c in itertools.combinations(TRACES, k)]


@pytest.mark.parametrize("keep", SUBSETS, ids="+".join)
def test_each_kept_trace_equals_the_keep_all_run(keep):
    mats = loops(50)
    ref = full(*mats)
    out = simulate_batch(PLANT, *mats, keep=keep)
    for name in TRACES:
        if name in keep:
            np.testing.assert_array_equal(getattr(out, name), getattr(ref, name))
            assert not getattr(out, name).flags.writeable
        else:
            assert getattr(out, name) is None
    assert dict(out.peaks) == {}


def test_peaks_are_the_largest_magnitude_of_each_trace():
    mats = loops(70)
    ref = full(*mats, disturbance=pulse(40, -2.0, start=3, length=5, size=2))
    out = simulate_batch(
        PLANT, *mats, disturbance=pulse(40, -2.0, start=3, length=5, size=2), keep=KEEP[3:]
    )
    assert out.delta_f is None and out.delta_r is None and out.states is None
    assert set(out.peaks) == set(TRACES)
    for name in TRACES:
        np.testing.assert_array_equal(out.peaks[name], np.max(np.abs(getattr(ref, name)), axis=1))
        assert not out.peaks[name].flags.writeable
    with pytest.raises(TypeError):
        out.peaks["delta_r"] = None


def test_states_true_adds_the_states_to_keep():
    mats = loops(5)
    out = simulate_batch(PLANT, *mats, keep="peak_delta_r", states=True)
    np.testing.assert_array_equal(out.states, full(*mats).states)
    assert out.delta_r is None and set(out.peaks) == {"delta_r"}


def test_peaks_and_traces_together_and_a_per_loop_disturbance():
    mats = loops(20)
    w = np.random.default_rng(1).normal(size=(20, 25, 2))
    ref = full(*mats, w)
    out = simulate_batch(PLANT, *mats, w, keep=("delta_r", "peak_delta_f", "peak_delta_r"))
    np.testing.assert_array_equal(out.delta_r, ref.delta_r)
    np.testing.assert_array_equal(out.peaks["delta_f"], np.abs(ref.delta_f).max(axis=1))
    np.testing.assert_array_equal(out.peaks["delta_r"], np.abs(ref.delta_r).max(axis=1))


# ---------------------------------------------------------------- chunks
def concatenated(parts, name):
    arrays = [getattr(p, name) if name in TRACES else p.peaks[name[5:]] for p in parts]
    return np.concatenate(arrays, axis=0)


@given(st.integers(1, 60), st.integers(1, 70), st.sampled_from([None, ("delta_r", "peak_states")]))
def test_chunks_concatenate_to_the_keep_all_result_exactly(count, chunk, keep):
    mats = loops(count, seed=count)
    ref = full(*mats, steps=20, keep=keep)
    parts = list(full(*mats, steps=20, chunk=chunk, keep=keep))
    assert [p.first for p in parts] == list(range(0, count, chunk))
    names = [t for t in TRACES if getattr(ref, t) is not None]
    names += ["peak_" + p for p in ref.peaks]
    for name in names:
        whole = getattr(ref, name) if name in TRACES else ref.peaks[name[5:]]
        np.testing.assert_array_equal(concatenated(parts, name), whole)
    for part in parts:
        np.testing.assert_array_equal(part.t, ref.t)
        assert part.stability_checked


@given(st.integers(1, 10**6))
def test_the_time_loops_chunks_cover_the_loops_in_order(count):
    parts = _chunks(count)
    assert parts[0].start == 0 and parts[-1].stop == count
    assert all(a.stop == b.start for a, b in itertools.pairwise(parts))
    sizes = [p.stop - p.start for p in parts]
    assert max(sizes) <= batch_module._CHUNK and max(sizes) - min(sizes) <= 1


def test_batch_across_the_time_loops_chunk_boundaries_equals_single_loops(monkeypatch):
    monkeypatch.setattr(batch_module, "_CHUNK", 16)
    monkeypatch.setattr(batch_module, "_MIN_CHUNK", 4)
    mats = loops(101)
    out = full(*mats, steps=15)
    bounds = {p.start for p in _chunks(101)} | {p.stop - 1 for p in _chunks(101)}
    assert len(bounds) > 6
    for i in sorted(bounds):
        one = full(*(a[i : i + 1] for a in mats), steps=15)
        np.testing.assert_array_equal(out.states[i], one.states[0])
        np.testing.assert_array_equal(out.delta_r[i], one.delta_r[0])


def test_a_chunked_call_checks_stability_before_it_returns():
    F, H, M, N = loops(30)
    F[17] = 2.0 * np.eye(3)  # unstable
    with pytest.raises(ParameterError, match="realization 17 of 30"):
        full(F, H, M, N, chunk=10)  # no iteration needed


def test_an_overflow_is_refused_when_its_chunk_is_reached():
    plant = (np.array([[0.5]]), np.array([[1e-10]]))
    N = np.zeros((6, 1, 1))
    N[-1] = -1e10  # the rate of the last loop overflows at step 6
    zeros = np.zeros_like(N)
    parts = simulate_batch(plant, zeros, zeros, zeros, N, 1e300, chunk=4)
    assert next(parts).first == 0
    with pytest.raises(ParameterError, match="blew up at step 6"):
        next(parts)


@pytest.mark.parametrize("keep", [("peak_delta_r",), ("delta_f", "peak_delta_r")])
def test_an_overflow_seen_only_in_a_peak_names_its_step(keep):
    plant = (np.array([[0.5]]), np.array([[1e-10]]))
    N = np.zeros((3, 1, 1))
    N[1] = -1e10
    zeros = np.zeros_like(N)
    with pytest.raises(ParameterError, match="blew up at step 6"):
        simulate_batch(plant, zeros, zeros, zeros, N, 1e300, keep=keep)
    out = simulate_batch(plant, zeros, zeros, zeros, N, 1e300, keep="delta_f")  # finite
    assert np.all(np.isfinite(out.delta_f))


# ---------------------------------------------------------------- the memory limit


def test_a_million_loops_of_500_steps_are_refused_whole_and_run_streamed():
    mats = muscle_loops(10**6)
    with pytest.raises(
        ParameterError, match=r"keep: keeping delta_f, delta_r of 1000000 .*chunk=536870"
    ):
        simulate_batch(MODEL, *mats, steps=500)
    with pytest.raises(ParameterError, match=r"chunk: .* 1000000 realizations"):
        simulate_batch(MODEL, *mats, steps=500, chunk=10**6)
    parts = simulate_batch(MODEL, *mats, steps=500, chunk=1000, check_stability=False)
    first = next(parts)
    assert first.delta_r.shape == (1000, 500, 1) and first.first == 0
    peaks = simulate_batch(MODEL, *mats, steps=8, keep="peak_delta_r", check_stability=False)
    assert peaks.peaks["delta_r"].shape == (10**6, 1)
    np.testing.assert_array_equal(peaks.peaks["delta_r"][::99_999], peaks.peaks["delta_r"][:11])


def test_a_static_controller_has_empty_states_and_empty_state_peaks():
    F, H, M = np.zeros((3, 0, 0)), np.zeros((3, 0, 1)), np.zeros((3, 1, 0))
    N = np.full((3, 1, 1), -0.05)
    ref = simulate_batch(MODEL, F, H, M, N)
    out = simulate_batch(MODEL, F, H, M, N, keep=("peak_states", "states", "delta_r"))
    assert out.states.shape == (3, 50, 0) and out.peaks["states"].shape == (3, 0)
    np.testing.assert_array_equal(out.delta_r, ref.delta_r)
    only = simulate_batch(MODEL, F, H, M, N, keep="peak_states")
    assert only.peaks["states"].shape == (3, 0)


def test_chunks_of_a_per_loop_disturbance_concatenate_exactly():
    mats = loops(23)
    w = np.random.default_rng(2).normal(size=(23, 30, 2))
    ref = full(*mats, w)
    parts = list(full(*mats, w, chunk=5, keep=("delta_f", "peak_delta_r")))
    np.testing.assert_array_equal(concatenated(parts, "delta_f"), ref.delta_f)
    np.testing.assert_array_equal(concatenated(parts, "peak_delta_r"), np.abs(ref.delta_r).max(1))
    np.testing.assert_array_equal(concatenated(parts, "states"), ref.states)
