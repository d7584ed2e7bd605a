"""The safe parser: user text becomes a SymPy expression without ever being evaluated.

:func:`parse_expr` walks Python's syntax tree and accepts only numbers, the
names it is given, ``+ - * / **``, parentheses and a short list of elementary
functions; :func:`parse_matrix` reads a matrix of such entries. SymPy's own
``sympify`` (and so ``Matrix(str)``, ``subs(str)``) runs ``eval``: symctl never
hands it user text.

>>> import sympy as sp
>>> from symctl._util.parse import parse_expr
>>> x = sp.Symbol("x")
>>> parse_expr("2*x**2 - exp(-x)/3", {"x": x})
2*x**2 - exp(-x)/3
>>> parse_expr("__import__('os')", {"x": x})
Traceback (most recent call last):
...
symctl.errors.ParseError: expression: function '__import__' is not allowed; use one of: Abs, ...
"""

from __future__ import annotations

import ast
from collections.abc import Iterable, Mapping

import sympy as sp

from symctl.errors import ParseError, SymctlTypeError

__all__ = ["parse_expr", "parse_matrix"]

_FUNCTIONS = {
    "exp": sp.exp,
    "log": sp.log,
    "sqrt": sp.sqrt,
    "sin": sp.sin,
    "cos": sp.cos,
    "tan": sp.tan,
    "tanh": sp.tanh,
    "sinh": sp.sinh,
    "cosh": sp.cosh,
    "atan": sp.atan,
    "Abs": sp.Abs,
}
_CONSTANTS = {"pi": sp.pi, "E": sp.E}
_BINOPS = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a**b,
}
_MAX_TEXT = 10_000


def _names_of(names: Mapping[str, sp.Basic] | Iterable[sp.Symbol] | None) -> dict:
    if names is None:
        return {}
    if isinstance(names, Mapping):
        return dict(names)
    return {s.name: s for s in names}


def parse_expr(
    text: str,
    names: Mapping[str, sp.Basic] | Iterable[sp.Symbol] | None = None,
    *,
    argname: str = "expression",
) -> sp.Expr:
    """Parse user text into a sympy expression without evaluating any code.

    Parameters
    ----------
    text : str
        Arithmetic in Python syntax, e.g. ``"f_max/(tau*(1 + exp(-r)))"``.
    names : mapping or iterable of symbols, optional
        The names the text may use. Decimal numbers become exact rationals.
    argname : str
        The argument name used in error messages.

    Raises
    ------
    ParseError
        For syntax errors, unknown names, calls of other functions, attribute
        access, subscripts and any other construct.
    """
    if not isinstance(text, str):
        raise SymctlTypeError(f"{argname}: expected a string, got {type(text).__name__}")
    if len(text) > _MAX_TEXT:
        raise ParseError(f"{argname}: text longer than {_MAX_TEXT} characters")
    allowed = {**_CONSTANTS, **_names_of(names)}
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ParseError(f"{argname}: cannot parse {text!r}: {exc.msg}") from None

    def walk(node: ast.AST) -> sp.Expr:
        if isinstance(node, ast.Constant) and isinstance(node.value, int | float):
            if isinstance(node.value, bool):
                raise ParseError(f"{argname}: booleans are not numbers")
            return (
                sp.Rational(repr(node.value))
                if isinstance(node.value, float)
                else sp.Integer(node.value)
            )
        if isinstance(node, ast.Name):
            if node.id in allowed:
                return allowed[node.id]
            choices = ", ".join(sorted(allowed)[:8])
            raise ParseError(
                f"{argname}: name {node.id!r} is not allowed; use one of: {choices}, ..."
            )
        if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
            return _BINOPS[type(node.op)](walk(node.left), walk(node.right))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
            value = walk(node.operand)
            return -value if isinstance(node.op, ast.USub) else value
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id in _FUNCTIONS
            and not node.keywords
        ):
            return _FUNCTIONS[node.func.id](*(walk(a) for a in node.args))
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            choices = ", ".join(sorted(_FUNCTIONS)[:6])
            raise ParseError(
                f"{argname}: function {node.func.id!r} is not allowed; use one of: {choices}, ..."
            )
        raise ParseError(f"{argname}: {type(node).__name__} is not allowed in {text!r}")

    return walk(tree.body)


def parse_matrix(text: str, argname: str) -> sp.Matrix:
    """A numeric matrix from user text: ``"2"``, ``"1/2"``, ``"[[1, 0], [0, 2]]"`` or ``"1,0;0,2"``.

    Entries are parsed by :func:`parse_expr` with no names, so only numbers and
    arithmetic are accepted.

    >>> from symctl._util.parse import parse_matrix
    >>> parse_matrix("[[1, 0], [0, 1/2]]", "Q")
    Matrix([
    [1,   0],
    [0, 1/2]])
    >>> parse_matrix("1,0;0,2", "Q").shape
    (2, 2)
    """
    if not isinstance(text, str):
        raise SymctlTypeError(f"{argname}: expected text, got {type(text).__name__}")
    body = text.strip()
    if body.startswith("[[") and body.endswith("]]"):
        body = body[2:-2].replace("],", ";").replace("]", "").replace("[", "")
    elif body.startswith("[") and body.endswith("]"):
        body = body[1:-1]
    rows = [row.split(",") for row in body.split(";")]
    if len({len(row) for row in rows}) != 1:
        raise ParseError(f"{argname}: rows of different lengths in {text!r}")
    entries = [[parse_expr(e, None, argname=argname) for e in row] for row in rows]
    return sp.Matrix(entries)
