r"""The plant: linearization, exact zero-order-hold discretization, the muscle model.

The paper's muscle (section "Problem setup"), linearized and discretized with a zero-order
hold, gives eq. (system), :math:`\delta_f(t+1) = A \delta_f(t) + B \delta_r(t)`.
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import cache
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl import symbols as S
from symctl._util.deprecate import renamed_attribute, renamed_keywords
from symctl._util.display import LatexMixin, latex
from symctl._util.validate import (
    MAX_EXPONENT,
    MAX_MAGNITUDE,
    MAX_STATES,
    MAX_SYMBOLIC_BLOCK,
    TS_TAU_MIN,
    bounded_number,
    max_size,
    numeric_matrix,
    positive_number,
    sampling_time,
    subs_rule,
    to_matrix,
)
from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["DiscretePlant", "Linearization", "MuscleModel", "discretize", "linearize"]


@dataclass(frozen=True)
class Linearization(LatexMixin):
    r"""Jacobians of :math:`\dot x = f(x, u)` at a point: :math:`\dot{\delta x} = a\,\delta x + b\,\delta u`
    (unpacks as ``a, b``; a value).

    Attributes
    ----------
    a, b, residual : sympy.ImmutableMatrix
        :math:`\partial f/\partial x`, :math:`\partial f/\partial u` and :math:`f` at the point.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import linearize
    >>> x, u = sp.symbols("x u")
    >>> lin = linearize([-x + 2 * u], [x], [u], [2], [1])
    >>> lin.a, lin.b, lin.residual
    (Matrix([[-1]]), Matrix([[2]]), Matrix([[0]]))
    """

    a: sp.ImmutableMatrix
    b: sp.ImmutableMatrix
    residual: sp.ImmutableMatrix

    def __post_init__(self):
        for name in ("a", "b", "residual"):
            object.__setattr__(self, name, sp.ImmutableMatrix(getattr(self, name)))

    def __iter__(self):
        return iter((self.a, self.b))

    def latex(self) -> str:
        return rf"a = {latex(self.a)},\quad b = {latex(self.b)}"


def _symbol_list(value, argname: str) -> list[sp.Symbol]:
    if isinstance(value, sp.Symbol | str):
        items = [value]
    elif isinstance(value, Iterable):
        items = list(itertools.islice(value, MAX_STATES + 1))
    else:
        raise SymctlTypeError(f"{argname}: expected symbols or names, got {value!r}")
    out = []
    for item in items:
        if isinstance(item, str):
            if not item.isidentifier():
                raise ParameterError(f"{argname}: {item!r} is not a valid symbol name")
            item = sp.Symbol(item, real=True)
        if not isinstance(item, sp.Symbol):
            raise SymctlTypeError(f"{argname}: expected symbols, got {item!r}")
        out.append(item)
    if len(set(out)) != len(out):
        raise ParameterError(f"{argname}: symbols must be distinct, got {out}")
    return out


def _is_zero(expr: sp.Expr) -> bool | None:
    value = sp.cancel(sp.together(sp.expand(expr)))
    return True if value == 0 else value.is_zero


def linearize(f, x, u, x_eq, u_eq, *, check_equilibrium: bool = True) -> Linearization:
    r"""Linearize a vector ODE :math:`\dot x = f(x, u)` at :math:`(x_{eq}, u_{eq})`.

    Parameters
    ----------
    f : sequence of expressions (or one expression)
        Right-hand side; text is read by the safe parser.
    x, u : sequence of symbols (or names)
    x_eq, u_eq : sequence of values
        The operating point, maybe symbolic; refused where provably :math:`f \ne 0` when
        ``check_equilibrium``.
    check_equilibrium : bool

    Returns
    -------
    Linearization

    Raises
    ------
    DimensionError
        Sizes that do not fit; no or over 1000 states or inputs.
    ParameterError
        Invalid or repeated names; a point provably not an equilibrium.
    SymctlTypeError
        ``x`` or ``u`` holding something other than symbols or names.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import linearize
    >>> x, u = sp.symbols("x u")
    >>> a, b = linearize([-x**3 + u], [x], [u], [1], [1])
    >>> a, b
    (Matrix([[-3]]), Matrix([[1]]))
    """
    if not isinstance(check_equilibrium, bool):
        raise SymctlTypeError(f"check_equilibrium: expected a bool, got {check_equilibrium!r}")
    xs, us = _symbol_list(x, "x"), _symbol_list(u, "u")
    for syms, name in ((xs, "x"), (us, "u")):
        if not 1 <= len(syms) <= MAX_STATES:
            raise DimensionError(
                f"{name}: needs between 1 and {MAX_STATES} variables, got {len(syms)}"
            )
    names = {s.name: s for s in (*xs, *us)}
    names.update({s.name: s for s in (S.tau, S.f_max, S.r_bar, S.T_s)})
    fv = to_matrix(f if not isinstance(f, str | sp.Basic) else [f], "f", names=names)
    if fv.shape[1] != 1:
        raise DimensionError(f"f: expected a vector, got shape {fv.shape}")
    if fv.shape[0] != len(xs):
        raise DimensionError(f"f: has {fv.shape[0]} entries but x has {len(xs)} states")
    xe = to_matrix(x_eq, "x_eq", (len(xs), 1), names)
    ue = to_matrix(u_eq, "u_eq", (len(us), 1), names)
    point = dict(zip(xs + us, list(xe) + list(ue), strict=True))
    a = fv.jacobian(xs).subs(point)
    b = fv.jacobian(us).subs(point)
    residual = fv.subs(point).applyfunc(lambda e: sp.cancel(sp.together(e)))
    if check_equilibrium and any(_is_zero(e) is False for e in residual):
        raise ParameterError(
            f"x_eq, u_eq: not an equilibrium, f(x_eq, u_eq) = {list(residual)} != 0"
        )
    return Linearization(a, b, residual)


def _tidy(expr: sp.Expr) -> sp.Expr:
    """Cheap canonical form for exponential expressions: common denominator, factored."""
    return sp.factor(sp.cancel(sp.together(sp.powsimp(sp.expand(expr)))))


@renamed_keywords(Ts="dt")
def discretize(a, b, dt) -> tuple[sp.Matrix, sp.Matrix]:
    r"""Exact zero-order-hold discretization of :math:`\dot x = a x + b u`: :math:`A = e^{a T_s}`,
    :math:`B = \int_0^{T_s} e^{a s}\,ds\; b`, read off the exponential of
    :math:`[[a, b], [0, 0]] T_s`, in closed form for symbols, by :func:`scipy.linalg.expm` for numbers.

    Parameters
    ----------
    a : (n, n) matrix-like
    b : (n, m) matrix-like
    dt : number or symbol
        > 0 when a number (``Ts=``: deprecated).

    Returns
    -------
    (sympy.Matrix, sympy.Matrix)

    Raises
    ------
    DimensionError
        Shapes that do not fit, over 1000 states, or symbols with over 3 states plus inputs.
    ParameterError
        A numeric ``dt <= 0``, non-finite entries, an overflowing :math:`e^{a\,dt}`.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import discretize
    >>> from symctl.symbols import tau, T_s
    >>> A, B = discretize(-1 / tau, 1 / tau, T_s)
    >>> A[0, 0], sp.simplify(B[0, 0] - (1 - sp.exp(-T_s / tau)))
    (exp(-T_s/tau), 0)
    """
    max_size(a, "a", MAX_STATES)
    max_size(b, "b", MAX_STATES)
    am = to_matrix(a, "a")
    n = am.shape[0]
    if am.shape != (n, n) or n == 0:
        raise DimensionError(f"a: must be square and non-empty, got shape {am.shape}")
    if n > MAX_STATES:
        raise DimensionError(f"a: at most {MAX_STATES} states, got {n}")
    bm = to_matrix(b, "b")
    if bm.shape[0] != n:
        raise DimensionError(f"b: must have {n} rows like a, got shape {bm.shape}")
    ts = sampling_time(dt, "dt")
    m = bm.shape[1]
    block = sp.zeros(n + m, n + m)
    block[:n, :n] = am
    block[:n, n:] = bm
    if block.free_symbols or ts.free_symbols:
        if n + m > MAX_SYMBOLIC_BLOCK:
            raise DimensionError(
                f"a, b: a symbolic discretization takes at most {MAX_SYMBOLIC_BLOCK} states "
                f"plus inputs (SymPy's matrix exponential), got {n} + {m}; substitute numbers first"
            )
        phi = (block * ts).exp().applyfunc(_tidy)
    else:
        from scipy.linalg import expm

        phi = sp.Matrix(_expm(numeric_matrix(block * ts, "a, b"), expm))
    return phi[:n, :n], phi[:n, n:]


def _expm(block: np.ndarray, expm) -> np.ndarray:
    """``expm(block)``, refusing an overflow."""
    with np.errstate(over="ignore", invalid="ignore"):
        phi = expm(block)
    if not np.all(np.isfinite(phi)):
        raise ParameterError(
            "a, dt: exp(a dt) overflows (largest |a dt| entry "
            f"{float(np.max(np.abs(block))):g}); use a shorter dt or rescale a"
        )
    return phi


@dataclass(frozen=True)
class DiscretePlant(LatexMixin):
    r"""A discrete-time linear plant :math:`x(t+1) = A x(t) + B u(t)` (a value, ``params`` aside;
    ``Ts``: deprecated name of ``dt``).

    Parameters
    ----------
    A : (n, n) matrix-like
    B : (n, m) matrix-like
    dt : number, symbol or None
        > 0 when a number.
    state_names, input_names : tuple of str, optional
        Default ``x`` (``x_1, x_2, ...``) and ``u``.
    x_eq, u_eq : matrix-like, optional
        The operating point of a linearized plant.
    params : mapping, optional
        The model parameters it came from (read-only).

    Raises
    ------
    DimensionError
        Shapes or name counts that do not fit.
    ParameterError
        A numeric ``dt <= 0``.

    Examples
    --------
    >>> from symctl import DiscretePlant
    >>> p = DiscretePlant([[1, 1], [0, 1]], [[0], [1]], dt=0.1)
    >>> p.n, p.m
    (2, 1)
    """

    A: sp.Matrix
    B: sp.Matrix
    dt: sp.Expr | None = None
    state_names: tuple[str, ...] = ()
    input_names: tuple[str, ...] = ()
    x_eq: sp.Matrix | None = None
    u_eq: sp.Matrix | None = None
    params: Mapping = field(default_factory=dict, compare=False)

    def __post_init__(self):
        A = to_matrix(self.A, "A")
        if A.shape[0] != A.shape[1] or A.shape[0] == 0:
            raise DimensionError(f"A: must be square and non-empty, got shape {A.shape}")
        B = to_matrix(self.B, "B")
        if B.shape[0] != A.shape[0] or B.shape[1] == 0:
            raise DimensionError(f"B: must have {A.shape[0]} rows like A, got shape {B.shape}")
        object.__setattr__(self, "A", sp.ImmutableMatrix(A))
        object.__setattr__(self, "B", sp.ImmutableMatrix(B))
        for name in ("x_eq", "u_eq"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, sp.ImmutableMatrix(to_matrix(value, name)))
        object.__setattr__(self, "params", MappingProxyType(dict(self.params)))
        if self.dt is not None:
            object.__setattr__(self, "dt", sampling_time(self.dt, "dt"))
        n, m = A.shape[0], B.shape[1]
        object.__setattr__(self, "state_names", tuple(self.state_names) or _names("x", n))
        object.__setattr__(self, "input_names", tuple(self.input_names) or _names("u", m))
        if len(self.state_names) != n or len(self.input_names) != m:
            raise DimensionError(
                f"state_names/input_names: need {n} and {m} names, got "
                f"{len(self.state_names)} and {len(self.input_names)}"
            )

    @property
    def n(self) -> int:
        return self.A.shape[0]

    @property
    def m(self) -> int:
        return self.B.shape[1]

    def subs(self, *args, **kwargs) -> DiscretePlant:
        """A new plant with symbols substituted (as :meth:`sympy.Basic.subs`)."""
        parts = {k: getattr(self, k) for k in ("A", "B", "dt", "x_eq", "u_eq")}
        parts = {k: m for k, m in parts.items() if m is not None}
        rule, flags = subs_rule(
            args, kwargs, set().union(*(m.free_symbols for m in parts.values()))
        )
        return dataclasses.replace(self, **{k: m.subs(rule, **flags) for k, m in parts.items()})

    def numeric(self) -> tuple[np.ndarray, np.ndarray]:
        """``(A, B)`` as float arrays; refuses free symbols."""
        return numeric_matrix(self.A, "A"), numeric_matrix(self.B, "B")

    def to_control(self):
        """The plant as a discrete ``control.StateSpace`` with full-state output."""
        import control

        A, B = self.numeric()
        dt = True if self.dt is None else float(self.dt)
        return control.ss(A, B, np.eye(self.n), np.zeros((self.n, self.m)), dt)

    def latex(self) -> str:
        return rf"A = {latex(self.A)},\quad B = {latex(self.B)}"

    Ts = renamed_attribute("Ts", "dt")


DiscretePlant.__init__ = renamed_keywords(Ts="dt")(DiscretePlant.__init__)


def _names(stem: str, count: int) -> tuple[str, ...]:
    return (stem,) if count == 1 else tuple(f"{stem}_{i + 1}" for i in range(count))


def _muscle_ode() -> sp.Expr:
    return S.f_max / (S.tau * (1 + sp.exp(-S.r))) - S.f / S.tau


def _muscle_f_bar() -> sp.Expr:
    return S.f_max / (1 + sp.exp(-S.r_bar))


@cache
def _muscle_linearization() -> Linearization:
    lin = linearize(_muscle_ode(), [S.f], [S.r], [_muscle_f_bar()], [S.r_bar])
    return Linearization(lin.a.applyfunc(_tidy), lin.b.applyfunc(_tidy), lin.residual)


@cache
def _muscle_discrete() -> DiscretePlant:
    a, b = _muscle_linearization()
    A, B = discretize(a, b, S.T_s)
    return DiscretePlant(
        A, B, S.T_s, ("delta_f",), ("delta_r",), sp.Matrix([_muscle_f_bar()]), sp.Matrix([S.r_bar])
    )


@dataclass(frozen=True)
class MuscleModel(LatexMixin):
    r"""The paper's muscle, :math:`\dot f = f_\text{max}/(\tau(1+e^{-r})) - f/\tau`, linearized
    about :math:`\bar f = f_\text{max}/(1+e^{-\bar r})`, exact until :meth:`plant` (``Ts``: ``dt``).

    Parameters
    ----------
    tau : float
        Muscle time constant [s] (the paper's 0.02).
    f_max : float
        Maximum force [N] (60).
    r_bar : float
        Equilibrium firing rate [spikes/s] (1).
    dt : float
        Sampling time [s] (0.01).

    Raises
    ------
    ParameterError, SymctlTypeError
        ``tau``, ``f_max``, ``dt`` outside ``[1e-100, 1e100]``, :math:`|\bar r| > 700`,
        :math:`T_s/\tau` outside :math:`[10^{-6}, 700]`; a parameter not a real number.

    Examples
    --------
    >>> from symctl import MuscleModel
    >>> MuscleModel().plant().A
    Matrix([[exp(-1/2)]])
    """

    tau: float = 0.02
    f_max: float = 60.0
    r_bar: float = 1.0
    dt: float = 0.01

    def __post_init__(self):
        for name in ("tau", "f_max", "dt"):
            positive_number(getattr(self, name), name)
            bounded_number(getattr(self, name), name, 1 / MAX_MAGNITUDE, MAX_MAGNITUDE)
        bounded_number(self.r_bar, "r_bar", -MAX_EXPONENT, MAX_EXPONENT)
        ratio = float(self.dt) / float(self.tau)
        if not TS_TAU_MIN <= ratio <= MAX_EXPONENT:
            raise ParameterError(
                f"dt, tau: dt/tau must be in [{TS_TAU_MIN:g}, {MAX_EXPONENT:g}] "
                f"(exp(-dt/tau) is the plant's A), got dt/tau = {self.dt!r}/{self.tau!r} = {ratio:g}"
            )

    @property
    def ode(self) -> sp.Expr:
        return _muscle_ode()

    @property
    def f_bar_symbolic(self) -> sp.Expr:
        return _muscle_f_bar()

    @property
    def values(self) -> dict[sp.Symbol, sp.Expr]:
        """The parameter values as exact numbers, keyed by the paper's symbols."""
        values = (self.tau, self.f_max, self.r_bar, self.dt)
        symbols = (S.tau, S.f_max, S.r_bar, S.T_s)
        return {s: sp.nsimplify(v, rational=True) for s, v in zip(symbols, values, strict=True)}

    @property
    def f_bar(self) -> float:
        """Equilibrium force in newtons (a float)."""
        return float(self.f_bar_symbolic.subs(self.values))

    def linearize_symbolic(self) -> Linearization:
        r""":math:`a = -1/\tau`, :math:`b = f_\text{max} e^{-\bar r}/(\tau(1+e^{-\bar r})^2)`."""
        return _muscle_linearization()

    def discrete_symbolic(self) -> DiscretePlant:
        return _muscle_discrete()

    def plant(self) -> DiscretePlant:
        """The discrete plant at this model's numbers (exact)."""
        return dataclasses.replace(
            self.discrete_symbolic().subs(self.values), params=self.as_dict()
        )

    def as_dict(self) -> dict[str, float]:
        return {"tau": self.tau, "f_max": self.f_max, "r_bar": self.r_bar, "Ts": self.dt}

    def rhs(self, f: np.ndarray, r: np.ndarray) -> np.ndarray:
        """The nonlinear ODE's right-hand side, with NumPy."""
        return self.f_max / (self.tau * (1 + np.exp(-r))) - f / self.tau

    def latex(self) -> str:
        return rf"\frac{{df}}{{dt}} = {latex(self.ode)}"

    Ts = renamed_attribute("Ts", "dt")


MuscleModel.__init__ = renamed_keywords(Ts="dt")(MuscleModel.__init__)
