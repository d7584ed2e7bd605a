r"""The pipeline: a model derived, plant to circuits, into one :class:`~symctl.derivation.Derivation`.

:func:`derive` runs the stages in order (plant -> delays -> LQR -> :math:`G(z)`
-> factors -> realizations -> delay graph and compatibility -> circuits ->
simulations -> closed loop -> nonlinear plant -> atlas) on a model, once per model: what
the circuits' figures need first, so that they can be drawn while the rest runs.

Examples
--------
>>> from symctl import derive_paper
>>> res = derive_paper()
>>> round(res.to_dict()["plant"]["f_bar"], 4)
43.8635
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable

import numpy as np
import sympy as sp

from symctl._util.deprecate import renamed_keywords
from symctl._util.validate import (
    MAX_CIRCUITS,
    MAX_DELAY,
    PAPER_MAX_DELAY,
    bounded_int,
    callable_or_none,
    nonneg_int,
    psd_matrix,
    to_matrix,
)
from symctl.circuitatlas.atlas import atlas
from symctl.circuitatlas.candidates import circuits_for
from symctl.compatibility.check import check_compatibility
from symctl.compatibility.controller import controller_compatibility
from symctl.compatibility.structure import Structure, ifp_structure
from symctl.derivation.derivation import CircuitRecord, Derivation, RealizationRecord
from symctl.derivation.paper import PAPER
from symctl.design.augment import augment
from symctl.design.controller import controller_tf, prove_controller_tf
from symctl.design.kalman import kalman_gains, lqg_tf, prove_lqg_tf
from symctl.design.lqr import lqr_gains
from symctl.design.plant import MuscleModel
from symctl.errors import NotRealizableError, NotStabilizableError, ParameterError
from symctl.model.modelfile import Model, load_model
from symctl.model.presets import muscle
from symctl.neural.circuit import Circuit
from symctl.neural.compensator import lqg_realization
from symctl.neural.firing import circuit_firing, structure_firing
from symctl.neural.montecarlo import monte_carlo
from symctl.neural.noise import Noise
from symctl.neural.nonlinear import longest_delay, nonlinear_check
from symctl.neural.simulate import closed_loop_response, open_loop_response
from symctl.realization.check import check_realization
from symctl.realization.draws import Draw, draw_realizations
from symctl.realization.factorization import EXPANDED_ZEROS_MAX as EXPANDED_ZEROS_MAX
from symctl.realization.factorization import Factorization, factor
from symctl.realization.realization import Realization
from symctl.realization.realizers import REALIZERS
from symctl.realization.reduction import controller_reduction

__all__ = ["derive", "derive_paper"]


SYMBOLIC_P_MAX_ORDER = 3  # order up to which the general realization keeps a symbolic P
MIMO_EXACT_MAX_ORDER = 12  # symbolic states checked exactly (beyond: randomized; 8 s at T = 20)
MIMO_MAX_ORDER = 48  # states of the largest MIMO block realization whose circuits are built
MIMO_GENERAL_MAX_ORDER = 16  # likewise, for the dense general realization
PAPER_ATLAS_MAX_ORDER = 2  # largest G2 order whose atlas circuits are listed


@renamed_keywords(Ts="dt", seed="rng")
def derive_paper(
    tau: float = PAPER.tau,
    f_max: float = PAPER.f_max,
    r_bar: float = PAPER.r_bar,
    dt: float = PAPER.Ts,
    sensor_delay: int = PAPER.sensor_delay,
    actuator_delay: int = PAPER.actuator_delay,
    Q=None,
    R=None,
    rng: int = PAPER.seed,
    realizations: int = PAPER.realizations,
    progress: Callable[[str], None] | None = None,
    early: Callable[[Derivation], None] | None = None,
) -> Derivation:
    r"""Run the paper's whole derivation on its muscle: ``derive(muscle().replace(**values))``
    (``examples/muscle.toml``), every value defaulting to the paper's.

    Parameters
    ----------
    tau, f_max, r_bar, dt : float
        The muscle's time constant [s], maximum force [N], equilibrium firing rate
        [spikes/s] and the sampling time [s] (``Ts=``: deprecated).
    sensor_delay, actuator_delay : int
        Delays in steps (>= 0), a net delay from 1 to
        :data:`~symctl._util.validate.PAPER_MAX_DELAY` (20).
    Q, R : matrix-like, optional
        State and input penalties of the cost (identity by default).
    rng : int
        Seed (>= 0) of the random realizations, recorded as ``seed`` (``seed=``: deprecated).
    realizations : int
        Random realizations simulated per circuit, from 1 to
        :data:`~symctl._util.validate.MAX_CIRCUITS` (1000).
    progress : callable, optional
        Called with the name of each step (``"plant"``, ``"delays"``, ...) before it runs.
    early : callable, optional
        As :func:`derive`'s: the derivation as far as the circuits' simulations.

    Returns
    -------
    Derivation

    Raises
    ------
    ParameterError
        A value out of range (``tau <= 0``, the delays, ``Q`` not positive semidefinite,
        ``dt/tau`` outside the muscle's admissible range, ...).
    SymctlTypeError
        ``rng``, a delay or ``realizations`` not an integer, ``progress`` not callable.
    DimensionError
        ``Q`` or ``R`` of the wrong shape.

    Examples
    --------
    >>> from symctl import derive, derive_paper
    >>> from symctl.model.presets import muscle
    >>> res = derive_paper()
    >>> res.G_symbolic.latex()
    '\\frac{K_{0}}{z^{2} - K_{1} z - K_{2}}'
    >>> [round(float(k), 6) for k in res.gains.K[0]]
    [-0.045972, -0.580041, -0.351813]
    >>> derive_paper(tau=0.05) is derive(muscle().replace(tau=0.05))  # one value, computed once
    True
    >>> derive_paper(sensor_delay=0, actuator_delay=0)
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: sensor_delay, actuator_delay: the derivation needs a net delay ...
    """
    step = callable_or_none(progress, "progress") or (lambda _name: None)
    step("plant")  # the values are checked in the step they belong to
    given = {
        "tau": tau,
        "f_max": f_max,
        "r_bar": r_bar,
        "dt": dt,
        "sensor_delay": sensor_delay,
        "actuator_delay": actuator_delay,
        "Q": Q,
        "R": R,
        "seed": rng,
        "realizations": realizations,
    }
    given = {k: v for k, v in given.items() if v is not None}
    _check_paper_values(given)
    model = muscle(**given)
    return derive(model, progress=lambda name: None if name == "plant" else step(name), early=early)


def _check_paper_values(given: dict) -> None:
    """The paper's values checked, with :func:`derive_paper`'s own messages."""
    if "seed" in given:
        nonneg_int(given["seed"], "rng")
    if "realizations" in given:
        bounded_int(given["realizations"], "realizations", 1, MAX_CIRCUITS)
    preset = muscle()
    delays = (
        nonneg_int(given.get("sensor_delay", preset.sensor_delay), "sensor_delay"),
        nonneg_int(given.get("actuator_delay", preset.actuator_delay), "actuator_delay"),
    )
    if sum(delays) > PAPER_MAX_DELAY:
        raise ParameterError(
            f"sensor_delay, actuator_delay: derive_paper handles a net delay of at most "
            f"{PAPER_MAX_DELAY} steps (the range its derivation and documents are measured on; "
            "the design "
            f"functions take up to {MAX_DELAY}), got {delays[0]} + {delays[1]} = {sum(delays)}"
        )
    if sum(delays) == 0:
        raise ParameterError(
            "sensor_delay, actuator_delay: the derivation needs a net delay "
            "T = sensor_delay + actuator_delay >= 1 (the delay graph and the IFP controller "
            "have T steps), got 0"
        )
    muscle_values = {k: given[k] for k in ("tau", "f_max", "r_bar", "dt") if k in given}
    if muscle_values:
        MuscleModel(**muscle_values)  # the muscle's admissible ranges, named
    for name, definite in (("Q", False), ("R", True)):
        if name in given:
            psd_matrix(to_matrix(given[name], name), name, 1, definite=definite)


def derive(
    model,
    *,
    progress: Callable[[str], None] | None = None,
    early: Callable[[Derivation], None] | None = None,
) -> Derivation:
    r"""Run the whole derivation on your own system: a model file, plant to circuits.

    A MIMO plant's controller is factored channel by channel and realized in block canonical
    forms (the IFP circuit and the atlas are SISO only: ``Derivation.skipped``); a controller
    that is not minimal is reduced right after :math:`G(z)` (``Derivation.reduction``). Equal
    models share one derivation (the ``DERIVATIONS_CACHED`` most recent;
    ``derive.cache_clear()`` empties the cache); ``progress`` is called only when computing.

    Parameters
    ----------
    model : Model, path or str
        A model, or a model file (path or TOML text) for :func:`~symctl.model.modelfile.load_model`.
    progress : callable, optional
        Called with the name of each step before it runs.
    early : callable, optional
        Called once with the derivation as far as the circuits' simulations, before the steps
        after them run (its ``closed_loop``, ``nonlinear``, ``longest``, ``variance``, ``atlas``
        and ``candidates`` still None), so that a caller can draw the circuits meanwhile; not
        called when the derivation comes from the cache.

    Returns
    -------
    Derivation

    Raises
    ------
    ModelFileError
        A bad model file, or a plant that the delays leave unstabilizable
        (naming the file and the field).

    Examples
    --------
    >>> from symctl import derive, derive_paper
    >>> from symctl.model.presets import muscle_text
    >>> a, b = derive(muscle_text()).to_dict(), derive_paper().to_dict()
    >>> a["model"]["file"].pop("path"), b["model"]["file"].pop("path")  # only the name differs
    ('<text>', 'muscle preset (examples/muscle.toml)')
    >>> a == b
    True
    """
    step = callable_or_none(progress, "progress") or (lambda _name: None)
    early = callable_or_none(early, "early")
    spec = model if isinstance(model, Model) else load_model(model)
    return _cached(spec, _Progress(step, early))


class _Progress:
    """The callbacks, kept out of the cache's key (every callback is the same key)."""

    def __init__(self, step: Callable[[str], None], early=None) -> None:
        self.step, self.early = step, early

    def __eq__(self, other) -> bool:
        return isinstance(other, _Progress)

    def __hash__(self) -> int:
        return 0


DERIVATIONS_CACHED = 8  # most derivations derive keeps (the most recently used)


@functools.lru_cache(maxsize=DERIVATIONS_CACHED)
def _cached(spec: Model, progress: _Progress) -> Derivation:
    return _derive(spec, progress.step, progress.early)


def _clear() -> None:
    """Empty :func:`derive`'s cache (a benchmark that times the computation itself)."""
    _cached.cache_clear()


derive.cache_clear = _clear


def _mimo_kinds(kinds: tuple, G, plant) -> tuple[tuple, str]:
    """The circuits a MIMO controller gets, and the sentence saying what is left out and why."""
    rows, cols = G.shape
    order = G.order * max(rows, cols)
    head = (
        f"the plant has {_count(plant.n, 'state')} and {_count(plant.m, 'input')}, so "
        f"G(z) is a {rows} x {cols} matrix"
    )
    if order > MIMO_MAX_ORDER:
        return (), (
            f"{head}, whose block realizations have up to {order} states: symctl builds the "
            f"circuits of a MIMO controller up to {MIMO_MAX_ORDER} states"
        )
    left = ["the IFP circuit and the circuit atlas (built for one state and one input)"]
    out = tuple(k for k in kinds if not REALIZERS[k].controller)
    if order > MIMO_GENERAL_MAX_ORDER and any(REALIZERS[k].takes_transform for k in out):
        out = tuple(k for k in out if not REALIZERS[k].takes_transform)
        left.append(
            f"the general realization (dense, {order} states; built up to {MIMO_GENERAL_MAX_ORDER})"
        )
    if G.order > MIMO_GENERAL_MAX_ORDER:
        left.append(
            f"the exact verdict on the delay graph and its circuit 'pathways' (G has order "
            f"{G.order}; built up to {MIMO_GENERAL_MAX_ORDER})"
        )
    *rest, last = left
    return out, f"{head}: left out are {', '.join(rest)}{' and ' if rest else ''}{last}"


def _count(k: int, noun: str) -> str:
    return f"{k} {noun}" + ("" if k == 1 else "s")


def _derive(spec: Model, step, early=None) -> Derivation:
    """The pipeline on ``spec``, stage by stage; ``early`` gets the derivation as far as the
    circuits' simulations."""
    ds, da = spec.sensor_delay, spec.actuator_delay
    seed, count = spec.seed, spec.realizations
    model = spec.ode
    step("plant")
    plant_symbolic, plant = spec.plant_symbolic, spec.plant
    step("delays")
    system = augment(plant, ds, da, Q=spec.Q, R=spec.R)
    step("LQR")
    try:
        gains = lqr_gains(system)
    except NotStabilizableError as exc:
        where = "discrete" if spec.ode is None else "states"
        raise spec.error(
            where, f"the plant cannot be stabilized with these delays: {exc}"
        ) from None
    kalman = noise = None
    if spec.C is not None:
        step("Kalman filter")
        kalman, noise = _kalman(spec, system)
    step("G(z)")
    if kalman is None:
        G_symbolic = controller_tf(system)
        proved = bool(prove_controller_tf(system, G_symbolic))
        reduction, gains = controller_reduction(system, gains)  # the minimal controller onwards
        G_symbolic = reduction.reduce(G_symbolic)
        G = G_symbolic.subs(gains.substitutions())
    else:  # the LQG compensator, K and L symbolic (with several inputs, their exact values)
        G_symbolic, reduction = lqg_tf(system, spec.C), None
        if plant.m == 1:
            proved = bool(prove_lqg_tf(system, spec.C, G_symbolic))
            G = G_symbolic.subs({**gains.substitutions(), **kalman.substitutions()})
        else:  # its symbolic fraction's expansion takes minutes
            exact = {**gains.substitutions(exact=True), **kalman.substitutions(exact=True)}
            G_symbolic = G = G_symbolic.subs(exact).expanded()
            proved = bool(prove_lqg_tf(system, spec.C, G, gains=gains, kalman=kalman))
            spec = dataclasses.replace(spec, notes=(*spec.notes, _EXACT_GAINS))
    w = spec.disturbance_signal()
    window = {"steps": spec.steps}
    graph = spec.graph
    kinds = spec.circuits
    skipped = None
    factors, records, circuits, found, candidates, G2_symbolic = None, {}, {}, None, None, None
    pathways = verified = None
    siso = plant.n == 1 and plant.m == 1 if kalman is None else G.is_siso
    if kalman is not None:
        kinds = tuple(k for k in kinds if not REALIZERS[k].controller)
        skipped = _estimating_skips(spec, G, siso)
    if not siso:
        kinds, mimo = _mimo_kinds(kinds, G, plant)
        skipped = mimo if skipped is None else f"{skipped}; {mimo}"
    if kinds:
        step("factorization")
        factors = factor(G_symbolic, ds, da)
        verified = factors.verify()
        step("realizations")
        G2_symbolic = factors.G2_symbolic
        names = [k for k in kinds if not REALIZERS[k].controller]
        # the realizations the circuits simulate, drawn from the seed (one stream per circuit)
        exact = gains.substitutions(exact=True)
        if kalman is not None:
            exact.update(kalman.substitutions(exact=True))
        G_exact = factors.G.subs(exact)
        draws = {k: draw_realizations(G_exact, ds, da, k, count, seed) for k in names}
        records = _realizations(factors, G2_symbolic, {k: draws[k][0] for k in names})
        step("compatibility")
        structures = {k: ifp_structure(system.T) for k in kinds if REALIZERS[k].controller}
        structures.update(
            {k: Structure.from_factorization(factors, records[k].symbolic) for k in names}
        )
        verdicts = {k: check_compatibility(S, graph) for k, S in structures.items()}
        G_path = G_symbolic if siso and kalman is None else G_exact
        pathways, realizes, left = _pathways(G_path, gains, spec, verdicts)
        skipped = f"{skipped}; left out is {left}" if left else skipped
        if realizes is not None:
            structures["pathways"], verdicts["pathways"] = pathways.structure, pathways.check
            kinds = (*kinds, "pathways")
        step("simulation")  # each circuit closed around the plant: the realizations drawn above
        if kalman is not None:  # the compensator's loop, with the model's noise
            window = {**window, "kalman": kalman, "noise": noise}
        firing = {
            k: circuit_firing(
                k,
                gains,
                count=1 if REALIZERS[k].controller else count,
                disturbance=w,
                draws=draws.get(k),
                **window,
            )
            for k in kinds
            if k != "pathways"
        }
        if "pathways" in kinds:
            step("pathways")
            firing["pathways"] = structure_firing(
                pathways.structure,
                gains,
                assignment=pathways.check,
                count=count,
                rng=seed,
                disturbance=w,
                **window,
            )
        circuits = {
            k: CircuitRecord(
                k,
                structures[k],
                verdicts[k],
                Circuit.from_structure(structures[k], verdicts[k] if verdicts[k].ok else None),
                firing[k],
                realizes if k == "pathways" else None,
            )
            for k in kinds
        }
    res = Derivation(
        model,
        plant_symbolic,
        plant,
        system,
        gains,
        G_symbolic,
        G,
        proved,
        seed,
        factors,
        records,
        graph,
        circuits,
        open_loop_response(plant, steps=spec.steps),
        None,
        None,
        G2_symbolic,
        spec=spec,
        skipped=skipped,
        pathways=pathways,
        verified=verified,
        reduction=reduction,
        kalman=kalman,
    )
    if early is not None:  # the circuits' figures can be drawn while the rest runs
        early(res)
    step("closed loop")
    amplitude = spec.disturbance[1]
    unit_w = w / amplitude if amplitude else w
    window = {"steps": spec.steps}
    variance = None
    if kalman is None:
        closed = closed_loop_response(gains, disturbance=w, **window)
    else:
        compensator = lqg_realization(gains, kalman)
        closed = closed_loop_response(
            compensator, plant, disturbance=w, outputs=kalman.C, noise=noise, rng=seed, **window
        )
        step("Monte Carlo")
        variance = monte_carlo(
            compensator,
            plant,
            noise=noise,
            outputs=kalman.C,
            count=MONTE_CARLO_LOOPS,
            Q=spec.Q,
            R=spec.R,
            rng=seed,
        )
    nonlinear = longest = None
    if spec.ode is not None:
        step("nonlinear")
        nonlinear = nonlinear_check(
            spec.ode,
            gains if kalman is None else _reading_states(compensator, kalman.C),
            amplitude * np.array([0.1, 0.3, 1.0, 3.0, 10.0]),
            steps=spec.steps,
            disturbance=unit_w,
            fail="mark",
        )
        if spec.longest_delay is not None and kalman is None:
            step("longest delay")
            top, tol = spec.longest_delay
            longest = longest_delay(
                spec.ode,
                Q=spec.Q,
                R=spec.R,
                disturbance=unit_w,
                amplitude=amplitude,
                max_delay=top,
                tolerance=tol,
                steps=spec.steps,
            )
    order2 = system.T if kalman is None else G.order  # G2's; the compensator's is n + T m
    if kinds and siso and (kalman is None or order2 <= PAPER_ATLAS_MAX_ORDER):
        step("atlas")
        found = atlas(2, workers=1)
        if order2 <= PAPER_ATLAS_MAX_ORDER:  # order 3 takes a minute: symctl atlas
            order = found if order2 == 2 else atlas(order2, workers=1)
            try:
                candidates = circuits_for(
                    G, graph, sensor_delay=ds, actuator_delay=da, atlas=order, rng=seed
                )
            except (NotRealizableError, ParameterError) as exc:  # e.g. a zero controller
                note = f"no atlas circuits for this controller: {exc}"
                spec = dataclasses.replace(spec, notes=(*spec.notes, note))
    return dataclasses.replace(
        res,
        closed_loop=closed,
        nonlinear=nonlinear,
        atlas=found,
        candidates=candidates,
        spec=spec,
        longest=longest,
        variance=variance,
    )


def _estimating_skips(spec: Model, G, siso: bool) -> str | None:
    """What an estimating model leaves out, and why."""
    out = ["the IFP circuit (it feeds back the full state)"] if siso else []
    if siso and G.order > PAPER_ATLAS_MAX_ORDER:
        out.append(
            f"the circuit atlas (the compensator's G2 has order n + Tm = {G.order}, the atlas "
            f"is searched here up to order {PAPER_ATLAS_MAX_ORDER})"
        )
    if spec.longest_delay is not None:
        out.append("the longest-delay search (it redesigns the full-state controller)")
    if not out:
        return None
    return "the controller estimates the state (the LQG compensator), so left out " + (
        f"{'is' if len(out) == 1 else 'are'} {', '.join(out[:-1])}{' and ' * (len(out) > 1)}"
        f"{out[-1]}"
    )


def _reading_states(compensator: Realization, C) -> Realization:
    """The compensator composed with ``y = C x``: a controller of the state (the nonlinear check)."""
    C = sp.Matrix(np.array(C.evalf(), dtype=float))
    F, H, M, N = compensator.F, compensator.H, compensator.M, compensator.N
    return Realization(F, H * C, M, N * C, compensator.dt)


_EXACT_GAINS = (
    "With several inputs the compensator's matrix fraction, expanded with K and L symbolic, "
    "takes minutes: G(z) is derived and proved with the gains' exact values (the binary "
    "floats' rationals) in Q[z] instead"
)

MONTE_CARLO_LOOPS = 4000  # noisy closed loops whose covariance is set beside the predicted one


def _kalman(spec: Model, system):
    """The model's Kalman filter and the :class:`Noise` it expects (errors name ``noise``)."""
    values = {k: np.array(v.evalf(), dtype=float) for k, v in spec.noise.items()}
    try:
        kalman = kalman_gains(
            system, spec.C, values.get("process"), values.get("sensor"), motor=values.get("motor")
        )
    except ParameterError as exc:
        raise spec.error("noise", str(exc)) from None
    return kalman, Noise(process=kalman.W, sensor=kalman.V)  # the motor noise is in W


def _pathways(G, gains, spec: Model, verdicts: dict):
    """The exact verdict on the delay graph (Theorems 1-3), the proof that its structure realizes
    ``G`` when its circuit is built (else None), and why a compatible one is not built."""
    if not G.is_siso and G.order > MIMO_GENERAL_MAX_ORDER:
        return None, None, None
    rows, cols = G.shape
    beyond = G.is_siso and _beyond_unit_chain(spec.graph)
    shared = len(spec.graph.sensors) == len(spec.graph.actuators) == 1  # one G2 for all entries
    verdict = controller_compatibility(
        G,
        spec.graph,
        base="observable" if shared and rows < cols else "controllable",  # the smaller block form
        construction="parallel" if beyond else "path",
        max_wire_delay=spec.max_wire_delay,
    )
    # a SISO controller's beyond a chain of unit steps, a MIMO one's when no other circuit fits
    if not verdict.ok or (not beyond if G.is_siso else any(v.ok for v in verdicts.values())):
        return verdict, None, None
    if len(verdict.parts) > 1 and not G.is_siso and max(abs(G.poles()), default=0) >= 1:
        return (
            verdict,
            None,
            (
                "the circuit 'pathways' (the theorem's construction, one copy of G's poles per "
                "entry: G has a pole on or outside the unit circle, so its copies would be hidden "
                "unstable modes of the circuit)"
            ),
        )
    values = gains.substitutions(exact=True)  # the symbols left are the sections': seconds
    return verdict, check_realization(verdict.realization.subs(values), G.subs(values)), None


def _beyond_unit_chain(graph) -> bool:
    """Whether the delay graph has parallel pathways or a step of several delays."""
    steps = graph.chain_delays
    return steps is None or max(steps) > 1


def _realizations(
    factors: Factorization, G2_symbolic, first: dict[str, Draw]
) -> dict[str, RealizationRecord]:
    """The realizations of G2: symbolic ones of ``G2_symbolic``, numeric ones the first drawn."""
    sections = (*factors.sensor_C, *factors.actuator_C)
    unit_C = {c: 1 for c in sections}
    out = {}
    for name in sorted(first, key=lambda k: not REALIZERS[k].canonical):  # the bases first
        draw = first[name]
        eps = {k: draw.values[k] for k in factors.poles}
        G2_num = draw.factors.G2
        realizer = REALIZERS[name]
        symbolic_options = {}
        numeric = draw.result
        if realizer.takes_transform:
            P_num = numeric.P
            n = P_num.shape[0]
            if n <= SYMBOLIC_P_MAX_ORDER:
                P = sp.Matrix(n, n, sp.symbols(f"p_1:{n + 1}(1:{n + 1})"))
            else:  # a fully symbolic P costs minutes beyond order 3: use the drawn one
                P = P_num
            symbolic_options = {"P": P}
        symbolic = realizer(G2_symbolic, **symbolic_options)
        out[name] = RealizationRecord(
            name,
            symbolic.realization,
            numeric.realization,
            {**{str(k): v for k, v in eps.items()}, **{str(k): 1 for k in unit_C}},
            _check(symbolic, G2_symbolic, realizer.takes_transform),
            _check(numeric, G2_num, realizer.takes_transform),
            symbolic.P if realizer.takes_transform else None,
            numeric.P if realizer.takes_transform else None,
        )
    return out


def _check(result, G2, transformed: bool):
    """The check of a realizer's result (a transformed one through its base)."""
    R = result.realization
    big = R.n > MIMO_EXACT_MAX_ORDER and bool(R.free_symbols)
    method = "auto" if big else "exact"
    if transformed:  # P F = F0 P, ...: multiplies, never raises a dense F to powers
        return check_realization(R, G2, method, similar_to=(result.base, result.P))
    return check_realization(R, G2, method)
