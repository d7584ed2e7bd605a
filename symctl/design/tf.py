r"""Discrete transfer functions in closed form, and the optimal delayed controller :math:`G(z)`.

:class:`DiscreteTF` is symctl's transfer-function type: an immutable pair of a
numerator matrix of polynomials in :math:`z` and one common, monic denominator
polynomial, exact or symbolic. SISO objects behave like a scalar.

:func:`controller_tf` derives the controller of the paper's section
"Optimal delayed controller" from the augmented system: with
:math:`\mu(t) = K_0 x(t) + \sum_{k=1}^T K_k \gamma_k(t)` and
:math:`\gamma_k = z^{-k} \mu`, eliminating the chain gives

.. math::
    G(z) = \frac{\Delta_r(z)}{X(z)} = D(z)^{-1} K_0,\qquad
    D(z) = z^T I - K_1 z^{T-1} - \dots - K_T,

which for a scalar plant is the paper's eq. (transfer_fn),
:math:`K_0/(z^T - K_1 z^{T-1} - \dots - K_T)`. The derivation is proved, not
trusted: :func:`prove_controller_tf` checks the polynomial identity
:math:`(zI - F_c)\,W(z) = H_c \det D(z)` against the controller's own
state-space matrices read off the augmented system.

>>> from symctl import z
>>> G = controller_tf(2)
>>> G.expr
K_0/(-K_1*z - K_2 + z**2)
>>> G.relative_degree
2
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache, reduce

import numpy as np
import sympy as sp
from sympy.polys.rings import ring

from symctl._util.display import LatexMixin, latex
from symctl._util.validate import nonneg_int, to_expr
from symctl.design.augment import AugmentedSystem
from symctl.design.lqr import Gains
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.symbols import gain_matrix_symbols, z

__all__ = ["DiscreteTF", "controller_tf", "descending_str", "prove_controller_tf"]


class _ZPoly:
    """A univariate polynomial in z read off a sparse ring element (the few views symctl needs)."""

    __slots__ = ("_coeffs",)

    def __init__(self, coeffs: dict[int, sp.Expr]):
        self._coeffs = {k: c for k, c in coeffs.items() if c != 0}

    @property
    def is_zero(self) -> bool:
        return not self._coeffs

    def degree(self) -> int:
        return max(self._coeffs) if self._coeffs else -1

    def LC(self) -> sp.Expr:
        return self._coeffs[self.degree()] if self._coeffs else sp.Integer(0)

    def all_coeffs(self) -> list[sp.Expr]:
        if not self._coeffs:
            return [sp.Integer(0)]
        return [self._coeffs.get(k, sp.Integer(0)) for k in range(self.degree(), -1, -1)]

    def coeff_monomial(self, monomial: sp.Expr) -> sp.Expr:
        power = 0 if monomial == 1 else sp.degree(monomial, z)
        return self._coeffs.get(int(power), sp.Integer(0))

    def terms(self) -> list[tuple[tuple[int], sp.Expr]]:
        return [((k,), self._coeffs[k]) for k in sorted(self._coeffs, reverse=True)]


@lru_cache(maxsize=4096)
def _poly(expr: sp.Expr) -> _ZPoly:
    """Coefficients of ``expr`` in z, computed with sparse ring arithmetic (no expression expansion)."""
    pairs = _ring_fractions([expr])
    if pairs is None:
        poly = sp.Poly(expr, z)
        return _ZPoly({k: c for (k,), c in poly.terms()})
    num, den = pairs[0]
    if den.degree(0) > 0:
        raise ParameterError(f"num/den: {expr} is not a polynomial in z")
    den_expr = den.as_expr()
    by_power: dict[int, dict] = {}
    for monom, coeff in num.items():
        by_power.setdefault(monom[0], {})[(0, *monom[1:])] = coeff
    ring_ = num.ring
    return _ZPoly(
        {k: sp.cancel(ring_.from_dict(terms).as_expr() / den_expr) for k, terms in by_power.items()}
    )


def _generators(exprs) -> list[sp.Symbol] | None:
    """z and the other symbols, or None when an expression holds floats or other atoms.

    Transcendental constants such as ``exp(1/2)`` are algebraically related
    (``exp(1/2) * exp(-1/2) = 1``); a polynomial ring would miss that, so such
    expressions take the expression path instead.
    """
    syms: set[sp.Symbol] = set()
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, sp.Symbol):
                syms.add(node)
            elif isinstance(node, sp.Float) or not (
                isinstance(node, sp.Add | sp.Mul | sp.Rational)
                or (isinstance(node, sp.Pow) and node.exp.is_Integer)
            ):
                return None
    return [z, *sorted(syms - {z}, key=str)]


def _ring_fractions(exprs: list[sp.Expr]) -> list[tuple] | None:
    """Each expression as a pair (numerator, denominator) of sparse polynomials over QQ.

    The ring's generators are z and every other symbol; sums, products and
    integer powers are carried out on the pairs with no gcd and no expansion
    of expression trees, so the cost is that of sparse polynomial
    multiplication. Returns None when :func:`_generators` does.
    """
    gens = _generators(exprs)
    if gens is None:
        return None
    R, *_ = ring(gens, sp.QQ)
    index = {g: i for i, g in enumerate(gens)}

    def conv(e: sp.Expr) -> tuple:
        if isinstance(e, sp.Symbol):
            return R.gens[index[e]], R.one
        if isinstance(e, sp.Rational):
            return R(e.p), R(e.q)
        if isinstance(e, sp.Add):
            num, den = conv(e.args[0])
            for arg in e.args[1:]:
                n2, d2 = conv(arg)
                num, den = (num + n2, den) if d2 == den else (num * d2 + n2 * den, den * d2)
            return num, den
        if isinstance(e, sp.Mul):
            num, den = R.one, R.one
            for arg in e.args:
                n2, d2 = conv(arg)
                num, den = num * n2, den * d2
            return num, den
        base_num, base_den = conv(e.base)  # Pow with an integer exponent
        k = int(e.exp)
        return (base_num**k, base_den**k) if k >= 0 else (base_den ** (-k), base_num ** (-k))

    return [conv(e) for e in exprs]


def _products_equal(left: list[sp.Expr], right: list[sp.Expr]) -> bool:
    """Exact test of prod(left) == prod(right) for rational expressions."""
    pairs = _ring_fractions([*left, *right])
    if pairs is None:
        return sp.expand(sp.Mul(*left) - sp.Mul(*right)) == 0
    num_l, den_l, num_r, den_r = (pairs[0][0].ring.one,) * 4
    for n_, d_ in pairs[: len(left)]:
        num_l, den_l = num_l * n_, den_l * d_
    for n_, d_ in pairs[len(left) :]:
        num_r, den_r = num_r * n_, den_r * d_
    return num_l * den_r == num_r * den_l


def _natural_key(symbol: sp.Symbol) -> list:
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", symbol.name)]


def _lcm(a: sp.Expr, b: sp.Expr) -> sp.Expr:
    """Least common multiple in z; equal denominators (also with floats) are kept as they are."""
    a, b = sp.expand(a), sp.expand(b)
    if a == b or b == 1:
        return a
    return b if a == 1 else sp.lcm(a, b)


@dataclass(frozen=True, eq=False)
class DiscreteTF(LatexMixin):
    r"""A transfer function (or matrix) :math:`N(z)/d(z)` in the symbol :data:`symctl.z`.

    Parameters
    ----------
    num : sympy Matrix or expression
        Numerator polynomial(s) in ``z``; a scalar for SISO.
    den : sympy expression
        Common denominator polynomial in ``z``; it is made monic.
    dt : number, symbol or None
        Sampling time, kept for conversions (``None``: unspecified).

    Use :meth:`from_expr` for any rational expression. ``num`` and ``den`` are
    stored in lowest terms only when built by :meth:`from_expr`.

    Examples
    --------
    >>> from symctl import z
    >>> G = DiscreteTF.from_expr(2 / (2*z**2 - 1), dt=0.01)
    >>> G.num, G.den
    (1, z**2 - 1/2)
    >>> G.den_coeffs()
    [1, 0, -1/2]
    """

    _num: sp.ImmutableMatrix
    den: sp.Expr
    dt: sp.Expr | None = None

    def __init__(self, num, den, dt=None):
        num_m = sp.ImmutableMatrix(num if isinstance(num, sp.MatrixBase) else [[num]])
        num_m = sp.ImmutableMatrix(num_m.applyfunc(lambda e: to_expr(e, "num")))
        den_e = sp.expand(to_expr(den, "den"))
        if den_e == 0:
            raise ParameterError("den: the denominator is identically zero")
        for e in (*num_m, den_e):
            if not e.is_polynomial(z):
                raise ParameterError(f"num/den: {e} is not a polynomial in z")
        lead = _poly(den_e).LC()
        if lead != 1:
            num_m = sp.ImmutableMatrix(num_m.applyfunc(lambda e: sp.expand(sp.cancel(e / lead))))
            den_e = sp.expand(sp.cancel(den_e / lead))
        poly = _poly(den_e)  # a float leading 1.0 is written as the integer 1
        d = poly.degree()
        den_e = z**d + sp.Add(*(c * z**k for (k,), c in poly.terms() if k != d))
        dt_e = None if dt is None else to_expr(dt, "dt")
        if dt_e is not None and dt_e.is_number and not dt_e.is_positive:
            raise ParameterError(f"dt: must be > 0, got {dt!r}")
        object.__setattr__(self, "_num", num_m)
        object.__setattr__(self, "den", den_e)
        object.__setattr__(self, "dt", dt_e)

    # ------------------------------------------------------------ construction
    @classmethod
    def from_expr(cls, expr, dt=None) -> DiscreteTF:
        """From a rational expression (or matrix of them) in ``z``, in lowest terms.

        >>> from symctl import z
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

    # ------------------------------------------------------------ views
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
        """Numerator as a matrix, also for SISO."""
        return self._num

    @property
    def expr(self):
        """The rational expression (SISO) or matrix of them (MIMO)."""
        if self.is_siso:
            return self._num[0, 0] / self.den
        return self._num / self.den

    @property
    def order(self) -> int:
        """Degree of the common denominator."""
        return _poly(self.den).degree()

    @property
    def relative_degree(self) -> int:
        """``deg d - max deg N_ij`` over the nonzero entries (``inf`` for G = 0)."""
        degrees = [_poly(e).degree() for e in self._num if e != 0]
        return self.order - max(degrees) if degrees else int(1e9)

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        """Symbols other than ``z``."""
        syms = set(self.den.free_symbols).union(*(e.free_symbols for e in self._num))
        return syms - {z}

    def free_symbols_sorted(self) -> list[sp.Symbol]:
        """:attr:`free_symbols` in a stable, natural order (``K_0, K_1, ..., K_10``)."""
        return sorted(self.free_symbols, key=_natural_key)

    def num_coeffs(self, i: int = 0, j: int = 0) -> list[sp.Expr]:
        """Coefficients of numerator ``(i, j)`` in descending powers of ``z``."""
        return _poly(self._num[i, j]).all_coeffs()

    def den_coeffs(self) -> list[sp.Expr]:
        """Coefficients of the denominator in descending powers of ``z`` (monic)."""
        return _poly(self.den).all_coeffs()

    # ------------------------------------------------------------ algebra
    def subs(self, *args, **kwargs) -> DiscreteTF:
        """Substitute symbols (as :meth:`sympy.Basic.subs`); ``z`` must stay free."""
        dt = None if self.dt is None else self.dt.subs(*args, **kwargs)
        return DiscreteTF(self._num.subs(*args, **kwargs), self.den.subs(*args, **kwargs), dt)

    def equals(self, other) -> bool:
        """Exact equality as rational functions (a difference that cancels to zero)."""
        other = DiscreteTF.from_expr(other)
        if other.shape != self.shape:
            return False
        return all(
            _products_equal([a, other.den], [b, self.den])
            for a, b in zip(self._num, other.num_matrix, strict=True)
        )

    def __mul__(self, other) -> DiscreteTF:
        """Series connection ``self * other`` (``other`` acts first)."""
        if isinstance(other, DiscreteTF):
            if self.shape[1] != other.shape[0]:
                raise DimensionError(f"other: cannot multiply {self.shape} by {other.shape}")
            dt = self.dt if self.dt is not None else other.dt
            num = self._num * other.num_matrix
            return DiscreteTF(num, self.den * other.den, dt)
        if isinstance(other, sp.Basic | int | float):
            return DiscreteTF(self._num * other, self.den, self.dt)
        return NotImplemented

    __rmul__ = __mul__

    # ------------------------------------------------------------ numbers
    def markov(self, count: int) -> list[sp.Matrix]:
        r"""The first ``count`` Markov parameters :math:`h_k` of :math:`G = \sum_k h_k z^{-k}`.

        Exact (symbolic entries stay symbolic). For a strictly proper ``G``
        these are the impulse response; :math:`h_0` is the feed-through.
        Requires a proper ``G``.

        >>> from symctl import z
        >>> [h[0] for h in DiscreteTF.from_expr(1 / (z - 2)).markov(4)]
        [0, 1, 2, 4]
        """
        count = nonneg_int(count, "count")
        d = self.order
        if self.relative_degree < 0:
            raise ParameterError("G: improper transfer function has no Markov expansion")
        a = self.den_coeffs()
        rows, cols = self.shape
        b = [
            sp.Matrix(rows, cols, lambda i, j, k=k: self._coeff(i, j, d - k)) for k in range(d + 1)
        ]
        h: list[sp.Matrix] = []
        for k in range(count):
            acc = b[k] if k <= d else sp.zeros(rows, cols)
            for i in range(1, min(k, d) + 1):
                acc = acc - a[i] * h[k - i]
            h.append(acc.applyfunc(sp.expand))
        return h

    def _coeff(self, i: int, j: int, power: int) -> sp.Expr:
        return _poly(self._num[i, j]).coeff_monomial(z**power) if power >= 0 else sp.Integer(0)

    def impulse_response(self, steps: int) -> np.ndarray:
        """Numeric impulse response, shape ``(steps, outputs, inputs)``; needs numbers."""
        if self.free_symbols:
            raise ParameterError(
                f"G: substitute values for {sorted(map(str, self.free_symbols))} first"
            )
        return np.array([np.array(h.evalf(), dtype=float) for h in self.markov(steps)])

    def lambdify(self, symbols=(), modules="numpy"):
        """A NumPy function ``f(z, *symbols)`` evaluating G (broadcasts over arrays)."""
        return sp.lambdify((z, *symbols), self.expr, modules=modules)

    def poles(self) -> np.ndarray:
        """Numeric roots of the denominator."""
        if self.free_symbols:
            raise ParameterError("G: poles need numeric coefficients")
        return np.roots([complex(c) for c in self.den_coeffs()])

    # ------------------------------------------------------------ interop
    def to_control(self):
        """As a ``control.TransferFunction`` with ``dt`` kept (numbers only)."""
        from symctl.interop import tf_to_control

        return tf_to_control(self)

    @classmethod
    def from_control(cls, sys) -> DiscreteTF:
        """From a ``control.TransferFunction`` (or anything python-control converts)."""
        from symctl.interop import tf_from_control

        return tf_from_control(sys)

    # ------------------------------------------------------------ display
    def latex(self) -> str:
        """LaTeX in the paper's style: a constant factor pulled out, descending powers of z."""
        den = _descending_latex(self.den)
        if not self.is_siso:
            return rf"\frac{{1}}{{{den}}} {latex(self._num)}"
        gain, rest = sp.factor_terms(self._num[0, 0]).as_independent(z, as_Add=False)
        prefix = "" if gain == 1 else ("-" if gain == -1 else latex(gain) + " ")
        if rest == 1:
            return latex(gain) if self.den == 1 else rf"\frac{{{latex(gain)}}}{{{den}}}"
        if self.den == 1:
            return prefix + _descending_latex(rest)
        return rf"{prefix}\frac{{{_descending_latex(rest)}}}{{{den}}}"

    def __repr__(self) -> str:
        return f"DiscreteTF({self}, dt={self.dt})"

    def __str__(self) -> str:
        den = descending_str(self.den)
        if self.is_siso:
            return f"({descending_str(self._num[0, 0])})/({den})"
        rows = ", ".join(
            "[" + ", ".join(descending_str(e) for e in row) + "]" for row in self._num.tolist()
        )
        return f"[{rows}]/({den})"


def _descending(expr: sp.Expr, printer=latex, times: str = " ") -> str:
    """A polynomial in z printed with its terms in descending powers, as papers write them.

    Each term is ``sign coefficient z^k`` with a sum coefficient in parentheses:
    ``z^2 - (epsilon_1 + epsilon_3) z + epsilon_1 epsilon_3``.
    """
    poly = _poly(expr)
    if poly.is_zero:
        return "0"
    terms = []
    for (power,), coeff in poly.terms():
        coeff = sp.factor_terms(coeff)
        negative = coeff.could_extract_minus_sign()
        mag = -coeff if negative else coeff
        if power == 0:
            body = printer(mag)
        else:
            zpart = printer(z**power)
            if mag == 1:
                body = zpart
            else:
                ctext = printer(mag)
                if isinstance(mag, sp.Add):
                    ctext = rf"\left({ctext}\right)" if printer is latex else f"({ctext})"
                body = f"{ctext}{times}{zpart}"
        if terms:
            terms.append(("- " if negative else "+ ") + body)
        else:
            terms.append(("-" if negative else "") + body)
    return " ".join(terms)


def _descending_latex(expr: sp.Expr) -> str:
    return _descending(expr)


def descending_str(expr: sp.Expr) -> str:
    """Plain text of a polynomial in z in descending powers: ``'z**2 - K_1*z - K_2'``."""
    return _descending(expr, sp.sstr, "*")


def _system_of(source) -> tuple[AugmentedSystem | None, int, int, int]:
    if isinstance(source, Gains):
        source = source.system
    if isinstance(source, AugmentedSystem):
        return source, source.T, source.m, source.n
    return None, nonneg_int(source, "T"), 1, 1


def controller_tf(source, gains: Gains | None = None) -> DiscreteTF:
    r"""The optimal delayed controller :math:`G(z) = \Delta_r(z)/X(z)` in closed form.

    Parameters
    ----------
    source : int, AugmentedSystem or Gains
        An integer ``T`` gives the scalar controller with symbolic gains
        :math:`K_0 \dots K_T`; an :class:`AugmentedSystem` gives the
        (possibly MIMO) controller for its sizes and delay with symbolic gain
        blocks and the plant's ``Ts``; :class:`Gains` give the numeric controller.
    gains : Gains, optional
        Substitute these gain values.

    Returns
    -------
    DiscreteTF
        ``m x n`` (plant inputs by plant states), relative degree ``T``.

    Examples
    --------
    >>> controller_tf(3).den
    -K_1*z**2 - K_2*z - K_3 + z**3
    >>> from symctl import MuscleModel, augment, lqr_gains
    >>> G = controller_tf(lqr_gains(augment(MuscleModel(), 1, 1)))
    >>> [round(float(c), 6) for c in G.den_coeffs()]
    [1.0, 0.580041, 0.351813]
    """
    if isinstance(source, Gains) and gains is None:
        gains = source
    system, T, m, n = _system_of(source)
    blocks = gain_matrix_symbols(T, m, n)
    D = z**T * sp.eye(m)
    for k in range(1, T + 1):
        D = D - blocks[k] * z ** (T - k)
    if m == 1:
        num, den = blocks[0], D[0, 0]
    else:
        num, den = (D.adjugate() * blocks[0]).applyfunc(sp.expand), sp.expand(D.det())
    dt = system.plant.Ts if system is not None else None
    G = DiscreteTF(num, den, dt)
    if G.relative_degree != T and any(e != 0 for e in num):
        raise AssertionError(f"internal: relative degree {G.relative_degree} != T = {T}")
    if gains is not None:
        G = G.subs(gains.substitutions())
    return G


def _controller_state_space(system: AugmentedSystem):
    """``(F_c, H_c, M_c)`` of the controller, read off the augmented matrices.

    Controller state: the chain ``gamma_1 .. gamma_T`` (last block is delta_r);
    input: the plant state x; output: delta_r.
    """
    n, m, T = system.n, system.m, system.T
    blocks = gain_matrix_symbols(T, m, n)
    K_chain = sp.Matrix.hstack(*blocks[1:])
    A_c = sp.Matrix(system.A[n:, n:])
    B_c = sp.Matrix(system.B[n:, :])
    F = A_c + B_c * K_chain
    H = B_c * blocks[0]
    M = sp.zeros(m, T * m)
    M[:, (T - 1) * m :] = sp.eye(m)
    return F, H, M


def prove_controller_tf(system: AugmentedSystem, G: DiscreteTF | None = None) -> bool:
    r"""Prove that ``G`` (default: :func:`controller_tf`) is the controller of ``system``.

    With the controller's state-space matrices :math:`(F_c, H_c, M_c)` read off
    :math:`\tilde A, \tilde B` and symbolic gains, and the candidate state
    numerators :math:`W = [z^{T-1}; \dots; 1] \otimes \operatorname{adj} D(z) K_0`,
    checks the polynomial identities :math:`(zI - F_c) W = H_c \det D` and
    :math:`M_c W = N_G` exactly. Together they give :math:`M_c (zI-F_c)^{-1} H_c = G`.

    >>> from symctl import MuscleModel, augment
    >>> prove_controller_tf(augment(MuscleModel(), 2, 3))
    True
    """
    if not isinstance(system, AugmentedSystem):
        raise SymctlTypeError(f"system: expected an AugmentedSystem, got {type(system).__name__}")
    G = controller_tf(system) if G is None else G
    T = system.T
    if T == 0:
        return G.equals(gain_matrix_symbols(0, system.m, system.n)[0])
    F, H, M = _controller_state_space(system)
    N = G.num_matrix
    W = sp.Matrix.vstack(*(N * z ** (T - k) for k in range(1, T + 1)))
    lhs = (z * sp.eye(F.shape[0]) - F) * W - H * G.den
    return all(sp.expand(e) == 0 for e in lhs) and all(sp.expand(e) == 0 for e in (M * W - N))
