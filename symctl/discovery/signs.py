r"""Dale's law as a polynomial sign problem, decided exactly by z3's nonlinear real arithmetic.

A **template** is a family of realizations of the whole controller
:math:`G = G_3 G_2 G_1` that share one circuit: the sections'
:math:`\epsilon_k, C_k` are unknowns, and :math:`G_2`'s realization is either a
canonical form (entries rational in the sections' unknowns) or a pattern
(:mod:`symctl.discovery.pattern`) whose nonzero entries are unknowns tied to
:math:`G_2` by the polynomial equations

.. math::
    \det(zI - F) = a(z),\qquad M\,\operatorname{adj}(zI - F)\,H = c(z),

:math:`G_2 = N + c/a`. The torus of positive diagonal similarities keeps every
sign, so the entries of a spanning tree (:meth:`Pattern.tree_slots`) are set
to :math:`\pm 1`, not 1: no sign is lost.

Dale's law asks for a sign per neuron, the sign of *every* synapse it sends
to another neuron; its self-dynamics and the circuit's read-out (the motor
command) are exempt. With a Boolean :math:`s_j` per neuron the conditions are

.. math::
    s_j \Rightarrow w > 0,\qquad \lnot s_j \Rightarrow w < 0
    \quad\text{for every outgoing weight } w \text{ of neuron } j,

together with :math:`|\epsilon_k| < 1` (stable sections), :math:`\epsilon_k \ne 0`
and no :math:`\epsilon_k` at a pole of :math:`G` (the circuit keeps its
self-dynamics and :math:`G_2` stays minimal), and every weight of the circuit
nonzero (the circuit keeps its graph).

**The sections' C.** Each :math:`C_k` is the weight of one synapse: from the
input (exempt), or the only synapse a section neuron (or :math:`G_2`'s
output neuron) sends on, which can take either sign. Besides, the :math:`C_k`
scale :math:`G_2` by :math:`1/\prod_k C_k`, and a positive scale moves into
:math:`H` and :math:`N` without changing a sign. So nothing is lost by
setting every :math:`C_k = 1` but the first, :math:`C = \pm 1`; the encoding
does, which removes the divisions and most of the unknowns.

This is a quantifier-free formula of
nonlinear real arithmetic; z3's ``nlsat`` (cylindrical algebraic
decomposition guided by conflicts) decides it: ``sat`` gives an exact
algebraic witness, ``unsat`` is a proof that none exists.

>>> import sympy as sp
>>> from symctl import factor, z
>>> from symctl.discovery.signs import template
>>> fs = factor(-sp.Rational(1, 20) / (z**2 + z / 2 + sp.Rational(1, 3)), 1, 1)
>>> t = template(fs, "controllable")
>>> sorted(t.outgoing)
['G1.x1', 'G2.x2', 'G2.y', 'G3.x1']
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass
from fractions import Fraction

import sympy as sp
import z3

from symctl.compatibility.structure import Structure
from symctl.discovery.fibre import coefficient_polynomials
from symctl.discovery.pattern import Pattern
from symctl.errors import ParameterError
from symctl.neural.circuit import Circuit
from symctl.realization.realization import (
    Realization,
    controllable_canonical,
    observable_canonical,
    split_proper,
)
from symctl.symbols import z

__all__ = ["Template", "decide", "full_pattern", "outgoing_synapses", "template", "to_z3"]

NAMED = ("general", "controllable", "observable")
"""The circuits named by a word: the general (full) pattern and the two canonical forms."""


def full_pattern(n: int) -> Pattern:
    """The pattern with every entry of :math:`(F, H, M)` nonzero: the paper's general circuit."""
    return Pattern(n, (1 << (n * n + 2 * n)) - 1)


@dataclass(frozen=True)
class Template:
    """One circuit's family of realizations of :math:`G`, as unknowns and polynomial equations.

    Attributes
    ----------
    label : str
        ``"general"``, ``"controllable"``, ``"observable"`` or a pattern's text.
    factorization : Factorization
        :math:`G = G_3 G_2 G_1` with the sections' symbols.
    R2 : Realization
        :math:`G_2`'s realization in the unknowns.
    unknowns : tuple of sympy.Symbol
        Entries of ``R2`` that are free (nonzero); ``signed`` ones are :math:`\\pm 1`.
    signed : tuple of sympy.Symbol
    equations : tuple of sympy.Expr
        Polynomials that vanish exactly when ``R2`` realizes :math:`G_2`.
    circuit : Circuit
        The whole controller's circuit in the unknowns.
    outgoing : dict
        Neuron name -> its weights onto other neurons (self-dynamics and read-out exempt).
    weights : tuple of sympy.Expr
        Every weight of the circuit (each must stay nonzero).
    delays : str
        :math:`G_2`'s structure convention.
    """

    label: str
    factorization: object
    R2: Realization
    unknowns: tuple
    signed: tuple
    equations: tuple
    circuit: Circuit
    outgoing: dict
    weights: tuple
    delays: str = "branch"

    @property
    def sections(self) -> tuple[sp.Symbol, ...]:
        """The sections' unknowns, epsilons then Cs."""
        f = self.factorization
        return (*f.sensor_eps, *f.actuator_eps, *f.sensor_C, *f.actuator_C)


def template(factorization, circuit, delays: str = "branch") -> Template:
    """The template of ``circuit`` (a name of :data:`NAMED` or a Pattern) for ``factorization``.

    ``delays`` is the structure convention of :math:`G_2` (the atlas's classes may use
    ``"state"``); the sections always take ``"branch"``.
    """
    G2 = factorization.G2
    n = G2.order
    if isinstance(circuit, str) and circuit != "general":
        canonical = {"controllable": controllable_canonical, "observable": observable_canonical}
        R2 = canonical[circuit](G2)
        return _finish(circuit, factorization, R2, (), (), (), delays)
    pattern = full_pattern(n) if circuit == "general" else circuit
    label = "general" if pattern == full_pattern(n) else pattern.text  # the dense class too
    syms = pattern.symbols()
    tree = set(pattern.tree_slots() or ())
    F, H, M = pattern.matrices(syms)
    N, c, a = split_proper(G2)
    charpoly, numer = coefficient_polynomials(F, H, M)
    equations = [sp.expand(p - q) for p, q in zip(charpoly, a, strict=True)]
    equations += [sp.together(p - q) for p, q in zip(numer, c, strict=True)]
    R2 = Realization(F, H, M, N, G2.dt)
    unknowns = tuple(syms[k] for k in pattern.indices)
    signed = tuple(syms[k] for k in sorted(tree))
    return _finish(label, factorization, R2, unknowns, signed, tuple(equations), delays)


def outgoing_synapses(circuit: Circuit) -> dict[str, tuple]:
    """Each neuron's synapses onto other neurons: what Dale's law signs (self and read-out exempt)."""
    names = {nr.name for nr in circuit.neurons}
    return {
        nr.name: tuple(s for s in nr.axon if s.target in names and s.target != nr.name)
        for nr in circuit.neurons
    }


def _finish(label, factorization, R2, unknowns, signed, equations, delays) -> Template:
    circuit = Circuit.from_structure(Structure.from_factorization(factorization, R2, delays))
    outgoing = {n: tuple(s.weight for s in out) for n, out in outgoing_synapses(circuit).items()}
    weights = [s.weight for nr in circuit.neurons for s in (*nr.synapses, *nr.self_terms)]
    return Template(
        label, factorization, R2, unknowns, signed, equations, circuit, outgoing,
        tuple(weights), delays,
    )  # fmt: skip


# ---------------------------------------------------------------- z3
def _expr(w) -> sp.Expr:
    """A weight as a SymPy expression (Python ints become Integers; nothing is parsed)."""
    return sp.Integer(w) if isinstance(w, int) else w


def to_z3(expr, env: dict, ctx=None):
    """A SymPy rational function of ``env``'s symbols as a z3 real term (exact rationals only).

    ``ctx`` is the z3 context of the terms (default: that of ``env``'s first term).
    """
    if ctx is None:
        ctx = next(iter(env.values())).ctx if env else None
    expr = _expr(expr)
    if expr.is_Symbol:
        return env[expr]
    if expr.is_Rational:
        return z3.RealVal(int(expr.p), ctx) / z3.RealVal(int(expr.q), ctx)
    if expr.is_Float:
        q = Fraction(float(expr))
        return z3.RealVal(q.numerator, ctx) / z3.RealVal(q.denominator, ctx)
    if expr.is_Add:
        return z3.Sum([to_z3(t, env, ctx) for t in expr.args])
    if expr.is_Mul:
        return z3.Product([to_z3(t, env, ctx) for t in expr.args])
    if expr.is_Pow and expr.exp.is_Integer:
        base = to_z3(expr.base, env, ctx)
        k = int(expr.exp)
        power = z3.Product([base] * abs(k)) if abs(k) > 1 else base
        return power if k > 0 else 1 / power
    raise ParameterError(f"G: a coefficient {expr} is not a rational function of the unknowns")


@dataclass(frozen=True)
class Encoding:
    """The z3 formula of one template (see the module text)."""

    env: dict
    solver: z3.Solver
    signs: dict
    mixed: dict


def encode(t: Template, poles, *, timeout: float, relax: bool = False, fixed=None) -> Encoding:
    """The template's constraints in a fresh ``QF_NRA`` solver (``relax``: a neuron may be mixed)."""
    symbols = sorted(
        {*t.sections, *t.unknowns}
        | set().union(*(_expr(w).free_symbols for w in (*t.weights, *t.equations))),
        key=str,
    )
    ctx = z3.Context()  # its own context: a call never depends on an earlier one
    env = {s: z3.Real(str(s), ctx) for s in symbols}
    solver = z3.SolverFor("QF_NRA", ctx=ctx)
    solver.set("timeout", max(1, int(timeout * 1000)))
    f = t.factorization
    for e in (*f.sensor_eps, *f.actuator_eps):
        x = env[e]
        solver.add(x > -1, x < 1, x != 0)
        solver.add(*(to_z3(sp.expand(p), {**env, z: x}, ctx) != 0 for p in poles))
    for k, c in enumerate((*f.sensor_C, *f.actuator_C)):  # see "The sections' C" above
        solver.add(env[c] * env[c] == 1 if k == 0 else env[c] == 1)
    for u in t.unknowns:
        solver.add(env[u] != 0)
    for u in t.signed:
        solver.add(env[u] * env[u] == 1)
    for eq in t.equations:
        num, den = sp.fraction(sp.together(eq))
        solver.add(to_z3(sp.expand(num), env, ctx) == 0)
        if not den.is_number:
            solver.add(to_z3(den, env, ctx) != 0)
    for w in t.weights:
        if not _expr(w).is_number:
            solver.add(to_z3(w, env, ctx) != 0)
    signs, mixed = {}, {}
    for name, ws in t.outgoing.items():
        if len(ws) < 2:  # one synapse has one sign: nothing to decide (it is nonzero above)
            continue
        s = signs[name] = z3.Bool(f"excitatory[{name}]", ctx)
        terms = [to_z3(w, env, ctx) for w in ws]
        rule = z3.If(s, z3.And(*[w > 0 for w in terms]), z3.And(*[w < 0 for w in terms]))
        if relax:
            m = mixed[name] = z3.Bool(f"mixed[{name}]", ctx)
            solver.add(z3.Or(m, rule))
        else:
            solver.add(rule)
    for sym, value in (fixed or {}).items():
        solver.add(env[sym] == to_z3(value, env, ctx))
    return Encoding(env, solver, signs, mixed)


def decide(enc: Encoding, free=(), *, budget: float = 30.0) -> tuple[str, list]:
    """``(verdict, assumptions)``: one z3 call per sign assignment of the multi-synapse neurons.

    nlsat is far faster on a conjunction than on the disjunction of all
    assignments, so the :math:`2^m` assignments (neurons in ``free``, allowed to be
    mixed, are skipped) are tried in turn, within ``budget`` seconds in all:
    ``"sat"`` with the assignment that holds, ``"unsat"`` when every one is
    refuted (a proof), else ``"unknown"``.
    """
    deadline = time.perf_counter() + budget
    names = [n for n in enc.signs if n not in free]
    fixed = [enc.mixed[n] if n in free else z3.Not(enc.mixed[n]) for n in enc.mixed]
    unknown = False
    for combo in itertools.product((True, False), repeat=len(names)):
        left = deadline - time.perf_counter()
        if left <= 0:
            return "unknown", []
        enc.solver.set("timeout", max(1, int(left * 1000)))
        assume = fixed + [b if v else z3.Not(b) for b, v in
                          zip((enc.signs[n] for n in names), combo, strict=True)]  # fmt: skip
        got = enc.solver.check(*assume)
        if got == z3.sat:
            return "sat", assume
        unknown |= got != z3.unsat
    return ("unknown" if unknown else "unsat"), []


# ---------------------------------------------------------------- witnesses
def value_of(v) -> sp.Expr:
    """A z3 model value as an exact SymPy number (a Rational or a CRootOf)."""
    if z3.is_int_value(v):
        return sp.Integer(v.as_long())
    if z3.is_rational_value(v):
        return sp.Rational(v.numerator_as_long(), v.denominator_as_long())
    if z3.is_algebraic_value(v):
        x = sp.Dummy("x")
        coeffs = [value_of(c) for c in v.poly()]
        poly = sp.Poly(sp.Add(*(c * x**k for k, c in enumerate(coeffs))), x)
        return sp.CRootOf(poly, v.index() - 1)
    raise ParameterError(f"z3 gave a value {v} that is neither rational nor algebraic")


def _candidates(v, count: int = 6):
    """Simple rationals near the real z3 value ``v``: its continued-fraction convergents."""
    approx = Fraction(v.approx(30).as_fraction()) if z3.is_algebraic_value(v) else None
    if approx is None:
        approx = Fraction(v.numerator_as_long(), v.denominator_as_long())
    out = []
    for den in (1, 2, 4, 10, 100, 1000, 10**4, 10**6, 10**9):
        q = approx.limit_denominator(den)
        if q != 0 and q not in out:
            out.append(q)
    return out[:count] if len(out) > count else out


def refine(enc: Encoding, order, *, timeout: float = 2.0, keep=()) -> dict:
    """A model with as many unknowns rational as z3 allows: each one pinned in turn.

    ``order`` lists the symbols, first to last. A symbol whose value is a
    simple rational (denominator at most 1000) is pinned to it; another is
    pinned to the first simple rational near its value for which the formula
    stays satisfiable (each try at most ``timeout`` seconds), or left to the
    equations. Pinning the free directions of a family first (the sections,
    then :math:`F` and :math:`H`) leaves the rest determined by linear
    equations, so rational too. ``keep`` are assumptions every check keeps
    (and the current model satisfies).
    """
    s = enc.solver
    s.set("timeout", max(1, int(timeout * 1000)))
    pinned: list = list(keep)
    model = s.model()
    for sym in order:
        x = enc.env[sym]
        v = model.eval(x, model_completion=True)
        if z3.is_rational_value(v) and v.denominator_as_long() <= 1000:
            pinned.append(x == v)
            continue
        for q in _candidates(v):
            pin = x == z3.RealVal(q.numerator, x.ctx) / z3.RealVal(q.denominator, x.ctx)
            if s.check(*pinned, pin) == z3.sat:
                pinned.append(pin)
                model = s.model()
                break
    m = model  # satisfies every pin: each was read off it, or checked and it was re-read
    values = {sym: value_of(m.eval(x, model_completion=True)) for sym, x in enc.env.items()}
    signs = {name: z3.is_true(m.eval(b, model_completion=True)) for name, b in enc.signs.items()}
    mixed = {name: z3.is_true(m.eval(b, model_completion=True)) for name, b in enc.mixed.items()}
    return {"values": values, "signs": signs, "mixed": mixed}
