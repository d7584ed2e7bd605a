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
    first_order_realization,
)
from symctl.spiking.nengo_export import MAX_POPULATION, nengo_response

nengo = need_spiking("nengo")


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
