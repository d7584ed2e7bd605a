"""Shared fixtures and hypothesis settings."""

from __future__ import annotations

import os
import shutil

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "symctl",
    max_examples=int(os.environ.get("SYMCTL_EXAMPLES", "40")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    # CI replays the same examples on every run (reproducible verdicts); local runs explore.
    derandomize=bool(os.environ.get("CI")),
)
settings.load_profile("symctl")


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(12345)


@pytest.fixture
def pdflatex() -> str:
    """The pdflatex executable; skips the test without it (fails where CI requires it)."""
    exe = shutil.which("pdflatex")
    if exe is None:
        if os.environ.get("SYMCTL_REQUIRE_PDFLATEX"):
            pytest.fail("pdflatex is required (SYMCTL_REQUIRE_PDFLATEX is set) but not installed")
        pytest.skip("pdflatex is not installed (Debian: apt-get install texlive-latex-base)")
    return exe
