"""Derivations shared by the report's tests (each is several seconds: derived once per session)."""

from __future__ import annotations

import pytest

from symctl import derive, derive_paper


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
