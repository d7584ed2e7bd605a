r"""Practical identifiability: what *these* data, with their noise, pin down.

With noise, a structurally identifiable neuron (:mod:`symctl.fitting.identify`) can still be
poorly determined. :func:`symctl.fit` gives every identifiable parameter an interval and every
identifiable neuron a pointwise band by a **parametric bootstrap**: at the fitted
:math:`\hat\theta`, each recorded trace :math:`\hat y_n` plus Gaussian noise of its residual
scale :math:`\hat\sigma_n^2 = \mathrm{RSS}_n / (m_n (1 - r/m))` (:math:`r` the structural rank,
:math:`m` the samples, :math:`m_n` the trace's) is refitted from :math:`\hat\theta`
``bootstrap`` times; intervals and bands are the :math:`(1 \mp \mathrm{level})/2` quantiles
of the refits (one set of refits gives every band, unlike a profile likelihood per step).
A neuron is **determined by these data** when it is identifiable and the RMS of its band's
width is at most the RMS of its predicted trace (calibration: ``benchmarks/fit.py``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import read_only

__all__ = ["Prediction", "Uncertainty"]

_GN_STEPS = 10  # Gauss-Newton steps of a refit before it falls back to the full fit
_GN_RTOL = 1e-12  # eigenvalues of J^T J kept by those steps (round-off is about 1e-16)


class Prediction(dict):
    """Every neuron's predicted trace, ``{name: (steps,) array}``, with its ``level`` band
    ``lower`` and ``upper`` per neuron (NaN where none).

    >>> import numpy as np
    >>> from symctl.fitting.uncertainty import Prediction
    >>> p = Prediction({"G2.y": np.ones(2)}, {"G2.y": np.zeros(2)}, {"G2.y": 2 * np.ones(2)})
    >>> p["G2.y"].tolist(), p.upper["G2.y"].tolist(), p.level
    ([1.0, 1.0], [2.0, 2.0], 0.95)
    """

    def __init__(self, traces: Mapping, lower: Mapping, upper: Mapping, level: float = 0.95):
        super().__init__(traces)
        self.lower = dict(lower)
        self.upper = dict(upper)
        self.level = level


@dataclass(frozen=True, eq=False)
class Uncertainty(ArrayValue, DictMixin):
    r"""Confidence intervals of a fit's parameters and prediction bands of its neurons, by
    parametric bootstrap (method: :mod:`symctl.fitting.uncertainty`).

    Attributes
    ----------
    level : float
        Confidence level of the intervals and bands.
    replicates : int
        Bootstrap refits behind them (0: every interval None, no band).
    intervals : mapping of str to (float, float) or None
        Per parameter, ``(lower, upper)``; None where it is not identifiable.
    lower, upper, sd : mapping of str to (steps,) array
        Per identifiable neuron, the pointwise band and the refits' standard deviation.
    determined : mapping of str to bool
        Per neuron: identifiable, and its band narrower than its signal.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, fit, lqr_gains, synthetic_traces
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> data = synthetic_traces(gains, sensor_delay=1, actuator_delay=1, rng=3, noise=0.01)
    >>> res = fit(data.select(["G2.x1", "G2.x2", "G2.y"]).traces, gains, sensor_delay=1,
    ...           actuator_delay=1, C=1, starts=2, bootstrap=50)
    >>> u = res.uncertainty
    >>> u.replicates, u.determined["G1.x1"], u.intervals["epsilon_1"][0] < u.intervals["epsilon_1"][1]
    (50, True, True)
    """

    level: float
    replicates: int
    intervals: Mapping
    lower: Mapping
    upper: Mapping
    sd: Mapping
    determined: Mapping

    def __post_init__(self) -> None:
        ivs = {k: None if v is None else tuple(map(float, v)) for k, v in self.intervals.items()}
        object.__setattr__(self, "intervals", MappingProxyType(ivs))
        for name in ("lower", "upper", "sd"):
            arrays = {k: read_only(v, float) for k, v in getattr(self, name).items()}
            object.__setattr__(self, name, MappingProxyType(arrays))
        object.__setattr__(self, "determined", MappingProxyType(dict(self.determined)))

    @property
    def method(self) -> str:
        return f"parametric bootstrap, {self.replicates} refits, {self.level:.0%} quantiles"


def _gauss_newton(both, theta: np.ndarray, k: int) -> np.ndarray | None:
    """Minimum-norm Gauss-Newton from ``theta``; None if a step rises or destabilizes a section."""
    r, J = both(theta)
    cost = r @ r
    for _ in range(_GN_STEPS):
        w, V = np.linalg.eigh(J.T @ J)  # the normal equations: lstsq is 50x slower here
        keep = w > _GN_RTOL * w[-1]
        new = theta - V[:, keep] @ ((V[:, keep].T @ (J.T @ r)) / w[keep])
        if np.max(np.abs(new[:k]), initial=0.0) >= 1.0:  # an unstable section
            return None
        r, J = both(new)
        if not r @ r <= cost * (1 + 1e-8):  # rises: diverging
            return None
        if cost - r @ r <= 1e-8 * cost:  # converged (to round-off)
            return new
        theta, cost = new, r @ r
    return None


def _replicates(data, fitted: Mapping, rank: int, count: int, gen) -> list[tuple]:
    """``count`` data sets: each recorded trace's fit plus noise of its residual scale."""
    m = sum(v.size for _, v in data)
    shrink = max(1.0 - rank / m, 1.0 / m)
    scale = {n: np.sqrt(np.mean((fitted[n] - v) ** 2) / shrink) for n, v in data}
    return [
        tuple((n, fitted[n] + scale[n] * gen.normal(size=v.size)) for n, v in data)
        for _ in range(count)
    ]


def _summary(names, params_ok, cells_ok, predicted, refits, level: float) -> Uncertainty:
    """The intervals and bands of the refits ``[(theta, {neuron: trace}), ...]``."""
    q = [(1 - level) / 2, (1 + level) / 2]
    thetas = np.array([th for th, _ in refits]).reshape(len(refits), len(names))
    intervals = {
        n: tuple(np.quantile(thetas[:, i], q)) if params_ok[n] and refits else None
        for i, n in enumerate(names)
    }
    lower, upper, sd, determined = {}, {}, {}, {}
    for n, trace in predicted.items():
        determined[n] = bool(cells_ok[n])
        if cells_ok[n] and refits:
            runs = np.array([tr[n] for _, tr in refits])
            lower[n], upper[n] = np.quantile(runs, q, axis=0)
            sd[n] = runs.std(axis=0, ddof=1) if len(refits) > 1 else np.zeros(trace.size)
            width = np.sqrt(np.mean((upper[n] - lower[n]) ** 2))
            determined[n] = bool(width <= np.sqrt(np.mean(trace**2)))
    return Uncertainty(level, len(refits), intervals, lower, upper, sd, determined)
