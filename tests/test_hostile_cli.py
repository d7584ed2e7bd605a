"""Hostile command lines: one line on stderr, never a traceback or a NumPy warning, exit 2.

A symctl error names the option;
a NumPy/SciPy/SymPy exception that bad input causes (``TypeError``,
``LinAlgError``, ``MemoryError``, ``OverflowError``, ...) is one line naming the
step it stopped and the options that step depends on, exit 2; any other exception
is one line ``symctl: internal error: ...``, exit 1; warnings of a successful
run are one line ``symctl: warning: ...``.
"""

from __future__ import annotations

import subprocess
import sys
import warnings

import numpy as np
import pytest

from symctl.cli import main
from symctl.errors import ParameterError

CLASS = "5"

HOSTILE = [
    # (the options, a word the one line must hold)
    (["--q", "1e9999"], "--q"),
    (["--r", "1e9999"], "--r"),
    (["--q", "0", "--r", "0"], "--r"),
    (["--seed", "-1"], "--seed"),
    (["--seed", "1e3"], "--seed"),
    (["--q", "nan"], "--q"),
    (["--q", "inf"], "--q"),
    (["--r", "-inf"], "--r"),
    (["--q", "1/0"], "--q"),
    (["--q", "-1"], "--q"),
    (["--q", "[[1]"], "--q"),
    (["--r", ""], "--r"),
    (["--q", "[[1, 2]]"], "--q"),
    (["--tau", "nan"], "--tau"),
    (["--f-max", "nan"], "--f-max"),
    (["--ts", "inf"], "--ts"),
    (["--ts", "1e-300"], ""),
    (["--f-max", "1e308"], ""),  # ten NumPy warnings before the error: none may show
    (["--q", "1e300"], ""),
    (["--tau", "1e-300"], ""),
    (["--actuator-delay", "-1"], "--actuator-delay"),
    (["--jobs", "-1"], "--jobs"),
    (["--out", ""], "--out"),
    (["--realizations", "-5"], "--realizations"),
]


def _one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err and ".py:" not in err, err  # no traceback, no shown warning
    return lines[0]


def _names(line: str, word: str) -> bool:
    """The line names the option as typed (``""``: a foreign exception, named by its step)."""
    return word in line


@pytest.mark.parametrize("args, word", HOSTILE, ids=[" ".join(a) for a, _ in HOSTILE])
def test_hostile_options_give_one_line_and_exit_2(tmp_path, capfd, args, word):
    code = main(["paper", "--out", str(tmp_path / "out"), "--no-figures", "--no-pdf", *args])
    line = _one_line(capfd.readouterr().err)
    assert code == 2 and line.startswith("symctl: error:") and _names(line, word), line
    assert not (tmp_path / "out").exists() and list(tmp_path.iterdir()) == []


HUGE = [
    (["--q", "exp(exp(exp(exp(10))))"], "--q: the value of 'exp(exp(exp(exp(10))))' is too large"),
    (["--r", "exp(exp(exp(exp(10))))"], "--r: the value of 'exp(exp(exp(exp(10))))' is too large"),
    (["--q", "exp(1000)"], "--q: the value of 'exp(1000)' is too large"),
    (["--r", "[[10**400]]"], "--r: the value of '10**400' is too large"),
    (["--q", "2^3"], "--q: '^' is not a power in '2^3'; use ** for powers"),
]


@pytest.mark.parametrize("args, words", HUGE, ids=[" ".join(a) for a, _ in HUGE])
def test_a_huge_or_misspelled_weight_names_its_option_and_the_problem(tmp_path, capfd, args, words):
    code = main(["paper", "--out", str(tmp_path / "out"), "--no-figures", "--no-pdf", *args])
    line = _one_line(capfd.readouterr().err)
    assert code == 2 and line.startswith(f"symctl: error: {words}"), line


DATA = "examples/data/paper_fit.csv"
PAPER = ["paper", "--no-figures", "--no-pdf"]
OPTIONS = [
    # (a command line with one bad option, that option as typed)
    ([*PAPER, "--tau", "-1"], "--tau"),
    ([*PAPER, "--tau", "x"], "--tau"),
    ([*PAPER, "--f-max", "0"], "--f-max"),
    ([*PAPER, "--r-bar", "x"], "--r-bar"),
    ([*PAPER, "--r-bar", "inf"], "--r-bar"),
    ([*PAPER, "--ts", "0"], "--ts"),
    ([*PAPER, "--sensor-delay", "-1"], "--sensor-delay"),
    ([*PAPER, "--sensor-delay", "21"], "--sensor-delay, --actuator-delay"),
    ([*PAPER, "--actuator-delay", "-1"], "--actuator-delay"),
    ([*PAPER, "--q", "[[1, 2]]"], "--q"),
    ([*PAPER, "--r", "0"], "--r"),
    ([*PAPER, "--seed", "-1"], "--seed"),
    ([*PAPER, "--realizations", "1001"], "--realizations"),
    ([*PAPER, "--jobs", "0"], "--jobs"),
    ([*PAPER, "--formats", "jpg"], "--formats"),
    (["derive", "examples/muscle.toml", "--no-pdf", "--jobs", "0"], "--jobs"),
    (["derive", "examples/muscle.toml", "--formats", "pdf;png"], "--formats"),
    (["atlas", "--order", "0"], "--order"),
    (["atlas", "--order", "5"], "--order"),
    (["atlas", "--order", "x"], "--order"),
    (["atlas", "--order", "1", "--max-size", "-1"], "--max-size"),
    (["atlas", "--order", "1", "--workers", "0"], "--workers"),
    (["atlas", "--order", "1", "--max-neurons", "0"], "--max-neurons"),
    (["atlas", "--order", "1", "--drawings", "-1"], "--drawings"),
    (["dale", "--timeout", "-1"], "--timeout"),
    (["dale", "--timeout", "nan"], "--timeout"),
    (["dale", "--sensor-delay", "-1"], "--sensor-delay"),
    (["dale", "--actuator-delay", "-1"], "--actuator-delay"),
    (["dale", "--sensor-delay", "1000"], "--sensor-delay, --actuator-delay"),
    (["dale", "--samples", "-1"], "--samples"),
    (["dale", "--atlas", "--workers", "0"], "--workers"),
    (["dale", "--circuit", "nope"], "--circuit"),
    (["fit", DATA, "--C", "nan"], "--C"),
    (["fit", DATA, "--C", "0"], "--C"),
    (["fit", DATA, "--starts", "0"], "--starts"),
    (["fit", DATA, "--seed", "-1"], "--seed"),
    (["fit", DATA, "--sensor-delay", "-1"], "--sensor-delay"),
    (["fit", DATA, "--actuator-delay", "-1"], "--actuator-delay"),
    (["fit", DATA, "--circuit", "nope"], "--circuit"),
    (["fit", DATA, "--workers", "0"], "--workers"),
]


@pytest.mark.parametrize("args, option", OPTIONS, ids=[" ".join(a) for a, _ in OPTIONS])
def test_every_commands_bad_option_is_named_as_typed(tmp_path, capfd, args, option):
    out = [] if args[0] == "dale" else ["--out", str(tmp_path / "out")]  # dale writes nothing
    code = main([*args, *out])
    line = _one_line(capfd.readouterr().err)
    typed = (f"symctl: error: {option}: ", f"Invalid value for '{option}'", f"for {option}:")
    assert code == 2 and any(t in line for t in typed), line
    assert "_" not in line.removeprefix("symctl: error: ").partition(": ")[0], line
    assert not (tmp_path / "out").exists()


CONSOLE = [
    (["--q", "0", "--r", "0"], "--r"),
    (["--q", "1e9999"], "--q"),
    (["--f-max", "1e308"], ""),  # ten NumPy/SciPy warnings reached stderr before the error
    (["--sensor-delay", "1000000"], "--sensor-delay"),  # a MemoryError today, a limit upstream
]


@pytest.mark.parametrize("args, word", CONSOLE, ids=[" ".join(a) for a, _ in CONSOLE])
def test_the_console_script_prints_no_traceback(tmp_path, args, word):
    cmd = [sys.executable, "-m", "symctl.cli", "paper", "--out", str(tmp_path / "out")]
    proc = subprocess.run(
        [*cmd, "--no-figures", "--no-pdf", *args],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    line = _one_line(proc.stderr)
    assert proc.returncode == 2 and line.startswith("symctl: error:") and _names(line, word), line


# ---------------------------------------------------------------- foreign exceptions
def _raises(exc: BaseException, where: str = "symctl.derivation.pipeline.lqr_gains"):
    def fake(*args, **kwargs):
        raise exc

    return where, fake


FOREIGN = {
    "LinAlgError in LQR": (np.linalg.LinAlgError("Singular matrix"), "lqr_gains", 2, "LQR"),
    "OverflowError in G(z)": (OverflowError("int too large"), "controller_tf", 2, "G(z)"),
    "MemoryError in the delays": (MemoryError(), "augment", 2, "--sensor-delay"),
    "ValueError in the simulation": (ValueError("x"), "circuit_firing", 2, "--realizations"),
    "RecursionError in the factors": (RecursionError("depth"), "factor", 2, "factorization"),
    "ZeroDivisionError in the plant": (ZeroDivisionError("0"), "MuscleModel", 2, "--tau"),
    "AttributeError (a bug)": (AttributeError("'NoneType' has no 'x'"), "lqr_gains", 1, "internal"),
    "KeyError (a bug)": (KeyError("K_0"), "controller_tf", 1, "internal error: KeyError"),
}


@pytest.mark.usefixtures("uncached_derive")
@pytest.mark.parametrize("case", list(FOREIGN))
def test_a_foreign_exception_is_one_line_naming_the_step(tmp_path, capfd, monkeypatch, case):
    exc, name, code, word = FOREIGN[case]
    monkeypatch.setattr(*_raises(exc, f"symctl.derivation.pipeline.{name}"))
    assert main(["paper", "--out", str(tmp_path / "out"), "--no-figures", "--no-pdf"]) == code
    line = _one_line(capfd.readouterr().err)
    assert line.startswith("symctl: error:" if code == 2 else "symctl: internal error:")
    assert word in line and type(exc).__name__ in line, line
    assert list(tmp_path.iterdir()) == []  # nothing staged, no lock left


@pytest.mark.usefixtures("uncached_derive")
def test_symctl_traceback_shows_the_traceback_of_a_bug(tmp_path, monkeypatch):
    monkeypatch.setenv("SYMCTL_TRACEBACK", "1")
    monkeypatch.setattr(*_raises(AttributeError("a bug")))
    with pytest.raises(AttributeError, match="a bug"):
        main(["paper", "--out", str(tmp_path / "out"), "--no-figures", "--no-pdf"])


# ---------------------------------------------------------------- warnings
def _warning_derivation(fail: bool):
    from symctl.derivation import pipeline

    real = pipeline.derive_paper

    def derive(**kwargs):
        with np.errstate(over="warn", invalid="warn"):
            np.exp(np.array([1000.0]))  # RuntimeWarning: overflow encountered in exp
            np.array([np.inf]) - np.array([np.inf])  # RuntimeWarning: invalid value
        warnings.warn("a SciPy-like warning", UserWarning, stacklevel=1)
        if fail:
            raise ParameterError("R: no stabilizing DARE solution")
        return real(**kwargs)

    return derive


def test_warnings_of_a_successful_run_are_one_line(tmp_path, capfd, monkeypatch):
    monkeypatch.setattr("symctl.derivation.pipeline.derive_paper", _warning_derivation(False))
    args = ["paper", "--out", str(tmp_path / "out"), "--no-figures", "--no-pdf"]
    assert main([*args, "--realizations", "1"]) == 0
    line = _one_line(capfd.readouterr().err)
    assert line.startswith("symctl: warning: RuntimeWarning: overflow encountered in exp")
    assert "(and 2 other warnings)" in line


def test_warnings_before_an_error_do_not_show(tmp_path, capfd, monkeypatch):
    monkeypatch.setattr("symctl.derivation.pipeline.derive_paper", _warning_derivation(True))
    assert main(["paper", "--out", str(tmp_path / "out"), "--no-figures", "--no-pdf"]) == 2
    assert _one_line(capfd.readouterr().err) == "symctl: error: --r: no stabilizing DARE solution"


def test_main_restores_the_signal_handlers_it_installs(tmp_path):
    import signal

    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    main(["paper", "--out", str(tmp_path / "out"), "--tau", "0"])
    assert {s: signal.getsignal(s) for s in before} == before
