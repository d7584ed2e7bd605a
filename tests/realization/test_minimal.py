"""Exact minimal realizations: orders against python-control's minreal and the Hankel rank."""

from __future__ import annotations

import control
import numpy as np
import pytest
import sympy as sp
from helpers import examples
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from symctl import ParameterError, Realization, SymctlTypeError, controllable_canonical, z
from symctl.realization.check import check_realization
from symctl.realization.minimal import minimal_realization


def _hankel_rank(R: Realization) -> int:
    """The McMillan degree: the rank of the (n x n)-block Hankel matrix of Markov parameters."""
    n = R.n
    h = R.markov(2 * n + 1)[1:]  # M F^k H, k = 0 .. 2n - 1
    if n == 0:
        return 0
    rows = [sp.Matrix.hstack(*h[i : i + n]) for i in range(n)]
    return sp.Matrix.vstack(*rows).rank()


def _padded(rng, p: int, q: int) -> Realization:
    """A random realization with uncontrollable and unobservable states mixed in by a similarity."""
    k = int(rng.integers(1, 4))
    a, b = int(rng.integers(0, 3)), int(rng.integers(0, 3))  # hidden states of each kind
    n = k + a + b

    def r(*shape):
        return sp.Matrix(*shape, lambda *_: sp.Rational(int(rng.integers(-9, 10)), 8))

    F = (
        sp.diag(r(k, k), r(a, a), r(b, b))
        if a and b
        else sp.diag(*[r(m, m) for m in (k, a, b) if m])
    )
    H = (
        sp.Matrix.vstack(r(k, q), r(a, q), sp.zeros(b, q))
        if b
        else sp.Matrix.vstack(r(k, q), r(a, q))
    )
    M = (
        sp.Matrix.hstack(r(p, k), sp.zeros(p, a), r(p, b))
        if a
        else sp.Matrix.hstack(r(p, k), r(p, b))
    )
    while True:
        P = r(n, n)
        if P.det() != 0:
            break
    return Realization(P.inv() * F * P, P.inv() * H, M * P, r(p, q))


@pytest.mark.slow
@settings(max_examples=examples(25), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), p=st.integers(1, 2), q=st.integers(1, 2))
def test_the_minimal_order_is_the_hankel_rank_and_the_transfer_function_is_kept(seed, p, q):
    R = _padded(np.random.default_rng(seed), p, q)
    Rm = minimal_realization(R)
    assert Rm.n == _hankel_rank(R)
    assert Rm.is_minimal()
    assert check_realization(Rm, R.to_tf()).ok  # exact
    poles = np.linalg.eigvals(np.array(Rm.F, dtype=float)) if Rm.n else np.array([])
    separated = all(abs(a - b) > 1e-2 for i, a in enumerate(poles) for b in poles[i + 1 :])
    if p == q == 1 and Rm.n and separated:  # python-control agrees (numerically, by
        # cancelling roots: a multiple root splits by about tol^(1/k), too far to cancel; a
        # constant G it leaves as 0/den with the whole denominator)
        sys = control.ss(*(np.array(m, dtype=float) for m in (R.F, R.H, R.M, R.N)), True)
        tf = control.ss2tf(sys).minreal(tol=1e-6)
        assert len(np.trim_zeros(tf.den[0][0], "f")) - 1 == Rm.n


def test_a_minimal_realization_is_kept_and_floats_are_exact():
    R = controllable_canonical(1 / (z**2 - z / 2 + sp.Rational(1, 16)))
    assert minimal_realization(R).n == 2
    Rf = Realization([[0.1, 0], [0, 0.1]], [[1], [1]], [[1, -1]], 0.5)  # the two states cancel
    out = minimal_realization(Rf)
    assert out.n == 0 and out.N[0, 0] == sp.Rational(1, 2)


def test_bad_input_is_refused():
    with pytest.raises(SymctlTypeError, match="R: expected a Realization"):
        minimal_realization("F")
    a = sp.Symbol("a")
    with pytest.raises(ParameterError, match=r"F\[1,1\] = a is not a rational"):
        minimal_realization(Realization([[a]], [[1]], [[1]], 0))
