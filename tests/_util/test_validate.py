"""Safe parsing of user text and argument checks."""

from __future__ import annotations

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from symctl import ParseError, SymctlTypeError
from symctl._util.parse import parse_expr, parse_matrix
from symctl._util.validate import nonneg_int, psd_matrix, to_matrix

x = sp.Symbol("x")


@pytest.mark.parametrize(
    "text",
    [
        "__import__('os').system('echo hi')",
        "x.__class__",
        "(lambda: 1)()",
        "[1, 2][0]",
        "open('f')",
        "exp(x, base=2)",
        "y + 1",
        "1 if x else 2",
        "x == 1",
        "'text'",
        "True",
    ],
)
def test_parser_refuses_anything_but_arithmetic(text):
    with pytest.raises(ParseError):
        parse_expr(text, [x])


def test_parser_keeps_decimals_exact():
    assert parse_expr("0.02*x + 1e-3", [x]) == sp.Rational(1, 50) * x + sp.Rational(1, 1000)


@given(st.integers(-1000, 1000), st.integers(1, 1000))
def test_parser_round_trips_rationals(p, q):
    assert parse_expr(f"{p}/{q}") == sp.Rational(p, q)


def test_parse_matrix_forms():
    assert parse_matrix("[[1, 2], [3, 4]]", "Q") == sp.Matrix([[1, 2], [3, 4]])
    assert parse_matrix("1, 2; 3, 4", "Q") == sp.Matrix([[1, 2], [3, 4]])
    with pytest.raises(ParseError, match="Q"):
        parse_matrix("1, 2; 3", "Q")


def test_checks_name_the_argument():
    with pytest.raises(ValueError, match="delay"):
        nonneg_int(-1, "delay")
    with pytest.raises(ValueError, match="W"):
        psd_matrix([[1, 0], [0, -1]], "W", 2)
    with pytest.raises(SymctlTypeError, match="M"):
        to_matrix(object(), "M")
