r"""Units of a model file: parsed safely, and checked where they are given.

A unit is text in the safe parser's syntax (``"N*m/rad"``, ``"1/s**2"``, ``"1"``); known
names convert to SI with a scale, any other name (``spikes``) is a base unit of its own.
Elementary functions return a pure number, their arguments unchecked (the muscle's :math:`e^{-r}`).

>>> from symctl.model.units import parse_unit
>>> parse_unit("N", "u") == parse_unit("kg*m/s**2", "u")
True
>>> parse_unit("ms", "u").scale
0.001
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import sympy as sp

from symctl._util.parse import parse_expr
from symctl.errors import ParameterError, ParseError

__all__ = ["Unit", "check_rhs", "parse_unit", "unit_of"]

MAX_UNIT_TEXT = 100  # longest unit text

_BASE = ("kg", "m", "s")
_KNOWN = {  # name: (scale, {base: exponent})
    "s": (1.0, {"s": 1}),
    "ms": (1e-3, {"s": 1}),
    "us": (1e-6, {"s": 1}),
    "min": (60.0, {"s": 1}),
    "h": (3600.0, {"s": 1}),
    "Hz": (1.0, {"s": -1}),
    "m": (1.0, {"m": 1}),
    "cm": (1e-2, {"m": 1}),
    "mm": (1e-3, {"m": 1}),
    "km": (1e3, {"m": 1}),
    "kg": (1.0, {"kg": 1}),
    "g": (1e-3, {"kg": 1}),
    "N": (1.0, {"kg": 1, "m": 1, "s": -2}),
    "J": (1.0, {"kg": 1, "m": 2, "s": -2}),
    "W": (1.0, {"kg": 1, "m": 2, "s": -3}),
    "rad": (1.0, {}),
    "deg": (math.pi / 180, {}),
}
_NAME = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")


@dataclass(frozen=True)
class Unit:
    """A unit: its ``scale`` to SI (``ms``: 0.001), the sorted ``dims`` (base unit, exponent),
    and the ``text`` it was read from.

    >>> from symctl.model.units import parse_unit
    >>> parse_unit("N*m", "u").dims
    (('kg', 1), ('m', 2), ('s', -2))
    """

    scale: float
    dims: tuple
    text: str = ""

    def __eq__(self, other) -> bool:
        if not isinstance(other, Unit):
            return NotImplemented
        return self.dims == other.dims and math.isclose(self.scale, other.scale, rel_tol=1e-12)

    def __hash__(self) -> int:
        return hash(self.dims)

    def __mul__(self, other: Unit) -> Unit:
        dims = dict(self.dims)
        for k, e in other.dims:
            dims[k] = dims.get(k, 0) + e
        return _unit(self.scale * other.scale, dims)

    def __pow__(self, e) -> Unit:
        return _unit(self.scale ** float(e), {k: v * e for k, v in self.dims})

    @property
    def dimensionless(self) -> bool:
        """No base unit (a scale alone, like ``deg``)."""
        return not self.dims

    def is_time(self) -> bool:
        """Whether this is a unit of time."""
        return self.dims == (("s", 1),)

    def __str__(self) -> str:
        return self.text or (" ".join(f"{k}^{e}" if e != 1 else k for k, e in self.dims) or "1")


def _unit(scale: float, dims: dict) -> Unit:
    return Unit(float(scale), tuple(sorted((k, v) for k, v in dims.items() if v != 0)))


ONE = _unit(1.0, {})
SECOND = _unit(1.0, {"s": 1})


def parse_unit(text: str, argname: str) -> Unit:
    """A unit read from text (``"N"``, ``"spikes/s"``, ``"rad/s**2"``, ``"1"``) by the safe parser;
    a ParameterError naming ``argname`` for text that is not a product of powers of units.

    >>> from symctl.model.units import parse_unit
    >>> str(parse_unit("spikes/s", "u")), parse_unit("deg", "u").dimensionless
    ('spikes/s', True)
    """
    if not isinstance(text, str):
        raise ParameterError(f"{argname}: a unit is text, got {text!r}")
    body = text.strip()
    if len(body) > MAX_UNIT_TEXT:
        raise ParameterError(f"{argname}: a unit has at most {MAX_UNIT_TEXT} characters")
    if body in ("", "1", "-"):
        return Unit(1.0, (), body)
    names = {n: sp.Symbol(n, positive=True) for n in _NAME.findall(body)}
    try:
        expr = parse_expr(body, names, argname=argname)
    except ParseError as exc:
        raise ParameterError(f"{argname}: {text!r} is not a unit ({exc})") from None
    scale, dims = 1.0, {}
    for factor, power in expr.as_powers_dict().items():
        if factor.is_Number:
            if not (power.is_Number and factor.is_positive):
                raise ParameterError(f"{argname}: {text!r} is not a unit")
            scale *= float(factor**power)
            continue
        if not (isinstance(factor, sp.Symbol) and power.is_Rational):
            raise ParameterError(f"{argname}: {text!r} is not a product of powers of units")
        s, base = _KNOWN.get(factor.name, (1.0, {factor.name: 1}))
        scale *= s ** float(power)
        for k, e in base.items():
            dims[k] = dims.get(k, 0) + e * power
    dims = {k: int(v) if sp.Integer(v) == v else sp.Rational(v) for k, v in dims.items()}
    u = _unit(scale, dims)
    return Unit(u.scale, u.dims, body)


def unit_of(expr: sp.Expr, units: dict) -> Unit | None:
    """The unit of ``expr`` given its symbols' (None where one is missing); ParameterError for
    the terms of a sum in different units, or a symbolic power of a quantity with a unit."""
    if expr.is_Number or expr in (sp.pi, sp.E):
        return ONE
    if isinstance(expr, sp.Symbol):
        return units.get(expr)
    if isinstance(expr, sp.Add):
        known = [(t, u) for t in expr.args if (u := unit_of(t, units)) is not None]
        for term, u in known[1:]:
            if u != known[0][1]:
                raise ParameterError(
                    f"the terms {sp.sstr(known[0][0])!r} [{known[0][1]}] and {sp.sstr(term)!r} "
                    f"[{u}] of a sum have different units"
                )
        return known[0][1] if len(known) == len(expr.args) else None
    if isinstance(expr, sp.Mul):
        out = ONE
        for factor in expr.args:
            u = unit_of(factor, units)
            if u is None:
                return None
            out = out * u
        return out
    if isinstance(expr, sp.Pow):
        base, exponent = expr.args
        if base is sp.E:  # exp(...) prints as a power of E
            return ONE
        u = unit_of(base, units)
        if exponent.is_Rational:
            return None if u is None else u**exponent
        if u is not None and not u.dimensionless:
            raise ParameterError(
                f"{sp.sstr(expr)!r}: a quantity in [{u}] raised to a symbolic power"
            )
        return ONE
    if isinstance(expr, sp.Abs):
        return unit_of(expr.args[0], units)
    if isinstance(expr, sp.Function):
        return ONE
    return None


def check_rhs(rhs: sp.Expr, state_unit: Unit | None, units: dict, argname: str) -> None:
    """Refuse a right-hand side whose unit is not ``state_unit`` per second, where both are known.

    >>> import sympy as sp
    >>> from symctl.model.units import check_rhs, parse_unit
    >>> x, tau = sp.symbols("x tau", positive=True)
    >>> units = {x: parse_unit("N", "x"), tau: parse_unit("s", "tau")}
    >>> check_rhs(-x / tau, units[x], units, "rhs")
    >>> check_rhs(-x * tau, units[x], units, "rhs")
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: rhs: has unit kg^1 m^1 s^-1 ...
    """
    try:
        u = unit_of(rhs, units)
    except ParameterError as exc:
        raise ParameterError(f"{argname}: {exc}") from None
    if u is None or state_unit is None:
        return
    want = state_unit * SECOND**-1
    if u != want:
        raise ParameterError(
            f"{argname}: has unit {_plain(u)} but d/dt of a state in [{state_unit}] has "
            f"{_plain(want)} (time in seconds)"
        )


def _plain(u: Unit) -> str:
    dims = " ".join(f"{k}^{e}" for k, e in u.dims) or "1"
    return dims if math.isclose(u.scale, 1.0) else f"{u.scale:g} {dims}"
