r"""A circuit as a nengo network: one node per neuron, its terms as delayed connections.

Each neuron is a passthrough :class:`nengo.Node`, each term a :class:`nengo.Connection` of
``transform`` its weight and ``synapse`` the pure delay :math:`z^{-d}`; run with ``dt``
:math:`= T_s`, step :math:`k + 1` holds the circuit's :math:`n(k)`. **Spiking populations**
(``n_neurons=N``) follow the Neural Engineering Framework [1]_: each neuron's sum drives
:math:`N` spiking neurons representing :math:`[-r, r]`, decoded by least squares through an
uncompensated lowpass of :math:`T_s/5` (that lag and the spike noise are what
:func:`~symctl.spiking.loop.spiking_response` measures), at ``SUBSTEPS`` simulator steps per
sample (the delay networks of [2]_ would use populations for the delays).

References
----------
.. [1] C. Eliasmith and C. H. Anderson, *Neural Engineering: Computation, Representation, and
   Dynamics in Neurobiological Systems*, MIT Press, 2003.
.. [2] A. R. Voelker and C. Eliasmith, "Improving spiking dynamical networks: accurate delays,
   higher-order synapses, and time cells", *Neural Computation* 30(3), 569-609, 2018.
"""

from __future__ import annotations

import numpy as np

from symctl._util.validate import as_generator, bounded_int, positive_number
from symctl.errors import ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit
from symctl.neural.simulate import pulse
from symctl.spiking.connections import _edges, _label, _no_population, _require, _samples, _traces

__all__ = ["MAX_POPULATION", "SUBSTEPS", "TAU_FRACTION", "nengo_response", "to_nengo"]

MAX_POPULATION = 10_000  # most spiking neurons per population
SUBSTEPS = 10  # simulator steps per sample of a spiking network (dt = Ts / SUBSTEPS)
TAU_FRACTION = 0.2  # a population's postsynaptic lowpass, as a fraction of Ts
RADIUS_MARGIN = 1.2  # a population's default radius: this times its neuron's linear peak


def _delay(nengo, steps: int):
    """The pure delay :math:`z^{-steps}` (``None`` for 0)."""
    return nengo.LinearFilter([1.0], [1.0] + [0.0] * steps, analog=False) if steps else None


def _radii(circuit: Circuit, traces: dict) -> dict[str, float]:
    """``RADIUS_MARGIN`` times each neuron's peak |trace| (1 for a neuron that never moves)."""
    peaks = {n.name: float(np.max(np.abs(traces[n.name]))) for n in circuit.neurons}
    return {name: RADIUS_MARGIN * p if p > 0 else 1.0 for name, p in peaks.items()}


def to_nengo(
    circuit: Circuit,
    n_neurons: int | None = None,
    *,
    neuron_type=None,
    rng=None,
    dt: float = 0.01,
    radius=None,
):
    r"""The circuit (numbers for weights) as a :class:`nengo.Network` (module text).

    ``n_neurons``: ``None`` for exact nodes (run with ``dt``, the sampling time in seconds),
    else that many spiking neurons per neuron, at most ``MAX_POPULATION`` (run with
    ``dt / SUBSTEPS``), of ``neuron_type`` (default ``nengo.LIF()``) and ``radius`` by neuron
    name (default ``RADIUS_MARGIN`` times the peak of its linear response to a pulse); ``rng``
    seeds encoders, gains and biases. The network has dicts by name: ``inputs``, ``neurons``
    (their sums, labelled ``"name @ v<vertex>"``), ``axons`` (the node, or its population's
    filtered decoded value), ``populations`` (empty when exact) and ``outputs``.

    Raises MissingDependencyError without nengo; ParameterError for symbols left in the
    weights, ``n_neurons`` out of range, ``neuron_type`` or ``radius`` without ``n_neurons``;
    SymctlTypeError for a ``circuit`` or ``neuron_type`` of another type.

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
    >>> len(to_nengo(c, 50, rng=1).populations["x1"].neurons)
    50
    """
    edges = _edges(circuit)
    nengo = _require("nengo")
    if neuron_type is not None and not isinstance(neuron_type, nengo.neurons.NeuronType):
        raise SymctlTypeError(
            f"neuron_type: expected a nengo neuron type (e.g. nengo.LIF()), got {neuron_type!r}"
        )
    dt = positive_number(dt, "dt")
    seed = int(as_generator(rng, "rng").integers(2**31))
    if n_neurons is None:
        _no_population(neuron_type=neuron_type, radius=radius)
        return _network(nengo, circuit, edges, seed)
    n_neurons = bounded_int(n_neurons, "n_neurons", 1, MAX_POPULATION)
    if radius is None:
        from symctl.neural.firing import _drive

        radius = _radii(circuit, _drive(circuit, pulse(size=len(circuit.inputs))))
    else:
        names = [n.name for n in circuit.neurons]
        if not isinstance(radius, dict) or sorted(radius) != sorted(names):
            raise ParameterError(f"radius: expected a dict of a radius for each of {names}")
        radius = {k: positive_number(v, f"radius[{k!r}]") for k, v in radius.items()}
    spiking = (n_neurons, neuron_type or nengo.LIF(), radius, TAU_FRACTION * dt)
    return _network(nengo, circuit, edges, seed, spiking)


def _network(nengo, circuit: Circuit, edges, seed: int, spiking=None):
    """:func:`to_nengo`'s network; ``spiking``: ``(n_neurons, neuron_type, radii, tau)``."""
    with nengo.Network(label=repr(circuit), seed=seed) as net:
        net.inputs = {u: nengo.Node(size_in=1, label=u) for u in circuit.inputs}
        net.neurons = {
            n.name: nengo.Node(size_in=1, label=_label(circuit, n.name)) for n in circuit.neurons
        }
        net.outputs = {
            o.target: nengo.Node(size_in=1, label=f"output {o.target}") for o in circuit.outputs
        }
        net.axons, net.populations = dict(net.neurons), {}
        if spiking is not None:
            size, kind, radii, tau = spiking
            for name, node in net.neurons.items():
                ens = nengo.Ensemble(size, 1, radius=radii[name], neuron_type=kind, label=name)
                nengo.Connection(node, ens, synapse=None)
                axon = nengo.Node(size_in=1, label=f"{name} axon")
                nengo.Connection(ens, axon, synapse=nengo.Lowpass(tau))
                net.populations[name], net.axons[name] = ens, axon
        substeps = 1 if spiking is None else SUBSTEPS
        for e in edges:
            nengo.Connection(
                net.axons[e.source] if e.source in net.axons else net.inputs[e.source],
                net.outputs[e.target] if e.kind == "output" else net.neurons[e.target],
                transform=e.weight,
                synapse=_delay(nengo, e.delay * substeps),
                label=f"{e.source} -> {e.node} (delay {e.delay})",
            )
    return net


def nengo_response(circuit: Circuit, u, *, dt: float = 1.0) -> dict[str, np.ndarray]:
    r"""Each neuron's trace ``(steps,)`` and ``"output"`` ``(steps[, outputs])`` of :func:`to_nengo`'s
    network driven from rest by ``u`` ``(steps[, inputs])`` in nengo's simulator (clock ``dt``).

    Examples
    --------
    >>> from symctl import Circuit, Structure, first_order_realization
    >>> from symctl.spiking.nengo_export import nengo_response
    >>> c = Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 1)))
    >>> nengo_response(c, [1.0, 0.0, 0.0, 0.0])["x1"]
    array([0.  , 1.  , 0.5 , 0.25])
    """
    dt = positive_number(dt, "dt")
    u = _samples(circuit, u)
    net = to_nengo(circuit)
    nengo = _require("nengo")
    steps = u.shape[0]
    with net:
        for j, name in enumerate(circuit.inputs):
            column = u[:, j]
            source = nengo.Node(lambda t, c=column: c[min(round(t / dt), steps) - 1])
            nengo.Connection(source, net.inputs[name], synapse=None)
        probes = {n: nengo.Probe(node) for n, node in net.neurons.items()}
        probes |= {f"output {t}": nengo.Probe(node) for t, node in net.outputs.items()}
    with nengo.Simulator(net, dt=dt, progress_bar=False) as sim:
        sim.run_steps(steps)
    return _traces(circuit, lambda name: sim.data[probes[name]][:, 0])
