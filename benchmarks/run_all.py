"""Run every benchmark and write ``docs/benchmarks.md``: what each measures and its table.

Each script prints a table with its baseline measured in the same run (naive SymPy,
python-control, brute force, the previous method). This runs them one after the
other, as ``make bench`` does, and writes the page of the documentation site from
what they printed: each script's purpose (the first paragraph of its docstring),
the command, and its output, under a heading of the machine and the revision.
The page is replaced only when it is complete (a temporary file, then
``os.replace``); a script that fails is reported on the page and in the exit code.

Run:  python benchmarks/run_all.py [--out docs/benchmarks.md] [--only NAME ...]
"""

from __future__ import annotations

import argparse
import ast
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
# the scripts in the order of the pipeline, with their arguments
SCRIPTS = (
    ("core.py", ()),
    ("checker.py", ()),
    ("compatibility.py", ()),
    ("simulate.py", ()),
    ("lqg.py", ()),
    ("paper.py", ()),
    ("scaling.py", ()),
    ("mimo.py", ()),
    ("atlas.py", ()),
    ("atlas_screen.py", ("--orders", "3")),  # order 4: hours on 2 cores; run it by hand
    ("examples.py", ()),
    ("long_delays.py", ()),
    ("dale.py", ("--workers", "2")),
    ("fit.py", ()),
    ("figures.py", ()),
    ("spiking.py", ()),
)


def purpose(script: Path) -> str:
    """The first paragraph of the script's docstring."""
    doc = ast.get_docstring(ast.parse(script.read_text())) or ""
    return doc.split("\n\n")[0].replace("\n", " ").strip()


def revision() -> str:
    run = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], cwd=HERE, capture_output=True, text=True
    )
    return run.stdout.strip() or "unknown"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=HERE.parent / "docs" / "benchmarks.md")
    parser.add_argument("--only", nargs="*", help="script names to run (default: all)")
    args = parser.parse_args(argv)
    chosen = [s for s in SCRIPTS if not args.only or s[0].removesuffix(".py") in args.only]
    sections, failed = [], []
    for name, extra in chosen:
        print(f"== benchmarks/{name} {' '.join(extra)}", flush=True)
        start = time.perf_counter()
        run = subprocess.run(
            [sys.executable, str(HERE / name), *extra], capture_output=True, text=True
        )
        took = time.perf_counter() - start
        print(run.stdout, end="", flush=True)
        if run.returncode:
            failed.append(name)
            print(run.stderr, file=sys.stderr)
        status = "" if run.returncode == 0 else f" **failed (exit {run.returncode})**"
        sections.append(
            f"## `benchmarks/{name}`\n\n{purpose(HERE / name)}\n\n"
            f"`python benchmarks/{name} {' '.join(extra)}`".rstrip()
            + f" ({took:.0f} s){status}:\n\n```\n{run.stdout.rstrip()}\n```\n"
        )
    head = (
        "# Benchmarks\n\n"
        "Written by `make bench` (`benchmarks/run_all.py`): every table below was printed by its\n"
        "script in one run, each against its baseline measured in the same run. Machine: "
        f"{os.cpu_count()} cores, Python {platform.python_version()}, {platform.machine()}; "
        f"revision {revision()}; {time.strftime('%Y-%m-%d')}. Times are of a shared machine:\n"
        "compare the columns of one table, not tables of different runs.\n"
    )
    text = "\n".join([head, *sections])
    tmp = args.out.with_name(f".{args.out.name}.tmp")
    tmp.write_text(text)
    os.replace(tmp, args.out)
    print(f"wrote {args.out}" + (f"; failed: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
