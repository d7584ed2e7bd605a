"""report/story: the derivation as blocks, in the paper's order."""

from __future__ import annotations

import re

import numpy as np
import pytest
import sympy as sp

from symctl import controllable_canonical, controller_tf, derive_paper, factor, observable_canonical
from symctl.latex import to_latex
from symctl.report.document import Graphic, Heading, Math, References, Table, Text
from symctl.report.prose import MARK
from symctl.report.reference import FIGURES, KEY
from symctl.report.shorthand import compact, remainder_poly, remainder_symbols
from symctl.report.spec import CIRCUIT_SPECS
from symctl.report.story import story


def test_only_the_figures_written_get_a_graphic_block():
    res = derive_paper(realizations=1)
    none = story(res)
    assert not [b for b in none if isinstance(b, Graphic)]
    some = story(res, figures=["nonlinear", "circuit_general"])
    assert [b.name for b in some if isinstance(b, Graphic)] == ["circuit_general", "nonlinear"]


def test_the_augmented_state_is_the_systems_chi():
    res = derive_paper(realizations=1)
    (eq,) = [b for b in story(res) if isinstance(b, Math) and b.label == "eq:augmented"]
    assert eq.rows[0] == (r"\chi", to_latex(res.system.chi))


def test_circuit_headings_use_the_specs_titles_with_their_math():
    res = derive_paper(realizations=1)
    headings = {b.text for b in story(res) if isinstance(b, Heading)}
    plain = {h.replace("$", "").replace("_", "") for h in headings}
    assert {CIRCUIT_SPECS[name].title for name in res.circuits} <= plain
    assert "$G_3 G_2 G_1$, controllable canonical $G_2$" in headings


def test_long_realization_entries_are_written_as_N_c_k_and_mean_the_same():
    f = factor(controller_tf(4), 2, 2)
    c = remainder_symbols(f)
    values = {sp.Symbol("N"): f.N, **dict(zip(c, f.remainder_coeffs, strict=True))}
    rewritten = f.N + f.N * remainder_poly(c) / f.G2.den
    assert sp.cancel(rewritten.subs(values) - f.G2.expr) == 0
    for R in (controllable_canonical(f.G2), observable_canonical(f.G2)):
        rows, short = compact(R, f, c)
        assert short
        for name, mat in rows:
            assert (mat.subs(values) - getattr(R, name)).applyfunc(sp.cancel).is_zero_matrix
        assert any(mat.has(sp.Symbol("N")) for _, mat in rows)


def test_the_delays_are_counted_in_words_not_step_s():
    for ds, word in ((1, "$d_s = 1$ step and"), (2, "$d_s = 2$ steps and")):
        text = " ".join(
            b.text
            for b in story(derive_paper(sensor_delay=ds, realizations=1))
            if isinstance(b, Text)
        )
        assert "step(s)" not in text and word in text


# ---------------------------------------------------------------- citing the paper


@pytest.fixture(scope="module")
def paper_blocks(derived_T2):
    return derived_T2, story(derived_T2, figures=derived_T2.figure_names())


def _prose(blocks) -> list[str]:
    out = []
    for b in blocks:
        if isinstance(b, Text | Heading):
            out.append(b.text)
        elif isinstance(b, Graphic):
            out.append(b.caption)
        elif isinstance(b, Table):
            out += [b.caption, *b.header, *(c for row in b.rows for c in row)]
    return out


def test_the_paper_is_cited_by_its_numbers_and_listed_in_the_references(paper_blocks):
    _, blocks = paper_blocks
    (refs,) = [b for b in blocks if isinstance(b, References)]
    assert blocks[-1] is refs and [k for k, _ in refs.entries] == [KEY]
    text = " ".join(_prose(blocks))
    cited = {m["key"] for m in MARK.finditer(text) if m["key"]}
    assert cited == {KEY}
    assert "[@li2024, Fig. 5]" in text and "[@li2024, Def. 4]" in text
    for label in FIGURES:  # never the paper's LaTeX labels ("Fig. ol_sims")
        assert not re.search(rf"Figs?\. {label}\b", text), label


def test_references_to_figures_point_to_figures_of_the_document(paper_blocks):
    _, blocks = paper_blocks
    shown = {f"fig:{b.name}" for b in blocks if isinstance(b, Graphic)}
    refs = {m["ref"] for m in MARK.finditer(" ".join(_prose(blocks))) if m["ref"]}
    assert {r for r in refs if r.startswith("fig:")} <= shown and "fig:delay_graph" in refs
    assert "tab:parameters" in refs


def test_each_figure_follows_the_heading_of_its_section(paper_blocks):
    _, blocks = paper_blocks
    heading = None
    under = {}
    for b in blocks:
        if isinstance(b, Heading):
            heading = b.text
        elif isinstance(b, Graphic):
            under[b.name] = heading
    assert under["open_loop"] == "Discretization" and under["nonlinear"] == "The nonlinear plant"
    assert under["closed_loop"] == "The controller $G(z)$"


def test_the_parameter_table_says_which_numbers_are_the_papers_and_which_ours(paper_blocks):
    _, blocks = paper_blocks
    (table,) = [b for b in blocks if isinstance(b, Table) and b.label == "parameters"]
    source = {row[0]: row[2] for row in table.rows}
    assert source["muscle time constant $\\tau$"] == "[@li2024, Sec. VI]"
    assert source["cost weights $Q$, $R$"].startswith("ours")
    assert all(source[k].startswith("ours") for k in source if "random" in k)
    values = {row[0]: row[1] for row in table.rows}
    assert values["equilibrium firing rate $\\bar{r}$"] == "1 spike/s"
    other = derive_paper(sensor_delay=3, tau=0.05, realizations=1)
    rows = {
        r[0]: r
        for b in story(other)
        if isinstance(b, Table) and b.label == "parameters"
        for r in b.rows
    }
    assert rows["muscle time constant $\\tau$"][2] == "this run ([@li2024]: 0.02)"
    assert rows["sensor delay $d_s$, actuator delay $d_a$"][1:] == (
        "3 steps and 1 step",
        "this run ([@li2024]: 1 and 1)",
    )


def test_both_readings_of_E_tilde_are_shown_where_they_differ(paper_blocks):
    res, blocks = paper_blocks
    (eq,) = [b for b in blocks if isinstance(b, Math) and b.label == "eq:Etilde-general"]
    assert [lhs for lhs, _ in eq.rows] == [r"\tilde E", r"\tilde E^{\mathrm{d}}"]
    direct = res.circuits["general"].compatibility.assignment.e_tilde("direct")
    assert np.isinf(direct[0, 2]) and eq.rows[1][1] == to_latex(direct)  # the paper's Eq. (14)
    assert any("Two readings of" in t for t in _prose(blocks))


def test_a_matrix_controller_too_wide_for_the_line_shows_every_entry_of_its_numerator(
    derived_oculomotor,
):
    """G(z) of a 1 x 2 controller was written K_{0,11}/a(z): its first entry only."""
    res = derived_oculomotor
    tables = [b for b in story(res) if isinstance(b, Table) and b.header[0] == "entry"]
    assert [row[:2] for row in tables[0].rows] == [
        ("$N_{11}$", "$K_{0,11}$"),
        ("$N_{12}$", "$K_{0,12}$"),
    ]
    maths = [b for b in story(res) if isinstance(b, Math) and b.label == "eq:G"]
    assert maths[0].rows[0] == ("G(z)", r"\frac{N(z)}{a(z)}")
