"""Helpers shared by the tests (importable thanks to ``pythonpath = tests``)."""

from __future__ import annotations

import numpy as np


def random_plant(rng: np.random.Generator, n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """A random plant, controllable with probability one."""
    A = rng.normal(size=(n, n)) / np.sqrt(n)
    B = rng.normal(size=(n, m))
    return A, B
