"""PNG files: RGB for an opaque figure (pdflatex copies it), the pixels savefig would write."""

from __future__ import annotations

import io

import numpy as np
import pytest
from matplotlib.figure import Figure
from PIL import Image

from symctl import Circuit, MuscleModel, ifp_structure, open_loop_response
from symctl.plotting.png import write_png
from symctl.report.figures import save


def colour_type(path) -> int:
    """The IHDR colour type of a PNG: 2 is RGB, 6 RGBA."""
    return path.read_bytes()[25]


def test_an_opaque_figure_is_written_as_rgb_with_the_pixels_of_savefig(tmp_path):
    figures = [
        open_loop_response(MuscleModel().plant()).plot(),  # constrained layout
        Circuit.from_structure(ifp_structure(2)).draw(),
    ]
    for k, fig in enumerate(figures):
        canvas, size = fig.canvas, fig.get_size_inches().copy()
        path = write_png(fig, tmp_path / f"{k}.png", dpi=120, metadata={"Software": "symctl"})
        assert colour_type(path) == 2
        assert fig.canvas is canvas and fig.dpi == 100 and (fig.get_size_inches() == size).all()
        ours = np.asarray(Image.open(path))
        fresh = [
            open_loop_response(MuscleModel().plant()).plot(),
            Circuit.from_structure(ifp_structure(2)).draw(),
        ][k]
        raw = io.BytesIO()
        fresh.savefig(raw, format="png", dpi=120)
        theirs = np.asarray(Image.open(raw))
        assert theirs.shape[2] == 4 and (theirs[..., 3] == 255).all()
        assert np.array_equal(ours, theirs[..., :3])
        assert Image.open(path).text == {"Software": "symctl"}


def test_a_translucent_figure_keeps_its_alpha_channel(tmp_path):
    fig = Figure(figsize=(2, 1))
    fig.patch.set_alpha(0.5)
    assert colour_type(write_png(fig, tmp_path / "a.png", dpi=50)) == 6


@pytest.mark.slow
def test_report_figures_are_rgb_and_the_same_bytes_twice(tmp_path):
    fig = open_loop_response(MuscleModel().plant()).plot()
    *_, png = save(fig, tmp_path, "open_loop")
    assert colour_type(png) == 2
    first = png.read_bytes()
    save(fig, tmp_path, "open_loop")
    assert png.read_bytes() == first


def test_a_png_from_the_figures_pdf_has_the_size_and_colours_of_matplotlibs(tmp_path):
    from symctl.plotting.png import render_pdf
    from symctl.plotting.vector import write_vector

    fig = open_loop_response(MuscleModel().plant()).plot()
    pdf = write_vector(fig, tmp_path / "a.pdf")
    ours = render_pdf(pdf, tmp_path / "a.png", dpi=120)
    theirs = write_png(fig, tmp_path / "b.png", dpi=120)
    assert colour_type(ours) == 2  # opaque: RGB
    a, b = (np.asarray(Image.open(p), dtype=float) for p in (ours, theirs))
    assert abs(a.shape[0] - b.shape[0]) <= 1 and abs(a.shape[1] - b.shape[1]) <= 1
    h, w = min(a.shape[0], b.shape[0]), min(a.shape[1], b.shape[1])
    # the same drawing rasterized by two renderers: antialiasing differs, the picture does not
    assert np.abs(a[:h, :w] - b[:h, :w]).mean() < 8  # of 255, per channel
    assert (a < 128).mean() == pytest.approx((b < 128).mean(), abs=0.01)  # as much ink


def test_every_renderer_of_a_process_shares_the_typeset_math_text(tmp_path):
    from matplotlib import mathtext

    from symctl.plotting.style import new_figure
    from symctl.plotting.vector import write_vector

    def figure():
        fig = new_figure("column", 1.0)
        fig.add_subplot().set_xlabel(r"$\epsilon_{17} + K_{23}$ [unusual]")
        return fig

    write_vector(figure(), tmp_path / "a.pdf")
    parse = mathtext.MathTextParser._parse_cached
    shared = parse.__closure__[parse.__code__.co_freevars.index("shared")].cell_contents
    misses = shared.cache_info().misses
    write_vector(figure(), tmp_path / "b.pdf")  # a new figure, a new renderer: nothing typeset
    assert shared.cache_info().misses == misses


def test_the_fonts_cut_for_the_pdf_subsets_are_closed_after_reading(tmp_path):
    import gc
    import warnings

    from symctl.plotting import vector

    fig = open_loop_response(MuscleModel().plant()).plot()
    vector._base_font.cache_clear()  # cut afresh here: each font file opened and read once
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        vector.write_vector(fig, tmp_path / "a.pdf")
        gc.collect()
    assert vector._base_font.cache_info().currsize > 0  # the fonts were cut in this test
    assert not [w for w in caught if issubclass(w.category, ResourceWarning)]
