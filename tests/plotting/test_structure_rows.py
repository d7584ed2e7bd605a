"""Whether a structure drawing can fit the page, decided before any text is measured.

Measuring text is most of the time of a layout (each gain value is a mathtext parse):
a MIMO block form of a hundred gains took seconds to lay out, in one piece and in
rows, only to be drawn as the overview. :func:`page_bound` lays out each part with
text of no size; these tests hold it to being a lower bound (a layout only grows with
its texts) and to deciding the overview without any layout with text.
"""

from __future__ import annotations

import functools
import itertools
import sys
from pathlib import Path

import pytest
import sympy as sp

from symctl import Structure, controller_tf, factor, general_realization
from symctl.plotting import structure as drawing
from symctl.plotting.common import text_size
from symctl.plotting.structure import draw_structure
from symctl.plotting.structure_layout import structure_layout
from symctl.plotting.structure_rows import _no_text, page_bound, structure_rows

sys.path.insert(0, str(Path(__file__).parent))
from test_structure_layout import ASSIGNMENTS, STRUCTURES, crude


def doubled(text: str, points: float) -> tuple[float, float]:
    """Twice the crude measure: every text larger."""
    w, h = crude(text, points)
    return 2 * w, 2 * h


@functools.cache
def too_large() -> Structure:
    """T = 6 with G2 in a general realization (numbers): G2 alone is about 10 in wide."""
    f = factor(controller_tf(6), 3, 3)
    P = sp.Matrix(6, 6, lambda i, j: 2 if i == j else int(j == i + 1))
    return Structure.from_factorization(f, general_realization(f.abbreviated(), P))


def _extent(layout) -> tuple[float, float]:
    x_lo, x_hi, y_lo, y_hi = layout.bounds
    return x_hi - x_lo, y_hi - y_lo


@pytest.mark.parametrize("name", sorted(STRUCTURES))
def test_a_layout_only_grows_with_its_texts(name):
    """The premise of page_bound: no text, small text, large text give nested extents."""
    S, where = STRUCTURES[name], ASSIGNMENTS[name]
    sizes = [
        _extent(structure_layout(S, measure, vertex_of=where))
        for measure in (_no_text, crude, doubled)
    ]
    for (w0, h0), (w1, h1) in itertools.pairwise(sizes):
        assert w0 <= w1 + 1e-9 and h0 <= h1 + 1e-9, sizes
    w, h = _extent(structure_layout(S, text_size, vertex_of=where))
    assert sizes[0][0] <= w + 1e-9 and sizes[0][1] <= h + 1e-9


@pytest.mark.parametrize("name", ["ifp2", "general", "ccr", "ocr", "ccr6", "mimo"])
def test_page_bound_lets_every_structure_that_fits_through(name):
    S, where = STRUCTURES[name], ASSIGNMENTS[name]
    bound = page_bound(S, vertex_of=where)
    assert bound and bound.fits
    assert structure_rows(S, text_size, vertex_of=where).fits


@pytest.mark.slow
def test_a_part_too_large_without_text_gives_the_overview_before_any_layout(monkeypatch):
    S = too_large()
    bound = page_bound(S)
    assert not bound and bound.part == "G2" and bound.width > 6.9
    assert not structure_rows(S, crude).fits  # the full layout agrees

    def no_layout(*args, **kwargs):
        raise AssertionError("laid out with text although the bound had decided")

    monkeypatch.setattr(drawing, "structure_rows", no_layout)
    texts = [t.get_text() for t in draw_structure(S, overview="auto").axes[0].texts]
    assert any("too many to draw block by block" in t for t in texts)
