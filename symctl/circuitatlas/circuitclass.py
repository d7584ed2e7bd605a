"""Circuit classes: patterns whose circuits are the same graph of neurons.

A pattern's **circuit** is :meth:`Circuit.from_structure` of its symbolic realization's
structure. Its **graph** has a node per input, neuron and output (a neuron labelled with its
self-dynamics delays) and an edge per connected pair labelled with the sorted delays of its
synapses; weights do not count. Patterns whose graphs are isomorphic with the labels kept (VF2,
after a Weisfeiler-Lehman hash) are one **class**.

>>> from symctl.circuitatlas.pattern import Pattern
>>> from symctl.circuitatlas.circuitclass import circuit_of
>>> c = circuit_of(Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1]))
>>> c.n_neurons, len(c.synapses)
(2, 4)
"""

from __future__ import annotations

import warnings
from collections import defaultdict
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property

import networkx as nx
import sympy as sp

from symctl.circuitatlas.pattern import Pattern
from symctl.circuitatlas.universality import Evidence
from symctl.compatibility.structure import Structure
from symctl.neural.circuit import Circuit
from symctl.realization.realization import Realization

__all__ = ["CircuitClass", "circuit_graph", "circuit_key", "circuit_of", "same_circuit"]

N_SYMBOL = sp.Symbol("N")


def circuit_of(pattern: Pattern, delays: str = "branch") -> Circuit:
    """The circuit of ``pattern``'s symbolic realization (weights are the entries' symbols)."""
    F, H, M = pattern.matrices(pattern.symbols())
    return Circuit.from_structure(
        Structure.from_realization(Realization(F, H, M, N_SYMBOL), delays)
    )


def circuit_graph(circuit: Circuit) -> nx.DiGraph:
    """The labelled graph whose isomorphism class is the circuit class (module text)."""
    graph = nx.DiGraph()
    for u in circuit.inputs:
        graph.add_node(u, label="input")
    edges: dict[tuple[str, str], list[int]] = defaultdict(list)
    for neuron in circuit.neurons:
        selfd = ",".join(str(d) for d in sorted(s.delay for s in neuron.self_terms))
        graph.add_node(neuron.name, label=f"neuron[{selfd}]")
        for s in neuron.synapses:
            edges[s.source, s.target].append(s.delay)
    for j, out in enumerate(circuit.outputs):
        graph.add_node(f"out{j + 1}", label="output")
        edges[out.source, f"out{j + 1}"].append(out.delay)
    for (a, b), ds in edges.items():
        graph.add_edge(a, b, label=",".join(map(str, sorted(ds))))
    return graph


def circuit_key(graph: nx.DiGraph) -> str:
    """A Weisfeiler-Lehman hash: equal for isomorphic circuit graphs."""
    with warnings.catch_warnings():  # networkx 3.5 notes that directed hashes changed
        warnings.simplefilter("ignore", UserWarning)
        return nx.weisfeiler_lehman_graph_hash(graph, node_attr="label", edge_attr="label")


def same_circuit(g1: nx.DiGraph, g2: nx.DiGraph) -> bool:
    """The two circuit graphs are isomorphic with their labels."""

    def match(a, b):
        return a["label"] == b["label"]

    return nx.is_isomorphic(g1, g2, node_match=match, edge_match=match)


@dataclass(frozen=True)
class CircuitClass:
    """One circuit class of an atlas: its patterns, its circuit, its counts and its universality.

    Attributes
    ----------
    order : int
    delays : str
        The structure convention (``"branch"`` or ``"state"``).
    representatives : tuple of Pattern
        One canonical pattern per state-permutation orbit, proved universal ones first.
    evidence : Evidence
        The class's verdict (its best pattern's).
    pattern_evidence : mapping of Pattern to Evidence
    n_neurons, n_synapses, n_branches : int
        Neurons, synapses onto neurons (self-dynamics excluded) and axon branches.
    label : str
        ``"A1"``, ``"A2"``, ... in the atlas's order.

    Examples
    --------
    >>> import symctl
    >>> best = symctl.atlas(2, workers=1).classes[0]
    >>> best.n_neurons, best.universal, best.evidence.method
    (2, True, 'closed form')
    """

    order: int
    delays: str
    representatives: tuple
    evidence: Evidence
    pattern_evidence: Mapping = field(compare=False, repr=False)
    n_neurons: int = 0
    n_synapses: int = 0
    n_branches: int = 0
    label: str = ""

    @property
    def universal(self) -> bool | None:
        """True (proved), False (refuted), or None (conjectured or not decided)."""
        return self.evidence.universal

    @property
    def conjectured(self) -> bool:
        """Whether the class is conjectured universal."""
        return self.evidence.conjectured

    @property
    def status(self) -> str:
        """``"universal"``, ``"conjectured"``, ``"not universal"`` or ``"not decided"``."""
        return self.evidence.status

    @property
    def patterns(self) -> tuple[Pattern, ...]:
        """Every pattern of the class (all state permutations of the representatives)."""
        return tuple(sorted({q for p in self.representatives for q in p.orbit()}))

    @cached_property
    def circuit(self) -> Circuit:
        """The circuit of the first representative, one symbol per weight."""
        return circuit_of(self.representatives[0], self.delays)

    def realize(self, G2) -> Realization:
        r"""A realization of ``G2`` with one of the class's patterns (every entry nonzero).

        A closed form (symbolic ``G2`` allowed), else an exact solve (a Groebner basis over
        :math:`\mathbb{Q}`; floats taken as the exact rationals they are; entries may be
        ``CRootOf``).

        Parameters
        ----------
        G2 : DiscreteTF or sympy expression in ``z``
            Proper, of the class's order, with :math:`N = G_2(\infty) \ne 0`.

        Returns
        -------
        Realization
            Its ``params`` say which pattern and method gave it.

        Raises
        ------
        ParameterError
            ``G2`` of another order, not proper, or with :math:`N = 0`.
        NotRealizableError
            No pattern of the class realizes this ``G2``; the message says why.

        Examples
        --------
        >>> import symctl
        >>> from symctl import z
        >>> A = symctl.atlas(2, workers=1)
        >>> R = A.classes[0].realize(1 + (z + 3) / (z**2 + z / 2 + 1))
        >>> bool(symctl.check_realization(R, 1 + (z + 3) / (z**2 + z / 2 + 1)))
        True
        """
        from symctl.circuitatlas.solve import realize_with

        return realize_with(self, G2)

    def to_dict(self) -> dict:
        """Plain data for ``atlas.json``."""
        return {
            "label": self.label,
            "neurons": self.n_neurons,
            "synapses": self.n_synapses,
            "branches": self.n_branches,
            "universal": self.universal,
            "conjectured": self.conjectured,
            "evidence": self.evidence.to_dict(),
            "patterns": [
                {
                    **dict(zip("FHM", p.arrays(), strict=True)),
                    "size": p.size,
                    "orbit": len(p.orbit()),
                    "evidence": self.pattern_evidence[p].to_dict(),
                }
                for p in self.representatives
            ],
        }

    @classmethod
    def from_dict(cls, data: dict, delays: str = "branch") -> CircuitClass:
        """The class :meth:`to_dict` wrote; ``delays`` is its atlas's (not in the class's dict).

        >>> import symctl
        >>> best = symctl.atlas(2, workers=1).classes[0]
        >>> type(best).from_dict(best.to_dict()) == best
        True
        """
        reps = tuple(Pattern.from_matrices(p["F"], p["H"], p["M"]) for p in data["patterns"])
        each = [Evidence.from_dict(p["evidence"]) for p in data["patterns"]]
        counts = (data[k] for k in ("neurons", "synapses", "branches", "label"))
        evidence = Evidence.from_dict(data["evidence"])
        return cls(reps[0].n, delays, reps, evidence, dict(zip(reps, each, strict=True)), *counts)

    def __repr__(self) -> str:
        return (
            f"CircuitClass({self.label or '?'}: {self.n_neurons} neurons, {self.n_synapses} "
            f"synapses, {len(self.representatives)} pattern(s), {self.status})"
        )

    def draw(self, ax=None, *, title: str | None = None):
        """Draw the class's circuit (a Figure) titled with its counts and verdict."""
        head = title or (
            f"{self.label}: {self.n_neurons} neurons, {self.n_synapses} synapses ({self.status})"
        )
        return self.circuit.draw(ax, title=head)
