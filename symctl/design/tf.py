"""Discrete transfer functions in closed form: the type :class:`DiscreteTF`."""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import reduce

import numpy as np
import sympy as sp

from symctl._util.display import (
    DISPLAY_DIGITS,
    LatexMixin,
    descending_latex,
    descending_str,
    latex,
    shortened,
)
from symctl._util.exact import products_equal, z_degree, z_poly
from symctl._util.validate import (
    MAX_STEPS,
    bounded_int,
    common_dt,
    finite_expr,
    sampling_time,
    subs_rule,
    symbol_tuple,
    to_expr,
)
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.symbols import z

__all__ = ["DiscreteTF", "convertible"]

_TEXT_NAMES = {"z": z}  # the names text for num/den may use (read by the safe parser)
_LAMBDIFY_MODULES = ("numpy", "math", "mpmath", "scipy", "sympy")


def _natural_key(symbol: sp.Symbol) -> list:
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", symbol.name)]


def _lcm(a: sp.Expr, b: sp.Expr) -> sp.Expr:
    """Least common multiple in z; equal denominators (also with floats) are kept as they are."""
    a, b = sp.expand(a), sp.expand(b)
    if a == b or b == 1:
        return a
    return b if a == 1 else sp.lcm(a, b)


def _z_coeffs(M: sp.MatrixBase, power: int) -> sp.Matrix:
    """The coefficients of ``z**power`` in the entries of ``M`` (zero below ``power = 0``)."""
    return sp.Matrix(M.applyfunc(lambda e: z_poly(e).coeff(power) if power >= 0 else 0))


def _replaced(expr, rule, flags: dict):
    """``expr.subs(rule, **flags)``; symbols to numbers by the same, far faster, ``xreplace``."""
    items = list(rule.items()) if isinstance(rule, dict) else list(rule)
    keys = [k for k, _ in items]
    if (
        items
        and len(set(keys)) == len(keys)
        and all(isinstance(k, sp.Symbol) and isinstance(v, sp.Number) for k, v in items)
    ):
        return expr.xreplace(dict(items))
    return expr.subs(rule, **flags)


class _Conversions:
    """``to_*``/``from_*`` for python-control, ``sympy.physics.control`` and ``scipy.signal``,
    each handed to :mod:`symctl.interop` (``tf_*`` for a transfer function, ``ss_*`` for a
    realization)."""

    def to_control(self):
        """As a discrete python-control system, ``dt`` kept (``True`` when unknown; numbers only)."""
        from symctl import interop

        return getattr(interop, f"{self._interop}_to_control")(self)

    @classmethod
    def from_control(cls, sys):
        """From a discrete python-control system."""
        from symctl import interop

        return getattr(interop, f"{cls._interop}_from_control")(sys)

    def to_sympy(self):
        """As a ``sympy.physics.control`` system, exactly."""
        from symctl import interop

        return getattr(interop, f"{self._interop}_to_sympy")(self)

    @classmethod
    def from_sympy(cls, sys, dt=None, *, var=None):
        """From a ``sympy.physics.control`` system, exactly."""
        from symctl import interop

        return getattr(interop, f"{cls._interop}_from_sympy")(sys, dt, var=var)

    def to_scipy(self):
        """As a discrete ``scipy.signal`` system."""
        from symctl import interop

        return getattr(interop, f"{self._interop}_to_scipy")(self)

    @classmethod
    def from_scipy(cls, sys):
        """From a discrete ``scipy.signal`` system."""
        from symctl import interop

        return getattr(interop, f"{cls._interop}_from_scipy")(sys)


def convertible(kind: str):
    """A class decorator: the ``to_*``/``from_*`` methods of :mod:`symctl.interop`'s ``{kind}_*``
    conversions, in the class itself (so that its API page lists them)."""

    def decorate(cls):
        for name, member in vars(_Conversions).items():
            if name.startswith(("to_", "from_")):
                setattr(cls, name, member)
        cls._interop = kind
        return cls

    return decorate


@convertible("tf")
@dataclass(frozen=True, eq=False)
class DiscreteTF(LatexMixin):
    r"""A transfer function (or matrix) :math:`N(z)/d(z)` over one monic denominator in :data:`symctl.z`.

    :meth:`from_expr` takes any rational expression. ``==`` compares numerator, denominator
    and ``dt`` structurally; :meth:`equals` as rational functions.

    Parameters
    ----------
    num : sympy Matrix or expression
        Numerator polynomial(s) in ``z``.
    den : sympy expression
        Denominator polynomial in ``z``, made monic.
    dt : number, symbol or None
        Sampling time.

    Raises
    ------
    ParameterError
        ``den`` zero, an entry not polynomial in ``z``, a numeric ``dt <= 0``.
    SymctlTypeError
        Entries that are not numbers or sympy expressions.

    Examples
    --------
    >>> from symctl import DiscreteTF, z
    >>> G = DiscreteTF.from_expr(2 / (2*z**2 - 1), dt=0.01)
    >>> G.num, G.den
    (1, z**2 - 1/2)
    >>> G.den_coeffs()
    [1, 0, -1/2]
    >>> G == DiscreteTF(1, z**2 - 0.5, dt=0.01), G.equals(1 / (z**2 - 0.5))
    (False, True)
    """

    _num: sp.ImmutableMatrix
    den: sp.Expr
    dt: sp.Expr | None = None

    def __init__(self, num, den, dt=None):
        if isinstance(num, sp.MatrixBase):
            num_m = sp.ImmutableMatrix(num.applyfunc(lambda e: to_expr(e, "num")))
        else:  # text never reaches ImmutableMatrix: it would be sympify'd (eval)
            num_m = sp.ImmutableMatrix([[to_expr(num, "num", _TEXT_NAMES)]])
        den_e = sp.expand(to_expr(den, "den", _TEXT_NAMES))
        if den_e == 0:
            raise ParameterError("den: the denominator is identically zero")
        for e in (*num_m, den_e):
            if not e.is_polynomial(z):
                raise ParameterError(f"num/den: {e} is not a polynomial in z")
        lead = z_poly(den_e).LC()
        if lead != 1:
            num_m = sp.ImmutableMatrix(num_m.applyfunc(lambda e: sp.expand(sp.cancel(e / lead))))
            den_e = sp.expand(sp.cancel(den_e / lead))
        poly = z_poly(den_e)  # a float leading 1.0 is written as the integer 1
        d = poly.degree()
        den_e = z**d + sp.Add(*(c * z**k for (k,), c in poly.terms() if k != d))
        dt_e = None if dt is None else sampling_time(dt, "dt")
        object.__setattr__(self, "_num", num_m)
        object.__setattr__(self, "den", den_e)
        object.__setattr__(self, "dt", dt_e)
        for e in (*num_m, den_e):  # NaN or oo in a coefficient
            finite_expr(e, "num/den")

    def __eq__(self, other) -> bool:
        if not isinstance(other, DiscreteTF):
            return NotImplemented
        return (self._num, self.den, self.dt) == (other._num, other.den, other.dt)

    def __hash__(self) -> int:
        return hash((DiscreteTF, self._num, self.den, self.dt))

    @classmethod
    def from_expr(cls, expr, dt=None) -> DiscreteTF:
        """From a rational expression (or matrix of them) in ``z``, in lowest terms.

        >>> from symctl import DiscreteTF, z
        >>> DiscreteTF.from_expr((z - 1) / (z**2 - 1)).expr
        1/(z + 1)
        """
        if isinstance(expr, DiscreteTF):
            return expr
        if isinstance(expr, sp.MatrixBase):
            entries = sp.Matrix(expr)
        else:
            if not isinstance(expr, sp.Basic):
                raise SymctlTypeError(
                    "G: expected a sympy expression in z or a DiscreteTF, "
                    f"got {type(expr).__name__}"
                )
            entries = sp.Matrix([[expr]])
        fractions = [sp.fraction(sp.cancel(sp.together(e))) for e in entries]
        for n_, d_ in fractions:
            if not (n_.is_polynomial(z) and d_.is_polynomial(z)):
                raise ParameterError(f"G: {n_ / d_} is not rational in z")
        den = reduce(_lcm, (d for _, d in fractions), sp.Integer(1))
        nums = [n_ if d_ == den else sp.quo(n_ * den, d_, z) for n_, d_ in fractions]
        return cls(sp.Matrix(entries.shape[0], entries.shape[1], nums), den, dt)

    @property
    def shape(self) -> tuple[int, int]:
        """``(outputs, inputs)``."""
        return self._num.shape

    @property
    def is_siso(self) -> bool:
        return self.shape == (1, 1)

    @property
    def num(self):
        """Numerator: a polynomial in ``z`` (SISO) or a matrix of them (MIMO)."""
        return self._num[0, 0] if self.is_siso else self._num

    @property
    def num_matrix(self) -> sp.ImmutableMatrix:
        return self._num

    @property
    def expr(self):
        """The rational expression (or matrix of them)."""
        if self.is_siso:
            return self._num[0, 0] / self.den
        return self._num / self.den

    @property
    def order(self) -> int:
        """Degree of the common denominator."""
        return z_degree(self.den)

    @property
    def relative_degree(self) -> int:
        """``deg d - max deg N_ij`` over the nonzero entries (``inf`` for G = 0)."""
        degrees = [z_degree(e) for e in self._num if e != 0]
        return self.order - max(degrees) if degrees else int(1e9)

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        """Symbols other than ``z``."""
        syms = set(self.den.free_symbols).union(*(e.free_symbols for e in self._num))
        return syms - {z}

    def free_symbols_sorted(self) -> list[sp.Symbol]:
        """:attr:`free_symbols` in natural order (``K_0, K_1, ..., K_10``)."""
        return sorted(self.free_symbols, key=_natural_key)

    def num_coeffs(self, i: int = 0, j: int = 0) -> list[sp.Expr]:
        """Coefficients of numerator ``(i, j)`` in descending powers of ``z``."""
        return z_poly(self._num[i, j]).all_coeffs()

    def den_coeffs(self) -> list[sp.Expr]:
        """Coefficients of the denominator in descending powers of ``z`` (monic)."""
        return z_poly(self.den).all_coeffs()

    def subs(self, *args, **kwargs) -> DiscreteTF:
        """Substitute symbols (as :meth:`sympy.Basic.subs`, text by the safe parser); ``z`` stays free."""
        rule, flags = subs_rule(args, kwargs, self.free_symbols | {z})
        dt = None if self.dt is None else _replaced(self.dt, rule, flags)
        return DiscreteTF(_replaced(self._num, rule, flags), _replaced(self.den, rule, flags), dt)

    def equals(self, other) -> bool:
        """Exact equality as rational functions (a difference that cancels to zero)."""
        other = DiscreteTF.from_expr(other)
        if other.shape != self.shape:
            return False
        return all(
            products_equal([a, other.den], [b, self.den])
            for a, b in zip(self._num, other.num_matrix, strict=True)
        )

    def __mul__(self, other) -> DiscreteTF:
        """Series connection ``self * other`` (``other`` acts first)."""
        if isinstance(other, DiscreteTF):
            if self.shape[1] != other.shape[0]:
                raise DimensionError(f"other: cannot multiply {self.shape} by {other.shape}")
            dt = common_dt(self.dt, other.dt, "other")
            num = self._num * other.num_matrix
            return DiscreteTF(num, self.den * other.den, dt)
        if isinstance(other, sp.Basic | int | float):
            return DiscreteTF(self._num * other, self.den, self.dt)
        if isinstance(other, str | bytes):  # text is never a factor (nor parsed here)
            raise SymctlTypeError(f"other: expected a DiscreteTF or a number, got {other!r}")
        return NotImplemented

    __rmul__ = __mul__

    def markov(self, count: int) -> list[sp.Matrix]:
        r"""The first ``count`` Markov parameters :math:`h_k` of a proper :math:`G = \sum_k h_k z^{-k}`.

        >>> from symctl import DiscreteTF, z
        >>> [h[0] for h in DiscreteTF.from_expr(1 / (z - 2)).markov(4)]
        [0, 1, 2, 4]
        """
        count = bounded_int(count, "count", 0, MAX_STEPS)
        if self.relative_degree < 0:
            raise ParameterError("G: improper transfer function has no Markov expansion")
        a, num, d = self._fraction()
        b = [_z_coeffs(num, d - k) for k in range(min(count, d + 1))]
        h: list[sp.Matrix] = []
        for k in range(count):  # d(z) G = N(z): h_k = b_k - sum_i a_i h_{k-i}
            acc = b[k] if k <= d else sp.zeros(*self.shape)
            for i in range(1, min(k, d) + 1):
                acc = acc - a[i] * h[k - i]
            h.append(acc.applyfunc(sp.expand))
        return h

    def _fraction(self) -> tuple[list, sp.MatrixBase, int]:
        r"""``(a, N, d)``: :math:`d(z) G = N(z)` with :math:`d = \sum_i a_i z^{d-i}`, ``a[0] = 1``."""
        return self.den_coeffs(), self._num, self.order

    def _coeff(self, i: int, j: int, power: int) -> sp.Expr:
        return z_poly(self._num[i, j]).coeff(power) if power >= 0 else sp.Integer(0)

    def impulse_response(self, steps: int) -> np.ndarray:
        """Numeric impulse response ``(steps, outputs, inputs)``; a ParameterError for free symbols,
        an improper ``G``, bad ``steps`` or an overflow.

        >>> from symctl import DiscreteTF, z
        >>> DiscreteTF.from_expr(1 / (z - 2)).impulse_response(4)[:, 0, 0]
        array([0., 1., 2., 4.])
        """
        steps = bounded_int(steps, "steps", 0, MAX_STEPS)
        if self.free_symbols:
            raise ParameterError(
                f"G: substitute values for {sorted(map(str, self.free_symbols))} first"
            )
        if self.relative_degree < 0:
            raise ParameterError("G: improper transfer function has no Markov expansion")
        from scipy.signal import lfilter

        d = self.order
        rows, cols = self.shape
        a = self._floats(self.den_coeffs())
        out = np.zeros((steps, rows, cols))
        impulse = np.zeros(steps)
        impulse[:1] = 1.0
        with np.errstate(over="ignore", invalid="ignore"):
            for i in range(rows):
                for j in range(cols):
                    b = self._floats([self._coeff(i, j, d - k) for k in range(d + 1)])
                    out[:, i, j] = lfilter(b, a, impulse) if steps else impulse
        bad = ~np.isfinite(out).reshape(steps, -1).all(axis=1)
        if bad.any():
            raise ParameterError(
                f"steps: the impulse response overflows at step {int(np.argmax(bad))} "
                f"(G has a pole of modulus {float(np.max(np.abs(self.poles()))):.4g}); "
                f"ask for fewer steps, got {steps}"
            )
        return out

    @staticmethod
    def _floats(coeffs, kind=float, what: str = "coefficients must be real numbers") -> np.ndarray:
        try:
            arr = np.array([kind(c) for c in coeffs])
        except (TypeError, OverflowError):
            raise ParameterError(f"G: {what} a float can hold, got {coeffs}") from None
        if not np.all(np.isfinite(arr)):
            raise ParameterError(f"G: {what} a float can hold (finite), got {coeffs}")
        return arr

    def lambdify(self, symbols=(), modules="numpy"):
        """A function ``f(z, *symbols)`` evaluating G (``symbols``: sympy Symbols, never text)."""
        symbols = symbol_tuple(symbols, "symbols")  # names become code in lambdify: no text
        if modules not in _LAMBDIFY_MODULES:
            raise ParameterError(
                f"modules: expected one of {', '.join(_LAMBDIFY_MODULES)}, got {modules!r}"
            )
        return sp.lambdify((z, *symbols), self.expr, modules=modules)

    def poles(self) -> np.ndarray:
        """Numeric roots of the denominator."""
        if self.free_symbols:
            raise ParameterError("G: poles need numeric coefficients")
        coeffs = self._floats(self.den_coeffs(), complex, "poles need coefficients")
        return np.roots(coeffs)

    def latex(self) -> str:
        r"""LaTeX in the paper's style: a constant factor pulled out, descending powers of z,
        floats to 6 significant digits.

        >>> import sympy as sp
        >>> from symctl import DiscreteTF, z
        >>> DiscreteTF(sp.Float(-0.0459718543789935), 1.0 * z**2 + 0.580040776580175 * z).latex()
        '\\frac{-0.0459719}{z^{2} + 0.580041 z}'
        """
        num, den_expr = shortened(self._num), shortened(self.den)
        den = descending_latex(den_expr, DISPLAY_DIGITS)
        if not self.is_siso:
            return rf"\frac{{1}}{{{den}}} {latex(num)}"
        gain, rest = sp.factor_terms(num[0, 0]).as_independent(z, as_Add=False)
        prefix = "" if gain == 1 else ("-" if gain == -1 else latex(gain) + " ")
        if rest == 1:
            return latex(gain) if den_expr == 1 else rf"\frac{{{latex(gain)}}}{{{den}}}"
        if den_expr == 1:
            return prefix + descending_latex(rest, DISPLAY_DIGITS)
        return rf"{prefix}\frac{{{descending_latex(rest, DISPLAY_DIGITS)}}}{{{den}}}"

    def __repr__(self) -> str:
        return f"DiscreteTF({self}, dt={self.dt})"

    def __str__(self) -> str:
        """``(num)/(den)`` in descending powers of z, floats to 6 significant digits.

        >>> from symctl import DiscreteTF, z
        >>> str(DiscreteTF(1, 1)), str(DiscreteTF(0.5, 1.0 * z - 0.25))
        ('1', '(0.5)/(z - 0.25)')
        """
        num, den_expr = shortened(self._num), shortened(self.den)
        den = descending_str(den_expr, DISPLAY_DIGITS)
        if self.is_siso:
            text = descending_str(num[0, 0], DISPLAY_DIGITS)
            return text if den_expr == 1 else f"({text})/({den})"
        rows = ", ".join(
            "[" + ", ".join(descending_str(e, DISPLAY_DIGITS) for e in row) + "]"
            for row in num.tolist()
        )
        return f"[{rows}]" if den_expr == 1 else f"[{rows}]/({den})"
