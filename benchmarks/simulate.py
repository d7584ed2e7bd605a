"""Batch closed-loop simulation: 10^5 realizations x 500 steps against python-control.

Every realization is the paper's controller G3 G2 G1 (optimal gains, Q = R = 1) with
random eps1, eps3 in (-0.9, 0.9), C1 = C3 = 1 and a random 2 x 2 similarity P for G2, so
all loops have the same force and rate traces while the neurons' states differ.
The baseline is python-control's ``forced_response`` on each closed loop (a discrete
``StateSpace`` per realization), timed on a sample and scaled to the full count.
Target: the batch under 2 s and at least 100x faster than the baseline.

The physical floor is the memory traffic of the outputs (force and rate of 10^5 loops
x 500 steps: 0.8 GB of float64): measured in the same run, NumPy's copy of an array of
that size (``np.copyto`` into a buffer already touched, best of 5; and ``a.copy()``,
which pays the page faults of a fresh buffer as ``simulate_batch`` does), and the
bandwidth ``simulate_batch`` achieves (bytes of outputs written / time) as a fraction
of it. The earlier time loop (one einsum per step and chunk of 8192 loops,
symctl commit 43dc9c6, copied below) runs in the same run as the old-method baseline.
The timings in the first table are the best of ``--repeat`` interleaved runs in one
process, where a fresh output buffer reuses memory just freed. The second table runs one
call in a fresh process: its time includes the first-touch page faults of the outputs,
whose cost depends on the kernel's free huge pages (0.05 to 4 s for 0.8 GB on the 2-core
test machine, the same for the old and the new loop), and its peak memory (VmHWM, reset
before the call) for keep-all and for the options that bound it (``keep=`` fewer traces or
only peaks, ``chunk=`` streaming); a 10^6 x 500 batch is streamed to show the memory
stays bounded.

Run: ``python benchmarks/simulate.py`` (options: ``--count``, ``--steps``, ``--sample``,
``--big``; ``--big 0`` skips the 10^6 run).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import control
import numpy as np
import sympy as sp

from symctl import (
    MuscleModel,
    augment,
    closed_loop_response,
    controller_realization,
    controller_tf,
    factor,
    general_realization,
    lqr_gains,
    simulate_batch,
)
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3


def realizations(count: int, seed: int = 0):
    """``(F, H, M, N)`` stacks for ``count`` random realizations of the paper's controller."""
    model = MuscleModel()
    gains = lqr_gains(augment(model, 1, 1))
    f = factor(controller_tf(2)).subs({**gains.substitutions(), C_1: 1, C_3: 1})
    P = sp.Matrix(2, 2, sp.symbols("p1:5"))
    R = controller_realization(f, general_realization(f.G2, P))
    fn = R.lambdify([epsilon_1, epsilon_3, *P])
    gen = np.random.default_rng(seed)
    eps = gen.uniform(-0.9, 0.9, size=(2, count))
    p = gen.normal(size=(4, count)) + 2.0 * np.array([1, 0, 0, 1])[:, None]  # away from singular
    return model, gains, fn(*eps, *p)


def baseline(model, F, H, M, N, w, t) -> float:
    """python-control: one closed-loop StateSpace and one forced_response per realization."""
    A, B = (float(v) for v in (model.plant().A[0, 0], model.plant().B[0, 0]))
    start = time.perf_counter()
    for i in range(F.shape[0]):
        nc = F.shape[1]
        Acl = np.block([[A + B * N[i], B * M[i]], [H[i], F[i]]])
        E = np.vstack([np.eye(1), np.zeros((nc, 1))])
        C = np.vstack([np.hstack([np.eye(1), np.zeros((1, nc))]), np.hstack([N[i], M[i]])])
        sys = control.ss(Acl, E, C, np.zeros((2, 1)), model.dt)
        control.forced_response(sys, T=t, U=w[:, 0])
    return time.perf_counter() - start


# ---------------------------------------------------------------- the old time loop
def old_simulate(model, F, H, M, N, w):
    """``(delta_f, delta_r)`` by symctl's earlier time loop (commit 43dc9c6).

    The closed loop realization-last, one ``einsum`` per step for ``A_cl x`` and one for
    the rate, the state copied into a time-major buffer, chunks of 8192 loops on every
    core; no stability check (compare with ``check_stability=False``).
    """
    A, B = model.plant().numeric()
    R, n, nc = F.shape[0], A.shape[0], F.shape[1]
    Acl = np.empty((n + nc, n + nc, R))
    Acl[:n, :n] = A[:, :, None] + np.einsum("ij,rjk->ikr", B, N)
    Acl[:n, n:] = np.einsum("ij,rjk->ikr", B, M)
    Acl[n:, :n] = np.moveaxis(H, 0, -1)
    Acl[n:, n:] = np.moveaxis(F, 0, -1)
    Cr = np.moveaxis(np.concatenate([N, M], axis=2), 0, -1)
    m, steps = Cr.shape[0], w.shape[0]
    wt = w[:, :, None]
    out = np.empty((steps, n + m, R))

    @np.errstate(over="ignore", invalid="ignore")
    def run(part: slice) -> int:
        a, c, o = (
            np.ascontiguousarray(Acl[..., part]),
            np.ascontiguousarray(Cr[..., part]),
            out[..., part],
        )
        quiet = ~np.any(wt, axis=(1, 2))
        x, nxt = np.zeros(a.shape[1:]), np.empty(a.shape[1:])
        for t in range(steps):
            o[t, :n] = x[:n]
            np.einsum("mjr,jr->mr", c, x, out=o[t, n : n + m])
            np.einsum("ijr,jr->ir", a, x, out=nxt)
            if not quiet[t]:
                nxt[:n] += wt[t]
            x, nxt = nxt, x
        finite = np.all(np.isfinite(o), axis=(1, 2))
        return steps if finite.all() else int(np.argmin(finite))

    parts = [slice(lo, min(R, lo + 8192)) for lo in range(0, R, 8192)]
    with ThreadPoolExecutor(min(len(parts), os.cpu_count() or 1)) as pool:
        assert min(pool.map(run, parts)) == steps
    loops = np.moveaxis(out, -1, 0)
    return loops[..., :n], loops[..., n:]


# ---------------------------------------------------------------- memory, in a fresh process
OLD = "old time loop (43dc9c6), keep all"
OPTIONS = {
    OLD: {},
    "keep all (default)": {},
    "keep=('delta_r',)": {"keep": ("delta_r",)},
    "keep=('peak_delta_r',)": {"keep": ("peak_delta_r",)},
    "chunk=10_000, each chunk dropped": {"chunk": 10_000},
    "chunk=50_000, keep=('peak_delta_r',)": {"chunk": 50_000, "keep": ("peak_delta_r",)},
}


def _status(key: str) -> float:
    """A ``/proc/self/status`` entry in MB."""
    with open("/proc/self/status") as fh:
        line = next(line for line in fh if line.startswith(key + ":"))
    return int(line.split()[1]) / 1024


def child(option: str, count: int, steps: int) -> None:
    """Run one option and print its time and memory as JSON (the parent reads it)."""
    model, gains, mats = realizations(count)
    kwargs = OPTIONS[option]
    before = _status("VmRSS")
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")  # resets the peak (VmHWM) to the current RSS
    t0 = time.perf_counter()
    if option == OLD:
        out = old_simulate(model, *mats, closed_loop_response(gains, steps=steps).w)
    else:
        out = simulate_batch(model, *mats, steps=steps, check_stability=False, **kwargs)
    if "chunk" in kwargs:
        for part in out:
            del part  # a consumer that keeps nothing: one chunk is alive at a time
    sec = time.perf_counter() - t0
    print(json.dumps({"sec": sec, "before": before, "peak": _status("VmHWM")}))


def in_child(option: str, count: int, steps: int) -> dict:
    cmd = [
        sys.executable,
        __file__,
        "--child",
        option,
        "--count",
        str(count),
        "--steps",
        str(steps),
    ]
    run = subprocess.run(cmd, capture_output=True, text=True, check=True)
    return json.loads(run.stdout.strip().splitlines()[-1])


def best(fn, repeat: int) -> float:
    """The shortest of ``repeat`` timed calls of ``fn`` (its result dropped before the next)."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
        del result
    return min(times)


def copy_times(nbytes: int, repeat: int) -> tuple[float, float]:
    """NumPy's copy of ``nbytes``: ``np.copyto`` into a touched buffer (best of 5), ``a.copy()``."""
    src = np.ones(nbytes // 8)
    dst = np.zeros_like(src)
    return best(lambda: np.copyto(dst, src), 5), best(src.copy, repeat)


def line(name: str, *cells: str) -> str:
    widths = (8, 9, 6, 9, 7)
    return " | ".join([f"{name:52}", *(f"{c:>{w}}" for c, w in zip(cells, widths, strict=False))])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=100_000)
    parser.add_argument("--steps", type=int, default=500)
    parser.add_argument("--sample", type=int, default=200)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--big", type=int, default=1_000_000)
    parser.add_argument("--child", choices=list(OPTIONS))
    args = parser.parse_args()
    if args.child:
        child(args.child, args.count, args.steps)
        return

    t0 = time.perf_counter()
    model, gains, (F, H, M, N) = realizations(args.count)
    build = time.perf_counter() - t0
    ref = closed_loop_response(gains, steps=args.steps)
    w = ref.w

    # outputs, the same numbers old and new, and against the optimal loop
    out = simulate_batch(model, F, H, M, N, steps=args.steps)
    old_f, old_r = old_simulate(model, F, H, M, N, w)
    same = np.array_equal(out.delta_f, old_f) and np.array_equal(out.delta_r, old_r)
    scale = max(float(np.max(np.abs(old_f))), float(np.max(np.abs(old_r))))
    dev_old = max(
        float(np.max(np.abs(out.delta_f - old_f))), float(np.max(np.abs(out.delta_r - old_r)))
    )
    err = max(
        float(np.max(np.abs(out.delta_f - ref.delta_f)) / np.max(np.abs(ref.delta_f))),
        float(np.max(np.abs(out.delta_r - ref.delta_r)) / np.max(np.abs(ref.delta_r))),
    )
    nbytes = out.delta_f.nbytes + out.delta_r.nbytes
    del out, old_f, old_r

    copyto, fresh_copy = copy_times(nbytes, args.repeat)

    # interleaved, best of --repeat: old and new in the same conditions
    def run(**kw):
        return lambda: simulate_batch(model, F, H, M, N, steps=args.steps, **kw)

    def streamed(**kw):
        return lambda: [None for _ in simulate_batch(model, F, H, M, N, steps=args.steps, **kw)]

    cases = [
        ("simulate_batch, stability checked", run(), nbytes),
        ("simulate_batch, no stability check", run(check_stability=False), nbytes),
        (
            "old time loop (43dc9c6), no stability check",
            lambda: old_simulate(model, F, H, M, N, w),
            nbytes,
        ),
        ("simulate_batch keep=('delta_r',)", run(keep=("delta_r",)), nbytes // 2),
        ("simulate_batch keep=('peak_delta_r',)", run(keep=("peak_delta_r",)), 8 * args.count),
        ("simulate_batch chunk=10_000 (streamed)", streamed(chunk=10_000), nbytes),
    ]
    times = {name: [] for name, _, _ in cases}
    for _ in range(args.repeat):
        for name, fn, _ in cases:
            times[name].append(best(fn, 1))
    k = min(args.sample, args.count)
    base = baseline(model, F[:k], H[:k], M[:k], N[:k], ref.w, ref.t) * args.count / k

    gb = 1e9
    print(
        f"{args.count:,} realizations x {args.steps} steps (controller order 4, loop order 5), "
        f"{os.cpu_count()} cores; outputs (force and rate, float64) {nbytes / gb:.2f} GB"
    )
    head = line("", "time [s]", "speed-up", "GB/s", "of copyto", "of copy")
    print(head)
    print("-" * len(head))
    print(line("build (lambdify the realizations)", f"{build:.3f}"))
    for name, _, written in cases:
        sec = min(times[name])
        bw = written / sec / gb
        cells = [f"{sec:.3f}", f"{base / sec:,.0f}x"]
        if written >= 1e6:
            cells += [
                f"{bw:.2f}",
                f"{bw * copyto * gb / nbytes:.1%}",
                f"{bw * fresh_copy * gb / nbytes:.1%}",
            ]
        print(line(name, *cells))
    copies = [
        ("numpy copyto (buffer touched, best of 5)", copyto),
        ("numpy a.copy() (fresh)", fresh_copy),
    ]
    for name, sec in copies:
        print(line(name, f"{sec:.3f}", "", f"{nbytes / sec / gb:.2f}"))
    print(line(f"python-control forced_response ({k} sampled, scaled)", f"{base:.3f}", "1x"))
    print(
        f"new time loop vs old: {'identical' if same else 'differ'} "
        f"(max |difference| / max |trace| = {dev_old / scale:.1e}); max relative deviation "
        f"of force/rate traces from the optimal loop: {err:.1e}"
    )

    print()
    print(
        f"one call in a fresh process ({args.count:,} x {args.steps}): its time, with the "
        "first-touch page faults of its outputs, and its peak memory (no stability check)"
    )
    head = f"{'':52} | time [s] | RSS before [MB] | peak RSS [MB] | above [MB]"
    print(head)
    print("-" * len(head))
    sizes = [(args.count, option) for option in OPTIONS]
    if args.big:
        sizes.append((args.big, "chunk=50_000, keep=('peak_delta_r',)"))
    for count, option in sizes:
        res = in_child(option, count, args.steps)
        name = option if count == args.count else f"{count:,} loops: {option}"
        print(
            f"{name:52} | {res['sec']:8.3f} | {res['before']:15.0f} | {res['peak']:13.0f} | "
            f"{res['peak'] - res['before']:10.0f}"
        )
    large_circuits(args.repeat)


def large_circuits(repeat: int) -> None:
    """Few loops of a large circuit (the antagonist's general circuit: 332 states, 18 nonzero
    terms per row): the grouped time loop against the row-by-row one (the previous method)."""
    from symctl.neural.timeloop import GROUPED_LOOPS, _run_groups, _run_rows

    size, n, m, steps, terms = 332, 4, 26, 100, 18
    gen = np.random.default_rng(1)
    mask = np.zeros((size, size), dtype=bool)
    for i in range(size):
        mask[i, gen.choice(size, terms, replace=False)] = True
    print()
    print(
        f"few loops of a large circuit ({size} states, {terms} terms per row, {m} rates, "
        f"{steps} steps): the grouped loop (used for a large sparse circuit up to "
        f"{GROUPED_LOOPS} loops) against the row-by-row loop (the previous method), "
        "best of --repeat"
    )
    head = line("", "grouped", "row by row", "speed-up", "same bits")
    print(head)
    print("-" * len(head))
    for count in (1, 4, 64, 512, 2048):  # A of 2048 loops: 1.8 GB
        A = np.where(mask[:, :, None], gen.normal(size=(size, size, count)), 0.0) * 0.2
        Cr = np.where(gen.random((m, size, 1)) < 0.05, gen.normal(size=(m, size, count)), 0.0)
        w = np.zeros((steps, n, 1))
        w[5:15] = 1.0
        outs, secs = [], []
        for run in (_run_groups, _run_rows):
            out = np.empty((steps, n + m + size - n, count))
            args = (A, Cr, n, w, out, list(range(out.shape[1])))
            secs.append(best(lambda run=run, args=args: run(*args), repeat))
            outs.append(out)
        same = np.array_equal(outs[0], outs[1], equal_nan=True)
        print(
            line(
                f"{count:,} loops",
                f"{secs[0]:.3f} s",
                f"{secs[1]:.3f} s",
                f"{secs[1] / secs[0]:.1f}x",
                "yes" if same else "NO",
            )
        )


if __name__ == "__main__":
    main()
