"""Compatibility of a controller structure with a delay graph: the verdict and its evidence
(:func:`check_compatibility`; :func:`brute_force_compatibility`, the tests' reference)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType

import numpy as np

from symctl._util.display import LatexMixin
from symctl._util.validate import positive_int
from symctl.compatibility.assignment import DelayAssignment
from symctl.compatibility.csp import build_problem, explain, solve_chain, solve_search
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.signalgraph import zero_one_bfs
from symctl.compatibility.structure import Structure
from symctl.errors import ParameterError, SymctlTypeError
from symctl.proof import Verdict

__all__ = ["METHODS", "CompatibilityResult", "brute_force_compatibility", "check_compatibility"]

METHODS = ("auto", "chain", "search", "brute-force")
"""Methods of :func:`check_compatibility`."""

_ALIASES = {"brute force": "brute-force"}  # the first spelling symctl documented


@dataclass(frozen=True)
class CompatibilityResult(Verdict, LatexMixin):
    r"""The verdict of :func:`check_compatibility`, truthy exactly when compatible.

    Parameters
    ----------
    ok : bool
        Whether a compatible delay assignment exists.
    assignment : DelayAssignment or None
        A witness when ``ok``.
    reason : str
        A summary of the witness, or a certificate: the too-fast signal paths and the case
        analysis ruling out every placement.
    method : str
        Which algorithm answered.
    structure : Structure
    graph : DelayGraph
    paths : tuple
        The certificate's paths ``(signals, delay)`` when not ``ok``.
    stats : mapping
        Search effort (decisions, backtracks, assignments enumerated).

    Attributes
    ----------
    E_tilde : numpy.ndarray or None
        The witness's :math:`\tilde E`, None when not ``ok``.

    Examples
    --------
    >>> from symctl import DelayGraph, check_compatibility, ifp_structure
    >>> r = check_compatibility(ifp_structure(2), DelayGraph.chain([0]))
    >>> bool(r), r.method, r.E_tilde.tolist()
    (True, 'chain: bounds arc consistency', [[0.0, 0.0], [inf, 0.0]])
    >>> print(r.reason)
    Compatible; a witness assignment: v1: x; v2: gamma, u, K0, K1, K2, mu.
    """

    ok: bool
    assignment: DelayAssignment | None
    reason: str
    method: str
    structure: Structure
    graph: DelayGraph
    paths: tuple = ()
    stats: Mapping[str, int] = field(default_factory=dict)

    def __post_init__(self):
        object.__setattr__(self, "ok", bool(self.ok))
        object.__setattr__(self, "paths", tuple(self.paths))
        object.__setattr__(self, "stats", MappingProxyType(dict(self.stats)))

    _verdict = "ok"

    @property
    def evidence(self):
        """The witness :attr:`assignment` when compatible, else the certificate's :attr:`paths`."""
        return self.assignment if self.ok else self.paths

    def __hash__(self) -> int:
        stats = frozenset(self.stats.items())
        return hash((self.ok, self.assignment, self.reason, self.method, self.paths, stats))

    @cached_property
    def E_tilde(self) -> np.ndarray | None:
        r"""The witness's :math:`\tilde E`, or None."""
        return None if self.assignment is None else self.assignment.E_tilde

    def latex(self) -> str:
        if not self.ok:
            return r"\text{not compatible (" + self.method + ")}"
        return r"\text{compatible: } " + self.assignment.latex() + r" \ge " + self.graph.latex()

    def __repr__(self) -> str:
        return f"CompatibilityResult(ok={self.ok}, method={self.method!r})"


def _result(structure, graph, place, method, stats, problem=None, core=None) -> CompatibilityResult:
    if place is None:
        reason, paths = explain(problem, core, method)
        return CompatibilityResult(False, None, reason, method, structure, graph, paths, stats)
    names = structure.signal_graph.names
    vertex_of = {n: v + 1 for n, v in zip(names, place, strict=True)}
    return _compatible(DelayAssignment(structure, graph, vertex_of), method, stats)


def _compatible(assignment: DelayAssignment, method: str, stats=()) -> CompatibilityResult:
    parts = []
    for v in range(1, assignment.graph.n + 1):
        names = assignment.signals_at(v)
        shown = ", ".join(names[:8]) + (f", ... ({len(names)} signals)" if len(names) > 8 else "")
        parts.append(f"v{v}: {shown or '-'}")
    text = "Compatible; a witness assignment: " + "; ".join(parts) + "."
    S, graph = assignment.structure, assignment.graph
    return CompatibilityResult(True, assignment, text, method, S, graph, (), dict(stats))


def witness_result(structure, graph, vertex_of, method: str) -> CompatibilityResult:
    """The result for a constructed assignment, checked by the definition's words (RuntimeError
    if not compatible: a construction contradicting its theorem)."""
    assignment = DelayAssignment(structure, graph, vertex_of)
    bad = assignment.violations()
    if bad:  # pragma: no cover - the constructions' theorems
        raise RuntimeError(f"the constructed assignment is not compatible: {bad[:3]}")
    return _compatible(assignment, method)


def _problem(structure, graph):
    """The checked arguments' constraint problem, or the verdict when the pins contradict."""
    if not isinstance(structure, Structure):
        raise SymctlTypeError(f"structure: expected a Structure, got {type(structure).__name__}")
    if not isinstance(graph, DelayGraph):
        raise SymctlTypeError(f"graph: expected a DelayGraph, got {type(graph).__name__}")
    problem = build_problem(structure, graph)
    if isinstance(problem, str):
        return CompatibilityResult(False, None, problem, "input/output check", structure, graph)
    return problem


MAX_DECISIONS = 1_000_000
"""Default bound on the backtracking search's decisions (:func:`check_compatibility`)."""


def check_compatibility(
    structure: Structure,
    graph: DelayGraph,
    *,
    method: str = "auto",
    max_decisions: int = MAX_DECISIONS,
) -> CompatibilityResult:
    """Decide whether a structure is compatible with a delay graph, with a witness or a proof.

    Parameters
    ----------
    structure : Structure
    graph : DelayGraph
    method : {"auto", "chain", "search", "brute-force"}
        ``"auto"``: bounds arc consistency on a chain (polynomial), else arc consistency and
        backtracking (exact); ``"brute-force"`` (or ``"brute force"``) enumerates assignments.
    max_decisions : int, default :data:`MAX_DECISIONS`
        Bound on the search's decisions.

    Returns
    -------
    CompatibilityResult

    Raises
    ------
    SymctlTypeError
        ``structure`` is not a Structure or ``graph`` not a DelayGraph.
    ParameterError
        ``method="chain"`` for a graph that is not a chain, or an unknown method; a search that
        needs more than ``max_decisions`` decisions (not decided).

    Examples
    --------
    >>> from symctl import (DelayGraph, Structure, check_compatibility, controllable_canonical,
    ...                     controller_tf, factor)
    >>> f = factor(controller_tf(2))
    >>> S = Structure.from_factorization(f, controllable_canonical(f.G2))
    >>> r = check_compatibility(S, DelayGraph.chain([1, 1]))
    >>> bool(r), r.E_tilde.tolist()
    (True, [[0.0, 1.0, 2.0], [inf, 0.0, 1.0], [inf, inf, 0.0]])
    """
    max_decisions = positive_int(max_decisions, "max_decisions")
    method = _ALIASES.get(method, method) if isinstance(method, str) else method
    if method not in METHODS:
        raise ParameterError(f"method: must be one of {METHODS}, got {method!r}")
    if method == "brute-force":
        return brute_force_compatibility(structure, graph)
    problem = _problem(structure, graph)
    if isinstance(problem, CompatibilityResult):
        return problem
    chain = graph.chain_order
    if method == "chain" and chain is None:
        raise ParameterError("method: 'chain' needs a chain delay graph; use 'search' or 'auto'")
    if chain is not None and method in ("auto", "chain"):
        place, core = solve_chain(problem, *chain)
        return _result(structure, graph, place, "chain: bounds arc consistency", {}, problem, core)
    place, pruning, stats = solve_search(problem, max_decisions)
    name = (
        f"search: arc consistency + backtracking ({stats['decisions']} decisions, "
        f"{stats['backtracks']} backtracks)"
    )
    return _result(structure, graph, place, name, stats, problem, pruning)


def brute_force_compatibility(
    structure: Structure, graph: DelayGraph, *, limit: int = 2_000_000
) -> CompatibilityResult:
    r"""Enumerate every assignment and test :math:`\tilde E \ge E` by the definition's words (all
    pairs of signals, no reduction to wires); a failure's certificate comes from the search.

    Parameters
    ----------
    structure : Structure
    graph : DelayGraph
    limit : int, default 2_000_000
        The most assignments to enumerate.

    Returns
    -------
    CompatibilityResult
        ``stats`` counts the assignments enumerated and the compatible ones.

    Raises
    ------
    SymctlTypeError
        ``structure`` is not a Structure or ``graph`` not a DelayGraph.
    ParameterError
        When more than ``limit`` assignments would be needed.

    Examples
    --------
    >>> from symctl import DelayGraph, brute_force_compatibility, ifp_structure
    >>> r = brute_force_compatibility(ifp_structure(2), DelayGraph.chain([1, 1]))
    >>> bool(r), r.stats["assignments"], r.stats["compatible_assignments"]
    (False, 243, 0)
    """
    problem = _problem(structure, graph)
    if isinstance(problem, CompatibilityResult):
        return problem
    cs = structure.signal_graph
    S = len(cs.names)
    N = graph.n
    free = [s for s in range(S) if s not in problem.pins]
    if len(free) * math.log(N) > math.log(limit):
        raise ParameterError(
            f"limit: brute force needs {N}^{len(free)} assignments, more than {limit}"
        )
    total = N ** len(free)
    pairs = [  # every pair joined by a path, with its fewest delays
        (a, b, d)
        for a in range(S)
        for b, d in enumerate(zero_one_bfs(cs, [a]))
        if d is not None and a != b
    ]
    found = None
    count = 0
    chunk = 1 << 15
    powers = N ** np.arange(len(free), dtype=np.int64)
    for start in range(0, total, chunk):
        idx = np.arange(start, min(total, start + chunk), dtype=np.int64)
        place = np.empty((len(idx), S), dtype=np.int64)
        for s, v in problem.pins.items():
            place[:, s] = v
        if free:
            place[:, free] = (idx[:, None] // powers[None, :]) % N
        ok = np.ones(len(idx), dtype=bool)
        for a, b, d in pairs:
            ok &= graph.E[place[:, a], place[:, b]] <= d
        count += int(ok.sum())
        if found is None and ok.any():
            found = place[int(np.argmax(ok))].tolist()
    method = f"brute force ({total} assignments)"
    stats = {"assignments": total, "compatible_assignments": count}
    if found is not None:
        return _result(structure, graph, found, method, stats)
    _, pruning, _ = solve_search(problem)
    return _result(structure, graph, None, method, stats, problem, pruning)
