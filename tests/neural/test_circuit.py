"""Circuits of stylized neurons: the paper's neuron counts, self-dynamics, synapses, vertices."""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest
import sympy as sp
from helpers import paper_assignment

from symctl import (
    DelayAssignment,
    DelayGraph,
    ParameterError,
    SymctlTypeError,
    check_compatibility,
    controllable_canonical,
    controller_tf,
    factor,
    general_realization,
    observable_canonical,
    z,
)
from symctl.compatibility.structure import Structure, ifp_structure
from symctl.neural.circuit import Circuit
from symctl.neural.neuron import Synapse
from symctl.realization.realizers import random_realization
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3, gain_symbols

matplotlib.use("Agg")

F = factor(controller_tf(2))
K0, K1, K2 = gain_symbols(2)
P = [[1, 2], [3, -1]]
REALIZATIONS = {
    "controllable": controllable_canonical(F.G2),
    "observable": observable_canonical(F.G2),
    "general": general_realization(F.G2, P),
}
E = DelayGraph.chain([1, 1])


def g2_circuit(kind):
    return Circuit.from_structure(Structure.from_realization(REALIZATIONS[kind]))


def full_circuit(kind, assignment=None):
    S = Structure.from_factorization(F, REALIZATIONS[kind])
    return Circuit.from_structure(S, assignment), S


@pytest.mark.parametrize(
    ("kind", "count"), [("controllable", 2), ("observable", 3), ("general", 3)]
)
def test_g2_circuits_have_the_papers_neuron_counts(kind, count):
    assert g2_circuit(kind).n_neurons == count


@pytest.mark.parametrize(
    ("kind", "count"), [("controllable", 4), ("observable", 5), ("general", 5)]
)
def test_g1_and_g3_add_one_neuron_each(kind, count):
    c, _ = full_circuit(kind)
    assert c.n_neurons == count
    parts = [n.part for n in c.neurons]
    assert parts.count("G1") == 1 and parts.count("G3") == 1


def test_controllable_canonical_x1_is_an_axon_delay_and_x2_has_two_lag_self_dynamics():
    c = g2_circuit("controllable")
    assert [n.name for n in c.neurons] == ["x2", "y"]
    x2 = c.neuron("x2")
    assert sp.expand(x2.self_dynamics - (K1 / z + K2 / z**2)) == 0
    assert [(s.source, s.weight, s.delay) for s in x2.synapses] == [("u", 1, 1)]
    assert x2.branches == 2
    assert sorted((s.target, s.delay) for s in x2.axon) == [("y", 0), ("y", 1)]


def test_observable_canonical_output_sum_is_a_neuron_with_two_terms():
    y = g2_circuit("observable").neuron("y")
    assert sorted(s.source for s in y.synapses) == ["u", "x2"]
    assert not y.self_terms


def test_g1_neuron_has_self_dynamics_eps1_and_synapse_c1():
    c, _ = full_circuit("controllable")
    g1 = c.neuron("G1.x1")
    assert g1.self_weight == epsilon_1
    assert g1.self_dynamics == epsilon_1 / z
    assert [(s.source, s.weight, s.delay, s.sign) for s in g1.synapses] == [("G1.u", C_1, 1, "?")]
    g3 = c.neuron("G3.x1")
    assert g3.self_weight == epsilon_3
    assert [(s.source, s.weight, s.delay) for s in g3.synapses] == [("G2.y", C_3, 1)]


@pytest.mark.parametrize(
    ("values", "kind", "count"),
    [
        ({epsilon_3: -K2 / epsilon_1}, "controllable", 2),
        ({epsilon_3: K1 - epsilon_1}, "controllable", 2),
        ({epsilon_3: -K2 / epsilon_1}, "observable", 2),
    ],
)
def test_choosing_eps_simplifies_the_middle_neuron_to_one_axon_branch(values, kind, count):
    build = controllable_canonical if kind == "controllable" else observable_canonical
    c = Circuit.from_structure(Structure.from_realization(build(F.G2.subs(values))))
    assert c.n_neurons == count
    assert c.neuron("x2").branches == 1
    assert g2_circuit("controllable").neuron("x2").branches == 2


def test_observable_canonical_with_k1_condition_keeps_three_neurons():
    R = observable_canonical(F.G2.subs({epsilon_3: K1 - epsilon_1}))
    assert Circuit.from_structure(Structure.from_realization(R)).n_neurons == 3


def test_simplified_full_circuit_keeps_one_neuron_for_g1_and_g3():
    f = F.subs({epsilon_3: -K2 / epsilon_1})
    c = Circuit.from_structure(Structure.from_factorization(f, controllable_canonical(f.G2)))
    assert c.n_neurons == 4
    assert c.neuron("G2.x2").branches == 1


def test_vertices_from_the_papers_assignment():
    c, S = full_circuit("controllable")
    a = DelayAssignment(S, E, paper_assignment(S))
    c = Circuit.from_structure(S, a)
    assert c.vertices == {"G1.x1": 2, "G2.x2": 2, "G2.y": 2, "G3.x1": 3}
    # the G1 adder cannot sit at v1: its delay-free path through N reaches the G2 output
    moved = dict(paper_assignment(S), **{"G1.x1": 1})
    assert not DelayAssignment(S, E, moved).is_compatible()


@pytest.mark.parametrize("kind", ["observable", "general"])
def test_vertices_from_a_compatibility_result(kind):
    _, S = full_circuit(kind)
    c = Circuit.from_structure(S, check_compatibility(S, E))
    assert {n.vertex for n in c.neurons if n.part == "G2"} == {2}
    assert c.neuron("G3.x1").vertex == 3


def test_ifp_structure_is_one_neuron_with_two_lag_self_dynamics():
    c = Circuit.from_structure(ifp_structure(2))
    assert c.n_neurons == 1
    mu = c.neuron("mu")
    assert sp.expand(mu.self_dynamics - (K1 / z + K2 / z**2)) == 0
    assert [(s.source, s.weight, s.delay) for s in mu.synapses] == [("x", K0, 0)]
    assert c.outputs[0][:4] == ("mu", "u", 1, 2)


def test_synapse_signs():
    assert Synapse("a", "b", sp.Integer(2), 0).sign == "+"
    assert Synapse("a", "b", sp.Integer(-2), 0).sign == "-"
    assert Synapse("a", "b", K1, 0).sign == "?"
    assert Synapse("a", "b", sp.Symbol("w", positive=True), 0).sign == "+"


def test_subs_and_linear_system_reproduce_the_controller():
    values = {
        K0: sp.Rational(-1, 2),
        K1: sp.Rational(3, 10),
        K2: sp.Rational(-1, 5),
        C_1: 1,
        C_3: 2,
        epsilon_1: sp.Rational(1, 4),
        epsilon_3: sp.Rational(-1, 3),
    }
    c, _ = full_circuit("general")
    num = c.subs(values)
    assert not num.free_symbols
    assert num.neuron("G1.x1").self_weight == sp.Rational(1, 4)
    A, B, C, D, states, _, outputs = num.as_linear_system(numeric=True)
    assert outputs == (*(n.name for n in num.neurons), "G3.x1")
    # impulse response of the circuit output equals that of G(z) = K0/(z^2 - K1 z - K2)
    G = sp.lambdify(z, controller_tf(2).expr.subs(values))
    freqs = np.exp(1j * np.array([0.3, 1.1, 2.0]))
    for w in freqs:
        H = C @ np.linalg.solve(w * np.eye(len(states)) - A, B) + D
        assert abs(H[-1, 0] - G(w)) < 1e-12
    with pytest.raises(ParameterError, match="numeric"):
        c.as_linear_system(numeric=True)


def test_neuron_traces_match_the_realization_state():
    values = {K0: -1, K1: sp.Rational(1, 2), K2: sp.Rational(-1, 4), C_1: 1, C_3: 1}
    vals = {**values, epsilon_1: sp.Rational(1, 5), epsilon_3: sp.Rational(1, 7)}
    R = general_realization(F.G2.subs(vals), P)
    c = Circuit.from_structure(Structure.from_realization(R))
    A, B, C, D, *_ = c.as_linear_system(numeric=True)
    F_, H_, M_, N_ = (np.array(m.tolist(), dtype=float) for m in (R.F, R.H, R.M, R.N))
    rng = np.random.default_rng(0)
    u = rng.normal(size=30)
    s, x = np.zeros(A.shape[0]), np.zeros(2)
    for t in range(30):
        o = C @ s + D[:, 0] * u[t]
        y = (M_ @ x)[0] + N_[0, 0] * u[t]
        assert np.allclose(o, [x[0], x[1], y, y])
        s, x = A @ s + B[:, 0] * u[t], F_ @ x + H_[:, 0] * u[t]


def test_display():
    c, _ = full_circuit("controllable")
    assert "G1.x1" in str(c) and "self-dynamics" in str(c)
    assert c.latex().startswith(r"\begin{gathered}")
    assert c._repr_latex_().startswith("$")
    assert "4 neurons" in repr(c)
    fig = c.draw()
    assert type(fig).__name__ == "Figure"
    assert any(p.get_gid() == "neuron:G2.x2" for p in fig.axes[0].patches)


def test_bad_input_names_the_argument():
    with pytest.raises(SymctlTypeError, match="S: expected a Structure"):
        Circuit.from_structure(REALIZATIONS["controllable"])
    _, S = full_circuit("controllable")
    with pytest.raises(SymctlTypeError, match="assignment"):
        Circuit.from_structure(S, {"G1.u": 1})
    other = Structure.from_factorization(F, REALIZATIONS["observable"])
    with pytest.raises(ParameterError, match=r"assignment: .*another structure"):
        Circuit.from_structure(S, check_compatibility(other, E))
    with pytest.raises(ParameterError, match="assignment: the compatibility check failed"):
        Circuit.from_structure(ifp_structure(2), check_compatibility(ifp_structure(2), E))
    bad = dict(paper_assignment(S), **{"G1.x1": 1})
    with pytest.raises(ParameterError, match="assignment: not compatible"):
        Circuit.from_structure(S, DelayAssignment(S, E, bad))
    with pytest.raises(ParameterError, match="name"):
        Circuit.from_structure(S).neuron("nope")
    inf = Structure(
        {
            "u": ("input",),
            "g": ("gain", ("u",), sp.oo),
            "d": ("delay", ("g",)),
            "s": ("sum", ("d", "u")),
        },
        "u",
        "s",
    )
    with pytest.raises(ParameterError, match="not finite"):
        Circuit.from_structure(inf)


def test_axon_branches_are_listed_in_neuron_order_whatever_the_hash_seed():
    # the branches used to follow the iteration order of a set of names (hash-seed dependent)
    f = factor(controller_tf(4), 0, 4)
    c = Circuit.from_structure(Structure.from_realization(observable_canonical(f.G2)))
    order = [n.name for n in c.neurons]
    assert [s.target for s in c.input_axons["u"]] == order == ["x1", "x2", "x3", "x4", "y"]
    rank = {
        **{name: k for k, name in enumerate(order)},
        **{o.target: len(order) for o in c.outputs},
    }
    for n in c.neurons:
        ranks = [rank[s.target] for s in n.axon]
        assert ranks == sorted(ranks), n.name


@pytest.mark.parametrize(("T", "path"), [(1, ()), (2, ("gamma",)), (3, ("gamma1", "gamma2"))])
def test_output_path_holds_only_the_signals_strictly_between_source_and_target(T, path):
    out = Circuit.from_structure(ifp_structure(T)).outputs[0]
    assert (out.source, out.target, out.delay, out.path) == ("mu", "u", T, path)


def test_subs_that_makes_a_gain_infinite_names_subs():
    c, _ = full_circuit("controllable")
    with pytest.raises(ParameterError, match=r"^subs: the gain 'G2\.M\[1\]' is not finite"):
        c.subs({C_1: 0})


@pytest.mark.parametrize(("ds", "da"), [(0, 0), (1, 0), (0, 2), (2, 0), (1, 2), (3, 0), (0, 3)])
@pytest.mark.parametrize("kind", ["controllable", "observable", "general"])
@pytest.mark.parametrize("delays", ["branch", "state"])
def test_linear_system_of_the_circuit_has_the_controllers_transfer_function(ds, da, kind, delays):
    rng = np.random.default_rng(ds + 10 * da)
    f = factor(controller_tf(ds + da), ds, da)

    def draw(symbols, low, high):
        return {s: sp.Rational(int(rng.integers(low, high)), 100) for s in symbols}

    values = draw(gain_symbols(ds + da), -90, 90)
    values |= draw((*f.sensor_eps, *f.actuator_eps), -90, 90)
    values |= draw((*f.sensor_C, *f.actuator_C), 20, 300)
    fs = f.subs(values)
    if kind == "general":
        R2 = random_realization(fs.G2, rng)
    else:
        R2 = (controllable_canonical if kind == "controllable" else observable_canonical)(fs.G2)
    c = Circuit.from_structure(Structure.from_factorization(fs, R2, delays))
    A, B, C, D, states, _, outputs = c.as_linear_system(numeric=True)
    assert outputs[: c.n_neurons] == tuple(n.name for n in c.neurons)
    G = sp.lambdify(z, controller_tf(ds + da).expr.subs(values))
    for w in np.exp(1j * np.array([0.3, 1.1, 2.0])):
        H = C @ np.linalg.solve(w * np.eye(len(states)) - A, B) + D
        assert abs(H[-1, 0] - G(w)) < 1e-9 * max(1.0, abs(G(w)))


def test_each_neuron_trace_obeys_its_self_dynamics_and_synapses():
    values = {K0: -1, K1: sp.Rational(1, 2), K2: sp.Rational(-1, 4), C_1: 2, C_3: -1}
    values |= {epsilon_1: sp.Rational(1, 5), epsilon_3: sp.Rational(-3, 7)}
    fs = F.subs(values)
    for R2 in (observable_canonical(fs.G2), general_realization(fs.G2, P)):
        c = Circuit.from_structure(Structure.from_factorization(fs, R2, "state"))
        A, B, C, D, *_, outputs = c.as_linear_system(numeric=True)
        u = np.random.default_rng(1).normal(size=25)
        s, rows = np.zeros(A.shape[0]), []
        for uk in u:
            rows.append(C @ s + D[:, 0] * uk)
            s = A @ s + B[:, 0] * uk
        trace = dict(zip(outputs, np.array(rows).T, strict=False)) | {c.inputs[0]: u}
        for n in c.neurons:
            want = np.zeros(u.size)
            for syn in (*n.self_terms, *n.synapses):
                d = syn.delay
                want[d:] += float(syn.weight) * trace[syn.source][: u.size - d]
            np.testing.assert_allclose(trace[n.name], want, atol=1e-12, err_msg=n.name)


def test_equations_round_coefficients_but_keep_exponents_exact():
    from symctl.realization.realization import first_order_realization
    from symctl.symbols import epsilon_1

    x = sp.Symbol("x", positive=True)
    R = first_order_realization(sp.Rational(1, 3) * sp.sqrt(x) + 0.123456789 * epsilon_1, 1)
    (eq,) = Circuit.from_structure(Structure.from_realization(R)).equations(digits=3)
    assert "0.333" in eq and "0.123" in eq and r"\sqrt{x}" in eq and "0.5" not in eq


def test_circuit_equal_by_value():
    a, b = full_circuit("controllable")[0], full_circuit("controllable")[0]
    assert a is not b and a.structure is not b.structure
    assert a == b and hash(a) == hash(b) and len({a, b}) == 1
    assert a != full_circuit("observable")[0]
    values = {epsilon_1: sp.Rational(1, 2)}
    assert a.subs(values) == b.subs(values) != a
    _, S = full_circuit("controllable")
    placed = Circuit.from_structure(S, DelayAssignment(S, E, paper_assignment(S)))
    assert placed != Circuit.from_structure(S)  # the vertices count


def test_neurons_and_synapses_compare_and_hash_by_value():
    a, b = full_circuit("general")[0], full_circuit("general")[0]
    assert a.neurons == b.neurons and {*a.neurons} == {*b.neurons}
    assert hash(a.neuron("G2.y")) == hash(b.neuron("G2.y"))
    assert a.neuron("G2.x1") != a.neuron("G2.x2")
    assert Synapse("u", "x", K1, 1) == Synapse("u", "x", K1, 1) != Synapse("u", "x", K2, 1)
    assert len({Synapse("u", "x", K1, 1), Synapse("u", "x", K1, 1)}) == 1


def test_circuit_insides_are_immutable():
    c, _ = full_circuit("controllable")
    with pytest.raises(TypeError):
        c.input_axons["G1.u"] = ()
    with pytest.raises(AttributeError):
        c.neurons = ()
