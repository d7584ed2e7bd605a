"""Circuit.to_nir: the graph read back from its file, and its equations run, are the circuit.

``nir_response`` runs a NIR graph read back from disk by NIR's node equations alone, on a
grid four times finer than the sampling time; test_exports runs it on every circuit family.
"""

from __future__ import annotations

import dataclasses
import graphlib
import itertools

import numpy as np
import pytest
import sympy as sp
from helpers import need_spiking

from symctl import (
    Circuit,
    ParameterError,
    Structure,
    SymctlTypeError,
    first_order_realization,
    pulse,
)
from symctl.neural.firing import _deviation, _drive
from symctl.spiking.connections import _label
from symctl.spiking.nengo_export import MAX_POPULATION

nir = need_spiking("nir")
DT, FINE = 0.01, 4


def _read_back(graph, tmp_path):
    nir.write(tmp_path / "circuit.nir", graph)
    return nir.read(tmp_path / "circuit.nir")


def nir_response(circuit: Circuit, u: np.ndarray, graph=None, fine: int = 4) -> dict:
    """to_nir's graph (or ``graph``), written and read back, run from rest by NIR's node
    equations on a grid ``fine`` times finer than Ts, with ``u`` held over each sample."""
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        graph = _read_back(circuit.to_nir(dt=DT) if graph is None else graph, Path(folder))
    u = u[:, None] if u.ndim == 1 else u
    h, steps = DT / fine, u.shape[0] * fine
    into = {name: [s for s, t in graph.edges if t == name] for name in graph.nodes}
    stateful = (nir.Delay, nir.LIF, nir.LI)  # their output now depends on the past only
    now = {n: set() if isinstance(graph.nodes[n], stateful) else set(into[n]) for n in into}
    order = list(graphlib.TopologicalSorter(now).static_order())
    out = {n: np.zeros((steps, graph.nodes[n].output_type["output"][0])) for n in graph.nodes}
    state = {n: np.zeros_like(out[n][0]) for n in graph.nodes}
    held = {name: np.repeat(u[:, j], fine) for j, name in enumerate(circuit.inputs)}

    def summed(name, j):
        return sum((out[s][j] for s in into[name]), np.zeros_like(out[into[name][0]][j]))

    for j in range(steps):
        for name in order:
            node = graph.nodes[name]
            if isinstance(node, nir.Input):
                out[name][j] = held[name][j]
            elif isinstance(node, nir.Delay):
                lag = round(float(node.delay[0]) / h)
                assert lag * h == pytest.approx(float(node.delay[0]), abs=1e-15)
                out[name][j] = summed(name, j - lag) if j >= lag else 0.0
            elif isinstance(node, nir.LIF):  # spikes as unit-area events: height 1/h
                out[name][j] = (state[name] > node.v_threshold) / h
                state[name] = np.where(out[name][j] > 0, node.v_reset, state[name])
            elif isinstance(node, nir.LI):
                out[name][j] = state[name]
            else:
                x = summed(name, j)
                out[name][j] = {
                    nir.Scale: lambda n, x: n.scale * x,
                    nir.Linear: lambda n, x: n.weight @ x,
                    nir.Affine: lambda n, x: n.weight @ x + n.bias,
                    nir.Output: lambda n, x: x,
                }[type(node)](node, x)
        for name in order:  # tau v' = v_leak - v + R I, exact over a step with I held
            node = graph.nodes[name]
            if isinstance(node, (nir.LIF, nir.LI)):
                decay = np.exp(-h / node.tau)
                steady = node.v_leak + node.r * summed(name, j)
                state[name] = steady + (state[name] - steady) * decay
    traces = {n.name: out[n.name][::fine, 0] for n in circuit.neurons}
    outs = [out[f"output {o.target}"][::fine, 0] for o in circuit.outputs]
    traces["output"] = outs[0] if len(outs) == 1 else np.stack(outs, axis=1)
    return traces


def _first_order(a=0.5) -> Circuit:
    return Circuit.from_structure(Structure.from_realization(first_order_realization(a, 2)))


def _same_graph(a, b) -> None:
    """Equal nodes (type, every parameter, metadata), edges and graph metadata."""
    assert sorted(a.nodes) == sorted(b.nodes)
    assert sorted(a.edges) == sorted(b.edges)
    assert a.metadata == b.metadata
    for name, node in a.nodes.items():
        other = b.nodes[name]
        assert type(node) is type(other), name
        for field in dataclasses.fields(node):
            np.testing.assert_array_equal(
                getattr(node, field.name), getattr(other, field.name), err_msg=name
            )


def test_the_exact_graph_reads_back_equal(derived_T2, tmp_path):
    symbolic = derived_T2.circuits["observable"].circuit  # placed at its vertices
    placed = symbolic.subs({s: sp.Rational(1, 3) for s in symbolic.free_symbols})
    assert None not in placed.vertices.values()
    for circuit in (placed, *derived_T2.circuits["general"].firing.circuits):
        graph = circuit.to_nir(dt=DT)
        _same_graph(graph, _read_back(graph, tmp_path))
        labels = [graph.nodes[n.name].metadata["label"] for n in circuit.neurons]
        assert labels == [_label(circuit, n.name) for n in circuit.neurons]


@pytest.mark.parametrize("a", [-0.5, 0.0, 1.0])
def test_a_neuron_without_a_continuous_time_leak_is_still_exact(a):
    """a <= 0 and a = 1 have no LI equivalent; as a delay loop they are the circuit."""
    c = _first_order(a)
    u = np.r_[1.0, np.zeros(6), -1.0, np.zeros(4)]
    got, ref = nir_response(c, u), _drive(c, u)
    for name, trace in ref.items():
        np.testing.assert_allclose(got[name], trace, rtol=0, atol=1e-12, err_msg=name)


def test_the_spiking_graph_reads_back_equal_and_is_nengos_lif(tmp_path):
    need_spiking("nengo")
    graph = _read_back(_first_order().to_nir(30, rng=2, dt=DT), tmp_path)
    _same_graph(graph, _first_order().to_nir(30, rng=2, dt=DT))
    chain = ["x1", "x1 encoders", "x1 LIF", "x1 decoders", "x1 synapse"]
    assert all(edge in graph.edges for edge in itertools.pairwise(chain))
    assert ("x1 synapse", "x1 -> x1 (delay 1) delay") in graph.edges
    lif, syn = graph.nodes["x1 LIF"], graph.nodes["x1 synapse"]
    assert np.all(lif.tau == 0.02) and np.all(lif.v_threshold == 1) and np.all(lif.v_reset == 0)
    assert syn.tau[0] == pytest.approx(0.2 * DT)
    # the read-back nodes represent x: LIF steady rates through the decoders give x back
    enc, dec = graph.nodes["x1 encoders"], graph.nodes["x1 decoders"]
    peak = np.max(np.abs(_drive(_first_order(), np.r_[1.0, np.zeros(20)])["x1"]))
    x = np.linspace(-peak, peak, 41)
    J = enc.weight @ x[None, :] + enc.bias[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        rates = np.where(J > 1, 1 / (lif.tau[:, None] * np.log1p(1 / (J - 1))), 0.0)
    assert np.max(np.abs(dec.weight @ rates - x)) < 0.1 * peak


def _nengo_run(nengo, circuit: Circuit, u: np.ndarray, seed: int) -> np.ndarray:
    """The same populations run in nengo (Ts/10 steps): neuron x1's sum at each sample."""
    kind = nengo.LIF(tau_ref=0, min_voltage=-np.inf)
    net = circuit.to_nengo(100, neuron_type=kind, rng=seed, dt=DT)
    with net:
        source = nengo.Node(lambda t: u[min(round(t / DT * 10 - 1) // 10, len(u) - 1)])
        nengo.Connection(source, net.inputs["u"], synapse=None)
        probe = nengo.Probe(net.neurons["x1"])
    with nengo.Simulator(net, dt=DT / 10, progress_bar=False) as sim:
        sim.run_steps(10 * len(u))
    return sim.data[probe][::10, 0]


def test_the_spiking_graph_runs_as_close_to_the_circuit_as_nengos_network():
    """Read back and run by NIR's equations (Ts/10 steps, as nengo's), 100 LIF neurons follow
    the circuit as nengo's run of the same network does (both about 0.25 of the peak at
    worst, over seeds: the Ts/5 lowpass lags both alike)."""
    nengo = need_spiking("nengo")
    c, u = _first_order(), pulse(40)[:, 0]
    ref = _drive(c, u)["x1"]
    ours, theirs = [], []
    for seed in (1, 2, 3):
        graph = c.to_nir(100, rng=seed, dt=DT)
        ours.append(_deviation(nir_response(c, u, graph, fine=10)["x1"], ref))
        theirs.append(_deviation(_nengo_run(nengo, c, u, seed), ref))
    ours, theirs = np.median(ours), np.median(theirs)
    assert ours < 0.35 and theirs < 0.35 and abs(ours - theirs) < 0.1


def test_symbolic_weights_are_refused_naming_the_circuit():
    from symctl.symbols import epsilon_1

    c = Circuit.from_structure(Structure.from_realization(first_order_realization(epsilon_1, 1)))
    with pytest.raises(ParameterError, match=r"circuit: .*epsilon_1.*subs"):
        c.to_nir()


@pytest.mark.parametrize("n", [0, -3, MAX_POPULATION + 1])
def test_a_population_size_out_of_range_is_refused(n):
    need_spiking("nengo")
    with pytest.raises(ParameterError, match="n_neurons"):
        _first_order().to_nir(n)


def test_a_refractory_period_or_a_voltage_floor_is_refused():
    nengo = need_spiking("nengo")
    for kind in (nengo.LIF(), nengo.LIF(tau_ref=0)):
        with pytest.raises(ParameterError, match="neuron_type: NIR's LIF has no refractory"):
            _first_order().to_nir(5, neuron_type=kind)
    for kind in (nengo.RectifiedLinear(), nengo.AdaptiveLIF(tau_ref=0, min_voltage=-np.inf)):
        with pytest.raises(SymctlTypeError, match=r"neuron_type: expected a nengo\.LIF"):
            _first_order().to_nir(5, neuron_type=kind)


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [({"dt": 0.0}, "dt"), ({"radius": {"x1": 1.0}}, "radius"), ({"neuron_type": 1}, "neuron_type")],
)
def test_bad_arguments_are_refused_by_name(kwargs, argument):
    with pytest.raises(ParameterError, match=argument):
        _first_order().to_nir(**kwargs)
