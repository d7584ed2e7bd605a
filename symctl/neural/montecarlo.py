r"""Many noisy closed loops at once, against the stationary covariance the loop predicts.

With the noise of :mod:`~symctl.neural.noise`, the stationary covariance :math:`\Sigma` of
:math:`\xi` solves the discrete Lyapunov equation

.. math::
    \Sigma = A_{cl} \Sigma A_{cl}^T + E_p W E_p^T + E_u W_u E_u^T + E_v V E_v^T
    + E_u \operatorname{diag}\!\big(\sigma^2 \odot \operatorname{diag}(\Sigma_{uu})\big) E_u^T,
    \qquad \Sigma_{uu} = C_r \Sigma C_r^T + D_v V D_v^T,

(iterated for the signal-dependent term, which converges when the loop is stable in mean
square); the expected cost per step is :math:`J = \operatorname{tr}(Q \Sigma_{xx}) +
\operatorname{tr}(R \Sigma_{uu})`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_discrete_lyapunov

from symctl._util.deprecate import rng_argument
from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import (
    MAX_OUTPUT_BYTES,
    MAX_STEPS,
    bounded_int,
    nonneg_int,
    numeric_matrix,
    psd_matrix,
)
from symctl.design.lqr import Gains
from symctl.errors import ParameterError, SymctlTypeError
from symctl.neural.noise import _BLOCK, Noise, _noisy_loop, _parts, _sensor_inputs
from symctl.neural.simulate import _freeze, _loop, _plant

__all__ = ["MonteCarlo", "monte_carlo"]

MAX_LOOPS = 10**6  # most loops of one monte_carlo
_SETTLED = 1e-8  # the burn-in: the transient's covariance decayed to this fraction
_ITERATIONS = 10_000  # most Lyapunov solves for signal-dependent noise


@dataclass(frozen=True, eq=False)
class MonteCarlo(ArrayValue, DictMixin):
    r"""The measured and predicted stationary covariance and cost of a noisy closed loop
    (:func:`monte_carlo`); read-only.

    Attributes
    ----------
    covariance, covariance_se : (n, n) arrays
        The plant state's covariance (the mean over loops of :math:`x x^T` after ``burn_in``)
        and its standard error.
    predicted_covariance : (n, n) array
        :math:`\Sigma_{xx}` from the Lyapunov equation (module docstring).
    cost, cost_se, predicted_cost : float
        The cost per step :math:`x^T Q x + u^T R u`, measured (± s.e.) and predicted.
    additive_covariance, additive_cost
        The prediction without the signal-dependent noise.
    count, steps, burn_in : int
        Loops, steps of each, and the first steps left out.
    state_names : tuple of str

    Examples
    --------
    >>> from symctl import MuscleModel, Noise, augment, lqr_gains, monte_carlo
    >>> mc = monte_carlo(lqr_gains(augment(MuscleModel(), 1, 1)), noise=Noise(process=1.0),
    ...                  count=2000, steps=100, rng=1)
    >>> bool(mc.z_score < 4), mc.burn_in
    (True, 3)
    """

    covariance: np.ndarray
    covariance_se: np.ndarray
    predicted_covariance: np.ndarray
    cost: float
    cost_se: float
    predicted_cost: float
    additive_covariance: np.ndarray
    additive_cost: float
    count: int
    steps: int
    burn_in: int
    state_names: tuple[str, ...]

    def __post_init__(self) -> None:
        _freeze(
            self, ("covariance", "covariance_se", "predicted_covariance", "additive_covariance")
        )

    @property
    def z_score(self) -> float:
        """The largest ``|measured - predicted| / standard error`` of the covariance and cost."""
        with np.errstate(divide="ignore", invalid="ignore"):
            z = np.abs(self.covariance - self.predicted_covariance) / self.covariance_se
            z = np.where(self.covariance_se > 0, z, 0.0)
            zc = abs(self.cost - self.predicted_cost) / self.cost_se if self.cost_se > 0 else 0.0
        return float(max(np.max(z, initial=0.0), zc))

    def table(self) -> str:
        """Measured (± standard error) beside predicted: each state's variance, and the cost."""
        rows = [
            (f"var {name}", self.covariance[i, i], self.covariance_se[i, i])
            for i, name in enumerate(self.state_names)
        ]
        predicted = [*np.diag(self.predicted_covariance), self.predicted_cost]
        additive = [*np.diag(self.additive_covariance), self.additive_cost]
        rows.append(("cost per step", self.cost, self.cost_se))
        width = max(len(r[0]) for r in rows)
        head = f"{'':<{width}} | measured ± s.e.          | predicted   | additive only"
        lines = [head, "-" * len(head)]
        for (name, value, se), pred, add in zip(rows, predicted, additive, strict=True):
            lines.append(
                f"{name:<{width}} | {value:11.5g} ± {se:<10.3g} | {pred:11.5g} | {add:.5g}"
            )
        lines.append(
            f"{self.count} loops x {self.steps} steps (first {self.burn_in} left out); "
            f"largest |measured - predicted| = {self.z_score:.2f} s.e."
        )
        return "\n".join(lines)


def _predicted(Acl, Cr, B, n, mats, Ev, Dv) -> tuple[np.ndarray, np.ndarray]:
    """``(Sigma, additive Sigma)``: the stationary covariances of the module docstring."""
    size = Acl.shape[0]
    S0 = np.zeros((size, size))
    S0[:n, :n] += mats.get("process", 0.0)
    if "motor" in mats:
        S0[:n, :n] += B @ mats["motor"] @ B.T
    if "sensor" in mats:
        S0 += Ev @ mats["sensor"] @ Ev.T
    additive = solve_discrete_lyapunov(Acl, S0)
    sd2 = mats.get("signal_dependent")
    if sd2 is None:
        return additive, additive
    sigma = additive
    for _ in range(_ITERATIONS):
        extra = np.zeros((size, size))
        extra[:n, :n] = (B * sd2**2 * np.diag(_uu(sigma, Cr, Dv, mats))) @ B.T
        new = solve_discrete_lyapunov(Acl, S0 + extra)
        if not np.trace(new) <= 1e12 * max(np.trace(additive), 1e-300):
            break
        if np.max(np.abs(new - sigma)) <= 1e-13 * np.max(np.abs(new)):
            return new, additive
        sigma = new
    raise ParameterError(
        "noise.signal_dependent: the loop is not stable in mean square under this "
        "signal-dependent noise (its variance grows without bound); make it smaller"
    )


def _uu(sigma, Cr, Dv, mats) -> np.ndarray:
    r"""The command's covariance :math:`\Sigma_{uu}`."""
    out = Cr @ sigma @ Cr.T
    return out + Dv @ mats["sensor"] @ Dv.T if "sensor" in mats else out


def _burn_in(Acl: np.ndarray, steps: int) -> int:
    """Steps until the transient's covariance is below ``_SETTLED`` (at most half)."""
    rho = float(np.max(np.abs(np.linalg.eigvals(Acl)), initial=0.0))
    settle = Acl.shape[0] if rho == 0 else math.ceil(math.log(_SETTLED) / (2 * math.log(rho)))
    return min(steps // 2, max(settle, 1))


def _weights(Q, R, controller, n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    if isinstance(controller, Gains):
        s = controller.system
        Q = s.Q_plant if Q is None else Q
        R = s.R if R is None else R
    Q = np.eye(n) if Q is None else psd_matrix(Q, "Q", n)
    R = np.zeros((m, m)) if R is None else psd_matrix(R, "R", m)
    return numeric_matrix(Q, "Q"), numeric_matrix(R, "R")


@rng_argument()
def monte_carlo(
    controller,
    plant=None,
    *,
    noise: Noise,
    count: int = 10_000,
    steps: int = 500,
    burn_in: int | None = None,
    Q=None,
    R=None,
    rng=0,
    outputs=None,
) -> MonteCarlo:
    """Simulate ``count`` noisy closed loops at once and measure their stationary covariance and cost.

    Each loop runs from rest under ``noise``; its steps after ``burn_in`` give its mean of
    :math:`x x^T` and of the cost, set beside the prediction (module docstring).

    Parameters
    ----------
    controller, plant, outputs
        As in :func:`~symctl.closed_loop_response` (``plant`` required unless ``controller``
        is ``Gains``; ``outputs``: the controller reads :math:`y = C x + v`).
    noise : Noise
        Not all zero.
    count : int
        Loops, 2 to ``MAX_LOOPS``.
    steps : int
        Steps of each loop, 2 to ``MAX_STEPS``.
    burn_in : int, optional
        Steps left out at the start, below ``steps``; default: until the transient's
        covariance decayed to 1e-8 (at most half the steps).
    Q, R : matrices, optional
        The cost's weights; default the gains' design, else the identity and zero.
    rng : int, numpy Generator or None, default 0
        Seeds the noise.

    Returns
    -------
    MonteCarlo

    Raises
    ------
    ParameterError, DimensionError, SymctlTypeError
        An unstable loop (or not in mean square), no noise, an argument out of range or of
        the wrong size or type, the loops' states over ``MAX_OUTPUT_BYTES``.

    Examples
    --------
    >>> from symctl import DiscretePlant, Noise, Realization, monte_carlo
    >>> plant = DiscretePlant([[0.5]], [[1]], dt=0.01)            # x(t+1) = 0.5 x + u + p
    >>> mc = monte_carlo(Realization([[0]], [[0]], [[0]], [[0]], dt=0.01), plant,
    ...                  noise=Noise(process=1.0), count=4000, steps=60, rng=3)
    >>> float(mc.predicted_covariance[0, 0])                     # 1 / (1 - 0.25)
    1.3333333333333333
    >>> bool(abs(mc.covariance[0, 0] - 4 / 3) < 4 * mc.covariance_se[0, 0])
    True
    """
    if not isinstance(noise, Noise):
        raise SymctlTypeError(f"noise: expected a symctl.Noise, got {type(noise).__name__}")
    if noise.is_zero:
        raise ParameterError("noise: all zero; a Monte Carlo needs some noise")
    count = bounded_int(count, "count", 2, MAX_LOOPS)
    steps = bounded_int(steps, "steps", 2, MAX_STEPS)
    p, Acl, Cr, _, sensor = _loop(controller, plant, outputs)
    _, A, B = _plant(p)
    Acl, Cr, n = Acl[:, :, 0], Cr[:, :, 0], p.n
    q = n if sensor is None else sensor[2].shape[0]
    burn = _burn_in(Acl, steps) if burn_in is None else nonneg_int(burn_in, "burn_in")
    if burn >= steps:
        raise ParameterError(f"burn_in: must be below steps = {steps}, got {burn}")
    parts = _parts(noise, n, p.m, q)
    normals = 2 * _BLOCK * sum(map(len, parts.values()))  # two blocks of normals in memory
    if 8 * count * (normals + 4 * Acl.shape[0] + n * n) > MAX_OUTPUT_BYTES:
        raise ParameterError(f"count: {count} loops take more than MAX_OUTPUT_BYTES; use fewer")
    Qw, Rw = _weights(Q, R, controller, n, p.m)
    Ev, Dv = _sensor_inputs(Acl, Cr, A, n) if sensor is None else sensor[:2]
    mats = noise.matrices(n, p.m, q)
    sigma, additive = _predicted(Acl, Cr, B, n, mats, Ev, Dv)

    def expected(S: np.ndarray) -> float:
        return float(np.trace(Qw @ S[:n, :n]) + np.trace(Rw @ _uu(S, Cr, Dv, mats)))

    m = p.m
    xx, uu = np.zeros((n, n, count)), np.zeros((m, m, count))  # each loop's sums of x x^T, u u^T

    def visit(t: int, x: np.ndarray, u: np.ndarray, y) -> None:
        if t >= burn:
            xx[...] += x[:n, None, :] * x[None, :n, :]
            uu[...] += u[:, None, :] * u[None, :, :]

    zero = np.zeros((steps, n))
    _noisy_loop(Acl, Cr, B, n, zero, parts, rng, count, visit, Ev, Dv, y=False)
    xx /= steps - burn
    uu /= steps - burn
    cost = np.einsum("ij,ijr->r", Qw, xx) + np.einsum("ij,ijr->r", Rw, uu)
    root = math.sqrt(count)
    return MonteCarlo(
        xx.mean(axis=2),
        xx.std(axis=2, ddof=1) / root,
        sigma[:n, :n],
        float(cost.mean()),
        float(cost.std(ddof=1) / root),
        expected(sigma),
        additive[:n, :n],
        expected(additive),
        count,
        steps,
        burn,
        p.state_names,
    )
