"""The overview of a structure too large to draw block by block."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from symctl import Structure, SymctlTypeError, controller_tf, factor, observable_canonical
from symctl.plotting.legibility import legibility
from symctl.plotting.structure import draw_structure_overview, parts_in_order
from symctl.plotting.structure_labels import end_labels
from symctl.realization.realization import first_order_realization

sys.path.insert(0, str(Path(__file__).parent))
from test_structure_layout import STRUCTURES


@pytest.mark.slow
@pytest.mark.parametrize("ds, da", [(1, 1), (3, 4), (10, 10)])
def test_overview_counts_every_block_of_every_part(ds, da):
    f = factor(controller_tf(ds + da), ds, da)
    S = Structure.from_factorization(f, observable_canonical(f.abbreviated()))
    parts = parts_in_order(S)
    assert parts[0][0].startswith("G1") and parts[-1][0].startswith("G3")
    assert len(parts) == ds + da + 1
    for kind in ("gain", "sum", "delay"):
        assert sum(c[kind] for _, c in parts) == S.count(kind)
    assert dict(parts)["G2"]["states"] == ds + da
    fig = draw_structure_overview(S)
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert all(p in texts for p, _ in parts)
    width, height = fig.get_size_inches()
    assert width <= 6.9 and height < 1.2 + 1.0 * (len(parts) // 5 + 1)  # page-shaped at any T
    assert S.draw(overview=True).get_size_inches().tolist() == [width, height]
    assert legibility(fig), legibility(fig)


def test_overview_refuses_other_objects():
    with pytest.raises(SymctlTypeError, match="S: expected a Structure"):
        draw_structure_overview("G2")


@pytest.mark.slow
def test_report_draws_large_structures_as_overview(monkeypatch):
    from symctl import derive_paper
    from symctl.report import figures

    res = derive_paper()
    full = figures.make_figure(res, "structure_general")
    monkeypatch.setattr(figures, "MAX_DRAWN_SIGNALS", 10)
    assert any(
        "too many" in t.get_text()
        for t in figures.make_figure(res, "structure_general").axes[0].texts
    )
    assert not any("too many" in t.get_text() for t in full.axes[0].texts)


def test_parallel_pathways_are_drawn_side_by_side_not_in_series():
    R = first_order_realization(1, 2)
    S = Structure.parallel(Structure.series(R, R, R), Structure.series(R, R))
    fig = draw_structure_overview(S)
    boxes = {t.get_text(): t.get_position() for t in fig.axes[0].texts if "." in t.get_text()}
    assert boxes["P1.G1"][1] != boxes["P2.G1"][1]  # one row per pathway
    assert boxes["P1.G1"][0] == boxes["P2.G1"][0]
    assert legibility(fig)


def test_overview_ends_carry_the_names_of_the_block_diagram():
    """The overview read "u" and "y" where the full drawing read the plant's names (f, r)."""
    f = factor(controller_tf(6), 3, 3)
    S = Structure.from_factorization(f, observable_canonical(f.abbreviated()))
    labels = {S.inputs[0]: "f", S.outputs[0]: "r"}
    texts = [t.get_text() for t in S.draw(overview=True, labels=labels).axes[0].texts]
    assert "$f$" in texts and "$r$" in texts
    assert "u" not in texts and "y" not in texts
    default = [t.get_text() for t in draw_structure_overview(S).axes[0].texts]
    assert f"${end_labels(S)[S.inputs[0]]}$" in default


def test_overview_lists_every_input_of_a_mimo_structure_at_its_arrow():
    S = STRUCTURES["mimo"]
    names = {"G1.u1": r"\theta", "G1.u2": r"\omega", "G3.x1": r"r_\text{flex}"}
    fig = draw_structure_overview(S, labels=names)
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert r"$\theta, \omega$" in texts and r"$r_\text{flex}$" in texts
    assert legibility(fig), legibility(fig)


def test_overview_box_holds_its_counts_and_the_heading_fits_the_figure():
    """The antagonist's general G2 (360 gains) overflowed its box; its long title was clipped."""
    R = first_order_realization(1, 2)
    S = Structure.series(R, R, R)
    title = "Structure: G3 G2 G1, general realization of G2, realization #1 of the simulations"
    fig = draw_structure_overview(S, title=title + " (numbers, a long title)", width=4.0)
    check = legibility(fig, page_width=4.0)
    assert check, str(check)
    assert fig.get_size_inches()[0] <= 4.0


def test_an_overview_with_an_empty_title_has_no_heading():
    R = first_order_realization(1, 2)
    fig = draw_structure_overview(Structure.series(R, R, R), title="")
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert not any(t.startswith("Controller structure") for t in texts)
    assert legibility(fig), legibility(fig)


def test_the_overview_of_a_structure_without_parts_is_one_box():
    # the IFP structure at T = 20 with its vertex bands is past the page (symctl paper)
    from symctl import ifp_structure

    fig = draw_structure_overview(ifp_structure(20))
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert any("20 delays" in t for t in texts)
