"""report/longform and story: every line of the documents fits the page, at any size.

By construction: every display row is within ``LINE_WIDTH`` glyphs of the width estimate
(calibrated on pdflatex, and checked here by compiling large objects), every table within
``TABLE_WIDTH`` at the size the document sets it; the paper's T = 2 document keeps its
matrices in full. The large objects are synthetic (the sizes of T = 2..20: up to 21 x 21,
dense symbolic and numeric, sparse, companion, delay matrices with infinities) so that the
test stays fast; benchmarks/documents.py runs the whole pipeline at large T.
"""

from __future__ import annotations

import re
import subprocess

import numpy as np
import pytest
import sympy as sp

from symctl import controller_tf, derive_paper
from symctl.report import longform as LF
from symctl.report import matrixview as MV
from symctl.report.document import Math, Table, Text, to_markdown, write_tex
from symctl.report.shorthand import display, eq, tf_long
from symctl.report.story import story
from symctl.symbols import gain_symbols

SIZES = (2, 3, 5, 8, 11, 13, 16, 21)  # matrices of T = 1..20 (T + 1 rows for the augmented ones)


def _companion(n: int) -> sp.Matrix:
    K = gain_symbols(n)
    F = sp.zeros(n, n)
    for i in range(n - 1):
        F[i, i + 1] = 1
    F[n - 1, :] = sp.Matrix([[K[n - j] for j in range(n)]])
    return F


def _objects(n: int) -> list[tuple[str, object]]:
    """Objects the story shows, of size ``n``: each kind of matrix and vector, symbolic and numeric."""
    rng = np.random.default_rng(n)
    dense = rng.normal(size=(n, n)) * 10.0 ** rng.integers(-8, 3, size=(n, n))
    shift = np.diag(np.ones(n - 1), -1)
    shift[0, 0], shift[0, n - 1] = 0.606531, 4.64165
    E = np.array([[j - i if j >= i else np.inf for j in range(n)] for i in range(n)], dtype=float)
    p = sp.Matrix(
        n,
        n,
        lambda i, j: (
            sp.Rational(int(rng.integers(-(10**6), 10**6)), 997)
            * sp.Symbol(f"sigma_{{{(i + j) % n + 1}}}")
            + sp.Symbol(f"p_{{{i + 1},{j + 1}}}")
        ),
    )
    K = gain_symbols(n)
    return [
        ("F", _companion(n)),
        ("F", _companion(n).T),
        ("H", sp.Matrix([0] * (n - 1) + [1])),
        ("M", sp.Matrix([[sp.Symbol("N") * sp.Symbol(f"c_{{{k}}}") for k in range(n, 0, -1)]])),
        ("M", sp.Matrix([[K[0] * (K[k] + sp.Symbol(f"sigma_{{{k}}}")) for k in range(1, n)]])),
        (r"\tilde A", shift),
        ("E", E),
        ("P", dense),
        ("P", p),
        ("K", rng.normal(size=(1, n))),
        (r"\chi", sp.Matrix([sp.Symbol(f"gamma_{{{k}}}") for k in range(n)])),
    ]


def _rows_fit(blocks) -> None:
    for b in blocks:
        if isinstance(b, Math):
            lead = max((LF.width(lhs) for lhs, _ in b.rows if lhs is not None), default=0.0) + 3
            for lhs, rhs in b.rows:
                assert lead + LF.width(rhs) <= LF.LINE_WIDTH, (b.label, lhs, rhs[:200])
            tall = sum(LF.height(rhs) for _, rhs in b.rows) > LF.DISPLAY_MAX_LINES
            assert b.breakable or not tall, b.label
        if isinstance(b, Table):
            shrink = 0.75 if LF.table_width(b.header, b.rows) > LF.TABLE_WIDTH else 1.0
            assert shrink * LF.table_width(b.header, b.rows) <= LF.TABLE_WIDTH, b.header


@pytest.mark.parametrize("n", SIZES)
def test_every_kind_of_large_matrix_fits_the_line(n):
    for lhs, obj in _objects(n):
        blocks = eq((lhs, obj), label="eq:x")
        _rows_fit(blocks)
        view = MV.show_matrix(lhs, obj)
        if view.full:
            assert n <= LF.MATRIX_MAX_ROWS


def test_a_large_matrix_is_shown_by_its_structure():
    n = 20
    rows = MV.show_matrix("H", sp.Matrix([0] * (n - 1) + [1])).rows
    assert rows == [("H", r"e_{20}\quad (20 \times 1)")]
    F = MV.show_matrix("F", _companion(n)).rows
    assert r"\ddots" in F[0][1] and F[1][1].startswith("(K_{20}, K_{19}")
    E = _objects(21)[6][1]
    view = MV.show_matrix("E", E)
    assert r"\begin{smallmatrix}" in view.rows[0][1]
    (intro, _, body) = view.tables[0]
    assert r"\infty" in intro and len(body) == 22  # a row per diagonal (two for k = 19)
    assert body[1] == ("${E}_{i,i+1}$", r"$i = 1, \dots, 20$", "$1$")
    dense = MV.show_matrix("P", np.arange(400.0).reshape(20, 20) + 0.5).rows[0][1]
    assert r"\cdots" in dense and r"\vdots" in dense and "399.5" in dense


def test_long_sums_break_at_their_signs_and_lists_at_their_commas():
    K = gain_symbols(40)
    s = sp.latex(sp.Add(*(k * sp.Symbol("z") ** i for i, k in enumerate(K))))
    rows = LF.fit_rows([("a(z)", s)])
    assert len(rows) > 2 and all(lhs is None for lhs, _ in rows[1:])
    joined = " ".join(r.replace(LF.INDENT, "") for _, r in rows)
    assert joined.split() == s.split()  # nothing lost, nothing added
    items = ", ".join(f"{x} + {x} i" for x in range(100, 140))
    broken = LF.fit_rows([("p", items)])
    assert all(r.rstrip().endswith(",") for _, r in broken[:-1])  # never inside an item


def test_a_very_long_equation_keeps_its_ends_and_counts_what_it_leaves_out():
    s = " + ".join(f"x_{{{k}}}" for k in range(2000))
    rows = LF.fit_rows([("s", s)])
    assert len(rows) == LF.TERM_MAX_LINES
    assert re.search(r"\((\d+) terms not shown\)", rows[-2][1])
    assert rows[-1][1].endswith("x_{1999}")


def test_a_term_wider_than_the_line_is_elided_with_its_length():
    frac = r"\frac{" + " ".join(f"C_{{{k}}}" for k in range(80)) + "}{2}"
    rows = LF.fit_rows([("N", frac)])
    assert "too long to print" in rows[0][1] and str(len(frac)) in rows[0][1]


def test_a_long_transfer_function_is_a_coefficient_table():
    G = controller_tf(20)
    num = G.subs({k: sp.Rational(-1, k_ + 2) for k_, k in enumerate(gain_symbols(20))})
    blocks = tf_long("G(z)", G, num, label="eq:G")
    _rows_fit(blocks)
    (table,) = [b for b in blocks if isinstance(b, Table)]
    assert len(table.rows) == 21 and table.rows[1][1] == "$- K_{1}$"
    assert any("a(z)" in r for _, r in blocks[0].rows)


def test_large_objects_compile_without_an_overfull_box(tmp_path, pdflatex):
    blocks = []
    for n in (13, 21):
        for k, (lhs, obj) in enumerate(_objects(n)):
            blocks += eq((lhs, obj), label=f"eq:{n}-{k}")
    G = controller_tf(20)
    blocks += tf_long("G(z)", G, G.subs({k: 0.123456789 for k in gain_symbols(20)}), label="eq:G")
    blocks += display(
        [("y(t)", " + ".join(rf"0.{k}123456\, x_{{{k}}}(t-{k})" for k in range(300)))], "eq:long"
    )
    blocks.append(Table(("k", "value"), tuple((str(k), f"${k}.5$") for k in range(80))))
    write_tex(blocks, tmp_path / "big.tex")
    run = subprocess.run(
        [pdflatex, "-interaction=nonstopmode", "big.tex"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        errors="replace",
        timeout=180,
    )
    log = (tmp_path / "big.log").read_text(errors="replace")
    assert run.returncode == 0, [line for line in log.splitlines() if line.startswith("!")][:3]
    assert "Overfull \\hbox" not in log and "symctl: shrunk" not in log


@pytest.fixture(scope="module")
def paper_T2():
    return story(derive_paper(realizations=1))


def test_the_papers_document_fits_and_keeps_its_matrices_in_full(paper_T2):
    _rows_fit(paper_T2)
    rhs = " ".join(r for b in paper_T2 if isinstance(b, Math) for _, r in b.rows)
    assert r"\times 1)" not in rhs and "smallmatrix" not in rhs and r"\ddots" not in rhs
    tall = {b.label: sum(LF.height(r) for _, r in b.rows) for b in paper_T2 if isinstance(b, Math)}
    breakable = {b.label for b in paper_T2 if isinstance(b, Math) and b.breakable}
    assert breakable == {k for k, h in tall.items() if h > LF.DISPLAY_MAX_LINES} == {"eq:augmented"}


def test_beyond_expanded_zeros_the_c_k_are_written_with_sigma_and_report_md_stays_short():
    res = derive_paper(sensor_delay=3, actuator_delay=2, realizations=1)
    assert res.abbreviated
    blocks = story(res)
    _rows_fit(blocks)
    (eq,) = [b for b in blocks if isinstance(b, Math) and b.label == "eq:G2rewritten"]
    c = dict(eq.rows[2:])
    assert c["c_{1}"] == r"K_{1} - \sigma_{1}" and c["c_{5}"] == r"K_{5} - \sigma_{5}"
    (factors,) = [b for b in blocks if isinstance(b, Math) and b.label == "eq:factors"]
    assert any(lhs == r"\sigma_k" for lhs, _ in factors.rows)
    md = to_markdown(blocks)
    assert max(len(line) for line in md.splitlines()) <= 300
    assert "too long to print" not in md and "terms not shown" not in md


def test_a_firing_table_of_many_realizations_shows_as_many_as_fit():
    blocks = story(derive_paper(realizations=12))
    _rows_fit(blocks)
    notes = [b.text for b in blocks if isinstance(b, Text) and "of the 12 realizations" in b.text]
    assert len(notes) == 3  # the three G3 G2 G1 circuits; the IFP controller has one
