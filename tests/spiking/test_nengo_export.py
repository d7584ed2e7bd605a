"""Circuit.to_nengo: the network run in nengo's simulator with dt = Ts is symctl's own simulation."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from helpers import need_spiking

from symctl import (
    Circuit,
    MissingDependencyError,
    ParameterError,
    Structure,
    SymctlTypeError,
    circuits_for,
    controllable_canonical,
    controller_tf,
    factor,
    first_order_realization,
    pulse,
)
from symctl.neural.firing import _drive
from symctl.spiking.nengo_export import MAX_POPULATION, nengo_response

nengo = need_spiking("nengo")


def _same_traces(circuit: Circuit, u: np.ndarray) -> None:
    """nengo's traces equal symctl's to 1e-9 relative to their peak, neuron by neuron."""
    ref, got = _drive(circuit, u), nengo_response(circuit, u)
    assert set(got) == set(ref)
    for name, trace in ref.items():
        scale = max(1.0, float(np.max(np.abs(trace))))
        np.testing.assert_allclose(got[name], trace, rtol=0, atol=1e-9 * scale, err_msg=name)


def _input(circuit: Circuit, steps: int = 40) -> np.ndarray:
    """A pulse on the first input and a shorter one of another height on each further input."""
    u = pulse(steps, 1.0, 3, 10, size=len(circuit.inputs))
    for j in range(1, u.shape[1]):
        u[:, j] = pulse(steps, -0.5 * j, 5 + j, 4)[:, 0]
    return u


@pytest.mark.parametrize("name", ["ifp", "general", "controllable", "observable"])
def test_every_paper_circuit_in_nengo_is_symctls_simulation(derived_T2, name):
    firing = derived_T2.circuits[name].firing
    for circuit in firing.circuits:
        _same_traces(circuit, _input(circuit))


def test_every_order_2_atlas_class_in_nengo_is_symctls_simulation(derived_T2):
    candidates = circuits_for(derived_T2.G)
    assert len({c.circuit_class.label for c in candidates}) == len(candidates) > 3
    for cand in candidates:
        _same_traces(cand.circuit, _input(cand.circuit))


def test_a_mimo_circuit_in_nengo_is_symctls_simulation(derived_oculomotor):
    for record in derived_oculomotor.circuits.values():
        if record.firing is not None:
            circuit = record.firing.circuits[0]
            break
    assert len(circuit.inputs) > 1 or len(circuit.outputs) > 1
    _same_traces(circuit, _input(circuit))


def test_multi_step_axons_are_delays_of_as_many_steps():
    T = 3
    G = controller_tf(T).subs({f"K_{k}": sp.Rational(k + 1, 5 * (k + 2)) for k in range(T + 1)})
    f = factor(G, 1, 0 + 2, eps=[sp.Rational(1, 3), sp.Rational(-1, 4), sp.Rational(1, 5)], C=1)
    R = controllable_canonical(f.G2)
    circuit = Circuit.from_structure(Structure.from_realization(R))
    assert max(s.delay for s in (*circuit.synapses, *circuit.outputs)) >= 2
    _same_traces(circuit, _input(circuit))
    net = circuit.to_nengo()
    delays = [c.label.rsplit("delay ", 1)[1] for c in net.connections]
    assert "2)" in delays


def test_the_network_is_labelled_with_names_and_vertices(derived_T2):
    symbolic = derived_T2.circuits["observable"].circuit  # placed at its vertices
    circuit = symbolic.subs({s: sp.Rational(1, 3) for s in symbolic.free_symbols})
    assert None not in circuit.vertices.values()
    net = circuit.to_nengo()
    assert [n.label for n in net.neurons.values()] == [
        f"{n.name} @ v{n.vertex}" for n in circuit.neurons
    ]
    assert list(net.inputs) == list(circuit.inputs)
    assert sum(1 for c in net.connections) == len(circuit.synapses) + sum(
        len(n.self_terms) for n in circuit.neurons
    ) + len(circuit.outputs)


def _first_order() -> Circuit:
    return Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 2)))


def test_symbolic_weights_are_refused_naming_the_circuit():
    from symctl.symbols import epsilon_1

    c = Circuit.from_structure(Structure.from_realization(first_order_realization(epsilon_1, 1)))
    with pytest.raises(ParameterError, match=r"circuit: .*epsilon_1.*subs"):
        c.to_nengo()


@pytest.mark.parametrize("n", [0, -3, MAX_POPULATION + 1])
def test_a_population_size_out_of_range_is_refused(n):
    with pytest.raises(ParameterError, match="n_neurons"):
        _first_order().to_nengo(n)


def test_a_neuron_type_that_is_not_nengos_is_refused():
    with pytest.raises((SymctlTypeError, ParameterError), match="neuron_type"):
        _first_order().to_nengo(neuron_type="LIF")


def test_bad_input_width_is_refused():
    with pytest.raises(ParameterError, match="u: "):
        nengo_response(_first_order(), np.zeros((5, 2)))


def test_without_nengo_the_error_says_how_to_install(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "nengo", None)  # import nengo raises ImportError
    with pytest.raises(MissingDependencyError, match=r"pip install symctl\[spiking\]"):
        _first_order().to_nengo()
