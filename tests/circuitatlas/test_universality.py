"""Universality verdicts: proofs, structural refutations, conjectures and generic counterexamples."""

from __future__ import annotations

import random

import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import z
from symctl.circuitatlas.pattern import Pattern
from symctl.circuitatlas.universality import (
    CONJECTURED,
    Evidence,
    decide,
    forced_real_zeros,
    generic_degree,
)


def _pattern(text: str) -> Pattern:
    """``"111 110 101 | 100 | 100"``: the rows of F, then H and M, as 0/1 digits."""
    rows, h, m = (part.split() for part in text.split("|"))
    return Pattern.from_matrices(
        [[int(d) for d in r] for r in rows], [int(d) for d in h[0]], [int(d) for d in m[0]]
    )


def _numerator(pattern: Pattern, rng: random.Random) -> sp.Poly:
    """M adj(zI - F) H of a random integer realization with exactly this support."""
    values = {k: rng.choice([-1, 1]) * rng.randint(1, 9) for k in pattern.indices}
    F, H, M = pattern.matrices(values)
    A = z * sp.eye(pattern.n) - F
    return sp.Poly(sp.expand((M * A.adjugate() * H)[0]), z)


SIMPLEST = "111 110 101 | 100 | 100"


def test_zeros_forced_real_refute_the_pattern_whose_numerator_is_m1_h1_z_minus_f22_z_minus_f33():
    ev = decide(_pattern(SIMPLEST))
    assert ev.universal is False and ev.proved and ev.method == "real zeros"
    assert ev.details["region"] == "complex zeros"
    assert ev.details["factors"] == ["(F_22 - z)", "(F_33 - z)"]


@settings(max_examples=examples(60), deadline=None)
@given(st.integers(min_value=0, max_value=2**15 - 1), st.integers(0, 2**32 - 1))
def test_a_pattern_refuted_by_real_zeros_has_only_real_zeros_at_random_realizations(mask, seed):
    pattern = Pattern(3, mask | 1 << 9 | 1 << 12)  # some H and M entry: a nonzero numerator
    ev = forced_real_zeros(pattern)
    if ev is None:
        return
    rng = random.Random(seed)
    for _ in range(5):
        b = _numerator(pattern, rng)
        if b.degree() == 2:
            assert len(sp.real_roots(b)) == 2  # exact: counted with multiplicity


def test_real_zeros_is_not_claimed_when_a_realization_has_complex_zeros():
    # the dense pattern reaches numerators with complex zeros: the rule must not fire
    dense = Pattern(3, (1 << 15) - 1)
    assert forced_real_zeros(dense) is None
    rng = random.Random(1)
    assert any(len(sp.real_roots(_numerator(dense, rng))) == 0 for _ in range(20))


def test_witnesses_make_a_conjecture_never_a_universal_verdict():
    conj = Evidence(None, CONJECTURED, False, "witnesses at sampled G2")
    assert not conj and conj.universal is None and conj.conjectured and not conj.proved
    assert (
        conj.status == "conjectured"
        and conj.verdict is None
        and Evidence.from_dict(conj.to_dict()) == conj
    )


def test_a_lift_from_a_conjectured_pattern_is_a_conjecture_and_from_a_proof_a_proof():
    ccf = Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1])
    dense = Pattern(2, (1 << 8) - 1)
    conj = Evidence(None, CONJECTURED, False, "witnesses at sampled G2")
    ev = decide(dense, [(ccf, conj)], exact=False)  # no exact proof of its own: a lift
    assert ev.universal is None and ev.conjectured and not ev.proved
    assert ev.details["source"] == ccf.text and ev.details["lifted"]
    own = decide(dense, [(ccf, conj)])  # its own slice, of odd degree, proves it
    assert own.universal is True and own.method == "odd degree" and own.details["fixed"]
    proved = decide(ccf)
    ev = decide(dense, [(ccf, conj), (ccf, proved)])
    assert ev.universal is True and ev.method == "lifted" and ev.proved


def test_a_target_whose_fibre_lost_a_point_to_infinity_refutes_nothing():
    # generic targets have 3 complex realizations (odd: always a real one); the target
    # a = [5/256, -1/8, 3/8], c = [9/2, 1/2, -2] has 2, none real, and is not generic
    pattern = _pattern("100 111 110 | 100 | 110")
    assert generic_degree(pattern) == 3
    ev = decide(pattern)
    assert ev.method != "counterexample" and ev.universal is not False


# patterns an independent exact real-fibre count found with open sets of unreachable G2
DISPUTED = (
    "111 011 101 | 100 | 100",
    "111 101 010 | 110 | 100",
    "011 111 010 | 110 | 100",
    "011 011 110 | 110 | 100",
    "011 101 011 | 110 | 100",
    "101 101 110 | 100 | 110",
    "001 111 110 | 100 | 110",
    "010 111 101 | 100 | 110",
    "010 101 111 | 100 | 110",
    "011 110 100 | 110 | 110",
    "111 001 100 | 110 | 110",
    "011 011 100 | 110 | 110",
    "101 001 110 | 110 | 110",
)


@pytest.mark.parametrize("text", (SIMPLEST, *DISPUTED))
def test_every_disputed_pattern_is_refuted_with_a_proof(text):
    ev = decide(_pattern(text))
    assert ev.universal is False and ev.proved
    assert ev.method in ("real zeros", "counterexample")


@pytest.mark.parametrize("text", [t for t in DISPUTED if t != "111 011 101 | 100 | 100"])
def test_a_counterexample_is_a_generic_target_with_no_real_realization(text):
    from symctl.circuitatlas.fibre import solve_at

    pattern = _pattern(text)
    ev = decide(pattern)
    assert ev.method == "counterexample" and "zeros" in ev.details["region"]
    assert ev.details["degree"] == ev.details["generic_degree"] == generic_degree(pattern)
    a = [sp.Rational(v) for v in ev.details["a"]]
    c = [sp.Rational(v) for v in ev.details["c"]]
    sol = solve_at(pattern, a, c, rng=random.Random(5))  # another linear form, same fibre
    assert sol["degree"] == generic_degree(pattern) and not sol["real"]
    assert sp.Poly(sol["_e"], sol["_t"]).is_sqf  # simple points: robust to perturbation


def test_conjectured_classes_are_counted_and_drawn_apart_from_the_proved_ones(tmp_path):
    import dataclasses
    from types import MappingProxyType

    import symctl
    from symctl.circuitatlas.atlas import Atlas
    from symctl.report.atlas import claim_json, write_atlas

    A = symctl.atlas(2, workers=1)
    conj = Evidence(None, CONJECTURED, False, "witnesses at sampled G2")
    last = A.universal_classes[-1]
    guess = dataclasses.replace(
        last,
        evidence=conj,
        pattern_evidence=MappingProxyType(dict.fromkeys(last.pattern_evidence, conj)),
    )
    B = Atlas(2, A.delays, tuple(guess if c is last else c for c in A.classes), A.stats)
    assert len(B.universal_classes) == 8 and B.conjectured_classes == (guess,)
    assert guess.universal is None and guess.status == "conjectured"
    assert guess.to_dict()["universal"] is None and guess.to_dict()["conjectured"] is True
    assert B.table()[A.classes.index(last)]["universal"] == "conjectured"
    assert claim_json(B)["universal"] == 8 and claim_json(B)["conjectured"] == 1
    written = {p.name for p in write_atlas(B, tmp_path, drawings=1, pdf=False)}
    assert {"atlas_overview.png", "atlas_conjectured.png"} <= written
    assert "only conjectured universal" in (tmp_path / "atlas.md").read_text()
