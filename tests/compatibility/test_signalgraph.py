"""The signal graph's searches: back edges, delay-free cycles, fewest delays (against networkx)."""

from __future__ import annotations

import itertools

import networkx as nx
import numpy as np

from symctl.compatibility.signalgraph import (
    SignalGraph,
    back_edges,
    delay_free_cycle,
    zero_one_bfs,
)


def random_signal_graph(rng) -> SignalGraph:
    n = int(rng.integers(1, 9))
    wires = [
        (a, b, int(rng.integers(2))) for a in range(n) for b in range(n) if rng.random() < 0.25
    ]
    names = [f"s{k}" for k in range(n)]
    return SignalGraph.from_wires(names, ["sum"] * n, wires, (0,), (n - 1,))


def test_removing_the_back_edges_leaves_an_acyclic_graph_and_only_cycles_are_cut():
    rng = np.random.default_rng(3)
    for _ in range(400):
        g = random_signal_graph(rng)
        cut = back_edges(g.successors, g.inputs)
        dag = nx.DiGraph()
        dag.add_nodes_from(range(len(g.names)))
        dag.add_edges_from((a, b) for a, b, _ in g.wires if (a, b) not in cut)
        assert nx.is_directed_acyclic_graph(dag)
        for a, b in cut:  # every cut edge closes a cycle: b reaches a
            assert a == b or nx.has_path(dag, b, a)


def test_delay_free_cycle_is_found_exactly_when_networkx_finds_one():
    rng = np.random.default_rng(4)
    found = 0
    for _ in range(400):
        g = random_signal_graph(rng)
        instant = nx.DiGraph([(a, b) for a, b, w in g.wires if w == 0])
        cycle = delay_free_cycle(g)
        assert (cycle is not None) == (not nx.is_directed_acyclic_graph(instant))
        if cycle is not None:
            found += 1
            assert cycle[0] == cycle[-1]
            index = [g.index[n] for n in cycle]
            assert all(instant.has_edge(a, b) for a, b in itertools.pairwise(index))
    assert found > 20


def test_zero_one_bfs_is_dijkstra_on_delays():
    rng = np.random.default_rng(5)
    for _ in range(300):
        g = random_signal_graph(rng)
        G = nx.DiGraph()
        G.add_nodes_from(range(len(g.names)))
        for a, b, w in g.wires:
            if not G.has_edge(a, b) or G.edges[a, b]["w"] > w:
                G.add_edge(a, b, w=w)
        expected = nx.single_source_dijkstra_path_length(G, 0, weight="w")
        dist = zero_one_bfs(g, [0])
        assert {k: d for k, d in enumerate(dist) if d is not None} == expected


def test_back_edges_take_named_nodes_as_well_as_indices():
    rng = np.random.default_rng(6)
    for _ in range(100):
        g = random_signal_graph(rng)
        named = {g.names[a]: [g.names[b] for b in out] for a, out in enumerate(g.successors)}
        by_index = back_edges(g.successors, g.inputs)
        by_name = back_edges(named, [g.names[i] for i in g.inputs])
        assert by_name == [(g.names[a], g.names[b]) for a, b in by_index]
