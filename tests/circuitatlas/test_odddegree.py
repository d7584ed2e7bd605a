"""The odd-degree proof: proved patterns have a real realization at every sampled generic target."""

from __future__ import annotations

import random

import pytest
import sympy as sp

from symctl.circuitatlas.fibre import count_real
from symctl.circuitatlas.odddegree import _prove, odd_degree_proof
from symctl.circuitatlas.pattern import Pattern
from symctl.circuitatlas.screen import _region_sample, _search_regions, generic_degree
from symctl.circuitatlas.universality import decide


def _pattern(text: str) -> Pattern:
    rows, h, m = (part.split() for part in text.split("|"))
    return Pattern.from_matrices(
        [[int(d) for d in r] for r in rows], [int(d) for d in h[0]], [int(d) for d in m[0]]
    )


# its counterexample's target had lost a point to infinity (not generic); its fibre has 3 points
DISPUTED_ODD = "100 111 110 | 100 | 110"


def test_the_pattern_with_a_non_generic_counterexample_is_proved_universal_by_its_odd_degree():
    ev = decide(_pattern(DISPUTED_ODD))
    assert ev.universal is True and ev.proved and ev.method == "odd degree"
    assert ev.details["degree"] == generic_degree(_pattern(DISPUTED_ODD)) == 3


@pytest.mark.parametrize(
    "text", [DISPUTED_ODD, "111 011 010 | 110 | 100", "111 101 100 | 100 | 110"]
)
def test_a_proved_pattern_has_a_real_realization_with_no_zero_entry_in_every_region(text):
    pattern = _pattern(text)
    proof = _prove(pattern.n, pattern.mask, 0)
    assert proof["proved"] and proof["degree"] % 2
    rng = random.Random(7)
    for _, pairs, signs, complex_zeros in _search_regions(3):
        a, c = _region_sample(3, pairs, signs, complex_zeros, rng)
        fibre = count_real(pattern, a, c, rng)
        if fibre is not None and fibre["degree"] == proof["degree"] and not fibre["zero_entry"]:
            assert fibre["real"]


def test_the_eliminant_vanishes_on_the_fibre_of_a_random_realization():
    pattern = _pattern(DISPUTED_ODD)
    proof = _prove(pattern.n, pattern.mask, 3)
    from symctl.circuitatlas.fibre import _system, coefficient_symbols

    unknowns, _, _, charpoly, numer = _system(pattern)
    a, c = coefficient_symbols(3)
    x0 = {x: sp.Integer(random.Random(i).randint(1, 50)) for i, x in enumerate(unknowns)}
    rule = {p: e.xreplace(x0) for p, e in zip((*a, *c), (*charpoly, *numer), strict=True)}
    f = sp.sympify(proof["eliminant"], locals={str(s): s for s in (*unknowns, *a, *c)})
    assert sp.expand(f.xreplace(rule).xreplace(x0)) == 0


def test_an_even_degree_proves_nothing():
    pattern = _pattern("011 111 010 | 110 | 100")  # degree 2, refuted by a counterexample
    assert generic_degree(pattern) == 2
    proof = _prove(pattern.n, pattern.mask, 0)
    assert not proof["proved"] and "even degree" in proof["why"]


def test_a_basis_beyond_its_cpu_limit_proves_nothing():
    # a millisecond of CPU time for every variable order: each basis is stopped, no proof made
    proof = odd_degree_proof(_pattern(DISPUTED_ODD), cpu_seconds=0.001)
    assert proof is not None and not proof["proved"] and "CPU" in proof["why"]


def _children() -> list[int]:
    """The living child processes of this one (read from /proc)."""
    import os
    from pathlib import Path

    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == os.getpid() and fields[0] != "Z":
            out.append(int(stat.parent.name))
    return out


def test_no_proving_process_is_left_behind():
    from symctl.circuitatlas.odddegree import proving

    before = _children()
    with proving():
        assert odd_degree_proof(_pattern(DISPUTED_ODD))["proved"]
        assert odd_degree_proof(_pattern(DISPUTED_ODD))["proved"]  # the same child, kept
        assert len(_children()) == len(before) + 1
    assert _children() == before
    assert odd_degree_proof(_pattern(DISPUTED_ODD))["proved"]  # alone: started, then stopped
    assert _children() == before
