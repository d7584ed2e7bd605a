r"""The sections of the derivation that depend on the plant, told with the model's names and units."""

from __future__ import annotations

import re

import numpy as np
import sympy as sp

from symctl import latex as L
from symctl.model.presets import muscle
from symctl.realization.draws import EPS_GRID as _EPS_GRID  # the grid of the random section poles
from symctl.realization.draws import EPS_MAX as _EPS_MAX
from symctl.report import shorthand as SH
from symctl.report.document import DocumentBlock, Heading, Table, Text
from symctl.report.reference import cite
from symctl.report.spec import PAPER

__all__ = ["counted", "longest", "names_tex", "nonlinear", "opening", "skipped", "theorem"]


def unit_text(unit: str, value: float | None = None) -> str:
    r"""A unit for prose and tables (``m/s**2`` as ``m/s$^{2}$``), singular after the ``value`` 1."""
    if not unit or unit == "1":
        return ""
    if value == 1:
        unit = re.sub(r"^([A-Za-z]{3,})s(?=$|[/*\s])", r"\1", unit)
    text = re.sub(r"\*\*\s*\(?(-?[0-9./]+)\)?", r"$^{\1}$", unit).replace("*", " ")
    return " " + text.replace("_", r"\_")


def counted(n: int, word: str) -> str:
    """``1 step``, ``2 steps``, ``0 steps``."""
    return f"{n} {word}{'' if n == 1 else 's'}"


def _sym(name: str) -> str:
    return L.to_latex(sp.Symbol(name))


def names_tex(names) -> str:
    r"""Signal names as inline math, joined by commas: ``$f$``, ``$\theta$, $f_\text{flex}$``."""
    return ", ".join(f"${_sym(n)}$" for n in names)


def _is_paper(spec) -> bool:
    """Whether the model is the paper's muscle (the preset's equations; its numbers may differ)."""
    preset = muscle()
    return (
        spec.name == preset.name
        and spec.ode is not None
        and preset.ode is not None
        and spec.ode.rhs == preset.ode.rhs
        and spec.ode.x_eq == preset.ode.x_eq
    )


_PAPER_SECTION = cite("Sec.", "simulations")


def _source(paper: bool, name: str, value) -> str:
    """Where a number comes from: the paper (its section), a change of the paper's, the file."""
    if not paper:
        return "model file"
    given = getattr(PAPER, name)
    if value == given:
        return _PAPER_SECTION
    return f"this run ({cite()}: {given:g})"


def _parameter_rows(res, paper: bool) -> list[tuple[str, str, str]]:
    """The parameter table: what the derivation starts from, its value, where it comes from."""
    spec, params = res.spec, res.parameters()
    rows = []
    if spec.ode is not None:
        for sym, value in spec.ode.params.items():
            what = spec.descriptions.get(sym.name) or "parameter"
            v = float(value)
            rows.append(
                (
                    f"{what} ${_sym(sym.name)}$",
                    f"{v:g}{unit_text(spec.unit(sym.name), v)}",
                    _source(paper and hasattr(PAPER, sym.name), sym.name, v),
                )
            )
    ds, da = params["sensor_delay"], params["actuator_delay"]
    delays = (
        counted(ds, "step") + " each"
        if ds == da
        else f"{counted(ds, 'step')} and {counted(da, 'step')}"
    )
    if not paper:
        delay_source = "model file"
    elif (ds, da) == (PAPER.sensor_delay, PAPER.actuator_delay):
        delay_source = cite("Secs.", "optimal_delayed_controller", "simulations")
    else:
        delay_source = f"this run ({cite()}: {PAPER.sensor_delay} and {PAPER.actuator_delay})"

    def ours(paper_says: str, otherwise: str = "symctl") -> str:
        return f"ours ({cite()}{paper_says})" if paper else otherwise

    states, amplitude, start, length = spec.disturbance
    hit = names_tex([res.names[0][i] for i in states])
    unit = unit_text(spec.unit(res.names[0][states[0]]), amplitude)
    rows += [
        ("sampling time $T_s$", f"{params['Ts']:g} s", _source(paper, "Ts", params["Ts"])),
        ("sensor delay $d_s$, actuator delay $d_a$", delays, delay_source),
        (
            "cost weights $Q$, $R$",
            f"${_weight(res.system.Q_plant)}$, ${_weight(res.system.R)}$",
            ours(" states none", "model file"),
        ),
        (
            "pulse disturbance on " + hit,
            f"{amplitude:g}{unit} per step, steps {start} to {start + length - 1} of {spec.steps}",
            ours(": a unit pulse", "model file"),
        ),
    ]
    if getattr(res, "factors", None) is not None:
        lo, hi = -_EPS_MAX / _EPS_GRID, _EPS_MAX / _EPS_GRID
        rows += [
            (
                "section gains $C$ of $G_1$, $G_3$ in the simulations",
                "1",
                ours(": any $C \\ne 0$"),
            ),
            (
                "section poles $\\epsilon$ of the random realizations",
                f"uniform on $[{lo:g}, {hi:g}]$, step ${1 / _EPS_GRID:g}$",
                ours(": random"),
            ),
            (
                "$P$ of the random general realization",
                "entries $N(0, 1)$ to 0.01, well conditioned",
                ours(": random, full rank"),
            ),
            (
                "random realizations per circuit, their seed",
                f"{spec.realizations}, seed {params['seed']}",
                ours(" shows 4, 3, 2", "model file"),
            ),
        ]
    return rows


def opening(res, figure) -> list[DocumentBlock]:
    """The parameter table and the plant's sections; ``figure(name, caption)`` gives a figure's blocks."""
    spec = res.spec
    ode = spec.ode
    paper = _is_paper(spec)
    where = f" ({spec.path})" if spec.path and not spec.path.startswith("muscle preset") else ""
    model = (
        f"the paper's muscle {cite('Sec.', 'problem_setup')}"
        if paper
        else f"the model {spec.name!r}{where}"
    )
    sources = (
        "the paper's numbers are those of its Sec. VI; it states no cost weights and draws its "
        "realizations at random without saying how, so those numbers are ours"
        if paper
        else "the model file gives the plant, the delays and the cost; the random "
        "realizations are drawn by symctl"
    )
    blocks: list[DocumentBlock] = [
        Text(
            f"This document carries out {'the derivation' if paper else 'the method'} of "
            f"{cite()} step by step on {model}. "
            "Every formula below was derived by symctl in closed form (SymPy) and, where stated, "
            "proved: an identity is shown by reducing a difference to the zero polynomial. "
            "Numbers are written to 6 significant digits. Table [#tab:parameters] lists the "
            f"numbers the derivation starts from and where each comes from: {sources}."
        ),
        Table(
            ("parameter", "value", "source"),
            tuple(_parameter_rows(res, paper)),
            caption="The numbers the derivation starts from.",
            label="parameters",
        ),
    ]
    for note in spec.notes:
        blocks.append(Text("Note: " + note.replace("_", r"\_") + "."))
    blocks.append(Heading("Plant model and linearization"))
    if spec.description:
        blocks.append(Text(spec.description))
    if paper:
        which = cite("Sec.", "problem_setup")
        blocks.append(
            Text(
                f"It is the model of {cite('Eq.', 'muscle')}, with the activation "
                f"parameters $D_0 = 0$, $D_1 = 1$ of {which}."
            )
        )
    xs, us = res.names
    signals = tuple(
        (
            f"{kind} ${_sym(n)}$",
            spec.descriptions.get(n) or "-",
            unit_text(spec.unit(n)).strip() or "-",
        )
        for kind, names in (("state", xs), ("input", us))
        for n in names
    )
    blocks.append(Table(("signal", "what it is", "unit"), signals))
    if ode is not None:
        rows = [
            (rf"\frac{{d{_sym(x.name)}}}{{dt}}", f)
            for x, f in zip(ode.states, ode.rhs, strict=True)
        ]
        values = ode.values
        for x, e, v in zip(ode.states, ode.x_eq, ode.x_bar, strict=True):
            shown = SH.both(e, float(v)) if e.free_symbols else L.number(float(v))
            rows.append((rf"\bar {_sym(x.name)}", shown + _unit_tex(spec.unit(x.name))))
        blocks += SH.eq(*rows, label=f"eq:{spec.name}")
        how = ode.equilibrium_method
        blocks.append(
            Text(
                f"The equilibrium: {'given in the model file and checked' if how == 'given' else how}. "
                "Linearized there, with $\\delta$ the deviations from it, "
                "$\\dot{\\delta x} = a\\,\\delta x + b\\,\\delta u$:"
            )
        )
        lin = ode.linearize_symbolic()
        if lin.a.shape == (1, 1) and lin.b.shape == (1, 1):
            rows = [
                ("a", SH.both(lin.a[0, 0], SH.num(lin.a[0, 0].subs(values)))),
                ("b", SH.both(lin.b[0, 0], SH.num(lin.b[0, 0].subs(values)))),
            ]
        else:
            rows = [
                ("a", lin.a),
                ("b", lin.b),
                ("a", SH.num(lin.a.subs(values))),
                ("b", SH.num(lin.b.subs(values))),
            ]
        blocks += SH.eq(*rows, label="eq:linear")
    else:
        blocks.append(Text("The model file gives the discrete plant directly."))
    sym, num = res.plant_symbolic, res.plant
    blocks.append(Heading("Discretization"))
    if ode is not None:
        blocks.append(
            Text(
                "A zero-order hold over the sampling time $T_s$ (the exact matrix exponential) gives "
                "$\\delta x(t+1) = A\\,\\delta x(t) + B\\,\\delta u(t)$ "
                f"(the form of {cite('Eq.', 'system')}) with"
                + (
                    ""
                    if sym is not None
                    else " (in numbers: beyond one state the closed form of "
                    "$e^{a T_s}$ is not printed)"
                )
            )
        )
    if sym is not None:
        rows = [
            ("A", SH.both(sym.A[0, 0], SH.num(num.A[0, 0]))),
            ("B", SH.both(sym.B[0, 0], SH.num(num.B[0, 0]))),
        ]
    else:
        rows = [("A", SH.num(num.A)), ("B", SH.num(num.B))]
    blocks += SH.eq(*rows, label="eq:discrete")
    blocks.append(
        Text(
            f"States ${', '.join(_sym('delta_' + x) for x in xs)}$, inputs "
            f"${', '.join(_sym('delta_' + u) for u in us)}$."
        )
    )
    blocks += figure(
        "open_loop",
        f"Open-loop response of the linear plant to a unit pulse in {names_tex(us)} "
        f"(as in {cite('Fig.', 'ol_sims')} for the muscle).",
    )
    return blocks


def _weight(M) -> str:
    """A cost weight: a number when 1 x 1, ``I`` or ``diag(...)`` when diagonal, else the matrix."""
    W = SH.num(M)
    if W.shape == (1, 1):
        return L.number(float(W[0, 0]))
    if np.array_equal(W, np.diag(np.diag(W))):
        d = np.diag(W)
        return "I" if np.all(d == 1) else rf"\operatorname{{diag}}({', '.join(map(L.number, d))})"
    return L.to_latex(W)


def _unit_tex(unit: str) -> str:
    return rf"\ \text{{{unit_text(unit).strip()}}}" if unit and unit != "1" else ""


def theorem(res) -> list[DocumentBlock]:
    """The exact verdict on the delay graph (Theorems 1 and 2 of symctl.compatibility.controller)."""
    verdict = getattr(res, "pathways", None)
    if verdict is None:
        return []
    names = res.spec.vertices if res.spec is not None and res.spec.vertices else None

    def vertex(v: int) -> str:
        if names and names[v - 1] != f"v{v}":
            return names[v - 1].replace("_", r"\_")
        return f"$v_{{{v}}}$"

    mimo = verdict.method.startswith("theorem 3")
    head = "For every realization at once (a theorem, not a search): some structure of the " + (
        "MIMO controller is compatible with this delay graph if and only if every nonzero "
        "entry $G_{ij}$ has relative degree at least the delay of the fastest path from "
        "input $j$'s sensor vertex to output $i$'s actuator vertex (Theorem 3 of "
        "symctl.compatibility.controller, proved there)."
        if mimo
        else "controller is compatible with this delay graph if and only if the relative degree "
        "of $G$ reaches the delay of the fastest path from the sensor to the actuator (Theorem "
        "1 of symctl.compatibility.controller, proved there; a wire may carry an axon of "
        "several steps)."
    )
    if not verdict.ok:
        return [Text(head + " Here: " + verdict.reason.split(";")[0] + ".")]
    parts = verdict.parts
    rows = tuple(
        (
            part.label if mimo else str(k + 1),
            r" $\to$ ".join(vertex(v) for v in part.path),
            ", ".join(map(str, part.delays)),
            str(part.delay),
        )
        for k, part in enumerate(parts)
    )
    if mimo and len(parts) > 1:
        what = "each entry as $G_3 G_2 G_1$ along its own path"
    elif mimo:
        what = (
            "$G_3 G_2 G_1$ along the one path from the sensors' vertex to the actuators', "
            "one section per channel and edge, one $G_2$ shared by every entry"
        )
    elif len(parts) > 1:
        what = (
            "$G$ split by its Markov parameters into one part per pathway (Theorem 2), each "
            "part factored as $G_3 G_2 G_1$ along its own path, the parts summed at the actuator"
        )
    else:
        what = "$G_3 G_2 G_1$ with one section per edge along the path"
    if "pathways" in res.circuits:
        proof = res.circuits["pathways"].realizes
        text = (
            f"Here it holds, and symctl built such a structure, {what}: the circuit 'pathways' "
            f"below, simulated, and {'proved' if proof.ok else 'NOT proved'} to realize $G$ "
            f"({proof.method}, with the optimal gains, for every section pole):"
        )
    else:
        text = f"Here it holds: such a structure exists, {what} (the proof's construction):"
    blocks = [
        Text(head + " " + text),
        Table(
            ("entry", "path", "edge delays [steps]", "delay")
            if mimo
            else ("part", "path", "edge delays [steps]", "Markov parameters from"),
            rows,
        ),
    ]
    if "pathways" not in res.circuits:
        blocks.append(Text(f"It is not among the circuits below: {_not_built(res)}."))
    return blocks


def _not_built(res) -> str:
    """Why the circuit 'pathways' of a compatible controller was not built."""
    fit = [f"'{k}'" for k, c in res.circuits.items() if c.compatibility.ok]
    if res.plant.n == 1 and res.plant.m == 1:
        return "on a chain of unit steps symctl builds its circuits from the factorization above"
    if fit:
        many = len(fit) > 1
        return f"the circuit{'s' * many} {', '.join(fit)} fit{'s' * (not many)} the graph already"
    return (
        "$G$ has a pole on or outside the unit circle, and the construction would copy it into "
        "every entry, a hidden unstable mode of the circuit"
    )


def skipped(res) -> list[DocumentBlock]:
    """What did not run, and why (a plant with more than one state or input)."""
    return [Heading("Beyond the controller"), Text("Not derived here: " + res.skipped + ".")]


def nonlinear(res, figure) -> list[DocumentBlock]:
    """The linear controller around the nonlinear plant: deviations against amplitude."""
    nl = res.nonlinear
    if nl is None:
        return []
    xs = res.names[0]
    unit = res.spec.unit(xs[0])
    u = f" [{unit}]" if unit else ""
    hit = {res.spec.unit(xs[i]) for i in res.spec.disturbance[0]}
    a_unit = f" [{hit.pop()}]" if len(hit) == 1 and "" not in hit else ""
    blocks: list[DocumentBlock] = [
        Heading("The nonlinear plant", 2),
        Text(
            "The linear controller closed around the nonlinear plant (integrated between "
            "samples, the inputs held over each step): how far the states depart from the linear "
            "prediction as the disturbance grows. A run that leaves the region where the ODE "
            "can be integrated is marked inf."
        ),
        Table(
            (
                f"pulse amplitude{a_unit}",
                f"max. deviation of {names_tex(xs[:1])}{u}",
                "relative",
                "final / peak",
            ),
            tuple(
                tuple(map(SH.fmt, row))
                for row in np.column_stack(
                    [nl.amplitudes, nl.max_deviation, nl.relative_deviation, nl.final_deviation]
                )
            ),
        ),
    ]
    return blocks + figure("nonlinear", "The linear controller around the nonlinear plant.")


def longest(res) -> list[DocumentBlock]:
    """The longest net delay for which the nonlinear loop still comes back."""
    L_ = res.longest
    if L_ is None:
        return []
    found = (
        f"the longest net delay for which the optimal controller still stabilizes the "
        f"nonlinear plant is $T = {L_.longest}$ steps ({L_.longest * res.spec.dt:g} s)"
        if L_.longest is not None
        else "not even one step of delay is stabilized"
    )
    if not L_.limited:
        found = f"every net delay up to {L_.delays[-1]} steps (the largest tried) is stabilized"
    rows = tuple(
        (str(T), SH.fmt(d) if np.isfinite(d) else "inf", "yes" if ok else "no")
        for T, d, ok in zip(L_.delays, L_.final_deviation, L_.stabilized, strict=True)
    )
    return [
        Heading("The longest delay", 2),
        Text(
            "For each net delay $T$ the optimal controller of the linear plant is closed around "
            "the nonlinear ODE under the same disturbance; the loop counts as stabilized when the "
            f"state ends within {L_.tolerance:g} of the linear loop's peak from the equilibrium. "
            f"Found: {found}."
        ),
        Table(("T [steps]", "final deviation / peak", "stabilized"), rows),
    ]
