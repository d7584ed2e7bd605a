r"""A circuit as a NIR graph (the neuromorphic intermediate representation, ``nir`` 1.0).

NIR defines every node in continuous time. The stylized neuron
:math:`n(t) = \sum_k w_k\, n(t-d_k) + \sum_j v_j\, s_j(t-e_j)` is a delay-difference
equation, and NIR carries it as one: each neuron is a ``Scale`` node of scale 1 (NIR
sums the edges into a node, so it outputs the sum of its terms), and each term a
``Delay`` node of :math:`d\,T_s` seconds (none for :math:`d = 0`) followed by a
``Linear`` node of the term's weight. With every input held over a sample,
:math:`u(t) = u(k)` on :math:`[kT_s, (k+1)T_s)`, every signal of the graph is held
too, and its value at :math:`t = kT_s` is the circuit's :math:`n(k)`: the export is
exact for every circuit, whatever its self-dynamics (:math:`a \le 0` and
:math:`a = 1` included).

NIR's ``LI`` and ``Integrator`` nodes do not carry a neuron exactly: an ``LI`` of
:math:`\tau = -T_s/\ln a` and :math:`R = 1/(1-a)` steps :math:`x(k+1) = a\,x(k) + I`
only when its input :math:`I` is held over the sample (and :math:`a = 1` is an
``Integrator``, :math:`a \le 0` has no such :math:`\tau`), but another neuron's output
is a continuous trace, not a held one, and NIR has no sample-and-hold node.

**Spiking populations** (``n_neurons=N``) are those of
:func:`~symctl.spiking.nengo_export.to_nengo`, built by nengo: the neuron's sum drives
an ``Affine`` node (nengo's encoders times gains over the radius, and its biases) into
a ``LIF`` node of :math:`N` neurons (:math:`\tau` nengo's ``tau_rc``, :math:`R = 1`,
leak and reset 0, threshold 1: nengo's LIF in continuous time), whose spikes
(unit-area events) go through a ``Linear`` node (the decoders) and an ``LI`` node (the
postsynaptic lowpass, :math:`\tau = T_s/5`, :math:`R = 1`) to the neuron's axon. NIR's
``LIF`` has no refractory period and no voltage floor, so the populations' neurons are
``nengo.LIF(tau_ref=0, min_voltage=-inf)``, and another neuron type is refused. The
decoders are solved for these neurons; the graph is as approximate as nengo's network,
and a NIR simulator's discretization and spike timing decide how close its run comes.
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
    r"""The circuit as a :class:`nir.NIRGraph`: exact delay-sum neurons, or LIF populations.

    Parameters
    ----------
    circuit : Circuit
        With numbers for weights.
    n_neurons : int, optional
        ``None``: every neuron exact (module text). An int in
        ``[1, MAX_POPULATION]``: a population of that many LIF neurons per neuron.
    dt : float
        The sampling time :math:`T_s` in seconds (the delays' unit).
    rng : int, numpy Generator or None
        Seeds nengo's encoders, gains and biases (only with ``n_neurons``).
    neuron_type : nengo.LIF, optional
        Only ``nengo.LIF(tau_ref=0, min_voltage=-np.inf)`` (the default), with
        ``tau_rc`` free: NIR's LIF has no refractory period and no voltage floor.
    radius : dict of str to float, optional
        Each population's radius, as for :func:`~symctl.spiking.nengo_export.to_nengo`.

    Returns
    -------
    nir.NIRGraph
        Nodes named after the circuit: an ``Input`` per input, a node per neuron (its
        sum, with its ``label`` ``"name @ v<vertex>"`` in metadata), ``"<source> -> <target>
        (delay <d>) delay"`` / ``"... weight"`` per term, an ``Output`` ``"output <name>"``
        per output; spiking, ``"<neuron> encoders"``, ``"<neuron> LIF"``,
        ``"<neuron> decoders"`` and ``"<neuron> synapse"`` per neuron. ``metadata["dt"]``
        is ``dt``.

    Raises
    ------
    MissingDependencyError
        nir (or, with ``n_neurons``, nengo) is not installed (``pip install symctl[spiking]``).
    ParameterError
        Symbols or non-real numbers left in the weights; ``dt`` not > 0; ``n_neurons``
        outside ``[1, MAX_POPULATION]``; a ``neuron_type`` with a refractory period or a
        voltage floor, or one or a ``radius`` without ``n_neurons``.
    SymctlTypeError
        ``circuit`` is not a Circuit; ``neuron_type`` is not a nengo LIF.

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
