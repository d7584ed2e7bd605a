"""check_realization(similar_to=(base, P)): the proof through a proved similar realization."""

from __future__ import annotations

import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import (
    SymctlTypeError,
    check_realization,
    controllable_canonical,
    controller_tf,
    factor,
    z,
)
from symctl.realization.realizers import random_full_rank


@pytest.mark.slow
@given(st.integers(1, 3), st.integers(0, 3), st.integers(0, 10**6))
@settings(max_examples=examples(25), deadline=None)
def test_similar_to_agrees_with_the_direct_proof(ds, da, seed):
    T = ds + da
    f = factor(controller_tf(T), ds, da)
    G2 = f.abbreviated()
    base = controllable_canonical(G2)
    P = random_full_rank(T, rng=seed)
    R = base.similar(P)
    via = check_realization(R, G2, similar_to=(base, P))
    assert via.ok and via.method == "exact" and via.details.startswith("similar to")
    assert check_realization(R, G2).ok
    wrong = G2.subs({f.sigma[0]: f.sigma[0] + 1})
    assert not check_realization(R, wrong, similar_to=(base, P)).ok
    assert not check_realization(R, wrong).ok


def test_a_wrong_transform_falls_back_to_the_direct_decision():
    f = factor(controller_tf(3), 1, 2)
    base = controllable_canonical(f.G2)
    P = random_full_rank(3, rng=1)
    R = base.similar(P)
    other = P + sp.eye(3)
    result = check_realization(R, f.G2, similar_to=(base, other))
    assert result.ok and not result.details.startswith("similar to")  # decided directly
    singular = sp.zeros(3, 3)
    assert not check_realization(R, f.G2, similar_to=(base, singular)).details.startswith("similar")
    # a realization that is not similar and not a realization of G2 is refused either way
    bad = base.similar(other)
    assert not check_realization(bad.subs({f.sensor_eps[0]: 2}), f.G2, similar_to=(base, P)).ok


def test_similar_to_is_checked():
    R = controllable_canonical(1 / (z - 2))
    with pytest.raises(SymctlTypeError, match="similar_to: expected a pair"):
        check_realization(R, 1 / (z - 2), similar_to=R)
