r"""The paper's parameters (:data:`PAPER`) and the report's circuits in reading order
(:data:`CIRCUITS`, :data:`CIRCUIT_SPECS`: read from the realizers' registry).

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

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from symctl.derivation.paper import PAPER, PaperSpec
from symctl.derivation.pipeline import SYMBOLIC_P_MAX_ORDER
from symctl.realization.factorization import EXPANDED_ZEROS_MAX

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


@dataclass(frozen=True)
class CircuitSpec:
    """One circuit of the report: its ``name``, its ``title`` in the text, its ``diagram``'s title.

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
    """``CIRCUIT_SPECS`` and ``CIRCUITS``, read from the registry at each access."""
    if name == "CIRCUIT_SPECS":
        return circuit_specs()
    if name == "CIRCUITS":
        return tuple(circuit_specs())
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
