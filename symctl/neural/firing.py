r"""Firing patterns of :math:`G_2`'s neurons under a pulse disturbance (the paper's Figs. 9-11):
every realization gives the same force and rate, while its neurons fire differently."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.deprecate import rng_argument
from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.texnames import signal_tex
from symctl._util.validate import MAX_CIRCUITS, bounded_int, numeric_matrix, positive_number
from symctl.compatibility.statespace import structure_realization
from symctl.compatibility.structure import Structure, ifp_structure
from symctl.design.augment import as_plant, same_dt
from symctl.design.controller import controller_tf
from symctl.design.kalman import KalmanGains, lqg_tf
from symctl.design.lqr import Gains
from symctl.design.plant import DiscretePlant
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit
from symctl.neural.compensator import lqg_realization
from symctl.neural.noise import Noise, _as_noise
from symctl.neural.simulate import (
    DEFAULT_DRAWS,
    DEFAULT_LENGTH,
    DEFAULT_START,
    Response,
    _closed_response,
    _freeze,
    _loop,
    _run,
    _signal,
    _traces,
)
from symctl.realization.draws import Draw, draw_realizations
from symctl.realization.draws import draw_eps as _draw_eps
from symctl.realization.realization import Realization, controller_realization
from symctl.realization.realizers import REALIZERS, circuit_names, get_realizer, ifp_realization
from symctl.symbols import gain_symbols

__all__ = ["KINDS", "FiringPatterns", "FiringSummary", "circuit_firing", "structure_firing"]

KINDS: tuple[str, ...]  # read from the registry at each access (__getattr__)


def __getattr__(name: str):
    """``KINDS``: the circuits :func:`circuit_firing` simulates, from the realizers' registry."""
    if name == "KINDS":
        return circuit_names()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


LEGEND_MAX_EPS = 4  # most epsilons a legend entry lists (beyond, their count)


@dataclass(frozen=True, eq=False)
class FiringSummary(ArrayValue, DictMixin):
    r"""How much the neurons' firing differs across realizations, and the behaviour does not
    (:meth:`FiringPatterns.summary`); read-only.

    Attributes
    ----------
    neurons : tuple of str
    peak : (count, k) array
        Each realization's signed peak firing per neuron [spikes/s] (NaN: no such neuron).
    spread, trace_spread : (k,) arrays
        Per neuron, ``max - min`` of ``peak`` over realizations, and the largest difference
        of two realizations' traces at one step (default ``spread``) [spikes/s].
    behaviour_spread : float
        The largest difference between realizations of the force and rate traces.

    Examples
    --------
    >>> import numpy as np
    >>> from symctl import FiringSummary
    >>> s = FiringSummary(("x1", "x2"), np.array([[1.0, -2.0], [3.0, -2.5]]), np.array([2.0, 0.5]), 0.0)
    >>> print(s.table())
     neuron | peak #1   | peak #2   | peak spread | trace spread
    ------------------------------------------------------------
     x1     |         1 |         3 |           2 |            2
     x2     |        -2 |      -2.5 |         0.5 |          0.5
    force/rate spread across realizations: 0.00e+00
    """

    neurons: tuple[str, ...]
    peak: np.ndarray
    spread: np.ndarray
    behaviour_spread: float
    trace_spread: np.ndarray | None = None

    def __post_init__(self) -> None:
        if self.trace_spread is None:
            object.__setattr__(self, "trace_spread", self.spread)
        _freeze(self, ("peak", "spread", "trace_spread"))

    def table(self) -> str:
        """A plain-text table: neuron, peak firing of each realization, spread."""
        count = self.peak.shape[0]
        width = max([6, *map(len, self.neurons)])
        head = f" {'neuron':<{width}} | " + " | ".join(f"peak #{i + 1:<3d}" for i in range(count))
        head += " | peak spread | trace spread"
        lines = [head, "-" * len(head)]
        for k, name in enumerate(self.neurons):
            peaks = " | ".join(f"{v:9.4g}" for v in self.peak[:, k])
            lines.append(
                f" {name:<{width}} | {peaks} | {self.spread[k]:11.4g} | {self.trace_spread[k]:12.4g}"
            )
        lines.append(f"force/rate spread across realizations: {self.behaviour_spread:.2e}")
        return "\n".join(lines)


@dataclass(frozen=True, eq=False)
class FiringPatterns(ArrayValue, DictMixin):
    r"""The firing of :math:`G_2`'s neurons in ``count`` realizations of one closed loop
    (:func:`circuit_firing`); read-only.

    Attributes
    ----------
    kind : str
        One of :func:`~symctl.realization.realizers.circuit_names`.
    t : (steps,) array
        Time, in ``reference.time_unit``.
    delta_f, delta_r : (count, steps) arrays
        Force [N] and motor-neuron rate [spikes/s] changes of each realization (checked equal).
    f_bar : float
        The force at the operating point [N].
    firing : mapping of str to (count, steps) array
        Each neuron's firing-rate change [spikes/s]; NaN rows where a realization lacks it.
    params : tuple of dict
        Per realization, the exact values drawn (:math:`\epsilon_1, \epsilon_3`, ``P``).
    realizations, circuits : tuple of Realization, tuple of Circuit
        Per realization, the :math:`G_2` used (the whole controller for ``"ifp"``) and the
        numeric circuit of the whole controller.
    reference : Response
        The optimal controller's closed loop.
    max_deviation : float
        The largest relative departure of a realization's force or rate from ``reference``.
    firing_sd, delta_f_sd, delta_r_sd, draws
        With noise: the standard deviations over the ``draws`` noisy runs (else None and 0).

    Examples
    --------
    >>> from symctl import MuscleModel, augment, circuit_firing, lqr_gains
    >>> fp = circuit_firing("observable", lqr_gains(augment(MuscleModel(), 1, 1)), count=2)
    >>> fp.kind, fp.count, fp.neurons
    ('observable', 2, ('G2.x1', 'G2.x2', 'G2.y'))
    >>> fp.legend_label(0)
    '#1: $\\epsilon_{1}$ = 0.631, $\\epsilon_{3}$ = 0.246'
    """

    kind: str
    t: np.ndarray
    delta_f: np.ndarray
    delta_r: np.ndarray
    f_bar: float
    firing: Mapping[str, np.ndarray]
    params: tuple[dict, ...]
    realizations: tuple[Realization, ...]
    circuits: tuple[Circuit, ...]
    reference: Response
    max_deviation: float
    firing_sd: Mapping[str, np.ndarray] | None = None
    delta_f_sd: np.ndarray | None = None
    delta_r_sd: np.ndarray | None = None
    draws: int = 0

    def __post_init__(self) -> None:  # read-only arrays, mappings as proxies
        arrays = ("t", "delta_f", "delta_r", "delta_f_sd", "delta_r_sd")
        _freeze(self, arrays, ("firing", "firing_sd"))
        params = tuple(MappingProxyType(dict(p)) for p in self.params)
        object.__setattr__(self, "params", params)

    @property
    def neurons(self) -> tuple[str, ...]:
        """The neuron names, in circuit order."""
        return tuple(self.firing)

    @property
    def count(self) -> int:
        """The number of realizations."""
        return self.delta_f.shape[0]

    def legend_label(self, i: int) -> str:
        r"""``"#1: $\epsilon_{1}$ = 0.312, $\epsilon_{3}$ = -0.54"`` for realization ``i`` (0-based)."""
        eps = [
            f"${signal_tex(str(k))}$ = {float(v):.3g}"
            for k, v in self.params[i].items()
            if str(k).startswith("epsilon")
        ]
        if len(eps) > LEGEND_MAX_EPS:
            return f"#{i + 1}: {len(eps)} random $\\epsilon$"
        return f"#{i + 1}" + (": " + ", ".join(eps) if eps else " (IFP)")

    def summary(self) -> FiringSummary:
        """Per neuron, the spread of peak firing across realizations (a :class:`FiringSummary`)."""
        names = self.neurons
        peak = np.full((self.count, len(names)), np.nan)
        for k, name in enumerate(names):  # NaN rows: realizations without the neuron
            tr = self.firing[name]
            at = np.argmax(np.abs(np.where(np.isnan(tr), 0.0, tr)), axis=1)
            peak[:, k] = np.where(np.isnan(tr).any(axis=1), np.nan, tr[np.arange(self.count), at])
        spread = np.nanmax(peak, axis=0) - np.nanmin(peak, axis=0) if names else np.zeros(0)
        ranges = [np.nanmax(self.firing[n], 0) - np.nanmin(self.firing[n], 0) for n in names]
        trace = np.array([float(np.nanmax(r)) for r in ranges])
        behaviour = max(float(np.max(np.abs(a - a[0]))) for a in (self.delta_f, self.delta_r))
        return FiringSummary(names, peak, spread, behaviour, trace)

    def plot(self, ncols: int = 3):
        """One panel per neuron (``ncols`` per row), the force on top: a Figure."""
        from symctl.plotting.firing import firing_plot

        return firing_plot(self, ncols)


def _kind(kind) -> str:
    kinds = circuit_names()
    if not isinstance(kind, str):
        raise SymctlTypeError(f"kind: expected one of {kinds}, got {kind!r}")
    if kind not in kinds:
        raise ParameterError(f"kind: must be one of {kinds}, got {kind!r}")
    return kind


def _whole(kind: str) -> bool:
    """Whether ``kind`` realizes the whole controller from its gains (the IFP controller)."""
    return kind in REALIZERS and REALIZERS[kind].controller


def _count(count, kind: str) -> int:
    if count is None:
        return 1 if _whole(kind) else 4
    count = bounded_int(count, "count", 1, MAX_CIRCUITS)
    if _whole(kind) and count != 1:
        raise ParameterError(
            f"count: the IFP controller has a single realization, so count must be 1, got {count}"
        )
    return count


def _gains(gains, kind: str) -> Gains:
    if not isinstance(gains, Gains):
        raise SymctlTypeError(
            f"gains: expected Gains (from symctl.lqr_gains), got {type(gains).__name__}"
        )
    s = gains.system
    if _whole(kind) and (s.n, s.m) != (1, 1):
        raise DimensionError(
            f"gains: firing patterns are drawn for a scalar plant (n = m = 1), got n = {s.n}, "
            f"m = {s.m}"
        )
    if _whole(kind) and s.T < 1:
        raise ParameterError(
            "gains: the IFP controller has a neuron only for a net delay T >= 1 "
            f"(mu sums K0 x and its own delayed copies), got T = {s.T}"
        )
    return gains


def _plant(plant, gains: Gains) -> DiscretePlant:
    if plant is None:
        return gains.system.plant
    p = as_plant(plant)
    same_dt(p, gains.system.plant.dt, "plant", "the gains' plant")
    g = gains.system.plant
    if (p.n, p.m) != (g.n, g.m):
        raise DimensionError(
            f"plant: has {p.n} states and {p.m} input{'s' * (p.m != 1)}, the gains' plant {g.n} and {g.m}"
        )
    return p


def _realizations(kind: str, gains: Gains, count: int, gen, draws=None, kalman=None):
    """Yield ``(params, R2, whole controller, circuit)`` per realization (numeric)."""
    s = gains.system
    if _whole(kind):
        K = np.asarray(gains.K, dtype=float).ravel()
        circuit = Circuit.from_structure(ifp_structure(s.T))
        circuit = circuit.subs(dict(zip(gain_symbols(s.T), map(sp.Float, K), strict=True)))
        R = ifp_realization(gains)
        yield {}, R, R, circuit
        return
    for d in draws if draws is not None else _draw(kind, gains, count, gen, kalman):
        R2 = d.result.realization
        params = {**d.values, **R2.params}
        R2 = Realization(R2.F, R2.H, R2.M, R2.N, R2.dt, params)
        circuit = Circuit.from_structure(Structure.from_factorization(d.factors, R2))
        yield params, R2, controller_realization(d.factors, R2), circuit


def _draw(kind: str, gains: Gains, count: int, gen, kalman=None) -> tuple[Draw, ...]:
    """``count`` realizations of the optimal controller's :math:`G_2` drawn from ``gen``."""
    s = gains.system
    get_realizer(kind, "kind")
    # the optimal controller with the gains as the exact rationals of their floats: every
    # realization is then exact rational arithmetic (python-flint), never float SymPy
    exact = gains.substitutions(exact=True)
    if kalman is None:
        G = controller_tf(s).subs(exact)
    else:
        G = lqg_tf(s, kalman.C).subs({**exact, **kalman.substitutions(exact=True)})
    return draw_realizations(G, s.sensor_delay, s.actuator_delay, kind, count, gen)


def _drive(circuit: Circuit, u: np.ndarray) -> dict[str, np.ndarray]:
    """Every neuron's axon output and the circuit output (``"output"``), driven from rest by ``u``
    ``(steps[, inputs])`` or ``(R, steps, inputs)``."""
    sys = circuit.as_linear_system(numeric=True)
    k = sys.A.shape[0]
    if u.ndim == 3:  # each loop of the stack its own input
        A, C = (np.broadcast_to(M[:, :, None], (*M.shape, len(u))) for M in (sys.A, sys.C))
        _, out, _ = _run(A, C, k, u @ sys.B.T, states=False)
        out = out + u @ sys.D.T
    else:
        u = u[:, None] if u.ndim == 1 else u  # (steps, inputs)
        _, out, _ = _run(sys.A[:, :, None], sys.C[:, :, None], k, u @ sys.B.T, states=False)
        out = out[0] + u @ sys.D.T
    n = circuit.n_neurons
    traces = dict(zip(sys.outputs[:n], np.moveaxis(out, -1, 0)[:n], strict=True))
    traces["output"] = out[..., n:] if out.shape[-1] - n > 1 else out[..., -1]
    return traces


def _deviation(a: np.ndarray, ref: np.ndarray) -> float:
    """``max |a - ref| / max |ref|`` (absolute when ``ref`` is zero)."""
    scale = float(np.max(np.abs(ref)))
    return float(np.max(np.abs(a - ref))) / (scale if scale > 0 else 1.0)


@rng_argument()
def circuit_firing(
    kind: str,
    gains: Gains,
    plant=None,
    *,
    count: int | None = None,
    rng=0,
    disturbance=1.0,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    rtol: float = 1e-9,
    draws: Sequence[Draw] | None = None,
    noise: Noise | None = None,
    noise_draws: int = DEFAULT_DRAWS,
    kalman: KalmanGains | None = None,
) -> FiringPatterns:
    r"""Simulate ``count`` realizations of the controller and record the firing of :math:`G_2`'s neurons.

    Each realization of :math:`G = G_3 G_2 G_1` (:math:`\epsilon_1, \epsilon_3` uniform in
    :math:`(-0.9, 0.9)` on a grid of 1/1000, :math:`C_1 = C_3 = 1`, for ``"general"`` a random
    ``P``) is closed around ``plant``; its force, rate and circuit output must equal the
    optimal controller's to ``rtol`` relative to their peak.

    Parameters
    ----------
    kind : str
        One of :func:`~symctl.realization.realizers.circuit_names` (``"ifp"``, ``"general"``...).
    gains : Gains
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system, optional
        The linear plant; default the one ``gains`` were computed for.
    count : int, optional
        Realizations, at most ``MAX_CIRCUITS`` (default 4; the IFP controller: 1).
    rng : int, numpy Generator or None, default 0
        Seeds the epsilons and ``P``.
    disturbance, steps, start, length
        As in :func:`~symctl.neural.simulate.simulate_realization`.
    rtol : float
        Tolerance of the behaviour check.
    draws : sequence of Draw, optional
        Realizations of :math:`G_2` drawn already (:func:`~symctl.realization.draws.draw_realizations`).
    noise, noise_draws : Noise, int, optional
        Every loop runs under the same ``noise_draws`` noisy runs (traces: their mean).
    kalman : KalmanGains, optional
        The LQG compensator (:func:`~symctl.lqg_realization`) instead, its circuits driven by
        the measured outputs ``kalman.C x`` (not ``"ifp"``).

    Returns
    -------
    FiringPatterns

    Raises
    ------
    ParameterError
        Unknown ``kind``, ``count`` out of range (``!= 1`` for ``"ifp"``), ``"ifp"`` at ``T = 0``,
        an unstable loop, a realization off by more than ``rtol``, a ``plant`` of another ``dt``.
    SymctlTypeError, DimensionError
        Arguments of the wrong type or size (``"ifp"`` needs a scalar plant).

    Examples
    --------
    >>> import numpy as np
    >>> from symctl import MuscleModel, augment, circuit_firing, lqr_gains
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> fp = circuit_firing("general", gains, count=3, rng=1)
    >>> fp.neurons
    ('G2.x1', 'G2.x2', 'G2.y')
    >>> bool(np.ptp(fp.delta_r, axis=0).max() < 1e-12)        # the same behaviour
    True
    >>> bool(np.ptp(fp.firing["G2.x1"], axis=0).max() > 1e-3)  # different firing
    True
    >>> circuit_firing("diagonal", gains)
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: kind: must be one of ('ifp', 'general', ...
    """
    kind = _kind(kind)
    gains = _gains(gains, kind)
    plant = _plant(plant, gains)
    count = _count(count, kind)
    if draws is not None:
        draws = tuple(draws)
        if kind == "ifp" or not draws or not all(isinstance(d, Draw) for d in draws):
            raise ParameterError(
                "draws: expected a non-empty sequence of Draw (draw_realizations) for a "
                f"realization of G2, got {type(draws).__name__} for kind {kind!r}"
            )
    if kalman is not None and _whole(kind):
        raise ParameterError("kind: the IFP controller feeds back the state; with kalman, no 'ifp'")
    rows = _realizations(kind, gains, count, rng, draws, kalman)
    window, noisy = (steps, start, length), (noise, noise_draws, kalman)
    return _simulate(kind, rows, gains, plant, disturbance, window, rtol, noisy, rng)


@rng_argument()
def structure_firing(
    structure: Structure,
    gains: Gains,
    plant=None,
    *,
    assignment=None,
    kind: str = "pathways",
    count: int | None = None,
    rng=0,
    disturbance=1.0,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    rtol: float = 1e-9,
    noise: Noise | None = None,
    noise_draws: int = DEFAULT_DRAWS,
    kalman: KalmanGains | None = None,
) -> FiringPatterns:
    r"""Simulate ``count`` realizations of any controller structure, as :func:`circuit_firing` does.

    The structure's gains may hold :math:`K` (given their values), ``epsilon...`` (drawn in
    :math:`(-0.9, 0.9)`) and ``C...`` (set to 1); the neurons of every ``G2`` part are recorded.

    Parameters
    ----------
    structure : Structure
        A SISO controller structure of the gains' controller.
    gains, plant, count, rng, disturbance, steps, start, length, rtol, noise, noise_draws, kalman
        As in :func:`circuit_firing`.
    assignment : DelayAssignment or CompatibilityResult, optional
        Places the circuits' neurons on the delay graph.
    kind : str, default "pathways"
        The label of the results.

    Returns
    -------
    FiringPatterns

    Raises
    ------
    ParameterError, SymctlTypeError
        Another gain symbol; a structure of another controller or not a Structure; the errors
        of :func:`circuit_firing`.

    Examples
    --------
    >>> from symctl import (DelayGraph, MuscleModel, augment, controller_compatibility,
    ...                     controller_tf, lqr_gains, structure_firing)
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> G = controller_tf(gains.system).subs(gains.substitutions(exact=True))
    >>> r = controller_compatibility(G, DelayGraph.chain([2]))  # one axon of 2 steps
    >>> fp = structure_firing(r.structure, gains, assignment=r.check, count=2)
    >>> fp.kind, fp.neurons, fp.max_deviation < 1e-9
    ('pathways', ('G2.x2', 'G2.y'), True)
    """
    if not isinstance(structure, Structure):
        raise SymctlTypeError(f"structure: expected a Structure, got {type(structure).__name__}")
    if not isinstance(kind, str) or not kind:
        raise ParameterError(f"kind: expected a label, got {kind!r}")
    gains = _gains(gains, "")  # never the whole controller: a structure of G3 G2 G1
    plant = _plant(plant, gains)
    count = _count(count, "")
    base = Circuit.from_structure(structure, assignment)
    values = gains.substitutions(exact=True)
    if base.free_symbols & set(values):
        base = base.subs(values)
    symbols = sorted(base.free_symbols, key=str)
    eps = [x for x in symbols if str(x).startswith("epsilon")]
    cs = [x for x in symbols if str(x).startswith("C")]
    other = [str(x) for x in symbols if x not in eps and x not in cs]
    if other:
        raise ParameterError(
            f"structure: its gains hold {other}; only section symbols (epsilon.., C..) are drawn"
        )

    def rows():
        for _ in range(count):
            drawn = _draw_eps(eps, rng)
            circuit = base.subs({**drawn, **{c: 1 for c in cs}})
            R = structure_realization(circuit.structure)
            yield drawn, R, R, circuit

    window, noisy = (steps, start, length), (noise, noise_draws, kalman)
    return _simulate(kind, rows(), gains, plant, disturbance, window, rtol, noisy, rng)


def _simulate(
    kind, rows, gains, plant, disturbance, window, rtol, noisy_args, gen
) -> FiringPatterns:
    """Close each realization of ``rows`` around ``plant``, check it, record its neurons."""
    rtol = positive_number(rtol, "rtol")
    steps, start, length = window
    noise, draws, kalman = noisy_args
    noise = _as_noise(noise)
    C = None if kalman is None else numeric_matrix(kalman.C, "kalman")
    reference, home = (gains, None) if kalman is None else (lqg_realization(gains, kalman), plant)
    seed = None if noise is None else gen.bit_generator.seed_seq.spawn(1)[0]  # shared draws
    w = _signal(disturbance, "disturbance", steps, plant.n, start, length)

    def simulated(p, Acl, Cr, _names, sensor) -> tuple[np.ndarray, ...]:
        gen = None if noise is None else np.random.default_rng(seed)
        return _traces(p, Acl, Cr, w, noise, draws, gen, sensor)

    loop = _loop(reference, home, C)
    ref_df, ref_dr, ref_xc, _ = simulated(*loop)
    ref = _closed_response(loop[0], w, ref_df, ref_dr, ref_xc, loop[3], noise is not None)
    out: list[tuple] = []
    worst = 0.0
    for i, (params, R2, R, circuit) in enumerate(rows):
        df, dr, _, y = simulated(*_loop(R, plant, C))
        traces = _drive(circuit, y if len(y) > 1 else y[0])
        output = traces.pop("output")
        dev = max(
            _deviation(df, ref_df),
            _deviation(dr, ref_dr),
            _deviation(output, ref_dr[..., 0] if ref_dr.shape[-1] == 1 else ref_dr),
        )
        if not dev <= rtol:
            raise ParameterError(
                f"plant: realization {i} ({kind}) departs from the optimal controller's closed "
                f"loop by {dev:.3g} (relative), above rtol = {rtol:g}; is plant the one the "
                "gains were computed for?"
            )
        worst = max(worst, dev)
        keep = {n.name for n in circuit.neurons if _whole(kind) or n.part.split(".")[-1] == "G2"}
        traces = {k: v if v.ndim == 2 else v[None] for k, v in traces.items() if k in keep}
        out.append((params, R2, circuit, df[..., 0], dr[..., 0], traces))
    params, realizations, circuits, dfs, drs, traced = zip(*out, strict=True)
    names = list(dict.fromkeys(n for tr in traced for n in tr))
    nan = np.full((1, ref.t.size), np.nan)

    def stat(f, arrays) -> np.ndarray:
        return np.array([f(a, axis=0) for a in arrays])

    def firing(f) -> dict[str, np.ndarray]:
        return {n: stat(f, [tr.get(n, nan) for tr in traced]) for n in names}

    spread = {}
    if noise is not None:
        spread = {"firing_sd": firing(np.std), "delta_f_sd": stat(np.std, dfs)}
        spread |= {"delta_r_sd": stat(np.std, drs), "draws": len(ref_df)}
    return FiringPatterns(
        kind,
        ref.t,
        stat(np.mean, dfs),
        stat(np.mean, drs),
        float(ref.f_bar[0]),
        firing(np.mean),
        params,
        realizations,
        circuits,
        ref,
        worst,
        **spread,
    )
