r"""Dale's law across the atlas: which circuit classes admit an E/I assignment for every controller.

A controller is :math:`G = k\,b(z)/a(z)`, :math:`a` monic of degree :math:`n`, :math:`b` monic
of degree :math:`n - d_s - d_a`. Per class: **never** (z3 proves no controller, its
coefficients unknowns, has an E/I realization in the class), **some** (a witness for one, a
refutation for another), **every** (every sampled controller has a witness: seeded exact
rationals, half with complex poles, modulus up to 1.5; evidence, not a proof) or ``None``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from symctl._util.deadline import Deadline
from symctl._util.deprecate import rng_argument
from symctl._util.serial import DictMixin
from symctl._util.validate import bounded_int, bounded_number, callable_or_none, nonneg_int
from symctl.circuitatlas.pattern import Pattern
from symctl.circuitatlas.search import open_pool, pool_options
from symctl.dalelaw.dale import MAX_TIMEOUT, _realizes, any_sat, controller_of, poles_of, solve
from symctl.dalelaw.signs import template
from symctl.design.tf import DiscreteTF
from symctl.errors import ParameterError
from symctl.realization.factorization import factor
from symctl.symbols import z

__all__ = ["MAX_SAMPLES", "DaleRow", "DaleTable", "dale_atlas"]

MAX_SAMPLES = 1000  # most sampled controllers per class


@dataclass(frozen=True)
class DaleRow:
    """One class of the E/I table; ``sampled`` counts E/I, not E/I, not realized, not decided."""

    label: str
    neurons: int
    synapses: int
    universal: bool | None
    verdict: str | None
    controller: bool | None
    sampled: tuple
    exists: str
    seconds: float


@dataclass(frozen=True)
class DaleTable(DictMixin):
    """The E/I table of an atlas (:func:`dale_atlas`).

    Attributes
    ----------
    order, sensor_delay, actuator_delay, samples : int
    rows : tuple of DaleRow
    seconds : float
    controller : str
        The controller of the ``controller`` column (empty when none was given).

    Examples
    --------
    >>> import symctl
    >>> T = symctl.dale_atlas(2, samples=1, classes=["A1"])
    >>> print(T.table().splitlines()[0])
    | class | neurons | synapses | universal | E/I for | sampled: E/I, not E/I, not realized, ? | exists |
    """

    order: int
    sensor_delay: int
    actuator_delay: int
    samples: int
    rows: tuple
    seconds: float
    controller: str = ""
    counts: dict = field(default_factory=dict)

    def table(self) -> str:
        """A Markdown table, one class per row."""
        head = (
            "| class | neurons | synapses | universal | E/I for | sampled: E/I, not E/I, "
            "not realized, ? | exists |"
        )
        if self.controller:
            head += " this controller |"
        lines = [head, "|" + "---|" * (head.count("|") - 1)]
        word = {True: "yes", False: "no", None: "?"}
        for r in self.rows:
            line = (
                f"| {r.label} | {r.neurons} | {r.synapses} | {word[r.universal]} | "
                f"{r.verdict or 'not decided'} | {'/'.join(map(str, r.sampled))} | {r.exists} |"
            )
            if self.controller:
                line += f" {word[r.controller]} |"
            lines.append(line)
        return "\n".join(lines)

    def summary(self) -> dict[str, list[str]]:
        """Class labels by verdict: ``{"every": [...], "some": [...], "never": [...], ...}``."""
        out: dict[str, list[str]] = {"every": [], "some": [], "never": [], "not decided": []}
        for r in self.rows:
            out[r.verdict or "not decided"].append(r.label)
        return out


def _symbolic(order: int, ds: int, da: int) -> DiscreteTF:
    """:math:`k\\,b/a` with coefficient symbols ``p_i`` (of ``a``), ``q_i`` (of ``b``)."""
    p = sp.symbols(f"p_0:{order}")
    m = order - ds - da
    q = sp.symbols(f"q_0:{m}") if m else ()
    a = z**order + sum(c * z**i for i, c in enumerate(p))
    b = z**m + sum(c * z**i for i, c in enumerate(q))
    return DiscreteTF(sp.Symbol("k") * b, a)


def _sample(order: int, ds: int, da: int, gen: np.random.Generator, i: int) -> DiscreteTF:
    """A seeded exact-rational controller: complex poles for odd ``i`` (when order >= 2)."""

    def rat(x):
        return sp.Rational(round(x * 1000), 1000) or sp.Rational(1, 1000)

    poles, degree = [], 0
    while degree < order:
        if i % 2 and order - degree >= 2:
            r, th = gen.uniform(0.1, 1.5), gen.uniform(0.1, np.pi - 0.1)
            re, mod2 = rat(r * np.cos(th)), rat(r * r)
            poles.append(z**2 - 2 * re * z + mod2)
            degree += 2
        else:
            poles.append(z - rat(gen.uniform(-1.5, 1.5)))
            degree += 1
    a = sp.expand(sp.Mul(*poles))
    zeros = [z - rat(gen.uniform(-1.5, 1.5)) for _ in range(order - ds - da)]
    k = rat(gen.choice([-1, 1]) * gen.uniform(0.1, 2.0))
    return DiscreteTF.from_expr(k * sp.Mul(*zeros) / a)


def _decide(G, patterns, delays, ds, da, timeout, relax=False) -> bool | None:
    """Some pattern realizes ``G`` with every neuron E or I (``relax``: signs free), in one ``timeout``."""
    deadline = Deadline(timeout)
    fs = factor(G, ds, da)
    templates = [template(fs, p, delays) for p in patterns]
    poles = poles_of(G)
    if relax:
        return _realizes(templates, poles, deadline)
    return any_sat(solve(G, t, poles, deadline, [], witness=False)[0] for t in templates)


def _row(spec, ds, da, samples, timeout, own):
    """Decide one class (runs in a worker: plain, picklable arguments)."""
    label, order, masks, delays, neurons, synapses, universal = spec
    t0 = time.perf_counter()
    patterns = [Pattern(order, m) for m in masks]
    counts = [0, 0, 0, 0]  # E/I, realized but not E/I, not realized, not decided
    for G in samples:
        ei = _decide(G, patterns, delays, ds, da, timeout)
        if ei is False:
            realized = _decide(G, patterns, delays, ds, da, timeout, relax=True)
            counts[{True: 1, False: 2, None: 3}[realized]] += 1
        else:
            counts[0 if ei else 3] += 1
    exists = "sat" if counts[0] else ""
    if counts[0] and counts[0] == len(samples):
        verdict = "every"
    elif counts[0] and (counts[1] or counts[2]):
        verdict = "some"
    else:  # no sampled witness: ask z3 whether any controller has one
        generic = _symbolic(order, ds, da)
        found = _decide(generic, patterns, delays, ds, da, 3 * timeout)  # more unknowns
        exists = {True: "sat", False: "unsat", None: "unknown"}[found]
        verdict = {True: "some", False: "never", None: None}[found]
        if counts[0]:  # sampled witnesses but undecided samples: not "every" for sure
            verdict = "some" if counts[1] or counts[2] else None
    mine = _decide(own, patterns, delays, ds, da, timeout) if own is not None else None
    seconds = time.perf_counter() - t0
    row = (label, neurons, synapses, universal, verdict, mine, tuple(counts), exists, seconds)
    return DaleRow(*row)


@rng_argument()
def dale_atlas(
    order: int = 2,
    *,
    sensor_delay: int = 1,
    actuator_delay: int = 1,
    samples: int = 24,
    rng=0,
    G=None,
    classes=None,
    timeout: float = 10.0,
    workers: int = 1,
    scheduler: str | None = None,
    progress: Callable[[str], None] | None = None,
) -> DaleTable:
    r"""The E/I table of the order-``order`` atlas: every, some or never (see the module text).

    Parameters
    ----------
    order : int
        The atlas's order, 1 or 2.
    sensor_delay, actuator_delay : int
        The split of the controllers; their sum is at most ``order``.
    samples : int
        Sampled controllers per class (at most 1000).
    rng : int, numpy Generator or None, default 0
        Seeds the samples.
    G : Gains, DiscreteTF or expression, optional
        A controller of its own column (e.g. the paper's gains).
    classes : list of str, optional
        Only these labels (default every class).
    timeout : float
        Seconds for each search (thrice for the generic controller).
    workers : int, scheduler : str, optional
        Processes (more than 1: dask's local cluster), or a dask scheduler's address.
    progress : callable, optional
        Called with each class's label once its row is decided.

    Returns
    -------
    DaleTable

    Raises
    ------
    ParameterError, SymctlTypeError
        An order outside 1..2, delays the order cannot carry, an unknown class label, bad
        ``samples``, ``timeout`` or ``workers``, an unreachable ``scheduler``; ``progress``
        not callable.

    Examples
    --------
    >>> import symctl
    >>> T = symctl.dale_atlas(2, samples=2, classes=["A1"], progress=print)
    A1
    >>> T.rows[0].verdict, T.rows[0].sampled
    ('every', (2, 0, 0, 0))
    """
    from symctl.circuitatlas.atlas import atlas

    t0 = time.perf_counter()
    order = bounded_int(order, "order", 1, 2)
    ds = nonneg_int(sensor_delay, "sensor_delay")
    da = nonneg_int(actuator_delay, "actuator_delay")
    if ds + da > order:
        raise ParameterError(
            f"sensor_delay: with actuator_delay, {ds} + {da} steps exceed the order {order} "
            "(G2 would have N = 0, and the atlas's circuits have N != 0)"
        )
    samples = bounded_int(samples, "samples", 0, MAX_SAMPLES)
    timeout = bounded_number(timeout, "timeout", 1e-3, MAX_TIMEOUT)
    workers, scheduler = pool_options(workers, scheduler)
    step = callable_or_none(progress, "progress") or (lambda _label: None)
    own, label = None, ""
    if G is not None:
        own, _, _ = controller_of(G, ds, da)
        label = str(own.expr)
    found = atlas(order, workers=1).classes
    if classes is not None:
        if isinstance(classes, str):
            classes = [classes]
        known = {c.label: c for c in found}
        bad = [c for c in classes if not isinstance(c, str) or c not in known]
        if bad:
            raise ParameterError(
                f"classes: unknown labels {bad}; the order-{order} atlas has "
                f"{found[0].label}..{found[-1].label}"
            )
        found = [known[c] for c in classes]
    sampled = [_sample(order, ds, da, rng, i) for i in range(samples)]
    jobs = []
    for c in found:
        masks = tuple(p.mask for p in c.representatives)
        spec = (c.label, order, masks, c.delays, c.n_neurons, c.n_synapses, c.universal)
        jobs.append((spec, ds, da, sampled, timeout, own))
    pool = open_pool(workers, scheduler)
    try:
        rows = []
        for row in pool.map(_row, jobs):
            rows.append(row)
            step(row.label)
    finally:
        pool.close()
    rank = {c.label: i for i, c in enumerate(found)}
    rows.sort(key=lambda r: rank[r.label])
    return DaleTable(order, ds, da, samples, tuple(rows), time.perf_counter() - t0, label)
