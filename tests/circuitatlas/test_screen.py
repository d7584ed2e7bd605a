"""The exact refutation screen: exact counts, generic counterexamples, and its agreement with decide."""

from __future__ import annotations

import random

import pytest
import sympy as sp
from flint import fmpq_poly
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl.circuitatlas.fibre import coefficient_polynomials, count_real
from symctl.circuitatlas.pattern import Pattern
from symctl.circuitatlas.rank import generic_rank
from symctl.circuitatlas.screen import TARGETS_PER_REGION, generic_degree, screen
from symctl.circuitatlas.search import canonical_masks
from symctl.circuitatlas.universality import decide
from symctl.symbols import z


def _pattern(text: str) -> Pattern:
    rows, h, m = (part.split() for part in text.split("|"))
    return Pattern.from_matrices(
        [[int(d) for d in r] for r in rows], [int(d) for d in h[0]], [int(d) for d in m[0]]
    )


# a fixed sample of order-3 patterns of 9 entries: proved universal (closed forms), refuted by a
# structural rule, refuted by a counterexample, and conjectured
SAMPLE = (
    "111 100 110 | 110 | 100",
    "110 111 010 | 110 | 100",
    "010 001 111 | 001 | 111",
    "111 100 101 | 110 | 100",
    "111 110 101 | 100 | 100",
    "111 110 010 | 110 | 100",
    "110 101 110 | 100 | 110",
    "011 111 010 | 110 | 100",
    "111 111 010 | 100 | 100",
)


def _agree(pattern: Pattern, per_region: int) -> tuple:
    """decide (seed 0) against an independent screen (seed 1, other targets and linear forms)."""
    ev = decide(pattern)
    checked = screen(pattern, per_region, seed=1)
    assert checked is not None  # 3n entries with a finite fibre: the screen applies
    if checked.universal is False:  # refuted by the screen: never reported universal
        assert ev.universal is False and ev.proved, (pattern.text, ev.method)
    if ev.universal:  # proved universal: every generic target of the screen has a real point
        assert checked.status == "conjectured" and checked.details["screened"] > 0
    return ev, checked


@pytest.mark.parametrize("text", SAMPLE)
def test_the_decision_and_an_independent_exact_screen_agree_on_a_fixed_sample(text):
    ev, checked = _agree(_pattern(text), 3)
    if ev.method == "real zeros":  # the structural rule's open set is where the screen fails
        assert checked.universal is False and checked.details["region"].endswith("complex zeros")


@pytest.mark.slow
def test_the_decision_and_the_full_screen_agree_on_every_fourth_full_rank_order_3_orbit():
    masks = canonical_masks(3, 9)[::4]
    full = [Pattern(3, m) for m in masks if generic_rank(Pattern(3, m)).rank == 6]
    assert len(full) > 40
    outcomes = [_agree(p, TARGETS_PER_REGION[3]) for p in full]
    assert any(ev.universal for ev, _ in outcomes)
    assert any(checked.universal is False for _, checked in outcomes)


def test_a_screen_counterexample_names_its_region_target_and_why_it_is_generic():
    pattern = _pattern("011 111 010 | 110 | 100")
    ev = screen(pattern)
    assert ev.universal is False and ev.proved and ev.method == "counterexample"
    assert ev.details["degree"] == ev.details["generic_degree"] == generic_degree(pattern) == 2
    assert "squarefree" in ev.details["generic"] and "none at infinity" in ev.details["generic"]
    a = [sp.Rational(v) for v in ev.details["a"]]
    c = [sp.Rational(v) for v in ev.details["c"]]
    again = count_real(pattern, a, c, random.Random(9))  # another linear form
    assert again["degree"] == 2 and again["real"] == 0 and not again["zero_entry"]


def test_positive_dimensional_fibres_are_not_screened():
    dense = Pattern(3, (1 << 15) - 1)
    assert screen(dense) is None and screen(_pattern(SAMPLE[0]), 0) is None


@settings(max_examples=examples(30), deadline=None)
@given(st.sampled_from(SAMPLE), st.integers(0, 2**32 - 1))
def test_a_target_made_from_a_real_realization_always_has_a_real_point(text, seed):
    """The screen never calls a reachable target unreachable (its counts are exact)."""
    pattern = _pattern(text)
    rng = random.Random(seed)
    values = {
        k: rng.choice([-1, 1]) * sp.Rational(rng.randint(1, 9), rng.randint(1, 5))
        for k in pattern.indices
    }
    a, c = coefficient_polynomials(*pattern.matrices(values))
    fibre = count_real(pattern, a, c, rng)
    if fibre is not None and fibre["degree"] == generic_degree(pattern):
        assert fibre["real"] >= 1


@settings(max_examples=examples(60), deadline=None)
@given(st.lists(st.integers(-20, 20), min_size=2, max_size=7))
def test_sturm_counts_the_real_roots_that_sympy_isolates(coeffs):
    from symctl.circuitatlas.fibre import real_root_count

    e = fmpq_poly(coeffs)
    if e.degree() < 1 or e.gcd(e.derivative()).degree() > 0:
        return
    assert real_root_count(e) == len(sp.Poly(coeffs[::-1], z).real_roots())
