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

Text is untrusted, so every input past a limit is a :class:`~symctl.errors.ParseError`
naming the argument, raised in well under a second (docs/reliability.md): text of at most
``MAX_TEXT`` = 10,000 characters and ``MAX_OPERATORS`` = 400 operator characters ``+-*/(``
(checked before Python parses), ``MAX_NODES`` = 1,000 syntax-tree nodes nested at most
``MAX_DEPTH`` = 100 deep, exponents ``|e| <= MAX_EXPONENT`` = 1,000, exact numbers (literal or
computed) of at most ``MAX_BITS`` = 20,000 bits, numbers with functions or constants within
floating point (``exp(exp(10))`` is refused), finite literals and a finite result (``1/0``).
"""

from __future__ import annotations

import ast
import math
import sys
from collections.abc import Iterable, Mapping
from types import MappingProxyType

import sympy as sp

from symctl.errors import ParseError, SymctlTypeError

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
    "logistic": lambda x: 1 / (1 + sp.exp(-x)),
}
_ARITY = {name: (1, 1) for name in _FUNCTIONS} | {"log": (1, 2)}
CONSTANTS = MappingProxyType({"pi": sp.pi, "E": sp.E})
"""The constants every expression may use undeclared: ``pi`` and ``E`` (Euler's number)."""
NAMES = frozenset(_FUNCTIONS) | frozenset(CONSTANTS)
"""The names the parser reads as its own functions and constants, never as symbols."""
_BINOPS = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a**b,
}
MAX_TEXT = 10_000
MAX_OPERATORS = 400
MAX_NODES = 1_000
MAX_DEPTH = 100
MAX_EXPONENT = 1_000
MAX_BITS = 20_000
_NON_FINITE = (sp.zoo, sp.oo, -sp.oo, sp.nan)


def _names_of(names: Mapping[str, sp.Basic] | Iterable[sp.Symbol] | None) -> dict:
    if names is None:
        return {}
    if isinstance(names, Mapping):
        return dict(names)
    return {s.name: s for s in names}


def _bits(value: sp.Rational) -> int:
    return max(int(value.p).bit_length(), int(value.q).bit_length())


def _fits_float(value: sp.Expr) -> bool:
    try:
        return math.isfinite(abs(complex(value)))
    except (ArithmeticError, ValueError, TypeError, RecursionError):  # mpmath's own overflow
        return False


def _shown(text: str) -> str:
    return text if len(text) <= 80 else text[:77] + "..."


def _too_large(text: str, argname: str) -> ParseError:
    return ParseError(
        f"{argname}: the value of {_shown(text)!r} is too large: it, or a number computed on the way, "
        f"is beyond floating point (|x| <= {sys.float_info.max:.3g})"
    )


def _check_size(value: sp.Expr, argname: str, text: str) -> sp.Expr:
    """Refuse an exact number past :data:`MAX_BITS`, a number of functions or constants past floats."""
    if isinstance(value, sp.Rational):
        if _bits(value) > MAX_BITS:
            raise ParseError(f"{argname}: a number with more than {MAX_BITS} bits is too large")
    elif isinstance(value, sp.Expr) and value.is_number and not _fits_float(value):
        raise _too_large(text, argname)
    return value


def _power(base: sp.Expr, exponent: sp.Expr, argname: str) -> sp.Expr:
    """``base**exponent`` after bounding the exponent and (for numbers) the result's size."""
    if exponent.is_number:
        try:
            magnitude = abs(complex(exponent))
        except (TypeError, ValueError, OverflowError):
            magnitude = float("inf")
        if not magnitude <= MAX_EXPONENT:
            shown = str(exponent) if len(str(exponent)) < 40 else "of this size"
            raise ParseError(
                f"{argname}: exponent {shown} is too large (|exponent| <= {MAX_EXPONENT})"
            )
        if (
            isinstance(base, sp.Rational)
            and isinstance(exponent, sp.Integer)
            and _bits(base) * abs(int(exponent)) > MAX_BITS
        ):
            raise ParseError(
                f"{argname}: a power with a {_bits(base)}-bit base and exponent {exponent} "
                f"would have more than {MAX_BITS} bits"
            )
    return base**exponent


def _check_shape(tree: ast.AST, argname: str) -> None:
    """Bound the number of nodes and the nesting depth (iteratively: no recursion)."""
    count = 0
    stack = [(tree, 1)]
    while stack:
        node, depth = stack.pop()
        count += 1
        if count > MAX_NODES:
            raise ParseError(f"{argname}: expression too large (more than {MAX_NODES} parts)")
        if depth > MAX_DEPTH:
            raise ParseError(
                f"{argname}: expression nested deeper than {MAX_DEPTH} levels "
                f"(a chain of more than {MAX_DEPTH} terms or signs is that deep)"
            )
        stack.extend((child, depth + 1) for child in ast.iter_child_nodes(node))


def _syntax_tree(text: str, argname: str) -> ast.AST:
    """Python's syntax tree of ``text``, after the cheap bounds that keep parsing itself small."""
    if len(text) > MAX_TEXT:
        raise ParseError(f"{argname}: text longer than {MAX_TEXT} characters")
    operators = sum(text.count(c) for c in "+-*/(")
    if operators > MAX_OPERATORS:
        raise ParseError(
            f"{argname}: too many operators ({operators} > {MAX_OPERATORS}) in the text"
        )
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ParseError(f"{argname}: cannot parse {_shown(text)!r}: {exc.msg}") from None
    except (ValueError, RecursionError, MemoryError):  # null bytes; a parser out of stack
        raise ParseError(f"{argname}: cannot parse the text (too complex)") from None
    _check_shape(tree, argname)
    return tree


def _number(value, argname: str) -> sp.Expr:
    if isinstance(value, bool):
        raise ParseError(f"{argname}: booleans are not numbers")
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ParseError(
                f"{argname}: numbers must be finite, got a float literal that is {value}"
            )
        return _check_size(sp.Rational(repr(value)), argname, "")
    if value.bit_length() > MAX_BITS:
        raise ParseError(
            f"{argname}: an integer literal with more than {MAX_BITS} bits is too large"
        )
    return sp.Integer(value)


def parse_expr(
    text: str,
    names: Mapping[str, sp.Basic] | Iterable[sp.Symbol] | None = None,
    *,
    argname: str = "expression",
) -> sp.Expr:
    """Parse user text (``"f_max/(tau*(1 + exp(-r)))"``) into a sympy expression, never evaluated.

    ``names`` (a mapping or symbols) are the names the text may use; decimals become exact
    rationals; ``argname`` names the text in errors. Anything else (unknown names, other
    calls, attributes, subscripts, text past the limits, non-finite values) is a
    :class:`ParseError`; text that is not a ``str`` a :class:`SymctlTypeError`.
    """
    if not isinstance(text, str):
        raise SymctlTypeError(f"{argname}: expected a string, got {type(text).__name__}")
    tree = _syntax_tree(text, argname)
    allowed = {**CONSTANTS, **_names_of(names)}
    shown = _shown(text)

    def walk(node: ast.AST) -> sp.Expr:
        if isinstance(node, ast.Constant) and isinstance(node.value, int | float):
            return _number(node.value, argname)
        if isinstance(node, ast.Name):
            if node.id in allowed:
                return allowed[node.id]
            choices = ", ".join(sorted(allowed)[:8])
            euler = "; Euler's number is E" if node.id == "e" else ""
            raise ParseError(
                f"{argname}: name {node.id!r} is not allowed; use one of: {choices}, ...{euler}"
            )
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
            return _check_size(_power(walk(node.left), walk(node.right), argname), argname, text)
        if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
            value = _BINOPS[type(node.op)](walk(node.left), walk(node.right))
            return _check_size(value, argname, text)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitXor):
            raise ParseError(f"{argname}: '^' is not a power in {shown!r}; use ** for powers")
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
            value = walk(node.operand)
            return -value if isinstance(node.op, ast.USub) else value
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id in _FUNCTIONS
            and not node.keywords
        ):
            low, high = _ARITY[node.func.id]
            if not low <= len(node.args) <= high or any(
                isinstance(a, ast.Starred) for a in node.args
            ):
                raise ParseError(
                    f"{argname}: {node.func.id} takes {low if low == high else f'{low} or {high}'}"
                    f" argument(s), got {len(node.args)}"
                )
            value = _FUNCTIONS[node.func.id](*(walk(a) for a in node.args))
            return _check_size(value, argname, text)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            choices = ", ".join(sorted(_FUNCTIONS)[:6])
            raise ParseError(
                f"{argname}: function {node.func.id!r} is not allowed; use one of: {choices}, ..."
            )
        raise ParseError(f"{argname}: {type(node).__name__} is not allowed in {shown!r}")

    try:
        result = walk(tree.body)
    except ParseError:
        raise
    except (ArithmeticError, ValueError, TypeError, RecursionError) as exc:
        raise ParseError(f"{argname}: cannot evaluate the text: {type(exc).__name__}") from None
    if isinstance(result, sp.Basic) and result.has(*_NON_FINITE):
        raise ParseError(f"{argname}: the value is not finite ({result}) in {text!r}")
    return result


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
    if len(text) > MAX_TEXT:
        raise ParseError(f"{argname}: text longer than {MAX_TEXT} characters")
    body = text.strip()
    if body.startswith("[[") and body.endswith("]]"):
        body = body[2:-2].replace("],", ";").replace("]", "").replace("[", "")
    elif body.startswith("[") and body.endswith("]"):
        body = body[1:-1]
    rows = [row.split(",") for row in body.split(";")]
    if len({len(row) for row in rows}) != 1:
        raise ParseError(f"{argname}: rows of different lengths in {text!r}")
    entries = [[parse_expr(e, None, argname=argname) for e in row] for row in rows]
    for row, texts in zip(entries, rows, strict=True):
        for value, entry in zip(row, texts, strict=True):
            if not _fits_float(value):
                raise _too_large(entry.strip(), argname)
    return sp.Matrix(entries)
