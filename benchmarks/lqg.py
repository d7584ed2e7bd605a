"""Noisy closed loops: a Monte Carlo of 10^4 loops x 500 steps of the forearm against python-control.

The forearm of ``examples/forearm.toml`` (2 states, net delay T = 6 at Ts = 5 ms) in closed
loop with its optimal delayed controller, under process noise on both states, additive
motor noise on the torque and sensor noise on the measured angle and rate. ``monte_carlo``
runs 10^4 loops of 500 steps at once and sets the measured stationary covariance and cost
(with their standard errors) beside the Lyapunov prediction. The baseline is
python-control's ``forced_response`` on the same closed loop (a discrete ``StateSpace``
whose inputs are the three noises), one call per draw: it is timed on ``--sample`` draws
(default 200) and scaled to 10^4, said so in the table. A second run adds
signal-dependent motor noise (standard deviation 0.5 |u|): its variance against the
additive-noise prediction the design assumes. Targets: the Monte Carlo under 3 s and at
least 100x faster than the baseline.

Then the forearm measured by its angle only (``examples/forearm_lqg.toml``, T = 6): the whole
``derive`` without figures (target under 5 s), and the symbolic LQG compensator with K and L
kept symbolic, derived and proved (target under 10 s), each beside python-control's numeric
equivalent in the same run (``dlqr`` on the augmented system, ``dlqe`` on the plant, the
compensator's state space and its transfer function).

Run: ``python benchmarks/lqg.py`` (options: ``--count``, ``--steps``, ``--sample``,
``--repeat``, ``--derive-repeat``).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import control
import numpy as np
from sympy.core.cache import clear_cache

from symctl import (
    Noise,
    augment,
    derive,
    load_model,
    lqg_tf,
    lqr_gains,
    monte_carlo,
    prove_lqg_tf,
    z,
)

FOREARM = Path(__file__).resolve().parent.parent / "examples" / "forearm.toml"
FOREARM_LQG = FOREARM.with_name("forearm_lqg.toml")
NOISE = Noise(process=[1e-6, 1e-4], motor=1e-4, sensor=[1e-6, 1e-4])


def forearm():
    """The forearm's optimal delayed controller (its gains on the augmented state)."""
    m = load_model(FOREARM)
    return lqr_gains(augment(m.plant, m.sensor_delay, m.actuator_delay, Q=m.Q, R=m.R))


def closed_loop(gains) -> control.StateSpace:
    """The loop as python-control sees it: inputs process (n), motor (m), sensor (n) noise;
    outputs the plant's states and the motor command."""
    s = gains.system
    A_aug = np.array(s.A, dtype=float)
    B_aug = np.array(s.B, dtype=float)
    B = np.array(s.plant.B, dtype=float)
    n, m, size = s.n, s.m, A_aug.shape[0]
    K = np.asarray(gains.K, dtype=float)
    E = np.zeros((size, 2 * n + m))
    E[:n, :n], E[:n, n : n + m], E[:, n + m :] = np.eye(n), B, B_aug @ K[:, :n]
    C = np.vstack([np.eye(n, size), np.eye(m, size, size - m)])
    return control.ss(A_aug + B_aug @ K, E, C, 0, float(s.plant.dt))


def baseline(loop: control.StateSpace, sample: int, steps: int) -> tuple[float, float]:
    """Seconds per draw of ``forced_response`` and the angle's variance over the draws."""
    gen = np.random.default_rng(0)
    roots = np.sqrt(np.concatenate([[1e-6, 1e-4], [1e-4], [1e-6, 1e-4]]))[:, None]
    burn, total = 184, 0.0
    start = time.perf_counter()
    for _ in range(sample):
        noise = roots * gen.standard_normal((loop.ninputs, steps))
        y = control.forced_response(loop, U=noise).outputs
        total += float(np.mean(y[0, burn:] ** 2))
    return (time.perf_counter() - start) / sample, total / sample


def best(repeat: int, run):
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = run()
        times.append(time.perf_counter() - start)
    return min(times), out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--count", type=int, default=10_000)
    parser.add_argument("--steps", type=int, default=500)
    parser.add_argument("--sample", type=int, default=200)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--derive-repeat", type=int, default=2)
    args = parser.parse_args(argv)
    estimating(args.derive_repeat)
    gains = forearm()
    kw = {"count": args.count, "steps": args.steps, "rng": 0}
    t_mc, mc = best(args.repeat, lambda: monte_carlo(gains, noise=NOISE, **kw))
    per_draw, var_pc = baseline(closed_loop(gains), args.sample, args.steps)
    t_pc = per_draw * args.count
    sd_noise = Noise(process=[1e-6, 1e-4], signal_dependent=0.5)
    t_sd, sd = best(args.repeat, lambda: monte_carlo(gains, noise=sd_noise, **kw))
    print(f"forearm, T = {gains.system.T}, {args.count} loops x {args.steps} steps")
    print(" method                                  | seconds | speed-up")
    print("-" * 64)
    print(f" symctl monte_carlo (additive noise)     | {t_mc:7.3f} | {t_pc / t_mc:7.0f}x")
    print(f" symctl monte_carlo (signal-dependent)   | {t_sd:7.3f} | {t_pc / t_sd:7.0f}x")
    print(
        f" python-control forced_response x {args.count:<6d}| {t_pc:7.1f} |       1x  "
        f"(timed on {args.sample} draws, {per_draw * 1e3:.2f} ms each, x {args.count})"
    )
    print(f"best of {args.repeat}; targets: under 3 s and at least 100x\n")
    print("additive process, motor and sensor noise:")
    print(mc.table())
    print(
        f"(python-control's {args.sample} draws: var theta = {var_pc:.4g}, "
        f"the same loop and noise)\n"
    )
    print("signal-dependent motor noise, sd = 0.5 |u| (the design assumes additive noise):")
    print(sd.table())
    rise = np.diag(sd.predicted_covariance) / np.diag(sd.additive_covariance) - 1
    print("variance above the additive prediction: " + ", ".join(f"{100 * r:.1f}%" for r in rise))


def python_control_lqg(m) -> control.TransferFunction:
    """python-control's numeric compensator: dlqr on the augmented system, dlqe on the plant."""
    s = augment(m.plant, m.sensor_delay, m.actuator_delay, Q=m.Q, R=m.R)
    A, B = np.array(s.A, dtype=float), np.array(s.B, dtype=float)
    Qeq = np.zeros_like(A)  # the cost on the plant's states and on mu (symctl.design.lqr)
    Qeq[: s.n, : s.n] = np.array(s.Q_plant, dtype=float)
    K, _, _ = control.dlqr(A, B, Qeq, np.array(s.R, dtype=float))
    Ap, Bp = np.array(s.plant.A, dtype=float), np.array(s.plant.B, dtype=float)
    C = np.array(m.C, dtype=float)
    W = Bp @ np.array(m.noise["motor"], dtype=float) @ Bp.T + np.array(
        m.noise["process"], dtype=float
    )
    L, _, _ = control.dlqe(Ap, np.eye(s.n), C, W, np.array(m.noise["sensor"], dtype=float))
    n, size = s.n, A.shape[0]
    Lt, Ct = np.zeros((size, C.shape[0])), np.hstack([C, np.zeros((C.shape[0], size - n))])
    Lt[:n] = L  # dlqe's gain is the predictor's
    F = A - B @ K - Lt @ Ct  # python-control's sign: u = -K x
    M = np.eye(s.m, size, size - s.m)
    return control.ss2tf(control.ss(F, Lt, M, 0, float(s.plant.dt)))


def estimating(repeat: int) -> None:
    """The angle-only forearm: derive and the symbolic compensator, beside python-control."""
    m = load_model(FOREARM_LQG)
    s = augment(m.plant, m.sensor_delay, m.actuator_delay, Q=m.Q, R=m.R)

    def run_derive():
        derive.cache_clear()
        clear_cache()  # SymPy's too: every run computes from scratch
        return derive(FOREARM_LQG)

    def symbolic():
        clear_cache()
        G = lqg_tf(s, m.C)
        return G, prove_lqg_tf(s, m.C, G)

    t_derive, res = best(repeat, run_derive)
    t_sym, (G, proof) = best(repeat, symbolic)
    t_pc, G_pc = best(repeat, lambda: python_control_lqg(m))
    point = 0.5 + 0.3j  # both transfer functions evaluated at one point
    ours = complex(res.G.expr.subs(z, point).evalf())
    same = abs(complex(G_pc(point)) - ours) <= 1e-6 * abs(ours)
    print(f"forearm measured by its angle only, T = {s.T} (examples/forearm_lqg.toml)")
    print(" step                                          | seconds")
    print("-" * 60)
    print(f" symctl derive, no figures (target < 5 s)      | {t_derive:7.2f}")
    print(f" symctl lqg_tf + prove_lqg_tf, K, L symbolic   | {t_sym:7.2f}   (target < 10 s)")
    print(f" python-control dlqr + dlqe + ss2tf (numbers)  | {t_pc:7.3f}")
    print(
        f"best of {repeat}; proved: {bool(proof)}; G of order {G.order} in "
        f"{len(G.free_symbols)} symbols; python-control's G equals symctl's numeric G: {same}\n"
    )


if __name__ == "__main__":
    main()
