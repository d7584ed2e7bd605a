"""report/document: blocks rendered as LaTeX and Markdown, and pdflatex."""

from __future__ import annotations

import shutil

import pytest
from helpers import long_sums

from symctl.errors import LatexError, SymctlTypeError
from symctl.report.document import (
    BLOCKS,
    Graphic,
    Heading,
    Math,
    References,
    Table,
    Text,
    Verbatim,
    compile_pdf,
    to_markdown,
    to_tex,
)


def test_prose_is_escaped_for_latex_and_math_kept():
    blocks = [
        Heading("Gains"),
        Text("100% of x_1 & $K_0 + \\epsilon_1$"),
        Math((("a", "1"),), "eq:a"),
    ]
    tex = to_tex(blocks)
    assert r"100\% of x\_1 \& $K_0 + \epsilon_1$" in tex
    md = to_markdown(blocks)
    assert "100% of x_1 & $K_0 + \\epsilon_1$" in md and r"\tag{1}" in md


def test_a_column_of_sums_wider_than_the_page_wraps_at_its_plus_and_minus_signs():
    tex = to_tex([long_sums()])
    assert r"\begin{tabularx}{\linewidth}{l>{\raggedright\arraybackslash}Xl}" in tex


def test_a_latex_error_is_reported_with_its_first_line(tmp_path, pdflatex):
    bad = tmp_path / "bad.tex"
    bad.write_text("\\documentclass{article}\\begin{document}\\undefinedmacro\\end{document}\n")
    with pytest.raises(LatexError, match="Undefined control sequence"):
        compile_pdf(bad)


def test_compile_pdf_without_pdflatex_returns_none(tmp_path, monkeypatch):
    monkeypatch.setattr(shutil, "which", lambda _name: None)
    (tmp_path / "a.tex").write_text("x")
    assert compile_pdf(tmp_path / "a.tex") is None


def test_tex_and_markdown_show_the_same_graphic_with_its_caption():
    blocks = [Graphic("open_loop", "Open loop, 100%.")]
    tex, md = to_tex(blocks), to_markdown(blocks)
    assert r"\fitgraphic{open_loop.pdf}" in tex  # the vector figure, at its natural size
    assert r"\caption{Open loop, 100\%.}\label{fig:open_loop}" in tex
    assert "![Open loop, 100%.](open_loop.png)" in md


def test_every_block_type_renders_in_both_formats():
    blocks = [
        Heading("A", 2),
        Text("t"),
        Math((("a", "1"), ("b", "2")), "eq:ab"),
        Table(("h1", "h2"), (("1", "a|b"),)),
        Graphic("g", "c"),
        Verbatim("x -> y"),
        References((("k", "An entry."),)),
    ]
    assert {type(b) for b in blocks} == set(BLOCKS)
    tex, md = to_tex(blocks), to_markdown(blocks)
    assert r"\subsection{A}" in tex and r"a &= 1 \\ b &= 2" in tex and r"\begin{verbatim}" in tex
    assert r"\bibitem{k} An entry." in tex
    assert "### A" in md and r"a\|b" in md and "```\nx -> y\n```" in md
    assert "## References\n\n[1] An entry." in md


def test_citations_and_references_are_numbered_alike_in_both_formats():
    blocks = [
        Text("As in [@b, Fig. 5] and [@a]; see Fig. [#fig:g], Table [#tab:t] and [#eq:x]."),
        Math((("x", "1"),), "eq:y"),
        Math((("x", "1"),), "eq:x"),
        Table(("h",), (("1",),), caption="A table.", label="t"),
        Graphic("g", "c"),
        References((("a", "First."), ("b", "Second."))),
    ]
    tex, md = to_tex(blocks), to_markdown(blocks)
    assert (
        r"As in~\cite[Fig. 5]{b} and~\cite{a}; see Fig.~\ref{fig:g}, Table~\ref{tab:t} and~"
        r"\eqref{eq:x}."
    ) in tex
    assert r"\caption{A table.}\label{tab:t}" in tex and r"\begin{table}" in tex
    assert "As in [2, Fig. 5] and [1]; see Fig. 1, Table 1 and (2)." in md
    assert "*Table 1: A table.*" in md and "*Figure 1: c*" in md


def test_a_figure_cited_in_its_caption_keeps_its_markdown_image_whole():
    md = to_markdown([Graphic("g", "As in [@a, Fig. 5]."), References((("a", "A."),))])
    assert "![As in (1, Fig. 5).](g.png)" in md and "*Figure 1: As in [1, Fig. 5].*" in md


def test_an_unknown_reference_is_question_marks_in_markdown():
    assert "Fig. ?? [??]" in to_markdown([Text("Fig. [#fig:none] [@none]")])


def test_every_section_heading_first_places_the_floats_of_the_section_before():
    tex = to_tex([Heading("A"), Graphic("g", "c"), Heading("B", 2), Heading("C")])
    assert tex.count(r"\symctlbarrier\section{") == 2 and r"\newcommand{\symctlbarrier}" in tex
    assert "\n\\subsection{B}" in tex


def test_the_title_is_a_parameter():
    assert to_markdown([], title="My title").startswith("# My title\n")
    assert r"\title{50\% done}" in to_tex([], title="50% done")


@pytest.mark.parametrize("render", [to_tex, to_markdown])
def test_a_non_block_is_a_type_error_naming_blocks(render):
    with pytest.raises(SymctlTypeError, match=r"blocks: element 1 is a str"):
        render([Text("a"), "not a block"])


def test_the_document_cites_the_paper_and_its_author():
    from symctl.report.document import Text, to_tex

    tex = to_tex([Text("x")])
    assert r"\author{Derived by symctl \\ \small with the method of Jing Shuang (Lisa) Li" in tex
    assert "Toward Neuronal Implementations of Delayed Optimal Control" in tex
