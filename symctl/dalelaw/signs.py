r"""Dale's law as a polynomial sign problem, decided exactly by z3's nonlinear real arithmetic.

A **template** is one circuit's family of realizations of :math:`G = G_3 G_2 G_1`: the sections'
:math:`\epsilon_k, C_k` are unknowns, and :math:`G_2`'s realization is a canonical form or a
pattern (:mod:`symctl.circuitatlas.pattern`) whose nonzero entries are unknowns tied to
:math:`G_2 = N + c/a` by :math:`\det(zI - F) = a(z)`, :math:`M\,\operatorname{adj}(zI - F)\,H =
c(z)`. Positive diagonal similarities keep every sign, so a spanning tree's entries
(:meth:`Pattern.tree_slots`) are set to :math:`\pm 1`: no sign is lost. A Boolean :math:`s_j`
per neuron asks :math:`s_j \Rightarrow w > 0`, :math:`\lnot s_j \Rightarrow w < 0` of each of its
outgoing weights; :math:`|\epsilon_k| < 1`, :math:`\epsilon_k \ne 0` off the poles of :math:`G`,
every weight nonzero.

**The sections' C.** Each :math:`C_k` weighs one synapse, from the input (exempt) or the only
one a section neuron sends on (either sign); and the :math:`C_k` scale :math:`G_2` by
:math:`1/\prod_k C_k`, a positive scale moving into :math:`H` and :math:`N` without changing a
sign. So nothing is lost by setting every :math:`C_k = 1` but the first, :math:`C = \pm 1`.
"""

from __future__ import annotations

import itertools
import threading
from dataclasses import dataclass, field
from fractions import Fraction

import sympy as sp
import z3

from symctl._util.deadline import Deadline, Unfinished
from symctl.circuitatlas.fibre import coefficient_polys
from symctl.circuitatlas.pattern import Pattern
from symctl.compatibility.structure import Structure
from symctl.errors import ParameterError
from symctl.neural.circuit import Circuit
from symctl.realization.realization import Realization, split_proper
from symctl.realization.realizers import circuit_names, get_realizer
from symctl.symbols import z

__all__ = ["Template", "decide", "full_pattern", "outgoing_synapses", "template", "to_z3"]


def __getattr__(name: str):
    """``NAMED``: the circuits of G2 named by a word, read from the registry at each access."""
    if name == "NAMED":
        return circuit_names(whole=False)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def full_pattern(n: int) -> Pattern:
    """The pattern with every entry of :math:`(F, H, M)` nonzero: the paper's general circuit."""
    return Pattern(n, (1 << (n * n + 2 * n)) - 1)


@dataclass(frozen=True)
class Template:
    """One circuit's family of realizations of :math:`G`: ``R2`` in the ``unknowns`` (``signed``:
    those set to :math:`\\pm 1`), the ``target`` ``(a, c)`` a pattern's ``R2`` must match."""

    label: str
    factorization: object
    R2: Realization
    unknowns: tuple
    signed: tuple
    target: tuple
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
    """The template of ``circuit`` (a name of ``NAMED`` or a Pattern) for ``factorization``."""
    G2 = factorization.G2
    n = G2.order
    if isinstance(circuit, str) and not get_realizer(circuit, "circuit").takes_transform:
        R2 = get_realizer(circuit, "circuit")(G2).realization  # a fixed form, no unknowns
        return _finish(circuit, factorization, R2, (), (), (), delays)
    pattern = full_pattern(n) if circuit == "general" else circuit
    label = "general" if pattern == full_pattern(n) else pattern.text  # the dense class too
    syms = pattern.symbols()
    tree = set(pattern.tree_slots() or ())
    F, H, M = pattern.matrices(syms)
    N, c, a = split_proper(G2)
    R2 = Realization(F, H, M, N, G2.dt)
    unknowns = tuple(syms[k] for k in pattern.indices)
    signed = tuple(syms[k] for k in sorted(tree))
    return _finish(label, factorization, R2, unknowns, signed, (tuple(a), tuple(c)), delays)


def outgoing_synapses(circuit: Circuit) -> dict[str, tuple]:
    """Each neuron's synapses onto other neurons: what Dale's law signs (self and read-out exempt)."""
    names = {nr.name for nr in circuit.neurons}
    return {
        nr.name: tuple(s for s in nr.axon if s.target in names and s.target != nr.name)
        for nr in circuit.neurons
    }


def _finish(label, factorization, R2, unknowns, signed, target, delays) -> Template:
    circuit = Circuit.from_structure(Structure.from_factorization(factorization, R2, delays))
    outgoing = {n: tuple(s.weight for s in out) for n, out in outgoing_synapses(circuit).items()}
    weights = tuple(s.weight for nr in circuit.neurons for s in (*nr.synapses, *nr.self_terms))
    args = (label, factorization, R2, unknowns, signed, target, circuit, outgoing, weights)
    return Template(*args, delays)


def _expr(w) -> sp.Expr:
    """A weight as a SymPy expression (Python ints become Integers; nothing is parsed)."""
    return sp.Integer(w) if isinstance(w, int) else w


def to_z3(expr, env: dict, ctx):
    """A SymPy rational function as a z3 real term, through z3's C API (the Python API is slow)."""
    expr = _expr(expr)
    if expr.is_Symbol:
        return env[expr]
    if expr.is_Rational or expr.is_Float:
        q = Fraction(int(expr.p), int(expr.q)) if expr.is_Rational else Fraction(float(expr))
        return _apply(z3.Z3_mk_div, [z3.RealVal(q.numerator, ctx), z3.RealVal(q.denominator, ctx)])
    if expr.is_Add or expr.is_Mul:
        args = [to_z3(t, env, ctx) for t in expr.args]
        return _apply(z3.Z3_mk_add if expr.is_Add else z3.Z3_mk_mul, args)
    if expr.is_Pow and expr.exp.is_Integer:
        base = to_z3(expr.base, env, ctx)
        k = int(expr.exp)
        power = _apply(z3.Z3_mk_mul, [base] * abs(k)) if abs(k) > 1 else base
        return power if k > 0 else 1 / power
    raise ParameterError(f"G: a coefficient {expr} is not a rational function of the unknowns")


def _apply(make, args: list):
    """The z3 term ``make(args)``, wrapped at once (z3 counts a reference)."""
    ctx = args[0].ctx
    array = [a.as_ast() for a in args]
    if make is z3.Z3_mk_div:
        return z3.ArithRef(make(ctx.ref(), *array), ctx)
    return z3.ArithRef(make(ctx.ref(), len(array), (z3.Ast * len(array))(*array)), ctx)


@dataclass(frozen=True)
class Encoding:
    """The z3 formula of one template; ``running``: z3 calls that outlived their deadline."""

    env: dict
    solver: z3.Solver
    signs: dict
    mixed: dict
    running: list = field(default_factory=list, repr=False, compare=False)


def encode(t: Template, poles, deadline: Deadline, *, relax: bool = False) -> Encoding:
    """The template's constraints in a fresh ``QF_NRA`` solver (``relax``: a neuron may be mixed)."""
    R2 = t.R2
    entries = (*R2.F, *R2.H, *R2.M, *t.weights, *(x for part in t.target for x in part))
    symbols = {*t.sections, *t.unknowns}.union(*(_expr(w).free_symbols for w in entries))
    symbols = sorted(symbols - {z}, key=str)
    ctx = z3.Context()  # its own context: a call never depends on an earlier one
    env = {s: z3.Real(str(s), ctx) for s in symbols}
    solver = z3.SolverFor("QF_NRA", ctx=ctx)
    solver.set("timeout", _ms(deadline))
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
    for num, den in _equations(t, symbols, deadline):
        solver.add(to_z3(num, env, ctx) == 0)
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
    deadline.check(f"the z3 formula of {t.label}")
    return Encoding(env, solver, signs, mixed)


def _equations(t: Template, symbols, deadline: Deadline):
    """``(numerator, denominator)`` of each coefficient equation of a pattern's ``R2``."""
    if not t.target:
        return
    ring, *_ = sp.ring([*symbols, z], sp.QQ)
    charpoly, numer = coefficient_polys(t.R2.F, t.R2.H, t.R2.M, ring, deadline=deadline)
    for p, q in zip((*charpoly, *numer), (*t.target[0], *t.target[1]), strict=True):
        num, den = sp.fraction(sp.together(q))
        yield _as_expr(p * ring.from_expr(den) - ring.from_expr(num), deadline, t.label), den


CHUNK = 500  # terms turned into a SymPy expression between two looks at the deadline


def _as_expr(poly, deadline: Deadline, label: str) -> sp.Expr:
    """``poly.as_expr()`` in :data:`CHUNK`-term pieces, the deadline checked between."""
    terms = poly.terms()
    parts = []
    for start in range(0, len(terms), CHUNK):
        deadline.check(f"the z3 formula of {label}")
        parts.append(poly.ring(dict(terms[start : start + CHUNK])).as_expr())
    return sp.Add(*parts)


def _ms(deadline: Deadline, cap: float | None = None) -> int:
    """z3's timeout in milliseconds: the time left (at most ``cap`` seconds), at least 1."""
    left = deadline.left() if cap is None else min(cap, deadline.left())
    return max(1, int(left * 1000))


GRACE = 0.25  # seconds a z3 call may run past its timeout before check stops waiting


def check(enc: Encoding, assume, deadline: Deadline, cap: float | None = None, *, grace=GRACE):
    """``enc.solver.check(*assume)`` within ``deadline`` (and ``cap`` s); z3 can overrun its
    timeout by a minute, so it runs in a thread given ``grace`` s more, then ``unknown``."""
    if not idle(enc, deadline):
        return z3.unknown
    left = deadline.left() if cap is None else min(cap, deadline.left())
    enc.solver.set("timeout", _ms(deadline, cap))
    out: list = []

    def run(enc=enc, assume=assume):  # holds every z3 object it uses until it ends
        try:
            out.append(enc.solver.check(*assume))
        except z3.Z3Exception as exc:  # pragma: no cover - z3 reports errors as exceptions
            out.append(exc)

    worker = threading.Thread(target=run, name="symctl-z3", daemon=True)
    worker.start()
    worker.join(left + grace)
    if worker.is_alive():
        enc.solver.ctx.interrupt()
        enc.running.append(worker)
        return z3.unknown
    if isinstance(out[0], Exception):  # pragma: no cover
        raise out[0]
    return out[0]


def idle(enc: Encoding, deadline: Deadline) -> bool:
    """The formula's context is free: no z3 call left running, or it ended before ``deadline``."""
    while enc.running:
        enc.running[0].join(deadline.left())
        if enc.running[0].is_alive():
            return False
        enc.running.pop(0)
    return True


def decide(enc: Encoding, free=(), *, deadline: Deadline) -> tuple[str, list]:
    """``(verdict, assumptions)``: one z3 call per sign assignment (nlsat is faster on
    conjunctions); ``free`` neurons may be mixed."""
    if deadline.expired() or not idle(enc, deadline):
        return "unknown", []
    names = [n for n in enc.signs if n not in free]
    fixed = [enc.mixed[n] if n in free else z3.Not(enc.mixed[n]) for n in enc.mixed]
    unknown = False
    for combo in itertools.product((True, False), repeat=len(names)):
        if deadline.expired():
            return "unknown", []
        assume = fixed + [
            b if v else z3.Not(b) for b, v in zip((enc.signs[n] for n in names), combo, strict=True)
        ]
        got = check(enc, assume, deadline)
        if got == z3.sat:
            return "sat", assume
        if enc.running:  # a call left running: its context is not to be touched
            return "unknown", []
        unknown |= got != z3.unsat
    return ("unknown" if unknown else "unsat"), []


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
    return out[:count]


def refine(enc: Encoding, order, *, deadline: Deadline, cap: float = 0.5, keep=()) -> dict:
    """A model with each unknown in ``order`` pinned in turn to a nearby simple rational that
    keeps the formula satisfiable (each try ``cap`` s); the rest then solve rationally."""
    s = enc.solver
    pinned: list = list(keep)
    model = s.model()
    for sym in order:
        x = enc.env[sym]
        v = model.eval(x, model_completion=True)
        if z3.is_rational_value(v) and v.denominator_as_long() <= 1000:
            pinned.append(x == v)
            continue
        for q in _candidates(v):
            if deadline.expired():
                raise Unfinished(f"pinning the witness's {sym} to a rational: out of time")
            pin = x == z3.RealVal(q.numerator, x.ctx) / z3.RealVal(q.denominator, x.ctx)
            got = check(enc, [*pinned, pin], deadline, cap)
            if not idle(enc, deadline):
                raise Unfinished(f"pinning the witness's {sym}: z3 still running at the deadline")
            if got == z3.sat:
                pinned.append(pin)
                model = s.model()
                break
    # the model satisfies every pin: each was read off it, or checked and it was re-read
    values = {sym: value_of(model.eval(x, model_completion=True)) for sym, x in enc.env.items()}
    signs = {n: z3.is_true(model.eval(b, model_completion=True)) for n, b in enc.signs.items()}
    mixed = {n: z3.is_true(model.eval(b, model_completion=True)) for n, b in enc.mixed.items()}
    return {"values": values, "signs": signs, "mixed": mixed}
