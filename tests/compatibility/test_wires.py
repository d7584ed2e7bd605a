"""Multi-step wires (axons) and delay graphs beyond chains: structures, checkers, theorems."""

from __future__ import annotations

import math
import re

import networkx as nx
import numpy as np
import pytest
import sympy as sp
from helpers import examples, random_graph, random_structure
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from symctl import Circuit, ParameterError, SymctlError, controller_tf, z
from symctl.compatibility.block import MAX_WIRE_STEPS, Block
from symctl.compatibility.check import brute_force_compatibility, check_compatibility
from symctl.compatibility.construction import fastest_path, markov_split, slowest_path
from symctl.compatibility.controller import controller_compatibility
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.statespace import structure_realization
from symctl.compatibility.structure import Structure
from symctl.design.tf import DiscreteTF
from symctl.realization.check import check_realization
from symctl.realization.realization import first_order_realization

# sensor -> spinal -> muscle beside sensor -> cortex -> spinal -> muscle
TWO_PATHWAYS = DelayGraph.from_edges(4, [(1, 2, 1), (2, 4, 1), (1, 3, 1), (3, 2, 1)])


def _relative_degree_G(r: int, rng) -> sp.Expr:
    """A random proper G of relative degree exactly r and order r + 1 (exact rationals)."""
    n = r + 1
    poles = [sp.Rational(int(rng.integers(-9, 10)), 10) for _ in range(n)]
    den = sp.Mul(*(z - p for p in poles))
    num = sum(sp.Rational(int(rng.integers(1, 9)), 4) * z**k for k in range(n - r + 1))
    return num / den


# ---------------------------------------------------------------- blocks
@pytest.mark.parametrize("steps", [0, -1, 1.5, True, "2", MAX_WIRE_STEPS + 1, None])
def test_a_wire_delay_must_be_a_positive_integer(steps):
    with pytest.raises(ParameterError, match=r"blocks\['d'\]\.steps"):
        Structure({"u": ("input",), "d": Block("delay", ("u",), steps=steps)}, "u", "d")


def test_only_delay_blocks_have_steps():
    with pytest.raises(ParameterError, match="only a delay block has steps"):
        Structure({"u": ("input",), "g": Block("gain", ("u",), 2, "", 3)}, "u", "g")


def test_a_k_step_block_is_a_wire_of_delay_k_everywhere():
    S = Structure(
        {"u": ("input",), "d": Block("delay", ("u",), steps=4), "y": ("sum", ("d", "u"))},
        "u",
        "y",
    )
    assert ("u", "d", 4) in set(S.wires())
    assert S.delay_distances("u") == {"u": 0, "d": 4, "y": 0}
    assert S.graph.edges["u", "d"]["delay"] == 4
    assert str(S.equations()[0]) == "Eq(d(t), u(t - 4))"
    R = structure_realization(S)
    assert R.n == 4 and sp.simplify(R.to_tf().expr - (1 + z**-4)) == 0
    # series and parallel keep the steps
    assert Structure.series(S, S).blocks["G1.d"].steps == 4
    assert Structure.parallel(S, S).blocks["P2.d"].steps == 4


@settings(max_examples=examples(60), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1))
def test_fewest_delays_with_axons_agree_with_networkx_dijkstra(seed):
    rng = np.random.default_rng(seed)
    S = random_structure(rng, 9, max_steps=4)
    g = nx.DiGraph()
    g.add_nodes_from(S.blocks)
    for a, b, w in S.wires():
        g.add_edge(a, b, weight=w)
    expected = nx.single_source_dijkstra_path_length(g, S.input)
    assert S.delay_distances(S.input) == expected


@settings(max_examples=examples(80), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), chain=st.booleans())
def test_checkers_with_axons_agree_with_brute_force(seed, chain):
    rng = np.random.default_rng(seed)
    S = random_structure(rng, 6, max_steps=3)
    graph = random_graph(rng, chain)
    fast = check_compatibility(S, graph)
    slow = brute_force_compatibility(S, graph)
    assert fast.ok == slow.ok
    if fast.ok:
        assert fast.assignment.is_compatible()


# ---------------------------------------------------------------- the theorems
def _fastest_over(graph: DelayGraph, W) -> float:
    g = nx.DiGraph()
    g.add_nodes_from(range(1, graph.n + 1))
    for i, j, d in graph.edges:
        if W is None or d <= W:
            g.add_edge(i, j, weight=d)
    try:
        return nx.dijkstra_path_length(g, 1, graph.n)
    except nx.NetworkXNoPath:
        return math.inf


@settings(max_examples=examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    seed=st.integers(0, 2**32 - 1),
    chain=st.booleans(),
    r=st.integers(0, 4),
    W=st.sampled_from([None, 1, 2]),
)
def test_theorem_1_compatible_iff_relative_degree_reaches_the_fastest_path(seed, chain, r, W):
    rng = np.random.default_rng(seed)
    graph = random_graph(rng, chain)
    G = _relative_degree_G(r, rng)
    result = controller_compatibility(G, graph, max_wire_delay=W)
    assert result.scope == "all realizations"
    assert result.ok == (r >= _fastest_over(graph, W))
    if not result.ok:
        return
    S = result.structure
    assert W is None or max((w for _, _, w in S.wires()), default=0) <= W
    assert result.check.assignment.is_compatible()
    assert brute_force_compatibility(S, graph, limit=10**9).ok if len(S) <= 12 else True
    proof = check_realization(structure_realization(S), G)  # exact: the structure is G
    assert proof.ok and proof.method == "exact"
    assert check_realization(result.realization, G).ok


def test_old_chain_theorem_is_the_corollary_for_unit_wires():
    G = controller_tf(3)
    for steps in ([1, 1, 1], [0, 1, 2], [3], [1, 0, 2], [2, 2]):
        unit = controller_compatibility(G, DelayGraph.chain(steps), max_wire_delay=1)
        axon = controller_compatibility(G, DelayGraph.chain(steps))
        assert unit.ok == (sum(steps) <= 3 and max(steps) <= 1)
        assert axon.ok == (sum(steps) <= 3)


def test_fastest_path_prefers_more_vertices_and_slowest_path_is_simple():
    g = DelayGraph.from_edges(3, [(1, 2, 1), (2, 3, 1), (1, 3, 2)])
    assert fastest_path(g) == (2, (1, 2, 3), (1, 1))
    assert fastest_path(g, 1) == (2, (1, 2, 3), (1, 1))
    assert fastest_path(DelayGraph.chain([2]), 1) is None
    assert slowest_path(TWO_PATHWAYS) == (3, (1, 3, 2, 4), (1, 1, 1))
    zero_cycle = DelayGraph.from_edges(3, [(1, 2, 0), (2, 1, 0), (2, 3, 1)])
    assert fastest_path(zero_cycle)[0] == 1


def test_parallel_decomposition_uses_both_pathways_and_adds_up_to_G():
    G = controller_tf(2)
    r = controller_compatibility(G, TWO_PATHWAYS, construction="parallel")
    assert r.ok and len(r.parts) == 2 and "parallel decomposition" in r.method
    assert [p.path for p in r.parts] == [(1, 2, 4), (1, 3, 2, 4)]
    total = sum((p.G for p in r.parts), sp.Integer(0))
    assert sp.cancel(sp.together(total - G.expr)) == 0  # exact
    for p in r.parts:
        assert DiscreteTF.from_expr(p.G).relative_degree >= p.delay
    assert 3 in r.check.assignment.vertex_of.values()  # the cortex vertex is used
    assert check_realization(structure_realization(r.structure), G).ok
    circuit = Circuit.from_structure(r.structure, r.check)
    assert set(circuit.vertices.values()) >= {2, 3, 4}


def test_markov_split_is_exact_for_a_symbolic_controller():
    G = controller_tf(2)
    parts = markov_split(G, [2, 3, 5])
    assert sp.cancel(sp.together(sum(parts) - G.expr)) == 0
    for L, part in zip([2, 3, 5], parts, strict=True):
        assert part == 0 or DiscreteTF.from_expr(part).relative_degree >= L


def test_paths_are_checked_and_named():
    G = controller_tf(2)
    for bad, message in (
        ([[1, 3, 4]], "not an edge"),
        ([[2, 4]], "from v1 to v4"),
        ([[1, 2, 1, 2, 4]], "each vertex once"),
        ("1 2 4", "vertex lists"),
        ([], "at least one"),
        ([["a", 2]], "sequence of vertices"),
    ):
        with pytest.raises(ParameterError, match="paths"):
            controller_compatibility(G, TWO_PATHWAYS, paths=bad)
        del message
    with pytest.raises(ParameterError, match="distinct delays"):
        controller_compatibility(
            G, TWO_PATHWAYS, construction="parallel", paths=[[1, 2, 4], [1, 2, 4]]
        )
    with pytest.raises(ParameterError, match="max_wire_delay"):
        controller_compatibility(G, DelayGraph.chain([2]), paths=[[1, 2]], max_wire_delay=1)
    for W in (0, -1, 1.5, True, "2", 10**9):
        with pytest.raises(SymctlError, match="max_wire_delay"):
            controller_compatibility(G, TWO_PATHWAYS, max_wire_delay=W)
    with pytest.raises(ParameterError, match="construction"):
        controller_compatibility(G, TWO_PATHWAYS, construction="tree")
    slow = controller_compatibility(G, TWO_PATHWAYS, paths=[[1, 3, 2, 4]])
    assert not slow.ok and "fastest path given" in slow.reason


# ---------------------------------------------------------------- circuits and simulation
def test_circuits_carry_axon_delays_and_simulate_them():
    sec = first_order_realization(sp.Rational(1, 2), 3)
    S = Structure.from_realization(sec, input_delay=3)
    c = Circuit.from_structure(S)
    (syn,) = [s for s in c.synapses if s.source == "u"]
    assert syn.delay == 3 and syn.weight == 3
    sym = c.as_linear_system()
    num = c.as_linear_system(numeric=True)
    assert np.allclose(np.array(sym.A, dtype=float), num.A)
    assert np.allclose(np.array(sym.B, dtype=float), num.B)
    # the impulse response: 3 (1/2)^(k-3) from k = 3 on
    s = np.zeros(num.A.shape[0])
    out = []
    for k in range(8):
        u = 1.0 if k == 0 else 0.0
        out.append(float((num.C @ s + num.D[:, 0] * u)[-1]))
        s = num.A @ s + num.B[:, 0] * u
    assert out == pytest.approx([0, 0, 0, 3, 1.5, 0.75, 0.375, 0.1875])
    with pytest.raises(ParameterError, match="input_delay"):
        Structure.from_realization(sec, "state", input_delay=2)


# ---------------------------------------------------------------- MIMO: theorem 3
def _channel_graph(rng) -> DelayGraph:
    """Two sensors v1, v2, a middle v3, two actuators v4, v5; random delays 0..2."""
    while True:
        edges = [(s, 3, int(rng.integers(0, 3))) for s in (1, 2)]
        edges += [(3, a, int(rng.integers(0, 3))) for a in (4, 5)]
        edges += [
            (s, a, int(rng.integers(0, 4))) for s in (1, 2) for a in (4, 5) if rng.random() < 0.3
        ]
        try:
            return DelayGraph.from_edges(5, edges, sensors=[1, 2], actuators=[4, 5])
        except ParameterError:  # pragma: no cover - every vertex is reached here
            continue


@pytest.mark.slow
@settings(max_examples=examples(15), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1))
def test_theorem_3_every_entry_along_its_own_path(seed):
    rng = np.random.default_rng(seed)
    graph = _channel_graph(rng)
    degrees = rng.integers(0, 4, size=(2, 2))
    zero = rng.random((2, 2)) < 0.2
    entries = [
        [
            sp.Integer(0) if zero[i, j] else _relative_degree_G(int(degrees[i, j]), rng)
            for j in range(2)
        ]
        for i in range(2)
    ]
    G = sp.Matrix(entries)
    result = controller_compatibility(G, graph)
    expected = all(
        zero[i, j] or degrees[i, j] >= graph.E[j, 3 + i] for i in range(2) for j in range(2)
    )
    assert result.ok == expected and result.scope == "all realizations"
    if result.ok:
        assert result.check.assignment.is_compatible()
        placed = result.check.assignment.vertex_of
        assert (placed["u1"], placed["u2"], placed["y1"], placed["y2"]) == (1, 2, 4, 5)
        assert check_realization(structure_realization(result.structure), G).ok


@pytest.mark.parametrize("base", ["controllable", "observable"])
def test_theorem_3_with_one_sensor_and_one_actuator_vertex_shares_one_G2(base):
    d = (z - sp.Rational(1, 2)) * (z + sp.Rational(1, 4)) * z**2
    G = sp.Matrix([[(z + 1) / d, 3 / d], [0, (2 * z - 1) / d]])  # relative degree 3 or more
    result = controller_compatibility(G, DelayGraph.chain([2, 1]), base=base)
    assert result.ok and result.method == "theorem 3 (MIMO) + path construction"
    (part,) = result.parts
    assert (part.label, part.path, part.delays) == ("G", (1, 2, 3), (2, 1))
    assert result.check.assignment.is_compatible()
    assert check_realization(structure_realization(result.structure), G).ok
    # one block form for all entries, not one G3 G2 G1 per entry ("G1,1.G2. ...")
    assert any(n.startswith("G2.x") for n in result.structure.blocks)
    assert not any(re.match(r"G\d+,\d+\.", n) for n in result.structure.blocks)
    too_fast = controller_compatibility(G, DelayGraph.chain([2, 2]), base=base)
    assert not too_fast.ok and "G[1,1]" in too_fast.reason


def test_a_graph_whose_channels_do_not_fit_the_controller_is_refused():
    from symctl import DimensionError

    G = sp.Matrix([[1 / z, 1 / z, 1 / z]])  # 3 inputs, 1 output
    two = DelayGraph.from_edges(3, [(1, 3, 1), (2, 3, 1)], sensors=[1, 2])
    with pytest.raises(DimensionError, match="graph: the delay graph has 2 sensor vertices"):
        controller_compatibility(G, two)
    with pytest.raises(ParameterError, match="paths"):
        controller_compatibility(G, DelayGraph.chain([1]), paths=[[1, 2]])


def test_batch_simulation_of_structures_with_axons_matches_the_optimal_loop():
    """Batch-simulate the state-space forms of axon constructions at random epsilons."""
    from symctl import MuscleModel, augment, closed_loop_response, lqr_gains, simulate_batch

    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    G = controller_tf(gains.system).subs(gains.substitutions(exact=True))
    r = controller_compatibility(G, DelayGraph.chain([2]))  # one axon of 2 steps
    R = structure_realization(r.structure)
    symbols = sorted(R.free_symbols, key=str)
    rng = np.random.default_rng(3)
    values = [
        rng.uniform(-0.9, 0.9, 5) if str(s).startswith("epsilon") else np.ones(5) for s in symbols
    ]
    mats = [np.asarray(m, dtype=float) for m in R.lambdify(symbols)(*values)]
    out = simulate_batch(gains.system.plant, *mats, 1.0, steps=40)
    ref = closed_loop_response(gains, disturbance=1.0, steps=40)
    assert np.abs(out.delta_r - ref.delta_r[None]).max() < 1e-9 * np.abs(ref.delta_r).max()


@pytest.mark.parametrize(
    "bad", [[1, 2.5, 4], [1, True, 4], [1, 9, 4], [[1], 2, 4], iter(range(10**9))]
)
def test_a_path_of_non_vertices_is_refused(bad):
    with pytest.raises(ParameterError, match=r"paths\[0\]"):
        controller_compatibility(controller_tf(2), TWO_PATHWAYS, paths=[bad])
