r"""Identifiability: which parameters and neurons a set of recorded neurons pins down.

With :math:`J` the (weighted) sensitivity of the recorded traces to the
parameters, a parameter is identifiable iff its unit vector lies in the row
space of :math:`J`, and an unrecorded neuron's trace iff its sensitivity rows
do (to ``1e-6``, relative); the rank of :math:`J` is reported per neuron set.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from symctl._util.deprecate import RenamedKeys, rng_argument
from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import bounded_int
from symctl.errors import ParameterError, SymctlTypeError
from symctl.fitting.fitargs import _circuit_neurons, _loop, _one_class, _window
from symctl.fitting.fitmodel import TraceModel, renamed_param, transformed
from symctl.neural.simulate import DEFAULT_LENGTH, DEFAULT_START

__all__ = ["Identifiability", "identifiability"]

_RANK_RTOL = 1e-8
_SPAN_RTOL = 1e-6


def _spans(S: np.ndarray, V: np.ndarray, scale: float = 0.0) -> bool:
    r"""Whether the rows of ``S`` lie in the span of the orthonormal rows of ``V`` (``S`` below
    ``1e-9 * scale`` is zero: an invariant trace such as :math:`\delta_r` is always known).
    """
    size = float(np.linalg.norm(S))
    if size <= 1e-9 * scale:
        return True
    rest = S - (S @ V.T) @ V if V.size else S
    return float(np.linalg.norm(rest)) <= _SPAN_RTOL * size


def _row_space(J: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(singular values kept, their right singular vectors (rank, p))`` of ``J``."""
    _, s, Vt = np.linalg.svd(J, full_matrices=False)
    keep = s > _RANK_RTOL * (s[0] if s.size and s[0] > 0 else 1.0)
    return s[keep], Vt[keep]


def _verdicts(model: TraceModel, jacs: dict, J: np.ndarray, neurons) -> tuple[dict, dict, tuple]:
    s, V = _row_space(J)
    eye = np.eye(model.n_params)
    params = {n: _spans(eye[i : i + 1], V) for i, n in enumerate(model.names)}
    scale = max(float(np.linalg.norm(jacs[n])) for n in neurons)
    cells = {n: _spans(jacs[n], V, scale) for n in neurons}
    return params, cells, (s, V)


@dataclass(frozen=True, eq=False)
class Identifiability(ArrayValue, DictMixin):
    r"""Which parameters and neurons a set of recorded neurons pins down.

    Attributes
    ----------
    recorded : tuple of str
    rank : int
        Rank of the sensitivity :math:`J` of the recorded traces to the parameters.
    n_params : int
    params : mapping of str to bool
        Identifiable parameters (unit vector in the row space of :math:`J`).
    neurons : mapping of str to bool
        Every neuron of the circuit: is its trace pinned down by the recorded ones?

    Examples
    --------
    >>> from symctl import MuscleModel, augment, identifiability, lqr_gains
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> rows = identifiability([["G1.x1", "G2.x1", "G2.y"]], gains, sensor_delay=1,
    ...                        actuator_delay=1, C=1)
    >>> rows[0].rank, rows[0].n_params, rows[0].neurons["G2.x2"]
    (4, 6, False)
    """

    recorded: tuple
    rank: int
    n_params: int
    params: Mapping = field(repr=False)
    neurons: Mapping = field(repr=False)

    def __post_init__(self) -> None:
        params = RenamedKeys(
            self.params, renamed_param, "Identifiability.params"
        )  # Q[i,j]: old name
        object.__setattr__(self, "params", params)
        object.__setattr__(self, "neurons", MappingProxyType(dict(self.neurons)))


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

    At a generic point (seeded random epsilons, Cs and :math:`P^{-1}`; see the module text).

    Parameters
    ----------
    neuron_sets : sequence of sequences of str
        Each a set of recorded neurons (at most 100 sets).
    G, sensor_delay, actuator_delay, circuit, disturbance, plant, C, steps, start, length
        As in :func:`fit` (one class).
    rng : int, numpy Generator or None, default 0
        Seeds the generic point (``seed=`` is its deprecated name).

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
    gen = rng
    k = model.n_sections
    theta = [gen.uniform(-0.8, 0.8, k)]
    if C is None:
        theta.append(gen.uniform(0.5, 2.0, k))
    if transformed(model.circuit):
        theta.append((np.eye(model.order) + 0.3 * gen.normal(size=(model.order,) * 2)).ravel())
    theta = np.concatenate(theta)
    vals, jacs = model.traces(theta, u)
    out = []
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
        J = np.vstack([jacs[n] / max(float(np.sqrt(np.mean(vals[n] ** 2))), 1e-12) for n in names])
        params, cells, (s, _) = _verdicts(model, jacs, J, neurons)
        out.append(Identifiability(tuple(names), int(s.size), model.n_params, params, cells))
    return tuple(out)
