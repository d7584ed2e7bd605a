"""Regenerate paper_fit.csv: a synthetic recording of 3 neurons of the paper's controller.

A hidden random general realization (seed 7: epsilons on the grid k/1000, C = 1, a
random rational P), the closed loop under the paper's unit pulse on the force (steps
5..14 of 500), 1% Gaussian noise; recorded: G1.x1, G2.x1, G2.y. Run from the repo root:
``python examples/data/make_paper_fit.py``.
"""

from pathlib import Path

from symctl import MuscleModel, Traces, augment, lqr_gains, synthetic_traces

gains = lqr_gains(augment(MuscleModel(), 1, 1))
data = synthetic_traces(gains, sensor_delay=1, actuator_delay=1, rng=7, steps=500, noise=0.01)
rec = data.select(["G1.x1", "G2.x1", "G2.y"])
meta = {
    "symctl traces": "synthetic recording for symctl fit (docs/fitting.md)",
    "controller": "the paper's: MuscleModel() (tau 0.02 s, f_max 60 N, r_bar 1, Ts 0.01 s), "
    "Q = R = 1, sensor delay 1 step, actuator delay 1 step",
    "circuit": "general",
    "sensor_delay": "1",
    "actuator_delay": "1",
    "columns": "t [s]; disturbance = force disturbance w(t) [N per step] (unit pulse, steps "
    "5..14); G1.x1 = sensor neuron (G1), G2.x1 = first state neuron of G2, G2.y = output "
    "neuron of G2; each its change of firing rate [spikes/s]",
    "noise": "1% of each trace's RMS, Gaussian",
    "hidden": data.meta["hidden"],
}
out = Path(__file__).with_name("paper_fit.csv")
Traces(rec.t, rec.traces, rec.disturbance, meta).to_csv(out)
print(f"wrote {out}")
