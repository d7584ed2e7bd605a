"""Time check_compatibility on long cascades (chain graphs) and random general delay graphs.

Structures: k copies of the paper's controller G3 G2 G1 (controllable canonical G2,
22 signals each) in series, from about 10^2 to 10^5 signals, plus the IFP structure.
Graphs: the neuromuscular chain [1, 1], a long unit chain with one step per section
(2k steps), and random general graphs (6 vertices, edges with delays 0..2).
Brute force (every assignment, definition's E~) runs in the same process where it
finishes (at most 2e6 assignments); elsewhere the table shows its size instead.

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
                (label, len(S), gname, "ok" if r.ok else "no", t, method, brute(S, g), t_build)
            )
    columns = [
        ("structure", ">16"),
        ("signals", ">7"),
        ("graph", ">12"),
        ("verdict", ">7"),
        ("check [s]", ">9"),
        ("method", "<28"),
        ("brute force [s]", ">15"),
        ("build [s]", ">9"),
    ]
    head = " | ".join(f"{name:{spec}}" for name, spec in columns)
    print(head)
    print("-" * len(head))
    for row in rows:
        cells = [*row[:4], f"{row[4]:.4f}", row[5], row[6], f"{row[7]:.3f}"]
        print(" | ".join(f"{c:{spec}}" for c, (_, spec) in zip(cells, columns, strict=True)))
    print("check = check_compatibility (decision + witness or certificate); brute force: time and")
    print("verdict where it finishes, else (vertices^free signals) assignments it would need.")


if __name__ == "__main__":
    main()
