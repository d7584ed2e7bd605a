r"""Fitting a circuit to recorded firing rates, keeping the behaviour: :func:`fit`.

Method. Each neuron's trace is a linear filter of the loop's :math:`\delta_f`
(:mod:`symctl.fitting.fitmodel`, exact Jacobians). Least squares minimises the sum over
recorded neurons of :math:`\|(\hat n - n)/\mathrm{rms}(n)\|^2` from ``starts`` seeded points
(for the general class the recorded rows of :math:`P^{-1}` solved linearly first); Dale's-law
``signs`` add penalty residuals and are checked exactly at the end. The values are rounded
to rationals (denominators at most ``10**6``) and the exact realization proved by
:func:`~symctl.realization.check.check_realization`. Standard errors are
:math:`\sqrt{\mathrm{diag}(\hat\sigma^2 (J^T J)^+)}`, :math:`\hat\sigma^2 = \mathrm{RSS}/(m -
\mathrm{rank})`, the pseudo-inverse kept to the structural rank (:mod:`symctl.fitting.identify`);
intervals and bands are a parametric bootstrap (:mod:`symctl.fitting.uncertainty`) whose
refits take minimum-norm Gauss-Newton steps, or Levenberg-Marquardt when a step fails.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from fractions import Fraction
from types import MappingProxyType

import numpy as np
import sympy as sp
from scipy.optimize import least_squares

from symctl._util.deprecate import RenamedKeys, rng_argument
from symctl._util.exact import nearest_rational
from symctl._util.pickling import ArrayValue
from symctl._util.pool import open_pool
from symctl._util.validate import bounded_int, bounded_number, callable_or_none, read_only
from symctl.compatibility.structure import Structure
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, NotRealizableError, ParameterError, SymctlTypeError
from symctl.fitting.fitargs import (
    MAX_FIT_STEPS,
    MAX_NEURONS,
    _circuit_arg,
    _circuit_neurons,
    _label,
    _loop,
    _signs,
    _traces,
    _window,
)
from symctl.fitting.fitmodel import TraceModel, renamed_param, transformed
from symctl.fitting.identify import _structural
from symctl.fitting.uncertainty import Prediction, Uncertainty, _gauss_newton, _replicates, _summary
from symctl.neural.circuit import Circuit
from symctl.neural.simulate import DEFAULT_LENGTH, DEFAULT_START
from symctl.realization.check import check_realization
from symctl.realization.realization import Realization, controller_realization

__all__ = ["MAX_BOOTSTRAP", "MAX_FIT_STEPS", "MAX_NEURONS", "MAX_STARTS", "FitResult", "fit"]

MAX_STARTS = 1000  # most starting points of one fit
MAX_BOOTSTRAP = 10_000  # most refits of the bootstrap of one fit
DENOMINATOR = 10**6  # the fitted values are rationals with denominators at most this
_MARGIN = 1e-4  # a signed weight keeps this distance from 0, so rounding cannot flip it
_EPS_BOUND = 0.999  # sections stay stable: |epsilon| < 1
_RANK_RTOL = 1e-8  # the numerical rank of the covariance (standard errors)


@dataclass(frozen=True)
class _Problem:
    """Everything a worker needs to run starts (plain, picklable data)."""

    G: DiscreteTF
    ds: int
    da: int
    circuit: object
    C: float | None
    data: tuple  # ((name, trace), ...)
    u: np.ndarray
    signs: tuple  # ((name, +1/-1), ...)
    cache: dict = field(default_factory=dict, compare=False, repr=False)  # shared by replace()

    def model(self) -> TraceModel:
        """The trace model, built once per process (lambdified functions do not pickle)."""
        if "model" not in self.cache:
            self.cache["model"] = TraceModel.build(self.G, self.ds, self.da, self.circuit, self.C)
        return self.cache["model"]

    def __getstate__(self) -> dict:
        return {**self.__dict__, "cache": {}}


def _weights(data) -> dict:
    """1 / RMS per recorded trace (1 for a trace that is all zeros)."""
    rms = {n: float(np.sqrt(np.mean(v**2))) for n, v in data}
    return {n: 1.0 / r if r > 0 else 1.0 for n, r in rms.items()}


def _residual_fns(problem: _Problem, model: TraceModel):
    w = _weights(problem.data)

    def both(theta):
        vals, jacs = model.traces(theta, problem.u)
        r = [w[n] * (vals[n] - v) for n, v in problem.data]
        J = [w[n] * jacs[n] for n, _ in problem.data]
        if problem.signs:
            pen, dpen = _penalty(model, theta, problem.signs)
            r.append(pen)
            J.append(dpen)
        return np.concatenate(r), np.vstack(J)

    return both


def _outgoing(model: TraceModel, theta: np.ndarray) -> dict:
    """The outgoing synaptic weights of every neuron, numerically (for the sign penalty)."""
    _, cs, Q = model.split(theta)
    k = model.n_sections
    e_c = theta[: 2 * k] if model.C is None else theta[:k]
    T = Q if Q is not None else model._T(e_c)[0]
    Ti = np.linalg.inv(T)
    F, H = T @ model.F0 @ Ti, T @ model.H0
    mn = model._mn(e_c)[0]
    M, N = mn[: model.order, 0] @ Ti, mn[model.order, 0]
    ds, da = model.sensor_delay, model.actuator_delay
    out = {}
    for j, name in enumerate(model.neurons[:ds]):
        out[name] = np.array([cs[j + 1]]) if j + 1 < ds else np.append(H, N)
    for i in range(model.order):
        out[f"G2.x{i + 1}"] = np.append(np.delete(F[:, i], i), M[i])
    out["G2.y"] = np.array([cs[ds]])
    for j, name in enumerate(model.neurons[-da:]):
        out[name] = np.array([cs[ds + j + 1]]) if j + 1 < da else np.array([1.0])
    return out


def _penalty(model: TraceModel, theta: np.ndarray, signs) -> tuple[np.ndarray, np.ndarray]:
    """Residuals ``10 max(0, 1e-4 - s w)`` per signed outgoing weight, and their Jacobian."""

    def pen(th):
        out = _outgoing(model, th)
        return np.concatenate([10.0 * np.maximum(0.0, _MARGIN - s * out[n]) for n, s in signs])

    p0 = pen(theta)
    J = np.empty((p0.size, theta.size))
    for j in range(theta.size):  # the few weights are cheap: central differences
        h = 1e-7 * max(1.0, abs(theta[j]))
        tp, tm = theta.copy(), theta.copy()
        tp[j] += h
        tm[j] -= h
        J[:, j] = (pen(tp) - pen(tm)) / (2 * h)
    return p0, J


def _start_points(problem: _Problem, model: TraceModel, starts: int, gen) -> list[np.ndarray]:
    """Seeded starts: epsilons uniform in (-0.9, 0.9), C = 1, Q's recorded rows by linear LS."""
    k = model.n_sections
    data = dict(problem.data)
    points = []
    for _ in range(starts):
        eps = gen.uniform(-0.9, 0.9, k)
        theta = np.concatenate([eps, np.ones(k) if model.C is None else []])
        if transformed(model.circuit):
            n = model.order
            Q = gen.normal(size=(n, n))  # either orientation: det Q < 0 and > 0 are not
            while np.linalg.cond(Q) > 20:  # connected through invertible Q
                Q = gen.normal(size=(n, n))
            vals, _ = model.traces(np.concatenate([theta, np.eye(n).ravel()]), problem.u)
            xc = np.column_stack([vals[f"G2.x{i + 1}"] for i in range(n)])  # Q = I: x_c
            for i in range(n):
                if f"G2.x{i + 1}" in data:
                    Q[i] = np.linalg.lstsq(xc, data[f"G2.x{i + 1}"], rcond=None)[0]
            theta = np.concatenate([theta, Q.ravel()])
        points.append(theta)
    return points


def _run_starts(problem: _Problem, points: list) -> list[tuple[float, np.ndarray]]:
    r"""Least squares from each start: ``[(cost, theta), ...]``; epsilons as :math:`0.999 \tanh\phi`
    (stable without bounds, so MINPACK's Levenberg-Marquardt runs: 5-20x the trust region's speed)."""
    model = problem.model()
    both = _residual_fns(problem, model)
    k = model.n_sections
    cache: dict = {}

    def theta_of(x):
        th = x.copy()
        th[:k] = _EPS_BOUND * np.tanh(x[:k])
        return th

    def value(x):
        r, J = both(theta_of(x))
        J = J.copy()
        J[:, :k] *= _EPS_BOUND * (1.0 - np.tanh(x[:k]) ** 2)
        cache["key"], cache["J"] = x.tobytes(), J
        return r

    def jac(x):
        if cache.get("key") != x.tobytes():
            value(x)
        return cache["J"]

    out = []
    for x0 in points:
        x0 = np.array(x0, dtype=float)
        x0[:k] = np.arctanh(np.clip(x0[:k], -0.99, 0.99) / _EPS_BOUND)
        try:
            with np.errstate(all="ignore"):  # a start that wanders onto a singular point fails
                res = least_squares(value, x0, jac=jac, method="lm", x_scale="jac")
        except (np.linalg.LinAlgError, ValueError):  # a singular Q on the way: skip the start
            continue
        if np.isfinite(res.cost):
            out.append((float(res.cost), theta_of(res.x)))
    return out


def _refits(problem: _Problem, theta: np.ndarray, datasets: list) -> list[tuple]:
    """The bootstrap's refits from ``theta``: ``[(theta_b, {neuron: trace}), ...]``."""
    model = problem.model()
    out = []
    for data in datasets:
        boot = replace(problem, data=data)
        try:
            with np.errstate(all="ignore"):
                th = _gauss_newton(_residual_fns(boot, model), theta, model.n_sections)
        except np.linalg.LinAlgError:
            th = None
        runs = [(0.0, th)] if th is not None else _run_starts(boot, [theta])
        out += [(th, model.traces(th, problem.u)[0]) for _, th in runs]
    return out


@dataclass(frozen=True, eq=False)
class FitResult(ArrayValue):
    r"""A circuit fitted to recorded firing rates; it realizes :math:`G` exactly.

    Attributes
    ----------
    realization, realization_G2 : Realization
        The whole controller :math:`G_3 G_2 G_1` and its :math:`G_2` part, exact rationals.
    circuit : Circuit
        The fitted circuit (exact weights).
    circuit_class : str
        A realizer's name or an atlas label.
    params : mapping of str to sympy.Rational
        The fitted values, exact (``epsilon_1``, ``C_1``, ``Pinv[i,j]``, ...; the old
        ``Q[i,j]`` warn); ``P`` is ``realization_G2.params["P"]``.
    stderr : mapping of str to float or None
        The standard error of each parameter; None where it is not identifiable.
    identifiable, neuron_identifiable : mapping of str to bool
        Per parameter, and per neuron of the circuit, structurally (never from the
        fitted point: the same for clean and noisy data).
    residuals : mapping of str to float
        RMS of data minus fit, per recorded neuron [spikes/s].
    data, t
        The recorded traces and the time of each sample.
    proof : RealizationCheck
        The exact :func:`~symctl.realization.check.check_realization` against :math:`G`.
    cost : float
        Half the sum of squared weighted residuals at the exact values.
    starts : int
        Starting points tried.
    alternatives, skipped : tuple of (str, float), tuple of (str, str)
        ``(class, cost)`` of every class fitted, best first; ``(class, reason)`` of those
        that could not take the data.
    identifiability : Identifiability
        The structural verdict behind ``identifiable`` and ``neuron_identifiable``.
    uncertainty : Uncertainty
        Practical identifiability: the parameters' ``intervals``, the neurons' bands
        (:meth:`predict`) and which neurons these data determine (``neuron_determined``).

    Examples
    --------
    >>> from symctl import MuscleModel, augment, fit, lqr_gains, synthetic_traces
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> data = synthetic_traces(gains, sensor_delay=1, actuator_delay=1, rng=2)
    >>> res = fit(data.select(["G1.x1", "G2.x1"]).traces, gains, sensor_delay=1,
    ...           actuator_delay=1, C=1)
    >>> res.exact, res.circuit_class, res.identifiable["Pinv[2,1]"], res.intervals["Pinv[2,1]"]
    (True, 'general', False, None)
    """

    realization: Realization
    realization_G2: Realization
    circuit: Circuit
    circuit_class: str
    params: Mapping
    stderr: Mapping
    identifiable: Mapping
    neuron_identifiable: Mapping
    residuals: Mapping
    data: Mapping
    t: np.ndarray
    proof: object
    cost: float
    starts: int
    alternatives: tuple
    _predicted: Mapping = field(repr=False)
    skipped: tuple = ()
    identifiability: object = None
    uncertainty: Uncertainty | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        for name in ("neuron_identifiable", "residuals"):
            object.__setattr__(self, name, MappingProxyType(dict(getattr(self, name))))
        for name in ("params", "stderr", "identifiable"):  # Q[i,j]: the old name of Pinv[i,j]
            value = RenamedKeys(getattr(self, name), renamed_param, f"FitResult.{name}")
            object.__setattr__(self, name, value)
        for name in ("data", "_predicted"):
            d = {k: read_only(v, float) for k, v in getattr(self, name).items()}
            object.__setattr__(self, name, MappingProxyType(d))
        object.__setattr__(self, "t", read_only(self.t, float))

    @property
    def exact(self) -> bool:
        """True: the fitted realization is proved to realize :math:`G` (``proof``)."""
        return bool(self.proof)

    @property
    def intervals(self) -> Mapping:
        """Per parameter, its confidence interval ``(lower, upper)``; None where not identifiable."""
        return self.uncertainty.intervals

    @property
    def neuron_determined(self) -> Mapping:
        """Per neuron: identifiable, and its prediction band narrower than its signal."""
        return self.uncertainty.determined

    def predict(self) -> Prediction:
        """Every neuron's trace at the fitted values, with its band (``.lower``, ``.upper``)."""
        u = self.uncertainty
        return Prediction(self._predicted, self._each(u.lower), self._each(u.upper), u.level)

    def band(self) -> dict:
        """One standard error of each neuron's predicted trace, per step (NaN if not identifiable)."""
        return self._each(self.uncertainty.sd)

    def _each(self, band: Mapping) -> dict:
        """``band`` for every neuron, NaN where it has none."""
        return {n: band.get(n, np.full(self.t.size, np.nan)) for n in self._predicted}

    def _verdict(self, name: str) -> str:
        if not self.neuron_identifiable[name]:
            return "not identifiable"
        return "identifiable" if self.neuron_determined[name] else "not determined by these data"

    def table(self) -> str:
        """Plain-text report: parameters with standard errors and intervals, residuals, predictions."""
        u = self.uncertainty
        level = f"{u.level:.0%}"
        lines = [f"circuit class: {self.circuit_class}; realizes G exactly: {self.exact}"]
        lines.append(f" parameter  | value       | std. error       | {level} interval")
        for name, v in self.params.items():
            se, iv = self.stderr[name], self.intervals[name]
            text = f"{se:<16.3g}" if se is not None else "not identifiable"
            band = f"[{iv[0]:.6g}, {iv[1]:.6g}]" if iv is not None else ""
            lines.append(f" {name:<10} | {float(v):11.6g} | {text} | {band}".rstrip())
        lines.append(f" neuron     | recorded | RMS residual | {level} band / RMS | prediction")
        for name in self.neuron_identifiable:
            rec = name in self.residuals
            res = f"{self.residuals[name]:12.3g}" if rec else " " * 12
            lines.append(
                f" {name:<10} | {'yes' if rec else 'no':<8} | {res} | "
                f"{self._width(name):>13} | {self._verdict(name)}"
            )
        return "\n".join(lines)

    def _width(self, name: str) -> str:
        """The band's RMS half-width over the trace's RMS ("" without a band)."""
        u, trace = self.uncertainty, self._predicted[name]
        if name not in u.lower:
            return ""
        half = np.sqrt(np.mean(((u.upper[name] - u.lower[name]) / 2) ** 2))
        rms = np.sqrt(np.mean(trace**2))
        return f"+-{half / rms:.1%}" if rms > 0 else f"+-{half:.3g}"

    def to_dict(self) -> dict:
        """Plain data for ``fit.json``: values as exact ``"p/q"`` text and floats."""
        return {
            "circuit_class": self.circuit_class,
            "exact": self.exact,
            "method": getattr(self.proof, "method", "exact"),
            "params": {k: {"exact": str(v), "value": float(v)} for k, v in self.params.items()},
            "stderr": dict(self.stderr),
            "identifiable": dict(self.identifiable),
            "neurons": {
                n: {
                    "recorded": n in self.residuals,
                    "identifiable": ok,
                    "determined": self.neuron_determined[n],
                }
                for n, ok in self.neuron_identifiable.items()
            },
            "identifiability": {
                k: getattr(self.identifiability, k) for k in ("method", "evidence", "exact")
            },
            "intervals": {k: None if v is None else list(v) for k, v in self.intervals.items()},
            "uncertainty": self.uncertainty.to_dict(),
            "residuals": dict(self.residuals),
            "cost": self.cost,
            "starts": self.starts,
            "alternatives": [list(a) for a in self.alternatives],
            "skipped": [list(a) for a in self.skipped],
        }

    def plot(self):
        """Data against fit, and the predicted traces of unrecorded neurons (a Figure)."""
        from symctl.plotting.fit import fit_plot

        return fit_plot(self)


@rng_argument()
def fit(
    traces: Mapping,
    G,
    *,
    sensor_delay: int,
    actuator_delay: int,
    circuit="general",
    disturbance=1.0,
    plant=None,
    C=None,
    signs: Mapping | None = None,
    starts: int = 8,
    rng=0,
    workers: int = 1,
    scheduler: str | None = None,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    bootstrap: int = 200,
    level: float = 0.95,
    progress: Callable[[str], None] | None = None,
    outputs=None,
) -> FitResult:
    r"""Fit a circuit's free parameters (epsilon, C, P, the class) to recorded firing rates.

    Every candidate implements :math:`G` exactly (method: :mod:`symctl.fitting.fit`).

    Parameters
    ----------
    traces : mapping of str to (steps,) array
        Recorded firing-rate changes by neuron name (``"G2.x1"``, ...), one sample per step
        of the closed loop's response to ``disturbance``.
    G : Gains or DiscreteTF
        Gains (their controller and plant), or a numeric SISO controller with ``plant``.
    sensor_delay, actuator_delay : int
        Sections of :math:`G_1` and :math:`G_3`.
    circuit : str, CircuitClass or list of them, default "general"
        A realizer's name or an order-2 atlas class with a closed form (``"A1"``, ...); a
        list fits each and keeps the best; ``"all"``: the named and closed-form classes.
    disturbance, steps, start, length
        As in :func:`~symctl.neural.simulate.closed_loop_response`.
    plant : optional
        The plant, required for a DiscreteTF ``G``.
    C : number, optional
        Fix every section gain to this value; else fitted.
    signs : mapping of str to {"+", "-"}, optional
        Dale's law: every outgoing synapse of the neuron has this sign.
    starts : int
        Seeded starting points, at most ``MAX_STARTS``.
    rng : int, numpy Generator or None, default 0
        Seeds the starts and the bootstrap (``seed=`` is its deprecated name).
    workers : int, scheduler : str, optional
        Run the starts and the bootstrap's refits on dask (local processes, or a scheduler).
    bootstrap : int, default 200
        Refits of the parametric bootstrap, at most ``MAX_BOOTSTRAP``; 0: none.
    level : float, default 0.95
        Confidence level of the intervals and bands, in (0, 1).
    outputs : matrix-like, optional
        ``1 x n``: ``G`` is a compensator fed by the measured output ``y = C x`` (a numeric
        :func:`~symctl.lqg_tf`), which is then the circuit's input trace; ``plant`` required.
    progress : callable, optional
        Called with the name of each stage as it starts.

    Returns
    -------
    FitResult

    Raises
    ------
    DimensionError
        A trace of the wrong length or shape; a MIMO ``G``; an atlas class of another order.
    ParameterError
        NaN or inf in a trace; an unknown neuron or class; more parameters than samples;
        no start met the ``signs``.
    NotRealizableError
        A class that cannot realize the controller.
    SymctlTypeError
        Arguments of the wrong type.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, fit, lqr_gains, synthetic_traces
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> data = synthetic_traces(gains, sensor_delay=1, actuator_delay=1, rng=3)
    >>> rec = {n: data.traces[n] for n in ("G2.x1", "G2.x2", "G2.y")}
    >>> res = fit(rec, gains, sensor_delay=1, actuator_delay=1, C=1)
    >>> bool(res.proof), res.neuron_identifiable["G1.x1"]
    (True, True)
    >>> fit({"G2.x9": data.traces["G2.y"]}, gains, sensor_delay=1, actuator_delay=1)
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: traces['G2.x9']: no such neuron in the general circuit; ...
    """
    ds = bounded_int(sensor_delay, "sensor_delay", 0, 50)
    da = bounded_int(actuator_delay, "actuator_delay", 0, 50)
    if ds < 1 or da < 1:
        raise ParameterError(
            f"sensor_delay, actuator_delay: fitting needs at least one section on each side, "
            f"got {ds} and {da}"
        )
    starts = bounded_int(starts, "starts", 1, MAX_STARTS)
    bootstrap = bounded_int(bootstrap, "bootstrap", 0, MAX_BOOTSTRAP)
    level = bounded_number(level, "level", 0.01, 0.999)
    step = callable_or_none(progress, "progress") or (lambda _name: None)
    if C is not None:
        if isinstance(C, bool) or not isinstance(C, int | float | Fraction | sp.Rational):
            raise SymctlTypeError(f"C: expected a number, got {C!r}")
        if not np.isfinite(float(C)) or float(C) == 0:
            raise ParameterError(f"C: must be a finite nonzero number, got {C!r}")
        C = float(C)
    classes = _circuit_arg(circuit)
    tf, u, t = _loop(G, plant, disturbance, _window(steps, start, length), outputs)
    data = _traces(traces, u.size)
    fits, skipped = [], []
    pool = None
    try:
        for cls in classes:
            try:
                model, neurons, problem = _setup(tf, ds, da, cls, C, data, u, signs)
            except (ParameterError, DimensionError, NotRealizableError) as exc:
                if len(classes) == 1:
                    raise
                skipped.append((_label(cls), str(exc)))  # this class cannot take the data
                continue
            step(f"{_label(cls)}: {starts} starts")
            points = _start_points(problem, model, starts, rng)
            if pool is None:
                pool = open_pool(workers, scheduler)
            runs = _on_pool(pool, workers, _run_starts, (problem,), points)
            fits.append((cls, model, neurons, problem, sorted(runs, key=lambda r: r[0])))
        if not fits:
            raise ParameterError(
                "circuit: no class can take these traces: "
                + "; ".join(f"{label}: {why}" for label, why in skipped)
            )
        boot = (bootstrap, level, rng, pool, max(1, int(workers)), step)
        return _best(fits, t, starts, tuple(skipped), boot)
    finally:
        if pool is not None:
            pool.close()


def _setup(tf, ds, da, cls, C, data, u, signs):
    """The model, the neurons and the problem of one class; errors name the bad input."""
    model = TraceModel.build(tf, ds, da, cls, C)
    neurons = _circuit_neurons(model)
    for name in data:
        if name not in neurons:
            raise ParameterError(
                f"traces[{name!r}]: no such neuron in the {_label(cls)} circuit; its "
                f"neurons are {', '.join(neurons)}"
            )
    samples = sum(v.size for v in data.values())
    if model.n_params > samples:
        raise ParameterError(
            f"traces: {samples} samples for {model.n_params} parameters "
            f"({', '.join(model.names)}); record more steps or neurons"
        )
    signs = _signs(signs, neurons)
    problem = _Problem(tf, ds, da, cls, C, tuple(data.items()), u, signs, {"model": model})
    return model, neurons, problem


def _rational(x: float) -> sp.Rational:
    return nearest_rational(x, DENOMINATOR)


def _exact(model: TraceModel, problem: _Problem, theta: np.ndarray):
    """The exact circuit at ``theta`` rounded to rationals, or None if it breaks a constraint."""
    q = np.array([float(_rational(v)) for v in theta])
    eps, cs, Q = model.split(q)
    fs = model.factorization([_rational(e) for e in eps], [_rational(c) for c in cs])
    if Q is not None:
        Q = sp.Matrix(model.order, model.order, [_rational(v) for v in Q.ravel()])
        if Q.det() == 0:
            return None
    R2 = model.realize(fs, Q)
    circuit = Circuit.from_structure(Structure.from_factorization(fs, R2))
    for name, s in problem.signs:  # Dale's law, checked exactly on the circuit
        if any(sp.sign(syn.weight) * s < 0 for syn in circuit.neuron(name).axon):
            return None
    return q, fs, R2, circuit


def _on_pool(pool, workers, fn, args: tuple, items: list) -> list:
    """``fn(*args, chunk)`` over ``items`` cut into one chunk per worker, results joined."""
    per = max(1, -(-len(items) // max(1, int(workers))))
    chunks = [(*args, items[i : i + per]) for i in range(0, len(items), per)]
    return [r for out in pool.map(fn, chunks) for r in out]


def _best(fits, t, starts, skipped, boot) -> FitResult:
    chosen, table = None, []
    for cls, model, neurons, problem, runs in fits:
        for cost, theta in runs:
            built = _exact(model, problem, theta)
            if built is not None:
                table.append((_label(cls), cost))
                if chosen is None or cost < chosen[0]:
                    chosen = (cost, cls, model, neurons, problem, built)
                break
    if chosen is None:
        why = "the signs" if any(f[3].signs for f in fits) else "a usable circuit"
        raise ParameterError(
            f"signs: no start of {starts} gave a circuit that meets {why} (sign patterns can be "
            "infeasible: two state neurons exciting each other force real poles)"
        )
    _, cls, model, neurons, problem, (q, fs, R2, circuit) = chosen
    R = controller_realization(fs, R2)
    proof = check_realization(R, model.G)
    if not proof:  # pragma: no cover - the family realizes G by construction
        raise NotRealizableError(f"circuit: the fitted {_label(cls)} circuit does not realize G")
    vals = model.traces(q, problem.u)[0]
    r, J = _residual_fns(replace(problem, signs=()), model)(q)  # without the sign penalty
    recorded = [n for n, _ in problem.data]
    bootstrap, level, gen, pool, workers, step = boot
    step("structural identifiability")
    verdict = _structural(model, [recorded], neurons, problem.u, np.random.default_rng(0))[0]
    params_ok, cells_ok = verdict.params, verdict.neurons
    _, s, Vt = np.linalg.svd(J, full_matrices=False)
    keep = s > _RANK_RTOL * (s[0] if s.size and s[0] > 0 else 1.0)
    keep &= np.arange(s.size) < verdict.rank  # noise adds no direction the model lacks
    s, V = s[keep], Vt[keep]
    dof = max(r.size - s.size, 1)
    sigma2 = float(r @ r) / dof
    var = (V**2 / s[:, None] ** 2).sum(axis=0) * sigma2 if s.size else np.zeros(model.n_params)
    stderr = {
        n: float(np.sqrt(var[i])) if params_ok[n] else None for i, n in enumerate(model.names)
    }
    step(f"bootstrap: {bootstrap} refits")
    datasets = _replicates(problem.data, vals, verdict.rank, bootstrap, gen)
    refits = _on_pool(pool, workers, _refits, (problem, q), datasets)
    predicted = {n: vals[n] for n in neurons}
    values = dict(zip(model.names, (_rational(v) for v in q), strict=True))
    alternatives = tuple(sorted(table, key=lambda a: a[1]))
    residuals = {n: float(np.sqrt(np.mean((vals[n] - v) ** 2))) for n, v in problem.data}
    summary = _summary(model.names, params_ok, cells_ok, predicted, refits, level)
    found = (R, R2, circuit, _label(cls), values, stderr, params_ok, cells_ok, residuals)
    run = (dict(problem.data), t, proof, 0.5 * float(r @ r), starts, alternatives, predicted)
    return FitResult(*found, *run, skipped, verdict, summary)
