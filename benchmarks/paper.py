"""The whole `symctl paper` command, and the import time of symctl.

Runs each command in a fresh interpreter (as a user would) ``--repeat`` times and
reports the fastest. Baselines measured in the same run: the bare interpreter,
importing the libraries symctl stands on (sympy, numpy, scipy, matplotlib,
control), and the command with its figures drawn in one process (``--jobs 1``).
Targets: the command on the defaults under 20 s on 2 cores; ``import symctl``
under 1 s.

Run: ``python benchmarks/paper.py`` (options: ``--repeat``).
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SYMCTL = [sys.executable, "-m", "symctl.cli"]


def best(cmd: list[str], repeat: int) -> float:
    """The fastest wall time of ``repeat`` runs of ``cmd`` [s]."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    out = Path(tempfile.mkdtemp(prefix="symctl-bench-"))
    py = [sys.executable, "-c"]
    paper = [*SYMCTL, "paper", "--out", str(out)]
    rows = [
        ("python -c pass (interpreter start)", [*py, "pass"]),
        ("import symctl", [*py, "import symctl"]),
        ("import symctl; symctl.MuscleModel", [*py, "import symctl; symctl.MuscleModel"]),
        (
            "import sympy, numpy, scipy, matplotlib, control (baseline)",
            [*py, "import sympy, numpy, scipy.linalg, matplotlib.figure, control"],
        ),
        ("symctl paper --no-figures --no-pdf", [*paper, "--no-figures", "--no-pdf"]),
        ("symctl paper --jobs 1 (figures in one process, baseline)", [*paper, "--jobs", "1"]),
        ("symctl paper (defaults: figures, PDF)", paper),
    ]
    pdflatex = shutil.which("pdflatex") is not None
    width = max(len(name) for name, _ in rows)
    print(f"best of {args.repeat} runs, wall time; pdflatex {'found' if pdflatex else 'MISSING'}")
    print(f"{'command':<{width}} | time [s]")
    print("-" * (width + 11))
    for name, cmd in rows:
        print(f"{name:<{width}} | {best(cmd, args.repeat):8.3f}", flush=True)
    shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    main()
