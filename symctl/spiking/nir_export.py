r"""A circuit as a NIR graph (the neuromorphic intermediate representation, ``nir`` 1.0).

A ``Scale`` node of scale 1 per neuron (NIR sums the edges into a node), per term a ``Delay``
node of :math:`d\,T_s` seconds (none for :math:`d = 0`) and a ``Linear`` node of its weight:
with every input held over a sample, every signal equals the circuit's :math:`n(k)` at
:math:`t = kT_s` (NIR has no sample-and-hold node, and an ``LI`` node would need a held input).

**Spiking populations** (``n_neurons=N``) are :func:`~symctl.spiking.nengo_export.to_nengo`'s:
an ``Affine`` node (encoders times gains over the radius, and biases), a ``LIF`` node of
:math:`N` neurons (:math:`R = 1`, leak and reset 0, threshold 1), a ``Linear`` node (the
decoders) and an ``LI`` node (the lowpass). NIR's ``LIF`` has no refractory period and no
voltage floor, so the neurons are ``nengo.LIF(tau_ref=0, min_voltage=-inf)``.
"""

from __future__ import annotations

import itertools

import numpy as np

from symctl._util.validate import positive_number
from symctl.errors import ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit
from symctl.spiking.connections import _edges, _label, _no_population, _require

__all__ = ["to_nir"]


def to_nir(
    circuit: Circuit,
    n_neurons: int | None = None,
    *,
    dt: float = 0.01,
    rng=None,
    neuron_type=None,
    radius=None,
):
    """The circuit as a :class:`nir.NIRGraph`: exact delay-sum neurons, or LIF populations.

    Options and errors as for :func:`~symctl.spiking.nengo_export.to_nengo`, but
    ``neuron_type`` only ``nengo.LIF(tau_ref=0, min_voltage=-np.inf)`` (the default). Nodes:
    an ``Input`` per input, one per neuron (``"name @ v<vertex>"`` in its metadata),
    ``"<source> -> <target> (delay <d>) delay"`` / ``"... weight"`` per term, an ``Output``
    ``"output <name>"`` per output; spiking, ``"<neuron> encoders"``, ``"... LIF"``,
    ``"... decoders"`` and ``"... synapse"``. ``metadata["dt"]`` is ``dt``.

    Examples
    --------
    >>> from symctl import Circuit, Structure, first_order_realization
    >>> from symctl.spiking.nir_export import to_nir
    >>> c = Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 2)))
    >>> g = to_nir(c)
    >>> g.nodes["x1 -> x1 (delay 1) delay"].delay, g.nodes["x1 -> x1 (delay 1) weight"].weight
    (array([0.01]), array([[0.5]]))
    >>> g.nodes["u -> x1 (delay 1) weight"].weight, sorted(g.outputs)
    (array([[2.]]), ['output x1'])
    """
    edges = _edges(circuit)
    nir = _require("nir")
    dt = positive_number(dt, "dt")
    one = np.ones(1)
    nodes = {u: nir.Input(np.array([1])) for u in circuit.inputs}
    for n in circuit.neurons:
        nodes[n.name] = nir.Scale(one, metadata={"label": _label(circuit, n.name)})
    nodes |= {f"output {o.target}": nir.Output(np.array([1])) for o in circuit.outputs}
    links = []
    axon = {u: u for u in circuit.inputs} | {n.name: n.name for n in circuit.neurons}
    if n_neurons is None:
        _no_population(neuron_type=neuron_type, radius=radius)
    else:
        links += _populations(nir, circuit, n_neurons, dt, rng, neuron_type, radius, nodes, axon)
    for e in edges:
        name = f"{e.source} -> {e.node} (delay {e.delay})"
        nodes[f"{name} weight"] = nir.Linear(np.array([[e.weight]]))
        chain = [axon[e.source], f"{name} weight", e.node]
        if e.delay:
            nodes[f"{name} delay"] = nir.Delay(np.array([e.delay * dt]))
            chain.insert(1, f"{name} delay")
        links += list(itertools.pairwise(chain))
    return nir.NIRGraph(nodes, links, metadata={"dt": dt})


def _populations(nir, circuit, n_neurons, dt, rng, neuron_type, radius, nodes, axon) -> list:
    """Add each neuron's encoders, LIF, decoders and synapse to ``nodes``; their edges."""
    from symctl.spiking.nengo_export import SUBSTEPS, to_nengo

    nengo = _require("nengo")
    kind = nengo.LIF(tau_ref=0, min_voltage=-np.inf) if neuron_type is None else neuron_type
    if type(kind) is not nengo.LIF:  # not a subclass either: AdaptiveLIF adapts
        raise SymctlTypeError(f"neuron_type: expected a nengo.LIF, got {kind!r}")
    if kind.tau_ref != 0 or kind.min_voltage != -np.inf:
        raise ParameterError(
            f"neuron_type: NIR's LIF has no refractory period and no voltage floor; "
            f"expected nengo.LIF(tau_ref=0, min_voltage=-np.inf), got {kind!r}"
        )
    net = to_nengo(circuit, n_neurons, neuron_type=kind, rng=rng, dt=dt, radius=radius)
    model = nengo.builder.Model(dt=dt / SUBSTEPS)
    nengo.builder.Builder.build(model, net)
    links = []
    for name, ens in net.populations.items():
        built = model.params[ens]
        (decode,) = [c for c in net.all_connections if c.pre_obj is ens]
        n = ens.n_neurons
        stages = {
            f"{name} encoders": nir.Affine(built.scaled_encoders, built.bias),
            f"{name} LIF": nir.LIF(
                np.full(n, kind.tau_rc), np.ones(n), np.zeros(n), np.ones(n), np.zeros(n)
            ),
            f"{name} decoders": nir.Linear(kind.amplitude * model.params[decode].weights),
            f"{name} synapse": nir.LI(np.array([decode.synapse.tau]), np.ones(1), np.zeros(1)),
        }
        nodes |= stages
        chain = [name, *stages]
        links += list(itertools.pairwise(chain))
        axon[name] = f"{name} synapse"
    return links
