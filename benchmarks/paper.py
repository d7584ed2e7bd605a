"""The whole `symctl paper` and `symctl derive` commands, the figures' share, and the import time.

Runs each command in a fresh interpreter (as a user would) ``--repeat`` times and
reports the fastest wall time and the fastest CPU time (user + system, of the command
and its figure workers: on a shared machine the wall time also counts the other
processes, the CPU time does not). Baselines measured in the same run:

* the bare interpreter, and importing the libraries symctl stands on;
* ``symctl paper`` without figures (the derivation, ``results.json`` and the documents);
* the previous way of writing the figures: every figure in all three formats (PDF, SVG
  and PNG) with matplotlib's own font subsetting, which reads each whole font file for
  each figure (the command run with :func:`symctl.plotting.vector._fast_subsets`
  switched off and ``--formats pdf,png,svg``);
* the package as it was at revision ``--before`` (default 8b675c7: PNGs drawn a second
  time by matplotlib's Agg, a cache of typeset math per renderer, the figure pool forked
  after the derivation), extracted from git in the same run and run on the same
  interpreter, for ``symctl paper`` and each example;
* each example model with ``symctl derive --no-figures``, beside the same command with
  its figures (the ratio is the figures' cost).

Targets: ``symctl paper`` (T = 2, figures and PDF) under 6 s on 2 cores; ``symctl derive``
on every example at most 1.5 times its time without figures; ``import symctl`` under 0.1 s.

Run: ``python benchmarks/paper.py`` (options: ``--repeat``, ``--no-examples``).
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SYMCTL = [sys.executable, "-m", "symctl.cli"]
BEFORE = [
    sys.executable,
    "-c",
    "import contextlib, sys, symctl.plotting.vector as v; "
    "v._fast_subsets = contextlib.nullcontext; "  # matplotlib's subsetting, as before
    "from symctl.cli import main; sys.exit(main(sys.argv[1:]))",
]
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def extract(rev: str, into: Path) -> dict:
    """The environment that runs the package as it was at git revision ``rev``."""
    repo = Path(__file__).resolve().parents[1]
    archive = subprocess.run(
        ["git", "-C", str(repo), "archive", rev, "symctl"], check=True, capture_output=True
    ).stdout
    into.mkdir(parents=True)
    subprocess.run(["tar", "-x", "-C", str(into)], input=archive, check=True)
    return {**os.environ, "PYTHONPATH": str(into)}


def best(cmd: list[str], repeat: int, env: dict | None = None) -> tuple[float, float]:
    """The fastest wall time and the fastest CPU time of ``repeat`` runs of ``cmd`` [s]."""
    walls, cpus = [], []
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        # from the root folder: `python -m` puts the working folder first on the path
        subprocess.run(cmd, check=True, capture_output=True, env=env, cwd="/")
        walls.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return min(walls), min(cpus)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--no-examples", action="store_true", help="Only `symctl paper`.")
    parser.add_argument("--before", default="8b675c7", help="The git revision to compare with.")
    args = parser.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="symctl-bench-"))
    old = extract(args.before, tmp / "before")
    out = ["--out", str(tmp / "out")]
    py = [sys.executable, "-c"]
    rows = [
        ("python -c pass (interpreter start)", [*py, "pass"]),
        ("import symctl", [*py, "import symctl"]),
        (
            "import sympy, numpy, scipy, matplotlib, control (baseline)",
            [*py, "import sympy, numpy, scipy.linalg, matplotlib.figure, control"],
        ),
        (
            "symctl paper --no-figures (derivation, JSON, LaTeX, PDF)",
            [*SYMCTL, "paper", *out, "--no-figures"],
        ),
        (
            "before: symctl paper, PDF+SVG+PNG, matplotlib's font subsets",
            [*BEFORE, "paper", *out, "--formats", "pdf,png,svg"],
        ),
        (
            "symctl paper --formats pdf,png,svg (SVG on request)",
            [*SYMCTL, "paper", *out, "--formats", "pdf,png,svg"],
        ),
        (f"before ({args.before}): symctl paper", [*SYMCTL, "paper", *out], old),
        ("symctl paper (defaults: PDF+PNG figures, PDF)", [*SYMCTL, "paper", *out]),
    ]
    if not args.no_examples:
        for model in sorted(EXAMPLES.glob("*.toml")):
            derive = [*SYMCTL, "derive", str(model), *out]
            rows.append((f"symctl derive {model.name} --no-figures", [*derive, "--no-figures"]))
            rows.append((f"before ({args.before}): symctl derive {model.name}", derive, old))
            rows.append((f"symctl derive {model.name}", derive))
    pdflatex = shutil.which("pdflatex") is not None
    width = max(len(row[0]) for row in rows)
    print(
        f"best of {args.repeat} runs; {os.cpu_count()} CPUs, load average "
        f"{os.getloadavg()[0]:.1f} at the start; pdflatex {'found' if pdflatex else 'MISSING'}"
    )
    print(f"| {'command':<{width}} | wall [s] | CPU [s] |")
    print(f"|{'-' * (width + 2)}|---------:|--------:|")
    for name, cmd, *env in rows:
        wall, cpu = best(cmd, args.repeat, *env)
        print(f"| {name:<{width}} | {wall:8.2f} | {cpu:7.2f} |", flush=True)
    print(f"load average {os.getloadavg()[0]:.1f} at the end")
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
