"""The linear controller around the nonlinear plant it was designed from: how far the loop
departs from the linear prediction, and the longest net delay it still brings back."""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
import scipy.integrate
import scipy.linalg

from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import MAX_COUNT, bounded_int, bounded_number, float_array
from symctl.design.augment import augment
from symctl.design.lqr import Gains, lqr_gains
from symctl.design.ode import ODEModel
from symctl.design.plant import MuscleModel
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.neural.simulate import (
    DEFAULT_LENGTH,
    DEFAULT_START,
    DEFAULT_STEPS,
    _freeze,
    _numeric_realization,
    simulate_realization,
)
from symctl.proof import Verdict
from symctl.realization.realization import Realization
from symctl.realization.realizers import ifp_realization

__all__ = ["DelaySearch", "NonlinearCheck", "longest_delay", "nonlinear_check"]

MAX_STEPS = 5000  # longest horizon (one ODE solve per sample: about 10 s at 5000)
RTOL_RANGE = (1e-13, 1e-2)  # admissible rtol of the ODE solver (SciPy refuses below 2.2e-14)
RETURN_TOLERANCE = 0.01  # returned: every state ends within this fraction of its linear peak
STIFF_RATIO = 1.0  # Ts max|eigenvalue| above which the ODE is solved with Radau (implicit)


@dataclass(frozen=True, eq=False)
class NonlinearCheck(ArrayValue, Verdict):
    r"""The linear controller around the nonlinear plant, against the linear prediction
    (:func:`nonlinear_check`); read-only. Truthy when the loop returned at every amplitude
    (every :attr:`final_deviation`, the ``evidence``, at most 1 %).

    Attributes
    ----------
    amplitudes : (k,) array
        Disturbance pulse amplitudes (in the disturbed states' units per step).
    t : (steps,) array
        Time [s].
    x_linear, x_nonlinear : (k, steps, n) arrays
        Absolute states of the linear model and of the nonlinear ODE.
    u_nonlinear : (k, steps, m) array
        Absolute inputs driving the nonlinear plant.
    max_deviation : (k,) array
        :math:`\max_t |x_1^\text{nonlinear} - x_1^\text{linear}|`, the first state's.
    relative_deviation, final_deviation : (k,) arrays
        The worst state's :math:`\max_t |x_i^\text{nonlinear} - x_i^\text{linear}|`, and its
        :math:`|x_i^\text{nonlinear}(t_\text{end}) - \bar x_i|` (inf: the ODE failed), over
        its linear peak :math:`\max_t |\delta x_i^\text{linear}|`.
    state_names, input_names, units : tuple of str
        The plant's names (the muscle's ``f``, ``r``) and the states' units (``"N"``).

    Examples
    --------
    >>> from symctl import nonlinear_check
    >>> chk = nonlinear_check(amplitudes=[0.1, 1.0], steps=20)
    >>> chk.f_nonlinear.shape, bool(chk.max_deviation[1] > chk.max_deviation[0])
    ((2, 20), True)
    >>> print(chk.table().splitlines()[0])
     amplitude | peak |δf| linear [N] | max |f_nl - f_lin| [N] | relative
    """

    amplitudes: np.ndarray
    t: np.ndarray
    x_linear: np.ndarray
    x_nonlinear: np.ndarray
    u_nonlinear: np.ndarray
    max_deviation: np.ndarray
    relative_deviation: np.ndarray
    final_deviation: np.ndarray
    state_names: tuple = ("f",)
    input_names: tuple = ("r",)
    units: tuple = ("N",)

    method = "the nonlinear ODE integrated with scipy.integrate.solve_ivp beside the linear loop"

    @property
    def verdict(self) -> bool:
        """Whether every :attr:`final_deviation` is at most ``RETURN_TOLERANCE`` (1 %)."""
        return bool(np.all(self.final_deviation <= RETURN_TOLERANCE))

    @property
    def evidence(self) -> np.ndarray:
        return self.final_deviation

    def __post_init__(self) -> None:  # the arrays are read-only copies
        _freeze(self, [field.name for field in fields(self)[:8]])

    @property
    def f_linear(self) -> np.ndarray:
        """The first state of the linear model, ``(k, steps)``."""
        return self.x_linear[:, :, 0]

    @property
    def f_nonlinear(self) -> np.ndarray:
        """The first state of the nonlinear plant, ``(k, steps)``."""
        return self.x_nonlinear[:, :, 0]

    @property
    def r_nonlinear(self) -> np.ndarray:
        """The first input driving the nonlinear plant, ``(k, steps)``."""
        return self.u_nonlinear[:, :, 0]

    def table(self) -> str:
        """A plain-text table: amplitude, peak linear change, max and relative deviation."""
        x0, unit = self.state_names[0], self.units[0] if self.units else ""
        u = f" [{unit}]" if unit else ""
        first = self.x_linear[:, :, 0]
        peak = np.max(np.abs(first - first[:, :1]), axis=1)  # x(0) = x_bar
        lines = [
            f" amplitude | peak |δ{x0}| linear{u} | max |{x0}_nl - {x0}_lin|{u} | relative",
            "-" * 78,
        ]
        for a, pk, d, rel in zip(
            self.amplitudes, peak, self.max_deviation, self.relative_deviation, strict=True
        ):
            lines.append(f" {a:9.4g} | {pk:20.4g} | {d:22.4g} | {rel:8.2e}")
        return "\n".join(lines)

    def plot(self):
        """State traces and the deviation against amplitude: a Figure."""
        from symctl.plotting.response import nonlinear_plot

        return nonlinear_plot(self)


def _as_ode(model) -> ODEModel:
    if model is None:
        model = MuscleModel()
    if isinstance(model, MuscleModel):
        return ODEModel.from_muscle(model)
    if not isinstance(model, ODEModel):
        raise SymctlTypeError(
            f"model: expected a MuscleModel or an ODEModel, got {type(model).__name__}"
        )
    return model


def nonlinear_check(
    model: MuscleModel | ODEModel | None = None,
    controller=None,
    amplitudes=(0.1, 0.3, 1.0, 3.0, 10.0),
    *,
    steps: int = DEFAULT_STEPS,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    rtol: float = 1e-10,
    disturbance=None,
    fail: str = "raise",
) -> NonlinearCheck:
    r"""Close the linear controller around the nonlinear plant and compare with the linear loop.

    At each sample the controller reads :math:`\delta x = x - \bar x`; its output :math:`u =
    \bar u + \delta u` is held while :func:`scipy.integrate.solve_ivp` integrates the ODE over
    :math:`T_s` (DOP853, or Radau with the exact Jacobian when :math:`T_s \max|\lambda| > 1`).

    Parameters
    ----------
    model : MuscleModel or ODEModel, optional
        The paper's muscle by default.
    controller : Gains or Realization, optional
        Default: the optimal controller for ``Q = R = 1``, one step each way (IFP).
    amplitudes : sequence of float
        Disturbance pulse amplitudes (per step), at most 10,000.
    steps, start, length : int
        Horizon (at most 5000) and pulse, as in :func:`~symctl.simulate_realization`.
    rtol : float
        Relative tolerance of the ODE solver, in ``RTOL_RANGE`` (1e-13 to 1e-2).
    disturbance : array (steps, n), optional
        The unit disturbance scaled by each amplitude (default: the pulse on every state).
    fail : {"raise", "mark"}
        On an ODE that fails: raise, or mark its traces NaN from there on.

    Returns
    -------
    NonlinearCheck

    Raises
    ------
    ParameterError, SymctlTypeError, DimensionError
        An argument out of range or of the wrong type, no amplitude, or an ODE that fails.

    Examples
    --------
    >>> from symctl import nonlinear_check
    >>> chk = nonlinear_check(amplitudes=[0.01, 1.0], steps=30)
    >>> bool(chk.relative_deviation[0] < 1e-3 < chk.relative_deviation[1])
    True
    """
    model = _as_ode(model)
    plant = model.plant()
    if controller is None:
        controller = lqr_gains(augment(plant, 1, 1))
    bounded_int(steps, "steps", 1, MAX_STEPS)
    rtol = bounded_number(rtol, "rtol", *RTOL_RANGE)
    if fail not in ("raise", "mark"):
        raise ParameterError(f"fail: must be 'raise' or 'mark', got {fail!r}")
    if not isinstance(controller, Gains | Realization):
        raise SymctlTypeError(
            f"controller: expected Gains or a Realization, got {type(controller).__name__}"
        )
    R = ifp_realization(controller) if isinstance(controller, Gains) else controller
    amps = float_array(amplitudes, "amplitudes").ravel()
    if amps.size == 0:
        raise DimensionError("amplitudes: give at least one amplitude")
    if amps.size > MAX_COUNT:
        raise DimensionError(f"amplitudes: at most {MAX_COUNT} amplitudes, got {amps.size}")
    w_in = 1.0 if disturbance is None else disturbance
    linear = simulate_realization(plant, R, w_in, steps=steps, start=start, length=length)
    F, H, M, N = (a[0] for a in _numeric_realization(R, plant))
    return _run_nonlinear(model, F, H, M, N, amps, linear, rtol, fail)


def _solver(model: ODEModel, k: int) -> dict:
    a = np.array(model.linearize_symbolic().a.subs(model.values).evalf(), dtype=float)
    if model.dt * float(np.max(np.abs(np.linalg.eigvals(a)))) <= STIFF_RATIO:
        return {"method": "DOP853"}
    n = model.n

    def jac(_t, y, u):  # one block per amplitude
        blocks = (model.jacobian_numeric(y[i * n : (i + 1) * n], u[:, i]) for i in range(k))
        return scipy.linalg.block_diag(*blocks)

    return {"method": "Radau", "jac": jac}


def _flow(model: ODEModel, solver: dict, x, u, rtol: float, scale: float) -> tuple:
    """``(y, sol)``: the states ``x`` ``(k, n)`` one sample later under held ``u`` (NaN: failed)."""
    k, n = x.shape
    options = dict(solver)
    if "jac" in options:
        options["jac"] = lambda _t, y, j=options["jac"]: j(_t, y, u.T)
    with np.errstate(over="ignore", invalid="ignore"):  # the caller checks
        sol = scipy.integrate.solve_ivp(
            lambda _t, y: model.rhs_numeric(y.reshape(k, n).T, u.T).T.ravel(),
            (0.0, model.dt),
            x.ravel(),
            rtol=rtol,
            atol=rtol * scale,
            **options,
        )
    return (sol.y[:, -1].reshape(k, n) if sol.success else np.full((k, n), np.nan)), sol


def ode_flow(model, rtol: float = 1e-9):
    """``(ode, step)``: the model as an ODEModel and ``step(x, u)``, its state one sample later.

    >>> from symctl.neural.nonlinear import ode_flow
    >>> ode, step = ode_flow(None)                # the paper's muscle
    >>> bool(abs(step(ode.x_bar, ode.u_bar) - ode.x_bar).max() < 1e-9)   # the equilibrium stays
    True
    """
    ode = _as_ode(model)
    solver = _solver(ode, 1)
    scale = max(1.0, float(np.max(np.abs(ode.x_bar))))

    def step(x, u) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        y, _ = _flow(ode, solver, x[None], np.asarray(u, dtype=float)[None], rtol, scale)
        if not np.all(np.isfinite(y)):
            raise ParameterError(f"nonlinear: the ODE failed from the state {x.tolist()}")
        return y[0]

    return ode, step


def _run_nonlinear(model, F, H, M, N, amps, linear, rtol, fail) -> NonlinearCheck:
    k, n, m = amps.size, model.n, model.m
    x_bar, u_bar = model.x_bar, model.u_bar
    w = linear.w  # (steps, n)
    steps = linear.t.size
    x = np.tile(x_bar, (k, 1))  # (k, n)
    xc = np.zeros((k, F.shape[0]))
    x_nl = np.full((k, steps, n), np.nan)
    u_nl = np.full((k, steps, m), np.nan)
    alive = np.ones(k, dtype=bool)
    solver = _solver(model, k)
    scale = max(1.0, float(np.max(np.abs(x_bar))))
    for t in range(steps):
        dx = x - x_bar
        u = u_bar + xc @ M.T + dx @ N.T  # (k, m)
        x_nl[alive, t], u_nl[alive, t] = x[alive], u[alive]
        y, sol = _flow(model, solver, x, u, rtol, scale)
        bad = ~np.all(np.isfinite(y), axis=1) & alive
        if np.any(bad):
            if fail == "raise":
                raise ParameterError(
                    f"amplitudes: the nonlinear ODE failed at step {t} (amplitudes up to "
                    f"{float(np.max(np.abs(amps))):g}): {sol.message}"
                )
            alive &= ~bad
            y[~alive] = x_bar
        x = y + amps[:, None] * w[t]
        xc = xc @ F.T + dx @ H.T
    x_lin = x_bar + amps[:, None, None] * linear.delta_f[None]
    diff = np.abs(x_nl - x_lin)  # (k, steps, n); NaN after a failure
    peak_i = np.abs(amps)[:, None] * np.max(np.abs(linear.delta_f), axis=0)[None]  # (k, n)
    with np.errstate(invalid="ignore", divide="ignore"):
        dev_i = np.nanmax(np.where(np.isnan(diff), -np.inf, diff), axis=1)  # (k, n)
        rel_i, fin_i = (
            np.where(peak_i > 0, d / np.where(peak_i > 0, peak_i, 1), 0.0)
            for d in (dev_i, np.abs(x_nl[:, -1] - x_bar))
        )
    dev = np.where(alive, dev_i[:, 0], np.inf)  # the first state's, in its unit
    rel = np.where(alive, np.max(rel_i, axis=1), np.inf)  # the worst state's, relative
    final = np.where(alive, np.max(fin_i, axis=1), np.inf)
    units = tuple(model.units.get(s.name, "") for s in model.states)
    names = tuple(s.name for s in model.states), tuple(s.name for s in model.inputs)
    return NonlinearCheck(amps, linear.t, x_lin, x_nl, u_nl, dev, rel, final, *names, units)


@dataclass(frozen=True, eq=False)
class DelaySearch(ArrayValue, DictMixin):
    r"""The longest net delay for which the optimal controller still stabilizes the nonlinear plant.

    Attributes
    ----------
    delays, final_deviation, stabilized : tuples
        The net delays tried, from 1 until the first failure; for each, the final distance
        from the equilibrium over the linear peak (inf: ran away), and whether within
        ``tolerance``.
    longest : int or None
        The longest delay with every shorter one stabilized (None: not even 1 step).
    tolerance : float
    limited : bool
        Whether a failure was found.

    Examples
    --------
    >>> from symctl import longest_delay
    >>> res = longest_delay(None, max_delay=2, steps=30)
    >>> res.longest, res.limited
    (2, False)
    """

    delays: tuple
    final_deviation: tuple
    stabilized: tuple
    longest: int | None
    tolerance: float
    limited: bool

    def table(self) -> str:
        """A plain-text table of the delays tried."""
        rows = [" T | final deviation | stabilized", "-" * 32]
        rows += [
            f"{T:2d} | {d:15.3g} | {'yes' if ok else 'no'}"
            for T, d, ok in zip(self.delays, self.final_deviation, self.stabilized, strict=True)
        ]
        return "\n".join(rows)


def longest_delay(
    model: MuscleModel | ODEModel | None,
    *,
    Q=None,
    R=None,
    disturbance=None,
    amplitude: float = 1.0,
    max_delay: int = 20,
    tolerance: float = RETURN_TOLERANCE,
    steps: int = DEFAULT_STEPS,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
) -> DelaySearch:
    r"""Search the longest net delay :math:`T` whose optimal controller stabilizes the nonlinear plant.

    For :math:`T = 1, \dots,` ``max_delay``, the optimal controller for that (actuator) delay
    is closed around the ODE (:func:`nonlinear_check`) until the state fails to end within
    ``tolerance`` of the equilibrium, relative to the linear loop's peak.

    Parameters
    ----------
    model : MuscleModel or ODEModel
        The plant (None: the paper's muscle).
    Q, R : matrix-like, optional
        The cost (identity by default).
    disturbance, amplitude : array (steps, n), float
        The disturbance of unit amplitude (default: the pulse on every state), and its size.
    max_delay : int
        Largest delay tried, 1 to 200.
    tolerance : float
        Largest final deviation (relative to the peak), > 0.
    steps, start, length : int
        Horizon and pulse, as in :func:`nonlinear_check`.

    Returns
    -------
    DelaySearch

    Examples
    --------
    >>> from symctl import longest_delay
    >>> longest_delay(None, max_delay=1, steps=30).stabilized
    (True,)
    """
    ode = _as_ode(model)
    bounded_int(max_delay, "max_delay", 1, 200)
    tolerance = bounded_number(tolerance, "tolerance", 1e-12, 1e12)
    amplitude = bounded_number(amplitude, "amplitude", -1e100, 1e100)
    plant = ode.plant()
    window = {"steps": steps, "start": start, "length": length, "disturbance": disturbance}
    finals = []
    for T in range(1, max_delay + 1):
        gains = lqr_gains(augment(plant, 0, T, Q=Q, R=R))
        chk = nonlinear_check(ode, gains, [amplitude], **window, fail="mark", rtol=1e-8)
        finals.append(float(chk.final_deviation[0]))
        if not finals[-1] <= tolerance:
            break
    oks = tuple(bool(f <= tolerance) for f in finals)  # all but the last hold
    delays = tuple(range(1, len(finals) + 1))
    return DelaySearch(delays, tuple(finals), oks, sum(oks) or None, tolerance, not all(oks))
