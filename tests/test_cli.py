"""The `symctl` command: outputs, options and one-line errors with exit code 2."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from symctl.cli import main


def test_paper_writes_results_json_with_the_documented_keys(tmp_path, capsys):
    assert main(["paper", "--out", str(tmp_path), "--no-figures", "--no-pdf"]) == 0
    data = json.loads((tmp_path / "results.json").read_text())
    assert data["parameters"]["tau"] == 0.02 and data["parameters"]["seed"] == 0
    assert round(data["plant"]["f_bar"], 4) == 43.8635
    assert data["plant"]["A"] == [[pytest.approx(0.606531, abs=1e-6)]]
    assert data["plant"]["B"] == [[pytest.approx(4.641646, abs=1e-6)]]
    assert data["gains"]["K"][0] == pytest.approx([-0.0459719, -0.580041, -0.351813], abs=1e-6)
    assert data["controller"]["numerator"] == pytest.approx([-0.0459719], abs=1e-6)
    assert data["controller"]["denominator"] == pytest.approx([1, 0.580041, 0.351813], abs=1e-6)
    assert data["controller"]["proved"] is True
    assert len(data["closed_loop"]["poles"]) == 3
    out = capsys.readouterr().out
    assert "K_0" in out and "results.json" in out
    # numbers as a reader writes them: no "[[0.606531]]", no 15 digits, no "1." or "(1)/(1)"
    assert "A = exp(-T_s/tau) = 0.606531\n" in out and "Q~ = [[1  0  0] [0  0  0] [0  0  1]]" in out
    assert "F = [[0, 1], [K_2, K_1]]" in out and "0.0459718543789935" not in out


def test_the_summary_prints_numbers_short_and_a_missing_section_in_words(tmp_path, capsys):
    from symctl.cli.summary import SUMMARY_TEXT, _fmt, _long

    assert _fmt([[0.6065306597]]) == "0.606531" and _fmt([[1.0, 0.0]]) == "[[1  0]]"
    assert _fmt([[0.0] * 9] * 9) == "(9 x 9, in results.json)"
    assert _long("x" * (SUMMARY_TEXT + 1), "G2").startswith(f"({SUMMARY_TEXT + 1:,} characters")
    args = ["paper", "--out", str(tmp_path), "--no-figures", "--no-pdf", "--sensor-delay", "0"]
    assert main([*args, "--realizations", "1"]) == 0
    out = capsys.readouterr().out
    assert "G1 = 1 (no sensor delay),  G3 = (C_3)/(z - epsilon_3)" in out and "(1)/(1)" not in out


def test_paper_options_are_used(tmp_path):
    args = ["paper", "--out", str(tmp_path), "--tau", "0.05", "--sensor-delay", "2"]
    args += ["--actuator-delay", "3", "--q", "2", "--r", "[[0.5]]", "--seed", "7"]
    args += ["--f-max", "80", "--r-bar", "0.5", "--ts", "0.005", "--realizations", "2"]
    assert main([*args, "--no-figures", "--no-pdf"]) == 0
    data = json.loads((tmp_path / "results.json").read_text())
    p = data["parameters"]
    assert (p["tau"], p["f_max"], p["r_bar"], p["Ts"]) == (0.05, 80, 0.5, 0.005)
    assert (p["sensor_delay"], p["actuator_delay"], p["seed"]) == (2, 3, 7)
    assert p["Q"] == [[2.0]] and p["R"] == [[0.5]]
    assert len(data["gains"]["K"][0]) == 6
    assert len(data["controller"]["denominator"]) == 6
    assert data["delay_graph"]["chain_delays"] == [1, 1, 1, 1, 1]
    assert all(
        len(c["realizations"]) == (1 if k == "ifp" else 2) for k, c in data["circuits"].items()
    )
    assert data["circuits"]["controllable"]["neurons"]["count"] == 2 + 2 + 3
    assert (tmp_path / "derivation.tex").exists() and not (tmp_path / "open_loop.png").exists()


@pytest.mark.parametrize(
    "args, word",
    [
        (["--tau", "-1"], "--tau"),
        (["--f-max", "0"], "--f-max"),
        (["--ts", "0"], "--ts"),
        (["--sensor-delay", "-2"], "--sensor-delay"),
        (["--actuator-delay", "1.5"], "--actuator-delay"),
        (["--q", "[[1, 0], [0, 1]]"], "--q"),
        (["--r", "-3"], "--r"),
        (["--q", "__import__('os')"], "--q"),
        (["--tau", "abc"], "--tau"),
        (["--no-such-option"], "no-such-option"),
        (["--realizations", "0"], "--realizations"),
        (["--sensor-delay", "0", "--actuator-delay", "0"], "--sensor-delay, --actuator-delay"),
        (["--jobs", "0"], "--jobs"),
        (["--seed", "-1"], "--seed"),
    ],
)
def test_bad_input_prints_one_line_and_exits_2(tmp_path, capsys, args, word):
    assert main(["paper", "--out", str(tmp_path), *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("symctl: error:") and word in err[0]


@pytest.mark.slow
def test_console_script_has_no_traceback_on_bad_input(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "symctl.cli", "paper", "--tau", "0", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and proc.stderr.count("\n") == 1


def test_an_unwritable_output_folder_is_one_line_and_exit_2(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    args = ["paper", "--out", str(blocker / "sub"), "--no-figures", "--no-pdf"]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("symctl: error: --out:")


def test_the_console_script_run_is_public_and_exits_with_mains_code(monkeypatch):
    from symctl import cli

    assert set(cli.__all__) == {"main", "run"}
    monkeypatch.setattr(sys, "argv", ["symctl", "paper", "--tau", "0"])

    def _exit(code):  # run leaves by os._exit (no interpreter teardown): not in this process
        raise SystemExit(code)

    monkeypatch.setattr(cli.os, "_exit", _exit)
    with pytest.raises(SystemExit) as exit_info:
        cli.run()
    assert exit_info.value.code == 2


@pytest.mark.parametrize("formats", ["jpg", "", ",", "pdf;png", "pdf,eps"])
def test_bad_formats_are_one_line_and_exit_2_before_any_work(
    tmp_path, capsys, monkeypatch, formats
):
    def no_derivation(*args, **kwargs):
        raise AssertionError("the derivation ran before --formats was checked")

    monkeypatch.setattr("symctl.derivation.pipeline.derive_paper", no_derivation)
    assert main(["paper", "--out", str(tmp_path / "p"), "--formats", formats]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("symctl: error: --formats: ")
    assert not (tmp_path / "p").exists()


@pytest.mark.slow
def test_formats_choose_the_figure_files_and_each_document_shows_its_own(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    from symctl.report import figures

    monkeypatch.setattr(figures, "make_figure", lambda res, name: Figure(figsize=(1, 1)))
    args = ["paper", "--out", str(tmp_path), "--no-pdf", "--realizations", "1", "--jobs", "1"]
    assert main([*args, "--formats", "svg,png"]) == 0
    suffixes = {p.suffix for p in tmp_path.iterdir() if p.stem == "open_loop"}
    assert suffixes == {".svg", ".png"}
    assert "open_loop.png" in (tmp_path / "report.md").read_text()
    assert r"\fitgraphic{" not in (tmp_path / "derivation.tex").read_text()  # no PDF to include


def _terminal(monkeypatch, module):
    """The command's console as a terminal (the live progress draws only on one), into a string."""
    import io

    from rich.console import Console

    text = io.StringIO()
    monkeypatch.setattr(module, "_console", Console(file=text, force_terminal=True, width=120))
    return text


def test_paper_shows_each_step_and_each_figure_on_a_terminal_and_exits_0(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    from symctl import cli
    from symctl.report import figures

    monkeypatch.setattr(figures, "make_figure", lambda res, name: Figure(figsize=(1, 1)))
    shown = _terminal(monkeypatch, cli)
    args = ["paper", "--out", str(tmp_path), "--no-pdf", "--jobs", "1", "--formats", "png"]
    assert main([*args, "--seed", "5", "--realizations", "1"]) == 0
    text = shown.getvalue()
    assert "LQR ..." in text and "figures: open_loop ..." in text and "done  figures" in text


def test_dale_shows_its_stages_on_a_terminal_and_none_in_its_json_elsewhere(monkeypatch, capsys):
    from symctl.cli import dale

    assert main(["dale", "--circuit", "observable", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["circuits"][0]["feasible"] is False
    shown = _terminal(monkeypatch, dale)
    assert main(["dale", "--circuit", "observable,controllable", "--ei"]) == 0
    text = shown.getvalue()
    assert "dale observable (1 of 2): observable: z3 ..." in text
    assert "cheapest E/I circuit: A1 ..." in text
