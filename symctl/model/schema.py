"""The fields of a model file, in one table: :data:`FIELDS` maps a section to its keys (a name
in angle brackets is the user's); the reader refuses any other, ``docs/model-file.md`` has each.

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
    "model": {
        "name": "identifier of the model (letters, digits, _ and -); required",
        "title": "title of the documents (default: the name)",
        "description": "a paragraph that opens the plant section of the derivation",
    },
    "parameters": {"<name>": "a number, or a table {value, unit, description}"},
    "parameter": {  # the keys of one parameter's table
        "value": "the number; required",
        "unit": "its unit (docs/model-file.md, Units)",
        "description": "what it is, for the parameter table",
    },
    "states": {  # array of tables
        "name": "identifier; required",
        "unit": "unit of the state",
        "description": "what it is",
        "rhs": "d(state)/dt as text (safe parser); required unless [discrete]",
        "equilibrium": "value or text in the parameters; solved when absent",
        "guess": "start of the numeric equilibrium search",
    },
    "inputs": {  # array of tables
        "name": "identifier; required",
        "unit": "unit of the input",
        "description": "what it is",
        "equilibrium": "value or text in the parameters (default 0)",
    },
    "outputs": {  # array of tables
        "name": "identifier of the measured output; required",
        "state": "the state it measures (default: the state of the same name)",
        "expr": "or an expression of the states (and parameters) it measures, linearized",
        "unit": "its unit (must be the state's or the expression's where both are known)",
        "description": "what it is",
    },
    "discrete": {
        "A": "state matrix of x(t+1) = A x(t) + B u(t): rows of numbers or text",
        "B": "input matrix",
        "numerator": "transfer function in z, descending powers (instead of A, B)",
        "denominator": "its denominator, descending powers, leading entry nonzero",
    },
    "sampling": {"Ts": "the sampling time: seconds, or {value, unit}; required"},
    "delays": {
        "sensor": "steps, or {steps = k} or {seconds = t} (rounded up to steps)",
        "actuator": "the same for the actuator side",
    },
    "cost": {
        "Q": "state weight: a number (times I), a matrix, or 'identity' (default)",
        "R": "input weight, likewise",
    },
    "noise": {
        "process": "covariance of the noise on the states: a number (times I), a diagonal, a matrix",
        "motor": "covariance of the noise on the inputs, likewise",
        "sensor": "covariance of the measurement noise, likewise, positive definite",
    },
    "delay_graph": {
        "vertices": "array of tables {name, description}",
        "edges": "array of tables {from, to, steps | seconds}",
        "sensor": "the vertex of the sensor, or a list: one per measured state (default: the first)",
        "actuator": "the vertex of the actuator, or a list: one per input (default: the last)",
        "max_wire_delay": "the most steps one wire may carry (default: any; 1 for unit delays)",
    },
    "vertex": {"name": "identifier; required", "description": "what it is"},
    "edge": {
        "from": "a vertex; required",
        "to": "a vertex; required",
        "steps": "the delay in steps",
        "seconds": "or the delay in seconds (rounded up to steps)",
        "description": "what it is",
    },
    "circuits": {
        "build": "which circuits to build, by realizer name (default all, in the registry's order)",
        "realizations": "random realizations simulated per circuit (default 4)",
        "seed": "seed of the random realizations (default 0)",
    },
    "simulation": {
        "steps": "horizon in steps (default 50)",
        "disturbance": "table {state, amplitude, start, length}",
    },
    "disturbance": {
        "state": "the state (or list of states) it is added to (default: every state)",
        "amplitude": "size per step, in the state's unit (default 1)",
        "start": "first step of the pulse (default 5)",
        "length": "steps of the pulse (default 10)",
    },
    "analysis": {
        "longest_delay": "search the longest stabilizable delay: true, or {max, tolerance}"
    },
    "longest_delay": {
        "max": "largest net delay tried, in steps (default 20)",
        "tolerance": "largest final deviation, relative to the peak (default 0.01)",
    },
}
FIELDS = MappingProxyType({k: MappingProxyType(v) for k, v in _FIELDS.items()})
"""Every section (and sub-table) of a model file and its keys, with a line of documentation."""

_SUBTABLES = ("parameter", "vertex", "edge", "disturbance", "longest_delay")  # inside sections
SECTIONS = tuple(k for k in FIELDS if k not in _SUBTABLES)
"""The top-level sections, in the order the documentation gives them."""
