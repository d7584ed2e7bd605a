r"""Neural circuits of stylized linear neurons, read off controller structures.

A stylized neuron's axon carries a weighted sum of its synaptic inputs and of its own past
outputs (its *self-dynamics*), with no activation function; an axon may branch.

The counting rule: a **term** is one input of an adder of the structure (a nonzero entry of a
row of :math:`[F\ H]` or :math:`[M\ N]`, a weighted signal :math:`w\,s(t-d)`; weight 1 is a
wire, still a term). Every adder of **two or more terms** is a neuron, the output sum
:math:`y = M x + N u` included; a single term passing through gains and unit delays (e.g.
:math:`x_1(t) = x_2(t-1)`) is an **axon**, the product of its gains a synaptic weight, its
delays the synapse's delay; a term whose axon starts at the neuron's own output is
**self-dynamics**, :math:`\sum_k w_k z^{-d_k}`, the others are **synapses**. A neuron's **axon
branches** are its synapses onto other neurons plus the circuit outputs it drives (two paths
onto one neuron are two branches, as in the paper's figure).

Under this rule the paper's counts hold (the tests check each): the controllable canonical
:math:`G_2` has 2 neurons (:math:`x_2` with self-dynamics :math:`K_1 z^{-1} + K_2 z^{-2}`, and
:math:`y`), the observable canonical one 3, a general realization 3; :math:`G_1` and
:math:`G_3` add one neuron each. With :math:`K_2 + \epsilon_1\epsilon_3 = 0` or :math:`K_1 -
\epsilon_1 - \epsilon_3 = 0` the controllable canonical middle neuron has one axon branch
instead of two; the observable canonical one with :math:`K_2 + \epsilon_1\epsilon_3 = 0` takes
the controllable canonical shape, with :math:`K_1 - \epsilon_1 - \epsilon_3 = 0` it keeps 3
neurons (the paper leaves this case open).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import NamedTuple

import numpy as np
import sympy as sp

from symctl._util.display import LatexMixin, latex
from symctl._util.texnames import signal_tex
from symctl._util.validate import positive_int, subs_rule, to_expr
from symctl.compatibility.assignment import DelayAssignment
from symctl.compatibility.check import CompatibilityResult
from symctl.compatibility.statespace import (
    block_gain,
    delay_states,
    signal_rows,
    structure_realization,
)
from symctl.compatibility.structure import Block, Structure
from symctl.errors import ParameterError, SymctlTypeError
from symctl.neural.neuron import Neuron, Synapse

__all__ = ["Circuit", "CircuitSystem", "Neuron", "Synapse"]


class CircuitSystem(NamedTuple):
    r"""A circuit as :math:`s(t+1) = A s + B u`, :math:`o = C s + D u` (:meth:`Circuit.as_linear_system`).

    Attributes
    ----------
    A, B, C, D : sympy Matrix or NumPy array
    states, inputs, outputs : tuple of str
        The structure's delay blocks; its inputs; the neurons' axon outputs, then the circuit's.

    Examples
    --------
    >>> from symctl import Circuit, ifp_structure
    >>> A, B, C, D, states, inputs, outputs = Circuit.from_structure(
    ...     ifp_structure(1)).as_linear_system()
    >>> states, inputs, outputs
    (('u',), ('x',), ('mu', 'u'))
    >>> A, B
    (Matrix([[K_1]]), Matrix([[K_0]]))
    """

    A: object
    B: object
    C: object
    D: object
    states: tuple[str, ...]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]


@dataclass(frozen=True, eq=False)
class Circuit(LatexMixin):
    """A circuit of stylized neurons, built by :meth:`from_structure`; compares and hashes by value.

    Attributes
    ----------
    structure : Structure
        The structure it was read from.
    neurons : tuple of Neuron
        In the structure's signal order.
    inputs : tuple of str
    outputs : tuple of Synapse
        Per structure output, the axon path reaching it (from ``"0"``, weight 0: zero signal).
    input_axons : mapping of str to tuple of Synapse
        The branches of each input's axon.

    Examples
    --------
    >>> from symctl import Circuit, Structure, controller_tf, factor, observable_canonical
    >>> S = Structure.from_realization(observable_canonical(factor(controller_tf(2)).G2))
    >>> c = Circuit.from_structure(S)
    >>> c.n_neurons, c.inputs, [o.source for o in c.outputs]
    (3, ('u',), ['y'])
    >>> c == Circuit.from_structure(S)
    True
    """

    structure: Structure
    neurons: tuple[Neuron, ...]
    inputs: tuple[str, ...]
    outputs: tuple[Synapse, ...]
    input_axons: Mapping[str, tuple[Synapse, ...]]

    def __post_init__(self) -> None:
        object.__setattr__(self, "input_axons", MappingProxyType(dict(self.input_axons)))

    def _key(self) -> tuple:
        S = self.structure
        return (tuple(S.blocks.items()), S.inputs, S.outputs, self.neurons)

    def __eq__(self, other) -> bool:
        if not isinstance(other, Circuit):
            return NotImplemented
        return self is other or self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    @classmethod
    def from_structure(
        cls, S: Structure, assignment: DelayAssignment | CompatibilityResult | None = None
    ) -> Circuit:
        r"""The circuit of a structure (the module text states the rule).

        Parameters
        ----------
        S : Structure
            E.g. :meth:`Structure.from_factorization` (zero entries substituted first make no
            block).
        assignment : DelayAssignment or CompatibilityResult, optional
            A compatible assignment of ``S``'s signals: each neuron sits at its adder's vertex.

        Returns
        -------
        Circuit

        Raises
        ------
        SymctlTypeError
            ``S`` is not a Structure, or ``assignment`` is of another type.
        ParameterError
            ``assignment`` for another structure or not compatible; a gain not finite; a loop
            of gains and delays with no adder.

        Examples
        --------
        >>> from symctl import Circuit, Structure, controllable_canonical, controller_tf, factor
        >>> f = factor(controller_tf(2))
        >>> c = Circuit.from_structure(Structure.from_realization(controllable_canonical(f.G2)))
        >>> c.n_neurons, c.neuron("x2").branches
        (2, 2)
        """
        if not isinstance(S, Structure):
            raise SymctlTypeError(f"S: expected a Structure, got {type(S).__name__}")
        return cls._build(S, _vertices(S, assignment))

    @classmethod
    def _build(
        cls, S: Structure, vertex_of: Mapping[str, int] | None, argname: str = "S"
    ) -> Circuit:
        infinite = (sp.nan, sp.zoo, sp.oo, -sp.oo)
        for name, b in S.blocks.items():
            if b.kind == "gain" and b.gain is not None and b.gain.has(*infinite):
                raise ParameterError(f"{argname}: the gain {name!r} is not finite: {b.gain}")
        names = [n for n, b in S.blocks.items() if b.kind == "sum" and len(b.inputs) >= 2]
        is_neuron = set(names)
        traced = {n: [_trace(S, term, n, is_neuron) for term in S.blocks[n].inputs] for n in names}
        incoming = {n: [s for s in syns if s is not None] for n, syns in traced.items()}
        zero = sp.Integer(0)  # an output of the zero signal comes from "0"
        outputs = tuple(_trace(S, o, o, is_neuron) or Synapse("0", o, zero, 0) for o in S.outputs)
        # a source's branches: its synapses onto neurons in neuron order, then the outputs
        outgoing: dict[str, list[Synapse]] = {}
        for s in (*(s for v in incoming.values() for s in v if s.source != s.target), *outputs):
            outgoing.setdefault(s.source, []).append(s)
        neurons = tuple(
            Neuron(
                name,
                S.blocks[name].part,
                tuple(s for s in incoming[name] if s.source != name),
                tuple(s for s in incoming[name] if s.source == name),
                tuple(outgoing.get(name, ())),
                None if vertex_of is None else vertex_of[name],
            )
            for name in names
        )
        axons = {u: tuple(outgoing.get(u, ())) for u in S.inputs}
        return cls(S, neurons, S.inputs, outputs, axons)

    @property
    def n_neurons(self) -> int:
        """The number of neurons."""
        return len(self.neurons)

    def neuron(self, name: str) -> Neuron:
        """The :class:`Neuron` named ``name`` (its adder's signal, e.g. ``"G2.x2"``).

        Raises
        ------
        ParameterError
            No neuron has that name.

        Examples
        --------
        >>> from symctl import Circuit, ifp_structure
        >>> Circuit.from_structure(ifp_structure(2)).neuron("mu").self_dynamics
        K_1/z + K_2/z**2
        """
        for n in self.neurons:
            if n.name == name:
                return n
        raise ParameterError(
            f"name: {name!r} is not a neuron; the neurons are {[n.name for n in self.neurons]}"
        )

    @property
    def synapses(self) -> tuple[Synapse, ...]:
        """Every synapse onto a neuron (self-dynamics excluded), neuron by neuron."""
        return tuple(s for n in self.neurons for s in n.synapses)

    def branches(self) -> dict[str, int]:
        """The number of axon branches of each neuron (in order), then of each input.

        Examples
        --------
        >>> from symctl import Circuit, ifp_structure
        >>> Circuit.from_structure(ifp_structure(2)).branches()
        {'mu': 1, 'x': 1}
        """
        out = {n.name: n.branches for n in self.neurons}
        out.update({u: len(a) for u, a in self.input_axons.items()})
        return out

    @property
    def vertices(self) -> dict[str, int | None]:
        """The delay-graph vertex of each neuron (None without an assignment)."""
        return {n.name: n.vertex for n in self.neurons}

    def subs(self, *args, **kwargs) -> Circuit:
        """The circuit with values substituted into every weight (arguments as SymPy's ``subs``);
        shape and vertices kept (a weight that becomes zero stays a synapse).

        Raises
        ------
        ParameterError
            A gain becomes infinite (e.g. a division by a symbol set to 0).

        Examples
        --------
        >>> import sympy as sp
        >>> from symctl import Circuit, Structure, first_order_realization
        >>> from symctl.symbols import epsilon_1, C_1
        >>> c = Circuit.from_structure(Structure.from_realization(
        ...     first_order_realization(epsilon_1, C_1)))
        >>> c.subs({epsilon_1: sp.Rational(1, 2), C_1: -1}).neuron("x1").synapses[0].sign
        '-'
        """
        gains = [b.gain for b in self.structure.blocks.values() if b.gain is not None]
        rule, flags = subs_rule(args, kwargs, set().union(*(g.free_symbols for g in gains)))
        blocks = {
            name: Block(b.kind, b.inputs, b.gain.subs(rule, **flags), b.part, b.steps)
            if b.kind == "gain" and b.gain is not None
            else b
            for name, b in self.structure.blocks.items()
        }
        S = Structure(blocks, self.structure.inputs, self.structure.outputs)
        placed = self.neurons and self.neurons[0].vertex is not None
        return self._build(S, self.vertices if placed else None, "subs")

    @property
    def free_symbols(self) -> set[sp.Symbol]:
        """The symbols left in the weights."""
        terms = (*self.synapses, *(t for n in self.neurons for t in n.self_terms), *self.outputs)
        return set().union(*(to_expr(s.weight, "weight").free_symbols for s in terms))

    def as_linear_system(self, numeric: bool = False) -> CircuitSystem:
        r"""The circuit as a :class:`CircuitSystem` (states: the structure's delayed signals).

        Parameters
        ----------
        numeric : bool
            Float NumPy arrays (every weight a number) instead of sympy matrices.

        Raises
        ------
        ParameterError
            ``numeric=True`` with symbols left in the weights.

        Examples
        --------
        >>> import sympy as sp
        >>> from symctl import Circuit, Structure, first_order_realization
        >>> c = Circuit.from_structure(Structure.from_realization(
        ...     first_order_realization(sp.Rational(1, 2), 3)))
        >>> sys = c.as_linear_system()
        >>> sys.states, sys.outputs, sys.A.tolist(), sys.B.T
        (('z^-1 F[1,1]', 'z^-1 H'), ('x1', 'x1'), [[1/2, 1/2], [0, 0]], Matrix([[0, 3]]))
        """
        S = self.structure
        states, feeds = delay_states(S)
        out_names = tuple(n.name for n in self.neurons) + S.outputs
        if not numeric:
            R = structure_realization(S, out_names)
            return CircuitSystem(R.F, R.H, R.M, R.N, states, S.inputs, out_names)
        left = sorted(map(str, self.free_symbols))
        if left:
            raise ParameterError(f"numeric: the weights still contain {left}; subs() first")
        k, m = len(states), len(S.inputs)

        def real(name, gain):
            if gain.free_symbols or not gain.is_real:
                raise ParameterError(
                    f"numeric: the gain of {name!r} is {gain}, not a real number; subs() first"
                )
            return float(gain)

        row = signal_rows(S, states, list(np.eye(k + m)), np.zeros(k + m), real)
        nxt = np.array([row[f] for f in feeds]).reshape(k, k + m)
        obs = np.array([row[s] for s in out_names]).reshape(len(out_names), k + m)
        return CircuitSystem(
            nxt[:, :k], nxt[:, k:], obs[:, :k], obs[:, k:], states, S.inputs, out_names
        )

    def equations(self, digits: int | None = None) -> list[str]:
        r"""One LaTeX equation per neuron, ``"<neuron>(t) = <weighted past outputs and synapses>"``.

        Parameters
        ----------
        digits : int, optional
            Significant digits of the weights' numbers; exact by default.

        Raises
        ------
        ParameterError
            ``digits`` is not an integer >= 1.

        Examples
        --------
        >>> from symctl import Circuit, Structure, first_order_realization
        >>> from symctl.symbols import epsilon_1, C_1
        >>> c = Circuit.from_structure(Structure.from_realization(
        ...     first_order_realization(epsilon_1, C_1)))
        >>> c.equations()
        ['x_{1}(t) = \\epsilon_{1}\\, x_{1}(t-1) + C_{1}\\, u(t-1)']
        """
        if digits is not None:
            digits = positive_int(digits, "digits")
        out = []
        for n in self.neurons:
            terms = []
            for s in (*n.self_terms, *n.synapses):
                w = to_expr(s.weight, "weight")
                if digits is not None:
                    w = _rounded(w, digits)
                tex = "" if w == 1 else "-" if w == -1 else latex(w) + r"\,"
                if isinstance(w, sp.Add):
                    tex = rf"\left({latex(w)}\right)\,"
                terms.append(
                    rf"{tex} {signal_tex(s.source)}(t{f'-{s.delay}' if s.delay else ''})".lstrip()
                )
            rhs = " + ".join(terms).replace("+ -", "- ") if terms else "0"
            out.append(rf"{signal_tex(n.name)}(t) = {rhs}")
        return out

    def latex(self) -> str:
        """The neurons' equations, one per line."""
        return r"\begin{gathered}" + r" \\ ".join(self.equations()) + r"\end{gathered}"

    def __str__(self) -> str:
        lines = [
            f"Circuit: {self.n_neurons} neuron{'s' if self.n_neurons != 1 else ''}; "
            f"inputs {', '.join(self.inputs)}; "
            f"outputs {', '.join(f'{o.target} <- {_syn_text(o)}' for o in self.outputs)}"
        ]
        for n in self.neurons:
            where = f" [v{n.vertex}]" if n.vertex is not None else ""
            lines += [
                f"  neuron {n.name}{where}",
                f"    self-dynamics: {n.self_dynamics if n.self_terms else 'none'}",
                *(f"    synapse from {_syn_text(s)}" for s in n.synapses),
            ]
            targets = [f"output {s.target}" if s in self.outputs else s.target for s in n.axon]
            word = "branch" if n.branches == 1 else "branches"
            lines.append(f"    axon: {n.branches} {word} -> {', '.join(targets) or 'none'}")
        for u, axon in self.input_axons.items():
            word = "branch" if len(axon) == 1 else "branches"
            targets = ", ".join(s.target for s in axon) or "none"
            lines.append(f"  input {u}: axon {len(axon)} {word} -> {targets}")
        return "\n".join(lines)

    def __repr__(self) -> str:
        names = ", ".join(n.name for n in self.neurons)
        return f"Circuit({self.n_neurons} neurons: {names}; inputs={self.inputs})"

    def draw(self, ax=None, **options):
        """Draw the circuit: a Figure by :func:`symctl.plotting.circuit.draw_circuit`."""
        from symctl.plotting.circuit import draw_circuit

        return draw_circuit(self, ax, **options)

    def to_nengo(self, n_neurons: int | None = None, **options):
        """A nengo network by :func:`symctl.spiking.nengo_export.to_nengo` (needs the ``spiking``
        extra); :meth:`to_nest` and :meth:`to_nir` likewise.

        Examples
        --------
        >>> from symctl import Circuit, Structure, first_order_realization
        >>> c = Circuit.from_structure(Structure.from_realization(first_order_realization(0.5, 2)))
        >>> sorted(c.to_nengo().neurons), sorted(c.to_nest().neurons), sorted(c.to_nir().inputs)
        (['x1'], ['x1'], ['u'])
        """
        from symctl.spiking.nengo_export import to_nengo

        return to_nengo(self, n_neurons, **options)

    def to_nest(self, **options):
        """NEST's linear rate neurons: :func:`symctl.spiking.nest_export.to_nest`."""
        from symctl.spiking.nest_export import to_nest

        return to_nest(self, **options)

    def to_nir(self, n_neurons: int | None = None, **options):
        """A NIR graph: :func:`symctl.spiking.nir_export.to_nir`."""
        from symctl.spiking.nir_export import to_nir

        return to_nir(self, n_neurons, **options)


def _rounded(w: sp.Expr, digits: int) -> sp.Expr:
    """``w`` with its numbers shown to ``digits`` significant digits (exponents stay exact)."""
    if w.is_number:
        return sp.Integer(w) if w == int(w) else sp.Float(w, digits)
    if w.is_Pow:
        return sp.Pow(_rounded(w.base, digits), w.exp)
    if w.args:
        return w.func(*(_rounded(a, digits) for a in w.args))
    return w


def _trace(S: Structure, start: str, target: str, neurons: set[str]) -> Synapse | None:
    """The axon path from ``start`` back to a neuron or an input; None for the zero signal."""
    node, weight, delay, path, seen = start, sp.Integer(1), 0, [], set()
    while True:
        block = S.blocks[node]
        if node in neurons or block.kind == "input":
            between = path[1:] if start == target else path  # strictly inside the path
            return Synapse(node, target, weight, delay, tuple(reversed(between)))
        if node in seen:
            raise ParameterError(
                f"S: a loop of gains and delays with no adder through {node!r} is not a circuit"
            )
        seen.add(node)
        path.append(node)
        if block.kind == "gain":
            weight = block_gain(block, node) * weight
        elif block.kind == "delay":
            delay += block.steps
        elif not block.inputs:  # an adder of nothing: the zero signal
            return None
        node = block.inputs[0]


def _vertices(S: Structure, assignment) -> dict[str, int] | None:
    if assignment is None:
        return None
    if isinstance(assignment, CompatibilityResult):
        if not assignment.ok or assignment.assignment is None:
            raise ParameterError(
                "assignment: the compatibility check failed, so there is no assignment: "
                + assignment.reason.splitlines()[0]
            )
        assignment = assignment.assignment
    if not isinstance(assignment, DelayAssignment):
        raise SymctlTypeError(
            "assignment: expected a DelayAssignment or a CompatibilityResult, got "
            f"{type(assignment).__name__}"
        )
    other = assignment.structure
    if other is not S and {n: (b.kind, b.inputs) for n, b in other.blocks.items()} != {
        n: (b.kind, b.inputs) for n, b in S.blocks.items()
    }:
        raise ParameterError("assignment: it assigns the signals of another structure than S")
    bad = assignment.violations()
    if bad:
        i, j, et, e = bad[0]
        raise ParameterError(
            "assignment: not compatible with its delay graph "
            f"(E~_{i}{j} = {et:g} < E_{i}{j} = {e:g})"
        )
    return dict(assignment.vertex_of)


def _syn_text(s: Synapse) -> str:
    delay = f", delay {s.delay}" if s.delay else ""
    return f"{s.source} (weight {s.weight}, sign {s.sign}{delay})"
