"""Structure drawings as printed: legible at their natural size, every wire with its head.

The figures are measured as drawn (:func:`symctl.plotting.legibility.legibility`): no
text under 6 pt, no two texts on each other, none off the figure, and no figure wider
than the derivation's text (6.9 in), for the paper's four structures at T = 2, the
T = 6 controller (folded into rows) and a MIMO controller.
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import matplotlib
import pytest
from matplotlib.patches import Polygon

from symctl import SymctlTypeError, ifp_structure
from symctl.compatibility.structure import Structure
from symctl.errors import ParameterError
from symctl.plotting.common import text_size
from symctl.plotting.legibility import legibility
from symctl.plotting.structure import draw_structure
from symctl.plotting.structure_labels import structure_text
from symctl.plotting.structure_rows import structure_rows
from symctl.plotting.style import TEXT_WIDTH

matplotlib.use("Agg")
sys.path.insert(0, str(Path(__file__).parent))
from test_structure_layout import ASSIGNMENTS, STRUCTURES

PRINTED = ["ifp2", "general", "ccr", "ocr", "ccr6", "mimo"]


def labels_of(name):
    S = STRUCTURES[name]
    return {S.inputs[0]: "f", S.outputs[0]: "r"} if len(S.inputs) == 1 else None


@functools.cache
def drawn(name):
    S = STRUCTURES[name]
    return draw_structure(
        S, assignment=ASSIGNMENTS[name], labels=labels_of(name), title=f"Structure {name}"
    )


@pytest.mark.slow
@pytest.mark.parametrize("name", PRINTED)
def test_structure_is_legible_at_its_printed_size(name):
    fig = drawn(name)
    check = legibility(fig)
    assert check, str(check)
    assert fig.get_size_inches()[0] <= TEXT_WIDTH + 1e-9


@pytest.mark.parametrize("name", PRINTED)
def test_every_wire_into_a_block_has_its_arrow_head(name):
    """The x2 -> G2.M[2] and x1 -> G2.F[2,1] wires of the general G2 had none."""
    S = STRUCTURES[name]
    heads = [p for p in drawn(name).axes[0].patches if isinstance(p, Polygon)]
    rows = structure_rows(S, text_size, labels=labels_of(name), vertex_of=ASSIGNMENTS[name])
    breaks = sum(len(layout.arrows_in) for layout, _ in rows.placed[1:])  # a row's ends
    assert len(heads) == len(list(S.wires())) + len(S.inputs) + len(S.outputs) + 2 * breaks


def test_gains_show_their_value_or_a_name_listed_in_the_key():
    """The general G2's gains were placeholders ("G2.F[1,2]") with no key."""
    text = structure_text(STRUCTURES["general"])
    assert text.gains["G2.F[1,2]"] == "F_{12}" and text.gains["G1.H"] == "C_{1}"
    keyed = {line.partition(" = ")[0] for line in text.key_lines()}
    assert {"F_{11}", "F_{12}", "F_{21}", "F_{22}", "H_{1}", "H_{2}", "M_{1}", "M_{2}"} <= keyed
    texts = [t.get_text() for t in drawn("general").axes[0].texts]
    assert not any("G2." in t for t in texts)
    assert sum(1 for t in texts if t.startswith("$F_{12} = ")) == 1


def test_the_vertex_bands_and_the_part_frames_are_drawn():
    patches = {p.get_gid() for p in drawn("ccr").axes[0].patches if p.get_gid()}
    assert {"band:v1", "band:v2", "band:v3"} <= patches
    assert {"part:G1", "part:G2", "part:G3"} <= patches
    texts = {t.get_text() for t in drawn("ccr").axes[0].texts}
    assert {"$v_{1}$", "$v_{2}$", "$v_{3}$", "G1", "G2", "G3", "$f$", "$r$"} <= texts


def test_the_ifp_names_its_ends_as_the_others_do():
    texts = {t.get_text() for t in drawn("ifp2").axes[0].texts}
    assert {"$f$", "$r$"} <= texts  # and x, u at their dots: the paper's names, as the checker's


def test_bad_assignments_and_labels_are_refused_by_name():
    S = ifp_structure(2)
    with pytest.raises(ParameterError, match="assignment: no vertex for the signals"):
        draw_structure(S, assignment={"x": 1})
    with pytest.raises(SymctlTypeError, match="assignment: expected a DelayAssignment"):
        draw_structure(S, assignment=[1, 2])
    with pytest.raises(ParameterError, match="labels: 'mu' is not an input or output"):
        draw_structure(S, labels={"mu": "m"})
    with pytest.raises(ParameterError, match="overview: must be True, False or 'auto'"):
        draw_structure(S, overview="yes")


def test_a_structure_that_fits_no_page_is_drawn_as_its_overview_when_asked():
    S = STRUCTURES["ccr6"]
    fig = S.draw(overview="auto", max_signals=20)
    assert any("too many" in t.get_text() for t in fig.axes[0].texts)
    assert legibility(fig)


def test_structure_latex_names_signals_readably():
    """The repr read \\operatorname{G1.zd}_{F[1,1]}; it now reads as the recursion of each state."""
    tex = STRUCTURES["ccr"].latex()
    assert "operatorname" not in tex and "zd" not in tex and "z^-1" not in tex
    assert r"{x_{1}}^{\mathrm{G1}}(t) &= \epsilon_{1} {x_{1}}^{\mathrm{G1}}(t - 1)" in tex
    assert Structure._repr_latex_(STRUCTURES["ccr"]).startswith("$")


def test_an_empty_title_draws_no_heading_and_a_lower_figure():
    S = ifp_structure(2)
    with_heading, without = draw_structure(S), draw_structure(S, title="")
    texts = [t.get_text() for t in without.axes[0].texts]
    assert not any(t.startswith("Controller structure") for t in texts)
    assert any(
        t.startswith("Controller structure")
        for t in (x.get_text() for x in with_heading.axes[0].texts)
    )
    assert without.get_size_inches()[1] < with_heading.get_size_inches()[1]
