"""The fields of a model file, in one table: :data:`FIELDS` maps a section to its keys (a name
in angle brackets is the user's); the reader refuses any other; ``docs/model-file.md`` has each.

>>> from symctl.model.schema import FIELDS
>>> sorted(FIELDS)[:4]
['analysis', 'circuits', 'cost', 'delay_graph']
>>> "rhs" in FIELDS["states"]
True
"""

from __future__ import annotations

from types import MappingProxyType

from symctl.realization.realizers import circuit_names

__all__ = ["CIRCUIT_KINDS", "FIELDS", "SECTIONS"]

CIRCUIT_KINDS: tuple[str, ...]  # read from the registry at each access (__getattr__)


def __getattr__(name: str):
    """``CIRCUIT_KINDS``: the circuits ``[circuits] build`` takes, read from the registry."""
    if name == "CIRCUIT_KINDS":
        return circuit_names()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


_FIELDS = {
    "model": ("name", "title", "description"),
    "parameters": ("<name>",),
    "parameter": ("value", "unit", "description"),
    "states": ("name", "unit", "description", "rhs", "equilibrium", "guess"),
    "inputs": ("name", "unit", "description", "equilibrium"),
    "outputs": ("name", "state", "expr", "unit", "description"),
    "discrete": ("A", "B", "numerator", "denominator"),
    "sampling": ("Ts",),
    "delays": ("sensor", "actuator"),
    "cost": ("Q", "R"),
    "noise": ("process", "motor", "sensor"),
    "delay_graph": ("vertices", "edges", "sensor", "actuator", "max_wire_delay"),
    "vertex": ("name", "description"),
    "edge": ("from", "to", "steps", "seconds", "description"),
    "circuits": ("build", "realizations", "seed"),
    "simulation": ("steps", "disturbance"),
    "disturbance": ("state", "amplitude", "start", "length"),
    "analysis": ("longest_delay",),
    "longest_delay": ("max", "tolerance"),
}
FIELDS = MappingProxyType(_FIELDS)
"""Every section (and sub-table) of a model file and its keys (each documented in docs/model-file.md)."""

_SUBTABLES = ("parameter", "vertex", "edge", "disturbance", "longest_delay")  # inside sections
SECTIONS = tuple(k for k in FIELDS if k not in _SUBTABLES)
"""The top-level sections, in the order the documentation gives them."""
