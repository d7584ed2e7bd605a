"""Argument checks at the public boundary, and the size limits (docs/reliability.md).

A wrong type is a ``SymctlTypeError``, a bad value a ``ParameterError`` (shapes:
``DimensionError``), each naming the argument; text goes through the safe parser only.
"""

from __future__ import annotations

import cmath
import math
import numbers
from collections.abc import Mapping

import numpy as np
import sympy as sp

from symctl._util.parse import parse_expr
from symctl._util.pickling import register_sympy
from symctl.errors import DimensionError, ParameterError, SymctlTypeError

register_sympy()  # exact expressions pickle as they are (every value module imports this one)


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
    """A sympy Matrix from a scalar (1 x 1), a flat list (a column), nested lists or an array."""
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
    return check_psd(numeric_matrix(value, argname, (size, size)), argname, definite=definite)


def check_psd(arr: np.ndarray, argname: str, *, definite: bool = False) -> np.ndarray:
    """``arr`` (square, finite) when symmetric positive semidefinite (or definite), else raise."""
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


def _float(value, argname: str) -> float:
    """``float(value)`` of a real number (not a bool); too large for a float: a ParameterError."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise SymctlTypeError(f"{argname}: expected a real number, got {value!r}")
    try:
        return float(value)
    except OverflowError:
        raise ParameterError(
            f"{argname}: must be finite, got a number too large for a float"
        ) from None


def positive_number(value, argname: str) -> float:
    """A finite, strictly positive float."""
    out = _float(value, argname)
    if not math.isfinite(out) or out <= 0:
        raise ParameterError(f"{argname}: must be a finite number > 0, got {value!r}")
    return out


def real_number(value, argname: str) -> float:
    """A finite float."""
    out = _float(value, argname)
    if not math.isfinite(out):
        raise ParameterError(f"{argname}: must be finite, got {value!r}")
    return out


def nonneg_int(value, argname: str) -> int:
    """An integer >= 0: a wrong type (bool, float, text) is a type error, a negative a value one."""
    return bounded_int(value, argname, 0, math.inf)


def as_generator(value, argname: str) -> np.random.Generator:
    """A NumPy ``Generator`` from a Generator, an int seed >= 0 or None (fresh entropy)."""
    if isinstance(value, np.random.Generator):
        return value
    if value is None:
        return np.random.default_rng()
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return np.random.default_rng(nonneg_int(value, argname))
    raise SymctlTypeError(f"{argname}: expected an int seed or a numpy Generator, got {value!r}")


def read_only(value, dtype=None) -> np.ndarray:
    """A read-only array: a copy (the caller's array is never frozen), unless read-only already."""
    arr = np.asarray(value, dtype=dtype)
    if arr.flags.writeable:
        arr = np.array(arr, order="C")
        arr.setflags(write=False)
    return arr


def sampling_time(value, argname: str) -> sp.Expr:
    """A sampling time: a sympy expression, > 0 when it is a number (symbols pass)."""
    ts = to_expr(value, argname)
    if ts.is_number and not ts.is_positive:
        raise ParameterError(f"{argname}: must be > 0, got {value!r}")
    return ts


def as_random(value, argname: str):
    """A ``random.Random`` (exact big integers) from None, an int seed, a Random or a Generator."""
    import random

    if value is None:
        return random.SystemRandom()
    if isinstance(value, random.Random):
        return value
    if isinstance(value, np.random.Generator):
        return random.Random(int(value.integers(0, 2**63)))
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return random.Random(int(value))
    raise SymctlTypeError(
        f"{argname}: expected None, an int seed, random.Random or numpy Generator, got {value!r}"
    )


def positive_int(value, argname: str) -> int:
    """An integer >= 1: a wrong type is a type error, a smaller integer a value error."""
    return bounded_int(value, argname, 1, math.inf)


def float_array(value, argname: str) -> np.ndarray:
    """A finite float64 array of any shape (not through sympy); text, None, ragged: a type error."""
    if isinstance(value, str | bytes) or value is None:
        raise SymctlTypeError(f"{argname}: expected an array of numbers, got {value!r}")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise SymctlTypeError(
            f"{argname}: expected an array of real numbers, got {type(value).__name__}"
        ) from None
    if not np.all(np.isfinite(arr)):
        raise ParameterError(f"{argname}: entries must be finite (no NaN or inf)")
    return arr


def _subs_key(key, names: dict, argname: str) -> sp.Basic:
    if isinstance(key, str):
        if key in names:
            return names[key]
        choices = ", ".join(sorted(names)) or "none"
        raise ParameterError(f"{argname}: no symbol named {key!r} (the symbols are: {choices})")
    if isinstance(key, sp.Basic):
        return key
    raise SymctlTypeError(
        f"{argname}: a key must be a sympy symbol (or expression) or a symbol's name, got {key!r}"
    )


def subs_rule(args: tuple, kwargs: dict, symbols=(), argname: str = "subs"):
    """The checked arguments of a ``subs`` method: ``(rule, flags)`` for :meth:`sympy.Basic.subs`.

    ``subs(old, new)``, ``subs(mapping)`` or ``subs(pairs)``, nothing SymPy would ``eval``: a
    key is a sympy object or the name of one of ``symbols``, a value goes through
    :func:`to_expr`; the only keyword is ``simultaneous``.
    """
    flags = {}
    for name, flag in kwargs.items():
        if name != "simultaneous":
            raise SymctlTypeError(f"{argname}: unexpected keyword argument {name!r}")
        if not isinstance(flag, bool):
            raise SymctlTypeError(f"{argname}: {name} must be True or False, got {flag!r}")
        flags[name] = flag
    ordered = True
    if len(args) == 2:
        pairs = [tuple(args)]
    elif len(args) == 1 and isinstance(args[0], Mapping):
        pairs, ordered = list(args[0].items()), False
    elif len(args) == 1 and isinstance(args[0], set | frozenset):
        pairs, ordered = list(args[0]), False
    elif len(args) == 1 and isinstance(args[0], list | tuple):
        pairs = list(args[0])
    else:
        raise SymctlTypeError(
            f"{argname}: expected (old, new), a mapping or a list of (old, new) pairs, got {args!r}"
        )
    names = {s.name: s for s in symbols if isinstance(s, sp.Symbol)}
    rule = []
    for pair in pairs:
        if not isinstance(pair, list | tuple) or len(pair) != 2:
            raise SymctlTypeError(f"{argname}: expected an (old, new) pair, got {pair!r}")
        key = _subs_key(pair[0], names, argname)
        rule.append((key, to_expr(pair[1], f"{argname}[{key}]", names)))
    return (rule if ordered else dict(rule)), flags


def symbol_tuple(value, argname: str) -> tuple[sp.Symbol, ...]:
    """A tuple of sympy Symbols (for ``lambdify``: a name there becomes Python code, so no text)."""
    if isinstance(value, sp.Symbol):
        return (value,)
    if isinstance(value, str | bytes) or not isinstance(value, list | tuple):
        raise SymctlTypeError(f"{argname}: expected a sequence of sympy Symbols, got {value!r}")
    for item in value:
        if not isinstance(item, sp.Symbol):
            raise SymctlTypeError(f"{argname}: expected sympy Symbols, got {item!r}")
    return tuple(value)


def common_dt(dt1, dt2, argname: str):
    """The sampling time of a combination of two systems with sampling times ``dt1``, ``dt2``."""
    if dt1 is None or dt2 is None or dt1 == dt2:
        return dt2 if dt1 is None else dt1
    if dt1.is_number and dt2.is_number:
        if math.isclose(float(dt1), float(dt2), rel_tol=1e-12, abs_tol=0.0):
            return dt1
    elif sp.expand(dt1 - dt2) == 0:
        return dt1
    raise ParameterError(f"{argname}: incompatible sampling times dt = {dt1} and dt = {dt2}")


def relative_tolerance(value, argname: str) -> float:
    """A relative tolerance: a real number with ``0 < value < 1``."""
    out = positive_number(value, argname) if value != 0 else 0.0
    if not 0 < out < 1:
        raise ParameterError(f"{argname}: must be a number in (0, 1), got {value!r}")
    return out


# Every size symctl accepts has a limit, checked before any work (docs/reliability.md).
MAX_DELAY = 500  # net delay T (steps) of augment and controller_tf (controller_tf(500): ~1 s)
MAX_STEPS = 10**6  # horizon (samples) of a simulation or an impulse response
MAX_SYMBOLIC_BLOCK = 3  # n + m of a symbolic zero-order hold (SymPy's expm of n + m = 3: ~30 s)
MAX_COUNT = 10_000  # numeric draws at once (realizations, amplitudes of the nonlinear check)
MAX_CIRCUITS = 1000  # realizations built into circuits and simulated at once (~50 ms each)
PAPER_MAX_DELAY = 20  # net delay of derive_paper: the range the documents are laid out for
MAX_STATES = 1000  # states of a plant and of a delay-augmented system
TS_TAU_MIN = 1e-6  # smallest Ts/tau of the muscle
MAX_EXPONENT = 700.0  # argument of the model's exponentials: Ts/tau, |r_bar| (e^709 overflows)
MAX_MAGNITUDE = 1e100  # a model parameter or cost entry: the LQR squares them (1e200 < 1.8e308)


def bounded_int(value, argname: str, low: int, high: int) -> int:
    """An integer in ``[low, high]``: a wrong type is a type error, one outside a value error."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise SymctlTypeError(f"{argname}: expected an integer, got {value!r}")
    if value < low:
        raise ParameterError(f"{argname}: must be an integer >= {low}, got {value!r}")
    if value > high:
        raise ParameterError(f"{argname}: must be an integer <= {high} (the limit), got {value!r}")
    return int(value)


def bounded_number(value, argname: str, low: float, high: float) -> float:
    """A finite float in ``[low, high]``."""
    out = real_number(value, argname)
    if not low <= out <= high:
        raise ParameterError(f"{argname}: must be a number in [{low:g}, {high:g}], got {value!r}")
    return out


_NON_FINITE = (sp.nan, sp.oo, -sp.oo, sp.zoo)


def finite_expr(expr, argname: str):
    """``expr`` unchanged, unless it holds NaN, an infinity or a non-finite float."""
    if isinstance(expr, sp.Basic):
        bad = expr in _NON_FINITE or expr.has(*_NON_FINITE)
        bad = bad or any(not math.isfinite(float(f)) for f in expr.atoms(sp.Float))
    else:
        bad = isinstance(expr, numbers.Number) and not cmath.isfinite(complex(expr))
    if bad:
        raise ParameterError(f"{argname}: must be finite (no NaN or infinity), got {expr}")
    return expr


def callable_or_none(value, argname: str):
    """``value`` when it is callable or None, else a :class:`SymctlTypeError`."""
    if value is not None and not callable(value):
        raise SymctlTypeError(f"{argname}: expected a callable or None, got {value!r}")
    return value


def check_magnitude(arr, argname: str):
    """``arr`` (a float array) unless an entry exceeds ``MAX_MAGNITUDE`` in magnitude."""
    big = float(np.max(np.abs(arr))) if arr.size else 0.0
    if big > MAX_MAGNITUDE:
        raise ParameterError(
            f"{argname}: entries must be at most {MAX_MAGNITUDE:g} in magnitude "
            f"(the LQR squares them), got {big:g}"
        )
    return arr


def max_size(value, argname: str, limit: int) -> None:
    """Refuse a matrix-like ``value`` with more than ``limit`` rows or columns, before SymPy."""
    if isinstance(value, str):
        return
    try:
        shape = value.shape if hasattr(value, "shape") else np.shape(value)
    except (TypeError, ValueError):  # ragged: to_matrix names it
        return
    if any(int(d) > limit for d in shape):
        raise DimensionError(
            f"{argname}: at most {limit} rows and columns, got shape {tuple(shape)}"
        )


MAX_EXPANDED_TERMS = 50_000  # terms of a MIMO D(z)^-1 N(z) expanded as num/den unless asked (~15 s)
MAX_OUTPUT_BYTES = 4 * 2**30  # traces one simulate_batch result (or chunk) holds: 4 GiB
