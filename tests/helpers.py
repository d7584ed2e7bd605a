"""Helpers shared by the tests (importable thanks to ``pythonpath = tests``)."""

from __future__ import annotations

import numpy as np


def random_plant(rng: np.random.Generator, n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """A random plant, controllable with probability one."""
    A = rng.normal(size=(n, n)) / np.sqrt(n)
    B = rng.normal(size=(n, m))
    return A, B


def paper_assignment(S) -> dict[str, int]:
    """The paper's assignment for G3 G2 G1: x and alpha1 (= C1 x) at v1, G2 at v2, G3's output at v3."""
    vertex = {}
    for name, block in S.blocks.items():
        if name in S.inputs or name == "G1.H":
            vertex[name] = 1
        elif block.part == "G3" and name != "G3.H":
            vertex[name] = 3
        else:
            vertex[name] = 2
    return vertex
