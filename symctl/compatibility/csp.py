r"""Compatibility as a constraint satisfaction problem: the model, two exact solvers, certificates.

**Reduction to one constraint per wire.** Write :math:`d(a, b)` for the fewest delays on a path
of the structure from signal :math:`a` to signal :math:`b`. A delay assignment :math:`v` is
compatible (:math:`\tilde E \ge E`, :mod:`~symctl.compatibility.assignment`) when :math:`d(a, b)
\ge E_{v(a) v(b)}` for every pair of signals joined by a path. When :math:`E` is a shortest-path
closure (:math:`E_{ik} \le E_{ij} + E_{jk}`, :math:`E_{ii} = 0`; every
:class:`~symctl.compatibility.delaygraph.DelayGraph` is one) this holds iff

.. math:: E_{v(a) v(b)} \le w \quad \text{for every wire } a \xrightarrow{w} b.

*Proof.* A wire is a path, so :math:`E_{v(a)v(b)} \le d(a, b) \le w`. Conversely, along a
fastest path :math:`a = s_0 \to \dots \to s_k = b` the triangle inequality gives
:math:`E_{v(a)v(b)} \le \sum_l E_{v(s_{l-1}) v(s_l)} \le \sum_l w_l = d(a, b)`. :math:`\square`

So compatibility is a binary CSP: one variable per signal with domain :math:`\{v_1, \dots,
v_N\}`, one constraint per wire.

**Chain graphs in polynomial time.** For a chain :math:`v_1 \to \dots \to v_N` with step delays
:math:`d_k \ge 0`, write :math:`D_j` for the delay from :math:`v_1` to :math:`v_j`. A wire of
delay :math:`w` allows exactly the pairs :math:`R_w = \{(i, j) : i \le j,\ D_j - D_i \le w\}`.
:math:`R_w` is closed under the componentwise max of two of its pairs: for :math:`(i_1, j_1),
(i_2, j_2) \in R_w` with :math:`j_1 \ge j_2`, either :math:`i_1 \ge i_2` (the max is
:math:`(i_1, j_1)`) or :math:`i_2 > i_1` and :math:`D_{j_1} - D_{i_2} \le D_{j_1} - D_{i_1} \le
w` (as :math:`D` is nondecreasing) with :math:`i_2 \le j_2 \le j_1`; likewise for the min. For
max-closed constraints (Jeavons and Cooper 1995) arc consistency decides satisfiability, and the
largest remaining value of every domain is a solution: for a wire :math:`(a, b)`, the max
:math:`i^*` of :math:`a`'s domain has a support :math:`(i^*, j')` and the max :math:`j^*` of
:math:`b`'s domain a support :math:`(i'', j^*)`; their max is :math:`(i^*, j^*) \in R_w`. Here
the domains stay intervals (the supports of :math:`R_w` are intervals), so arc consistency is
bounds propagation,

.. math::
    \mathrm{hi}_b \leftarrow \min(\mathrm{hi}_b, f_w(\mathrm{hi}_a)),\ \mathrm{lo}_b \leftarrow
    \max(\mathrm{lo}_b, \mathrm{lo}_a),\ \mathrm{hi}_a \leftarrow \min(\mathrm{hi}_a,
    \mathrm{hi}_b),\ \mathrm{lo}_a \leftarrow \max(\mathrm{lo}_a, g_w(\mathrm{lo}_b)),

with :math:`f_w(i) = \max\{j : D_j \le D_i + w\}` and :math:`g_w(j) = \min\{i : D_i \ge D_j -
w\}`: each bound moves at most :math:`N` times, so the work is :math:`O(N \cdot \text{wires})`.
The witness (every signal at the top of its interval) is checked wire by wire before it is
returned.

**General graphs** (NP-complete for some) are decided by arc consistency and backtracking that
maintains it. On failure the certificate is a minimal set of signal paths and, for every
placement of the signals where they meet, one path it makes too fast.
"""

from __future__ import annotations

import bisect
from collections import Counter, deque
from dataclasses import dataclass

import numpy as np

from symctl.compatibility.delaygraph import DelayGraph, _fmt
from symctl.compatibility.signalgraph import SignalGraph
from symctl.compatibility.structure import Structure
from symctl.errors import ParameterError

__all__ = ["Problem", "build_problem", "explain", "solve_chain", "solve_search"]

_MINIMIZE_LIMIT = 80  # cores up to this many wires are minimized wire by wire
_CASES_LIMIT = 243  # case analyses up to this many leaves are printed in full
_SHOWN_PATHS = 40  # a certificate's text lists this many paths; .paths keeps them all


@dataclass(frozen=True)
class Problem:
    """A signal graph's wires as constraints: pinned signals and E, with vertices from 0."""

    graph: SignalGraph
    pins: dict[int, int]
    E: np.ndarray

    def restrict(self, wire_ids) -> Problem:
        """The problem with only some wires, on the signals they touch."""
        g = self.graph
        wires = [g.wires[e] for e in sorted(wire_ids)]
        used = sorted({s for a, b, _ in wires for s in (a, b)})
        where = {s: k for k, s in enumerate(used)}
        sub = SignalGraph.from_wires(
            [g.names[s] for s in used],
            [g.kinds[s] for s in used],
            [(where[a], where[b], w) for a, b, w in wires],
            [where[s] for s in g.inputs if s in where],
            [where[s] for s in g.outputs if s in where],
        )
        return Problem(sub, {where[s]: v for s, v in self.pins.items() if s in where}, self.E)

    def satisfied(self, place: list[int]) -> bool:
        E = self.E
        return all(place[s] == v for s, v in self.pins.items()) and all(
            E[place[a], place[b]] <= w for a, b, w in self.graph.wires
        )


def build_problem(structure: Structure, graph: DelayGraph) -> Problem | str:
    """The constraint problem; a string when the pins alone contradict each other."""
    cs = structure.signal_graph
    at_in, at_out = graph.pins(len(cs.inputs), len(cs.outputs))
    pins: dict[int, int] = {}
    for s, v in zip(cs.inputs, at_in, strict=True):
        pins[s] = v - 1
    for s, v in zip(cs.outputs, at_out, strict=True):
        if pins.get(s, v - 1) != v - 1:
            role = "an input" if s in cs.inputs else "an output"
            return (
                f"The signal {cs.names[s]!r} is both {role} (at v{pins[s] + 1}) and an output "
                f"(at v{v}); no assignment can put it at two vertices (give the output a signal "
                "of its own, e.g. a unit gain, and the delay graph decides)."
            )
        pins[s] = v - 1
    return Problem(cs, pins, graph.E)


def solve_chain(problem: Problem, order: tuple[int, ...], D: tuple[int, ...]):
    """Bounds arc consistency on chain positions; returns (placement | None, core wires)."""
    N = len(D)
    position = {v - 1: p for p, v in enumerate(order)}
    S = len(problem.graph.names)
    tables: dict[int, tuple[list[int], list[int]]] = {}

    def table(w):  # f_w and g_w of the module text, on chain positions
        if w not in tables:
            f = [bisect.bisect_right(D, D[p] + w) - 1 for p in range(N)]
            tables[w] = f, [bisect.bisect_left(D, D[q] - w) for q in range(N)]
        return tables[w]

    lo = [0] * S
    hi = [N - 1] * S
    events: list[tuple[int, int]] = []  # (wire, parent event); pins have wire -1
    lo_ev = [-1] * S
    hi_ev = [-1] * S
    for s, v in problem.pins.items():  # consistent: build_problem refuses contradictions
        lo[s] = hi[s] = position[v]
        events.append((-1, -1))
        lo_ev[s] = hi_ev[s] = len(events) - 1
    queue = deque(problem.pins)
    queued = [s in problem.pins for s in range(S)]
    succ, pred = problem.graph.succ, problem.graph.pred

    def tighten(v: int, new_hi: int, new_lo: int, e: int, x: int) -> bool:
        """Narrow v's interval to [new_lo, new_hi] (wire e, from x); True when it empties."""
        moved = [(hi, hi_ev, new_hi)] if new_hi < hi[v] else []
        if new_lo > lo[v]:
            moved.append((lo, lo_ev, new_lo))
        for bound, ev, new in moved:  # each move records the event that caused it
            bound[v] = new
            events.append((e, ev[x]))
            ev[v] = len(events) - 1
        if not moved:
            return False
        if lo[v] > hi[v]:
            return True
        if not queued[v]:
            queued[v] = True
            queue.append(v)
        return False

    failed = -1
    while queue and failed < 0:
        x = queue.popleft()
        queued[x] = False
        hx, lx = hi[x], lo[x]
        for b, w, e in succ[x]:  # b after x: at most f_w(hi_x), at least lo_x
            if tighten(b, table(w)[0][hx], lx, e, x):
                failed = b
                break
        else:
            for a, w, e in pred[x]:  # a before x: at most hi_x, at least g_w(lo_x)
                if tighten(a, hx, table(w)[1][lx], e, x):
                    failed = a
                    break
    if failed >= 0:
        core = set()
        for ev in (lo_ev[failed], hi_ev[failed]):
            while ev >= 0:
                wire, ev = events[ev]
                if wire >= 0:
                    core.add(wire)
        return None, core
    place = [order[p] - 1 for p in hi]
    if not problem.satisfied(place):  # pragma: no cover - the max-closure theorem
        raise RuntimeError("chain propagation produced a witness that violates a wire")
    return place, set()


def solve_search(problem: Problem, max_decisions: int | None = None):
    """Arc consistency + backtracking (maintaining arc consistency).

    Returns ``(placement | None, pruning wires, stats)``; the wires that ever removed a value
    form an unsatisfiable core when there is no solution.
    """
    E = problem.E
    N = E.shape[0]
    S = len(problem.graph.names)
    full = (1 << N) - 1
    allowed: dict[tuple[int, int], list[int]] = {}
    cache: dict[tuple[int, int, int], int] = {}

    def support(d, w, dom):  # d = 0: the targets supported by some value of dom; 1: the sources
        out = cache.get((d, w, dom))
        if out is None:
            if (d, w) not in allowed:
                allowed[0, w] = [sum(1 << j for j in range(N) if E[i, j] <= w) for i in range(N)]
                allowed[1, w] = [sum(1 << i for i in range(N) if E[i, j] <= w) for j in range(N)]
            out = 0
            for i in range(N):
                if dom >> i & 1:
                    out |= allowed[d, w][i]
            cache[d, w, dom] = out
        return out

    doms = [full] * S
    trail: list[tuple[int, int]] = []
    pruning: set[int] = set()
    succ, pred = problem.graph.succ, problem.graph.pred
    stats = {"decisions": 0, "backtracks": 0}

    def propagate(start) -> bool:
        queue = list(start)
        queued = set(queue)

        def narrow(v: int, allowed, e: int) -> bool:
            """Intersect v's domain with ``allowed`` (wire e); False when it empties."""
            new = doms[v] & allowed
            if new == doms[v]:
                return True
            pruning.add(e)
            trail.append((v, doms[v]))
            doms[v] = new
            if not new:
                return False
            if v not in queued:
                queued.add(v)
                queue.append(v)
            return True

        while queue:
            x = queue.pop()
            queued.discard(x)
            dx = doms[x]
            if not all(narrow(b, support(0, w, dx), e) for b, w, e in succ[x]):
                return False
            if not all(narrow(a, support(1, w, dx), e) for a, w, e in pred[x]):
                return False
        return True

    for s, v in problem.pins.items():
        doms[s] = 1 << v
    if not propagate(list(problem.pins)):
        return None, pruning, stats
    # static order: breadth first from the pinned signals, so choices follow the wires
    order: list[int] = []
    seen = [False] * S
    for root in [*problem.pins, *range(S)]:
        if seen[root]:
            continue
        seen[root] = True
        bfs = deque([root])
        while bfs:
            x = bfs.popleft()
            order.append(x)
            for y, _, _ in (*succ[x], *pred[x]):
                if not seen[y]:
                    seen[y] = True
                    bfs.append(y)
    stack: list[list] = []
    pos = 0
    while True:
        while pos < S and doms[order[pos]] & (doms[order[pos]] - 1) == 0:
            pos += 1
        if pos == S:
            place = [d.bit_length() - 1 for d in doms]
            if not problem.satisfied(place):  # pragma: no cover - arc consistency
                raise RuntimeError("search produced a witness that violates a wire")
            return place, pruning, stats
        values = [v for v in range(N - 1, -1, -1) if doms[order[pos]] >> v & 1]
        stack.append([len(trail), pos, values])
        while stack:
            mark, p, values = stack[-1]
            while len(trail) > mark:
                x, old = trail.pop()
                doms[x] = old
            if not values:
                stack.pop()
                stats["backtracks"] += 1
                continue
            v = values.pop(0)
            stats["decisions"] += 1
            if max_decisions is not None and stats["decisions"] > max_decisions:
                raise ParameterError(
                    f"max_decisions: the search stopped after {max_decisions} decisions "
                    "without a verdict (not decided); raise max_decisions to search further"
                )
            x = order[p]
            trail.append((x, doms[x]))
            doms[x] = 1 << v
            if propagate([x]):
                pos = p
                break
        else:
            return None, pruning, stats


def _minimal_core(problem: Problem, core: set[int]) -> list[int]:
    """An unsatisfiable set of wires, minimized wire by wire when small."""

    def unsat(ids):
        return solve_search(problem.restrict(ids))[0] is None

    core_list = sorted(core)
    if not core_list or not unsat(core_list):
        core_list = list(range(len(problem.graph.wires)))
    if len(core_list) <= _MINIMIZE_LIMIT:
        k = 0
        while k < len(core_list):
            trial = core_list[:k] + core_list[k + 1 :]
            if unsat(trial):
                core_list = trial
            else:
                k += 1
    return core_list


def _paths(problem: Problem, core: list[int]) -> list[tuple[list[int], int]]:
    """Merge wires through free signals with one wire in and one out, one of them delay-free.

    Exact: such a signal can sit at the vertex of the neighbour across its delay-free wire, so
    the merged path asks :math:`E \\le w_1 + w_2` and nothing else.
    """
    wires = problem.graph.wires
    paths = {k: ([wires[e][0], wires[e][1]], wires[e][2]) for k, e in enumerate(core)}
    ins: dict[int, list[int]] = {}
    outs: dict[int, list[int]] = {}
    for k, (sig, _) in paths.items():
        outs.setdefault(sig[0], []).append(k)
        ins.setdefault(sig[-1], []).append(k)
    changed = True
    while changed:
        changed = False
        for m in list(ins):
            if m in problem.pins or len(ins.get(m, ())) != 1 or len(outs.get(m, ())) != 1:
                continue
            k_in, k_out = ins[m][0], outs[m][0]
            (s1, w1), (s2, w2) = paths[k_in], paths[k_out]
            if k_in == k_out or (w1 and w2):
                continue
            paths[k_in] = (s1 + s2[1:], w1 + w2)
            del paths[k_out]
            ins[m], outs[m] = [], []
            end = ins[s2[-1]]
            end[end.index(k_out)] = k_in
            changed = True
    return sorted(paths.values(), key=lambda p: (p[0][0] not in problem.pins, p[0]))


def explain(problem: Problem, core: set[int], method: str) -> tuple[str, tuple]:
    E = problem.E
    names = problem.graph.names
    N = E.shape[0]
    core_list = _minimal_core(problem, core)
    paths = _paths(problem, core_list)
    letters = [
        "abcdefghijklmnopqrstuvwxyz"[k] if k < 26 else f"p{k + 1}" for k in range(len(paths))
    ]

    lines = [
        "No delay assignment of this structure is compatible with the delay graph "
        f"(decided by {method}). These signal paths suffice for the contradiction:"
    ]
    for k, (letter, (sig, w)) in enumerate(zip(letters, paths, strict=True)):
        if k == _SHOWN_PATHS and len(paths) > _SHOWN_PATHS + 1:
            lines.append(f"  ... {len(paths) - k} more paths (all of them in the result's .paths)")
            break
        lines.append(f"  ({letter}) {' -> '.join(names[s] for s in sig)}, delay {w}")
    pinned = sorted({p for sig, _ in paths for p in (sig[0], sig[-1]) if p in problem.pins})
    if pinned:
        where = ", ".join(
            f"{names[s]} at v{problem.pins[s] + 1} ({'input' if s in problem.graph.inputs else 'output'})"
            for s in pinned
        )
        lines.append(
            f"with {where}.".replace(", ", " and ", 1) if len(pinned) == 2 else f"with {where}."
        )
    meets = Counter(p for sig, _ in paths for p in {sig[0], sig[-1]} if p not in problem.pins)
    junctions = sorted(meets, key=lambda s: (-meets[s], s))

    def violated(place):
        """The path this placement makes too fast by the widest margin (None if none)."""
        found = [
            (E[place[sig[0]], place[sig[-1]]] - w, letter, sig[0], sig[-1], w)
            for letter, (sig, w) in zip(letters, paths, strict=True)
            if sig[0] in place and sig[-1] in place and E[place[sig[0]], place[sig[-1]]] > w
        ]
        if not found:
            return None
        _, letter, a, b, w = max(found, key=lambda f: f[0])  # the first of the widest
        i, j = place[a] + 1, place[b] + 1
        return (
            f"path ({letter}) runs from {names[a]} at v{i} to {names[b]} at v{j} with "
            f"delay {w}, so Ẽ[{i},{j}] <= {w} < E[{i},{j}] = {_fmt(E[i - 1, j - 1])}"
        )

    base = dict(problem.pins)
    first = violated(base)
    if first:
        lines.append(f"Already {first}.")
    elif N ** len(junctions) <= _CASES_LIMIT:
        lines.append("Every placement fails:")

        def tree(level, place, indent):
            s = junctions[level]
            for v in range(N):
                here = {**place, s: v}
                why = violated(here)
                head = f"{indent}{names[s]} at v{v + 1}"
                if why:
                    lines.append(f"{head}: {why}")
                elif level + 1 < len(junctions):
                    lines.append(f"{head}:")
                    tree(level + 1, here, indent + "  ")
                else:  # pragma: no cover - the core is unsatisfiable
                    lines.append(f"{head}: (no path violated; certificate incomplete)")

        tree(0, base, "  ")
    else:
        lines.append(
            f"No placement of the {len(junctions)} signals where these paths meet "
            f"({', '.join(names[s] for s in junctions[:6])}{', ...' if len(junctions) > 6 else ''}) "
            f"satisfies all of them ({N}^{len(junctions)} placements, excluded by {method})."
        )
    certificate = tuple((tuple(names[s] for s in sig), w) for sig, w in paths)
    return "\n".join(lines), certificate
