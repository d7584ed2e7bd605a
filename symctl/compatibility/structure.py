r"""Controller structures: signal-flow graphs of scalar signals, gains, adders and unit delays.

The paper's definition (section "Structure, delay graphs, and compatibility"):
the *structure* of a controller is the block diagram of one realization, made
of gain and addition blocks joined by scalar signals, possibly with delays.
Here every block produces exactly one scalar **signal**, so a structure is a
directed graph whose nodes are signals, each labelled with the kind of block
that makes it:

``"input"``
    a controller input (:math:`u`; the paper's IFP structure calls it :math:`x`);
``"gain"``
    :math:`g \cdot a(t)` of its one input :math:`a` (the gain value is kept for
    drawings; it does not change the structure);
``"sum"``
    the sum of its inputs (an adder);
``"delay"``
    its one input delayed by one step, :math:`a(t-1)` (a broken line in the
    paper's figures; the delayed signal is a signal, e.g. the paper's
    :math:`\gamma`).

A wire ``a -> b`` has delay 1 when ``b`` is a delay block and 0 otherwise.
Loops without a delay (algebraic loops) are refused.

Two conventions keep the diagrams as the paper draws them: a gain equal to
``1`` is a plain wire (no block), and an adder with a single input is no block
(the signal passes through). Zero entries make no block.

:meth:`Structure.from_realization` gives the two structures of a realization
that the paper's Fig. g1g3 contrasts:

* ``delays="branch"`` (default; the paper's choice for :math:`G_1` and
  :math:`G_3`): every term :math:`F_{ij} x_j` and :math:`H_i u` passes through
  its own unit delay into the adder that forms :math:`x_i`, so
  :math:`x_i(t) = \sum_j F_{ij} x_j(t-1) + H_i u(t-1)`;
* ``delays="state"``: one delay after each adder,
  :math:`x_i(t+1) = p_i(t)`, :math:`p_i = \sum_j F_{ij} x_j + H_i u`;

and in both :math:`y = M x + N u`.

>>> from symctl import controllable_canonical, observable_canonical, z
>>> S = Structure.from_realization(controllable_canonical(1 / (z**2 - z / 2)))
>>> S.inputs, S.outputs, S.count("delay")
(('u',), ('x1',), 3)
>>> same_structure(ifp_structure(2), ifp_structure(2))
True
"""

from __future__ import annotations

import itertools
import math
import re
from collections import deque
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import cached_property
from types import MappingProxyType
from typing import NamedTuple

import networkx as nx
import sympy as sp

from symctl._util.display import LatexMixin, latex
from symctl._util.validate import nonneg_int, to_expr
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.plotting.common import (  # drawing moves out next
    figure_and_axes,
    finish_figure,
    text_size,
)
from symctl.realization.realization import Realization
from symctl.symbols import gain_symbols

__all__ = ["KINDS", "Block", "Structure", "ifp_structure", "same_structure"]

KINDS = ("input", "gain", "sum", "delay")
"""The block kinds of a structure."""


class Block(NamedTuple):
    """One block of a structure and the signal it produces.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    inputs : tuple of str
        Names of the signals it reads (none for an input, one for a gain or a
        delay, any number for a sum).
    gain : sympy expression or None
        The gain value of a gain block (for display; structure ignores it).
    part : str
        The part of a series connection it came from (``""`` if none).

    >>> Block("gain", ("u",), 2)
    Block(kind='gain', inputs=('u',), gain=2, part='')
    """

    kind: str
    inputs: tuple[str, ...] = ()
    gain: sp.Expr | None = None
    part: str = ""


class _Compiled(NamedTuple):
    """Integer form of a structure for the checkers: signals ``0..S-1``."""

    names: tuple[str, ...]
    index: dict[str, int]
    kinds: tuple[str, ...]
    wires: tuple[tuple[int, int, int], ...]  # (source, target, delay)
    succ: tuple[tuple[tuple[int, int, int], ...], ...]  # per signal: (target, delay, wire id)
    pred: tuple[tuple[tuple[int, int, int], ...], ...]  # per signal: (source, delay, wire id)
    inputs: tuple[int, ...]
    outputs: tuple[int, ...]


@dataclass(frozen=True, eq=False)
class Structure(LatexMixin):
    r"""A controller structure: scalar signals produced by gains, adders and unit delays.

    Parameters
    ----------
    blocks : mapping of str to Block (or tuple ``(kind, inputs, gain)``)
        Every signal of the structure, by name, with the block producing it.
    inputs : str or sequence of str
        The controller's input signal(s); they are exactly the ``"input"`` blocks.
    outputs : str or sequence of str
        The controller's output signal(s) (any signals).

    Raises
    ------
    ParameterError
        Unknown kind or signal name, a gain or delay without exactly one input,
        an algebraic loop (a cycle without delay), inputs that are not the
        input blocks.
    SymctlTypeError
        ``blocks`` is not a mapping.

    Examples
    --------
    The paper's IFP controller for :math:`T = 1`, :math:`\mu = K_0 x + K_1 u`,
    :math:`u(t+1) = \mu(t)`:

    >>> S = Structure(
    ...     {"x": ("input",), "K0": ("gain", ("x",), 3), "K1": ("gain", ("u",), 2),
    ...      "mu": ("sum", ("K0", "K1")), "u": ("delay", ("mu",))},
    ...     inputs="x", outputs="u")
    >>> len(S), S.count("gain"), sorted(S.wires())[:2]
    (5, 2, [('K0', 'mu', 0), ('K1', 'mu', 0)])
    """

    blocks: Mapping[str, Block]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]

    def __init__(self, blocks, inputs, outputs):
        if not isinstance(blocks, Mapping):
            raise SymctlTypeError(
                f"blocks: expected a mapping of signal names to blocks, got {type(blocks).__name__}"
            )
        clean: dict[str, Block] = {}
        for name, value in blocks.items():
            clean[_name(name, "blocks")] = _block(name, value)
        ins = _names(inputs, "inputs")
        outs = _names(outputs, "outputs")
        for name, block in clean.items():
            for src in block.inputs:
                if src not in clean:
                    raise ParameterError(
                        f"blocks: signal {name!r} reads {src!r}, which is not a signal"
                    )
        for argname, group in (("inputs", ins), ("outputs", outs)):
            for name in group:
                if name not in clean:
                    raise ParameterError(f"{argname}: {name!r} is not a signal of the structure")
        declared = [n for n, b in clean.items() if b.kind == "input"]
        if sorted(declared) != sorted(ins) or len(set(ins)) != len(ins):
            raise ParameterError(
                f"inputs: must list each input block once; input blocks are {declared}, got {ins}"
            )
        if not ins:
            raise ParameterError("inputs: a structure needs at least one input")
        if not outs:
            raise ParameterError("outputs: a structure needs at least one output")
        object.__setattr__(self, "blocks", MappingProxyType(clean))
        object.__setattr__(self, "inputs", ins)
        object.__setattr__(self, "outputs", outs)
        loop = _algebraic_loop(self._compiled)
        if loop:
            raise ParameterError(
                "blocks: algebraic loop (a cycle without delay) through " + " -> ".join(loop)
            )

    # ------------------------------------------------------------ views
    def __len__(self) -> int:
        return len(self.blocks)

    @property
    def signals(self) -> tuple[str, ...]:
        """All signal names, in construction order."""
        return tuple(self.blocks)

    @property
    def input(self) -> str:
        """The input signal of a single-input structure."""
        if len(self.inputs) != 1:
            raise DimensionError(f"input: the structure has {len(self.inputs)} inputs")
        return self.inputs[0]

    @property
    def output(self) -> str:
        """The output signal of a single-output structure."""
        if len(self.outputs) != 1:
            raise DimensionError(f"output: the structure has {len(self.outputs)} outputs")
        return self.outputs[0]

    def count(self, kind: str) -> int:
        """Number of blocks of one kind (``"gain"``, ``"sum"``, ``"delay"``, ``"input"``)."""
        if kind not in KINDS:
            raise ParameterError(f"kind: must be one of {KINDS}, got {kind!r}")
        return sum(1 for b in self.blocks.values() if b.kind == kind)

    def wires(self) -> Iterable[tuple[str, str, int]]:
        """The wires ``(source, target, delay)``; delay 1 exactly into a delay block."""
        names = self._compiled.names
        return ((names[a], names[b], w) for a, b, w in self._compiled.wires)

    @cached_property
    def _compiled(self) -> _Compiled:
        names = tuple(self.blocks)
        index = {n: i for i, n in enumerate(names)}
        kinds = tuple(b.kind for b in self.blocks.values())
        succ: list[list] = [[] for _ in names]
        pred: list[list] = [[] for _ in names]
        wires = []
        for b, block in enumerate(self.blocks.values()):
            w = 1 if block.kind == "delay" else 0
            for src in block.inputs:
                a = index[src]
                succ[a].append((b, w, len(wires)))
                pred[b].append((a, w, len(wires)))
                wires.append((a, b, w))
        return _Compiled(
            names,
            index,
            kinds,
            tuple(wires),
            tuple(map(tuple, succ)),
            tuple(map(tuple, pred)),
            tuple(index[n] for n in self.inputs),
            tuple(index[n] for n in self.outputs),
        )

    @cached_property
    def graph(self) -> nx.DiGraph:
        """The structure as a :class:`networkx.DiGraph`.

        Node attributes ``kind``, ``gain``, ``part`` and ``role`` (a tuple of
        ``("in", k)`` / ``("out", k)`` marks); edge attribute ``delay``.
        """
        g = nx.DiGraph()
        for name, block in self.blocks.items():
            role = tuple(("in", k) for k, n in enumerate(self.inputs) if n == name) + tuple(
                ("out", k) for k, n in enumerate(self.outputs) if n == name
            )
            g.add_node(name, kind=block.kind, gain=block.gain, part=block.part, role=role)
        for a, b, w in self.wires():
            g.add_edge(a, b, delay=w)
        return g

    def delay_distances(self, source: str) -> dict[str, int]:
        """Fewest delays on any path from ``source`` to each reachable signal (0-1 BFS)."""
        cs = self._compiled
        if source not in cs.index:
            raise ParameterError(f"source: {source!r} is not a signal of the structure")
        dist = _zero_one_bfs(cs, [cs.index[source]])
        return {cs.names[i]: d for i, d in enumerate(dist) if d is not None}

    # ------------------------------------------------------------ constructors
    @classmethod
    def from_realization(cls, R: Realization, delays: str = "branch") -> Structure:
        r"""The structure of a realization :math:`(F, H, M, N)`.

        Signals: inputs ``u`` (``u1, u2, ...`` for several), states ``x1 .. xn``,
        gain outputs named by their entry (``F[1,2]`` is :math:`F_{12} x_2`,
        ``H[1]``, ``M[2]``, ``N``), delayed branch terms ``z^-1 F[1,2]``, adders
        ``p1 ..`` (state delays) and the output ``y`` (unless the output is an
        existing signal, e.g. ``y = x_2``).

        Parameters
        ----------
        R : Realization
        delays : {"branch", "state"}
            Where the unit delays sit relative to the adders (see the module text).

        >>> from symctl.realization.realization import first_order_realization
        >>> import sympy as sp
        >>> eps, C = sp.symbols("epsilon C")
        >>> S = Structure.from_realization(first_order_realization(eps, C))
        >>> sorted(S.wires())[:3]
        [('F[1,1]', 'z^-1 F[1,1]', 1), ('H', 'z^-1 H', 1), ('u', 'H', 0)]
        """
        if not isinstance(R, Realization):
            raise SymctlTypeError(f"R: expected a Realization, got {type(R).__name__}")
        if delays not in ("branch", "state"):
            raise ParameterError(f"delays: must be 'branch' or 'state', got {delays!r}")
        n = R.n
        p, q = R.shape
        u = ["u"] if q == 1 else [f"u{k + 1}" for k in range(q)]
        x = [f"x{i + 1}" for i in range(n)]
        y = ["y"] if p == 1 else [f"y{k + 1}" for k in range(p)]
        blocks: dict[str, Block] = {name: Block("input") for name in u}

        def entry(mat, letter, i, j):
            rows, cols = mat.shape
            if letter != "F" and cols == 1 and rows == 1:
                return letter
            if letter != "F" and cols == 1:
                return f"{letter}[{i + 1}]"
            if letter != "F" and rows == 1:
                return f"{letter}[{j + 1}]"
            return f"{letter}[{i + 1},{j + 1}]"

        def terms(i, mats):
            """Nonzero terms of row i: (value, source signal, label)."""
            out = []
            for mat, letter, sources in mats:
                for j, src in enumerate(sources):
                    value = mat[i, j]
                    if not _is_zero(value):
                        out.append((value, src, entry(mat, letter, i, j)))
            return out

        def signal(value, src, label):
            """The signal carrying value * src: src itself for a unit gain."""
            if value == 1:
                return src
            blocks[label] = Block("gain", (src,), value)
            return label

        for i in range(n):
            row = terms(i, ((R.F, "F", x), (R.H, "H", u)))
            if delays == "branch":
                carried = [(signal(*t), t[2]) for t in row]
                if len(carried) == 1:
                    blocks[x[i]] = Block("delay", (carried[0][0],))
                else:
                    names = []
                    for src, label in carried:
                        blocks[f"z^-1 {label}"] = Block("delay", (src,))
                        names.append(f"z^-1 {label}")
                    blocks[x[i]] = Block("sum", tuple(names))
            else:
                carried = [signal(*t) for t in row]
                if len(carried) == 1:
                    src = carried[0]
                else:
                    src = f"p{i + 1}"
                    blocks[src] = Block("sum", tuple(carried))
                blocks[x[i]] = Block("delay", (src,))
        outputs = []
        for k in range(p):
            row = terms(k, ((R.M, "M", x), (R.N, "N", u)))
            if len(row) == 1:
                value, src, _ = row[0]
                outputs.append(signal(value, src, y[k]))
            else:
                blocks[y[k]] = Block("sum", tuple(signal(*t) for t in row))
                outputs.append(y[k])
        return cls(blocks, u, outputs)

    @classmethod
    def series(cls, *parts: Realization | Structure, names: Iterable[str] | None = None):
        """The series connection of ``parts`` in signal-flow order (the first acts first).

        Realizations are turned into structures with ``delays="branch"``. Each
        part's signals are prefixed by its name (``G1.``, ``G2.``, ... by
        default) and recorded in :attr:`Block.part`; the outputs of one part
        *are* the inputs of the next (no extra block).

        >>> from symctl import controller_tf
        >>> from symctl.realization.factorization import factor
        >>> from symctl.realization.realization import controllable_canonical, first_order_realization
        >>> f = factor(controller_tf(2))
        >>> G1 = first_order_realization(f.sensor_eps[0], f.sensor_C[0])
        >>> G3 = first_order_realization(f.actuator_eps[0], f.actuator_C[0])
        >>> S = Structure.series(G1, controllable_canonical(f.G2), G3)
        >>> S.inputs, S.outputs
        (('G1.u',), ('G3.x1',))
        """
        if not parts:
            raise ParameterError("parts: give at least one realization or structure")
        labels = [f"G{k + 1}" for k in range(len(parts))] if names is None else list(names)
        if len(labels) != len(parts) or len(set(labels)) != len(labels):
            raise ParameterError(f"names: need {len(parts)} distinct names, got {labels!r}")
        structures = []
        for k, part in enumerate(parts):
            if isinstance(part, Realization):
                part = cls.from_realization(part)
            elif not isinstance(part, Structure):
                raise SymctlTypeError(
                    f"parts[{k}]: expected a Realization or a Structure, got {type(part).__name__}"
                )
            structures.append(part)
        blocks: dict[str, Block] = {}
        inputs: tuple[str, ...] = ()
        previous: tuple[str, ...] = ()
        for k, (label, part) in enumerate(zip(labels, structures, strict=True)):
            if k and len(part.inputs) != len(previous):
                raise DimensionError(
                    f"parts: {len(previous)} outputs of part {k} feed "
                    f"{len(part.inputs)} inputs of part {k + 1}"
                )
            rename = {s: f"{label}.{s}" for s in part.blocks}
            if k:
                rename.update(zip(part.inputs, previous, strict=True))
            for name, block in part.blocks.items():
                if k and block.kind == "input":
                    continue
                blocks[rename[name]] = Block(
                    block.kind,
                    tuple(rename[s] for s in block.inputs),
                    block.gain,
                    f"{label}.{block.part}" if block.part else label,
                )
            if not k:
                inputs = tuple(rename[s] for s in part.inputs)
            previous = tuple(rename[s] for s in part.outputs)
        return cls(blocks, inputs, previous)

    # ------------------------------------------------------------ display
    @classmethod
    def from_factorization(
        cls, factorization, R2: Realization, delays: str = "branch"
    ) -> Structure:
        r"""The structure of the whole controller :math:`G_3 G_2 G_1` (the paper's Fig. g1g3).

        The first-order sections of :math:`G_1` and :math:`G_3` take the
        ``"branch"`` structure (the paper's choice, a unit delay on each branch
        into the adder); ``R2``, a realization of ``factorization.G2``, takes
        ``delays``. Parts are named ``G1``, ``G2``, ``G3`` (``G1.1``, ``G1.2``, ...
        when a side has several sections).

        >>> from symctl import controller_tf, controllable_canonical, factor
        >>> f = factor(controller_tf(2))
        >>> S = Structure.from_factorization(f, controllable_canonical(f.G2))
        >>> S.count("sum"), S.count("delay")
        (4, 8)
        """
        from symctl.realization.realization import first_order_realization

        f = factorization
        dt = f.G.dt
        first = [
            first_order_realization(e, c, dt) for e, c in zip(f.sensor_eps, f.sensor_C, strict=True)
        ]
        last = [
            first_order_realization(e, c, dt)
            for e, c in zip(f.actuator_eps, f.actuator_C, strict=True)
        ]
        ds, da = len(first), len(last)
        names = [f"G1.{k + 1}" if ds > 1 else "G1" for k in range(ds)]
        names += ["G2"] + [f"G3.{k + 1}" if da > 1 else "G3" for k in range(da)]
        parts = [cls.from_realization(p, "branch") for p in first]
        parts += [cls.from_realization(R2, delays)]
        parts += [cls.from_realization(p, "branch") for p in last]
        return cls.series(*parts, names=names)

    def equations(self) -> list[sp.Eq]:
        r"""One equation per adder and delay, with the gains written into them.

        >>> ifp_structure(2).equations()[-1]
        Eq(mu(t), K_0*x(t) + K_1*gamma(t) + K_2*u(t))
        """
        t = sp.Symbol("t", integer=True)

        def value(name, time):
            block = self.blocks[name]
            if block.kind == "gain":
                gain = block.gain if block.gain is not None else sp.Symbol(_symbol_name(name))
                return gain * value(block.inputs[0], time)
            return sp.Function(_symbol_name(name))(time)

        out = []
        for name, block in self.blocks.items():
            if block.kind == "delay":
                rhs = value(block.inputs[0], t - 1)
            elif block.kind == "sum":
                rhs = sp.Add(*(value(s, t) for s in block.inputs))
            else:
                continue
            out.append(sp.Eq(sp.Function(_symbol_name(name))(t), rhs, evaluate=False))
        return out

    def latex(self) -> str:
        """The equations of :meth:`equations`, one per line."""
        body = r" \\ ".join(latex(eq) for eq in self.equations())
        return r"\begin{gathered}" + body + r"\end{gathered}"

    def _repr_latex_(self) -> str | None:
        if len(self) > 60:
            return None  # too long to be useful; Jupyter falls back to repr
        return super()._repr_latex_()

    def __repr__(self) -> str:
        counts = ", ".join(f"{self.count(k)} {k}" for k in ("gain", "sum", "delay"))
        return f"Structure({len(self)} signals: {counts}; inputs={self.inputs}, outputs={self.outputs})"

    def draw(self, ax=None, *, title: str | None = None, max_signals: int = 400):
        """Draw the structure in the style of the paper's block diagrams.

        Gains are boxes with their value, adders circles with a plus, one-step
        delays broken (dashed) lines into the delayed signal (a small dot, named
        when the paper names it, e.g. :math:`\\gamma`); inputs on the left,
        outputs on the right. Returns a :class:`matplotlib.figure.Figure`; the
        caller saves it (``fig.savefig("ifp.svg")`` or ``.png``).

        >>> fig = ifp_structure(2).draw()
        >>> type(fig).__name__
        'Figure'
        """
        return _draw(self, ax=ax, title=title, max_signals=max_signals)


# ---------------------------------------------------------------- helpers
def _name(value, argname: str) -> str:
    if not isinstance(value, str) or not value:
        raise SymctlTypeError(f"{argname}: signal names must be non-empty strings, got {value!r}")
    return value


def _names(value, argname: str) -> tuple[str, ...]:
    if isinstance(value, str):
        return (value,)
    if not isinstance(value, Iterable):
        raise SymctlTypeError(f"{argname}: expected a signal name or names, got {value!r}")
    return tuple(_name(v, argname) for v in value)


def _block(name: str, value) -> Block:
    if isinstance(value, Block):
        block = value
    elif isinstance(value, tuple | list) and 1 <= len(value) <= 4:
        block = Block(*value)
    else:
        raise SymctlTypeError(
            f"blocks[{name!r}]: expected a Block or a tuple (kind, inputs, gain), got {value!r}"
        )
    if block.kind not in KINDS:
        raise ParameterError(f"blocks[{name!r}]: kind must be one of {KINDS}, got {block.kind!r}")
    inputs = (block.inputs,) if isinstance(block.inputs, str) else tuple(block.inputs)
    for src in inputs:
        _name(src, f"blocks[{name!r}].inputs")
    expected = {"input": (0, 0), "gain": (1, 1), "delay": (1, 1), "sum": (0, None)}[block.kind]
    low, high = expected
    if len(inputs) < low or (high is not None and len(inputs) > high):
        raise ParameterError(
            f"blocks[{name!r}]: a {block.kind} block takes "
            f"{'exactly ' + str(high) if high is not None else 'any number of'} "
            f"input(s), got {list(inputs)}"
        )
    gain = None
    if block.kind == "gain" and block.gain is not None:
        gain = to_expr(block.gain, f"blocks[{name!r}].gain")
    if not isinstance(block.part, str):
        raise SymctlTypeError(f"blocks[{name!r}].part: expected a string, got {block.part!r}")
    return Block(block.kind, inputs, gain, block.part)


def _is_zero(value) -> bool:
    value = sp.sympify(value)
    if value == 0:
        return True
    return bool(value.free_symbols) and sp.cancel(value) == 0


def _symbol_name(name: str) -> str:
    return name.replace(" ", "").replace("^-1", "d_")


def _zero_one_bfs(cs: _Compiled, sources, allowed=None) -> list[int | None]:
    """Fewest delays from any of ``sources`` to every signal (None if unreachable)."""
    dist: list[int | None] = [None] * len(cs.names)
    queue = deque()
    for s in sources:
        dist[s] = 0
        queue.append(s)
    done = [False] * len(cs.names)
    while queue:
        a = queue.popleft()
        if done[a]:
            continue
        done[a] = True
        da = dist[a]
        for b, w, _ in cs.succ[a]:
            if allowed is not None and not allowed[b]:
                continue
            nd = da + w
            if dist[b] is None or nd < dist[b]:
                dist[b] = nd
                if w:
                    queue.append(b)
                else:
                    queue.appendleft(b)
    return dist


def _algebraic_loop(cs: _Compiled) -> list[str] | None:
    """A cycle of delay-free wires, or None (Kahn's algorithm on those wires)."""
    indeg = [sum(1 for _, w, _ in p if w == 0) for p in cs.pred]
    stack = [i for i, d in enumerate(indeg) if d == 0]
    seen = 0
    while stack:
        a = stack.pop()
        seen += 1
        for b, w, _ in cs.succ[a]:
            if w == 0:
                indeg[b] -= 1
                if indeg[b] == 0:
                    stack.append(b)
    if seen == len(cs.names):
        return None
    # walk backwards inside the remaining nodes until a node repeats
    node = next(i for i, d in enumerate(indeg) if d > 0)
    path: list[int] = []
    position: dict[int, int] = {}
    while node not in position:
        position[node] = len(path)
        path.append(node)
        node = next(a for a, w, _ in cs.pred[node] if w == 0 and indeg[a] > 0)
    cycle = path[position[node] :][::-1]
    return [cs.names[i] for i in (*cycle, cycle[0])]


# ---------------------------------------------------------------- the paper's structures
def ifp_structure(T: int = 2) -> Structure:
    r"""The structure of the paper's IFP controller, eqs. augmented_states and ifp_controller.

    .. math::
        \mu(t) = K_0 x(t) + K_1 \gamma_1(t) + \dots + K_{T-1}\gamma_{T-1}(t) + K_T u(t),
        \quad \gamma_1(t+1) = \mu(t),\ \gamma_{k+1}(t+1) = \gamma_k(t),\
        u(t+1) = \gamma_{T-1}(t)

    (for :math:`T = 1`, :math:`u(t+1) = \mu(t)`). As in the paper's compatibility
    argument, the input is called ``x`` (:math:`\delta_f`) and the output ``u``
    (:math:`\delta_r`); for :math:`T = 2` the one intermediate signal is ``gamma``.
    Gain blocks are named ``K0 .. KT``; the delays are the broken lines of
    Fig. ifp_diagram.

    >>> S = ifp_structure(2)
    >>> S.signals
    ('x', 'gamma', 'u', 'K0', 'K1', 'K2', 'mu')
    >>> S.count("delay"), S.inputs, S.outputs
    (2, ('x',), ('u',))
    """
    if isinstance(T, bool) or not isinstance(T, int):
        raise ParameterError(f"T: must be an integer >= 1, got {T!r}")
    T = nonneg_int(T, "T")
    if T < 1:
        raise ParameterError(f"T: must be an integer >= 1, got {T!r}")
    K = gain_symbols(T)
    gammas = ["gamma"] if T == 2 else [f"gamma{k}" for k in range(1, T)]
    blocks: dict[str, Block] = {"x": Block("input")}
    chain = ["mu", *gammas, "u"]
    for prev, nxt in itertools.pairwise(chain):
        blocks[nxt] = Block("delay", (prev,))
    for k, src in enumerate(["x", *gammas, "u"]):
        blocks[f"K{k}"] = Block("gain", (src,), K[k])
    blocks["mu"] = Block("sum", tuple(f"K{k}" for k in range(T + 1)))
    return Structure(blocks, "x", "u")


def same_structure(a: Structure, b: Structure) -> bool:
    """Whether two structures have the same block configuration, whatever the gain values.

    A graph isomorphism (networkx VF2) that maps block kinds to the same kinds and
    inputs and outputs to the inputs and outputs of the same position. The
    paper's remark: swapping :math:`x_1, x_2` in the observable canonical
    realization changes the sparsity pattern but not the structure.

    >>> import sympy as sp
    >>> from symctl import observable_canonical, controllable_canonical, z
    >>> G2 = (2*z**2 + z + 1) / (z**2 - z / 2 - sp.Rational(1, 8))
    >>> R = observable_canonical(G2)
    >>> swapped = R.similar([[0, 1], [1, 0]])
    >>> def pattern(R):
    ...     return [[int(e != 0) for e in row] for row in R.F.tolist()]
    >>> pattern(R), pattern(swapped)
    ([[0, 1], [1, 1]], [[1, 1], [1, 0]])
    >>> same_structure(Structure.from_realization(R), Structure.from_realization(swapped))
    True
    >>> same_structure(Structure.from_realization(R),
    ...                Structure.from_realization(controllable_canonical(G2)))
    False
    """
    for argname, value in (("a", a), ("b", b)):
        if not isinstance(value, Structure):
            raise SymctlTypeError(f"{argname}: expected a Structure, got {type(value).__name__}")
    if len(a) != len(b) or len(a.inputs) != len(b.inputs) or len(a.outputs) != len(b.outputs):
        return False
    if any(a.count(k) != b.count(k) for k in KINDS):
        return False

    def match(n1, n2):
        return n1["kind"] == n2["kind"] and n1["role"] == n2["role"]

    return nx.is_isomorphic(a.graph, b.graph, node_match=match)


# ---------------------------------------------------------------- drawing
# Drawing coordinates are inches (one data unit is one inch of the figure), so
# text measured in points fits its box whatever the size of the structure.
_FONT = 9  # points: gain values and adders
_NAME_FONT = 8  # points: signal names
_GAP = 0.55  # horizontal gap between layers
_ROW = 0.72  # vertical pitch of the rows inside a layer
_SUM_R = 0.12  # adder radius
_DOT_R = 0.03  # dot of a named signal (input, delayed signal)
_PAD = 0.07  # padding around a gain value inside its box
_MAX_LABEL = 25  # gain values with more visible characters are shown by block name
_INK = "0.15"


class _Route(NamedTuple):
    """A feedback wire drawn below (or above) the rows: ``source -> *chain -> target``."""

    source: str
    chain: tuple[str, ...]
    target: str


def _gain_label(block: Block, name: str) -> str:
    """The gain value as mathtext, or the block name when it is long or not renderable."""
    if block.gain is None:
        return name
    text = latex(block.gain)
    visible = re.sub(r"\\(left|right|frac|dfrac)\b", "", text)
    visible = re.sub(r"\\[a-zA-Z]+", "m", visible)
    if len(re.sub(r"[{}_^\s]", "", visible)) > _MAX_LABEL:
        return name
    try:
        text_size(f"${text}$", _FONT)
    except ValueError:
        return name
    return f"${text}$"


def _signal_label(name: str) -> str:
    """``gamma2`` -> ``$\\gamma_{2}$``, ``G2.x1`` -> ``$x_{1}$`` (the part is labelled apart)."""
    from sympy.printing.latex import greek_letters_set

    short = name.rpartition(".")[2]
    match = re.fullmatch(r"([A-Za-z]+)(\d*)", short)
    if not match:
        return short
    stem, digits = match.groups()
    stem = "\\" + stem if stem in greek_letters_set else stem
    return f"${stem}_{{{digits}}}$" if digits else f"${stem}$"


def _feedback_edges(S: Structure, g: nx.DiGraph) -> list[tuple[str, str]]:
    """Wires closing a cycle, found by a depth-first search from the inputs (in order)."""
    order = list(S.inputs) + [n for n in g if n not in S.inputs]
    state: dict[str, int] = {}
    back = []
    for root in order:
        if root in state:
            continue
        stack = [(root, iter(g.successors(root)))]
        state[root] = 1
        while stack:
            node, children = stack[-1]
            child = next(children, None)
            if child is None:
                state[node] = 2
                stack.pop()
            elif state.get(child) == 1:
                back.append((node, child))
            elif child not in state:
                state[child] = 1
                stack.append((child, iter(g.successors(child))))
    return back


def _feedback_routes(S: Structure, g: nx.DiGraph) -> list[_Route]:
    """Each feedback wire with the single-input, single-output gains and delays before it.

    Those blocks (e.g. the IFP's :math:`K_1, K_2`, a state's self-gain :math:`F_{ii}`) are
    drawn on the feedback arc itself, as the paper does, and take no place in the rows.
    """
    ends = set(S.inputs) | set(S.outputs)
    taken: set[str] = set()
    routes = []
    for tail, head in _feedback_edges(S, g):
        chain: list[str] = []
        node = tail
        while (
            node not in ends
            and node != head
            and node not in taken
            and g.nodes[node]["kind"] in ("gain", "delay")
            and g.in_degree(node) == 1
            and g.out_degree(node) == 1
        ):
            chain.insert(0, node)
            taken.add(node)
            node = next(iter(g.predecessors(node)))
        routes.append(_Route(node, tuple(chain), head))
    return routes


def _layering(S: Structure, g: nx.DiGraph, routes: list[_Route]) -> tuple[nx.DiGraph, dict]:
    """The forward graph (feedback removed) and its layers: longest path from the inputs."""
    on_arcs = {n for r in routes for n in r.chain}
    index = {n: k for k, n in enumerate(S.blocks)}
    dag = nx.DiGraph()
    dag.add_nodes_from(n for n in S.blocks if n not in on_arcs)
    skip = {(r.chain[-1] if r.chain else r.source, r.target) for r in routes}
    dag.add_edges_from((a, b) for a, b in g.edges if a in dag and b in dag and (a, b) not in skip)
    layer: dict[str, int] = {}
    for node in nx.lexicographical_topological_sort(dag, key=index.__getitem__):
        layer[node] = max((layer[p] + 1 for p in dag.predecessors(node)), default=0)
    last = max(layer.values(), default=0)
    if any(layer[n] == last for n in dag if n not in S.outputs):
        last += 1
    for n in S.outputs:
        if n not in S.inputs and n in layer:
            layer[n] = last
    return dag, layer


def _pava_rows(desired: list[float]) -> list[int]:
    """Integer rows, top first, one apart at least, closest to ``desired`` (isotonic fit)."""
    blocks: list[list[float]] = []  # [mean, weight] of pooled z_i = y_i + i, non-increasing
    for i, d in enumerate(desired):
        blocks.append([d + i, 1.0])
        while len(blocks) > 1 and blocks[-2][0] < blocks[-1][0]:
            mean, weight = blocks.pop()
            blocks[-1][0] = (blocks[-1][0] * blocks[-1][1] + mean * weight) / (
                blocks[-1][1] + weight
            )
            blocks[-1][1] += weight
    z = [mean for mean, weight in blocks for _ in range(int(weight))]
    rows = [math.floor(zi - i + 0.5) for i, zi in enumerate(z)]
    for i in range(1, len(rows)):
        rows[i] = min(rows[i], rows[i - 1] - 1)
    return rows


def _order_rows(columns: dict[int, list], preds: dict, succs: dict) -> dict:
    """Rows inside each layer: barycenter sweeps (left to right, back, and again)."""
    row: dict = {}
    for neighbours in (preds, succs, preds, succs, preds):
        cols = sorted(columns, reverse=neighbours is succs)
        for c in cols:
            nodes = columns[c]
            desired = {}
            for n in nodes:
                ys = [row[m] for m in neighbours[n] if m in row]
                desired[n] = sum(ys) / len(ys) if ys else row.get(n, 0.0)
            nodes.sort(key=lambda n, d=desired: -d[n])
            row.update(zip(nodes, _pava_rows([desired[n] for n in nodes]), strict=True))
    return row


class _Geometry:
    """Sizes of the drawn blocks (inches) and where a wire meets them."""

    def __init__(self, S: Structure):
        self.S = S
        self.label: dict[str, str] = {}
        self.size: dict[str, tuple[float, float]] = {}
        self.name: dict[str, tuple[str, float]] = {}
        for name, block in S.blocks.items():
            if block.kind == "gain":
                label = _gain_label(block, name)
                w, h = text_size(label, _FONT)
                self.label[name] = label
                self.size[name] = (max(w + 2 * _PAD, 0.3), max(h + 2 * _PAD, 0.26))
            elif block.kind == "sum":
                self.size[name] = (2 * _SUM_R, 2 * _SUM_R)
            else:
                self.size[name] = (2 * _DOT_R, 2 * _DOT_R)
            if block.kind != "gain" and not name.rpartition(".")[2].startswith("z^-1"):
                text = _signal_label(name)
                self.name[name] = (text, text_size(text, _NAME_FONT)[0])

    def kind(self, name) -> str:
        return self.S.blocks[name].kind if name in self.S.blocks else "dummy"

    def half(self, name) -> float:
        """Half the width a node needs in its column, its name included."""
        if name not in self.size:
            return 0.05
        w = self.size[name][0] / 2
        if name in self.name:
            w = max(w, w + 0.03 + self.name[name][1])
        return w

    def reach(self, name, offset: float, axis: int) -> float:
        """Distance from the centre to the edge along ``axis`` (0 = x) at ``offset`` across."""
        if name not in self.size:
            return 0.0
        if self.kind(name) == "sum":
            return math.sqrt(max(_SUM_R**2 - offset**2, 0.0))
        return self.size[name][axis] / 2


def _spread(count: int, half: float) -> list[float]:
    """``count`` offsets from ``+half`` to ``-half`` (0 for one)."""
    if count <= 1:
        return [0.0] * count
    return [half - 2 * half * k / (count - 1) for k in range(count)]


def _draw(S: Structure, ax=None, *, title=None, max_signals=400):

    if len(S) > max_signals:
        raise ParameterError(
            f"max_signals: the structure has {len(S)} signals, more than {max_signals}; "
            "raise max_signals to draw it anyway"
        )
    g = S.graph
    geo = _Geometry(S)
    routes = _feedback_routes(S, g)
    dag, layer = _layering(S, g, routes)

    # forward wires spanning several layers pass through one dummy slot per layer
    columns: dict[int, list] = {}
    for node in dag:
        columns.setdefault(layer[node], []).append(node)
    preds: dict = {n: [] for n in dag}
    succs: dict = {n: [] for n in dag}
    paths: dict[tuple[str, str], list] = {}
    for a, b in dag.edges:
        path = [a, *(("~", a, b, k) for k in range(layer[a] + 1, layer[b])), b]
        for k, node in enumerate(path[1:-1], start=layer[a] + 1):
            columns[k].append(node)
            preds[node], succs[node] = [], []
        for p, q in itertools.pairwise(path):
            succs[p].append(q)
            preds[q].append(p)
        paths[(a, b)] = path
    row = _order_rows(columns, preds, succs)
    col = {n: c for c, nodes in columns.items() for n in nodes}
    y = {n: _ROW * r for n, r in row.items()}

    # column widths, then widen where a feedback arc must hold its blocks
    ncol = max(columns) + 1
    hw = [max(geo.half(n) for n in columns[c]) for c in range(ncol)]
    gaps = [_GAP] * (ncol + 1)  # gaps[c] lies left of column c
    item_width = {n: geo.size[n][0] for r in routes for n in r.chain}
    for r in routes:
        need = sum(item_width[n] for n in r.chain) + 0.3 * len(r.chain) + 0.2
        a, b = col[r.source], col[r.target]
        if a == b:
            hw[a] = max(hw[a], (need - _GAP) / 2)
    x = [0.0] * ncol
    for c in range(1, ncol):
        x[c] = x[c - 1] + hw[c - 1] + gaps[c] + hw[c]
    for r in routes:
        need = sum(item_width[n] for n in r.chain) + 0.3 * len(r.chain) + 0.2
        a, b = col[r.source], col[r.target]
        if a > b and x[a] - x[b] < need:
            for c in range(b + 1, a + 1):
                gaps[c] += (need - (x[a] - x[b])) / (a - b)
    for c in range(1, ncol):
        x[c] = x[c - 1] + hw[c - 1] + gaps[c] + hw[c]
    pos = {n: (x[col[n]], y[n]) for n in col}

    # feedback arcs: side (below unless more is in the way there), legs, blocks, lane
    lowest = {c: min(y[n] for n in columns[c]) for c in columns}
    highest = {c: max(y[n] for n in columns[c]) for c in columns}
    # a leg straight down (up) from a node unless something is below (above) it in its
    # column or a self-loop hangs there
    looped = {r.source for r in routes if r.source == r.target}
    # legs in a gap: drops left of rises, the longest arcs outermost (they take outer lanes)
    legs: dict[int, list] = {}  # gap index -> [(order, route id, "drop" | "rise")]
    side, drop, rise, straight = {}, {}, {}, {}
    for k, r in enumerate(routes):
        ends = ((r.source, col[r.source]), (r.target, col[r.target]))
        above = sum(y[n] > y[e] for e, c in ends for n in columns[c])
        below = sum(y[n] < y[e] for e, c in ends for n in columns[c])
        sign = 1 if below > above else -1
        side[k] = sign
        edge = highest if sign > 0 else lowest
        s_col, t_col = col[r.source], col[r.target]
        straight[k] = (
            r.source not in looped and y[r.source] == edge[s_col],
            r.target not in looped and y[r.target] == edge[t_col],
        )
        if straight[k][0]:
            drop[k] = pos[r.source][0]
        else:
            legs.setdefault(s_col + 1, []).append((0, s_col - t_col, k, "drop"))
        if straight[k][1]:
            rise[k] = pos[r.target][0]
        else:
            legs.setdefault(t_col, []).append((1, t_col - s_col, k, "rise"))
    for gap, entries in legs.items():
        left = x[gap - 1] + hw[gap - 1] if gap > 0 else x[0] - hw[0] - gaps[0]
        right = x[gap] - hw[gap] if gap < ncol else left + gaps[gap]
        for j, (*_, k, what) in enumerate(sorted(entries)):
            xj = left + (right - left) * (j + 1) / (len(entries) + 1)
            (drop if what == "drop" else rise)[k] = xj

    items: dict[int, list[tuple[str, float]]] = {}
    for k, r in enumerate(routes):
        widths = [item_width[n] for n in r.chain]
        total = sum(widths) + 0.3 * max(len(widths) - 1, 0)
        cursor = (drop[k] + rise[k]) / 2 + total / 2
        placed = []
        for n, w in zip(r.chain, widths, strict=True):
            placed.append((n, cursor - w / 2))
            cursor -= w + 0.3
        items[k] = placed

    def boxes(k):
        return [(cx - item_width[n] / 2, cx + item_width[n] / 2) for n, cx in items[k]]

    def span(k):
        ends = [drop[k], rise[k], *itertools.chain.from_iterable(boxes(k))]
        return min(ends) - 0.1, max(ends) + 0.1

    lane = _assign_lanes(side, drop, rise, boxes, span)

    pitch = max([0.42] + [geo.size[n][1] + 0.16 for r in routes for n in r.chain])

    def extent(n, sign):
        reach = geo.size[n][1] / 2 if n in geo.size else 0.0
        if sign > 0:
            return y[n] + reach + (0.25 if n in geo.name else 0.08)
        return y[n] - reach - 0.12

    # an arc runs just clear of the columns it spans, outside every inner arc it overlaps
    heights: dict[int, float] = {}
    for k in sorted(lane, key=lambda k: (lane[k], k)):
        sign, r = side[k], routes[k]
        spanned = [n for c in range(col[r.target], col[r.source] + 1) for n in columns[c]]
        level = sign * max(sign * extent(n, sign) for n in spanned) + sign * pitch / 2
        for q, hq in heights.items():
            if side[q] == sign and lane[q] < lane[k]:
                (lo, hi), (qlo, qhi) = span(k), span(q)
                if lo < qhi and qlo < hi:
                    level = sign * max(sign * level, sign * (hq + sign * pitch))
        heights[k] = level
    bottom = min([extent(n, -1) for n in y] + [h - pitch / 2 for h in heights.values()])
    top = max([extent(n, 1) for n in y] + [h + pitch / 2 for h in heights.values()])

    # where wires enter a node: from the left (spread across), from below or above
    enter_left: dict[str, list] = {}
    enter_vert: dict[tuple[str, int], list] = {}
    for a, b in dag.edges:
        last = paths[(a, b)][-2]
        enter_left.setdefault(b, []).append((-y[last], ("wire", a)))
    for k, r in enumerate(routes):
        if straight[k][1]:
            enter_vert.setdefault((r.target, side[k]), []).append((-lane[k], k))
        else:
            enter_left.setdefault(r.target, []).append((-side[k] * 1e6 - lane[k], ("arc", k)))
    offset: dict = {}
    for b, entries in enter_left.items():
        half = 0.7 * (_SUM_R if geo.kind(b) == "sum" else geo.size[b][1] / 2)
        for (_, key), off in zip(sorted(entries), _spread(len(entries), half), strict=True):
            offset[(b, key)] = off
    for (b, _), entries in enter_vert.items():
        half = 0.55 * (_SUM_R if geo.kind(b) == "sum" else geo.size[b][0] / 2)
        # outer lanes enter on the left so that arcs do not cross
        for (_, k), off in zip(sorted(entries), _spread(len(entries), half)[::-1], strict=True):
            rise[k] = pos[b][0] + off

    fig, ax, own = figure_and_axes(ax)
    wires = []  # (points, dashed)

    def out_point(a):
        xa, ya = pos[a]
        return (xa + geo.reach(a, 0, 0), ya)

    def in_points(b, off):
        xb, yb = pos[b]
        return [(xb - hw[col[b]], yb + off), (xb - geo.reach(b, off, 0), yb + off)]

    for a, b in dag.edges:
        path = paths[(a, b)]
        pts = [out_point(a), (pos[a][0] + hw[col[a]], pos[a][1])]
        for d in path[1:-1]:
            pts += [(pos[d][0] - hw[col[d]], pos[d][1]), (pos[d][0] + hw[col[d]], pos[d][1])]
        pts += in_points(b, offset[(b, ("wire", a))])
        wires.append((pts, g.edges[a, b]["delay"]))
    for k, r in enumerate(routes):
        sign, ly = side[k], heights[k]
        xs, ys = pos[r.source]
        if straight[k][0]:
            pts = [(xs, ys + sign * geo.reach(r.source, 0, 1)), (xs, ly)]
        else:
            pts = [out_point(r.source), (drop[k], ys), (drop[k], ly)]
        prev = r.source
        for n, cx in items[k]:
            pts.append((cx + item_width[n] / 2, ly))
            wires.append((pts, g.edges[prev, n]["delay"]))
            pos[n] = (cx, ly)
            pts, prev = [(cx - item_width[n] / 2, ly)], n
        xt, yt = pos[r.target]
        if straight[k][1]:
            off = rise[k] - xt
            pts += [(rise[k], ly), (rise[k], yt - sign * geo.reach(r.target, off, 1))]
        else:
            off = offset[(r.target, ("arc", k))]
            pts += [(rise[k], ly), *in_points(r.target, off)]
            pts[-2] = (rise[k], yt + off)
        wires.append((pts, g.edges[prev, r.target]["delay"]))

    _draw_wires(ax, wires)
    _draw_blocks(ax, S, geo, pos)

    # input and output arrows
    for name in S.inputs:
        xa, ya = pos[name]
        _draw_wires(ax, [([(xa - hw[col[name]] - 0.35, ya), (xa - geo.reach(name, 0, 0), ya)], 0)])
    for name in S.outputs:
        xa, ya = pos[name]
        end = xa + hw[col[name]] + 0.45
        _draw_wires(ax, [([out_point(name), (end, ya)], 0)])

    # extent, parts, title and legend
    xs_all = [p[0] for p in pos.values()]
    x_lo = min(x[0] - hw[0] - gaps[0], min(xs_all)) - 0.15
    x_hi = x[-1] + hw[-1] + 0.6
    y_lo, y_hi = bottom, top
    parts: dict[str, list[float]] = {}
    for n in dag:
        part = S.blocks[n].part.partition(".")[0]
        if part:
            parts.setdefault(part, []).append(pos[n][0])
    if len(parts) > 1:
        y_hi += 0.05
        for part, xs in parts.items():
            ax.plot([min(xs) - 0.1, max(xs) + 0.1], [y_hi, y_hi], color="0.6", lw=0.8)
            ax.text(
                (min(xs) + max(xs)) / 2,
                y_hi + 0.04,
                part,
                ha="center",
                va="bottom",
                fontsize=_FONT,
                color="0.35",
            )
        y_hi += 0.25
    counts = ", ".join(
        f"{S.count(k)} {word}{'s' if S.count(k) != 1 else ''}"
        for k, word in (("gain", "gain"), ("sum", "adder"), ("delay", "one-step delay"))
    )
    heading = title or f"controller structure: {counts}"
    legend = (
        "boxes: gains (their values; long ones by block name)   circles: adders   "
        "dashed arrows: one-step delays   dots: signals"
    )
    return finish_figure(fig, ax, own, (x_lo, x_hi, y_lo, y_hi), heading, legend, top=0.62)


def _assign_lanes(side, drop, rise, boxes, span) -> dict[int, int]:
    """Lane 1, 2, ... (away from the rows) of each feedback arc, narrowest arcs first.

    Arcs in one lane must not overlap; the vertical legs of an outer arc must not pass
    through a block on an inner arc. If no lane avoids every clash, the least bad one.
    """
    lane: dict[int, int] = {}

    def clashes(k, level):
        count = 0
        for q, lq in lane.items():
            if side[q] != side[k]:
                continue
            if lq == level:
                (lo, hi), (qlo, qhi) = span(k), span(q)
                count += lo < qhi and qlo < hi
            else:
                inner, outer = (q, k) if lq < level else (k, q)
                count += any(
                    lo - 0.12 < v < hi + 0.12
                    for v in (drop[outer], rise[outer])
                    for lo, hi in boxes(inner)
                )
        return count

    for k in sorted(side, key=lambda k: (span(k)[1] - span(k)[0], k)):
        levels = range(1, len(lane) + 2)
        lane[k] = min(levels, key=lambda level, k=k: (clashes(k, level) > 0, clashes(k, level)))
    return lane


def _draw_wires(ax, wires) -> None:
    """Polylines ending in an arrow head; dashed for a one-step delay."""
    from matplotlib.patches import FancyArrowPatch

    for pts, dashed in wires:
        xs, ys = zip(*pts, strict=True)
        style = (0, (3.5, 2.2)) if dashed else "-"
        ax.plot(xs, ys, color=_INK, lw=1.0, linestyle=style, zorder=1, solid_capstyle="butt")
        (x0, y0), (x1, y1) = pts[-2], pts[-1]
        length = math.hypot(x1 - x0, y1 - y0)
        if length == 0:
            continue
        back = min(0.08, length) / length
        ax.add_patch(
            FancyArrowPatch(
                (x1 - (x1 - x0) * back, y1 - (y1 - y0) * back),
                (x1, y1),
                arrowstyle="-|>,head_length=0.5,head_width=0.22",
                mutation_scale=11,
                color=_INK,
                lw=0.8,
                shrinkA=0,
                shrinkB=0,
                zorder=1.5,
            )
        )


def _draw_blocks(ax, S: Structure, geo: _Geometry, pos) -> None:
    """Gain boxes with their values, adders with a plus, dots and names for signals."""
    from matplotlib.patches import Circle, Rectangle

    for name, block in S.blocks.items():
        xc, yc = pos[name]
        w, h = geo.size[name]
        if block.kind == "gain":
            ax.add_patch(
                Rectangle(
                    (xc - w / 2, yc - h / 2),
                    w,
                    h,
                    fc="white",
                    ec="black",
                    lw=1.0,
                    zorder=2,
                    gid=f"gain:{name}",
                )
            )
            ax.text(
                xc,
                yc,
                geo.label[name],
                ha="center",
                va="center",
                fontsize=_FONT,
                zorder=3,
                gid=f"gain:{name}",
            )
        elif block.kind == "sum":
            ax.add_patch(
                Circle(
                    (xc, yc), _SUM_R, fc="white", ec="black", lw=1.0, zorder=2, gid=f"sum:{name}"
                )
            )
            ax.text(xc, yc, "+", ha="center", va="center_baseline", fontsize=_FONT + 1, zorder=3)
        else:
            ax.add_patch(Circle((xc, yc), _DOT_R, fc="black", zorder=2, gid=f"signal:{name}"))
        if name in geo.name:
            ax.text(
                xc + w / 2 + 0.03,
                yc + 0.035,
                geo.name[name][0],
                ha="left",
                va="bottom",
                fontsize=_NAME_FONT,
                color="0.3",
                zorder=3,
            )
