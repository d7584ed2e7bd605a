"""The fraction-free similarity transform agrees with SymPy's cancel, in value and in form."""

from __future__ import annotations

import random

import pytest
import sympy as sp
from flint import fmpq, fmpq_mat, fmpz_mpoly_ctx
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import (
    ParameterError,
    Realization,
    check_realization,
    controllable_canonical,
    controller_tf,
    factor,
    general_realization,
    observable_canonical,
)
from symctl._util.exact import PolyFractions, fold
from symctl.realization._similarity import _gauss_jordan, _Ring, similar_exact
from symctl.realization.realization import _similar_sympy

G2 = factor(controller_tf(2)).G2
a, b, c = sp.symbols("a b c", real=True)


def symbolic_P(n: int) -> sp.Matrix:
    return sp.Matrix(n, n, sp.symbols(f"p_1:{n + 1}(1:{n + 1})"))


def both(F, H, M, P):
    """The SymPy path and the flint path on the same input."""
    F, H, M, P = (sp.Matrix(x) for x in (F, H, M, P))
    return _similar_sympy(F, H, M, P), similar_exact(F, H, M, P)


def assert_same_values(old, new) -> None:
    """Entry for entry the same rational function (cross-multiplied in fmpz_mpoly)."""
    symbols = sorted(set().union(*(A.free_symbols for A in (*old, *new))), key=str)
    ctx = fmpz_mpoly_ctx.get(("x", len(symbols)), "lex")
    algebra, memo = PolyFractions(ctx, symbols), {}
    for A, B in zip(old, new, strict=True):
        assert A.shape == B.shape
        for x, y in zip(A, B, strict=True):
            (nx, dx), (ny, dy) = fold(x, algebra, memo), fold(y, algebra, memo)
            assert nx * dy == ny * dx, (x, y)


def assert_same_form(old, new) -> None:
    for A, B in zip(old, new, strict=True):
        for x, y in zip(A, B, strict=True):
            assert x == y and x.args == y.args, (sp.srepr(x), sp.srepr(y))


@pytest.mark.parametrize("base", [controllable_canonical, observable_canonical])
@pytest.mark.parametrize(
    "P",
    [
        symbolic_P(2),
        sp.Matrix([[sp.Rational(3, 2), -1], [sp.Rational(1, 7), 2]]),
        sp.Matrix([[1, a], [0, b]]),
        sp.Matrix([[0, a], [b, 0]]),  # a zero pivot: a row swap
    ],
)
def test_papers_G2_similar_is_the_sympy_result_entry_for_entry(base, P):
    R = base(G2)
    old, new = both(R.F, R.H, R.M, P)
    assert_same_form(old, new)


@pytest.mark.parametrize("n", [3])
def test_symbolic_P_of_the_order_n_controller_equals_the_sympy_path(n):
    R = controllable_canonical(controller_tf(n))
    old, new = both(R.F, R.H, R.M, symbolic_P(n))
    assert_same_form(old, new)


def _rational(rng: random.Random) -> sp.Rational:
    return sp.Rational(rng.randint(-9, 9), rng.choice([1, 1, 2, 3, 7]))


def _entry(rng: random.Random, kind: int) -> sp.Expr:
    q = _rational
    if kind == 0:
        return q(rng)
    if kind == 1:
        return q(rng) + q(rng) * a + q(rng) * b
    if kind == 2:
        return (q(rng) * a + q(rng)) / (c * rng.choice([1, 2, a]))
    return q(rng) * a * b + q(rng) * c**2 - q(rng)


def _case(seed: int):
    rng = random.Random(seed)
    n, kind = rng.randint(1, 4), rng.randint(0, 3)
    symbolic = rng.random() < 0.3
    F = sp.Matrix(n, n, lambda i, j: _entry(rng, kind) if rng.random() < 0.7 else 0)
    H = sp.Matrix(n, 1, lambda i, j: _entry(rng, kind))
    M = sp.Matrix(1, n, lambda i, j: _entry(rng, rng.randint(0, 3)))
    if not symbolic:
        P = sp.Matrix(n, n, lambda i, j: _rational(rng) if rng.random() < 0.8 else 0)
    else:  # SymPy's path is slow here beyond 3 x 3
        n = min(n, 3)
        F, H, M = F[:n, :n], H[:n, :], M[:, :n]
        P = sp.Matrix(
            n, n, lambda i, j: rng.choice([_rational(rng), a, b, 0, a * b - 1, 1 / (a + 1)])
        )
    return F, H, M, P


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(60))
def test_random_similarity_equals_the_sympy_path_in_value_and_form(seed):
    old, new = both(*_case(seed))
    if old[0] is None:
        assert new == "singular"
        return
    assert_same_values(old, new)
    assert_same_form(old, new)


@pytest.mark.slow
@settings(max_examples=examples(15))  # each example runs SymPy's cancel too
@given(st.integers(0, 2**32))
def test_property_flint_similarity_has_the_value_of_the_sympy_one(seed):
    old, new = both(*_case(seed))
    if old[0] is None:
        assert new == "singular"
    else:
        assert_same_values(old, new)


@pytest.mark.parametrize(
    "P", [[[1, 2], [2, 4]], [[a, a], [1, 1]], [[a, b], [2 * a, 2 * b]], [[0, 0], [a, 1]]]
)
def test_singular_P_is_refused_on_both_paths(P):
    with pytest.raises(ParameterError, match="P: singular"):
        controllable_canonical(G2).similar(P)


def test_floats_take_the_sympy_path_unchanged():
    R = Realization([[0.5, 1], [0, 0.25]], [[1], [0]], [[1, 2]], 0)
    P = sp.Matrix([[1, 2], [3, 4]])
    assert similar_exact(R.F, R.H, R.M, P) is None
    old = _similar_sympy(R.F, R.H, R.M, P)
    assert R.similar(P).F == old[0]


@given(st.integers(0, 2**32), st.integers(1, 5))
def test_property_fraction_free_gauss_jordan_gives_det_times_inverse(seed, n):
    rng = random.Random(seed)
    rows = [[rng.choice([0, 0, 1, -2, 3, 5]) for _ in range(n)] for _ in range(n)]
    ring = _Ring([])
    got = _gauss_jordan([[ring.ctx.constant(x) for x in row] for row in rows], ring)
    exact = fmpq_mat(n, n, [fmpq(x) for row in rows for x in row])
    if exact.det() == 0:
        assert got is None
        return
    delta, A = got
    d = int(delta.leading_coefficient())
    assert abs(d) == abs(int(exact.det()))
    inv = exact.inv()
    assert all(
        fmpq(int(A[i][j].leading_coefficient()) if not A[i][j].is_zero() else 0) == d * inv[i, j]
        for i in range(n)
        for j in range(n)
    )


@given(st.integers(0, 2**32))
def test_property_terms_built_from_flint_equal_sympys_evaluated_sum(seed):
    rng = random.Random(seed)
    syms = (*sp.symbols("x y_1 y_10 y_2"), sp.Symbol("K_1", real=True), sp.Dummy("d"))
    ring = _Ring(sorted(syms, key=sp.default_sort_key))
    for _ in range(5):  # one ring: its pool of factors grows between the sums
        terms = {
            tuple(rng.choice([0, 0, 0, 1, 2, 3]) for _ in syms): rng.choice([1, -1, 2, -3, 5])
            for _ in range(rng.randint(1, 8))
        }
        poly = ring.ctx.from_dict(terms)
        for q in (1, 6):
            ref = sp.Add(
                *[
                    sp.Mul(
                        sp.Rational(int(k), q),
                        *[s**e for s, e in zip(ring.symbols, exps, strict=True)],
                    )
                    for exps, k in poly.terms()
                ]
            )
            got = ring.expr(poly, q)
            assert got == ref and got.args == ref.args and hash(got) == hash(ref)


@pytest.mark.slow
def test_fully_symbolic_5x5_P_of_the_order_5_controller_is_built_and_proved():
    G = controller_tf(5)
    R = general_realization(G, symbolic_P(5))
    assert R.F[0, 0].as_numer_denom()[1] == sp.expand(symbolic_P(5).det(method="berkowitz"))
    assert check_realization(R, G).ok
