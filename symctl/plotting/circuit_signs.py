r"""The sign of a synaptic weight, as a circuit drawing colours it: known, or depending on symbols.

A weight such as :math:`K_0 (K_2 + \epsilon_1\epsilon_3)/(C_1 C_3)` has no sign until its
symbols have values. Given ``signs_at`` (a number per symbol, or a range ``(lo, hi)`` for
one that varies), a weight is ``"+"`` / ``"-"`` when so for *every* value (numbers
substituted exactly, ranges by SymPy's interval arithmetic,
:class:`~sympy.calculus.accumulationbounds.AccumulationBounds`, which never claims a sign
some point lacks), ``"0"`` when zero, else ``"?"``. Without, the sign is SymPy's from the
symbols' assumptions.

>>> import sympy as sp
>>> from symctl.plotting.circuit_signs import SignValues, weight_sign
>>> K0, K2, e1, e3, C1 = sp.symbols("K_0 K_2 epsilon_1 epsilon_3 C_1", real=True)
>>> at = SignValues.of({K0: -0.046, K2: -0.35, C1: 1, e1: (-0.9, 0.9), e3: (-0.9, 0.9)})
>>> weight_sign(K0 / C1, at), weight_sign(K0 * (K2 + e1 * e3) / C1, at)
('-', '?')
>>> weight_sign(K0 * (K2 - e1**2) / C1, at)   # K_2 - eps^2 < 0 on the whole range
'+'
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import sympy as sp

from symctl._util.validate import real_number, to_expr
from symctl.errors import ParameterError, SymctlTypeError

__all__ = ["SignValues", "weight_sign"]


@dataclass(frozen=True)
class SignValues:
    r"""The values at which a drawing reads the signs of its symbolic weights.

    Attributes
    ----------
    numbers : mapping of Symbol to Rational or Float
        A value per symbol.
    ranges : mapping of Symbol to (float, float)
        A closed range ``(lo, hi)``, ``lo < hi``, per symbol that varies.

    Build one with :meth:`of`.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl.plotting.circuit_signs import SignValues
    >>> K0, e1 = sp.symbols("K_0 epsilon_1")
    >>> at = SignValues.of({K0: -0.05, "epsilon_1": (-0.9, 0.9)}, symbols={K0, e1})
    >>> sorted(map(str, at.numbers)), sorted(map(str, at.ranges))
    (['K_0'], ['epsilon_1'])
    """

    numbers: Mapping = field(default_factory=dict)
    ranges: Mapping = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "numbers", MappingProxyType(dict(self.numbers)))
        object.__setattr__(self, "ranges", MappingProxyType(dict(self.ranges)))

    def __hash__(self) -> int:
        return hash((tuple(self.numbers.items()), tuple(self.ranges.items())))

    def __eq__(self, other) -> bool:
        if not isinstance(other, SignValues):
            return NotImplemented
        return dict(self.numbers) == dict(other.numbers) and dict(self.ranges) == dict(other.ranges)

    def __bool__(self) -> bool:
        return bool(self.numbers or self.ranges)

    @classmethod
    def of(cls, values, argname: str = "signs_at", symbols=()) -> SignValues:
        """Check ``values``: a mapping of symbols (or their names) to numbers or ``(lo, hi)``.

        Parameters
        ----------
        values : mapping or SignValues or None
            Keys are SymPy symbols, or the names of ``symbols`` (a name is matched,
            never parsed); values real numbers or ranges ``(lo, hi)`` with ``lo < hi``.
        argname : str
            The argument named in an error.
        symbols : iterable of Symbol
            The symbols a name may refer to.

        Returns
        -------
        SignValues

        Raises
        ------
        SymctlTypeError
            ``values`` is not a mapping, a key is neither a symbol nor a string, or a
            value neither a number nor a pair.
        ParameterError
            A name that is no symbol's, a value that is not finite, or a range with
            ``lo >= hi``.

        Examples
        --------
        >>> from symctl.plotting.circuit_signs import SignValues
        >>> SignValues.of({"x": (1, 0)}, symbols=__import__("sympy").symbols("x,"))
        Traceback (most recent call last):
        ...
        symctl.errors.ParameterError: signs_at: the range of x must have lo < hi, got (1, 0)
        """
        if values is None:
            return cls()
        if isinstance(values, SignValues):
            return values
        if not isinstance(values, Mapping):
            raise SymctlTypeError(
                f"{argname}: expected a mapping of symbols to numbers or (lo, hi) ranges, "
                f"got {type(values).__name__}"
            )
        names = {str(s): s for s in symbols}
        nums, ranges = {}, {}
        for key, value in values.items():
            sym = _symbol(key, names, argname)
            if isinstance(value, tuple | list) and len(value) == 2:
                lo, hi = (real_number(v, f"{argname}[{sym}]") for v in value)
                if not lo < hi:
                    raise ParameterError(
                        f"{argname}: the range of {sym} must have lo < hi, got {tuple(value)}"
                    )
                ranges[sym] = (lo, hi)
            elif isinstance(value, sp.Basic | numbers.Real) and not isinstance(value, bool):
                v = to_expr(value, f"{argname}[{sym}]")
                if not (v.is_number and v.is_real and v.is_finite):
                    raise ParameterError(f"{argname}[{sym}]: must be a finite real number, got {v}")
                nums[sym] = v
            else:
                raise SymctlTypeError(
                    f"{argname}[{sym}]: expected a real number or a (lo, hi) range, got {value!r}"
                )
        return cls(nums, ranges)


def _symbol(key, names: dict, argname: str) -> sp.Symbol:
    if isinstance(key, sp.Symbol):
        return key
    if isinstance(key, str):
        if key in names:
            return names[key]
        raise ParameterError(
            f"{argname}: no symbol named {key!r} (the symbols are: {', '.join(sorted(names))})"
        )
    raise SymctlTypeError(f"{argname}: a key must be a sympy Symbol or its name, got {key!r}")


def _sign_of_bounds(value) -> str:
    if isinstance(value, sp.AccumBounds):
        return "+" if value.min.is_positive else "-" if value.max.is_negative else "?"
    if value.is_zero:
        return "0"
    if value.is_positive:
        return "+"
    if value.is_negative:
        return "-"
    return "?"


def weight_sign(weight, at: SignValues | None = None) -> str:
    """``"+"``, ``"-"``, ``"0"`` or ``"?"``: the sign of ``weight`` for all the values ``at``.

    Parameters
    ----------
    weight : sympy expression or number
    at : SignValues, optional
        Numbers and ranges of its symbols; without, SymPy's sign from the assumptions.

    Returns
    -------
    str

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl.plotting.circuit_signs import SignValues, weight_sign
    >>> x = sp.Symbol("x")
    >>> weight_sign(-2), weight_sign(x), weight_sign(x, SignValues(ranges={x: (0.5, 2.0)}))
    ('-', '?', '+')
    """
    w = to_expr(weight, "weight")
    if at:
        if at.numbers:
            w = w.xreplace(dict(at.numbers))
        left = {s: sp.AccumBounds(*at.ranges[s]) for s in w.free_symbols if s in at.ranges}
        if left and w.free_symbols <= set(left):
            try:
                return _sign_of_bounds(w.xreplace(left))
            except (TypeError, ValueError, ZeroDivisionError):  # e.g. a range through a pole
                return "?"
    return _sign_of_bounds(w)
