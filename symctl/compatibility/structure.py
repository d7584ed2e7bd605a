r"""Controller structures: signal-flow graphs of scalar signals, gains, adders and delays.

The *structure* of a controller is the block diagram of one realization (the paper's section
"Structure, delay graphs, and compatibility"). A wire ``a -> b`` has delay ``k`` when ``b`` is a
delay block of ``k`` steps, else 0; algebraic loops are refused. As the paper draws them, a gain
of ``1`` is a plain wire, a one-input adder no block, a zero entry nothing.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import cached_property
from types import MappingProxyType

import networkx as nx
import sympy as sp

from symctl._util.display import LatexMixin, latex
from symctl._util.exact import ring_fractions
from symctl._util.texnames import signal_tex
from symctl._util.validate import bounded_int
from symctl.compatibility.block import KINDS, MAX_WIRE_STEPS, Block, signal_name, signal_names
from symctl.compatibility.block import block as checked_block
from symctl.compatibility.signalgraph import SignalGraph, delay_free_cycle, zero_one_bfs
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.realization.realization import Realization, section_realizations
from symctl.symbols import gain_symbols

__all__ = ["KINDS", "MAX_WIRE_STEPS", "Block", "Structure", "ifp_structure", "same_structure"]

MAX_SIGNALS = 1_000_000
"""Most signals (blocks) of one structure: every algorithm on it is then bounded."""


@dataclass(frozen=True)
class Structure(LatexMixin):
    r"""A controller structure: scalar signals produced by gains, adders and delays.

    A frozen value, equal when its blocks (in any order), inputs and outputs are.

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
        Unknown kind or signal, a gain or delay without exactly one input, an algebraic loop,
        inputs that are not the input blocks.
    SymctlTypeError
        ``blocks`` is not a mapping, or a name is not a non-empty string.

    Examples
    --------
    The paper's IFP controller for :math:`T = 1`:

    >>> from symctl import Structure, ifp_structure
    >>> S = Structure(
    ...     {"x": ("input",), "K0": ("gain", ("x",), 3), "K1": ("gain", ("u",), 2),
    ...      "mu": ("sum", ("K0", "K1")), "u": ("delay", ("mu",))},
    ...     inputs="x", outputs="u")
    >>> len(S), S.count("gain"), sorted(S.wires())[:2]
    (5, 2, [('K0', 'mu', 0), ('K1', 'mu', 0)])
    >>> S == ifp_structure(1), S == Structure(S.blocks, "x", "u")
    (False, True)
    """

    blocks: Mapping[str, Block]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]

    def __post_init__(self):
        blocks, inputs, outputs = self.blocks, self.inputs, self.outputs
        if not isinstance(blocks, Mapping):
            raise SymctlTypeError(
                f"blocks: expected a mapping of signal names to blocks, got {type(blocks).__name__}"
            )
        if len(blocks) > MAX_SIGNALS:
            raise ParameterError(
                f"blocks: a structure has at most {MAX_SIGNALS} signals, got {len(blocks)}"
            )
        clean: dict[str, Block] = {}
        for name, value in blocks.items():
            clean[signal_name(name, "blocks")] = checked_block(name, value)
        ins = signal_names(inputs, "inputs")
        outs = signal_names(outputs, "outputs")
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
        loop = delay_free_cycle(self.signal_graph)
        if loop:
            raise ParameterError(
                "blocks: algebraic loop (a cycle without delay) through " + " -> ".join(loop)
            )

    def __hash__(self) -> int:
        return hash((frozenset(self.blocks.items()), self.inputs, self.outputs))

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
        """The wires ``(source, target, delay)``; a wire into a delay block carries its steps."""
        names = self.signal_graph.names
        return ((names[a], names[b], w) for a, b, w in self.signal_graph.wires)

    @cached_property
    def signal_graph(self) -> SignalGraph:
        """The integer form of the structure that the checkers search (signals in order)."""
        names = tuple(self.blocks)
        index = {n: i for i, n in enumerate(names)}
        wires = [
            (index[src], b, blk.delay)
            for b, blk in enumerate(self.blocks.values())
            for src in blk.inputs
        ]
        return SignalGraph.from_wires(
            names,
            tuple(b.kind for b in self.blocks.values()),
            wires,
            tuple(index[n] for n in self.inputs),
            tuple(index[n] for n in self.outputs),
        )

    @cached_property
    def graph(self) -> nx.DiGraph:
        """A frozen :class:`networkx.DiGraph`: nodes with ``kind``, ``gain``, ``part``, ``role``
        (``("in", k)``, ``("out", k)``), edges with ``delay``."""
        g = nx.DiGraph()
        for name, block in self.blocks.items():
            role = tuple(("in", k) for k, n in enumerate(self.inputs) if n == name) + tuple(
                ("out", k) for k, n in enumerate(self.outputs) if n == name
            )
            g.add_node(name, kind=block.kind, gain=block.gain, part=block.part, role=role)
        for a, b, w in self.wires():
            g.add_edge(a, b, delay=w)
        return nx.freeze(g)

    def delay_distances(self, source: str) -> dict[str, int]:
        """Fewest delays on any path from ``source`` to each reachable signal (0-1 BFS)."""
        cs = self.signal_graph
        if source not in cs.index:
            raise ParameterError(f"source: {source!r} is not a signal of the structure")
        dist = zero_one_bfs(cs, [cs.index[source]])
        return {cs.names[i]: d for i, d in enumerate(dist) if d is not None}

    @classmethod
    def from_realization(
        cls, R: Realization, delays: str = "branch", *, input_delay: int = 1
    ) -> Structure:
        r"""The structure of a realization :math:`(F, H, M, N)` (the paper's Fig. 7).

        Signals: inputs ``u`` (``u1, ...``), states ``x1 .. xn``, gains by their entry
        (``F[1,2]``, ``H[1]``, ``M[2]``, ``N``), delayed branch terms ``z^-1 F[1,2]``, adders
        ``p1 ..`` and the output ``y`` (``y = u`` is a unit gain ``y``).

        Parameters
        ----------
        R : Realization
        delays : {"branch", "state"}
            ``"branch"``: every term through its own delay, :math:`x_i(t) = \sum_j F_{ij}
            x_j(t-1) + H_i u(t-1)`; ``"state"``: one delay after each adder.
        input_delay : int, default 1
            With ``"branch"``, the steps :math:`k` of the branches carrying :math:`H u` (axons):
            the transfer function is :math:`M (zI - F)^{-1} H z^{1-k} + N`.

        >>> from symctl import Structure
        >>> from symctl.realization.realization import first_order_realization
        >>> import sympy as sp
        >>> eps, C = sp.symbols("epsilon C")
        >>> S = Structure.from_realization(first_order_realization(eps, C))
        >>> sorted(S.wires())[:3]
        [('F[1,1]', 'z^-1 F[1,1]', 1), ('H', 'z^-1 H', 1), ('u', 'H', 0)]
        >>> S3 = Structure.from_realization(first_order_realization(eps, C), input_delay=3)
        >>> sorted(S3.wires())[:3]
        [('F[1,1]', 'z^-1 F[1,1]', 1), ('H', 'z^-3 H', 3), ('u', 'H', 0)]
        """
        if not isinstance(R, Realization):
            raise SymctlTypeError(f"R: expected a Realization, got {type(R).__name__}")
        if delays not in ("branch", "state"):
            raise ParameterError(f"delays: must be 'branch' or 'state', got {delays!r}")
        k_in = bounded_int(input_delay, "input_delay", 1, MAX_WIRE_STEPS)
        if k_in != 1 and delays != "branch":
            raise ParameterError(
                "input_delay: only the branch structure carries the input on its own wires; "
                f"got input_delay={k_in} with delays={delays!r}"
            )
        n = R.n
        p, q = R.shape
        u = ["u"] if q == 1 else [f"u{k + 1}" for k in range(q)]
        x = [f"x{i + 1}" for i in range(n)]
        y = ["y"] if p == 1 else [f"y{k + 1}" for k in range(p)]
        blocks: dict[str, Block] = {name: Block("input") for name in u}

        def entry(mat, letter, i, j):
            rows, cols = mat.shape
            if letter == "F" or (rows > 1 and cols > 1):
                return f"{letter}[{i + 1},{j + 1}]"
            index = [i + 1] * (rows > 1) + [j + 1] * (cols > 1)
            return letter + "".join(f"[{k}]" for k in index)

        def terms(i, mats):  # nonzero terms of row i: (value, source signal, label)
            return [
                (mat[i, j], src, entry(mat, letter, i, j))
                for mat, letter, sources in mats
                for j, src in enumerate(sources)
                if not _is_zero(mat[i, j])
            ]

        def signal(value, src, label):  # the signal carrying value * src
            if value == 1:
                return src
            blocks[label] = Block("gain", (src,), value)
            return label

        for i in range(n):
            row = terms(i, ((R.F, "F", x), (R.H, "H", u)))
            if delays == "branch":
                carried = [(signal(*t), t[2], k_in if t[1] in u else 1) for t in row]
                if len(carried) == 1:
                    src, _, steps = carried[0]
                    blocks[x[i]] = Block("delay", (src,), steps=steps)
                    continue
                for src, label, steps in carried:
                    blocks[f"z^-{steps} {label}"] = Block("delay", (src,), steps=steps)
                blocks[x[i]] = Block("sum", tuple(f"z^-{st} {label}" for _, label, st in carried))
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
            if len(row) == 1 and row[0][0] == 1 and row[0][1] in u:
                # y = u gets its own signal, so the delay graph decides (E_1N = 0)
                blocks[y[k]] = Block("gain", (row[0][1],), sp.Integer(1))
                outputs.append(y[k])
            elif len(row) == 1:
                value, src, _ = row[0]
                outputs.append(signal(value, src, y[k]))
            else:
                blocks[y[k]] = Block("sum", tuple(signal(*t) for t in row))
                outputs.append(y[k])
        return cls(blocks, u, outputs)

    @classmethod
    def series(cls, *parts: Realization | Structure, names: Iterable[str] | None = None):
        """The series connection of ``parts`` (the first acts first; realizations take the branch
        structure); signals are prefixed by the part's name (``G1.``, ...; :attr:`Block.part`).

        >>> from symctl import Structure, controllable_canonical, controller_tf, factor
        >>> from symctl.realization.realization import first_order_realization
        >>> f = factor(controller_tf(2))
        >>> G1 = first_order_realization(f.sensor_eps[0], f.sensor_C[0])
        >>> G3 = first_order_realization(f.actuator_eps[0], f.actuator_C[0])
        >>> S = Structure.series(G1, controllable_canonical(f.G2), G3)
        >>> S.inputs, S.outputs
        (('G1.u',), ('G3.x1',))
        """
        labels = _labels(parts, names, "G")
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
                inner = tuple(rename[s] for s in block.inputs)
                where = f"{label}.{block.part}" if block.part else label
                blocks[rename[name]] = block._replace(inputs=inner, part=where)
            if not k:
                inputs = tuple(rename[s] for s in part.inputs)
            previous = tuple(rename[s] for s in part.outputs)
        return cls(blocks, inputs, previous)

    @classmethod
    def parallel(cls, *parts: Realization | Structure, names: Iterable[str] | None = None):
        """The parallel connection of ``parts`` (prefixed ``P1.``, ...): the inputs shared, the
        outputs summed by adders ``y`` (``y1, ...``).

        >>> from symctl import Structure
        >>> from symctl.realization.realization import first_order_realization
        >>> S = Structure.parallel(first_order_realization(1, 2), first_order_realization(0, 3))
        >>> S.inputs, S.outputs, S.blocks["y"].inputs
        (('P1.u',), ('y',), ('P1.x1', 'P2.x1'))
        """
        labels = _labels(parts, names, "P")
        structures = [
            cls.series(part, names=[label]) for label, part in zip(labels, parts, strict=True)
        ]
        first = structures[0]
        blocks: dict[str, Block] = {}
        ends = []
        for k, part in enumerate(structures):
            if len(part.inputs) != len(first.inputs) or len(part.outputs) != len(first.outputs):
                raise DimensionError(
                    f"parts: part {k + 1} has {len(part.inputs)} inputs and {len(part.outputs)} "
                    f"outputs, part 1 {len(first.inputs)} and {len(first.outputs)}"
                )
            rename = dict(zip(part.inputs, first.inputs, strict=True))
            ends.append([rename.get(s, s) for s in part.outputs])
            for name, b in part.blocks.items():
                if k and b.kind == "input":
                    continue
                blocks[name] = b._replace(inputs=tuple(rename.get(s, s) for s in b.inputs))
        if len(structures) == 1:
            return first
        p = len(first.outputs)
        outputs = ["y"] if p == 1 else [f"y{k + 1}" for k in range(p)]
        for k, out in enumerate(outputs):  # free names: every part's carry a prefix
            blocks[out] = Block("sum", tuple(end[k] for end in ends))
        return cls(blocks, first.inputs, outputs)

    @classmethod
    def from_factorization(
        cls, factorization, R2: Realization, delays: str = "branch", *, axons=None
    ) -> Structure:
        r"""The structure of :math:`G_3 G_2 G_1`: branch sections, ``R2`` (of
        ``factorization.G2``) with ``delays``; parts ``G1``, ``G2``, ``G3`` (``G1.1``, ...).
        ``axons``: the steps of each section's input branch, sensor side first (default 1).

        >>> from symctl import Structure, controllable_canonical, controller_tf, factor
        >>> f = factor(controller_tf(2))
        >>> S = Structure.from_factorization(f, controllable_canonical(f.G2))
        >>> S.count("sum"), S.count("delay")
        (4, 8)
        """
        first, last = section_realizations(factorization)
        ds, da = len(first), len(last)
        steps = [1] * (ds + da) if axons is None else list(axons)
        if len(steps) != ds + da:
            raise ParameterError(f"axons: expected {ds + da} steps, one per section, got {steps}")
        names = [f"G1.{k + 1}" if ds > 1 else "G1" for k in range(ds)]
        names += ["G2"] + [f"G3.{k + 1}" if da > 1 else "G3" for k in range(da)]
        parts = [
            cls.from_realization(p, "branch", input_delay=e)
            for p, e in zip([*first, *last], steps, strict=True)
        ]
        parts.insert(ds, cls.from_realization(R2, delays))
        return cls.series(*parts, names=names)

    def equations(self) -> list[sp.Eq]:
        r"""One equation per adder and delay, with the gains written into them.

        >>> from symctl import ifp_structure
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
                rhs = value(block.inputs[0], t - block.steps)
            elif block.kind == "sum":
                rhs = sp.Add(*(value(s, t) for s in block.inputs))
            else:
                continue
            out.append(sp.Eq(sp.Function(_symbol_name(name))(t), rhs, evaluate=False))
        return out

    def latex(self) -> str:
        r"""The equations as an ``aligned`` block for a reader: readable names, the part as a
        superscript, delayed branch terms written into the adder they feed.

        >>> from symctl import ifp_structure
        >>> for row in ifp_structure(2).latex().split(r" \\ "):
        ...     print(row)
        \begin{aligned}\gamma(t) &= \mu(t - 1)
        u(t) &= \gamma(t - 1)
        \mu(t) &= K_{0} x(t) + K_{1} \gamma(t) + K_{2} u(t)\end{aligned}
        """

        def terms(name: str, lag: int) -> list[str]:
            block = self.blocks[name]
            if block.kind == "gain":
                inner = terms(block.inputs[0], lag)
                if block.gain is None:
                    gain = signal_tex(name)
                else:
                    gain = latex(block.gain)
                    if isinstance(block.gain, sp.Add):
                        gain = rf"\left({gain}\right)"
                if gain == "1":
                    return inner
                if gain == "-1":
                    return ["-" + t for t in inner]
                return [f"{gain} {t}" for t in inner]
            if block.kind == "delay" and _branch_term(name):
                return terms(block.inputs[0], lag + block.steps)
            return [signal_tex(name) + ("(t)" if lag == 0 else f"(t - {lag})")]

        rows = []
        for name, block in self.blocks.items():
            if block.kind == "sum":
                rhs = [t for src in block.inputs for t in terms(src, 0)]
            elif block.kind == "delay" and not _branch_term(name):
                rhs = terms(block.inputs[0], block.steps)
            else:
                continue
            body = " + ".join(rhs).replace("+ -", "- ")
            rows.append(f"{signal_tex(name)}(t) &= {body}")
        return r"\begin{aligned}" + r" \\ ".join(rows) + r"\end{aligned}"

    def _repr_latex_(self) -> str | None:  # None: too long, Jupyter falls back to repr
        return None if len(self) > 60 else super()._repr_latex_()

    def __repr__(self) -> str:
        counts = ", ".join(f"{self.count(k)} {k}" for k in ("gain", "sum", "delay"))
        return f"Structure({len(self)} signals: {counts}; inputs={self.inputs}, outputs={self.outputs})"

    def draw(self, ax=None, **options):
        """Draw the structure as a block diagram (a Figure); ``options`` go to
        :func:`symctl.plotting.structure.draw_structure` (``title``, ``assignment``, ``labels``, ...).

        Examples
        --------
        >>> from symctl import ifp_structure
        >>> fig = ifp_structure(2).draw(labels={"x": "f", "u": "r"})
        >>> type(fig).__name__
        'Figure'
        """
        from symctl.plotting.structure import draw_structure

        return draw_structure(self, ax, **options)


def _symbol_name(name: str) -> str:
    return name.replace(" ", "").replace("^-1", "d_")


def _branch_term(name: str) -> bool:
    return name.rpartition(".")[2].startswith("z^-")


def _labels(parts, names, prefix: str) -> list[str]:
    if not parts:
        raise ParameterError("parts: give at least one realization or structure")
    labels = [f"{prefix}{k + 1}" for k in range(len(parts))] if names is None else list(names)
    if len(labels) != len(parts) or len(set(labels)) != len(labels):
        raise ParameterError(f"names: need {len(parts)} distinct names, got {labels!r}")
    return labels


def _is_zero(value) -> bool:
    """Exactly zero: by the numerator as a sparse polynomial, else by ``cancel``."""
    value = sp.sympify(value)
    if value == 0:
        return True
    if not value.free_symbols:
        return False
    pairs = ring_fractions([value])
    if pairs is not None:
        return not pairs[0][0]
    return sp.cancel(value) == 0


def ifp_structure(T: int = 2) -> Structure:
    r"""The structure of the paper's IFP controller (eqs. augmented_states, ifp_controller).

    :math:`\mu(t) = K_0 x(t) + K_1 \gamma_1(t) + \dots + K_T u(t)`, :math:`\gamma_1(t+1) =
    \mu(t)`, :math:`\gamma_{k+1}(t+1) = \gamma_k(t)`, :math:`u(t+1) = \gamma_{T-1}(t)`.

    Parameters
    ----------
    T : int, default 2
        The total delay of the loop in steps, :math:`T \ge 1`.

    Returns
    -------
    Structure

    Raises
    ------
    ParameterError
        ``T`` is not an integer :math:`\ge 1`.

    Examples
    --------
    >>> from symctl import ifp_structure
    >>> S = ifp_structure(2)
    >>> S.signals
    ('x', 'gamma', 'u', 'K0', 'K1', 'K2', 'mu')
    >>> S.count("delay"), S.inputs, S.outputs
    (2, ('x',), ('u',))
    """
    if isinstance(T, bool) or not isinstance(T, int) or T < 1:
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
    """Whether two structures have the same block configuration, blind to names and gains.

    A kind- and role-preserving graph isomorphism (VF2): swapping :math:`x_1, x_2` of the
    observable canonical form changes the sparsity pattern, not the structure.

    Parameters
    ----------
    a, b : Structure

    Returns
    -------
    bool

    Raises
    ------
    SymctlTypeError
        ``a`` or ``b`` is not a Structure.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import Structure, controllable_canonical, observable_canonical, same_structure, z
    >>> G2 = (2*z**2 + z + 1) / (z**2 - z / 2 - sp.Rational(1, 8))
    >>> R = observable_canonical(G2)
    >>> swapped = R.similar([[0, 1], [1, 0]])
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
