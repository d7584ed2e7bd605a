"""Time check_compatibility on long cascades (chain graphs) and random general delay graphs.

Structures: k copies of the paper's controller G3 G2 G1 (controllable canonical G2,
22 signals each) in series, from about 10^2 to 10^5 signals, plus the IFP structure.
Graphs: the neuromuscular chain [1, 1], a long unit chain with one step per section
(2k steps), and random general graphs (6 vertices, edges with delays 0..2).
Brute force (every assignment, definition's E~) runs in the same process where it
finishes (at most 2e6 assignments); elsewhere the table shows its size instead.
OR-Tools CP-SAT (when installed: pip install ortools) solves the same constraint
problem in the same run: one variable per signal (its vertex), one table constraint
per wire (the vertex pairs with E <= the wire's delay), the inputs and outputs pinned.

The second table is MIMO: parallel copies of the G3 G2 G1 structure of a 2-input,
4-state plant (4 inputs, 2 outputs, 128 signals per copy), about 10^4 signals, on
graphs with parallel pathways (receptor -> spinal -> muscle beside receptor ->
cortex -> spinal), one sensor vertex per measured signal and one actuator vertex
per muscle, or all of them grouped.

Run: python benchmarks/compatibility.py
"""

from __future__ import annotations

import time

import numpy as np

from symctl import (
    DelayGraph,
    ParameterError,
    Structure,
    brute_force_compatibility,
    check_compatibility,
    controllable_canonical,
    controller_tf,
    factor,
    ifp_structure,
)


def paper_controller() -> Structure:
    f = factor(controller_tf(2))
    return Structure.from_factorization(f, controllable_canonical(f.G2))


def random_graph(rng: np.random.Generator, n: int = 6) -> DelayGraph:
    while True:
        edges = [
            (i, j, int(rng.integers(0, 3)))
            for i in range(1, n + 1)
            for j in range(1, n + 1)
            if i != j and rng.random() < 0.35
        ]
        try:
            return DelayGraph.from_edges(n, edges)
        except ParameterError:
            continue


def timed(fn):
    start = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - start


def cp_sat(S, g) -> str:
    """The same problem in OR-Tools CP-SAT: time and verdict (or why it did not run)."""
    try:
        from ortools.sat.python import cp_model
    except ImportError:
        return "(no ortools)"
    if len(S) > 50_000:
        return "(skipped)"
    start = time.perf_counter()
    cs = S.signal_graph
    E, N = g.E, g.n
    model = cp_model.CpModel()
    x = [model.new_int_var(0, N - 1, name) for name in cs.names]
    at_in, at_out = g.pins(len(cs.inputs), len(cs.outputs))
    for s, v in (*zip(cs.inputs, at_in, strict=True), *zip(cs.outputs, at_out, strict=True)):
        model.add(x[s] == v - 1)
    tables: dict[int, list] = {}
    for a, b, w in cs.wires:
        if w not in tables:
            tables[w] = [(i, j) for i in range(N) for j in range(N) if E[i, j] <= w]
        model.add_allowed_assignments([x[a], x[b]], tables[w])
    solver = cp_model.CpSolver()
    solver.parameters.num_workers = 2
    status = solver.solve(model)
    t = time.perf_counter() - start
    ok = status in (cp_model.OPTIMAL, cp_model.FEASIBLE)
    return f"{t:.4f} {'ok' if ok else 'no' if status == cp_model.INFEASIBLE else '?'}"


def mimo_unit() -> Structure:
    from symctl import augment

    A = [[1, 0.01, 0, 0], [-0.4, 0.96, 0.005, -0.005], [0, 0, 0.6, 0], [0, 0, 0, 0.6]]
    B = [[0, 0], [0.01, -0.01], [4.6, 0], [0, 4.6]]
    f = factor(controller_tf(augment((A, B), 1, 1)), 1, 1)
    return Structure.from_factorization(f, controllable_canonical(f.G2))


def pathways(spinal: int, cortical: int, per_channel: bool) -> DelayGraph:
    """v1..v4 receptors, v5 spinal, v6 cortex, v7 v8 muscles."""
    edges = [(k, 5, spinal) for k in range(1, 5)] + [(k, 6, cortical) for k in range(1, 5)]
    edges += [(6, 5, 1), (5, 7, 1), (5, 8, 1)]
    if per_channel:
        return DelayGraph.from_edges(8, edges, sensors=[1, 2, 3, 4], actuators=[7, 8])
    hub = [(1, k, 0) for k in range(2, 5)] + [(7, 8, 0), (8, 7, 0)]
    return DelayGraph.from_edges(8, edges + hub, sensors=[1], actuators=[8])


def mimo_table() -> None:
    unit = mimo_unit()
    print()
    head = (
        f"{'MIMO structure':>16} | {'signals':>7} | {'graph':>30} | {'verdict':>7} | "
        f"{'check [s]':>9} | {'cp-sat [s]':>10}"
    )
    print(head)
    print("-" * len(head))
    for copies in (1, 10, 80):
        S = Structure.parallel(*[unit] * copies)
        for gname, g in (
            ("per channel, spinal 1 cortex 1", pathways(1, 1, True)),
            ("grouped, spinal 1 cortex 1", pathways(1, 1, False)),
            ("per channel, spinal 2 cortex 1", pathways(2, 1, True)),
        ):
            r, t = timed(lambda S=S, g=g: check_compatibility(S, g))
            print(
                f"{copies:>3} x G3G2G1 2in | {len(S):>7} | {gname:>30} | "
                f"{'ok' if r.ok else 'no':>7} | {t:>9.4f} | {cp_sat(S, g):>10}"
            )
    print(
        "check = check_compatibility (AC + backtracking here; decision + witness or certificate);"
    )
    print("cp-sat = OR-Tools CP-SAT on the same constraints, model building included, 2 workers.")


def brute(S, g) -> str:
    try:
        r, t = timed(lambda: brute_force_compatibility(S, g))
    except ParameterError:
        free = len(S) - len(S.inputs) - len(S.outputs)
        return f"({g.n}^{free})"
    return f"{t:.4f} {'ok' if r.ok else 'no'}"


def main() -> None:
    unit = paper_controller()
    rng = np.random.default_rng(0)
    rows = []
    cases = [("IFP T=2", ifp_structure(2), 0)]
    for copies in (1, 5, 46, 455, 4546):
        S, t_build = timed(lambda copies=copies: Structure.series(*[unit] * copies))
        cases.append((f"{copies} x G3G2G1", S, t_build))
    for label, S, t_build in cases:
        graphs = [
            ("chain [1,1]", DelayGraph.chain([1, 1])),
            ("chain 1x10", DelayGraph.chain([1] * 10)),
        ]
        if len(S) <= 20_000:
            graphs.append(("random n=6", random_graph(rng)))
        for gname, g in graphs:
            r, t = timed(lambda S=S, g=g: check_compatibility(S, g))
            method = r.method.split(" (")[0] if r.method.startswith("search") else r.method
            method = method.replace(
                "search: arc consistency + backtracking", "search: AC + backtracking"
            )
            rows.append(
                (
                    label,
                    len(S),
                    gname,
                    "ok" if r.ok else "no",
                    t,
                    method,
                    brute(S, g),
                    cp_sat(S, g),
                    t_build,
                )
            )
    columns = [
        ("structure", ">16"),
        ("signals", ">7"),
        ("graph", ">12"),
        ("verdict", ">7"),
        ("check [s]", ">9"),
        ("method", "<28"),
        ("brute force [s]", ">15"),
        ("cp-sat [s]", ">10"),
        ("build [s]", ">9"),
    ]
    head = " | ".join(f"{name:{spec}}" for name, spec in columns)
    print(head)
    print("-" * len(head))
    for row in rows:
        cells = [*row[:4], f"{row[4]:.4f}", row[5], row[6], row[7], f"{row[8]:.3f}"]
        print(" | ".join(f"{c:{spec}}" for c, (_, spec) in zip(cells, columns, strict=True)))
    print("check = check_compatibility (decision + witness or certificate); brute force: time and")
    print("verdict where it finishes, else (vertices^free signals) assignments it would need;")
    print("cp-sat = OR-Tools CP-SAT on the same constraints (model building included).")
    mimo_table()


if __name__ == "__main__":
    main()
