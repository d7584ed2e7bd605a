"""report/document: long displays, tables and prose are laid out to fit, in LaTeX and Markdown."""

from __future__ import annotations

import re

from symctl.report.document import MD_LINE, TABLE_MAX_ROWS, Math, Table, Text, to_markdown, to_tex


def test_a_breakable_display_is_an_align_with_one_number_on_its_first_row():
    tex = to_tex([Math((("a", "1"), (None, r"\qquad + 2"), ("b", "3")), "eq:ab", breakable=True)])
    body = tex[tex.index(r"\begin{align}") : tex.index(r"\end{align}")]
    assert body.count(r"\label{eq:ab}") == 1 and body.count(r"\notag") == 2
    assert r"a &= 1 \label{eq:ab}" in body and r"& \qquad + 2 \notag" in body


def test_a_continuation_row_has_no_equals_sign_in_both_formats():
    b = Math((("y", "x_1"), (None, r"\qquad + x_2")), "eq:y")
    assert r"y &= x_1 \\ & \qquad + x_2" in to_tex([b])
    assert r"y &= x_1 \\ & \qquad + x_2" in to_markdown([b])


def test_a_long_table_is_a_longtable_and_a_short_one_a_tabular():
    rows = tuple((str(k), f"${k}$") for k in range(TABLE_MAX_ROWS + 1))
    long, short = to_tex([Table(("k", "v"), rows)]), to_tex([Table(("k", "v"), rows[:3])])
    assert r"\begin{longtable}" in long and r"\usepackage{longtable}" in long
    assert r"\begin{tabular}" in short and "longtable" not in short


def test_a_wide_table_wraps_its_prose_columns_and_keeps_the_others():
    rows = (("G3 G2 G1, controllable canonical G2 " * 2, "$4$", "yes", "$1.8 \\times 10^{-15}$"),)
    head = ("circuit", "neurons", "compatible", "max. deviation " * 3)
    tex = to_tex([Table(head, rows)])
    x = r">{\raggedright\arraybackslash}X"
    assert rf"\begin{{tabularx}}{{\linewidth}}{{{x}lll}}" in tex and r"\usepackage{tabularx}" in tex
    long = to_tex([Table(head, rows * (TABLE_MAX_ROWS + 1))])  # a longtable: fixed widths
    assert r"\begin{longtable}{>{\raggedright\arraybackslash}p{\dimexpr(\linewidth-" in long


def test_a_wide_table_that_cannot_wrap_is_set_smaller():
    wide = to_tex(
        [Table(tuple(f"$x_{{{k}}} + y_{{{k}}} + z_{{{k}}}$" for k in range(12)), (("$1$",) * 12,))]
    )
    assert r"\footnotesize\setlength{\tabcolsep}{3pt}" in wide and "tabularx" not in wide


def test_markdown_cuts_long_math_after_matrix_rows_and_wraps_prose_outside_math():
    matrix = r"\begin{bmatrix}" + r" \\ ".join(" & ".join(["0.123456"] * 20) for _ in range(20))
    md = to_markdown(
        [
            Math((("P", matrix + r"\end{bmatrix}"),), "eq:P"),
            Text("word " * 40 + "$a + b + c + d$ " + "word " * 40),
        ]
    )
    lines = md.splitlines()
    assert max(map(len, lines)) <= MD_LINE
    assert "$a + b + c + d$" in md  # never broken inside inline math
    assert re.sub(r"\s+", "", md).count("0.123456") == 400
