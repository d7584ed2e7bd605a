r"""Compatibility of a controller (a transfer function) with a delay graph: the theorems.

A controller is compatible with a delay graph when one of its realizations has a compatible
structure. Notation: :math:`G \ne 0` proper with Markov parameters :math:`h_0, h_1, \dots` and
relative degree :math:`r` (the first :math:`j` with :math:`h_j \ne 0`); wires carry at most
:math:`W` steps each (``max_wire_delay``, :math:`\infty` by default); :math:`L_W` is the delay of
the fastest path from the sensor :math:`v_1` to the actuator :math:`v_N` over edges of at most
:math:`W` steps (:math:`\infty` if there is none; :math:`L_\infty = E_{1N}`).

**Theorem 1.** Some structure, with wires of at most :math:`W` steps, of some realization of
:math:`G` is compatible with the delay graph iff :math:`r \ge L_W`.

*Proof.* Necessity. Unroll the structure in time: :math:`h_j` is the sum, over the walks of the
structure from its input to its output whose wires carry :math:`j` steps in all, of the products
of their gains. As :math:`h_r \ne 0`, some walk :math:`s_0 \to \dots \to s_k` has total delay
:math:`r`. In a compatible assignment every wire :math:`a \xrightarrow{w} b` has :math:`E_{v(a)
v(b)} \le w \le W` (the reduction to one constraint per wire, :mod:`symctl.compatibility.csp`).
A fastest route from :math:`v(a)` to :math:`v(b)` has delay :math:`E_{v(a) v(b)}`, so each of
its edges has at most that many steps, at most :math:`W`. Joining these routes gives a walk from
:math:`v_1` (the input's vertex) to :math:`v_N` (the output's) over edges of at most :math:`W`
steps, of delay :math:`\sum E_{v(s_{l-1}) v(s_l)} \le \sum w_l = r`; hence :math:`L_W \le r`.

Sufficiency. Take a fastest such path :math:`q_0 = v_1 \to \dots \to q_m = v_N` with edge delays
:math:`e_1, \dots, e_m` (:math:`\sum e_l = L_W`). Factor :math:`G = G_3 G_2 G_1` with one
first-order section :math:`C z^{1-e}/(z - \epsilon)` per edge of :math:`e \ge 1` steps: a branch
structure whose self-loop has a unit delay and whose input branch an axon of :math:`e \le W`
steps, the first half of the sections in :math:`G_1`, the rest in :math:`G_3`. :math:`G_1 G_3`
has relative degree :math:`L_W \le r`, so :math:`G_2 = G / (G_3 G_1)` is proper and any
realization of it has unit delays. Put each section's input gain at the vertex where its edge
starts and the rest of it where the edge ends, and all of :math:`G_2` at the vertex after the
last sensor-side section. Every wire then either stays at one vertex (:math:`E = 0`), crosses
zero-delay edges with delay 0, or crosses one edge of :math:`e` steps with delay :math:`e`; on
the path read as a chain every wire constraint holds, and on the whole graph too, since
:math:`E` between two vertices of the path is at most their distance along it. :math:`G = 0` is
compatible with any graph. :math:`\square`

*Corollary (chain graphs).* A chain with steps :math:`d_k`, total :math:`D`: with unit wires
compatible iff :math:`r \ge D` and every :math:`d_k \le 1`; with axons iff :math:`r \ge D` (a 10
ms axon sampled at 5 ms is one wire of delay 2).

**Theorem 2 (parallel decomposition).** Let :math:`P_1, \dots, P_k` be paths from :math:`v_1` to
:math:`v_N` over edges of at most :math:`W` steps, of delays :math:`L_1 < \dots < L_k`, and
:math:`r \ge L_1`. Then :math:`G = G_1 + \dots + G_k` with :math:`G_i = \sum_{L_i \le j <
L_{i+1}} h_j z^{-j}` (:math:`i < k`) and :math:`G_k = \sum_{j \ge L_k} h_j z^{-j}`; each
:math:`G_i` has relative degree at least :math:`L_i`, is factored along :math:`P_i` as in
Theorem 1, and the parallel connection (the input shared at :math:`v_1`, the parts' outputs
summed by an adder at :math:`v_N`) is compatible: each part's wires satisfy their constraints as
in Theorem 1 and the adder's wires stay at :math:`v_N`. A part with no Markov parameter is left
out. :math:`\square`

**Theorem 3 (MIMO).** Let input :math:`j` enter at sensor vertex :math:`s_j` and output
:math:`i` leave at actuator vertex :math:`a_i`
(:meth:`~symctl.compatibility.delaygraph.DelayGraph.pins`: one vertex for all, or one per
channel). Some structure of some realization of the :math:`p \times m` controller :math:`G` is
compatible iff every nonzero entry :math:`G_{ij}` has relative degree at least :math:`L_W(s_j
\to a_i)`, the delay of the fastest path from :math:`s_j` to :math:`a_i` over edges of at most
:math:`W` steps.

*Proof.* Necessity: the first nonzero Markov parameter of :math:`G_{ij}` is a sum over walks
from input :math:`j` to output :math:`i`; the argument of Theorem 1 applies to one such walk,
from :math:`s_j` to :math:`a_i`. Sufficiency: realize each nonzero entry as in Theorem 1 along
its own fastest path, read its input from input :math:`j` (at :math:`s_j`) and sum the entries
of output :math:`i` in one adder at :math:`a_i`; each entry's wires satisfy their constraints as
in Theorem 1 and the adders' wires stay at :math:`a_i`. :math:`\square`
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import sympy as sp

from symctl._util.display import LatexMixin
from symctl._util.validate import bounded_int
from symctl.compatibility.block import MAX_WIRE_STEPS
from symctl.compatibility.check import CompatibilityResult, witness_result
from symctl.compatibility.construction import (
    PathPart,
    along_path,
    fastest_path,
    markov_split,
    path_delays,
    slowest_path,
)
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.statespace import structure_realization
from symctl.compatibility.structure import Structure
from symctl.design.tf import DiscreteTF
from symctl.errors import ParameterError, SymctlTypeError
from symctl.proof import Verdict
from symctl.realization.realizers import get_realizer

__all__ = ["CONSTRUCTIONS", "ControllerCompatibility", "controller_compatibility"]

CONSTRUCTIONS = ("path", "parallel")
"""The constructions of :func:`controller_compatibility` (Theorems 1 and 2)."""

_SCOPE = "all realizations"


@dataclass(frozen=True)
class ControllerCompatibility(Verdict, LatexMixin):
    """Whether some realization of a controller has a structure compatible with a delay graph.

    The verdict of :func:`controller_compatibility`, truthy exactly when compatible.

    Parameters
    ----------
    ok : bool
        Whether a compatible realization exists.
    realization : Realization or None
        A realization whose structure is ``structure``.
    structure : Structure or None
        The constructed compatible structure.
    check : CompatibilityResult or None
        The structure-level result with the witness assignment.
    reason : str
        The theorem's condition that fails, or the construction.
    scope : str
        ``"all realizations"``: the verdict is a theorem about every realization.
    method : str
        The theorem and construction that answered.
    parts : tuple of PathPart
        The parts of the construction, each a transfer function along a path.

    Examples
    --------
    >>> from symctl import DelayGraph, controller_compatibility, controller_tf
    >>> r = controller_compatibility(controller_tf(2), DelayGraph.chain([1, 1]))
    >>> bool(r), r.scope, bool(r.check), r.parts[0].path
    (True, 'all realizations', True, (1, 2, 3))
    """

    ok: bool
    realization: object
    structure: Structure | None
    check: CompatibilityResult | None
    reason: str
    scope: str
    method: str
    parts: tuple[PathPart, ...] = ()

    _verdict = "ok"

    @property
    def evidence(self):
        """The structure-level :attr:`check` when compatible, else the :attr:`reason`."""
        return self.check if self.ok else self.reason

    def __hash__(self) -> int:
        return hash((self.ok, self.structure, self.reason, self.scope, self.method))

    def latex(self) -> str:
        verdict = "compatible" if self.ok else "not compatible"
        return rf"\text{{{verdict} ({self.scope})}}"

    def __repr__(self) -> str:
        return (
            f"ControllerCompatibility(ok={self.ok}, scope={self.scope!r}, method={self.method!r})"
        )


def controller_compatibility(
    G,
    graph: DelayGraph,
    *,
    base: str = "controllable",
    delays: str = "branch",
    max_wire_delay: int | None = None,
    construction: str = "path",
    paths=None,
) -> ControllerCompatibility:
    """Decide whether a controller :math:`G` has a realization compatible with a delay graph.

    Exact for every delay graph (Theorems 1-3 of the module text); when compatible, a structure
    is built along a path or several (Theorem 2) and checked.

    Parameters
    ----------
    G : DiscreteTF or sympy expression in z
        The controller, proper; SISO, or MIMO (Theorem 3: ``construction`` and ``paths`` do not
        apply).
    graph : DelayGraph
    base : str
        The realization of :math:`G_2` in the construction: a realizer that keeps the symbols
        (``"controllable"``, ``"observable"``, ``"general"``, ...).
    delays : {"branch", "state"}
        The structure of :math:`G_2` in the construction.
    max_wire_delay : int, optional
        The most steps one wire may carry (default: no bound; ``1``: the paper's unit delays).
    construction : {"path", "parallel"}
        ``"path"``: :math:`G = G_3 G_2 G_1` along the fastest path (or ``paths[0]``);
        ``"parallel"``: Theorem 2, by default along the fastest and slowest simple paths.
    paths : sequence of sequences of int, optional
        The paths to build along, as vertex lists from 1 (e.g. ``[1, 2, 4]``), following edges
        of the graph from :math:`v_1` to :math:`v_N`.

    Returns
    -------
    ControllerCompatibility

    Raises
    ------
    SymctlTypeError
        ``graph`` is not a DelayGraph.
    DimensionError
        The graph's sensor or actuator vertices fit neither one for all of ``G``'s inputs
        (outputs) nor one per input (output).
    ParameterError
        ``G`` improper; an unknown ``base``, ``delays`` or ``construction``; a bad
        ``max_wire_delay``; a path that is not a path of the graph.

    Examples
    --------
    >>> from symctl import DelayGraph, controller_compatibility, controller_tf
    >>> r = controller_compatibility(controller_tf(2), DelayGraph.chain([1, 1, 1]))
    >>> r.ok, r.scope
    (False, 'all realizations')
    >>> print(r.reason)  # doctest: +ELLIPSIS
    Not compatible: the relative degree 2 of G is below 3, the delay of the fastest path ...
    >>> two = DelayGraph.from_edges(4, [(1, 2, 1), (2, 4, 1), (1, 3, 1), (3, 2, 1)])
    >>> p = controller_compatibility(controller_tf(2), two, construction="parallel")
    >>> p.ok, [part.path for part in p.parts]
    (True, [(1, 2, 4), (1, 3, 2, 4)])
    """
    tf = DiscreteTF.from_expr(G)
    if not isinstance(graph, DelayGraph):
        raise SymctlTypeError(f"graph: expected a DelayGraph, got {type(graph).__name__}")
    get_realizer(base, "base", where=lambda r: r.keeps_symbols)
    if delays not in ("branch", "state"):
        raise ParameterError(f"delays: must be 'branch' or 'state', got {delays!r}")
    if construction not in CONSTRUCTIONS:
        raise ParameterError(f"construction: must be one of {CONSTRUCTIONS}, got {construction!r}")
    W = None
    if max_wire_delay is not None:
        W = bounded_int(max_wire_delay, "max_wire_delay", 1, MAX_WIRE_STEPS)
    r = tf.relative_degree
    if r < 0:
        raise ParameterError("G: improper (numerator degree above denominator degree)")
    if not tf.is_siso:
        if paths is not None:
            raise ParameterError(
                "paths: give paths for a SISO controller; a MIMO one takes "
                "each entry's fastest path"
            )
        return _mimo(tf, graph, W, base, delays)
    zero = tf.num == 0
    (src,), (dst,) = graph.pins(1, 1)
    routes = _routes(graph, W, construction, paths)
    theorem = "theorem 1" + (" (chain graphs)" if graph.is_chain else "")
    bound = "" if W is None else f" over edges of at most {W} step{'s' * (W != 1)}"
    if routes is None and not zero:
        return _no(
            f"Not compatible: no path from v{src} to v{dst} uses only edges of at most {W} "
            f"step{'s' * (W != 1)}; every wire of the structures asked for carries at most {W}, "
            "so no signal path from the input to the output can cross the graph.",
            theorem,
        )
    if not zero and r < routes[0][0]:
        which = "the fastest path" if paths is None else "the fastest path given"
        return _no(
            f"Not compatible: the relative degree {r} of G is below {routes[0][0]}, the delay of "
            f"{which} from v{src} to v{dst}{bound}; every path from the input to the output of "
            "a compatible structure has at least that many delays, so the first Markov "
            "parameters of G would vanish.",
            theorem,
        )
    if zero:
        S = Structure({"u": ("input",), "y": ("sum", ())}, "u", "y")
        check = witness_result(S, graph, {"u": src, "y": dst}, "construction (G = 0)")
        return _yes(S, check, "Compatible: G = 0 has no signal path. ", "G = 0")
    pieces = [tf.expr]
    if construction == "parallel" and len(routes) > 1:
        pieces = markov_split(tf, [L for L, _, _ in routes])
    parts = tuple(
        along_path(piece, route[1], route[2], base=base, structure=delays)
        for piece, route in zip(pieces, routes, strict=True)
        if piece != 0
    )
    if len(parts) == 1:
        S, vertex_of, R = parts[0].structure, parts[0].vertex_of, parts[0].realization
    else:
        labels = [f"P{k + 1}" for k in range(len(parts))]
        S = Structure.parallel(*(p.structure for p in parts), names=labels)
        vertex_of, R = _parallel_places(S, parts, labels, src, dst), None
    method = f"{theorem} + {'parallel decomposition' if len(parts) > 1 else 'path construction'}"
    check = witness_result(S, graph, vertex_of, method)
    return _yes(S, check, f"Compatible ({theorem}): {_describe(parts)}. ", method, parts, R)


def _mimo(tf: DiscreteTF, graph: DelayGraph, W, base: str, delays: str):
    """Theorem 3: each nonzero entry along its own fastest path, summed at the actuators (or
    :func:`_shared` with one sensor and one actuator vertex).
    """
    p, m = tf.shape
    at_in, at_out = graph.pins(m, p)
    routes = []
    for i in range(p):
        for j in range(m):
            e = DiscreteTF.from_expr(sp.cancel(tf.expr[i, j]), dt=tf.dt)
            if e.num == 0:
                continue
            route = fastest_path(graph, W, (at_in[j], at_out[i]))
            where = f"G[{i + 1},{j + 1}] (v{at_in[j]} -> v{at_out[i]})"
            if route is None:
                return _no(
                    f"Not compatible: no path for {where} uses only edges of at most {W} steps.",
                    "theorem 3 (MIMO)",
                )
            if e.relative_degree < route[0]:
                return _no(
                    f"Not compatible: the relative degree {e.relative_degree} of {where} is "
                    f"below {route[0]}, the delay of its fastest path; every path from input "
                    f"{j + 1} to output {i + 1} of a compatible structure has at least that many "
                    "delays.",
                    "theorem 3 (MIMO)",
                )
            routes.append((i, j, e, route))
    if routes and len(set(at_in)) == len(set(at_out)) == 1:
        return _shared(tf, graph, routes[0][3], base, delays)
    entries = []
    for i, j, e, route in routes:
        part = along_path(e, route[1], route[2], base=base, structure=delays)
        entries.append((i, j, dataclasses.replace(part, label=f"G[{i + 1},{j + 1}]")))
    blocks: dict = {f"u{j + 1}": ("input",) for j in range(m)}
    place = {f"u{j + 1}": at_in[j] for j in range(m)}
    sums: list[list[str]] = [[] for _ in range(p)]
    for i, j, part in entries:
        label = f"G{i + 1},{j + 1}"
        S = Structure.series(part.structure, names=[label])
        rename = {S.inputs[0]: f"u{j + 1}"}
        for name, b in S.blocks.items():
            if b.kind == "input":
                continue
            blocks[name] = b._replace(inputs=tuple(rename.get(x, x) for x in b.inputs))
            place[name] = part.vertex_of[name.removeprefix(label + ".")]
        sums[i].append(rename.get(S.outputs[0], S.outputs[0]))
    outputs = [f"y{i + 1}" for i in range(p)]
    for i, name in enumerate(outputs):
        blocks[name] = ("sum", tuple(sums[i]))
        place[name] = at_out[i]
    S = Structure(blocks, tuple(f"u{j + 1}" for j in range(m)), outputs)
    check = witness_result(S, graph, {n: place[n] for n in S.blocks}, "theorem 3 (MIMO)")
    reason = (
        f"Compatible (theorem 3, MIMO): each of the {len(entries)} nonzero entries G[i,j] = "
        "G3 G2 G1 along its fastest path from input j's sensor vertex to output i's actuator "
        "vertex, the entries of each output summed there. "
    )
    parts = [part for *_, part in entries]
    return _yes(S, check, reason, "theorem 3 (MIMO) + construction per entry", parts)


def _shared(tf: DiscreteTF, graph: DelayGraph, route, base: str, delays: str):
    """Theorem 3 with one pathway: Theorem 1's construction by channel, one :math:`G_2` for all."""
    part = dataclasses.replace(
        along_path(tf, route[1], route[2], base=base, structure=delays), label="G"
    )
    S = part.structure
    check = witness_result(S, graph, part.vertex_of, "theorem 3 (MIMO)")
    reason = (
        "Compatible (theorem 3, MIMO): every input has one sensor vertex and every output one "
        "actuator vertex, so " + _describe([part]) + ", with one section per channel and edge "
        "and one G2 for every entry. "
    )
    return _yes(S, check, reason, "theorem 3 (MIMO) + path construction", [part], part.realization)


def _yes(S, check, reason, method, parts=(), realization=None) -> ControllerCompatibility:
    R = structure_realization(S) if realization is None else realization
    reason += check.reason
    return ControllerCompatibility(True, R, S, check, reason, _SCOPE, method, tuple(parts))


def _no(reason: str, theorem: str) -> ControllerCompatibility:
    return ControllerCompatibility(False, None, None, None, reason, _SCOPE, theorem)


def _routes(graph: DelayGraph, W, construction: str, paths):
    """The paths to build along, fastest first, as ``(delay, vertices, edge delays)``."""
    if paths is not None:
        if isinstance(paths, str) or not hasattr(paths, "__iter__"):
            raise ParameterError("paths: expected a sequence of vertex lists, e.g. [[1, 2, 3]]")
        routes = []
        for k, path in enumerate(paths):
            vertices, steps = path_delays(graph, path, W, f"paths[{k}]")
            routes.append((sum(steps), vertices, steps))
        if not routes:
            raise ParameterError("paths: give at least one path")
        if construction == "path" and len(routes) > 1:
            raise ParameterError("paths: the path construction takes one path; use 'parallel'")
        routes.sort()
        if len({L for L, _, _ in routes}) != len(routes):
            raise ParameterError(
                "paths: the paths of a parallel decomposition need distinct delays, got "
                f"{[L for L, _, _ in routes]}"
            )
        return routes
    fast = fastest_path(graph, W)
    if fast is None:
        return None
    if construction == "path":
        return [fast]
    slow = slowest_path(graph, W)
    return [fast] if slow is None or slow[0] == fast[0] else [fast, slow]


def _parallel_places(S: Structure, parts, labels, src: int, dst: int) -> dict[str, int]:
    place = {
        f"{label}.{name}": v
        for part, label in zip(parts, labels, strict=True)
        for name, v in part.vertex_of.items()
    }
    place |= dict.fromkeys(S.inputs, src) | dict.fromkeys(S.outputs, dst)
    return {name: place[name] for name in S.blocks}


def _describe(parts) -> str:
    out = []
    for k, part in enumerate(parts):
        route = " -> ".join(f"v{v}" for v in part.path)
        axons = [e for e in part.delays if e > 1]
        note = f", axons of {', '.join(map(str, axons))} steps" if axons else ""
        crossing = sum(1 for e in part.delays if e > 0)
        what = "G" if len(parts) == 1 else f"part {k + 1} (Markov parameters from {part.delay})"
        out.append(
            f"{what} = G3 G2 G1 along {route} (delay {part.delay}{note}; "
            f"{crossing // 2} sensor-side and {crossing - crossing // 2} actuator-side sections)"
        )
    return "; ".join(out)
