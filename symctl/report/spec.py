r"""The paper's parameters and the circuits of its report, stated once.

:data:`PAPER` holds the inputs of :func:`~symctl.report.pipeline.derive_paper`
(and the defaults of ``symctl paper``). The muscle's parameters are not
repeated here: they are read from the defaults of
:class:`~symctl.design.plant.MuscleModel` (the paper's section "Simulations":
:math:`\tau = 0.02` s, :math:`f_\text{max} = 60` N, :math:`\bar r = 1`
spike/s, :math:`T_s = 0.01` s), and the delays from those of
:func:`~symctl.design.augment.augment` (one step each), so each number lives
in one place. :data:`CIRCUITS` names the report's circuits in reading order and
:data:`CIRCUIT_SPECS` gives each its titles, both read from the realizers' registry
(:data:`~symctl.realization.realizers.REALIZERS`).

Examples
--------
>>> from symctl.report.spec import CIRCUITS, PAPER
>>> PAPER.tau, PAPER.f_max, PAPER.r_bar, PAPER.Ts
(0.02, 60.0, 1.0, 0.01)
>>> PAPER.sensor_delay, PAPER.actuator_delay, PAPER.seed, PAPER.realizations
(1, 1, 0, 4)
>>> CIRCUITS
('ifp', 'general', 'controllable', 'observable', 'pathways')
"""

from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from symctl.design.augment import augment
from symctl.design.plant import MuscleModel

__all__ = [
    "CIRCUITS",
    "CIRCUIT_SPECS",
    "EXPANDED_ZEROS_MAX",
    "PAPER",
    "SCHEMA_VERSION",
    "SYMBOLIC_P_MAX_ORDER",
    "CircuitSpec",
    "PaperSpec",
    "circuit_specs",
]

CIRCUITS: tuple[str, ...]  # read from the registry at each access (__getattr__)
CIRCUIT_SPECS: Mapping  # likewise

SCHEMA_VERSION = 1
"""Version of the ``results.json`` schema (README, section "results.json")."""
SYMBOLIC_P_MAX_ORDER = 3  # the general realization keeps a fully symbolic P up to this order
EXPANDED_ZEROS_MAX = 4
r"""Sections up to which the symbolic :math:`G_2` is realized with its zeros multiplied out.

The zeros :math:`\prod_i (z - \epsilon_i)` of :math:`d` sections have :math:`2^d`
monomials (:math:`inom{d}{k}` in the k-th coefficient): up to this many
sections the realizations show them, as the paper does (:math:`K_1 - \epsilon_1
- \epsilon_3`); beyond, they realize
:meth:`~symctl.realization.factorization.Factorization.abbreviated`, the
coefficients written :math:`\sigma_k = e_k(\epsilon)`, so that every entry stays
a few terms long at any delay.
"""

_MUSCLE = {f.name: f.default for f in dataclasses.fields(MuscleModel)}
_DELAYS = {
    name: p.default
    for name, p in inspect.signature(augment).parameters.items()
    if name in ("sensor_delay", "actuator_delay")
}


@dataclass(frozen=True)
class PaperSpec:
    r"""The inputs of the paper's derivation, defaulting to the paper's values.

    Parameters
    ----------
    tau, f_max, r_bar, Ts : float
        The muscle's time constant [s], maximum force [N], equilibrium firing
        rate [spikes/s] and the sampling time [s]; defaults are those of
        :class:`~symctl.design.plant.MuscleModel`.
    sensor_delay, actuator_delay : int
        Delays in steps; defaults are those of :func:`~symctl.design.augment.augment`.
    seed : int
        Seed of the random realizations.
    realizations : int
        Random realizations simulated per circuit (the IFP controller has one).

    Examples
    --------
    >>> from symctl.report.spec import PaperSpec
    >>> PaperSpec(tau=0.05).tau, PaperSpec().f_max
    (0.05, 60.0)
    """

    tau: float = _MUSCLE["tau"]
    f_max: float = _MUSCLE["f_max"]
    r_bar: float = _MUSCLE["r_bar"]
    Ts: float = _MUSCLE["dt"]
    sensor_delay: int = _DELAYS["sensor_delay"]
    actuator_delay: int = _DELAYS["actuator_delay"]
    seed: int = 0
    realizations: int = 4


PAPER = PaperSpec()
"""The paper's parameters (the defaults of ``derive_paper`` and ``symctl paper``)."""


@dataclass(frozen=True)
class CircuitSpec:
    """One circuit of the report: its name and how the report titles it.

    Parameters
    ----------
    name : str
        The circuit's name (a kind of :func:`~symctl.neural.firing.circuit_firing`).
    title : str
        Its title in the headings and tables of the derivation.
    diagram : str
        Its title on the structure and circuit diagrams.

    Examples
    --------
    >>> from symctl.report.spec import CIRCUIT_SPECS
    >>> CIRCUIT_SPECS["general"].title
    'G3 G2 G1, general G2'
    """

    name: str
    title: str
    diagram: str


_DIAGRAMS = {"general": "G3 G2 G1, general realization of G2 (symbolic P)"}
_PATHWAYS = CircuitSpec(
    "pathways",
    "G3 G2 G1 along the delay graph's pathways",
    "G3 G2 G1 built along the delay graph's pathways (axons, parallel parts)",
)


def circuit_specs() -> Mapping[str, CircuitSpec]:
    """The report's circuits by name, in reading order: the realizers' circuits, then pathways.

    Titles come from the realizers' registry
    (:data:`~symctl.realization.realizers.REALIZERS`): the whole controller's own
    title, or ``G3 G2 G1, <form> G2``; read at each call, so that a realizer
    registered later is among them.

    Examples
    --------
    >>> from symctl.report.spec import circuit_specs
    >>> circuit_specs()["controllable"].title
    'G3 G2 G1, controllable canonical G2'
    """
    from symctl.realization.realizers import REALIZERS, circuit_names  # not at `symctl --help`

    specs = {}
    for name in circuit_names():
        r = REALIZERS[name]
        title = r.title if r.controller else f"G3 G2 G1, {r.form} G2"
        specs[name] = CircuitSpec(name, title, _DIAGRAMS.get(name, title))
    return MappingProxyType({**specs, _PATHWAYS.name: _PATHWAYS})


def __getattr__(name: str):
    """``CIRCUIT_SPECS`` (:func:`circuit_specs`) and ``CIRCUITS``, the circuits of the report:
    the IFP controller, G3 G2 G1 with each realization of G2, and the structure built along the
    delay graph's pathways (when the graph is not a chain of unit steps); read at each access."""
    if name == "CIRCUIT_SPECS":
        return circuit_specs()
    if name == "CIRCUITS":
        return tuple(circuit_specs())
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
