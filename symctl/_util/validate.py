"""Argument checks at the public boundary, and a safe parser for user text.

Every public function of symctl checks its arguments here, so that bad input
fails early with one of :mod:`symctl.errors`' types and a message naming the
argument and its value.

User text is never evaluated: :func:`parse_expr` walks Python's syntax tree
and accepts only numbers, the names it is given, ``+ - * / **``, parentheses
and a short list of elementary functions.

>>> import sympy as sp
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
import math
import numbers
from collections.abc import Iterable, Mapping

import numpy as np
import sympy as sp

from symctl.errors import DimensionError, ParameterError, ParseError, SymctlTypeError

__all__ = [
    "as_generator",
    "nonneg_int",
    "numeric_matrix",
    "parse_expr",
    "parse_matrix",
    "positive_number",
    "psd_matrix",
    "real_number",
    "to_expr",
    "to_matrix",
]

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


def to_expr(value, argname: str, names=None) -> sp.Expr:
    """A sympy expression from a number, a sympy object or (safely parsed) text."""
    if isinstance(value, str):
        return parse_expr(value, names, argname=argname)
    if isinstance(value, sp.Basic):
        return value
    if isinstance(value, bool) or not isinstance(value, numbers.Number):
        raise SymctlTypeError(
            f"{argname}: expected a number, a sympy expression or text, got {value!r}"
        )
    if isinstance(value, numbers.Integral):
        return sp.Integer(int(value))
    if isinstance(value, numbers.Real):
        if not math.isfinite(float(value)):
            raise ParameterError(f"{argname}: must be finite, got {value!r}")
        return sp.Float(float(value))
    raise SymctlTypeError(f"{argname}: complex values are not supported, got {value!r}")


def to_matrix(value, argname: str, shape: tuple[int, int] | None = None, names=None) -> sp.Matrix:
    """A sympy Matrix from a scalar, nested lists, a NumPy array or a sympy matrix.

    A scalar becomes a 1 x 1 matrix; a flat list a column. ``shape`` is
    checked when given.
    """
    if isinstance(value, sp.MatrixBase):
        mat = sp.Matrix(value)
    elif isinstance(value, np.ndarray | list | tuple):
        arr = np.asarray(value, dtype=object)
        if arr.ndim == 0:
            arr = arr.reshape(1, 1)
        elif arr.ndim == 1:
            arr = arr.reshape(-1, 1)
        elif arr.ndim != 2:
            raise DimensionError(f"{argname}: expected a matrix, got an array of {arr.ndim} dims")
        mat = sp.Matrix(arr.shape[0], arr.shape[1], lambda i, j: to_expr(arr[i, j], argname, names))
    else:
        mat = sp.Matrix([[to_expr(value, argname, names)]])
    if shape is not None and mat.shape != tuple(shape):
        raise DimensionError(f"{argname}: expected shape {tuple(shape)}, got {mat.shape}")
    return mat


def numeric_matrix(value, argname: str, shape: tuple[int, int] | None = None) -> np.ndarray:
    """A finite float64 array (2-D) from any matrix-like value without free symbols."""
    mat = to_matrix(value, argname, shape)
    if mat.free_symbols:
        names = ", ".join(sorted(str(s) for s in mat.free_symbols))
        raise ParameterError(f"{argname}: needs numbers, but has the free symbols {names}")
    try:
        arr = np.array(mat.evalf(), dtype=float)
    except TypeError:
        raise ParameterError(
            f"{argname}: entries must be real numbers, got {mat.tolist()}"
        ) from None
    if not np.all(np.isfinite(arr)):
        raise ParameterError(f"{argname}: entries must be finite, got {arr.tolist()}")
    return arr


def psd_matrix(value, argname: str, size: int, *, definite: bool = False) -> np.ndarray:
    """A symmetric positive semidefinite (or definite) ``size x size`` float array."""
    arr = numeric_matrix(value, argname, (size, size))
    scale = max(1.0, float(np.max(np.abs(arr))))
    if not np.allclose(arr, arr.T, atol=1e-12 * scale):
        raise ParameterError(f"{argname}: must be symmetric, got {arr.tolist()}")
    low = float(np.min(np.linalg.eigvalsh((arr + arr.T) / 2)))
    if low < -1e-12 * scale or (definite and low <= 1e-12 * scale):
        kind = "positive definite" if definite else "positive semidefinite"
        raise ParameterError(
            f"{argname}: must be {kind}, but has eigenvalue {low:.3g} (got {arr.tolist()})"
        )
    return arr


def positive_number(value, argname: str) -> float:
    """A finite, strictly positive float."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise SymctlTypeError(f"{argname}: expected a real number, got {value!r}")
    out = float(value)
    if not math.isfinite(out) or out <= 0:
        raise ParameterError(f"{argname}: must be a finite number > 0, got {value!r}")
    return out


def real_number(value, argname: str) -> float:
    """A finite float."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise SymctlTypeError(f"{argname}: expected a real number, got {value!r}")
    out = float(value)
    if not math.isfinite(out):
        raise ParameterError(f"{argname}: must be finite, got {value!r}")
    return out


def nonneg_int(value, argname: str) -> int:
    """An integer >= 0 (bools and non-integral numbers are refused)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ParameterError(f"{argname}: must be an integer >= 0, got {value!r}")
    if value < 0:
        raise ParameterError(f"{argname}: must be an integer >= 0, got {value!r}")
    return int(value)


def parse_matrix(text: str, argname: str) -> sp.Matrix:
    """A numeric matrix from user text: ``"2"``, ``"1/2"``, ``"[[1, 0], [0, 2]]"`` or ``"1,0;0,2"``.

    Entries are parsed by :func:`parse_expr` with no names, so only numbers and
    arithmetic are accepted.

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


def as_generator(value, argname: str) -> np.random.Generator:
    """A NumPy ``Generator`` from a Generator, an int seed or None (fresh entropy)."""
    if isinstance(value, np.random.Generator):
        return value
    if value is None or (isinstance(value, numbers.Integral) and not isinstance(value, bool)):
        return np.random.default_rng(value)
    raise SymctlTypeError(f"{argname}: expected an int seed or a numpy Generator, got {value!r}")


def positive_int(value, argname: str) -> int:
    """An integer >= 1 (bools and non-integral numbers are refused)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
        raise ParameterError(f"{argname}: must be an integer >= 1, got {value!r}")
    return int(value)
