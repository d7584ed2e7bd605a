r"""Structural identifiability: which parameters and neurons a set of recorded neurons pins down.

A property of the model, the recorded set and the window, never of the recorded values,
so clean and noisy data get the same verdicts.

**Reduction to Markov parameters.** Every neuron's trace is the loop's :math:`\delta_f = u`
through the circuit's :math:`N = d_s + n + d_a` states: :math:`n(t) = \sum_{s<t} h_n(t-s)
u(s)`, :math:`h_n(j) = M_n F^{j-1} H`, rational in :math:`\theta`. With :math:`u(t_0)` the
first nonzero input, the traces of a window of :math:`L` steps are a triangular, invertible
linear image of :math:`h_n(1), \dots, h_n(L-1-t_0)`, so their sensitivities :math:`J` and
those :math:`K` of the Markov parameters have the same row space at every :math:`\theta`. A
sequence with a recurrence of order at most :math:`N` (Cayley-Hamilton) is fixed by its first
:math:`2N` terms, so the image of :math:`h(1..)` projects injectively onto that of
:math:`h(1..2N)`: :math:`W = \min(L-1-t_0, 2N)` terms have the same generic ranks.

**Verdicts.** Parameter :math:`\theta_i` is (locally) identifiable from the recorded set
:math:`R` iff :math:`\operatorname{rank}[K_R; e_i] = \operatorname{rank} K_R` generically; an
unrecorded neuron :math:`m` iff :math:`\operatorname{rank}[K_R; K_m] = \operatorname{rank} K_R`.
The ranks are exact, over :math:`\mathbb{Q}` (python-flint ``fmpq_mat``), at ``POINTS``
random integer points with coordinates uniform in :math:`S = \{1, \dots, 2^{62}\}`, each
matrix taking its largest rank. A rank at a point is at most the generic rank (a nonzero minor
is a nonzero polynomial), so **full column rank of** :math:`K_R` **at one point proves** every
parameter and neuron identifiable (``exact``). Otherwise the verdicts are Schwartz-Zippel
evidence: with :math:`a, b` the degrees of the numerators and of the common denominator
:math:`D` of :math:`T, M_0, N` (:mod:`symctl.fitting.fitmodel`), every entry of :math:`K` is a
polynomial of degree at most :math:`\delta = W + \max(a, b) + b` over :math:`D^2`, so a
generic rank above the one found needs a nonzero polynomial of degree at most
:math:`d = p\,\delta + b` to vanish at every point: probability at most
:math:`(d/|S|)^{\mathrm{points}}` per matrix, times the matrices tested (``error_bound``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import reduce
from types import MappingProxyType

import numpy as np
import sympy as sp
from flint import fmpq, fmpq_mat

from symctl._util.deprecate import RenamedKeys, rng_argument
from symctl._util.pickling import ArrayValue
from symctl._util.validate import bounded_int
from symctl.errors import ParameterError, SymctlTypeError
from symctl.fitting.fitargs import _circuit_neurons, _loop, _one_class, _window
from symctl.fitting.fitmodel import TraceModel, renamed_param, transformed
from symctl.neural.simulate import DEFAULT_LENGTH, DEFAULT_START
from symctl.proof import Verdict

__all__ = ["POINTS", "Identifiability", "identifiability"]

POINTS = 2  # random integer points at which the ranks are computed
_FIELD = 2**62  # coordinates uniform in 1..2**62 (Schwartz-Zippel's |S|)


def _degrees(model: TraceModel) -> tuple[int, int]:
    """``(a, b)``: degrees of the numerators over, and of, the common denominator of T, M0, N."""
    free = model.exact[2]
    fracs = [e.as_numer_denom() for m, _ in _parts(model) for e in m]
    dens = [sp.Poly(d, *free) for _, d in fracs]
    b = reduce(sp.lcm, set(dens)).total_degree()
    a = max(
        sp.Poly(n, *free).total_degree() + b - d.total_degree()
        for (n, _), d in zip(fracs, dens, strict=True)
    )
    return max(a, 1 if transformed(model.circuit) else 0), b


def _parts(model: TraceModel) -> list:
    """``[(M, its gradients)]`` of ``[M0^T; N]`` and of ``T`` (for a fixed class), SymPy."""
    return [f.exact for f in (model._mn, model._T) if f is not None]


def _markov(model: TraceModel, theta: list, W: int) -> dict | None:
    """Per neuron, the exact ``(W, p)`` sensitivity of its Markov parameters ``h(1..W)`` at the
    integer point ``theta`` (the traces of an impulse, in exact arithmetic); None at a pole."""
    u = np.zeros(W + 1, dtype=object)
    u[0] = fmpq(1)
    try:
        _, jacs = model.traces([fmpq(v) for v in theta], u, exact=True)
    except ZeroDivisionError:
        return None
    return {name: jac[1:] for name, jac in jacs.items()}


def _kernel(rows: np.ndarray, p: int) -> tuple[int, fmpq_mat | None]:
    """``(rank, kernel basis as columns)`` of the exact ``(m, p)`` matrix ``rows`` (None: full rank)."""
    if not len(rows):
        return 0, fmpq_mat([[int(i == j) for j in range(p)] for i in range(p)])
    N, nullity = fmpq_mat(rows.tolist()).numer_denom()[0].nullspace()
    basis = fmpq_mat([[N[i, j] for j in range(nullity)] for i in range(p)]) if nullity else None
    return p - nullity, basis


def _spans(B: np.ndarray, N: fmpq_mat) -> bool:
    """Whether the exact rows ``B`` lie in the row space of the matrix whose kernel is ``N``."""
    return not len(B) or not any((fmpq_mat(B.tolist()) * N).entries())


def _structural(model: TraceModel, sets: list, neurons: tuple, u: np.ndarray, gen) -> list:
    """One :class:`Identifiability` per recorded set, decided as the module text says."""
    nz = np.flatnonzero(u)
    W = max(0, min(u.size - 1 - int(nz[0]), 2 * (model.n_sections + model.order))) if nz.size else 0
    p = model.n_params
    points = []
    for _ in range(10 * POINTS):  # a pole of T, M0 or N is a probability-(b/|S|) event
        theta = [int(v) for v in gen.integers(1, _FIELD, size=p, endpoint=True)]
        jac = _markov(model, theta, W)
        if jac is not None:
            points.append(jac)
        if len(points) == POINTS:
            break
    a, b = _degrees(model)
    d = p * (W + max(a, b) + b) + b
    out = []
    for names in sets:
        kernels = [_kernel(np.vstack([jac[n] for n in names]), p) for jac in points]
        rank = max(r for r, _ in kernels)
        full = rank == p
        best = [(jac, N) for jac, (r, N) in zip(points, kernels, strict=True) if r == rank]

        params = {
            n: full or all(not any(N.tolist()[i]) for _, N in best)
            for i, n in enumerate(model.names)
        }
        cells = {m: full or all(_spans(jac[m], N) for jac, N in best) for m in neurons}
        bound = 0.0 if full else (1 + p + len(neurons)) * (d / _FIELD) ** len(points)
        evidence = (
            f"K_R has full column rank {p} at a point: every verdict is proved"
            if full
            else f"Schwartz-Zippel: some verdict is wrong with probability at most {bound:.1e} "
            f"(degree bound {d}, |S| = 2^62, {W} Markov parameters)"
        )
        out.append(Identifiability(tuple(names), rank, p, params, cells, evidence, full, bound))
    return out


@dataclass(frozen=True, eq=False)
class Identifiability(ArrayValue, Verdict):
    r"""Which parameters and neurons a set of recorded neurons pins down, structurally.

    Truthy when every neuron's trace is identifiable (method: :mod:`symctl.fitting.identify`).

    Attributes
    ----------
    recorded : tuple of str
    rank, n_params : int
        Generic rank of the recorded traces' sensitivity to the parameters, and their number.
    params, neurons : mapping of str to bool
        Per parameter, and per neuron of the circuit: is it pinned down by the recorded ones?
    evidence : str
        What backs the verdicts: a proof, or the Schwartz-Zippel bound.
    exact : bool
        True when the verdicts are proved (the rank is full).
    error_bound : float
        Probability that some verdict is wrong (0 when ``exact``).

    Examples
    --------
    >>> from symctl import MuscleModel, augment, identifiability, lqr_gains
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> rows = identifiability([["G1.x1", "G2.x1", "G2.y"]], gains, sensor_delay=1,
    ...                        actuator_delay=1, C=1)
    >>> rows[0].rank, rows[0].n_params, rows[0].neurons["G2.x2"], rows[0].exact
    (4, 6, False, False)
    >>> bool(rows[0]), rows[0].error_bound < 1e-30
    (False, True)
    """

    _verdict = "complete"

    recorded: tuple
    rank: int
    n_params: int
    params: Mapping = field(repr=False)
    neurons: Mapping = field(repr=False)
    evidence: str = ""
    exact: bool = False
    error_bound: float = 0.0

    def __post_init__(self) -> None:
        params = RenamedKeys(self.params, renamed_param, "Identifiability.params")  # Q[i,j]: old
        object.__setattr__(self, "params", params)
        object.__setattr__(self, "neurons", MappingProxyType(dict(self.neurons)))

    @property
    def complete(self) -> bool:
        """Whether every neuron's trace is identifiable from the recorded ones."""
        return all(self.neurons.values())

    @property
    def method(self) -> str:
        return f"exact rank over Q at {POINTS} random integer points (generic rank)"


@rng_argument()
def identifiability(
    neuron_sets: Sequence,
    G,
    *,
    sensor_delay: int,
    actuator_delay: int,
    circuit="general",
    disturbance=1.0,
    plant=None,
    C=None,
    rng=0,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
) -> tuple[Identifiability, ...]:
    r"""Which parameters, and which neurons' traces, each set of recorded neurons pins down.

    Structurally, independent of any data (method and error bound: :mod:`symctl.fitting.identify`).

    Parameters
    ----------
    neuron_sets : sequence of sequences of str
        Each a set of recorded neurons (at most 100 sets).
    G, sensor_delay, actuator_delay, circuit, disturbance, plant, C, steps, start, length
        As in :func:`fit` (one class).
    rng : int, numpy Generator or None, default 0
        Seeds the random points (``seed=`` is its deprecated name).

    Returns
    -------
    tuple of Identifiability
        One per set, in order.

    Raises
    ------
    ParameterError
        A name the circuit does not have; the errors of :func:`fit`.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, identifiability, lqr_gains
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> a, b = identifiability([["G2.x1", "G2.x2", "G2.y"], ["G2.y"]], gains,
    ...                        sensor_delay=1, actuator_delay=1, C=1)
    >>> a.rank, a.neurons["G1.x1"], b.rank, b.neurons["G1.x1"]
    (6, True, 1, False)
    """
    if isinstance(neuron_sets, str) or not isinstance(neuron_sets, Sequence):
        raise SymctlTypeError(
            f"neuron_sets: expected a list of lists of names, got {neuron_sets!r}"
        )
    if not 1 <= len(neuron_sets) <= 100:
        raise ParameterError(f"neuron_sets: expected 1 to 100 sets, got {len(neuron_sets)}")
    ds = bounded_int(sensor_delay, "sensor_delay", 1, 50)
    da = bounded_int(actuator_delay, "actuator_delay", 1, 50)
    cls = _one_class(circuit, "identifiability")
    C = None if C is None else float(C)
    tf, u, _ = _loop(G, plant, disturbance, _window(steps, start, length))
    model = TraceModel.build(tf, ds, da, cls, C)
    neurons = _circuit_neurons(model)
    for i, names in enumerate(neuron_sets):
        if isinstance(names, str) or not isinstance(names, Sequence) or not names:
            raise SymctlTypeError(
                f"neuron_sets[{i}]: expected a non-empty list of names, got {names!r}"
            )
        for n in names:
            if n not in neurons:
                raise ParameterError(
                    f"neuron_sets[{i}]: no neuron {n!r}; the circuit's neurons are {', '.join(neurons)}"
                )
    return tuple(_structural(model, [list(n) for n in neuron_sets], neurons, u, rng))
