"""The README's Python examples run, in order, in one fresh namespace (as a reader pastes them)."""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib
import pytest

README = Path(__file__).resolve().parent.parent / "README.md"


@pytest.mark.slow
def test_readme_python_blocks_run(tmp_path, monkeypatch):
    matplotlib.use("Agg")
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    assert len(blocks) >= 5
    monkeypatch.chdir(tmp_path)  # the examples write g3g2g1.png and out/paper
    # res.write("out/paper") draws the report's 20 figures: here dots (forked workers inherit
    # it), as the figures are drawn, saved and checked in tests/report; the rest is real
    from matplotlib.figure import Figure

    from symctl.report import figures

    monkeypatch.setattr(figures, "make_figure", lambda res, name: Figure(figsize=(1, 1)))
    (tmp_path / "examples").symlink_to(README.parent / "examples")  # they read examples/data
    namespace: dict = {"__name__": "__main__"}
    for k, code in enumerate(blocks):
        code = code.replace("[...]", "[]")  # the elided argument of symctl.latex.document
        exec(compile(code, f"README.md python block {k + 1}", "exec"), namespace)
    assert (tmp_path / "g3g2g1.png").is_file()
    assert (tmp_path / "out" / "paper" / "results.json").is_file()


def test_the_papers_figures_are_cited_by_number_not_by_latex_label():
    """A reader has the paper's PDF, not its LaTeX: "Fig. 9", never "Fig. full_diagram"."""
    from symctl.report.reference import FIGURES

    root = README.parent
    texts = [
        README,
        *sorted((root / "docs").glob("*.md")),
        *sorted((root / "notebooks").glob("*.ipynb")),
    ]
    labels = "|".join(FIGURES)
    pattern = re.compile(rf"Figs?\.\s+(?:[\w ,]*?\b)?({labels})\b")
    found = [f"{p.name}: {m.group(0)}" for p in texts for m in pattern.finditer(p.read_text())]
    assert not found, found
