"""The exact screen of a fibre that is a curve: critical points of a distance, checked three ways."""

from __future__ import annotations

import random

import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl.circuitatlas.critical import _point, count_critical, critical_degree, curve_target
from symctl.circuitatlas.fibre import coefficient_polynomials, solve_at
from symctl.circuitatlas.pattern import Pattern
from symctl.circuitatlas.screen import _region_sample, _search_regions
from symctl.circuitatlas.universality import decide

# order 2, 7 entries: a curve of degree-7 critical systems (cheap)
CURVE_2 = Pattern.from_matrices([[0, 1], [1, 1]], [1, 1], [1, 1])
# order 3, 10 entries, proved universal by a slice of odd degree
UNIVERSAL_3 = Pattern.from_matrices([[1, 1, 0], [0, 0, 1], [1, 1, 1]], [0, 0, 1], [1, 1, 1])
# order 3, 10 entries, which no sampled witness refuted: the critical points do
REFUTED_3 = Pattern(3, 15079)


def _realized_target(pattern: Pattern, rng):
    values = {
        k: rng.choice([-1, 1]) * sp.Rational(rng.randint(1, 9), rng.randint(1, 5))
        for k in pattern.indices
    }
    return coefficient_polynomials(*pattern.matrices(values))


@pytest.mark.parametrize(
    "pattern",
    [CURVE_2, pytest.param(REFUTED_3, marks=pytest.mark.slow)],
    ids=["order 2", "order 3"],
)
def test_the_critical_degree_over_a_prime_field_is_the_count_at_a_random_rational_target(pattern):
    rng = random.Random(3)
    a = [sp.Rational(rng.randint(-999, 999), rng.randint(1, 999)) for _ in range(pattern.n)]
    c = [sp.Rational(rng.randint(-999, 999), rng.randint(1, 999)) for _ in range(pattern.n)]
    got = count_critical(pattern, a, c, _point(rng, 2 * pattern.n + 1), rng)
    assert got["degree"] == critical_degree(pattern) > 0


@settings(max_examples=examples(40), deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_a_target_made_from_a_real_realization_always_has_a_real_critical_point(seed):
    """The nearest point of a nonempty real fibre is a real solution: never none."""
    rng = random.Random(seed)
    a, c = _realized_target(CURVE_2, rng)
    got = count_critical(CURVE_2, a, c, _point(rng, 5), rng)
    if got is not None and got["degree"] == critical_degree(CURVE_2):
        assert got["real"] >= 1


def test_a_pattern_proved_universal_is_never_refuted_by_its_critical_points():
    rng = random.Random(0)
    for _, pairs, signs, zeros in _search_regions(3)[:6]:
        for _ in range(2):
            got = curve_target(UNIVERSAL_3, *_region_sample(3, pairs, signs, zeros, rng), rng)
            assert got is None or got["real"]


def test_a_curve_refutation_names_its_target_and_independent_slices_find_no_real_point():
    ev = decide(REFUTED_3)
    assert ev.universal is False and ev.proved and ev.method == "counterexample"
    assert ev.details["region"] in {r for r, *_ in _search_regions(3)}
    assert ev.details["degree"] == critical_degree(REFUTED_3) and "critical points" in ev.text
    a = [sp.Rational(v) for v in ev.details["a"]]
    c = [sp.Rational(v) for v in ev.details["c"]]
    rng = random.Random(11)  # another distance point: still no real critical point
    again = count_critical(REFUTED_3, a, c, _point(rng, 7), rng)
    assert again["degree"] == ev.details["degree"] and again["real"] == 0
    # independently: slices of the curve (one more entry fixed) are finite and have no real point
    slots = [k for k in REFUTED_3.indices if k not in set(REFUTED_3.tree_slots())]
    for s in (-7, -1, sp.Rational(1, 3), 2, 50):
        sol = solve_at(REFUTED_3, a, c, fixed={slots[-1]: s})
        assert sol is not None and sol["real"] == []


@pytest.mark.slow
def test_every_region_of_a_proved_universal_curve_has_an_exact_real_point():
    rng = random.Random(1)
    for region, pairs, signs, zeros in _search_regions(3):
        targets = (_region_sample(3, pairs, signs, zeros, rng) for _ in range(4))
        got = [curve_target(UNIVERSAL_3, a, c, rng) for a, c in targets]
        assert any(g is not None and g["real"] for g in got), region
        assert all(g is None or g["real"] for g in got), region
