"""Time the loop through spiking populations, and the sweep of what spikes cost each circuit.

1. Simulation rate (simulated seconds per wall second) of ``symctl.spiking_response`` for the
   paper's circuits at 10, 100 and 1,000 neurons per population, beside nengo's reference
   simulator running the same network in the same run: ``Circuit.to_nengo`` with the radii
   symctl chose, closed around the same plant node, built and run by ``nengo.Simulator``
   (build and run, and run alone), without a decoder cache, as symctl runs it. symctl's time
   adds its linear loop (the radii and the reference), the network and the read-out. BLAS
   runs single-threaded, as in the dask workers (on 2 shared cores, a multithreaded
   Cholesky of the 1,000-neuron decoders took 2 s instead of 15 ms).
2. The sweep ``symctl.spiking_cost`` of every circuit of the paper's controller, 3 sizes x 10
   seeds, on 2 dask workers: wall time, runs, and the simulated seconds per wall second it
   reaches in all. Target: under 5 minutes on 2 cores.

Run: python benchmarks/spiking.py [--steps N] [--repeats N] [--workers N] [--no-sweep]
"""

from __future__ import annotations

import argparse
import os
import time

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # before NumPy loads its BLAS

import nengo  # noqa: E402
import numpy as np  # noqa: E402

import symctl  # noqa: E402

SIZES = (10, 100, 1000)
CIRCUITS = ("ifp", "controllable", "general")


def _best(fn, repeats: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def _nengo_loop(res, circuit, n: int, radius, steps: int):
    """The same closed loop built by hand from the public export: the circuit's network and a
    plant node stepping once per sample (10 simulator steps)."""
    Ts = float(res.gains.system.plant.dt)
    A, B = (np.asarray(m, dtype=float) for m in res.gains.system.plant.numeric())
    net = circuit.to_nengo(n, rng=0, dt=Ts, radius=dict(radius))
    sub = 10
    w = np.zeros(steps)
    w[0] = 1.0
    state = {"x": np.zeros(A.shape[0])}

    def step(t, dr):
        j = round(t * sub / Ts)
        if j >= 2 and (j - 1) % sub == 0 and (j - 1) // sub <= steps - 1:
            state["x"] = A @ state["x"] + B @ dr + w[(j - 1) // sub - 1]
        return state["x"]

    with net:
        plant = nengo.Node(step, size_in=1, size_out=1)
        nengo.Connection(plant, net.inputs[circuit.inputs[0]], synapse=None)
        one = nengo.LinearFilter([1.0], [1.0, 0.0], analog=False)
        nengo.Connection(net.outputs[circuit.outputs[0].target], plant, synapse=one)
        nengo.Probe(plant)
    return net, Ts / sub, steps * sub


def rates(steps: int, repeats: int) -> list[tuple]:
    res = symctl.derive_paper()
    rows = []
    for name in CIRCUITS:
        circuit = res.circuits[name].firing.circuits[0]
        for n in SIZES:
            simulated = steps * float(res.gains.system.plant.dt)
            t_sym, r = _best(
                lambda c=circuit, n=n: symctl.spiking_response(
                    res.gains, c, n_neurons=n, rng=0, steps=steps
                ),
                repeats,
            )
            net, dt, count = _nengo_loop(res, circuit, n, r.radius, steps)

            def build_run(net=net, dt=dt, count=count):
                model = nengo.builder.Model(dt=dt, decoder_cache=nengo.cache.NoDecoderCache())
                with nengo.Simulator(net, progress_bar=False, model=model) as sim:
                    t0 = time.perf_counter()
                    sim.run_steps(count)
                    return time.perf_counter() - t0

            t_all, run_only = _best(build_run, repeats)
            rows.append(
                (
                    name,
                    len(circuit.neurons),
                    n,
                    simulated / t_sym,
                    simulated / t_all,
                    simulated / run_only,
                    r.deviation,
                )
            )
            print(_row(rows[-1]), flush=True)
    return rows


def _row(r) -> str:
    return f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.2f} | {r[4]:.2f} | {r[5]:.2f} | {r[6]:.3f} |"


def sweep(workers: int) -> None:
    res = symctl.derive_paper()
    t0 = time.perf_counter()
    cost = symctl.spiking_cost(res, workers=workers)
    wall = time.perf_counter() - t0
    runs = cost.deviation.size
    simulated = runs * 50 * float(res.gains.system.plant.dt)
    print(
        f"\nsweep: {len(cost.circuits)} circuits x {len(cost.neurons)} sizes x {cost.seeds} "
        f"seeds = {runs} runs on {workers} workers: {wall:.1f} s ({runs / wall:.2f} runs/s, "
        f"{simulated / wall:.2f} simulated s per wall s)"
    )
    print(cost.finding())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=100, help="samples per run (Ts = 10 ms)")
    ap.add_argument("--repeats", type=int, default=2, help="runs timed, the fastest kept")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--no-sweep", action="store_true")
    args = ap.parse_args()
    print("simulated seconds per wall second (the fastest of the repeats):\n")
    print(
        "| circuit | populations | neurons each | symctl spiking_response | "
        "nengo build + run | nengo run only | deviation |"
    )
    print("|---|---|---|---|---|---|---|")
    rates(args.steps, args.repeats)
    if not args.no_sweep:
        sweep(args.workers)


if __name__ == "__main__":
    main()
