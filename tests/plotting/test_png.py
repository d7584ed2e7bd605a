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
