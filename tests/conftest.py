"""Shared fixtures and hypothesis settings."""

from __future__ import annotations

import os
import shutil

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

from symctl import derive, derive_paper

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


# ---------------------------------------------------------------- shared derivations
# derive is computed once per model (its cache): these fixtures, the doctests and any test
# asking for the same model in one run share one derivation.
@pytest.fixture(scope="session")
def derived_T2():
    """The paper's derivation as ``symctl paper`` runs it (T = 2)."""
    return derive_paper()


@pytest.fixture(scope="session")
def derived_T6():
    """The paper's muscle with three steps of delay on each side (T = 6)."""
    return derive_paper(sensor_delay=3, actuator_delay=3)


@pytest.fixture(scope="session")
def derived_oculomotor():
    """A model file with a matrix controller (two measured states, one input)."""
    return derive("examples/oculomotor.toml")


@pytest.fixture
def uncached_derive(monkeypatch):
    """derive computes afresh in this test (one that patches a stage); the shared cache stays."""
    from symctl.derivation import pipeline

    monkeypatch.setattr(
        pipeline,
        "_cached",
        lambda spec, progress: pipeline._derive(spec, progress.step, progress.early),
    )
