"""Every notebook in notebooks/ executes top to bottom, and is stored with its outputs.

The notebooks are committed with their outputs (``make notebooks``, which runs
``docs/run_notebooks.py``), so that a reader browsing the repository sees formulas and
figures; these tests run each one again the same way, and read the stored outputs.
"""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("run_notebooks", ROOT / "docs" / "run_notebooks.py")
run_notebooks = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(run_notebooks)
NOTEBOOKS = run_notebooks.NOTEBOOKS

LOCAL_PATH = re.compile(r"(/tmp/|/work/|/home/|/root/|/Users/|[A-Z]:\\\\)")
"""A path of the machine that ran the notebook: never stored."""


def _code(path: Path) -> list:
    return [c for c in nbformat.read(path, as_version=4).cells if c.cell_type == "code"]


def _texts(cell) -> list[str]:
    """The text of each output of a cell (streams, plain and LaTeX reprs, errors)."""
    found = []
    for out in cell.get("outputs", []):
        data = out.get("data", {})
        found += [out.get("text", ""), data.get("text/plain", ""), data.get("text/latex", "")]
        found += out.get("traceback", [])
    return ["".join(t) if isinstance(t, list) else t for t in found if t]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs(path, tmp_path):
    nb = run_notebooks.execute(path, tmp_path)
    assert not run_notebooks.errors(nb)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_is_stored_executed_top_to_bottom_with_outputs(path):
    cells = _code(path)
    assert [c.execution_count for c in cells] == list(range(1, len(cells) + 1)), path.name
    assert any(c.get("outputs") for c in cells), path.name
    assert not run_notebooks.errors(nbformat.read(path, as_version=4)), path.name


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_stored_figures_are_shown_not_printed(path):
    """A figure is an image in the notebook, never its repr ``<Figure size ...>`` (what a
    notebook that forces a non-interactive backend, or lacks ``%matplotlib inline``, shows)."""
    for cell in _code(path):
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            text = "".join(data.get("text/plain", "")) + "".join(out.get("text", ""))
            if "<Figure size" in text:
                assert "image/png" in data, (path.name, cell.source[:80])


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_stored_outputs_hold_no_local_path(path):
    for cell in _code(path):
        for text in _texts(cell):
            assert not LOCAL_PATH.search(text), (path.name, cell.source[:80], text[:200])
