r"""The linear controller around the paper's original, nonlinear muscle.

The design is linear (the muscle linearized at its operating point,
:class:`~symctl.design.plant.MuscleModel`); :func:`nonlinear_check` closes the same
controller around the nonlinear ODE
:math:`\dot f = f_\text{max}/(\tau(1+e^{-r})) - f/\tau` and measures how far the
force departs from the linear prediction as the disturbance grows: quadratically
in its amplitude, since the linearization is exact to first order.

>>> from symctl import nonlinear_check
>>> chk = nonlinear_check(amplitudes=[0.01, 0.1], steps=30)
>>> round(float(chk.max_deviation[1] / chk.max_deviation[0]))   # second order
100
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.integrate

from symctl._util.validate import (
    MAX_COUNT,
    bounded_int,
    bounded_number,
    float_array,
    read_only,
)
from symctl.design.augment import augment
from symctl.design.lqr import Gains, lqr_gains
from symctl.design.plant import MuscleModel
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.neural.simulate import (
    DEFAULT_LENGTH,
    DEFAULT_START,
    DEFAULT_STEPS,
    _as_realization,
    _numeric_realization,
    simulate_realization,
)
from symctl.realization.realization import Realization

__all__ = ["NonlinearCheck", "nonlinear_check"]

MAX_STEPS = 5000
"""Longest horizon of :func:`nonlinear_check` (one ODE solve per sample: about 10 s at 5000)."""

RTOL_RANGE = (1e-13, 1e-2)
"""Admissible ``rtol`` of the ODE solver (SciPy refuses below about 2.2e-14)."""

STIFF_RATIO = 1.0
r""":math:`T_s/\tau` above which the ODE counts as stiff and is solved with Radau (implicit)."""


@dataclass(frozen=True, eq=False)
class NonlinearCheck:
    r"""The linear controller around the nonlinear muscle, against the linear prediction.

    Attributes
    ----------
    amplitudes : (k,) array
        Disturbance pulse amplitudes [N per step].
    t : (steps,) array
        Time [s].
    f_linear, f_nonlinear : (k, steps) arrays
        Absolute force [N] of the linear model and of the nonlinear ODE.
    r_nonlinear : (k, steps) array
        Absolute motor-neuron rate [spikes/s] driving the nonlinear muscle.
    max_deviation : (k,) array
        :math:`\max_t |f_\text{nonlinear} - f_\text{linear}|` [N].
    relative_deviation : (k,) array
        ``max_deviation`` over :math:`\max_t |\delta_f^\text{linear}|`.

    Made by :func:`nonlinear_check`; the arrays are read-only copies.

    Examples
    --------
    >>> from symctl import nonlinear_check
    >>> chk = nonlinear_check(amplitudes=[0.1, 1.0], steps=20)
    >>> chk.f_nonlinear.shape, bool(chk.max_deviation[1] > chk.max_deviation[0])
    ((2, 20), True)
    >>> print(chk.table().splitlines()[0])
     amplitude [N] | peak |δf| linear [N] | max |f_nl - f_lin| [N] | relative
    """

    amplitudes: np.ndarray
    t: np.ndarray
    f_linear: np.ndarray
    f_nonlinear: np.ndarray
    r_nonlinear: np.ndarray
    max_deviation: np.ndarray
    relative_deviation: np.ndarray

    def __post_init__(self) -> None:  # the arrays are read-only copies
        for name in (
            "amplitudes",
            "t",
            "f_linear",
            "f_nonlinear",
            "r_nonlinear",
            "max_deviation",
            "relative_deviation",
        ):
            object.__setattr__(self, name, read_only(getattr(self, name), float))

    def table(self) -> str:
        """A plain-text table: amplitude, peak linear force change, max and relative deviation."""
        peak = np.max(np.abs(self.f_linear - self.f_linear[:, :1]), axis=1)  # f(0) = f_bar
        lines = [
            " amplitude [N] | peak |δf| linear [N] | max |f_nl - f_lin| [N] | relative",
            "-" * 78,
        ]
        for a, pk, d, rel in zip(
            self.amplitudes, peak, self.max_deviation, self.relative_deviation, strict=True
        ):
            lines.append(f" {a:13.4g} | {pk:20.4g} | {d:22.4g} | {rel:8.2e}")
        return "\n".join(lines)

    def plot(self):
        """Force traces (nonlinear solid, linear dashed) and the deviation against amplitude.

        Returns
        -------
        matplotlib.figure.Figure
            Drawn by :func:`symctl.plotting.response.nonlinear_plot`.

        Examples
        --------
        >>> from symctl import nonlinear_check
        >>> fig = nonlinear_check(amplitudes=[0.1, 1.0], steps=20).plot()
        >>> fig.axes[0].get_ylabel()
        'force f [N]'
        """
        from symctl.plotting.response import nonlinear_plot

        return nonlinear_plot(self)


def nonlinear_check(
    model: MuscleModel | None = None,
    controller=None,
    amplitudes=(0.1, 0.3, 1.0, 3.0, 10.0),
    *,
    steps: int = DEFAULT_STEPS,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    rtol: float = 1e-10,
) -> NonlinearCheck:
    r"""Close the linear controller around the nonlinear muscle ODE and compare with the linear loop.

    At each sample the controller reads :math:`\delta_f = f - \bar f`, its output
    :math:`r = \bar r + \delta_r` is held constant over the step, and
    :math:`\dot f = f_\text{max}/(\tau(1+e^{-r})) - f/\tau` (:meth:`MuscleModel.rhs`)
    is integrated over :math:`T_s` with :func:`scipy.integrate.solve_ivp` (all
    amplitudes as one vector ODE, relative tolerance ``rtol``); the disturbance is
    added to the force at the sample, as in the linear model. The solver is
    explicit (DOP853) while :math:`T_s/\tau \le` ``STIFF_RATIO`` (1, the paper's
    is 0.5) and implicit beyond (Radau, with the exact Jacobian
    :math:`-1/\tau`), so that a stiff muscle (a small ``tau``) takes seconds too.

    Parameters
    ----------
    model : MuscleModel, optional
        The paper's by default.
    controller : Gains or Realization, optional
        Default: the optimal delayed controller for ``Q = R = 1``, one step of delay
        each way (as the IFP realization).
    amplitudes : sequence of float
        Disturbance pulse amplitudes [N per step]; default 0.1 .. 10; at most
        ``MAX_COUNT`` (10,000) of them.
    steps, start, length : int
        Horizon (at most ``MAX_STEPS``, 5000) and disturbance pulse, as in
        :func:`~symctl.simulate_realization`.
    rtol : float
        Relative tolerance of the ODE solver, in ``RTOL_RANGE`` ``[1e-13, 1e-2]``.

    Returns
    -------
    NonlinearCheck

    Raises
    ------
    ParameterError
        ``steps`` above ``MAX_STEPS``, ``rtol`` outside ``RTOL_RANGE``, non-finite
        amplitudes, or an ODE that fails (naming the amplitudes).
    SymctlTypeError
        ``model`` not a MuscleModel, or arguments of the wrong type.
    DimensionError
        No amplitude.

    Examples
    --------
    >>> from symctl import nonlinear_check
    >>> chk = nonlinear_check(amplitudes=[0.01, 1.0], steps=30)
    >>> bool(chk.relative_deviation[0] < 1e-3 < chk.relative_deviation[1])
    True
    """
    model = MuscleModel() if model is None else model
    if not isinstance(model, MuscleModel):
        raise SymctlTypeError(f"model: expected a MuscleModel, got {type(model).__name__}")
    if controller is None:
        controller = lqr_gains(augment(model, 1, 1))
    bounded_int(steps, "steps", 1, MAX_STEPS)
    rtol = bounded_number(rtol, "rtol", *RTOL_RANGE)
    if not isinstance(controller, Gains | Realization):
        raise SymctlTypeError(
            f"controller: expected Gains or a Realization, got {type(controller).__name__}"
        )
    R = _as_realization(controller)
    amps = float_array(amplitudes, "amplitudes").ravel()
    if amps.size == 0:
        raise DimensionError("amplitudes: give at least one amplitude")
    if amps.size > MAX_COUNT:
        raise DimensionError(f"amplitudes: at most {MAX_COUNT} amplitudes, got {amps.size}")
    linear = simulate_realization(model, R, 1.0, steps=steps, start=start, length=length)
    F, H, M, N = (a[0] for a in _numeric_realization(R, model.plant()))
    w = linear.w[:, 0]
    f_bar, r_bar, Ts = model.f_bar, model.r_bar, model.Ts
    f = np.full(amps.size, f_bar)
    xc = np.zeros((amps.size, F.shape[0]))
    f_nl = np.empty((amps.size, linear.t.size))
    r_nl = np.empty_like(f_nl)
    if Ts / model.tau <= STIFF_RATIO:
        solver = {"method": "DOP853"}
    else:  # stiff: implicit, with the exact (diagonal) Jacobian of rhs in f
        jac = -np.eye(amps.size) / model.tau
        solver = {"method": "Radau", "jac": lambda _t, _y: jac}
    for k in range(linear.t.size):
        df = f - f_bar
        r = r_bar + (xc @ M.T)[:, 0] + N[0, 0] * df
        f_nl[:, k], r_nl[:, k] = f, r
        with np.errstate(over="ignore", invalid="ignore"):  # checked just below
            sol = scipy.integrate.solve_ivp(
                lambda _t, y, r=r: model.rhs(y, r), (0.0, Ts), f,
                rtol=rtol, atol=rtol * max(1.0, abs(f_bar)), **solver,
            )  # fmt: skip
        if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
            raise ParameterError(
                f"amplitudes: the nonlinear ODE failed at step {k} (amplitudes up to "
                f"{float(np.max(np.abs(amps))):g}): {sol.message}"
            )
        f = sol.y[:, -1] + amps * w[k]
        xc = xc @ F.T + df[:, None] @ H.T
    f_lin = f_bar + amps[:, None] * linear.delta_f[:, 0]
    dev = np.max(np.abs(f_nl - f_lin), axis=1)
    peak = np.abs(amps) * np.max(np.abs(linear.delta_f))
    rel = np.divide(dev, peak, out=np.zeros_like(dev), where=peak > 0)
    return NonlinearCheck(amps, linear.t, f_lin, f_nl, r_nl, dev, rel)
