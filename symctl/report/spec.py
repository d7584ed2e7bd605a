r"""The paper's parameters (:data:`PAPER`) and the report's circuits in reading order
(:data:`CIRCUITS`, :data:`CIRCUIT_SPECS`: read from the realizers' registry at each access)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from symctl.derivation.paper import PAPER
from symctl.derivation.paper import PaperSpec as PaperSpec  # still importable here
from symctl.derivation.pipeline import SYMBOLIC_P_MAX_ORDER as SYMBOLIC_P_MAX_ORDER
from symctl.realization.factorization import EXPANDED_ZEROS_MAX

__all__ = ["CIRCUITS", "CIRCUIT_SPECS", "EXPANDED_ZEROS_MAX", "PAPER", "SCHEMA_VERSION"]

CIRCUITS: tuple[str, ...]  # read from the registry at each access (__getattr__)
CIRCUIT_SPECS: Mapping  # likewise

SCHEMA_VERSION = 1  # of results.json (docs/guide/paper.md)


@dataclass(frozen=True)
class CircuitSpec:
    """One circuit of the report: its ``name`` and its ``title`` in the text."""

    name: str
    title: str


def circuit_specs() -> Mapping[str, CircuitSpec]:
    """The report's circuits by name, in reading order: the realizers' circuits, then pathways."""
    from symctl.realization.realizers import REALIZERS, circuit_names  # not at `symctl --help`

    specs = {}
    for name in circuit_names():
        r = REALIZERS[name]
        specs[name] = CircuitSpec(name, r.title if r.controller else f"G3 G2 G1, {r.form} G2")
    specs["pathways"] = CircuitSpec("pathways", "G3 G2 G1 along the delay graph's pathways")
    return MappingProxyType(specs)


def __getattr__(name: str):
    if name == "CIRCUIT_SPECS":
        return circuit_specs()
    if name == "CIRCUITS":
        return tuple(circuit_specs())
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
