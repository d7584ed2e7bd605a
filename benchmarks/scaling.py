"""Time and peak memory of every step of the paper's derivation against the net delay T.

Steps, as ``derive_paper`` runs them (symctl/report/pipeline.py), with the net
delay split sensor_delay = T // 2, actuator_delay = T - T // 2: augment, LQR
gains, the symbolic G(z), its proof, the factorization G = G3 G2 G1, the
firing of the four circuits (count=4), the three realizations of G2 (symbolic
and numeric; the general one with a fully symbolic P up to order 3, the drawn
numeric P beyond), check_realization of all six, the structures and
check_compatibility on DelayGraph.chain, Circuit.from_structure, and the whole
``derive_paper`` (no files written). T = 1..8 (derive_paper's limit,
PAPER_MAX_DELAY); the design steps alone up to T = 20. Also: the exact checker
against the order n of a general realization with a fully symbolic n x n P,
building and proving separately. Last, the growth exponent of each step.

Each case runs in its own forked process, one step after the other; before each
step the process's peak RSS is reset (``/proc/self/clear_refs``), so a step's
memory is the peak RSS of the process while it ran (baseline included: the
interpreter with symctl and its imports). A step past ``--cap`` seconds stops
its case; it and the rest of the case print "> cap".

Run:  python benchmarks/scaling.py [--cap SECONDS] [--max-T N] [--max-design-T N] [--max-n N]
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import queue as queue_mod
import time

import numpy as np
import sympy as sp

from symctl import (
    Circuit,
    DelayGraph,
    MuscleModel,
    Structure,
    augment,
    check_compatibility,
    check_realization,
    circuit_firing,
    controllable_canonical,
    controller_tf,
    derive_paper,
    factor,
    general_realization,
    ifp_structure,
    lqr_gains,
    observable_canonical,
    prove_controller_tf,
)

CIRCUITS = ("ifp", "general", "controllable", "observable")  # symctl.report.spec.CIRCUITS
SYMBOLIC_P_MAX_ORDER = 3  # symctl.report.spec.SYMBOLIC_P_MAX_ORDER
PAPER_MAX_DELAY = 8  # symctl._util.validate.PAPER_MAX_DELAY
DESIGN = ("augment", "LQR", "G(z)", "proof")
STEPS = (
    *DESIGN,
    "factor",
    "firing",
    "ctrb",
    "obsv",
    "general",
    "check",
    "compat",
    "circuit",
)


# --- measurement -------------------------------------------------------------------------------


def _reset_peak() -> None:
    """Reset the process's peak RSS (VmHWM) to its current RSS (Linux >= 4.0)."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:  # not Linux: the peak then stays the process's overall peak
        pass


def _peak_mb() -> float:
    """The process's peak RSS since the last reset [MB]."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _worker(plan, args, queue) -> None:
    def step(name, fn, *a, **kw):
        _reset_peak()
        start = time.perf_counter()
        out = fn(*a, **kw)
        queue.put((name, time.perf_counter() - start, _peak_mb()))
        return out

    plan(step, *args)
    queue.put(None)


def run_case(plan, args: tuple, cap: float) -> dict[str, tuple[float, float]]:
    """``{step: (seconds, peak MB)}`` of the steps of ``plan(step, *args)`` that finished.

    The plan runs in a forked process; a step that takes more than ``cap``
    seconds ends it (the steps it did not reach are missing from the result).
    """
    queue = mp.Queue()
    proc = mp.Process(target=_worker, args=(plan, args, queue))
    proc.start()
    got = {}
    while True:
        try:
            item = queue.get(timeout=cap)
        except queue_mod.Empty:
            proc.terminate()
            break
        if item is None:
            break
        got[item[0]] = item[1:]
    proc.join()
    return got


# --- the plans -----------------------------------------------------------------------------------


def derivation(step, T: int, full: bool) -> None:
    """The steps of derive_paper at net delay T (only the design ones unless ``full``)."""
    s, a = T // 2, T - T // 2
    plant = MuscleModel().plant()
    system = step("augment", augment, plant, s, a)
    gains = step("LQR", lqr_gains, system)
    G = step("G(z)", controller_tf, system)
    assert step("proof", prove_controller_tf, system, G)
    if not full:
        return
    f = step("factor", factor, G, s, a)
    firing = step(
        "firing",
        lambda: {
            k: circuit_firing(k, gains, count=1 if k == "ifp" else 4, seed=0) for k in CIRCUITS
        },
    )
    # the numeric G2 of each circuit: exact gains, C = 1, the drawn epsilons
    unit_C = {c: 1 for c in (*f.sensor_C, *f.actuator_C)}
    exact = {k: sp.Rational(v) for k, v in gains.substitutions().items()}
    G2_gains = f.G2.subs(exact).subs(unit_C)

    def numeric(name):
        drawn = firing[name].params[0]
        return G2_gains.subs({k: v for k, v in drawn.items() if isinstance(k, sp.Symbol)}), drawn

    def canonical(realize, name):
        G2_num, _ = numeric(name)
        return (realize(f.G2), f.G2), (realize(G2_num), G2_num)

    def general():
        G2_num, drawn = numeric("general")
        P_num = drawn["P"]
        n = P_num.shape[0]
        P = sp.Matrix(n, n, sp.symbols(f"p_1:{n + 1}(1:{n + 1})")) if n <= 3 else P_num
        return (general_realization(f.G2, P), f.G2), (general_realization(G2_num, P_num), G2_num)

    pairs = {
        "controllable": step("ctrb", canonical, controllable_canonical, "controllable"),
        "observable": step("obsv", canonical, observable_canonical, "observable"),
        "general": step("general", general),
    }
    step(
        "check",
        lambda: [bool(check_realization(R, G2)) for pair in pairs.values() for R, G2 in pair],
    )
    graph = DelayGraph.chain([1] * T)

    def compat():
        S = {"ifp": ifp_structure(T)}
        S.update({k: Structure.from_factorization(f, pairs[k][0][0]) for k in CIRCUITS[1:]})
        return S, {k: check_compatibility(v, graph) for k, v in S.items()}

    structures, verdicts = step("compat", compat)
    step(
        "circuit",
        lambda: [
            Circuit.from_structure(structures[k], verdicts[k] if verdicts[k].ok else None)
            for k in CIRCUITS
        ],
    )


def baseline(step) -> None:
    step("baseline", int)


def whole(step, T: int) -> None:
    step("derive_paper", derive_paper, sensor_delay=T // 2, actuator_delay=T - T // 2)


def checker(step, n: int) -> None:
    """A general realization of the order-n controller with a fully symbolic n x n P."""
    G = controller_tf(n)
    P = sp.Matrix(n, n, sp.symbols(f"p_1:{n + 1}(1:{n + 1})"))
    R = step("build", general_realization, G, P)
    assert step("prove", check_realization, R, G)


# --- the tables ----------------------------------------------------------------------------------


def cell(got: dict, name: str, index: int, fmt: str, width: int) -> str:
    if name in got:
        return f"{got[name][index]:{width}{fmt}}"
    return f"{'> cap':>{width}}"


def slope(points: list[tuple[float, float]]) -> float | None:
    """Least-squares slope of log t against log x over the points with t > 10 ms."""
    pts = [(x, t) for x, t in points if t > 0.01]
    if len(pts) < 2 or len({x for x, _ in pts}) < 2:
        return None
    xs, ts = zip(*pts, strict=True)
    return float(np.polyfit(np.log(xs), np.log(ts), 1)[0])


def table(title: str, rows: dict[int, dict], steps: tuple, key: str, index: int, fmt: str):
    w = max(8, *(len(s) for s in steps))
    print(title)
    print(f"{key:>3} | " + " | ".join(f"{s:>{w}}" for s in steps))
    print("-" * (6 + (w + 3) * len(steps)))
    for x, got in rows.items():
        print(f"{x:>3} | " + " | ".join(cell(got, s, index, fmt, w) for s in steps), flush=True)


def exponents(rows: dict[int, dict], steps: tuple, key: str) -> None:
    w = max(8, *(len(s) for s in steps))
    fits = []
    for s in steps:
        k = slope([(x, got[s][0]) for x, got in rows.items() if s in got])
        fits.append(f"{'-':>{w}}" if k is None else f"{k:{w}.2f}")
    print(f"{'exp':>3} | " + " | ".join(fits))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cap", type=float, default=30.0, help="time cap of one step [s]")
    parser.add_argument("--max-T", type=int, default=PAPER_MAX_DELAY, help="the full derivation")
    parser.add_argument("--max-design-T", type=int, default=20, help="the design steps")
    parser.add_argument("--max-n", type=int, default=5, help="the checker against n")
    args = parser.parse_args()
    controller_tf(augment(MuscleModel().plant(), 1, 1))  # warm the caches before forking
    base = run_case(baseline, (), args.cap)["baseline"][1]
    load = os.getloadavg()
    start = time.perf_counter()
    print(
        f"{os.cpu_count()} cores, load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}; "
        f"cap {args.cap:g} s per step; baseline RSS of a case {base:.0f} MB\n"
    )

    rows = {}
    for T in range(1, max(args.max_T, args.max_design_T) + 1):
        rows[T] = run_case(derivation, (T, T <= args.max_T), args.cap)
        if "proof" not in rows[T]:  # the design steps hit the cap: larger T only gets worse
            break
    full = {T: got for T, got in rows.items() if T <= args.max_T}
    design = {T: {s: got[s] for s in DESIGN if s in got} for T, got in rows.items()}

    table(
        "time [s] of each step of the derivation, against the net delay T",
        full,
        STEPS,
        "T",
        0,
        ".3f",
    )
    exponents(full, STEPS, "T")
    last = max((T for T, got in full.items() if got), default=None)
    if last is not None:
        total = sum(v[0] for v in full[last].values())
        ranked = sorted(full[last].items(), key=lambda kv: -kv[1][0])
        print(
            f"where the time goes at T = {last} ({total:.1f} s): "
            + ", ".join(f"{s} {100 * v[0] / total:.0f}%" for s, v in ranked[:5])
        )
    print()
    table("peak RSS [MB] during each step", full, STEPS, "T", 1, ".0f")
    print()

    whole_rows = {}
    for T in range(1, args.max_T + 1):
        whole_rows[T] = run_case(whole, (T,), 4 * args.cap)
        if "derive_paper" not in whole_rows[T]:
            break
    w = 12
    print("the whole derive_paper(sensor_delay=T//2, actuator_delay=T-T//2), no files written")
    print(f"{'T':>3} | {'time [s]':>{w}} | {'peak RSS [MB]':>{w}} | {'sum of steps':>{w}}")
    print("-" * (6 + 3 * (w + 3)))
    for T, got in whole_rows.items():
        steps_sum = sum(v[0] for v in full.get(T, {}).values())
        print(
            f"{T:>3} | {cell(got, 'derive_paper', 0, '.3f', w)} | "
            f"{cell(got, 'derive_paper', 1, '.0f', w)} | {steps_sum:{w}.3f}",
            flush=True,
        )
    k = slope([(T, got["derive_paper"][0]) for T, got in whole_rows.items() if got])
    print(f"exp | {'-' if k is None else f'{k:.2f}':>{w}}")
    print()

    table("time [s] of the design steps, T up to the design limit", design, DESIGN, "T", 0, ".4f")
    exponents(design, DESIGN, "T")
    print()

    n_rows = {}
    for n in range(2, args.max_n + 1):
        n_rows[n] = run_case(checker, (n,), args.cap)
        if "prove" not in n_rows[n]:
            break
    table(
        "general realization of the order-n controller with a fully symbolic n x n P",
        {n: {f"{s} [s]": v for s, v in got.items()} for n, got in n_rows.items()},
        ("build [s]", "prove [s]"),
        "n",
        0,
        ".3f",
    )
    print(
        f"{'':>3}   peak RSS [MB]: "
        + ", ".join(
            f"n={n}: " + "/".join(f"{v[1]:.0f}" for v in got.values()) for n, got in n_rows.items()
        )
    )
    exponents(
        {n: {f"{s} [s]": v for s, v in got.items()} for n, got in n_rows.items()},
        ("build [s]", "prove [s]"),
        "n",
    )
    print()

    print(
        "wall time (perf_counter) and peak RSS of a forked process per case (one T or n), reset\n"
        "before each step; '> cap': the step passed the cap (the rest of its case did not run).\n"
        "exp: least-squares slope of log time against log T (or n), over the cases that finished\n"
        "and took > 10 ms. firing: circuit_firing of the four circuits (count=4, ifp 1); ctrb,\n"
        "obsv, general: symbolic + numeric realizations of G2; check: check_realization of the\n"
        "six; compat: the four structures and check_compatibility on DelayGraph.chain.\n"
        f"total {time.perf_counter() - start:.0f} s"
    )


if __name__ == "__main__":
    main()
