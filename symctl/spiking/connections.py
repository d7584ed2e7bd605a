"""A numeric circuit as a connection list, which every export reads (JSON, nengo, NEST, NIR)."""

from __future__ import annotations

import importlib
import json
import warnings
from pathlib import Path
from typing import NamedTuple

import numpy as np

from symctl._util.validate import float_array, positive_number, to_expr
from symctl.errors import MissingDependencyError, ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit


class _Edge(NamedTuple):
    """``target(t) += weight * source(t - delay)``; ``kind``: ``"self"``, ``"synapse"``, ``"output"``."""

    source: str
    target: str
    weight: float
    delay: int
    kind: str

    @property
    def node(self) -> str:
        """The target's node name: the neuron, or ``"output <name>"``."""
        return f"output {self.target}" if self.kind == "output" else self.target


def _require(module: str):
    """The optional package ``module``, or a MissingDependencyError."""
    try:
        with warnings.catch_warnings():  # nengo 4.1 reads numpy.core, deprecated by NumPy 2
            warnings.simplefilter("ignore", DeprecationWarning)
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


def _samples(circuit: Circuit, u) -> np.ndarray:
    """``u`` as ``(steps, inputs)`` floats, one column per circuit input."""
    u = float_array(u, "u")
    u = u[:, None] if u.ndim == 1 else u
    if u.ndim != 2 or u.shape[1] != len(circuit.inputs):
        raise ParameterError(
            f"u: expected (steps, {len(circuit.inputs)}) samples of {circuit.inputs}, "
            f"got shape {u.shape}"
        )
    return u


def _traces(circuit: Circuit, read) -> dict:
    """Each neuron's trace ``read(name)`` and ``"output"``: the outputs' (side by side if many)."""
    traces = {n.name: read(n.name) for n in circuit.neurons}
    outs = [read(f"output {o.target}") for o in circuit.outputs]
    traces["output"] = outs[0] if len(outs) == 1 else np.stack(outs, axis=1)
    return traces


def _label(circuit: Circuit, name: str) -> str:
    """A neuron's name with its delay-graph vertex (``"G2.x1 @ v2"``), an input's name."""
    vertex = circuit.vertices.get(name)
    return name if vertex is None else f"{name} @ v{vertex}"


def _no_population(**options) -> None:
    """Refuse the options of spiking populations given without ``n_neurons``."""
    for name, value in options.items():
        if value is not None:
            raise ParameterError(f"{name}: needs n_neurons (spiking populations), got None")


FORMAT = "symctl-circuit"  # the "format" field of export_circuit's JSON (version 1)


def export_circuit(circuit: Circuit, path=None, *, dt: float | None = None) -> dict:
    r"""The circuit as a simulator-neutral connection list (JSON types only), written to ``path``.

    Neurons follow :math:`n(t) = \sum_k w_k\, n(t-d_k) + \sum_j v_j\, s_j(t-e_j)`, outputs
    :math:`o(t) = v\, s(t - e)`, from rest::

        {"format": "symctl-circuit", "version": 1, "dt": 0.01 or null, "equation": "...",
         "inputs": ["u", ...],
         "neurons": [{"name", "part", "vertex" (int or null),
                      "self_dynamics": [{"weight", "delay_steps", "delay_s"}, ...]}, ...],
         "synapses": [{"source", "target", "weight", "delay_steps", "delay_s"}, ...],
         "outputs": [{"name", "source" (null: zero), "weight", "delay_steps", "delay_s"}, ...]}

    Parameters
    ----------
    circuit : Circuit
        With numbers for weights.
    path : str or Path, optional
        Where to write the JSON (UTF-8, indented).
    dt : float, optional
        The sampling time :math:`T_s` in seconds (``delay_s = delay_steps * dt``, else null).

    Returns
    -------
    dict

    Raises
    ------
    ParameterError, SymctlTypeError
        Symbols or non-real numbers left in the weights; ``dt`` not > 0; not a Circuit.

    Examples
    --------
    >>> from symctl import Circuit, Structure, export_circuit, first_order_realization
    >>> c = Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 2)))
    >>> data = export_circuit(c, dt=0.01)
    >>> data["neurons"][0]["self_dynamics"]
    [{'weight': 0.5, 'delay_steps': 1, 'delay_s': 0.01}]
    >>> data["synapses"][0]["source"], data["synapses"][0]["weight"], data["outputs"][0]["source"]
    ('u', 2.0, 'x1')
    """
    edges = _edges(circuit)
    outs = {e.target: e for e in edges if e.kind == "output"}
    if dt is not None:
        dt = positive_number(dt, "dt")

    def timed(e: _Edge) -> dict:
        seconds = None if dt is None else e.delay * dt
        return {"weight": e.weight, "delay_steps": e.delay, "delay_s": seconds}

    data = {
        "format": FORMAT,
        "version": 1,
        "dt": dt,
        "equation": "neuron(t) = sum of weight * neuron(t - delay_steps) over its self_dynamics "
        "+ sum of weight * source(t - delay_steps) over the synapses onto it; "
        "output(t) = weight * source(t - delay_steps); every signal 0 before t = 0",
        "inputs": list(circuit.inputs),
        "neurons": [
            {
                "name": n.name,
                "part": n.part,
                "vertex": n.vertex,
                "self_dynamics": [
                    timed(e) for e in edges if e.kind == "self" and e.target == n.name
                ],
            }
            for n in circuit.neurons
        ],
        "synapses": [
            {"source": e.source, "target": e.target} | timed(e)
            for e in edges
            if e.kind == "synapse"
        ],
        "outputs": [
            {"name": o.target, "source": outs[o.target].source} | timed(outs[o.target])
            if o.target in outs
            else {"name": o.target, "source": None, "weight": 0.0, "delay_steps": 0, "delay_s": 0.0}
            for o in circuit.outputs
        ],
    }
    if path is not None:
        Path(path).write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    return data
