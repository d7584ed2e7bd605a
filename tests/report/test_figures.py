"""Writing the report's figures: the slowest drawn first, the paths in reading order."""

from __future__ import annotations

import gc

import pytest
from matplotlib.figure import Figure

from symctl import derive_paper
from symctl.report import figures


@pytest.fixture(scope="module")
def paper():
    return derive_paper(realizations=1)


def test_the_slowest_figures_are_drawn_first_and_the_paths_come_in_reading_order(
    paper, tmp_path, monkeypatch
):
    log = tmp_path / "drawn.txt"

    def quick(res, name):  # the forked workers inherit it: each logs its name and draws a dot
        with open(log, "a") as f:
            f.write(name + "\n")
        return Figure(figsize=(1, 1))

    monkeypatch.setattr(figures, "make_figure", quick)
    out = tmp_path / "out"
    out.mkdir()
    paths = figures.write_figures(paper, out, jobs=2)
    names = figures.figure_names(paper)
    assert [p.stem for p in paths] == [n for n in names for _ in figures.FORMATS]
    drawn = log.read_text().split()
    assert sorted(drawn) == sorted(names)
    kinds = [n for n in names if n.startswith("circuit_")]
    assert set(drawn[: len(kinds)]) == set(kinds)  # the circuits first, the slowest kind
    assert drawn.index("open_loop") > max(drawn.index(k) for k in kinds)
    assert gc.get_freeze_count() == 0  # the parent's objects are thawed again
