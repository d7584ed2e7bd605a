"""The circuit drawings' curve router: its candidate curves judged in batches, against one by one.

For ``symctl paper`` (T = 2) and every example model: the derivation once, then each circuit
figure of the report (``circuit_*``, ``simplified_*``) made in this process (best of 2), with the
router as it is (:func:`symctl.plotting.circuit_layout.route`: the curves a link may take are
generated lazily and judged against the obstacles in batches of 4, 16, 64, ... by
``layered.hits_many``) and with the previous method in the same run (each candidate judged
alone by ``layered.hits``, the loop below). Both must choose the same curves: the script
stops if a single coordinate differs. Times are CPU seconds of this process (on a shared
machine wall times vary twofold). Each figure is made once untimed first, so that both runs
find its texts typeset and measured (cached) and differ only in the routing.

Run: ``python benchmarks/circuit_routes.py`` (about 1 min on 2 quiet cores).
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from unittest import mock

import numpy as np

from symctl import derive, derive_paper, load_model
from symctl.plotting import circuit_layout, layered

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def route_one_by_one(arcs, pos, col, radius, labels, obstacles, *, search=True):
    """The previous router: the same candidates, in the same order, each judged alone."""
    DOT, PAIR, SWING = circuit_layout.DOT, circuit_layout._PAIR, circuit_layout._SWING
    clear, labelled, up = True, True, 1.0
    chosen, heights_of, ports, lines = [], {}, {}, []
    for a, b, s in arcs:
        pa, pb = np.asarray(pos[a], float), np.asarray(pos[b], float)
        ra, rb = radius.get(a, DOT), radius.get(b, DOT)
        forward = col[b] > col[a]
        adjacent = forward and col[b] == col[a] + 1
        if adjacent:
            prefer = 1.0
        elif forward:
            prefer, up = up, -up
        else:
            prefer = -1.0
        taken = heights_of.setdefault(frozenset((a, b)), [])
        size = labels.get(s) if s is not None else None
        apart = max(PAIR, size[1] + 0.03) if size else PAIR
        if search:
            tiers = [
                (layered.bulges(adjacent, prefer, 0.16 if forward else 0.22, 0.1, 24), SWING, 3),
                (layered.bulges(adjacent, prefer, 0.12, 0.08, 40), 2 * SWING, 8),
            ]
        else:
            tiers = [
                ([0.0] if adjacent else [prefer * (0.08 + 0.06 * abs(col[b] - col[a]))], SWING, 3)
            ]
        used = ports.setdefault(b, []) if b in radius else []
        others = np.concatenate(lines) if lines else None
        pick, fallback = None, None
        u = (pb - pa) / max(float(np.hypot(*(pb - pa))), 1e-12)
        qa, qb = tuple(pa + ra * u), tuple(pb - rb * u)
        for cands, swing, count in tiers:
            cands = [h for h in cands if all(abs(h - t) >= apart for t in taken)] or [
                (max(map(abs, taken)) + apart) * prefer
            ]
            for h in cands:
                curve = layered.bridge(qa, qb, h)
                natural = math.atan2(curve[2][1] - pb[1], curve[2][0] - pb[0])
                angles = layered.end_angles(natural, used, rb, swing, count)
                for angle in angles or [natural]:
                    drawn = layered.trimmed(curve, pa, ra, pb, rb + layered.TIP, angle)
                    nh = layered.hits(layered.bezier_points(drawn), obstacles, {a, b})
                    nh += not angles
                    if fallback is None or nh < fallback[0]:
                        fallback = (nh, h, drawn, angle)
                    if nh:
                        continue
                    where = layered.place_label(drawn, size, obstacles, others) if size else None
                    if size is None or where is not None:
                        pick = (h, drawn, where, angle)
                        break
                if pick is not None or not search:
                    break
            if pick is not None:
                break
        if pick is None:
            nh, h, drawn, angle = fallback
            clear = clear and nh == 0
            where = None
            if size is not None:
                where = layered.place_label(drawn, size, obstacles, others)
                labelled = labelled and where is not None
                circles = layered.Obstacles(
                    obstacles.centres, obstacles.radii, obstacles.keys, np.zeros((0, 4)), ()
                )
                where = where or layered.place_label(drawn, size, circles, others)
                where = where or tuple(float(v) for v in layered.bezier_points(drawn, [0.5])[0])
            pick = (h, drawn, where, angle)
        h, drawn, where, angle = pick
        taken.append(h)
        used.append(angle)
        chosen.append((h, drawn, where))
        lines.append(layered.bezier_points(drawn))
        if where is not None:
            obstacles = obstacles.with_box(layered.box(*where, size))
    return chosen, clear, labelled


def timed(res, name: str, router) -> tuple[float, list]:
    """CPU seconds to make the figure ``name`` with ``router``, and every route it chose."""
    routes = []

    def recording(*args, **kw):
        out = router(*args, **kw)
        routes.append(out)
        return out

    with mock.patch.object(circuit_layout, "route", recording):
        start = time.process_time()
        res.figure(name)
        return time.process_time() - start, routes


def main() -> None:
    import matplotlib.pyplot as plt

    cases = [("paper", derive_paper)] + [
        (p.stem, lambda p=p: derive(load_model(p))) for p in sorted(EXAMPLES.glob("*.toml"))
    ]
    print("| model | figure | batched [s] | one by one [s] | speed-up |")
    print("|---|---|---:|---:|---:|")
    total_new = total_old = 0.0
    for label, make in cases:
        res = make()
        for name in res.figure_names():
            if not name.startswith(("circuit_", "simplified_")):
                continue
            res.figure(name)  # untimed: the texts typeset and measured (cached) for both
            (new, chosen), (old, before) = (
                min(timed(res, name, router) for _ in range(2))
                for router in (circuit_layout.route, route_one_by_one)
            )
            plt.close("all")
            if repr(chosen) != repr(before):
                raise SystemExit(f"{label} {name}: the two routers chose different curves")
            total_new, total_old = total_new + new, total_old + old
            print(f"| {label} | {name} | {new:.2f} | {old:.2f} | {old / max(new, 1e-9):.1f}x |")
    print(
        f"| all | (same curves everywhere) | {total_new:.2f} | {total_old:.2f} | "
        f"{total_old / total_new:.1f}x |"
    )


if __name__ == "__main__":
    main()
