"""The safe parser bounds its work.

Each hostile text must give a ParseError naming the argument, in well under a
second, never a hang, a MemoryError, a RecursionError or a foreign exception.
"""

from __future__ import annotations

import pytest
import sympy as sp
from helpers import bounded

from symctl import DiscreteTF, ParseError, controller_tf, z
from symctl._util.parse import (
    MAX_BITS,
    MAX_DEPTH,
    MAX_EXPONENT,
    MAX_NODES,
    MAX_OPERATORS,
    MAX_TEXT,
    parse_expr,
    parse_matrix,
)

CLASS = "1"
CALLS = 200_000  # generous: each case makes at most a few thousand calls

HOSTILE = {
    "tower 9**9**9": "9**9**9",
    "tower 2**2**2**2**2**2": "2**2**2**2**2**2",
    "tower of pi": "pi**pi**pi**pi",
    "tower of E with a symbol": "x**(E**(E**E**E))",
    "power of a big base": "(2**1000)**1000",
    "power 10**300 ** 67": "(10**300)**67",
    "huge negative exponent": "2**-2000",
    "huge symbolic exponent": "x**(10**6)",
    "float exponent 1e300": "x**1e300",
    "10,000-term sum": "+".join(["1"] * 10_000),
    "5,000-term symbolic sum": "+".join(["x"] * 5_000),
    "400-term sum": "+".join(["x"] * 400),
    "150-term product": "*".join(["x"] * 150),
    "10,000 unary minus": "-" * 10_000 + "1",
    "4,999 unary minus": "-" * 4_999 + "1",
    "300 unary minus": "-" * 300 + "1",
    "300 unary plus": "+" * 300 + "1",
    "5,000 parentheses": "(" * 5_000 + "1" + ")" * 5_000,
    "150 nested exp": "exp(" * 150 + "x" + ")" * 150,
    "1e9999": "1e9999",
    "-1e9999": "-1e9999",
    "1e9999 in a sum": "x + 1e9999",
    "inf name": "inf",
    "nan name": "nan",
    "division by zero": "1/0",
    "zero to a negative power": "0**-1",
    "log of zero": "log(0)",
    "5,000-digit integer": "9" * 5_000,
    "4,000-digit integer (too many bits)": "9" * 4_000 + "*" + "9" * 4_000 + "*" + "9" * 1_900,
    "hex literal of 36,000 bits": "0x" + "f" * 9_000,
    "text over the length limit": "x" * (MAX_TEXT + 1),
    "1 MB of spaces": " " * 1_000_000,
    "null byte": "1\x00",
    "too many function arguments": "Abs(" + ",".join(["1"] * 3_000) + ")",
    "wrong arity": "exp(1, 2)",
    "starred argument": "exp(*x)",
    "keyword argument": "exp(x=1)",
    "complex literal": "1j",
    "string literal": "'abc'",
    "comprehension": "[x for x in ()]",
    "lambda": "(lambda: 1)()",
    "attribute": "x.__class__",
    "subscript": "x[0]",
    "walrus": "(y := 1)",
    "bool": "True",
    "comparison": "1 < 2",
    "boolean operation": "x and x",
    "bitwise xor": "2 ^ 3",
    "matmul": "x @ x",
    "modulo": "x % 2",
    "dunder import": "__import__('os').system('echo RAN')",
    "unknown name": "os",
    "format string": "f'{1}'",
    "ellipsis": "...",
    "many names (node limit)": "+".join(["x*x"] * 900),
}


def _counted(call):
    """The error ``call`` raised (None if it returned), counted against the call budget."""
    with bounded(CALLS):
        try:
            call()
        except ParseError as exc:
            return exc
    return None


@pytest.mark.parametrize("text", HOSTILE.values(), ids=HOSTILE.keys())
def test_hostile_text_is_a_parse_error_naming_the_argument_within_a_bounded_work(text):
    error = _counted(lambda: parse_expr(text, {"x": sp.Symbol("x")}, argname="Q"))
    assert error is not None, "accepted"
    assert str(error).startswith("Q: "), str(error)
    assert len(str(error)) < 400, "the message quotes too much text"


ENTRY_POINTS = {
    "DiscreteTF(num)": lambda t: DiscreteTF(t, z),
    "DiscreteTF(den)": lambda t: DiscreteTF(1, t),
    "DiscreteTF.subs": lambda t: controller_tf(2).subs({"K_0": t}),
    "parse_matrix": lambda t: parse_matrix(f"[[{t}, 0], [0, 1]]", "Q"),
    "parse_matrix rows": lambda t: parse_matrix(";".join([t] * 3), "Q"),
}
SAMPLE = ["9**9**9", "2**2**2**2**2**2", "1e9999", "-" * 4_999 + "1", "+".join(["1"] * 4_000)]


@pytest.mark.parametrize("text", SAMPLE, ids=["9**9**9", "2**...**2", "1e9999", "minus", "sum"])
@pytest.mark.parametrize("entry", ENTRY_POINTS.values(), ids=ENTRY_POINTS.keys())
def test_hostile_text_through_the_api_is_a_parse_error_within_a_bounded_work(entry, text):
    error = _counted(lambda: entry(text))
    assert error is not None


def test_parse_matrix_refuses_text_over_the_length_limit():
    with pytest.raises(ParseError, match="Q: text longer than"):
        parse_matrix(",".join(["1"] * MAX_TEXT), "Q")


BENIGN = {
    "paper expression": ("f_max/(tau*(1 + exp(-x)))", None),
    "power at the exponent limit": (f"x**{MAX_EXPONENT}", None),
    "big exact number within bits": ("10**1000", sp.Integer(10) ** 1000),
    "decimal": ("0.1", sp.Rational(1, 10)),
    "1e308 exact": ("1e308", sp.Integer(10) ** 308),
    "tiny float is exact": ("1e-300", sp.Rational(1, 10**300)),
    "sum of 90 terms": ("+".join(["x"] * 90), 90 * sp.Symbol("x")),
    "log with a base": ("log(8, 2)", sp.log(8) / sp.log(2)),
    "90 parentheses": ("(" * 90 + "2" + ")" * 90, sp.Integer(2)),
    "150 parentheses (no nodes)": ("(" * 150 + "2" + ")" * 150, sp.Integer(2)),
    "sqrt": ("sqrt(2)**2", sp.Integer(2)),
}


@pytest.mark.parametrize(("text", "expected"), BENIGN.values(), ids=BENIGN.keys())
def test_benign_text_within_the_limits_is_accepted(text, expected):
    names = {n: sp.Symbol(n) for n in ("x", "f_max", "tau")}
    with bounded(CALLS):
        value = parse_expr(text, names)
    if expected is not None:
        assert sp.simplify(value - expected) == 0


def test_the_limits_are_documented_in_the_module_docstring():
    import symctl._util.parse as parse

    doc = parse.__doc__
    for limit in (MAX_TEXT, MAX_OPERATORS, MAX_NODES, MAX_DEPTH, MAX_EXPONENT, MAX_BITS):
        assert f"{limit:,}" in doc or str(limit) in doc


@pytest.mark.parametrize(
    "text", ["exp(exp(exp(exp(10))))", "exp(1000)", "exp(700)*exp(700)", "pi**1000", "E**1000"]
)
def test_a_number_beyond_floating_point_is_too_large_naming_the_argument(text):
    error = _counted(lambda: parse_expr(text, argname="--q"))
    assert error is not None and str(error).startswith("--q: "), "accepted"
    assert "too large" in str(error) and text in str(error)


def test_an_exact_matrix_entry_beyond_floating_point_is_too_large():
    with pytest.raises(ParseError, match=r"--r: the value of '10\*\*400' is too large"):
        parse_matrix("[[1, 0], [0, 10**400]]", "--r")


def test_a_caret_says_to_use_double_star_for_powers():
    with pytest.raises(ParseError, match=r"x: '\^' is not a power in 'x\^2'; use \*\* for powers"):
        parse_expr("x^2", {"x": sp.Symbol("x")}, argname="x")


def test_a_lowercase_e_is_not_eulers_number_and_the_message_says_so():
    with pytest.raises(ParseError, match=r"name 'e' is not allowed.*Euler's number is E"):
        parse_expr("e**2")
