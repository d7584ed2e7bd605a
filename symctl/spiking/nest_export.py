r"""A circuit in NEST: each neuron a linear rate transformer, each term a rate connection.

NEST's ``rate_transformer_lin`` (gain 1, linear summation) sums the rates it receives: the
stylized neuron exactly; what differs is time. Measured in NEST 3.10 at resolution
:math:`h = T_s`, a ``rate_connection_instantaneous`` lags one step, a
``rate_connection_delayed`` of delay :math:`D h` lags :math:`D + 1`, and a
``step_rate_generator`` through one lags :math:`D - 1` after its amplitude time: no lag is 0,
so a term of delay 0 (an output sum :math:`y = M x + N u`) cannot be copied one to one.

The export **retimes** the circuit: neuron :math:`n` runs :math:`L_n` steps late (NEST's step
:math:`k` holds :math:`n(k - L_n)`), and a term :math:`s \to n` of delay :math:`e` becomes a
connection of lag :math:`e + L_n - L_s \ge 1` (2 from an input's generator). The smallest lags
of these difference constraints are shortest paths (Bellman-Ford); they exist exactly when
every loop has at least as many unit delays as neurons, which every state-space realization
satisfies (each state update delays one step). The traces then equal symctl's to rounding.
"""

from __future__ import annotations

import os
from typing import NamedTuple

import networkx as nx
import numpy as np

from symctl._util.validate import positive_number
from symctl.errors import ParameterError
from symctl.neural.circuit import Circuit
from symctl.spiking.connections import _edges, _require, _samples, _traces

__all__ = ["NestNetwork", "nest_response", "to_nest"]

GENERATOR_LAG = 2  # a step_rate_generator's lag: read at step k, it arrives as step k - 2


class NestNetwork(NamedTuple):
    """:func:`to_nest`'s nodes by name, and ``lags``: step ``k`` of node ``n`` holds ``n(k - lags[n])``."""

    neurons: dict
    outputs: dict
    inputs: dict
    lags: dict


def _nest():
    """NEST, quiet (no banner, errors only)."""
    os.environ.setdefault("PYNEST_QUIET", "1")
    nest = _require("nest")
    nest.verbosity = nest.VerbosityLevel.ERROR
    return nest


def _lags(circuit: Circuit, edges) -> dict[str, int]:
    """The smallest lags with every connection's at least 1 (2 from an input), module text."""
    nodes = [*circuit.inputs, *(n.name for n in circuit.neurons)]
    nodes += [f"output {o.target}" for o in circuit.outputs]
    # L_s - L_t <= e - least(s): an arc t -> s of that length; every node starts at 0
    least = {u: GENERATOR_LAG for u in circuit.inputs}
    graph, start = nx.MultiDiGraph(), object()
    graph.add_weighted_edges_from((start, n, 0) for n in nodes)
    graph.add_weighted_edges_from(
        (e.node, e.source, e.delay - least.get(e.source, 1)) for e in edges
    )
    try:
        lag = nx.single_source_bellman_ford_path_length(graph, start)
    except nx.NetworkXUnbounded:
        raise ParameterError(
            "circuit: a loop has fewer unit delays than neurons, and NEST's rate "
            "connections delay every value by at least one step"
        ) from None
    # every neuron at least 1 step late, every input at least 0 (its generator starts after 0)
    low = min(lag[n] for n in nodes if n not in circuit.inputs)
    shift = max(1 - low, -min((lag[u] for u in circuit.inputs), default=0))
    return {n: lag[n] + shift for n in nodes}


def to_nest(circuit: Circuit, *, dt: float = 0.01) -> NestNetwork:
    r"""Build the circuit (numbers for weights) in NEST's kernel, reset to the resolution ``dt``
    (the sampling time in seconds); :func:`nest_response` drives it. Raises
    MissingDependencyError without NEST, ParameterError for symbols left in the weights or a
    loop with fewer delays than neurons, SymctlTypeError for a ``circuit`` of another type.

    Examples
    --------
    >>> from symctl import Circuit, Structure, first_order_realization
    >>> from symctl.spiking.nest_export import to_nest
    >>> c = Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 2)))
    >>> to_nest(c).lags
    {'u': 0, 'x1': 1, 'output x1': 2}
    """
    edges = _edges(circuit)
    dt = positive_number(dt, "dt")
    lags = _lags(circuit, edges)
    nest = _nest()
    nest.ResetKernel()
    nest.resolution = 1000.0 * dt
    # the generators first: one created after the neurons reaches them two steps later (measured)
    inputs = {u: nest.Create("step_rate_generator") for u in circuit.inputs}
    linear = {"g": 1.0, "linear_summation": True}
    net = NestNetwork(
        {n.name: nest.Create("rate_transformer_lin", params=linear) for n in circuit.neurons},
        {
            f"output {o.target}": nest.Create("rate_transformer_lin", params=linear)
            for o in circuit.outputs
        },
        inputs,
        lags,
    )
    nodes = {**net.neurons, **net.outputs, **net.inputs}
    for e in edges:
        lag = e.delay + lags[e.node] - lags[e.source]
        if lag == 1:
            spec = {"synapse_model": "rate_connection_instantaneous", "weight": e.weight}
        else:
            spec = {"synapse_model": "rate_connection_delayed", "weight": e.weight}
            spec["delay"] = (lag - 1) * nest.resolution
        nest.Connect(nodes[e.source], nodes[e.node], syn_spec=spec)
    return net


def nest_response(circuit: Circuit, u, *, dt: float = 0.01) -> dict[str, np.ndarray]:
    r"""The traces of :func:`to_nest`'s network driven by ``u``, as ``nengo_response`` gives them.

    Examples
    --------
    >>> from symctl import Circuit, Structure, first_order_realization
    >>> from symctl.spiking.nest_export import nest_response
    >>> c = Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 1)))
    >>> nest_response(c, [1.0, 0.0, 0.0, 0.0])["x1"]
    array([0.  , 1.  , 0.5 , 0.25])
    """
    u = _samples(circuit, u)
    net = to_nest(circuit, dt=dt)
    nest = _nest()
    h, steps = nest.resolution, u.shape[0]
    for j, (name, gen) in enumerate(net.inputs.items()):
        first = net.lags[name] + GENERATOR_LAG  # the step whose amplitude reaches as u(0)
        times = h * np.arange(first, first + steps)
        gen.set(amplitude_times=list(times), amplitude_values=list(u[:, j]))
    meters = {}
    for name, node in {**net.neurons, **net.outputs}.items():
        meters[name] = nest.Create("multimeter", params={"record_from": ["rate"], "interval": h})
        nest.Connect(meters[name], node)
    nest.Simulate(h * (steps + max(net.lags.values()) + 1))

    def trace(name: str) -> np.ndarray:  # the circuit's steps 0..steps-1 of a node
        rate = meters[name].events["rate"]  # rate[i]: NEST step i + 1
        return rate[net.lags[name] - 1 : net.lags[name] - 1 + steps]

    return _traces(circuit, trace)
