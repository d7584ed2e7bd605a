"""Hostile output folders: a folder is the old complete one or the new complete one, never a mix.

``symctl paper`` and ``PaperResults.write`` stage the files beside
``--out``, lock ``<out>.lock``, and rename the staged folder into place only when
every file is written; a bad ``--out`` is refused before any derivation; an error,
a second run, SIGINT or SIGTERM leave ``--out`` as it was, no staged folder, no
lock file and no worker process behind.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from matplotlib.figure import Figure

from symctl import PaperResults, derive_paper
from symctl.cli import main
from symctl.errors import LatexError, ParameterError, SymctlError, SymctlTypeError
from symctl.report import document, output
from symctl.report import figures as figures_module

CLASS = "2"

OLD = {"results.json": '{"old": true}\n', "report.md": "# old run\n", "open_loop.png": "old png"}


@pytest.fixture(scope="module")
def res() -> PaperResults:
    return derive_paper(realizations=1)


def _old_run(folder: Path) -> dict[str, str]:
    """An earlier run's folder (its files, by name)."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in OLD.items():
        (folder / name).write_text(text)
    return _contents(folder)


def _contents(folder: Path) -> dict[str, str]:
    return {p.name: p.read_bytes().decode(errors="replace") for p in sorted(folder.iterdir())}


def _leftovers(parent: Path, name: str) -> list[str]:
    """What a run on ``parent/name`` may leave beside it: staged folders, backups, the lock."""
    return sorted(p.name for p in parent.iterdir() if p.name != name)


def _one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def _processes():
    """``(pid, stat fields after the name)`` of every process (from /proc: psutil is no dependency)."""
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                yield int(entry.name), (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue


def _children(pid: int) -> list[int]:
    """The living processes whose parent is ``pid``."""
    return [p for p, fields in _processes() if int(fields[1]) == pid and fields[0] != "Z"]


def _in_group(pgid: int) -> list[int]:
    """The processes of process group ``pgid`` (zombies included: they are not reaped)."""
    return [p for p, fields in _processes() if int(fields[2]) == pgid]


# ---------------------------------------------------------------- refused before any work
def _bad_outs(tmp: Path) -> dict[str, tuple[str, str]]:
    """Unusable output folders, by case: (the --out text, a word of the message)."""
    (tmp / "file").write_text("a file")
    (tmp / "foreign").mkdir()
    (tmp / "foreign" / "thesis.tex").write_text("my own work")
    (tmp / "dir_named_like_ours").mkdir()
    (tmp / "dir_named_like_ours" / "derivation.tex").mkdir()
    (tmp / "dir_named_like_ours" / "derivation.tex" / "notes.txt").write_text("mine")
    return {
        "empty": ("", "must name a folder"),
        "blank": ("   ", "must name a folder"),
        "a file": (str(tmp / "file"), "is a file, not a folder"),
        "under a file": (str(tmp / "file" / "sub"), "is a file"),
        "under /dev/null": ("/dev/null/out", "is a file"),
        "holds other files": (
            str(tmp / "foreign"),
            "holds files that symctl paper, derive, atlas and fit do not",
        ),
        "a folder named derivation.tex": (str(tmp / "dir_named_like_ours"), "derivation.tex"),
        "NUL": (str(tmp / "a\0b"), "NUL"),
        "root": ("/", "root"),
        "not creatable (/proc)": ("/proc/symctl-no-such/out", "cannot make"),
    }


BAD_CASES = [
    "empty",
    "blank",
    "a file",
    "under a file",
    "under /dev/null",
    "holds other files",
    "a folder named derivation.tex",
    "NUL",
    "root",
    "not creatable (/proc)",
]


def _no_derivation(*args, **kwargs):
    raise AssertionError("the derivation ran before --out was checked")


@pytest.mark.parametrize("case", BAD_CASES)
def test_cli_refuses_an_unusable_out_before_deriving(tmp_path, capsys, monkeypatch, case):
    text, word = _bad_outs(tmp_path)[case]
    before = {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*")}
    monkeypatch.setattr("symctl.derivation.pipeline.derive_paper", _no_derivation)
    if "\0" in text:  # the OS refuses NUL in argv: the API's check is the one tested
        with pytest.raises(ParameterError, match=r"out: .*NUL"):
            output.check_output_folder(text, "--out")
        return
    assert main(["paper", "--out", text, "--no-pdf"]) == 2
    line = _one_error_line(capsys.readouterr().err)
    assert line.startswith("symctl: error: --out:") and word in line, line
    assert {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*")} == before  # nothing touched


@pytest.mark.parametrize("case", BAD_CASES)
def test_write_refuses_an_unusable_out_before_writing(res, tmp_path, monkeypatch, case):
    text, word = _bad_outs(tmp_path)[case]
    before = {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*")}
    monkeypatch.setattr("symctl.report.results.write_files", _no_derivation)
    with pytest.raises(ParameterError) as info:
        res.write(text, pdf=False)
    assert str(info.value).startswith("out: ") and word in str(info.value)
    assert {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*")} == before


@pytest.mark.parametrize("out", [None, 3, 1.5, b"out", ["out"]])
def test_write_refuses_an_out_that_is_not_a_path_as_a_type_error(res, out):
    with pytest.raises(SymctlTypeError, match="out: expected a folder path"):
        res.write(out, figures=False, pdf=False)


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_a_read_only_parent_is_refused_before_deriving(tmp_path, capsys, monkeypatch):
    ro = tmp_path / "ro"
    ro.mkdir(mode=0o555)
    monkeypatch.setattr("symctl.derivation.pipeline.derive_paper", _no_derivation)
    assert main(["paper", "--out", str(ro / "out")]) == 2
    assert "not writable" in _one_error_line(capsys.readouterr().err)


# ---------------------------------------------------------------- errors while writing
def _tex_is_a_folder(blocks, path, **kwargs):
    Path(path).mkdir()  # derivation.tex is a folder in the staged folder
    return _real_write_tex(blocks, path, **kwargs)


_real_write_tex = document.write_tex


def _latex_fails(tex, **kwargs):
    raise LatexError("pdflatex failed on derivation.tex: ! Undefined control sequence.")


def _interrupted(blocks, path, **kwargs):
    raise KeyboardInterrupt


WRITE_ERRORS = {
    "derivation.tex is a folder": ("write_tex", _tex_is_a_folder, IsADirectoryError),
    "pdflatex fails": ("compile_pdf", _latex_fails, LatexError),
    "Ctrl-C while writing": ("write_markdown", _interrupted, KeyboardInterrupt),
}


@pytest.mark.parametrize("case", list(WRITE_ERRORS))
def test_an_error_while_writing_leaves_the_old_folder_and_no_staged_one(
    res, tmp_path, monkeypatch, case
):
    name, fake, error = WRITE_ERRORS[case]
    out = tmp_path / "paper"
    old = _old_run(out)
    monkeypatch.setattr(document, name, fake)
    with pytest.raises(error):
        res.write(out, figures=False, pdf=True)
    assert _contents(out) == old and _leftovers(tmp_path, "paper") == []


def test_an_error_while_writing_is_one_line_and_exit_2_on_the_cli(tmp_path, capsys, monkeypatch):
    out = tmp_path / "paper"
    old = _old_run(out)
    monkeypatch.setattr(document, "write_tex", _tex_is_a_folder)
    assert (
        main(["paper", "--out", str(out), "--no-figures", "--no-pdf", "--realizations", "1"]) == 2
    )
    line = _one_error_line(capsys.readouterr().err)
    assert line.startswith("symctl: error: --out:") and "derivation.tex" in line
    assert _contents(out) == old and _leftovers(tmp_path, "paper") == []


def _broken_figure(res, name):
    """The nonlinear figure fails; every other one is a quick dot (the real ones are drawn and
    saved elsewhere: here only the failure's path matters)."""
    if name == "nonlinear":
        raise RuntimeError("drawing failed")
    return Figure(figsize=(1, 1))


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_failing_figure_stops_every_worker_and_leaves_the_old_folder(
    res, tmp_path, monkeypatch, jobs
):
    out = tmp_path / "paper"
    old = _old_run(out)
    monkeypatch.setattr(figures_module, "make_figure", _broken_figure)  # forked workers see it
    with pytest.raises(RuntimeError, match="drawing failed"):
        res.write(out, pdf=False, jobs=jobs)
    assert _contents(out) == old and _leftovers(tmp_path, "paper") == []
    assert _children(os.getpid()) == []


def _killed_figure(res, name):
    """The worker drawing the nonlinear figure is killed outright (as the OOM killer would)."""
    if name == "nonlinear":
        os.kill(os.getpid(), signal.SIGKILL)
    return Figure(figsize=(1, 1))


def test_a_killed_figure_worker_is_an_error_not_a_hang(res, tmp_path, monkeypatch):
    out = tmp_path / "paper"
    old = _old_run(out)
    monkeypatch.setattr(figures_module, "make_figure", _killed_figure)  # forked workers see it
    with pytest.raises(SymctlError, match="a figure worker died"):
        res.write(out, pdf=False, jobs=2)
    assert _contents(out) == old and _leftovers(tmp_path, "paper") == []
    assert _children(os.getpid()) == []


class _Stopped(BaseException):
    pass


_ARMED: list = []


def _signal_in_fork() -> None:
    """After a fork, in the parent: SIGTERM when armed (as if it came at that instant)."""
    if _ARMED:
        _ARMED.clear()
        os.kill(os.getpid(), signal.SIGTERM)


os.register_at_fork(after_in_parent=_signal_in_fork)


def test_a_signal_while_the_workers_are_forked_is_raised_after_not_lost():
    # a handler's exception raised inside the fork's own hooks is printed and ignored:
    # unless the signal is held back while forking, the run goes on as if never stopped
    from symctl.report.workers import FigureWorkers

    def stop(signum, frame):
        raise _Stopped(signum)

    previous = signal.signal(signal.SIGTERM, stop)
    try:
        _ARMED.append(True)
        with pytest.raises(_Stopped), FigureWorkers(jobs=2):
            pytest.fail("the signal was lost")
    finally:
        _ARMED.clear()
        signal.signal(signal.SIGTERM, previous)
    assert _children(os.getpid()) == []


RENAME_FAILURES = {
    "staged -> out fails (disk full)": (".paper.tmp-", OSError(28, "No space left on device")),
    "Ctrl-C between the two renames": (".paper.tmp-", KeyboardInterrupt()),
    "out -> .old fails": ("paper", OSError(16, "Device or resource busy")),
}


@pytest.mark.parametrize("case", list(RENAME_FAILURES))
def test_a_failing_rename_into_place_puts_the_old_folder_back(res, tmp_path, monkeypatch, case):
    source, error = RENAME_FAILURES[case]  # the rename whose source name starts so fails
    out = tmp_path / "paper"
    old = _old_run(out)
    real_replace = os.replace

    def replace(src, dst):
        name = Path(src).name
        if name == source or (source.endswith("-") and name.startswith(source)):
            raise error
        return real_replace(src, dst)

    monkeypatch.setattr(output.os, "replace", replace)
    with pytest.raises(type(error)):
        res.write(out, figures=False, pdf=False)
    assert _contents(out) == old and _leftovers(tmp_path, "paper") == []


# ---------------------------------------------------------------- complete replacement
def test_a_new_run_replaces_every_file_of_the_old_one(res, tmp_path):
    out = tmp_path / "paper"
    _old_run(out)
    (out / "derivation.aux").write_text("left by a failed pdflatex")
    out.chmod(0o750)
    written = res.write(out, figures=False, pdf=False)
    assert [p.parent for p in written] == [out.resolve()] * 3
    assert sorted(p.name for p in out.iterdir()) == ["derivation.tex", "report.md", "results.json"]
    assert '"old"' not in (out / "results.json").read_text()  # no file of the old run is left
    assert (out.stat().st_mode & 0o777) == 0o750 and _leftovers(tmp_path, "paper") == []


def test_missing_parents_are_made_and_the_folder_has_the_usual_mode(res, tmp_path):
    out = tmp_path / "a" / "b" / "paper"
    res.write(out, figures=False, pdf=False)
    umask = os.umask(0)
    os.umask(umask)
    assert (out / "results.json").exists() and (out.stat().st_mode & 0o777) == 0o777 & ~umask


def test_what_a_killed_run_left_is_cleared_and_a_lost_folder_restored(res, tmp_path):
    out = tmp_path / "paper"
    (tmp_path / ".paper.tmp-0badf00d").mkdir()  # a staged folder of a killed run
    (tmp_path / ".paper.tmp-0badf00d" / "results.json").write_text("{}")
    backup = tmp_path / ".paper.old-0badf00d"  # killed between the renames: out is missing
    old = _old_run(backup)
    with output.OutputFolder(out) as folder:
        assert _contents(out) == old  # the old folder is back in its place
        assert _leftovers(tmp_path, "paper") == sorted([folder.staging.name, "paper.lock"])
    assert _leftovers(tmp_path, "paper") == [] and list(out.iterdir()) == []  # staged: nothing
    res.write(out, figures=False, pdf=False)
    assert _leftovers(tmp_path, "paper") == []


# ---------------------------------------------------------------- two runs at once
_HOLDER = """
import sys, time
from symctl.report.output import OutputFolder
with OutputFolder(sys.argv[1]) as folder:
    (folder.staging / "results.json").write_text("{}")
    print("locked", flush=True)
    time.sleep(60)
"""


def _holder(out: Path) -> subprocess.Popen:
    proc = subprocess.Popen(
        [sys.executable, "-c", _HOLDER, str(out)], stdout=subprocess.PIPE, text=True
    )
    assert proc.stdout.readline().strip() == "locked"
    return proc


def test_a_second_run_on_the_same_out_is_refused_at_once(res, tmp_path, capsys, monkeypatch):
    out = tmp_path / "paper"
    old = _old_run(out)
    holder = _holder(out)
    try:
        monkeypatch.setattr("symctl.derivation.pipeline.derive_paper", _no_derivation)
        # refused before any work: the derivation is replaced by one that fails the test
        assert main(["paper", "--out", str(out), "--no-pdf"]) == 2
        line = _one_error_line(capsys.readouterr().err)
        assert f"being written by another symctl run (pid {holder.pid}" in line
        assert line.startswith("symctl: error: --out:")
        with pytest.raises(ParameterError, match=r"out: .* being written by another symctl run"):
            res.write(out, figures=False, pdf=False)
        assert _contents(out) == old
    finally:
        holder.kill()
        holder.wait()
    # killed outright: its lock is gone with it, its staged folder is cleared by the next run
    res.write(out, figures=False, pdf=False)
    assert _leftovers(tmp_path, "paper") == [] and '"old"' not in (out / "results.json").read_text()


def test_two_cli_runs_at_once_give_one_complete_folder(tmp_path):
    out = tmp_path / "paper"
    args = [sys.executable, "-m", "symctl.cli", "paper", "--out", str(out), "--no-figures"]
    args += ["--no-pdf", "--realizations", "1"]
    procs = {
        seed: subprocess.Popen(
            [*args, "--seed", str(seed)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        for seed in (3, 5)
    }
    codes = {seed: (p.wait(timeout=300), p.stderr.read()) for seed, p in procs.items()}
    winners = [seed for seed, (code, _) in codes.items() if code == 0]
    assert winners, codes
    for code, err in codes.values():
        assert code in (0, 2), err
        if code == 2:
            assert "being written by another symctl run" in _one_error_line(err)
    import json

    seed = json.loads((out / "results.json").read_text())["parameters"]["seed"]
    assert seed in winners
    assert sorted(p.name for p in out.iterdir()) == ["derivation.tex", "report.md", "results.json"]
    assert _leftovers(tmp_path, "paper") == []


# ---------------------------------------------------------------- signals
SIGNALS = {
    "SIGTERM to the process, in the figures": (signal.SIGTERM, False, "figures"),
    "SIGINT to the group (Ctrl-C), in the figures": (signal.SIGINT, True, "figures"),
    "SIGINT to the process, in the figures": (signal.SIGINT, False, "figures"),
    "SIGTERM to the process, in the derivation": (signal.SIGTERM, False, "derivation"),
    "SIGTERM to the group, in the derivation": (signal.SIGTERM, True, "derivation"),
}


def _staged(parent: Path, name: str, pattern: str) -> bool:
    return any(any(p.glob(pattern)) for p in parent.glob(f".{name}.tmp-*"))


@pytest.mark.parametrize("case", list(SIGNALS))
def test_a_signal_stops_every_worker_and_leaves_the_old_folder(tmp_path, case):
    sig, group, when = SIGNALS[case]
    out = tmp_path / "paper"
    old = _old_run(out)
    cmd = [sys.executable, "-m", "symctl.cli", "paper", "--out", str(out), "--no-pdf"]
    proc = subprocess.Popen(
        [*cmd, "--jobs", "2"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,  # its own process group: the workers are found by it
    )
    try:
        pattern = "*.png" if when == "figures" else "*"
        for _ in range(6000):  # polls 0.02 s apart: a hang guard, not a speed assertion
            if (when == "derivation" and (tmp_path / "paper.lock").exists()) or (
                when == "figures" and _staged(tmp_path, "paper", pattern)
            ):
                break
            assert proc.poll() is None, "it ended before it got there"
            time.sleep(0.02)
        else:
            pytest.fail("never got there")
        if when == "derivation":
            time.sleep(0.3)
        (os.killpg if group else os.kill)(proc.pid, sig)
        err = proc.communicate(timeout=120)[1]  # a hang guard, not a speed assertion
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 128 + sig, err
    line = _one_error_line(err)
    assert line.startswith("symctl: interrupted by " + signal.Signals(sig).name)
    time.sleep(0.2)
    assert _in_group(proc.pid) == []  # no worker left running (and none holding the terminal)
    assert _contents(out) == old and _leftovers(tmp_path, "paper") == []


# ---------------------------------------------------------------- pdflatex that misbehaves
@pytest.mark.parametrize("kind", ["hangs", "not executable"])
def test_a_misbehaving_pdflatex_is_a_latex_error(tmp_path, monkeypatch, kind):
    exe = tmp_path / "pdflatex"
    exe.write_text("#!/bin/sh\nexec sleep 30\n")
    if kind == "hangs":
        exe.chmod(0o755)
        monkeypatch.setattr(document, "PDFLATEX_TIMEOUT", 0.5)
    tex = document.write_tex([document.Text("Hello.")], tmp_path / "a.tex")
    # the hanging one is stopped by the timeout (its message says so), not waited for
    expected = (
        r"pdflatex did not finish a\.tex within 0\.5 s" if kind == "hangs" else r"pdflatex .*a\.tex"
    )
    with pytest.raises(LatexError, match=expected):
        document.compile_pdf(tex, pdflatex=str(exe))


def test_stale_leftovers_that_are_links_or_files_are_removed_without_following(res, tmp_path):
    target = tmp_path / "elsewhere"
    target.mkdir()
    (target / "keep.txt").write_text("not ours")
    parent = tmp_path / "p"
    parent.mkdir()
    (parent / ".paper.tmp-0000beef").symlink_to(target)
    (parent / ".paper.old-1111beef").symlink_to(tmp_path / "missing")  # a broken link
    (parent / ".paper.tmp-2222beef").write_text("a file")
    res.write(parent / "paper", figures=False, pdf=False)
    assert sorted(p.name for p in parent.iterdir()) == ["paper"]
    assert (target / "keep.txt").read_text() == "not ours"


def test_every_file_symctl_atlas_writes_counts_as_an_earlier_runs(tmp_path):
    names = [
        "atlas.json",
        "atlas.md",
        "atlas_overview.pdf",
        "atlas_conjectured.png",
        "class_A3.svg",
    ]
    for name in names:
        (tmp_path / name).write_text("")
    assert output._foreign(tmp_path) == []
