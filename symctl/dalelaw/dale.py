"""Dale's law for one circuit of the controller: :func:`dale` and its verdict (docs/guide/dale.md)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import sympy as sp

from symctl._util.deadline import Deadline, Unfinished, deadline_of
from symctl._util.validate import callable_or_none, nonneg_int
from symctl.circuitatlas.circuitclass import CircuitClass
from symctl.circuitatlas.fibre import binary_rationals
from symctl.circuitatlas.pattern import MAX_ORDER, Pattern
from symctl.compatibility.structure import Structure
from symctl.dalelaw.signs import (
    Template,
    _expr,
    decide,
    encode,
    outgoing_synapses,
    refine,
    template,
)
from symctl.dalelaw.witness import search_general
from symctl.design.controller import controller_tf
from symctl.design.lqr import Gains
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, NotRealizableError, ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit
from symctl.proof import Verdict
from symctl.realization.check import check_realization
from symctl.realization.factorization import factor
from symctl.realization.realization import Realization, controller_realization
from symctl.realization.realizers import circuit_names
from symctl.symbols import z

__all__ = ["METHOD", "DaleResult", "controller_of", "dale", "templates_of"]

METHOD = "z3 nlsat (a complete decision procedure for nonlinear real arithmetic)"
MAX_TIMEOUT = 3600.0  # most seconds a ``timeout`` may give
GENERAL_Z3_FIRST = 3.0  # seconds of z3 on the general circuit before the numeric search
GENERAL_SEARCH = 20.0  # most seconds of the general circuit's numeric search
WITNESS_PIN = 0.5  # most seconds of each z3 call that pins a witness's value to a rational


@dataclass(frozen=True)
class DaleResult(Verdict):
    r"""The verdict of :func:`dale`: a witness (truthy; ``evidence`` the witness circuit), a
    proof that none exists, or "not decided" (``evidence`` the reason).

    Attributes
    ----------
    feasible : bool or None
        True (a witness), False (proved: no E/I realization of this circuit), None.
    realization : Realization or None
        The exact witness of the whole controller :math:`G_3 G_2 G_1`.
    signs : mapping
        Neuron name -> ``"+"`` or ``"-"`` (one driving only the read-out is ``"+"``).
    method, reason, circuit : str
        How it was decided, the evidence (or what was tried), and the circuit asked about.
    witness, R2, sections
        The witness circuit, :math:`G_2`'s realization in it, its :math:`\epsilon_k, C_k`.
    exact : bool
        The witness was verified in exact arithmetic (always, for a witness).
    realizes : bool or None
        Whether the circuit realizes :math:`G` at all, signs aside.
    elapsed : float

    Examples
    --------
    >>> import sympy as sp, symctl
    >>> from symctl import z
    >>> r = symctl.dale(-sp.Rational(1, 20) / (z**2 + z / 2 + sp.Rational(1, 3)),
    ...                 sensor_delay=1, actuator_delay=1, circuit="general")
    >>> r.feasible, r.exact, bool(symctl.check_realization(r.realization, r.G))
    (True, True, True)
    """

    feasible: bool | None
    realization: Realization | None
    signs: Mapping = field(default_factory=dict)
    method: str = METHOD
    reason: str = ""
    circuit: str = ""
    witness: Circuit | None = field(default=None, repr=False)
    R2: Realization | None = field(default=None, repr=False)
    sections: Mapping = field(default_factory=dict, repr=False)
    exact: bool = False
    elapsed: float = 0.0
    G: DiscreteTF | None = field(default=None, repr=False)
    realizes: bool | None = None

    _verdict = "feasible"

    @property
    def evidence(self):
        """The :attr:`witness` circuit when feasible, else the :attr:`reason`."""
        return self.witness if self.feasible else self.reason

    def __post_init__(self) -> None:
        object.__setattr__(self, "signs", MappingProxyType(dict(self.signs)))
        object.__setattr__(self, "sections", MappingProxyType(dict(self.sections)))

    def draw(self, ax=None, *, title: str | None = None):
        """Draw the witness circuit (a Figure); ParameterError when there is none."""
        if self.witness is None:
            raise ParameterError(
                f"draw: there is no witness to draw (feasible = {self.feasible}): {self.reason}"
            )
        return self.witness.draw(ax, title=title or f"E/I witness of the {self.circuit} circuit")

    def __str__(self) -> str:
        verdict = {True: "feasible", False: "infeasible", None: "not decided"}[self.feasible]
        lines = [f"Dale's law, circuit {self.circuit}: {verdict} ({self.method})", self.reason]
        if self.signs:
            lines.append("signs: " + ", ".join(f"{k} {v}" for k, v in self.signs.items()))
        return "\n".join(lines)


def controller_of(G, sensor_delay, actuator_delay) -> tuple[DiscreteTF, int, int]:
    """``(G, ds, da)``: a numeric SISO controller, its floats as exact binary rationals."""
    ds = da = 1
    if isinstance(G, Gains):
        ds, da = G.system.sensor_delay, G.system.actuator_delay
        G = controller_tf(G.system).subs(G.substitutions(exact=True))
    if isinstance(G, sp.Basic) and not isinstance(G, sp.MatrixBase):
        G = DiscreteTF.from_expr(G)
    if not isinstance(G, DiscreteTF):
        raise SymctlTypeError(
            f"G: expected Gains, a DiscreteTF or a SymPy expression in z, got {type(G).__name__}"
        )
    if G.shape != (1, 1):
        raise DimensionError(f"G: Dale's law is decided for a SISO controller, got {G.shape}")
    extra = sorted(str(s) for s in G.free_symbols - {z})
    if extra:
        raise ParameterError(
            f"G: must be numeric to decide Dale's law, but has the symbols {extra}; "
            "substitute the gains first (e.g. G.subs(gains.substitutions(exact=True)))"
        )
    ds = nonneg_int(ds if sensor_delay is None else sensor_delay, "sensor_delay")
    da = nonneg_int(da if actuator_delay is None else actuator_delay, "actuator_delay")
    return DiscreteTF.from_expr(binary_rationals(G.expr), G.dt), ds, da


def templates_of(factorization, circuit) -> tuple[str, list[Template]]:
    """``(label, templates)`` of ``circuit``: one per representative pattern of a class."""
    n = factorization.G2.order
    if isinstance(circuit, str):
        if circuit not in circuit_names(whole=False):
            raise ParameterError(
                f"circuit: must be one of {circuit_names(whole=False)} or a CircuitClass of the "
                f"atlas, got {circuit!r}"
            )
        if n == 0:
            raise NotRealizableError(
                "circuit: G2 is a constant (order 0), so it has no neurons of its own to sign"
            )
        if circuit == "general" and n > MAX_ORDER:
            raise ParameterError(
                f"circuit: the general circuit is decided up to order {MAX_ORDER} (its "
                f"equations grow as n! n^2 terms), but this G2 has order {n}; take "
                "'controllable' or 'observable'"
            )
        return circuit, [template(factorization, circuit)]
    if isinstance(circuit, Pattern):
        patterns, label, delays = [circuit], circuit.text, "branch"
    elif isinstance(circuit, CircuitClass):
        patterns, label, delays = list(circuit.representatives), circuit.label, circuit.delays
        label = label or "class"
    else:
        raise SymctlTypeError(
            f"circuit: expected {circuit_names(whole=False)}, a CircuitClass or a Pattern, got "
            f"{type(circuit).__name__}"
        )
    order = patterns[0].n
    if order != n:
        raise NotRealizableError(
            f"circuit: {label} has order {order}, but this controller's G2 has order {n}; "
            f"take a class of symctl.atlas({n})"
        )
    if factorization.N == 0:
        raise NotRealizableError(
            "circuit: the atlas's circuits have N = G2(oo) != 0, but this G2 has N = 0 "
            "(relative degree above the delays); use 'general', 'controllable' or 'observable'"
        )
    return label, [template(factorization, p, delays) for p in patterns]


def poles_of(G: DiscreteTF) -> list[sp.Expr]:
    """The denominator of ``G`` as a polynomial in ``z`` (the sections must avoid its roots)."""
    return [sp.fraction(sp.together(G.expr))[1]]


def dale(
    G,
    *,
    sensor_delay: int | None = None,
    actuator_delay: int | None = None,
    circuit="general",
    timeout: float = 30.0,
    progress: Callable[[str], None] | None = None,
) -> DaleResult:
    r"""Decide whether ``circuit`` can carry the controller ``G`` with every neuron E or I.

    What varies keeps :math:`G_3 G_2 G_1 = G` exact: :math:`\epsilon_k \in (-1, 1)` (nonzero,
    off the poles of :math:`G`), :math:`C_k \ne 0` and :math:`G_2`'s realization.

    Parameters
    ----------
    G : Gains, DiscreteTF or sympy expression in ``z``
        A numeric SISO controller (floats as the exact binary rationals they are); ``Gains``
        give the optimal controller with their delays.
    sensor_delay, actuator_delay : int, optional
        The split :math:`G_1`, :math:`G_3` (default the gains' delays, else 1 and 1).
    circuit : {"general", "controllable", "observable"}, CircuitClass or Pattern
        The circuit of :math:`G_2`, or a class of :func:`symctl.atlas` (each representative).
    timeout : float or Deadline
        Seconds for the whole call (default 30, at most 3600), or a running Deadline.
    progress : callable, optional
        Called with the name of each stage before it runs (``"general: z3"``, ...).

    Returns
    -------
    DaleResult

    Raises
    ------
    ParameterError, DimensionError
        Unknown ``circuit`` name, ``G`` with symbols or MIMO, a bad ``timeout``, delays that
        ``G``'s relative degree cannot carry.
    NotRealizableError
        A class of another order than :math:`G_2`, or :math:`N = 0` for a class.
    SymctlTypeError
        ``G`` or ``circuit`` of a wrong type, ``progress`` not callable.

    Examples
    --------
    >>> import symctl
    >>> from symctl import MuscleModel, augment, lqr_gains
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> r = symctl.dale(gains, circuit="general")     # the paper's controller
    >>> r.feasible, r.signs["G1.x1"] in "+-"
    (True, True)
    >>> stages = []
    >>> symctl.dale(gains, circuit="observable", progress=stages.append).feasible
    False
    >>> stages[:2]
    ['observable: equations', 'observable: z3']
    >>> symctl.dale(gains, circuit="diagonal")
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: circuit: must be one of ('general', 'controllable', ...
    """
    deadline = deadline_of(timeout, "timeout", MAX_TIMEOUT)
    step = callable_or_none(progress, "progress") or (lambda _name: None)
    G, ds, da = controller_of(G, sensor_delay, actuator_delay)
    fs = factor(G, ds, da)
    label, templates = templates_of(fs, circuit)
    poles = poles_of(G)
    tried: list[str] = []
    verdicts = []
    for t in templates:
        verdict, model = solve(G, t, poles, deadline, tried, progress=step)
        if verdict == "sat":
            step(f"{t.label}: witness check")
            return _witness(G, fs, t, model, label, tried, deadline)
        verdicts.append(verdict)
    if all(v == "unsat" for v in verdicts):
        step(f"{label}: G without signs")
        realizes = _realizes(templates, poles, deadline)
        why = {
            True: "it realizes G, but never with every neuron excitatory or inhibitory",
            False: "it does not realize this G at all, whatever the signs",
            None: "whether it realizes G at all was not decided",
        }[realizes]
        reason = (
            f"z3 proved the sign constraints unsatisfiable for every pattern of {label} "
            f"({'; '.join(tried)}), with stable nonzero sections: {why}"
        )
        elapsed = deadline.elapsed()
        return DaleResult(
            False, None, {}, METHOD, reason, label, G=G, realizes=realizes, elapsed=elapsed
        )
    reason = (
        f"not decided within timeout = {deadline.seconds:g} s ({'; '.join(tried)}); "
        "raise timeout to search longer"
    )
    return DaleResult(None, None, {}, METHOD, reason, label, G=G, elapsed=deadline.elapsed())


def any_sat(verdicts) -> bool | None:
    """True at the first ``"sat"`` (the rest not asked), False when all are ``"unsat"``, else None."""
    unknown = False
    for verdict in verdicts:
        if verdict == "sat":
            return True
        unknown |= verdict != "unsat"
    return None if unknown else False


def _realizes(templates, poles, deadline: Deadline) -> bool | None:
    """Some template realizes G with its signs free (every neuron allowed to be mixed)."""

    def verdicts():
        for t in templates:
            try:
                enc = encode(t, poles, deadline, relax=True)
            except Unfinished:
                yield "unknown"
                continue
            yield decide(enc, tuple(enc.mixed), deadline=deadline)[0]

    return any_sat(verdicts())


def solve(
    G, t: Template, poles, deadline: Deadline, tried: list, witness: bool = True, progress=None
) -> tuple[str, dict | None]:
    """``(verdict, model)`` of one template: z3 briefly, the general circuit's numeric search,
    z3 again (``witness``: the model pinned to rationals; ``tried`` gets each attempt)."""
    general = t.label == "general" and not G.free_symbols - {z}
    step = progress or (lambda _name: None)
    step(f"{t.label}: equations")
    try:
        enc = encode(t, poles, deadline)
    except Unfinished as exc:  # out of time, or the equations too large: z3 is not asked
        enc = None
        tried.append(f"{t.label}: z3 not asked ({exc})")
    verdict, assume = "unknown", []
    if enc is not None:
        step(f"{t.label}: z3")
        verdict, assume = decide(
            enc, deadline=deadline.within(GENERAL_Z3_FIRST) if general else deadline
        )
    if verdict == "unknown" and general:
        if deadline.expired():
            tried.append("general: no time left for the numeric search")
        else:
            step("general: numeric search")
            found = search_general(G, t, deadline=deadline.within(GENERAL_SEARCH))
            if found is not None:
                tried.append(
                    f"general: z3 undecided in {GENERAL_Z3_FIRST:g} s; Nelder-Mead found a "
                    "witness, made exact"
                )
                return "sat", {"values": found}
            tried.append("general: Nelder-Mead found no witness")
        if enc is not None:
            step("general: z3 again")
            verdict, assume = decide(enc, deadline=deadline)
    if enc is not None:
        tried.append(f"{t.label}: z3 {verdict}")
    if verdict != "sat" or not witness:
        return verdict, None
    order = [*t.sections, *t.unknowns]
    step(f"{t.label}: exact witness")
    try:
        return verdict, refine(enc, order, deadline=deadline, cap=WITNESS_PIN, keep=assume)
    except Unfinished as exc:  # z3 found one, but it is not exact yet: not a verdict
        tried.append(f"{t.label}: the witness not made exact ({exc})")
        return "unknown", None


def _witness(G, fs, t: Template, model: dict, label: str, tried, deadline, mixed=()) -> DaleResult:
    """The exact witness circuit of a model, verified (the ``mixed`` neurons may be mixed)."""
    values = model["values"]
    sections = {str(s): values[s] for s in t.sections}
    fixed = {s: values[s] for s in (*t.sections, *t.unknowns)}
    R2 = t.R2.subs(fixed)
    sub = fs.subs(fixed)
    whole = controller_realization(sub, R2)
    algebraic = any(not v.is_Rational for v in fixed.values())
    if algebraic:
        proof = "z3 evaluated every constraint exactly at the algebraic witness"
    else:
        check = check_realization(whole, G)
        if not check.ok:  # pragma: no cover - z3's model satisfies the equations
            raise ParameterError(f"circuit: the witness does not realize G ({check.details})")
        proof = "G3 G2 G1 = G proved by check_realization (exact rational arithmetic)"
    witness = Circuit.from_structure(Structure.from_factorization(sub, R2, t.delays))
    signs = _signs(witness, mixed)
    reason = (
        f"a witness of {t.label}: {proof}; every neuron's outgoing synapses have one sign "
        f"(read off the witness circuit exactly); z3: {'; '.join(tried)}"
    )
    elapsed = deadline.elapsed()
    return DaleResult(
        True, whole, signs, METHOD, reason, label, witness, R2, sections, True, elapsed, G, True
    )


def _signs(circuit: Circuit, mixed=()) -> dict[str, str]:
    """Each neuron's sign, read exactly off its outgoing weights (``mixed``: the majority)."""
    out = {}
    for name, synapses in outgoing_synapses(circuit).items():
        pos = sum(1 for s in synapses if _expr(s.weight) > 0)
        if 0 < pos < len(synapses) and name not in mixed:  # pragma: no cover - the constraints
            raise ParameterError(f"circuit: the witness's neuron {name} has mixed signs")
        out[name] = "+" if 2 * pos >= len(synapses) else "-"
    return out
