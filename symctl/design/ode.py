r"""A nonlinear plant of your own: :math:`\dot x = f(x, u; p)`, its equilibrium, linearization and ZOH.

:class:`ODEModel` generalizes :class:`~symctl.design.plant.MuscleModel` to any states, inputs
and named parameters, symbolic until :meth:`ODEModel.plant` substitutes them exactly.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl import symbols as S
from symctl._util.deprecate import renamed_attribute, renamed_keywords
from symctl._util.display import LatexMixin, latex
from symctl._util.pickling import CachedState
from symctl._util.validate import MAX_MAGNITUDE, bounded_number, sampling_time, to_matrix
from symctl.design.plant import DiscretePlant, Linearization, _tidy, discretize, linearize
from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["MAX_MODEL_STATES", "ODEModel", "exact_value", "parameter_symbol", "solve_equilibrium"]

MAX_MODEL_STATES = 20
"""Most states (and most inputs) of an :class:`ODEModel`: the Jacobians are symbolic."""
ROOT_STARTS = 12  # of the numeric equilibrium search without a guess
ROOT_TOL = 1e-9  # residual, relative to the scale of f, of a numeric equilibrium


def exact_value(value, argname: str) -> sp.Expr:
    """A parameter value as an exact SymPy number: a float as its shortest decimal's rational
    (0.1 -> 1/10); refuses non-finite values and ``|value| > 1e100``."""
    if isinstance(value, sp.Basic):
        if not (value.is_number and value.is_real and value.is_finite):
            raise ParameterError(f"{argname}: expected a finite real number, got {value}")
        return value
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise SymctlTypeError(f"{argname}: expected a number, got {type(value).__name__}")
    bounded_number(value, argname, -MAX_MAGNITUDE, MAX_MAGNITUDE)
    if isinstance(value, int | np.integer):
        return sp.Integer(int(value))
    q = Fraction(repr(float(value)))  # the shortest decimal that reads back as this float
    return sp.Rational(q.numerator, q.denominator)


def parameter_symbol(name: str, value) -> sp.Symbol:
    """The symbol of a parameter: positive when its value is (closed forms simplify), else real."""
    return sp.Symbol(name, positive=True) if value > 0 else sp.Symbol(name, real=True)


def _symbols(values, argname: str) -> tuple[sp.Symbol, ...]:
    if isinstance(values, sp.Symbol) or not isinstance(values, Sequence):
        raise SymctlTypeError(f"{argname}: expected a sequence of symbols, got {values!r}")
    out = tuple(values)
    if not 1 <= len(out) <= MAX_MODEL_STATES:
        raise DimensionError(f"{argname}: needs 1 to {MAX_MODEL_STATES} symbols, got {len(out)}")
    if not all(isinstance(s, sp.Symbol) for s in out):
        raise SymctlTypeError(f"{argname}: expected symbols, got {out}")
    return out


def _vector(values, n: int, argname: str, names: dict) -> sp.ImmutableMatrix:
    """``n`` SymPy values or numbers naming only ``names`` (text is refused)."""
    if isinstance(values, str) or not isinstance(values, Sequence | sp.MatrixBase):
        raise SymctlTypeError(f"{argname}: expected a sequence of {n} expressions, got {values!r}")
    items = list(values)
    if len(items) != n:
        raise DimensionError(f"{argname}: needs {n} entries, got {len(items)}")
    out = []
    for i, item in enumerate(items):
        if isinstance(item, str):
            raise SymctlTypeError(
                f"{argname}[{i}]: text is read by model files (symctl.load_model) or "
                "symctl._util.parse.parse_expr; give a SymPy expression or a number"
            )
        value = exact_value(item, f"{argname}[{i}]") if not isinstance(item, sp.Basic) else item
        unknown = value.free_symbols - set(names.values())
        if unknown:
            raise ParameterError(
                f"{argname}[{i}]: names {sorted(map(str, unknown))}, which is not a state, "
                "input or parameter"
            )
        out.append(value)
    return sp.ImmutableMatrix(out)


SYMBOLIC_MAX_DENOMINATOR = 10_000  # of a rational in a for a closed-form ZOH (factor hangs)


def _small_rationals(M: sp.MatrixBase) -> bool:
    """Whether every rational in ``M`` has a numerator and denominator below the limit."""
    limit = SYMBOLIC_MAX_DENOMINATOR
    return all(abs(q.q) <= limit and abs(q.p) <= limit**2 for e in M for q in e.atoms(sp.Rational))


def _affine(rhs: sp.MatrixBase, states) -> bool:
    """Whether every entry of ``rhs`` is affine in ``states`` (its Hessian is zero)."""
    J = rhs.jacobian(list(states))
    return all(sp.expand(sp.diff(e, x)) == 0 for e in J for x in states)


def solve_equilibrium(
    rhs, states, inputs, u_eq, values: Mapping, *, guess=None, argname: str = "equilibrium"
) -> tuple[sp.ImmutableMatrix, str]:
    r"""``(x_eq, method)``: the states with :math:`f(\bar x, \bar u) = 0` (``values`` the
    parameters'), exactly when :math:`f` is affine in the states, by exact real-root isolation
    for one polynomial state (degree up to 12), else numerically from ``guess`` or seeded
    starts; a ParameterError naming ``argname`` when there is none, or several."""
    states, inputs = list(_symbols(states, "states")), list(_symbols(inputs, "inputs"))
    if not isinstance(values, Mapping) or not all(isinstance(k, sp.Symbol) for k in values):
        raise SymctlTypeError("values: expected a mapping of symbols to numbers")
    values = {k: exact_value(v, f"values[{k}]") for k, v in values.items()}
    names = {s.name: s for s in (*states, *inputs, *values)}
    rhs = to_matrix(rhs, "rhs", (len(states), 1), names)
    u_eq = to_matrix(u_eq, "u_eq", (len(inputs), 1), {s.name: s for s in values})
    f = rhs.subs(dict(zip(inputs, u_eq, strict=True)))
    if _affine(f, states):
        J = f.jacobian(states)
        c = f.subs({x: 0 for x in states})
        Jn = np.array(J.subs(values).evalf(), dtype=float)
        if np.linalg.matrix_rank(Jn) < len(states):
            raise ParameterError(
                f"{argname}: f is affine in the states with a singular Jacobian, so the "
                "equilibrium is not unique (or does not exist); give the states' equilibrium values"
            )
        x = J.LUsolve(-c).applyfunc(_tidy)
        return sp.ImmutableMatrix(x), "exact (affine in the states)"
    if len(states) == 1 and guess is None:
        found = _polynomial_equilibrium(f[0].subs(values), states[0], argname)
        if found is not None:
            return found
    return _numeric_equilibrium(f, states, values, guess, argname)


MAX_EXACT_DEGREE = 12  # of a one-state polynomial equilibrium found exactly


def _polynomial_equilibrium(f: sp.Expr, x: sp.Symbol, argname: str):
    """The unique real root of a polynomial f(x), exactly isolated; None if f is not one."""
    num, den = sp.fraction(sp.cancel(sp.together(f)))  # no common factor: num's roots are f's
    try:
        poly = sp.Poly(num, x, domain="QQ")
        sp.Poly(den, x, domain="QQ")  # a rational function of x with rational coefficients
    except (sp.PolynomialError, sp.polys.polyerrors.CoercionFailed, ValueError):
        return None
    if not 2 <= poly.degree() <= MAX_EXACT_DEGREE:
        return None
    roots = sorted(set(poly.real_roots()), key=float)
    if not roots:
        raise ParameterError(
            f"{argname}: no equilibrium: f is a polynomial of degree {poly.degree()} in "
            f"{x} with no real root (exact, SymPy real_roots)"
        )
    if len(roots) > 1:
        shown = ", ".join(f"{x} = {float(r):.6g}" for r in roots[:4])
        raise ParameterError(
            f"{argname}: several equilibria ({shown}{', ...' if len(roots) > 4 else ''}; "
            "exact, SymPy real_roots); give the state's equilibrium value or a guess"
        )
    root = roots[0]
    if root.is_Rational:
        return sp.ImmutableMatrix([root]), "exact (the one real root of a polynomial)"
    value = exact_value(float(root), argname)
    return sp.ImmutableMatrix([value]), (
        "exact count (the one real root of a polynomial, SymPy real_roots), its value to "
        "double precision"
    )


def _numeric_equilibrium(f, states, values, guess, argname):
    import scipy.optimize

    fn = sp.lambdify([states], list(f.subs(values)), modules="numpy")
    jac = sp.lambdify([states], f.subs(values).jacobian(states), modules="numpy")
    n = len(states)

    def residual(x):
        return np.asarray(fn(x), dtype=float)

    def jacobian(x):
        return np.asarray(jac(x), dtype=float)

    if guess is not None:
        starts = [np.asarray(guess, dtype=float)]
    else:
        gen = np.random.default_rng(0)
        scales = [1.0] * 6 + [10.0] * (ROOT_STARTS - 7)  # near the origin, then farther
        starts = [np.zeros(n)] + [gen.normal(scale=s, size=n) for s in scales]
    found: list[np.ndarray] = []
    with np.errstate(all="ignore"):
        for x0 in starts:
            try:
                sol = scipy.optimize.root(residual, x0, jac=jacobian, method="hybr")
            except (ValueError, ArithmeticError):
                continue
            if not np.all(np.isfinite(sol.x)):
                continue
            scale = 1.0 + float(np.max(np.abs(residual(x0)))) if np.all(np.isfinite(x0)) else 1.0
            if float(np.max(np.abs(residual(sol.x)))) > ROOT_TOL * scale:
                continue
            if not any(np.allclose(sol.x, y, rtol=1e-6, atol=1e-9) for y in found):
                found.append(sol.x)
    if not found:
        where = "from the guess" if guess is not None else f"from {len(starts)} starts"
        raise ParameterError(
            f"{argname}: no equilibrium found {where} (scipy.optimize.root); give the states' "
            "equilibrium values or a guess"
        )
    if len(found) > 1:
        shown = "; ".join(
            ", ".join(f"{s} = {v:.6g}" for s, v in zip(states, x, strict=True)) for x in found[:3]
        )
        raise ParameterError(
            f"{argname}: several equilibria ({shown}{'; ...' if len(found) > 3 else ''}); "
            "give the states' equilibrium values or a guess"
        )
    how = "numeric (scipy.optimize.root from " + (
        "the guess)" if guess is not None else f"{len(starts)} starts, one solution)"
    )
    return sp.ImmutableMatrix([exact_value(float(v), argname) for v in found[0]]), how


@dataclass(frozen=True, eq=False)
class ODEModel(CachedState, LatexMixin):
    r"""A continuous-time nonlinear plant :math:`\dot x = f(x, u; p)` with an operating point,
    symbolic until :meth:`plant` substitutes the parameters exactly.

    Parameters
    ----------
    states, inputs : sequence of sympy.Symbol
        1 to ``MAX_MODEL_STATES`` (20) each.
    rhs : sequence of sympy expressions
        :math:`f`, one entry per state.
    params : mapping of sympy.Symbol to number
        Every parameter with its value (kept exact, :func:`exact_value`).
    x_eq, u_eq : sequence, optional
        The operating point; ``x_eq`` solved (:func:`solve_equilibrium`) when omitted,
        ``u_eq`` 0 by default.
    dt : float
        The sampling time [s], > 0 (``Ts``: deprecated).
    guess : sequence of float, optional
        Start of the numeric equilibrium search.
    name : str
    units : mapping of str to str, optional
        Units of the states, inputs and parameters by name.

    Attributes
    ----------
    equilibrium_method : str
        ``"given"``, or how :func:`solve_equilibrium` found ``x_eq``.

    Raises
    ------
    ParameterError
        Not an equilibrium (to 1e-9 of the scale), unknown names, no or several equilibria.
    DimensionError, SymctlTypeError
        Sizes or types that do not fit.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl.design.ode import ODEModel
    >>> th, w, u = sp.symbols("theta omega u", real=True)
    >>> g = sp.Symbol("g", positive=True)
    >>> m = ODEModel([th, w], [u], [w, g * sp.sin(th) + u], {g: 9.81}, x_eq=[0, 0], dt=0.01)
    >>> m.linearize_symbolic().a.tolist()
    [[0, 1], [g, 0]]
    >>> round(float(m.plant().A[1, 0]), 6)
    0.098116
    """

    states: tuple
    inputs: tuple
    rhs: sp.ImmutableMatrix
    params: Mapping
    x_eq: sp.ImmutableMatrix | None = None
    u_eq: sp.ImmutableMatrix | None = None
    dt: float = 0.01
    guess: tuple | None = None
    name: str = "model"
    units: Mapping = field(default_factory=dict)
    equilibrium_method: str = field(default="given", init=False)

    def __post_init__(self) -> None:
        states, inputs = _symbols(self.states, "states"), _symbols(self.inputs, "inputs")
        if len(set(states + inputs)) != len(states) + len(inputs):
            raise ParameterError("states, inputs: names must be distinct")
        if not isinstance(self.params, Mapping):
            raise SymctlTypeError(f"params: expected a mapping, got {type(self.params).__name__}")
        params = {}
        for k, v in self.params.items():
            if not isinstance(k, sp.Symbol):
                raise SymctlTypeError(f"params: keys must be symbols, got {k!r}")
            params[k] = exact_value(v, f"params[{k}]")
        if set(params) & set(states + inputs):
            raise ParameterError("params: a parameter has the name of a state or an input")
        names = {s.name: s for s in (*states, *inputs, *params)}
        pnames = {s.name: s for s in params}
        rhs = _vector(self.rhs, len(states), "rhs", names)
        u_eq = (
            sp.ImmutableMatrix.zeros(len(inputs), 1)
            if self.u_eq is None
            else _vector(self.u_eq, len(inputs), "u_eq", pnames)
        )
        ts = sampling_time(exact_value(self.dt, "dt"), "dt")
        object.__setattr__(self, "states", states)
        object.__setattr__(self, "inputs", inputs)
        object.__setattr__(self, "params", MappingProxyType(params))
        object.__setattr__(self, "rhs", rhs)
        object.__setattr__(self, "u_eq", u_eq)
        object.__setattr__(self, "dt", float(ts))
        object.__setattr__(self, "units", MappingProxyType(dict(self.units)))
        if self.guess is not None:
            object.__setattr__(self, "guess", tuple(float(g) for g in self.guess))
        if self.x_eq is None:
            x_eq, how = solve_equilibrium(
                rhs, states, inputs, u_eq, self.values, guess=self.guess, argname="x_eq"
            )
            object.__setattr__(self, "equilibrium_method", how)
        else:
            x_eq = _vector(self.x_eq, len(states), "x_eq", pnames)
        object.__setattr__(self, "x_eq", x_eq)
        self._check_equilibrium()

    def _check_equilibrium(self) -> None:
        point = dict(zip(self.states + self.inputs, [*self.x_eq, *self.u_eq], strict=True))
        residual = self.rhs.subs(point).subs(self.values)
        values = np.array([complex(sp.N(e, 30)) for e in residual])
        terms = [t for e in residual for t in sp.Add.make_args(sp.expand(e))]
        scale = 1.0 + max(abs(complex(sp.N(t, 30))) for t in terms)
        if np.max(np.abs(values)) > 1e-9 * scale:
            shown = ", ".join(f"{v.real:.4g}" for v in values)
            raise ParameterError(
                f"x_eq, u_eq: not an equilibrium, f(x_eq, u_eq) = [{shown}] != 0 at the "
                "parameter values"
            )

    @property
    def n(self) -> int:
        """Number of states."""
        return len(self.states)

    @property
    def m(self) -> int:
        """Number of inputs."""
        return len(self.inputs)

    @property
    def values(self) -> dict:
        """The exact values of the parameters and of :math:`T_s` (``symctl.symbols.T_s``)."""
        return {**self.params, S.T_s: exact_value(self.dt, "dt")}

    @cached_property
    def _linearization(self) -> Linearization:
        lin = linearize(
            list(self.rhs),
            list(self.states),
            list(self.inputs),
            list(self.x_eq),
            list(self.u_eq),
            check_equilibrium=False,
        )
        return Linearization(lin.a.applyfunc(_tidy), lin.b.applyfunc(_tidy), lin.residual)

    def linearize_symbolic(self) -> Linearization:
        """The Jacobians at the operating point."""
        return self._linearization

    @cached_property
    def _discrete(self) -> DiscretePlant | None:
        if self.n != 1 or self.m != 1:
            return None
        a, b = self._linearization
        if not _small_rationals(a) or not _small_rationals(b):
            return None  # e^{a T_s} with a rational of a large denominator: SymPy's factor hangs
        A, B = discretize(a, b, S.T_s)
        return self._plant(A, B, S.T_s, self.x_eq, self.u_eq)

    def discrete_symbolic(self) -> DiscretePlant | None:
        """The closed-form ZOH plant in symbols for one state and one input, else None."""
        return self._discrete

    def _plant(self, A, B, Ts, x_eq, u_eq) -> DiscretePlant:
        return DiscretePlant(
            A,
            B,
            Ts,
            tuple(f"delta_{s.name}" for s in self.states),
            tuple(f"delta_{s.name}" for s in self.inputs),
            x_eq,
            u_eq,
            {str(k): float(v) for k, v in self.values.items()},
        )

    @classmethod
    def from_muscle(cls, muscle) -> ODEModel:
        """The paper's muscle (a :class:`~symctl.design.plant.MuscleModel`) as an ODEModel, in the
        symbols a model file gives.

        >>> from symctl import MuscleModel
        >>> from symctl.design.ode import ODEModel
        >>> m = ODEModel.from_muscle(MuscleModel())
        >>> m.plant().A == MuscleModel().plant().A, round(float(m.x_bar[0]), 4)
        (True, 43.8635)
        """
        names = ("tau", "f_max", "r_bar")
        params = {parameter_symbol(k, getattr(muscle, k)): getattr(muscle, k) for k in names}
        rename = dict(zip((S.tau, S.f_max, S.r_bar), params, strict=True))
        return cls(
            [S.f],
            [S.r],
            [muscle.ode.xreplace(rename)],
            params,
            [muscle.f_bar_symbolic.xreplace(rename)],
            [rename[S.r_bar]],
            muscle.dt,
            name="muscle",
            units={"tau": "s", "f_max": "N", "r_bar": "spikes/s", "f": "N", "r": "spikes/s"},
        )

    @cached_property
    def _numeric_plant(self) -> DiscretePlant:
        values = self.values
        if self._discrete is not None:
            p = self._discrete.subs(values)
            return self._plant(p.A, p.B, p.dt, p.x_eq, p.u_eq)
        a, b = self._linearization
        A, B = discretize(a.subs(values).evalf(), b.subs(values).evalf(), self.dt)
        return self._plant(A, B, self.dt, self.x_eq.subs(values), self.u_eq.subs(values))

    def plant(self) -> DiscretePlant:
        """The discrete linear plant at the parameter values (exact for one state)."""
        return self._numeric_plant

    @property
    def x_bar(self) -> np.ndarray:
        """The equilibrium states as floats."""
        return np.array([float(sp.N(e.subs(self.values), 17)) for e in self.x_eq])

    @property
    def u_bar(self) -> np.ndarray:
        """The equilibrium inputs as floats."""
        return np.array([float(sp.N(e.subs(self.values), 17)) for e in self.u_eq])

    @cached_property
    def _rhs_numeric(self):
        f = self.rhs.subs(self.values)
        fn = sp.lambdify([self.states, self.inputs], list(f), modules="numpy")
        jac = sp.lambdify([self.states, self.inputs], f.jacobian(list(self.states)), "numpy")
        return fn, jac

    def rhs_numeric(self, x: np.ndarray, u: np.ndarray) -> np.ndarray:
        """:math:`f(x, u)` with NumPy; ``x`` is ``(n, k)``, ``u`` is ``(m, k)`` for ``k`` points."""
        fn, _ = self._rhs_numeric
        out = fn(list(x), list(u))
        return np.array([np.broadcast_to(np.asarray(v, dtype=float), x.shape[1:]) for v in out])

    def jacobian_numeric(self, x: np.ndarray, u: np.ndarray) -> np.ndarray:
        r""":math:`\partial f/\partial x` at one point (``x`` of length n, ``u`` of length m)."""
        _, jac = self._rhs_numeric
        return np.asarray(jac(list(x), list(u)), dtype=float)

    def as_dict(self) -> dict[str, float]:
        """The parameters and ``Ts`` as plain floats, in order (for JSON)."""
        return {**{str(k): float(v) for k, v in self.params.items()}, "Ts": self.dt}

    def __eq__(self, other) -> bool:
        if not isinstance(other, ODEModel):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def _key(self) -> tuple:
        return (
            self.states,
            self.inputs,
            self.rhs,
            tuple(self.params.items()),
            self.x_eq,
            self.u_eq,
            self.dt,
            self.name,
        )

    def latex(self) -> str:
        rows = [
            rf"\frac{{d{latex(x)}}}{{dt}} &= {latex(f)}"
            for x, f in zip(self.states, self.rhs, strict=True)
        ]
        return r"\begin{aligned}" + r" \\ ".join(rows) + r"\end{aligned}"

    Ts = renamed_attribute("Ts", "dt")


ODEModel.__init__ = renamed_keywords(Ts="dt")(ODEModel.__init__)
