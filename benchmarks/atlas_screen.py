"""Time the atlas's exact refutation screen at orders 3 and 4 beside the previous method, in the same run.

symctl: ``symctl.atlas(3)`` (every pattern) and ``symctl.atlas(4)`` (its sparsest classes:
12 entries, circuits of at most 3 neurons) on 2 dask workers; a pattern of 3n entries of odd
generic degree goes to the odd-degree proof (a Groebner basis over Q(a, c)), and every other
one that no proof or structural rule settles is screened exactly (real-fibre counts at 30
rational targets per region of poles and zeros at order 3, 5 at order 4).

Previous method (measured in the same run, on the same workers): the revision before the
screen (``--baseline``, by default 8b675c7): one Krawczyk-certified witness per region, and
an exact solve of the fibre only where that search failed (order 3). Each search runs in a
fresh interpreter, the two methods one after the other for each order. The screen's own
cost is timed in this process on a sample of the patterns it screened.

Run: python benchmarks/atlas_screen.py [--baseline REV] [--orders 3 4]
"""

from __future__ import annotations

import argparse
import json
import os
import random
import subprocess
import sys
import tarfile
import tempfile
import time
from io import BytesIO
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SAMPLE = 12

DRIVER = """
import json, sys, time
import symctl

if __name__ == "__main__":
    n = int(sys.argv[1])
    start = time.perf_counter()
    A = symctl.atlas(n, workers=2)
    seconds = time.perf_counter() - start
    status = [c.status for c in A.classes]
    screened = sorted(
        p.mask
        for c in A.classes
        for p, ev in c.pattern_evidence.items()
        if "screened" in ev.details
    )
    print(json.dumps({
        "seconds": seconds,
        "decided": A.stats["canonical"] - A.stats["skipped"],
        "universal": status.count("universal"),
        "refuted": status.count("not universal"),
        "conjectured": status.count("conjectured"),
        "undecided": status.count("not decided"),
        "screened": screened,
        "odd": sum(
            ev.method == "odd degree" for c in A.classes for ev in c.pattern_evidence.values()
        ),
    }))
"""


def _search(n: int, code: Path, driver: Path) -> dict:
    env = {**os.environ, "PYTHONPATH": str(code)}
    run = subprocess.run(
        [sys.executable, str(driver), str(n)],
        cwd=code,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(run.stdout.strip().splitlines()[-1])


def _baseline(rev: str, into: Path) -> Path:
    archive = subprocess.run(
        ["git", "-C", str(ROOT), "archive", rev, "symctl"], capture_output=True, check=True
    )
    with tarfile.open(fileobj=BytesIO(archive.stdout)) as tar:
        tar.extractall(into, filter="data")
    return into


def _screen_cost(n: int, masks: list[int]) -> tuple[int, float, float]:
    """Patterns timed, mean and largest seconds of one screen (in this process, one core)."""
    from symctl.circuitatlas.pattern import Pattern
    from symctl.circuitatlas.screen import screen

    chosen = random.Random(n).sample(masks, min(SAMPLE, len(masks)))
    times = []
    for mask in chosen:
        start = time.perf_counter()
        screen(Pattern(n, mask))
        times.append(time.perf_counter() - start)
    return len(times), sum(times) / max(len(times), 1), max(times, default=0.0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--baseline", default="8b675c7")
    parser.add_argument("--orders", nargs="*", type=int, default=[3, 4])
    args = parser.parse_args()
    print(f"circuit atlas on 2 dask workers ({os.cpu_count()} cores); classes by verdict\n")
    print(
        "| order | method | seconds | orbits decided | proved universal | refuted | conjectured "
        "| not decided | patterns screened | odd-degree proofs |"
    )
    print("|" + "---|" * 10, flush=True)
    costs = []
    with tempfile.TemporaryDirectory() as tmp:
        driver = Path(tmp) / "driver.py"
        driver.write_text(DRIVER)
        before = _baseline(args.baseline, Path(tmp) / "baseline")
        for n in args.orders:
            for label, code in ((f"previous ({args.baseline})", before), ("exact screen", ROOT)):
                r = _search(n, code, driver)
                screened = len(r["screened"]) if code is ROOT else "-"
                odd = r.get("odd", "-") if code is ROOT else "-"
                print(
                    f"| {n} | {label} | {r['seconds']:.1f} | {r['decided']} | {r['universal']} | "
                    f"{r['refuted']} | {r['conjectured']} | {r['undecided']} | {screened} | {odd} |",
                    flush=True,
                )
            costs.append((n, _screen_cost(n, r["screened"])))
    print()
    for n, (count, mean, worst) in costs:
        print(
            f"order {n}: the screen of one pattern, {count} sampled screened patterns timed on "
            f"one core: mean {1000 * mean:.0f} ms, largest {1000 * worst:.0f} ms"
        )


if __name__ == "__main__":
    main()
