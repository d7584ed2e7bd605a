"""Proofs are results: truthy by their verdict, equal by value, carrying method and evidence."""

from __future__ import annotations

from symctl import controller_tf, factor
from symctl.proof import Proof


def test_factorization_proof_is_truthy_and_names_its_method():
    proof = factor(controller_tf(3), 2, 1).verify()
    assert proof and proof.claim == "G3 G2 G1 = G" and "polynomials" in proof.method


def test_proofs_compare_by_value_and_with_their_verdict():
    a, b = Proof(True, "c", "m"), Proof(True, "c", "m")
    assert a == b and hash(a) == hash(b) and a == True  # noqa: E712
    assert Proof(False, "c", "m", "x") != a and Proof(False, "c", "m") == False  # noqa: E712
    assert Proof(1, "c", "m").holds is True
