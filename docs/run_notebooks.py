"""Execute the notebooks of ``notebooks/`` and store them with their outputs (``make notebooks``).

The notebooks are committed with their outputs, so that a reader browsing the repository
sees the formulas and figures. Each runs top to bottom in a fresh kernel, in a temporary
folder (the notebooks write files), with a fixed hash seed, no timing metadata and each
cell's printing stored as one output per stream, so that running it again changes the
stored outputs only where the code's results change (the notebooks seed their randomness).
A notebook whose run raises an error is not written, and the command exits with 1.
``tests/test_notebooks.py`` runs the notebooks the same way (:func:`execute`).

Usage: ``python docs/run_notebooks.py [NOTEBOOK ...]`` (default: every notebook).
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import nbformat
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
"""Every notebook of the repository."""
TIMEOUT = 600
"""Seconds one cell may take."""
KERNEL_ENV = {"PYTHONHASHSEED": "0"}
"""The kernel's environment beyond the caller's: sets and dicts print in one order."""


def execute(path: Path, cwd: Path) -> nbformat.NotebookNode:
    """The notebook at ``path``, run top to bottom in a fresh kernel whose folder is ``cwd``."""
    nb = nbformat.read(path, as_version=4)
    os.environ.update(KERNEL_ENV)  # the kernel inherits it
    NotebookClient(
        nb,
        timeout=TIMEOUT,
        kernel_name="python3",
        record_timing=False,
        resources={"metadata": {"path": str(cwd)}},
    ).execute()
    return coalesce_streams(nb)


def coalesce_streams(nb: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """``nb`` with each run of consecutive outputs to one stream (stdout, stderr) made one
    output: how a cell's printing is cut into outputs depends on timing, not on the code."""
    for cell in nb.cells:
        merged: list = []
        for out in cell.get("outputs", []):
            last = merged[-1] if merged else None
            if (
                last is not None
                and out.output_type == last.output_type == "stream"
                and out.name == last.name
            ):
                last.text += out.text
            else:
                merged.append(out)
        if cell.cell_type == "code":
            cell.outputs = merged
    return nb


def errors(nb: nbformat.NotebookNode) -> list[str]:
    """The errors raised by the notebook's cells, as ``"cell N: Name: message"``."""
    return [
        f"cell {i}: {out.get('ename')}: {out.get('evalue')}"
        for i, cell in enumerate(nb.cells)
        if cell.cell_type == "code"
        for out in cell.get("outputs", [])
        if out.output_type == "error"
    ]


def main(argv: list[str]) -> int:
    paths = [Path(a).resolve() for a in argv] or NOTEBOOKS
    failed = 0
    for path in paths:
        start = time.perf_counter()
        with tempfile.TemporaryDirectory(prefix="symctl-notebook-") as cwd:
            nb = execute(path, Path(cwd))
        found = errors(nb)
        seconds = time.perf_counter() - start
        if found:
            failed += 1
            print(f"{path.name}: not written, {len(found)} error(s): " + "; ".join(found))
            continue
        nbformat.validate(nb)
        nbformat.write(nb, path)
        print(f"{path.name}: executed and stored ({seconds:.0f} s)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
