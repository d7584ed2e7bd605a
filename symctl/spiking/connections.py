"""A numeric circuit as a connection list: every self-term, synapse and output as one edge.

The simulators' exports read a :class:`~symctl.neural.circuit.Circuit` through
:func:`_edges`, so that each one sees the same numbers in the same order.
"""

from __future__ import annotations

import importlib
from typing import NamedTuple

from symctl._util.validate import to_expr
from symctl.errors import MissingDependencyError, ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit


class _Edge(NamedTuple):
    """``target(t) += weight * source(t - delay)``; ``kind``: ``"self"``, ``"synapse"``, ``"output"``."""

    source: str
    target: str
    weight: float
    delay: int
    kind: str


def _require(module: str):
    """The optional package ``module``, or a MissingDependencyError saying how to install it."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise MissingDependencyError(
            f"{module} is not installed: pip install symctl[spiking] (or pip install {module})"
        ) from exc


def _edges(circuit: Circuit, argname: str = "circuit") -> list[_Edge]:
    """The circuit's edges in neuron order (self-terms, then synapses), then its outputs."""
    if not isinstance(circuit, Circuit):
        raise SymctlTypeError(f"{argname}: expected a Circuit, got {type(circuit).__name__}")
    left = sorted(map(str, circuit.free_symbols))
    if left:
        raise ParameterError(
            f"{argname}: the weights still contain {left}; substitute numbers first (subs())"
        )

    def edge(s, kind: str) -> _Edge:
        w = to_expr(s.weight, "weight")
        if not w.is_real:
            raise ParameterError(
                f"{argname}: the weight {s.source} -> {s.target} is {w}, not a real number"
            )
        return _Edge(s.source, s.target, float(w), int(s.delay), kind)

    out = []
    for n in circuit.neurons:
        out += [edge(s, "self") for s in n.self_terms]
        out += [edge(s, "synapse") for s in n.synapses]
    return out + [edge(s, "output") for s in circuit.outputs if s.source != "0"]


def _label(circuit: Circuit, name: str) -> str:
    """A neuron's name with its delay-graph vertex (``"G2.x1 @ v2"``), an input's name."""
    vertex = circuit.vertices.get(name)
    return name if vertex is None else f"{name} @ v{vertex}"
