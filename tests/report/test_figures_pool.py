"""The figure pool never waits forever: a worker that dies outright is an error, not a hang."""

from __future__ import annotations

import os
import signal

import pytest

from symctl.report import figures


@pytest.mark.slow
def test_a_figure_worker_killed_outright_is_an_error_not_a_hang(tmp_path, monkeypatch):
    monkeypatch.setattr(figures, "FIGURE_TIMEOUT", 5)
    monkeypatch.setattr(figures, "figure_names", lambda res: ["a", "b"])
    monkeypatch.setattr(figures, "_worker", _die)
    with pytest.raises(RuntimeError, match=r"figure \w: no result within 5 s"):
        figures.write_figures(object(), tmp_path, jobs=2)


def _die(name):
    os.kill(os.getpid(), signal.SIGKILL)
