"""Fixtures of the drawing tests."""

from __future__ import annotations

import pytest

from symctl import augment, controller_tf, factor


@pytest.fixture(scope="session")
def mimo_factorization():
    """G3 G2 G1 of a 4-state, 2-input plant (the antagonist pair's shape), gains symbolic."""
    A = [[1, 0.01, 0, 0], [-0.4, 0.96, 0.005, -0.005], [0, 0, 0.6, 0], [0, 0, 0, 0.6]]
    B = [[0, 0], [0.01, -0.01], [4.6, 0], [0, 4.6]]
    return factor(controller_tf(augment((A, B), 1, 1)), 1, 1)
