"""The coefficient polynomials of a realization: exact, by minors, within a deadline and a size."""

from __future__ import annotations

import pytest
import sympy as sp

from symctl import z
from symctl._util.deadline import Deadline, OutOfTime, Unfinished
from symctl.circuitatlas import fibre
from symctl.circuitatlas.pattern import Pattern
from symctl.dalelaw.signs import full_pattern


def test_coefficient_polynomials_of_order_6_stop_at_a_passed_deadline():
    p = full_pattern(6)
    F, H, M = p.matrices(p.symbols())
    ring, *_ = sp.ring([*sorted(p.symbols().values(), key=str), z], sp.QQ)
    with pytest.raises(OutOfTime, match="coefficient polynomials of an order-6 realization"):
        fibre.coefficient_polys(F, H, M, ring, deadline=Deadline.passed())


def test_coefficient_polynomials_stop_past_their_size_limit(monkeypatch):
    monkeypatch.setattr(fibre, "MAX_TERMS", 20)
    p = full_pattern(3)
    F, H, M = p.matrices(p.symbols())
    ring, *_ = sp.ring([*sorted(p.symbols().values(), key=str), z], sp.QQ)
    with pytest.raises(Unfinished, match="exceed 20 terms"):
        fibre.coefficient_polys(F, H, M, ring)


@pytest.mark.parametrize("n", [1, 2, 3])
def test_coefficient_polynomials_are_the_characteristic_polynomial_and_the_adjugate(n):
    """The division-free expansion by minors against SymPy's own det and adjugate."""
    p = full_pattern(n)
    F, H, M = p.matrices(p.symbols())
    charpoly, numer = fibre.coefficient_polynomials(F, H, M)
    A = z * sp.eye(n) - F
    want_a = sp.Poly(A.det(), z).all_coeffs()[::-1][:n]
    want_c = sp.Poly(sp.expand((M * A.adjugate() * H)[0, 0]), z).all_coeffs()[::-1]
    assert [sp.expand(a - b) for a, b in zip(charpoly, want_a, strict=True)] == [0] * n
    assert [sp.expand(a - b) for a, b in zip(numer, want_c, strict=True)] == [0] * n


def _reference(F, H, M):
    n = F.shape[0]
    A = z * sp.eye(n) - F
    charpoly = sp.Poly(A.det(), z).all_coeffs()[::-1][:n]
    numer = sp.Poly(sp.expand((M * A.adjugate() * H)[0, 0]), z).all_coeffs()[::-1]
    return charpoly, numer + [sp.Integer(0)] * (n - len(numer))


@pytest.mark.parametrize("mask", [0b111010011101011, 0b101101110010111, 0b011111000111101])
def test_sparse_patterns_with_unit_tree_entries_match_the_adjugate_exactly(mask):
    """The atlas's systems (its tree entries set to 1): the same expressions as before."""
    p = Pattern(3, mask)
    tree = set(p.tree_slots() or ())
    syms = p.symbols()
    F, H, M = p.matrices({k: sp.Integer(1) if k in tree else syms[k] for k in p.indices})
    assert fibre.coefficient_polynomials(F, H, M) == _reference(F, H, M)
