r"""A circuit as a nengo network: one node per neuron, its synapses as delayed connections.

A stylized neuron :math:`n(t) = \sum_k w_k\, n(t-d_k) + \sum_j v_j\, s_j(t-e_j)` is a
passthrough :class:`nengo.Node` (it sums what reaches it) and each term a
:class:`nengo.Connection` with ``transform`` the weight and ``synapse`` the pure delay
:math:`z^{-d}` (a discrete :class:`nengo.LinearFilter`, or ``None`` for no delay): a
delay is an axon, not a filter. Run in nengo's simulator with ``dt`` the circuit's
sampling time :math:`T_s`, step :math:`k + 1` of the network holds the circuit's
:math:`n(k)` when the input node holds :math:`u(k)` (nengo's first step is
:math:`t = dt`): the network reproduces symctl's linear simulation to rounding.
"""

from __future__ import annotations

import numpy as np

from symctl._util.validate import as_generator, bounded_int, float_array, positive_number
from symctl.errors import ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit
from symctl.spiking.connections import _edges, _label, _require

__all__ = ["MAX_POPULATION", "nengo_response", "to_nengo"]

MAX_POPULATION = 10_000
"""Most spiking neurons per population of :func:`to_nengo` (``n_neurons``)."""


def _delay(nengo, steps: int):
    """The pure delay of ``steps`` samples, :math:`z^{-steps}` (``None``: none)."""
    return nengo.LinearFilter([1.0], [1.0] + [0.0] * steps, analog=False) if steps else None


def to_nengo(circuit: Circuit, n_neurons: int | None = None, *, neuron_type=None, rng=None):
    r"""The circuit as a :class:`nengo.Network`, run with ``dt`` the sampling time :math:`T_s`.

    Parameters
    ----------
    circuit : Circuit
        With numbers for weights (e.g. one of :attr:`FiringPatterns.circuits`, or
        :meth:`Circuit.subs`).
    n_neurons : None
        ``None``: every neuron is exact, a non-spiking node.
    neuron_type : None
        Reserved for spiking populations; must be ``None`` with ``n_neurons=None``.
    rng : int, numpy Generator or None
        Seeds the network (``nengo.Network(seed=...)``).

    Returns
    -------
    nengo.Network
        With dicts ``inputs`` (one passthrough node per circuit input: connect your signal
        to it), ``neurons`` (one node per neuron, labelled ``"name @ v<vertex>"``) and
        ``outputs`` (one node per circuit output), by name.

    Raises
    ------
    MissingDependencyError
        nengo is not installed (``pip install symctl[spiking]``).
    ParameterError
        Symbols or non-real numbers left in the weights; ``n_neurons`` outside
        ``[1, MAX_POPULATION]``; a ``neuron_type`` without ``n_neurons``.
    SymctlTypeError
        ``circuit`` is not a Circuit; ``neuron_type`` is not a nengo neuron type.

    Examples
    --------
    >>> from symctl import Circuit, Structure, first_order_realization
    >>> from symctl.spiking.nengo_export import nengo_response, to_nengo
    >>> c = Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 2)))
    >>> net = to_nengo(c)
    >>> sorted(net.neurons), [c.label for c in net.connections]
    (['x1'], ['x1 -> x1 (delay 1)', 'u -> x1 (delay 1)', 'x1 -> output x1 (delay 0)'])
    >>> nengo_response(c, [1.0, 0.0, 0.0])["x1"]
    array([0., 2., 1.])
    """
    edges = _edges(circuit)
    nengo = _require("nengo")
    if neuron_type is not None and not isinstance(neuron_type, nengo.neurons.NeuronType):
        raise SymctlTypeError(
            f"neuron_type: expected a nengo neuron type (e.g. nengo.LIF()), got {neuron_type!r}"
        )
    if n_neurons is not None:
        bounded_int(n_neurons, "n_neurons", 1, MAX_POPULATION)
        raise ParameterError(
            "n_neurons: spiking populations are not available yet; use n_neurons=None"
        )
    if neuron_type is not None:
        raise ParameterError("neuron_type: needs n_neurons (spiking populations), got None")
    seed = int(as_generator(rng, "rng").integers(2**31))
    with nengo.Network(label=repr(circuit), seed=seed) as net:
        net.inputs = {u: nengo.Node(size_in=1, label=u) for u in circuit.inputs}
        net.neurons = {
            n.name: nengo.Node(size_in=1, label=_label(circuit, n.name)) for n in circuit.neurons
        }
        net.outputs = {
            o.target: nengo.Node(size_in=1, label=f"output {o.target}") for o in circuit.outputs
        }
        for e in edges:
            target = net.outputs[e.target] if e.kind == "output" else net.neurons[e.target]
            name = f"output {e.target}" if e.kind == "output" else e.target
            nengo.Connection(
                net.neurons[e.source] if e.source in net.neurons else net.inputs[e.source],
                target,
                transform=e.weight,
                synapse=_delay(nengo, e.delay),
                label=f"{e.source} -> {name} (delay {e.delay})",
            )
    return net


def nengo_response(circuit: Circuit, u, *, dt: float = 1.0) -> dict[str, np.ndarray]:
    r"""Drive :func:`to_nengo`'s network from rest by ``u`` in nengo's reference simulator.

    Parameters
    ----------
    circuit : Circuit
        As for :func:`to_nengo`.
    u : (steps,) or (steps, inputs) array
        The circuit inputs, one row per sample, in ``circuit.inputs`` order.
    dt : float
        The sampling time :math:`T_s` in seconds (only nengo's clock reads it).

    Returns
    -------
    dict of str to array
        Every neuron's trace ``(steps,)`` by name, and ``"output"``: the circuit outputs
        ``(steps,)`` (one output) or ``(steps, outputs)``, as symctl's own simulation gives.

    Raises
    ------
    As :func:`to_nengo`; ParameterError for ``u`` of the wrong width.

    Examples
    --------
    >>> from symctl import Circuit, Structure, first_order_realization
    >>> from symctl.spiking.nengo_export import nengo_response
    >>> c = Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 1)))
    >>> nengo_response(c, [1.0, 0.0, 0.0, 0.0])["x1"]
    array([0.  , 1.  , 0.5 , 0.25])
    """
    dt = positive_number(dt, "dt")
    u = float_array(u, "u")
    u = u[:, None] if u.ndim == 1 else u
    if u.ndim != 2 or u.shape[1] != len(circuit.inputs):
        raise ParameterError(
            f"u: expected (steps, {len(circuit.inputs)}) samples of {circuit.inputs}, "
            f"got shape {u.shape}"
        )
    net = to_nengo(circuit)
    nengo = _require("nengo")
    steps = u.shape[0]
    with net:
        for j, name in enumerate(circuit.inputs):
            column = u[:, j]
            source = nengo.Node(lambda t, c=column: c[min(round(t / dt), steps) - 1])
            nengo.Connection(source, net.inputs[name], synapse=None)
        probes = {n: nengo.Probe(node) for n, node in net.neurons.items()}
        out_probes = [nengo.Probe(net.outputs[o.target]) for o in circuit.outputs]
    with nengo.Simulator(net, dt=dt, progress_bar=False) as sim:
        sim.run_steps(steps)
    traces = {n: sim.data[p][:, 0] for n, p in probes.items()}
    outs = [sim.data[p][:, 0] for p in out_probes]
    traces["output"] = outs[0] if len(outs) == 1 else np.stack(outs, axis=1)
    return traces
