"""The report's figures: legible in print, written as PDF, SVG and PNG, the slowest drawn first.

Every time-series figure (open and closed loop, the firing patterns, the nonlinear check)
is measured as printed (symctl.plotting.legibility: no text under 6 pt, no two texts
overlapping, none off the figure, no wider than the derivation's text, a unit on every
axis), for the paper at T = 2 and T = 6 and for a model file (the oculomotor plant).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure
from matplotlib.text import Text

from symctl import derive, derive_paper
from symctl.errors import ParameterError, SymctlTypeError
from symctl.plotting.legibility import legibility, missing_units
from symctl.plotting.style import COLUMN, TEXT_WIDTH
from symctl.report import figures
from symctl.report.figures import figure_names, make_figure

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
TIME_SERIES = ("open_loop", "closed_loop", "nonlinear", "firing_")


@pytest.fixture(scope="module")
def paper():
    return derive_paper()  # the report's four realizations: the keys at their real length


@pytest.fixture(scope="module")
def paper_T6():
    return derive_paper(sensor_delay=3, actuator_delay=3)


@pytest.fixture(scope="module")
def oculomotor():
    return derive(EXAMPLES / "oculomotor.toml")


def _texts(fig):
    return [t.get_text() for t in fig.findobj(Text) if t.get_visible() and t.get_text()]


def _check(fig, name):
    """Legible at print size, a unit on every axis, no heading, one column or the text wide."""
    found = legibility(fig)
    assert found, f"{name}: {found}"
    assert not missing_units(fig), (name, missing_units(fig))
    assert fig._suptitle is None, f"{name}: a report figure has no heading (the caption says it)"
    width = float(fig.get_size_inches()[0])
    assert width == pytest.approx(COLUMN) or width == pytest.approx(TEXT_WIDTH), (name, width)


def _time_series(res):
    return [n for n in figure_names(res) if n.startswith(TIME_SERIES)]


def test_the_slowest_figures_are_drawn_first_and_the_paths_come_in_reading_order(
    paper, tmp_path, monkeypatch
):
    log = tmp_path / "drawn.txt"

    def quick(res, name):  # the forked workers inherit it: each logs its name and draws a dot
        with open(log, "a") as f:
            f.write(f"{os.getpid()} {name}\n")
        return Figure(figsize=(1, 1))

    monkeypatch.setattr(figures, "make_figure", quick)
    out = tmp_path / "out"
    out.mkdir()
    paths = figures.write_figures(paper, out, jobs=2)
    names = figures.figure_names(paper)
    assert [p.name for p in paths] == [f"{n}.{f}" for n in names for f in ("pdf", "png")]
    drawn = [line.split() for line in log.read_text().splitlines()]
    assert sorted(name for _, name in drawn) == sorted(names)
    assert os.getpid() not in {int(pid) for pid, _ in drawn}  # drawn by the workers
    # each worker takes the next figure in the order of drawing: the slowest kinds first
    for pid in {pid for pid, _ in drawn}:
        ranks = [figures._drawing_rank(name) for p, name in drawn if p == pid]
        assert ranks == sorted(ranks), (pid, drawn)
    assert figures._drawing_rank("circuit_general") < figures._drawing_rank("open_loop")


@pytest.mark.parametrize("jobs", [1, 2])
def test_the_figures_stage_reports_each_figure_once_it_is_saved(paper, tmp_path, monkeypatch, jobs):
    monkeypatch.setattr(figures, "make_figure", lambda res, name: Figure(figsize=(1, 1)))
    saved = []
    paths = figures.write_figures(
        paper, tmp_path, jobs=jobs, formats=("png",), progress=saved.append
    )
    assert sorted(saved) == sorted(figure_names(paper)) == sorted(p.stem for p in paths)
    with pytest.raises(SymctlTypeError, match="progress"):
        figures.write_figures(paper, tmp_path, progress="x")


def test_every_time_series_figure_of_the_paper_is_legible_with_units_and_no_heading(paper):
    names = _time_series(paper)
    assert len(names) == 7
    for name in names:
        _check(make_figure(paper, name), name)


def test_the_structure_figures_leave_their_heading_to_the_caption(paper):
    """The caption names the structure: the figure repeated it as a heading above its key."""
    for name in ("structure_ifp", "g1g3_structures"):
        texts = _texts(make_figure(paper, name))
        assert not any(
            t.startswith(("Structure:", "Two structures", "Controller structure")) for t in texts
        ), (name, texts[-3:])
        assert "boxes: gains" in " ".join(texts), name  # the key to the symbols stays
    texts = _texts(make_figure(paper, "structure_ifp"))  # what departs from the caption stays
    assert "Not compatible (no vertex bands)" in texts, texts


@pytest.mark.parametrize("name", ["closed_loop", "firing_general"])  # the most panels and keys
def test_the_T6_figures_are_legible(paper_T6, name):
    _check(make_figure(paper_T6, name), name)


def test_the_figures_of_a_model_file_are_legible(oculomotor):
    names = _time_series(oculomotor)
    assert {"open_loop", "closed_loop", "nonlinear", "firing_general"} <= set(names)
    for name in ("open_loop", "closed_loop", "nonlinear", "firing_general"):
        fig = make_figure(oculomotor, name)
        _check(fig, name)
        assert any("deg" in t for t in _texts(fig)), name  # the model's own units


def test_the_nonlinear_figure_marks_f_max_and_the_force_crosses_it_only_under_the_pulse(paper):
    # nonlinear.png showed 63.7 N, above f_max = 60 N: the muscle's own drive
    # f_max / (1 + exp(-r)) stays below f_max, and the force is above it only just after a
    # sample that added the disturbance w (10 N per step at the largest amplitude)
    chk, w = paper.nonlinear, paper.closed_loop.w[:, 0]
    assert 60.0 < chk.f_nonlinear.max() < 64.0
    assert (60.0 / (1 + np.exp(-chk.r_nonlinear))).max() < 60.0
    above = np.flatnonzero((chk.f_nonlinear > 60.0).any(axis=0))
    assert above.size and np.all(w[above - 1] != 0)
    assert figures._state_bounds(paper) == [
        (60.0, r"$f_{max}$ = 60 N: the most $f$ reaches without $w$"),
        (0.0, r"0 N: the least $f$ reaches without $w$"),
    ]
    fig = make_figure(paper, "nonlinear")
    key = [t.get_text() for t in fig.legends[0].get_texts()]
    assert r"$f_{max}$ = 60 N: the most $f$ reaches without $w$" in key
    assert not any(t.startswith("0 N") for t in key)  # far below the traces: left out
    flat = [ln.get_ydata() for ln in fig.axes[0].get_lines() if len(ln.get_ydata()) == 2]
    assert [float(y[0]) for y in flat] == [60.0]


def test_a_plant_without_a_bound_of_its_own_gets_no_line(oculomotor):
    assert figures._state_bounds(oculomotor) == []  # two states: no such argument


def test_save_writes_pdf_svg_and_png_with_the_same_bytes_twice(tmp_path):
    first = {}
    for k in range(2):
        out = tmp_path / str(k)
        out.mkdir()
        fig = Figure(figsize=(2.0, 1.2), layout="constrained")
        ax = fig.add_subplot()
        ax.plot([0, 1, 2], [0, 1, 0], label=r"$\delta f$")
        ax.set_ylabel(r"$\delta f$ [N]")
        ax.legend()
        paths = figures.save(fig, out, "open_loop")
        assert [p.name for p in paths] == ["open_loop.pdf", "open_loop.svg", "open_loop.png"]
        got = {p.suffix: p.read_bytes() for p in paths}
        assert got[".pdf"][:5] == b"%PDF-" and b"CreationDate" not in got[".pdf"]
        assert got[".svg"].lstrip().startswith(b"<?xml") and b"<dc:date>" not in got[".svg"]
        assert got[".png"][:8] == b"\x89PNG\r\n\x1a\n"
        first = first or got
        assert got == first  # byte-reproducible: no date, no random ids


def test_save_writes_only_the_formats_asked_for_in_the_order_of_formats(tmp_path):
    fig = Figure(figsize=(2.0, 1.2))
    fig.add_subplot().plot([0, 1], [1, 0])
    paths = figures.save(fig, tmp_path, "a", formats=("png", "svg"))
    assert [p.name for p in paths] == ["a.svg", "a.png"] and sorted(tmp_path.iterdir()) == sorted(
        paths
    )


@pytest.mark.parametrize(
    ("given", "expected"),
    [("pdf,png", ("pdf", "png")), (" SVG , pdf ,svg", ("pdf", "svg")), (["png"], ("png",))],
)
def test_figure_formats_are_read_in_the_order_of_formats(given, expected):
    assert figures.figure_formats(given) == expected


@pytest.mark.parametrize(
    ("given", "words"),
    [
        ("", "name at least one"),
        (",", "name at least one"),
        ("pdf,jpg", "unknown format 'jpg'"),
        ("pdf;png", "unknown format 'pdf;png'"),
        (3, "expected format names"),
        ([b"pdf"], "expected format names"),
    ],
)
def test_bad_figure_formats_are_a_parameter_error_naming_the_argument(given, words):
    with pytest.raises(ParameterError, match=rf"^formats: .*{words}"):
        figures.figure_formats(given)


def test_a_pdf_embeds_only_the_glyphs_it_shows_with_the_fonts_outlines(tmp_path):
    # each font is cut down once per process; a figure's subset is cut from that one
    import io
    import re
    import zlib

    from fontTools import ttLib
    from matplotlib import font_manager

    fig = Figure(figsize=(2.0, 1.2))
    fig.text(0.1, 0.5, r"fifty $\epsilon_1 \leq \tau$")
    data = figures.save(fig, tmp_path, "a", formats=("pdf",))[0].read_bytes()
    streams = [
        zlib.decompress(m) for m in re.findall(rb"stream\r?\n(.*?)\r?\nendstream", data, re.S)
    ]
    embedded = [ttLib.TTFont(io.BytesIO(s)) for s in streams if s[:4] == b"\x00\x01\x00\x00"]
    full = ttLib.TTFont(font_manager.findfont("DejaVu Sans"))
    sans = next(f for f in embedded if "f" in f.getGlyphOrder())
    assert "fi" not in sans.getGlyphOrder()  # no ligature the text does not show
    assert not {"GSUB", "GPOS", "MATH"} & set(sans.keys())
    assert sans["head"].modified == full["head"].modified  # no date of the run: the same bytes
    for name in ("f", "i", "y"):
        assert sans["glyf"][name].getCoordinates(sans["glyf"]) == full["glyf"][name].getCoordinates(
            full["glyf"]
        )


def test_a_glyph_beyond_the_fonts_base_set_is_embedded_by_matplotlibs_own_subset(tmp_path):
    import io
    import re
    import zlib

    from fontTools import ttLib
    from matplotlib import font_manager

    fig = Figure(figsize=(2.0, 1.2))
    fig.text(0.1, 0.5, "\u0416 a")  # Cyrillic: not among the characters fonts are cut to first
    data = figures.save(fig, tmp_path, "a", formats=("pdf",))[0].read_bytes()
    streams = [
        zlib.decompress(m) for m in re.findall(rb"stream\r?\n(.*?)\r?\nendstream", data, re.S)
    ]
    fonts = [ttLib.TTFont(io.BytesIO(s)) for s in streams if s[:4] == b"\x00\x01\x00\x00"]
    name = ttLib.TTFont(font_manager.findfont("DejaVu Sans")).getBestCmap()[0x416]
    assert any(name in f.getGlyphOrder() for f in fonts)


def test_the_derivation_includes_the_vector_figures_at_their_natural_size(tmp_path, pdflatex):
    import subprocess

    from symctl.report.document import Graphic, Text, to_tex

    # the text is 6.93 x 9.43 in; a figure up to the text less four lines (8.68 in) is not
    # scaled: the order-2 atlas (8.63 in) was, to 0.85, its 7-pt text printed at 6 pt
    sizes = {"small": (3.4, 1.5), "wide": (9.0, 1.5), "tall": (3.4, 8.63), "taller": (3.4, 8.8)}
    for name, size in sizes.items():
        fig = Figure(figsize=size)
        fig.add_subplot().plot([0, 1], [0, 1])
        figures.save(fig, tmp_path, name)
    blocks = [Text("Four figures."), *(Graphic(name, f"{name}.") for name in sizes)]
    tex = to_tex(blocks, title="Figures")
    assert r"\fitgraphic{small.pdf}" in tex and ".png" not in tex
    assert "width=\\linewidth" not in tex.split("\\begin{document}")[1]  # no scaling in the body
    (tmp_path / "f.tex").write_text(tex)
    subprocess.run(
        [pdflatex, "-interaction=nonstopmode", "-halt-on-error", "f.tex"],
        cwd=tmp_path,
        check=True,
        capture_output=True,
        timeout=120,
    )
    log = (tmp_path / "f.log").read_text(errors="replace")
    assert "symctl: scaled figure wide.pdf down to fit the page" in log
    assert "symctl: scaled figure taller.pdf down to fit the page" in log
    assert "scaled figure small.pdf" not in log  # at its natural size
    assert "scaled figure tall.pdf" not in log
