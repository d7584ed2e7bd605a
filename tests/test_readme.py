"""The README's Python examples run, in order, in one fresh namespace (as a reader pastes them).

So do the user guides' examples (docs/guide/), page after page in one namespace of their own.
"""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib
import pytest

README = Path(__file__).resolve().parent.parent / "README.md"
GUIDES = [
    README.parent / "docs" / "guide" / f"{name}.md"
    for name in ("api", "atlas", "dale", "fit", "noise")
]


def _blocks(*pages: Path) -> list[tuple[str, str]]:
    return [
        (f"{page.name} python block {k + 1}", code)
        for page in pages
        for k, code in enumerate(re.findall(r"```python\n(.*?)```", page.read_text(), re.S))
    ]


@pytest.mark.slow
@pytest.mark.parametrize("pages", [[README], GUIDES], ids=["README", "guides"])
def test_readme_python_blocks_run(tmp_path, monkeypatch, pages):
    matplotlib.use("Agg")
    blocks = _blocks(*pages)
    assert len(blocks) >= 2
    monkeypatch.chdir(tmp_path)  # the examples write g3g2g1.png and out/paper
    # res.write("out/paper") draws the report's 20 figures: here dots (forked workers inherit
    # it), as the figures are drawn, saved and checked in tests/report; the rest is real
    from matplotlib.figure import Figure

    from symctl.report import figures

    monkeypatch.setattr(figures, "make_figure", lambda res, name: Figure(figsize=(1, 1)))
    (tmp_path / "examples").symlink_to(README.parent / "examples")  # they read examples/data
    namespace: dict = {"__name__": "__main__"}
    for name, code in blocks:
        code = code.replace("[...]", "[]")  # the elided argument of symctl.latex.document
        exec(compile(code, name, "exec"), namespace)
    if pages == GUIDES:
        assert (tmp_path / "g3g2g1.png").is_file()
        assert (tmp_path / "out" / "paper" / "results.json").is_file()


def test_the_papers_figures_are_cited_by_number_not_by_latex_label():
    """A reader has the paper's PDF, not its LaTeX: "Fig. 9", never "Fig. full_diagram"."""
    from symctl.report.reference import FIGURES

    root = README.parent
    texts = [
        README,
        *sorted(p for p in (root / "docs").rglob("*.md") if "_build" not in p.parts),
        *sorted((root / "notebooks").glob("*.ipynb")),
    ]
    labels = "|".join(FIGURES)
    pattern = re.compile(rf"Figs?\.\s+(?:[\w ,]*?\b)?({labels})\b")
    found = [f"{p.name}: {m.group(0)}" for p in texts for m in pattern.finditer(p.read_text())]
    assert not found, found


def test_the_readme_is_a_short_front_door_without_development_history():
    """The README points to the docs; the repository's prose never cites its own issues."""
    text = README.read_text()
    assert len(text.splitlines()) < 250
    root = README.parent
    prose = [README, *(p for p in (root / "docs").rglob("*.md") if "_build" not in p.parts)]
    found = [
        f"{p.relative_to(root)}: {m.group(0)}"
        for p in prose
        for m in re.finditer(r"\bissues? \d+", p.read_text(), re.I)
    ]
    assert not found, found
