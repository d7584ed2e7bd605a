"""The layouts' isotonic fits, through SciPy, give what the hand-written pool-adjacent-violators gave.

The reference functions below are the layouts' former own PAVA, kept here only to
compare against on random data. On generic reals the rows are the same; where a
pooled mean is exactly half-way between two rows (barycenters of small integers),
the former float code fell either way by its rounding noise, and the rows are
compared with the same code run in exact rationals, which rounds half up.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from symctl.plotting.layered import fit_rows, isotonic


def _reference_rows(desired: list[float]) -> list[int]:
    blocks: list[list] = []  # [mean, weight] of pooled z_i = y_i + i, non-increasing
    for i, d in enumerate(desired):
        blocks.append([d + i, 1])  # exact for Fraction input
        while len(blocks) > 1 and blocks[-2][0] < blocks[-1][0]:
            mean, weight = blocks.pop()
            blocks[-1][0] = (blocks[-1][0] * blocks[-1][1] + mean * weight) / (
                blocks[-1][1] + weight
            )
            blocks[-1][1] += weight
    z = [mean for mean, weight in blocks for _ in range(int(weight))]
    rows = [math.floor(zi - i + 0.5) for i, zi in enumerate(z)]
    for i in range(1, len(rows)):
        rows[i] = min(rows[i], rows[i - 1] - 1)
    return rows


def _reference_pack(target, weight, gaps) -> np.ndarray:
    offset = np.concatenate(([0.0], np.cumsum(gaps)))
    blocks: list[list[float]] = []  # [mean, weight, count]
    for value, w in zip(np.asarray(target) - offset, weight, strict=True):
        blocks.append([value, w, 1])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            (m1, w1, c1), (m2, w2, c2) = blocks.pop(-2), blocks.pop()
            blocks.append([(m1 * w1 + m2 * w2) / (w1 + w2), w1 + w2, c1 + c2])
    return np.repeat([b[0] for b in blocks], [b[2] for b in blocks]) + offset


@pytest.mark.parametrize("seed", range(40))
def test_structure_rows_are_the_exact_pava_rows_on_random_barycenters(seed):
    rng = np.random.default_rng(seed)
    # barycenters as the layout makes them: means of a few integer rows, sorted top first
    parts = [
        rng.integers(-6, 7, size=int(rng.integers(1, 4))) for _ in range(int(rng.integers(0, 14)))
    ]
    desired = sorted((float(p.mean()) for p in parts), reverse=True)
    exact = sorted((Fraction(int(p.sum()), len(p)) for p in parts), reverse=True)
    assert fit_rows(desired) == _reference_rows(exact)


@pytest.mark.parametrize("seed", range(40))
def test_structure_rows_match_the_former_pava_rows_on_random_reals(seed):
    rng = np.random.default_rng(1000 + seed)
    desired = list(rng.normal(0.0, 3.0, size=int(rng.integers(1, 15))))
    assert fit_rows(desired) == _reference_rows(desired)


@pytest.mark.parametrize("seed", range(40))
def test_delay_graph_packing_is_the_former_weighted_pava_on_random_targets(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 12))
    target = rng.normal(0.0, 2.0, size=n)
    weight = rng.choice([0.5, 1.0, 30.0, 60.0, 91.0], size=n)
    gaps = rng.uniform(0.5, 2.0, size=n - 1)
    packed = isotonic(target, weight, gaps)
    np.testing.assert_allclose(packed, _reference_pack(target, weight, gaps), rtol=0, atol=1e-12)
    assert np.all(np.diff(packed) >= gaps - 1e-12)


def test_empty_layers_pack_and_row_to_nothing():
    assert fit_rows([]) == []
    assert isotonic(np.zeros(0), np.ones(0), np.zeros(0)).shape == (0,)
