"""Long delays: a forearm at T = 8 and `symctl paper` at T = 20, beside the previous revision.

Each command runs in a fresh interpreter (as a user would), with its figures and PDF, and
prints its wall time, its CPU time (user + system, with the figure workers: on a shared
machine the wall time also counts the other processes) and the size of its
``results.json`` and ``derivation.tex``; the same commands run on the package as it was at
revision ``--before`` (extracted from git in the same run, as benchmarks/paper.py does),
stopped after ``--cap`` seconds. The forearm (2 states, one torque input, 4 + 4 steps of
delay on a graph of two 20 ms axons) is ``tests/data/forearm_long_delays.toml``.
Targets: the forearm under 20 s with ``results.json`` under 200 KB; ``symctl paper
--sensor-delay 10 --actuator-delay 10`` under 30 s.

Run: ``python benchmarks/long_delays.py`` (options: ``--before``, ``--cap``).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from paper import SYMCTL, extract

FOREARM = Path(__file__).resolve().parents[1] / "tests" / "data" / "forearm_long_delays.toml"
CASES = (
    ("forearm T = 8 (symctl derive)", ["derive", str(FOREARM)], 20.0),
    (
        "paper T = 20 (symctl paper)",
        ["paper", "--sensor-delay", "10", "--actuator-delay", "10"],
        30.0,
    ),
)


def run(args: list[str], out: Path, cap: float, env: dict | None = None) -> tuple:
    """``(wall, cpu, results.json KB, derivation.tex KB)``; wall None past ``cap`` seconds."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    try:
        subprocess.run(
            [*SYMCTL, *args, "--out", str(out)],
            check=True,
            capture_output=True,
            env=env,
            cwd="/",
            timeout=cap,
        )
        wall = time.perf_counter() - start
    except subprocess.TimeoutExpired:
        wall = None
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    sizes = [
        (out / f).stat().st_size / 1000 if wall else None
        for f in ("results.json", "derivation.tex")
    ]
    return wall, cpu, *sizes


def _cell(value, fmt: str) -> str:
    return "> cap" if value is None else format(value, fmt)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", default="87fb0d8", help="The git revision to compare with.")
    parser.add_argument("--cap", type=float, default=300.0, help="Seconds before a run stops.")
    args = parser.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="symctl-long-"))
    old = extract(args.before, tmp / "before")
    print(f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f} at the start")
    print(
        f"| {'case':<30} | {'package':<8} | wall [s] | CPU [s] | results.json [KB] | derivation.tex [KB] |"
    )
    print(f"|{'-' * 32}|{'-' * 10}|---------:|--------:|------------------:|--------------------:|")
    verdicts = []
    for name, cmd, target in CASES:
        for label, env in ((args.before, old), ("now", None)):
            wall, cpu, js, tex = run(cmd, tmp / "out", args.cap, env)
            print(
                f"| {name:<30} | {label:<8} | {_cell(wall, '8.1f')} | {cpu:7.1f} | "
                f"{_cell(js, '17.0f')} | {_cell(tex, '19.0f')} |",
                flush=True,
            )
        met = wall is not None and wall < target
        verdicts.append(
            f"{name} < {target:.0f} s: {_cell(wall, '.1f')} s {'met' if met else 'MISSED'}"
        )
        if name.startswith("forearm"):
            small = js is not None and js < 200
            verdicts.append(
                f"its results.json < 200 KB: {_cell(js, '.0f')} KB {'met' if small else 'MISSED'}"
            )
    print(f"load average {os.getloadavg()[0]:.1f} at the end")
    print("targets: " + "; ".join(verdicts))


if __name__ == "__main__":
    sys.exit(main())
