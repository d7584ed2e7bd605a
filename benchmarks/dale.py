"""Time Dale's-law decisions, and print the E/I table of the order-2 atlas.

symctl: ``symctl.dale`` per circuit, z3's nlsat called once per sign assignment
of the neurons that send two or more synapses (signs.decide), with the
sections' C reduced to one sign.

Baselines, measured in the same run:

* the previous encoding: one z3 call on the disjunction of every sign
  assignment (and every C free), with the same timeout;
* brute force: random realizations (random epsilon, C = +-1 and, for the
  general circuit, a random P), checked for Dale's law in floating point, for
  a fixed number of tries. It can find witnesses but never prove that none exists.

Tables:

1. the paper's controller (T = 2, delays 1 + 1): every order-2 class and the
   three named circuits, with times;
2. the cheapest E/I circuit (symctl.ei_circuit) for the paper's controller at
   T = 2 and T = 3;
3. the E/I table (symctl.dale_atlas): which classes admit an E/I assignment
   for every, some or no second-order controller k / (z^2 + a1 z + a0).

Run: python benchmarks/dale.py [--samples N] [--workers N]
"""

from __future__ import annotations

import argparse
import time

import numpy as np
import sympy as sp
import z3

import symctl
from symctl import MuscleModel, augment, lqr_gains, z
from symctl._util.deadline import Deadline
from symctl.compatibility.structure import Structure
from symctl.dalelaw.dale import controller_of, poles_of, templates_of
from symctl.dalelaw.signs import encode
from symctl.neural.circuit import Circuit
from symctl.realization.factorization import factor
from symctl.realization.realization import controllable_canonical, observable_canonical

TIMEOUT = 10.0
TRIES = 300


def previous(fs, circuit, poles) -> tuple[str, float]:
    """One z3 call on the whole disjunction, every C free (the first encoding)."""
    t0 = time.perf_counter()
    verdicts = []
    for t in templates_of(fs, circuit)[1]:
        enc = encode(t, poles, Deadline(TIMEOUT))
        ctx = enc.solver.ctx
        s = z3.SolverFor("QF_NRA", ctx=ctx)
        s.set("timeout", int(TIMEOUT * 1000))
        c_syms = {str(c) for c in (*fs.sensor_C, *fs.actuator_C)}
        for a in enc.solver.assertions():  # drop the C normalization, keep C != 0
            text = str(a)
            if any(text in (f"{c}*{c} == 1", f"{c} == 1") for c in c_syms):
                continue
            s.add(a)
        for c in c_syms:
            s.add(z3.Real(c, ctx) != 0)
        verdicts.append(str(s.check()))
        if verdicts[-1] == "sat":
            break
    verdict = "sat" if "sat" in verdicts else "unsat" if set(verdicts) == {"unsat"} else "unknown"
    return verdict, time.perf_counter() - t0


def brute(G, ds, da, circuit, rng) -> tuple[bool, float]:
    """Random realizations checked in floating point; True if one obeys Dale's law."""
    t0 = time.perf_counter()
    k = ds + da
    for _ in range(TRIES):
        eps = [float(e) for e in rng.uniform(-0.95, 0.95, k)]
        cs = [float(rng.choice([-1.0, 1.0]))] + [1.0] * (k - 1)
        fs = factor(G, ds, da, eps=[round(e, 3) for e in eps], C=cs)
        if circuit == "general":
            n = fs.G2.order
            R2 = symctl.general_realization(fs.G2, rng.normal(size=(n, n)).round(3).tolist())
        elif circuit == "controllable":
            R2 = controllable_canonical(fs.G2)
        else:
            R2 = observable_canonical(fs.G2)
        c = Circuit.from_structure(Structure.from_factorization(fs, R2))
        names = {nr.name for nr in c.neurons}
        ok = True
        for nr in c.neurons:
            ws = [float(s.weight) for s in nr.axon if s.target in names and s.target != nr.name]
            if ws and not (all(w > 0 for w in ws) or all(w < 0 for w in ws)):
                ok = False
                break
        if ok:
            return True, time.perf_counter() - t0
    return False, time.perf_counter() - t0


def table1(gains, rng) -> None:
    G, ds, da = controller_of(gains, None, None)
    fs = factor(G, ds, da)
    poles = poles_of(G)
    classes = symctl.atlas(2, workers=1).classes
    word = {True: "E/I", False: "none (proved)", None: "not decided"}
    word2 = {True: "yes", False: "no (proved)", None: "?"}
    print("Table 1. Dale's law for the paper's controller (T = 2, delays 1 + 1), per circuit")
    print(
        "| circuit | neurons | symctl | realizes G | time [s] | previous encoding | time [s] | "
        f"brute force ({TRIES} tries) | time [s] |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    total = prev_total = 0.0
    for circuit in [*symctl.dalelaw.signs.NAMED, *classes]:
        r = symctl.dale(gains, circuit=circuit, timeout=TIMEOUT)
        total += r.elapsed
        v, tp = previous(fs, circuit, poles)
        prev_total += tp
        label = circuit if isinstance(circuit, str) else circuit.label
        n = templates_of(fs, circuit)[1][0].circuit.n_neurons
        if isinstance(circuit, str):
            found, tb = brute(G, ds, da, circuit, rng)
            bf, bt = ("found" if found else "none found"), f"{tb:.2f}"
        else:
            bf, bt = "-", "-"
        print(
            f"| {label} | {n} | {word[r.feasible]} | {word2[r.realizes]} | {r.elapsed:.3f} | {v} | "
            f"{tp:.3f} | "
            f"{bf} | {bt} |"
        )
    print(f"total: symctl {total:.1f} s, previous encoding {prev_total:.1f} s\n")


def table2() -> None:
    print("Table 2. The cheapest E/I circuit (symctl.ei_circuit)")
    print(
        "| controller | circuits searched | winner | neurons | unconstrained minimum | "
        "Dale's cost | time [s] |"
    )
    print("|---|---|---|---|---|---|---|")
    unstable = sp.Rational(1, 10) / (z**2 - sp.Rational(5, 2) * z + sp.Rational(3, 2))
    cases = [
        ("muscle, delays 1 + 1", lqr_gains(augment(MuscleModel(), 1, 1)), None),
        ("muscle, delays 2 + 1", lqr_gains(augment(MuscleModel(), 2, 1)), None),
        ("muscle, delays 1 + 1", lqr_gains(augment(MuscleModel(), 1, 1)), ["observable"]),
        ("0.1/(z^2 - 2.5 z + 1.5), delays 1 + 1", unstable, None),
    ]
    for name, G, circuits in cases:
        t0 = time.perf_counter()
        e = symctl.ei_circuit(
            G,
            sensor_delay=1 if "1 + 1" in name else 2,
            actuator_delay=1,
            circuits=circuits,
            timeout=TIMEOUT,
        )
        what = "observable only" if circuits else f"{len(e.candidates)}"
        print(
            f"| {name} | {what} | {e.circuit} | {e.neurons} | {e.minimum} | "
            f"{e.cost} | {time.perf_counter() - t0:.1f} |"
        )
    print()


def table3(gains, samples: int, workers: int) -> None:
    t0 = time.perf_counter()
    T = symctl.dale_atlas(2, samples=samples, G=gains, timeout=TIMEOUT, workers=workers)
    print(
        f"Table 3. E/I table of the order-2 atlas: controllers k / (z^2 + a1 z + a0), delays 1 + 1, "
        f"{samples} sampled controllers per class (seed 0), {time.perf_counter() - t0:.1f} s, "
        f"{workers} worker(s)"
    )
    print(T.table())
    print()
    for verdict, labels in T.summary().items():
        print(f"{verdict}: {', '.join(labels) if labels else '-'}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--samples", type=int, default=24)
    ap.add_argument("--workers", type=int, default=1)
    args = ap.parse_args()
    rng = np.random.default_rng(0)
    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    table1(gains, rng)
    table2()
    table3(gains, args.samples, args.workers)


if __name__ == "__main__":
    main()
