"""Test tiers, and doctests in a fresh namespace.

Two tiers (``make test`` runs the fast one, ``make test-all`` both):

- **fast**: unit, property and doctests on small objects, and one end-to-end run
  of each CLI command;
- **slow** (marker ``slow``): every example end to end, the notebooks, PDF
  compiles, dask clusters, subprocess runs of the console script, the full
  paper's figures and documents.

A test is slow by its marker (``@pytest.mark.slow``) or by its location: the
files in ``SLOW_FILES`` and the doctests of the modules in ``SLOW_DOCTESTS`` (the
report's, whose examples write whole derivations). The tier of a test is decided
here and nowhere else.

Doctests run in a fresh namespace: an Examples block must import what it uses.
pytest gives a module's doctests the module's globals, so an example that forgets
an import still passes there but fails when pasted into a fresh interpreter.
Emptying the namespace makes every doctest self-contained.
"""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

import pytest
from _pytest.doctest import DoctestItem

ROOT = Path(__file__).resolve().parent

# whole files of the slow tier: end-to-end runs, notebooks, PDF compiles, subprocesses
SLOW_FILES = (
    "tests/test_notebooks.py",
    "tests/test_hostile_cli.py",
    "tests/model/test_examples.py",
    "tests/report/test_pipeline.py",
    "tests/report/test_hostile_output.py",
    "tests/report/test_document_log.py",
    "tests/report/test_figures.py",
    "tests/report/test_story_layout.py",
    "tests/report/test_story.py",
    "tests/report/test_pipeline_long_delays.py",
    "tests/derivation/test_derive_lqg.py",  # the LQG examples derived whole
    "tests/derivation/test_pathways.py",  # the forearm examples' pathways circuits
)
# modules whose doctests derive and write the whole paper, or decide hard cases
SLOW_DOCTESTS = (
    "symctl/report/",
    "symctl/dalelaw/dale.py",
    "symctl/circuitatlas/candidates.py",
    "symctl/dalelaw/interneurons.py",
)

# doctests that need the spiking extra (nengo, NEST): skipped without it, except where
# SYMCTL_REQUIRE_SPIKING is set (make test-all), where they run and fail if it is missing
SPIKING_DOCTESTS = (
    "symctl/spiking/nengo_export.py",
    "symctl/spiking/nest_export.py",
    "symctl/spiking/loop.py",
    "symctl/spiking/cost.py",
    "symctl/plotting/spiking.py",
    "symctl/report/spiking.py",
)
SPIKING_METHODS = (".to_nengo", ".to_nest")


def _spiking_installed() -> bool:
    return all(importlib.util.find_spec(m) is not None for m in ("nengo", "nest"))


def _is_slow(item) -> bool:
    path = Path(str(item.fspath)).resolve().relative_to(ROOT).as_posix()
    if isinstance(item, DoctestItem):
        return path.startswith(SLOW_DOCTESTS)
    return path in SLOW_FILES


def _needs_spiking(item) -> bool:
    path = Path(str(item.fspath)).resolve().relative_to(ROOT).as_posix()
    return path.startswith(SPIKING_DOCTESTS) or item.name.endswith(SPIKING_METHODS)


def pytest_collection_modifyitems(config, items):
    for item in items:
        if isinstance(item, DoctestItem):
            item.dtest.globs = {"__name__": "__main__"}
            if _needs_spiking(item) and not _spiking_installed():
                if not os.environ.get("SYMCTL_REQUIRE_SPIKING"):
                    item.add_marker(pytest.mark.skip(reason="pip install symctl[spiking]"))
        if _is_slow(item):
            item.add_marker(pytest.mark.slow)


def pytest_sessionstart(session):
    missing = [f for f in (*SLOW_FILES, *SLOW_DOCTESTS) if not (ROOT / f).exists()]
    if missing:  # a renamed file would silently join the fast tier
        raise pytest.UsageError(
            f"conftest.SLOW_FILES/SLOW_DOCTESTS name files that do not exist: {missing}"
        )
