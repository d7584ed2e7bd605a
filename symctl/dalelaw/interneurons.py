r"""The cheapest E/I circuit of a controller, with sign-flipping interneurons where needed.

A neuron :math:`j` with **mixed** signs keeps Dale's law with one inhibitory interneuron
:math:`I_j`: :math:`j` (sign :math:`\sigma`) sends :math:`\sigma` to :math:`I_j` (delay 0),
and :math:`I_j` sends :math:`w_t / \sigma < 0` to each target :math:`t` whose weight
:math:`w_t` has the other sign: the product is :math:`w_t`, so :math:`G` is unchanged. z3
finds each circuit's fewest mixed neurons (every smaller subset refuted).
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import sympy as sp

from symctl._util.deadline import Deadline, Unfinished, deadline_of
from symctl._util.serial import DictMixin
from symctl._util.validate import callable_or_none
from symctl.dalelaw.dale import (
    GENERAL_SEARCH,
    MAX_TIMEOUT,
    METHOD,
    WITNESS_PIN,
    _witness,
    controller_of,
    poles_of,
    search_general,
    templates_of,
)
from symctl.dalelaw.signs import _expr, decide, encode, outgoing_synapses, refine
from symctl.errors import ParameterError
from symctl.realization.factorization import factor
from symctl.realization.realizers import circuit_names

__all__ = ["EICandidate", "EICircuit", "Interneuron", "ei_circuit"]

ATLAS_MAX_ORDER = 2  # highest order of G2 whose atlas classes are searched by default


@dataclass(frozen=True)
class Interneuron:
    """An inhibitory interneuron ``I[source]`` relaying the minority-sign synapses of the mixed
    neuron ``source`` (which keeps ``sign``) to ``targets`` with negative ``weights``."""

    name: str
    source: str
    sign: str
    targets: tuple
    weights: tuple


@dataclass(frozen=True)
class EICandidate:
    """One searched circuit: its neurons and the fewest mixed neurons it needs (or why not)."""

    label: str
    neurons: int | None
    mixed: int | None
    status: str

    @property
    def total(self) -> int | None:
        """Neurons plus one interneuron per mixed neuron."""
        return None if self.mixed is None or self.neurons is None else self.neurons + self.mixed


@dataclass(frozen=True)
class EICircuit(DictMixin):
    r"""The cheapest E/I circuit found by :func:`ei_circuit`.

    Attributes
    ----------
    circuit : str
        The winning circuit's label.
    base_neurons, neurons : int
        Its neurons (sections included), and with one interneuron per mixed neuron.
    interneurons : tuple of str
        The mixed neurons, each relayed by an inhibitory interneuron (:attr:`relays`).
    minimum, cost : int
        The fewest neurons of any searched circuit realizing :math:`G` without Dale's law,
        and ``neurons - minimum``, what Dale's law costs.
    signs : mapping
        Every neuron's sign in the E/I circuit (interneurons ``"-"``).
    relays : tuple of Interneuron
    realization : Realization
        The exact witness of :math:`G_3 G_2 G_1`; the relays leave it unchanged.
    candidates : tuple of EICandidate
        Every circuit searched, with its verdict.
    method, reason : str

    Examples
    --------
    >>> import sympy as sp, symctl
    >>> from symctl import z
    >>> e = symctl.ei_circuit(-sp.Rational(1, 20) / (z**2 + z / 2 + sp.Rational(1, 3)),
    ...                       sensor_delay=1, actuator_delay=1)
    >>> e.cost, e.neurons == e.minimum
    (0, True)
    """

    circuit: str
    base_neurons: int
    interneurons: tuple
    neurons: int
    minimum: int
    cost: int
    signs: Mapping = field(default_factory=dict)
    relays: tuple = ()
    realization: object = field(default=None, repr=False)
    candidates: tuple = field(default=(), repr=False)
    method: str = METHOD
    reason: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "signs", MappingProxyType(dict(self.signs)))

    def table(self) -> str:
        """The searched circuits, one line each."""
        rows = [f"{'circuit':>14} | neurons | mixed | total | status"]
        for c in self.candidates:
            mixed = "" if c.mixed is None else str(c.mixed)
            total = "" if c.total is None else str(c.total)
            rows.append(f"{c.label:>14} | {c.neurons!s:>7} | {mixed:>5} | {total:>5} | {c.status}")
        return "\n".join(rows)


def _candidates(circuits, n: int):
    if circuits is not None:
        if isinstance(circuits, str) or not isinstance(circuits, Iterable):
            raise ParameterError(
                "circuits: expected a list of circuits (names, CircuitClass or Pattern), "
                f"got {circuits!r}"
            )
        out = list(circuits)
        if not out:
            raise ParameterError("circuits: empty; give at least one circuit")
        return out
    out = list(circuit_names(whole=False))
    if 1 <= n <= ATLAS_MAX_ORDER:
        from symctl.circuitatlas.atlas import atlas

        out += list(atlas(n, workers=1).classes)
    return out


def _fewest_mixed(G, t, poles, deadline: Deadline):
    """``(verdict, k, model)``: the fewest mixed neurons of template ``t`` and a witness."""
    try:
        enc = encode(t, poles, deadline, relax=True)
    except Unfinished:
        return "unknown", None, None
    names = list(enc.mixed)
    unknown = False
    for k in range(len(names) + 1):
        for free in itertools.combinations(names, k):
            if deadline.expired():
                return "unknown", None, None
            verdict, assume = decide(enc, free, deadline=deadline)
            if verdict == "sat":
                order = [*t.sections, *t.unknowns]
                try:
                    model = refine(enc, order, deadline=deadline, cap=WITNESS_PIN, keep=assume)
                except Unfinished:  # satisfiable, but the witness is not exact in time
                    return "unknown", None, None
                return ("sat" if not unknown else "bound"), k, model | {"proved": not unknown}
            unknown |= verdict == "unknown"
    return ("unknown" if unknown else "unsat"), None, None


def ei_circuit(
    G,
    *,
    sensor_delay: int | None = None,
    actuator_delay: int | None = None,
    circuits=None,
    timeout: float = 30.0,
    progress: Callable[[str], None] | None = None,
) -> EICircuit:
    r"""The cheapest circuit of ``G`` that obeys Dale's law, with interneurons where it must.

    Parameters
    ----------
    G, sensor_delay, actuator_delay
        As in :func:`~symctl.dalelaw.dale.dale`.
    circuits : list, optional
        Names, ``CircuitClass`` or ``Pattern``; default the named circuits and, for
        :math:`G_2` of order 1 or 2, every class of ``symctl.atlas(order)``.
    timeout : float or Deadline
        Seconds for each circuit's search (at most 3600), or a Deadline for the whole call.
    progress : callable, optional
        Called with each circuit's label before its search.

    Returns
    -------
    EICircuit

    Raises
    ------
    ParameterError, SymctlTypeError
        No searched circuit realizes ``G`` (or none was decided), an empty ``circuits``,
        ``progress`` not callable; the errors of :func:`~symctl.dalelaw.dale.dale`.

    Examples
    --------
    >>> import sympy as sp, symctl
    >>> from symctl import z
    >>> G = -sp.Rational(1, 20) / (z**2 + z / 2 + sp.Rational(1, 3))
    >>> e = symctl.ei_circuit(G, sensor_delay=1, actuator_delay=1,
    ...                       circuits=["observable", "controllable"], progress=print)
    observable
    controllable
    >>> e.circuit, e.cost, [(c.label, c.mixed) for c in e.candidates]
    ('controllable', 0, [('observable', 1), ('controllable', 0)])
    """
    t0 = time.perf_counter()
    shared = isinstance(timeout, Deadline)
    whole = deadline_of(timeout, "timeout", MAX_TIMEOUT)
    step = callable_or_none(progress, "progress") or (lambda _name: None)
    G, ds, da = controller_of(G, sensor_delay, actuator_delay)
    fs = factor(G, ds, da)
    poles = poles_of(G)
    found: list[EICandidate] = []
    best = None
    for circuit in _candidates(circuits, fs.G2.order):
        deadline = whole if shared else Deadline(whole.seconds)  # this circuit's search
        step(getattr(circuit, "label", None) or getattr(circuit, "text", str(circuit)))
        try:
            label, templates = templates_of(fs, circuit)
        except ParameterError as exc:  # a class of another order, or N = 0
            name = getattr(circuit, "label", str(circuit))
            found.append(EICandidate(name, None, None, f"cannot realize: {exc}"))
            continue
        outcome = None
        for t in templates:
            verdict, k, model = _fewest_mixed(G, t, poles, deadline)
            if verdict == "unknown" and t.label == "general":
                values = search_general(G, t, deadline=deadline.within(GENERAL_SEARCH))
                if values is not None:
                    verdict, k, model = "sat", 0, {"values": values, "mixed": {}}
            if verdict in ("sat", "bound") and (outcome is None or k < outcome[1]):
                outcome = (t, k, model)
            elif outcome is None:
                outcome = verdict
        neurons = templates[0].circuit.n_neurons
        if isinstance(outcome, tuple):
            t, k, model = outcome
            proved = model.get("proved", True)
            status = "decided (z3)" if proved else "upper bound (z3 undecided below)"
            found.append(EICandidate(label, neurons, k, status))
            if best is None or (neurons + k, k) < best[0]:  # at a tie, fewer interneurons
                best = ((neurons + k, k), label, t, model, neurons)
        else:
            status = "cannot realize G" if outcome == "unsat" else "not decided (z3 timeout)"
            found.append(EICandidate(label, neurons, None, status))
    if best is None:
        raise ParameterError(
            "circuits: no searched circuit realizes G (or none was decided within the timeout)"
        )
    _, label, t, model, neurons = best
    minimum = min(c.neurons for c in found if c.mixed is not None)
    relays, signs, realization = _relays(G, fs, t, model)
    total = neurons + len(relays)
    reason = (
        f"{len(found)} circuits searched in {time.perf_counter() - t0:.1f} s; the fewest mixed "
        "neurons of each is proved by z3 (that bound is satisfiable, one fewer is not); "
        f"{label} needs {len(relays)} interneuron{'' if len(relays) == 1 else 's'}"
    )
    mixed, cost = tuple(r.source for r in relays), total - minimum
    args = (label, neurons, mixed, total, minimum, cost, signs, tuple(relays), realization)
    return EICircuit(*args, tuple(found), METHOD, reason)


def _relays(G, fs, t, model):
    """The witness's interneurons, every neuron's sign and the whole controller (exact)."""
    mixed = {name for name, m in model.get("mixed", {}).items() if m}
    witness = _witness(G, fs, t, {"values": model["values"]}, t.label, [], Deadline(0.0), mixed)
    relays, signs = [], {}
    for source, out in outgoing_synapses(witness.witness).items():
        sign = signs[source] = witness.signs[source]
        sigma = 1 if sign == "+" else -1
        flip = [(s.target, _expr(s.weight) / sigma) for s in out if _expr(s.weight) * sigma < 0]
        if flip:  # a mixed neuron: its minority-sign synapses through an interneuron
            name = f"I[{source}]"
            targets, weights = tuple(a for a, _ in flip), tuple(w for _, w in flip)
            relays.append(Interneuron(name, source, sign, targets, weights))
            signs[name] = "-"
    if any(not all(sp.sign(w) < 0 for w in r.weights) for r in relays):  # pragma: no cover
        raise ParameterError("circuits: an interneuron's relayed weights are not all negative")
    return relays, signs, witness.realization
