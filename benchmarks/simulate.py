"""Batch closed-loop simulation: 10^5 realizations x 500 steps against python-control.

Every realization is the paper's controller G3 G2 G1 (optimal gains, Q = R = 1) with
random eps1, eps3 in (-0.9, 0.9), C1 = C3 = 1 and a random 2 x 2 similarity P for G2, so
all loops have the same force and rate traces while the neurons' states differ.
The baseline is python-control's ``forced_response`` on each closed loop (a discrete
``StateSpace`` per realization), timed on a sample and scaled to the full count.
Target: the batch under 2 s and at least 100x faster than the baseline.

Run: ``python benchmarks/simulate.py`` (options: ``--count``, ``--steps``, ``--sample``).
"""

from __future__ import annotations

import argparse
import os
import time

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
        sys = control.ss(Acl, E, C, np.zeros((2, 1)), model.Ts)
        control.forced_response(sys, T=t, U=w[:, 0])
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=100_000)
    parser.add_argument("--steps", type=int, default=500)
    parser.add_argument("--sample", type=int, default=200)
    args = parser.parse_args()

    t0 = time.perf_counter()
    model, gains, (F, H, M, N) = realizations(args.count)
    build = time.perf_counter() - t0
    ref = closed_loop_response(gains, steps=args.steps)

    t0 = time.perf_counter()
    out = simulate_batch(model, F, H, M, N, steps=args.steps)
    batch = time.perf_counter() - t0
    t0 = time.perf_counter()
    simulate_batch(model, F, H, M, N, steps=args.steps, check_stability=False)
    batch_nocheck = time.perf_counter() - t0
    err = max(
        float(np.max(np.abs(out.delta_f - ref.delta_f)) / np.max(np.abs(ref.delta_f))),
        float(np.max(np.abs(out.delta_r - ref.delta_r)) / np.max(np.abs(ref.delta_r))),
    )
    del out

    k = min(args.sample, args.count)
    base = baseline(model, F[:k], H[:k], M[:k], N[:k], ref.w, ref.t) * args.count / k
    rows = [
        ("build (lambdify 10^5 realizations)", build, ""),
        ("simulate_batch, stability checked", batch, f"{base / batch:,.0f}x"),
        ("simulate_batch, no stability check", batch_nocheck, f"{base / batch_nocheck:,.0f}x"),
        (f"python-control forced_response ({k} sampled, scaled)", base, "1x"),
    ]
    print(
        f"{args.count:,} realizations x {args.steps} steps (controller order 4, loop order 5), "
        f"{os.cpu_count()} cores"
    )
    print(f"{'':52} | {'time [s]':>9} | speed-up")
    print("-" * 76)
    for name, sec, speed in rows:
        print(f"{name:52} | {sec:9.3f} | {speed:>8}")
    print(f"max relative deviation of force/rate traces from the optimal loop: {err:.1e}")


if __name__ == "__main__":
    main()
