"""The report's small helpers: widths, wrapping, words and folders (their examples, kept as tests)."""

from __future__ import annotations

import pytest

from symctl.errors import ParameterError
from symctl.report.figures import figure_formats
from symctl.report.longform import cell_width, column_widths, fit_rows, height, table_width
from symctl.report.model_story import counted, names_tex
from symctl.report.output import OutputFolder, check_output_folder
from symctl.report.prose import verbatim_lines


def test_widths_and_heights_are_counted_in_glyphs_and_lines():
    assert height("x") == 1 and height(r"\frac{a}{b}") == 2
    assert height(r"\begin{bmatrix}1 \\ 2 \\ 3\end{bmatrix}") == 3
    assert cell_width("abc") == 3 and cell_width("$x$") == 1.15
    assert column_widths(("a", "bb"), (("ccc", "d"),)) == [3, 2]
    assert table_width(("a", "bb"), (("ccc", "d"),)) == 9.8


def test_a_row_that_fits_is_left_as_it_is():
    assert fit_rows([("a", "1")]) == [("a", "1")]


def test_preformatted_text_wraps_with_its_continuations_indented():
    lines = verbatim_lines("  " + "word " * 30)
    assert len(lines) == 2 and lines[1][:8] == "      wo"


def test_counted_words_and_signal_names():
    assert (counted(1, "step"), counted(3, "realization")) == ("1 step", "3 realizations")
    assert names_tex(["theta", "f_flex"]) == r"$\theta$, $f_\text{flex}$"


def test_an_unknown_figure_format_is_refused_by_name():
    with pytest.raises(ParameterError, match="formats: unknown format 'jpg'; choose among pdf"):
        figure_formats("pdf,jpg")
    with pytest.raises(ParameterError, match="--formats: name at least one of"):
        figure_formats(" , ", "--formats")


def test_a_new_output_folder_is_accepted_and_a_failed_run_leaves_nothing(tmp_path):
    assert check_output_folder(tmp_path / "new").name == "new"
    with pytest.raises(RuntimeError), OutputFolder(tmp_path / "run"):
        raise RuntimeError("disk full")
    assert list(tmp_path.iterdir()) == []


def test_widths_of_fractions_tables_that_wrap_and_rows_broken_to_fit():
    from symctl.report.longform import width, wrapped_columns

    assert width("2") == 1.0 and width(r"\frac{a + b}{c}") == width("a + b") + 0.4
    wide = ("a circuit with a long name, " * 4, "$1$", "yes")
    assert wrapped_columns(("circuit", "n", "ok"), (wide,)) == (0,)
    assert wrapped_columns(("circuit", "n"), (("short", "$1$"),)) == ()
    sums = "$" + " - ".join(["K_{1,12} K_{2,21}"] * 12) + "$"
    assert wrapped_columns(("k", "a_k"), (("$1$", sums),)) == (1,)
    rows = fit_rows([("s", " + ".join(["x"] * 60))], budget=20)
    assert rows[:2] == [("s", "x + x + x + x + x"), (None, r"\qquad + x + x + x")]


def test_large_matrices_are_shown_by_their_diagonals_and_patterns():
    import numpy as np

    from symctl.report.matrixview import show_matrix

    view = show_matrix("D", 2 * np.eye(15) + np.eye(15, k=1))
    assert view.rows[0][1].startswith(r"\left[\begin{smallmatrix}")
    assert view.tables[0][2] == (
        ("${D}_{i,i}$", r"$i = 1, \dots, 15$", "$2$"),
        ("${D}_{i,i+1}$", r"$i = 1, \dots, 14$", "$1$"),
    )
    assert show_matrix("Q", np.diag([1.0, 0, 0, 0, 0, 1])).rows == [
        ("Q", r"\operatorname{diag}\left(1, \underbrace{0, \dots, 0}_{4}, 1\right)")
    ]


def test_prose_marks_become_latex_references_and_markdown_numbers():
    from symctl.report.prose import markdown_lines, markdown_text, tex_text

    assert tex_text("a_b & $a_b$ [#eq:x]") == r"a\_b \& $a_b$~\eqref{eq:x}"
    assert markdown_text("Fig. [#fig:a], [@x]", {}) == "Fig. ??, [??]"
    lines = markdown_lines("word " * 40 + "$a + b + c$")
    assert max(map(len, lines)) <= 100 and lines[-1].endswith("$a + b + c$")


def test_the_paper_is_cited_by_its_own_numbers():
    from symctl.report.reference import cite

    assert cite() == "[@li2024]"
    assert cite("Figs.", "full_diagram", "ocr_diagram") == "[@li2024, Figs. 9, 11]"
    assert cite("Sec.", "simulations") == "[@li2024, Sec. VI]"
    assert cite("Eq.", "transfer_fn") == "[@li2024, Eq. (9)]"
    with pytest.raises(ParameterError, match="labels"):
        cite("Fig.", "no_such_figure")


def test_units_read_as_prose_singular_after_one():
    from symctl.report.model_story import unit_text

    assert (unit_text("N*m*s"), unit_text("m/s**2"), unit_text("1")) == (" N m s", " m/s$^{2}$", "")
    assert (unit_text("spikes/s", 1.0), unit_text("spikes/s", 2.0)) == (" spike/s", " spikes/s")


def test_the_papers_parameters_and_the_reports_circuits():
    from symctl.report.spec import CIRCUITS, PAPER, circuit_specs

    assert (PAPER.tau, PAPER.f_max, PAPER.r_bar, PAPER.Ts) == (0.02, 60.0, 1.0, 0.01)
    assert CIRCUITS == ("ifp", "general", "controllable", "observable", "pathways")
    assert circuit_specs()["controllable"].title == "G3 G2 G1, controllable canonical G2"


def test_a_library_argument_in_an_error_is_named_as_the_option():
    from symctl.cli.options import options_named

    with pytest.raises(ParameterError, match=r"^--ts: must be a finite number > 0, got 0$"):
        with options_named(aliases={"dt": "--ts"}):
            raise ParameterError("dt: must be a finite number > 0, got 0")


@pytest.mark.parametrize(
    "args",
    [
        ["paper", "--realizations", "0"],
        ["dale", "--circuit", "diagonal"],
        ["fit", "no-such-file.csv", "--out", "never-written"],
        ["spiking", "--neurons", "10,ten", "--out", "never-written"],
    ],
)
def test_bad_input_to_each_command_exits_2(args):
    from symctl.cli import main

    assert main(args) == 2


def test_formats_come_once_each_in_the_house_order():
    assert figure_formats("png, svg,png") == ("svg", "png")


def test_figure_workers_run_a_task_per_name_and_refuse_zero_jobs():
    import operator

    from symctl.report.workers import FigureWorkers

    with FigureWorkers(jobs=2) as workers:
        assert workers.submit(operator.add, "fig_", ["a", "b"])() == {"a": "fig_a", "b": "fig_b"}
    with pytest.raises(ParameterError, match="jobs: must be an integer >= 1, got 0"):
        FigureWorkers(jobs=0)


def test_figure_workers_remove_the_values_handed_to_them_even_when_nobody_waits(
    tmp_path, monkeypatch
):
    import operator
    import tempfile

    from symctl.report.workers import FigureWorkers

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    with pytest.raises(RuntimeError, match="the caller failed"), FigureWorkers(jobs=2) as workers:
        pending = workers.submit(operator.add, "fig_", ["a"])  # never waited for
        assert len(list(tmp_path.iterdir())) == 1
        raise RuntimeError("the caller failed")
    assert callable(pending) and not list(tmp_path.iterdir())  # removed though still referenced


def test_blocks_become_latex_and_markdown():
    from symctl.report.document import Graphic, Math, Text, to_markdown, to_tex

    tex = to_tex([Text("100% sure: $a = 1$"), Math((("a", "1"),), "eq:a")], title="Demo")
    assert r"100\% sure: $a = 1$" in tex and r"\label{eq:a}" in tex
    md = to_markdown([Graphic("open_loop", "The open loop.")], title="Demo")
    assert md == "# Demo\n\n![The open loop.](open_loop.png)\n\n*Figure 1: The open loop.*\n"


def test_the_fit_writes_its_json_predictions_and_report(tmp_path):
    from symctl import MuscleModel, augment, fit, lqr_gains, synthetic_traces
    from symctl.report.fit import write_fit

    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    data = synthetic_traces(gains, sensor_delay=1, actuator_delay=1, rng=3)
    traces = data.select(["G2.x1", "G2.y"]).traces
    res = fit(traces, gains, sensor_delay=1, actuator_delay=1, C=1, starts=2)
    written = write_fit(res, tmp_path, figures=False)
    assert sorted(p.name for p in written) == ["fit.json", "predictions.csv", "report.md"]


def test_the_spiking_sweep_writes_its_json_and_markdown(tmp_path):
    pytest.importorskip("nengo")
    import symctl
    from symctl.report.spiking import write_spiking

    cost = symctl.spiking_cost(symctl.derive_paper(), circuits=["ifp"], neurons=(10, 30), seeds=1)
    written = write_spiking(cost, tmp_path, figures=False)
    assert sorted(p.name for p in written) == ["spiking.json", "spiking.md"]
