r"""The paper's derivation told as a document: :func:`story` turns results into blocks."""

from __future__ import annotations

import re
from collections.abc import Iterable

import numpy as np
import sympy as sp

from symctl import latex as L
from symctl._util.display import descending_latex
from symctl._util.texnames import signal_tex
from symctl.realization.factorization import remainder
from symctl.realization.realizers import REALIZERS
from symctl.report import longform as LF
from symctl.report import matrixview as MV
from symctl.report import mimo_story as MIMO
from symctl.report import model_story as MS
from symctl.report import shorthand as SH
from symctl.report.document import (
    DocumentBlock,
    Graphic,
    Heading,
    References,
    Table,
    Text,
    Verbatim,
)
from symctl.report.estimation import estimation_section
from symctl.report.reference import REFERENCES, cite
from symctl.report.shorthand import COMPACT_LENGTH as COMPACT_LENGTH  # still importable here
from symctl.report.spec import circuit_specs

__all__ = ["POLE_ZERO_TOL", "story"]


_GRAPH_CAPTION = (
    "The delay graph: the sensor (green) on the left, the actuator (orange) on the right, each "
    f"direct edge with its delay in steps (as in {cite('Fig.', 'muscle_system')}, right)."
)


_G1G3_CAPTION = (
    f"Two structures of one first-order section of $G_1$ or $G_3$ (as in {cite('Fig.', 'g1g3')}, "
    "left): "
    "a unit delay on each branch into the adder, the one symctl builds, puts the section's input "
    "and gain at one vertex and its state at the next; one delay after the adder cannot, since "
    "the state feeds the adder without delay."
)


_CIRCUIT_COLUMNS = ("circuit", "neurons", "of them in $G_2$", "synapses", "compatible")
_CIRCUIT_COLUMNS += ("realizations", "max. deviation")
_DIAGRAMS = {"general": "full_diagram", "controllable": "ccr_diagram", "observable": "ocr_diagram"}
_PAPER_STRUCTURE = {"ifp": f" (as in {cite('Fig.', 'ifp_diagram')})"} | {
    k: f" (as in {cite('Fig.', d)}, left, with $G_1$ and $G_3$)" for k, d in _DIAGRAMS.items()
}
_PAPER_CIRCUIT = {k: f" (as in {cite('Fig.', d)}, right)" for k, d in _DIAGRAMS.items()}
_PAPER_FIRING = {k: f" (as in {cite('Fig.', d)})" for k, d in _DIAGRAMS.items()}


# the two readings of the delay assignment matrix, and why the verdicts agree
_READINGS = Text(
    f"Two readings of $\\tilde E$. The paper defines $\\tilde E_{{ij}}$ as the delay along "
    f"the fastest path from a signal at vertex $i$ to a signal at vertex $j$ "
    f"{cite('Def.', 'delay_assignment_matrix')}. Read by its words, a path may pass "
    "through signals at any vertex: this is the matrix $\\tilde E$ shown below. The "
    f"matrix the paper prints for its $G_3 G_2 G_1$ {cite('Eq.', 'E_tilde')} counts only "
    "the paths whose signals all sit at $v_i$ or $v_j$; it has $\\tilde E_{13} = \\infty$ "
    "although a path of delay 2 runs from $v_1$ through $v_2$ to $v_3$. This direct "
    "reading is shown as $\\tilde E^{\\mathrm{d}}$ where it differs. The fastest reading is "
    "entrywise at most the direct one, and $E$ holds the shortest delays of the graph "
    "(it obeys the triangle inequality), so an assignment meets $\\tilde E \\ge E$ in one "
    "reading exactly when it meets it in the other (proved in "
    "symctl.compatibility.assignment): the verdicts below hold in both."
)


def _e_tilde(E, assignment, name: str) -> list[DocumentBlock]:
    """The witness assignment's delay matrix in both readings (one row when they agree)."""
    fast, direct = assignment.e_tilde("fastest"), assignment.e_tilde("direct")
    big = not MV.show_matrix("E", E).full
    rows = [(r"\tilde E", "E" if big and np.array_equal(fast, E) else fast)]
    if not np.array_equal(direct, fast):
        rows.append((r"\tilde E^{\mathrm{d}}", direct))
    return SH.eq(*rows, label=f"eq:Etilde-{name}")


def _ascii(text: str) -> str:
    return text.replace("Ẽ", "E~").replace("→", "->").replace("≤", "<=").replace("≥", ">=")


def story(res, figures: Iterable[str] = ()) -> list[DocumentBlock]:
    r"""The derivation ``res`` as document blocks, in the paper's order, with a
    :class:`~symctl.report.document.Graphic` for each of the ``figures`` written beside it.
    """
    shown = set(figures)
    blocks: list[DocumentBlock] = []
    add, put = blocks.append, blocks.extend

    def figure(name: str, caption: str) -> list[DocumentBlock]:
        return [Graphic(name, caption)] if name in shown else []

    def say(text: str) -> None:
        add(Text(text))

    def show(name: str, caption: str) -> None:
        put(figure(name, caption))

    def display(*rows, label: str) -> None:
        put(SH.eq(*rows, label=label))

    def see(name: str) -> str:
        """`` (Fig. n)`` for a figure of the document, nothing for one not written."""
        return f" (Fig. [#fig:{name}])" if name in shown else ""

    s, g, f = res.system, res.gains, res.factors
    put(MS.opening(res, figure))
    xs = res.names[0]
    x0, u0 = MS.names_tex(xs[:1]), MS.names_tex(res.names[1][:1])  # the signals the figures plot

    # 3. delays
    add(Heading("Delays and the augmented system"))
    say(
        f"The sensor delays the measured {MS.names_tex(xs)} by $d_s = {s.sensor_delay}$ "
        f"step{'s' * (s.sensor_delay != 1)} and the actuator "
        f"the command $\\mu$ by $d_a = {s.actuator_delay}$ step{'s' * (s.actuator_delay != 1)}; "
        f"only the net delay $T = d_s + d_a = {s.T}$ enters the optimal control problem "
        f"{cite('Sec.', 'optimal_delayed_controller')}. The delayed commands become states: "
        "the augmented state $\\chi$ evolves as "
        "$\\chi(t+1) = \\tilde A \\chi(t) + \\tilde B \\mu(t)$, and the cost is "
        "$\\sum_t \\chi(t)^\\top \\tilde Q \\chi(t)$ (no penalty on $\\mu$ itself; for $T = 2$ these "
        f"are {cite('Eqs.', 'augmented_states', 'augmented_system', 'augmented_cost')}):"
    )
    display(
        (r"\chi", s.chi),
        (r"\tilde A", SH.num(s.A)),
        (r"\tilde B", SH.num(s.B)),
        (r"\tilde Q", SH.num(s.Q)),
        label="eq:augmented",
    )

    # 4. gains
    add(Heading("Optimal gains"))
    say(
        "The discrete algebraic Riccati equation gives the optimal feedback "
        f"$\\mu(t) = K \\chi(t)$ (the paper's sign, {cite('Eq.', 'ifp_controller')}), "
        f"$K = [K_0, \\dots, K_{{{s.T}}}]$, and the closed loop's poles (those below "
        f"${L.number(POLE_ZERO_TOL)}$ in magnitude written as 0: a multiple pole at 0 splits by the "
        "square root of the rounding error in floating point):"
    )
    poles = ", ".join(_pole(p) for p in g.poles)
    display(
        ("K", np.asarray(g.K, dtype=float)),
        (r"\operatorname{eig}(\tilde A + \tilde B K)", rf"\{{{poles}\}}"),
        (r"\rho", SH.num(g.spectral_radius)),
        label="eq:gains",
    )

    # 5. controller
    G_num = res.G
    add(Heading("The controller $G(z)$"))
    say(
        "Eliminating the delayed commands, the controller from the measured states to the "
        "inputs is a transfer function of the gains, kept symbolic (for $T = 2$ the paper's "
        f"{cite('Eq.', 'transfer_fn')}):"
    )
    whole = SH.both(res.G_symbolic, G_num.expr.evalf(6))
    long_G = not SH.fits("G(z)", whole)
    put(
        SH.tf_long("G(z)", res.G_symbolic, G_num, label="eq:G")
        if long_G
        else SH.eq(("G(z)", whole), label="eq:G")
    )
    say(
        "Proved: "
        + ("yes" if res.proved else "NO")
        + " (the derivation of $G$ checked against the controller's state-space matrices "
        "read off $\\tilde A$ and $\\tilde B$, as a polynomial identity). Relative degree "
        f"{G_num.relative_degree}."
    )
    put(MIMO.reduction(res))
    put(estimation_section(res))
    hit = MS.names_tex([xs[i] for i in res.spec.disturbance[0]])
    like = cite("Fig.", "cl_sims")
    show(
        "closed_loop",
        f"Closed loop of the {'LQG compensator' if res.kalman else 'optimal delayed controller'}"
        f": response to a unit pulse disturbance on {hit} (as in {like})"
        + (
            ", the mean of the noisy runs in a band of 2 standard deviations."
            if res.kalman
            else "."
        ),
    )
    if f is None:
        put(MS.skipped(res))
        show("delay_graph", _GRAPH_CAPTION)
        put(MS.nonlinear(res, figure))
        put(MS.longest(res))
        add(References(REFERENCES))
        return blocks

    names: dict[str, dict[str, str]] = {}  # LaTeX of long weights -> N c_k, per circuit
    if not f.is_siso:  # per-channel sections and block forms
        put(MIMO.factorization(res))
        put(MIMO.realizations(res))
    else:
        # 6. factorization
        add(Heading("Factorization $G = G_3 G_2 G_1$"))
        say(
            "To fit the delays, the sensor side $G_1$ and the actuator side $G_3$ take one "
            "first-order section $C/(z - \\epsilon)$ per delay step, and $G_2$ keeps the rest "
            f"(for $T = 2$ the paper's {cite('Eq.', 'factors')}, realized as in "
            f"{cite('Eq.', 'sections')}):"
        )
        den = descending_latex(f.G2.den)
        zeros = SH.zeros_tex((*f.sensor_eps, *f.actuator_eps))
        if not SH.fits("G_2(z)", zeros):
            zeros = " ".join(SH.zeros_tex(e, product=True) for e in (f.sensor_eps, f.actuator_eps))
        f_N, f_coeffs, sigma_rows = _remainder(res)
        c = SH.remainder_symbols(f_coeffs)
        remainder = descending_latex(SH.remainder_poly(c))
        named_den = []  # the row defining the denominator's name, where it is first used
        if not (
            SH.fits("G_2(z)", rf"N\,\frac{{{zeros}}}{{{den}}}")
            and SH.fits("G_2(z)", rf"N + N\,\frac{{{remainder}}}{{{den}}}")
        ):
            same = f.G2.den_coeffs() == res.G_symbolic.den_coeffs()
            named_den = [] if long_G and same else [("a(z)" if same else "d(z)", den)]
            den = "a(z)" if same else "d(z)"
        if not SH.fits("G_2(z)", rf"N + N\,\frac{{{remainder}}}{{{den}}}"):
            n = len(c)
            remainder = rf"\sum_{{k=1}}^{{{n}}} c_k\, z^{{{n}-k}}"
        G2_row, b_rows = ("G_2(z)", rf"N\,\frac{{{zeros}}}{{{den}}}"), []
        if res.kalman is not None:  # the compensator's numerator b(z) is a polynomial in z
            sections = " ".join(L.to_latex(x) for x in (*f.sensor_C, *f.actuator_C))
            G2_row = ("G_2(z)", rf"\frac{{b(z)}}{{{sections}}}\,\frac{{{zeros}}}{{{den}}}")
            b = descending_latex(res.G_symbolic.num)
            b_rows = [("b(z)", b if SH.fits("b(z)", b) else r"\text{the numerator of } G(z)")]
        display(
            ("G_1(z)", SH.sections_tex(f.sensor_C, f.sensor_eps)),
            ("G_3(z)", SH.sections_tex(f.actuator_C, f.actuator_eps)),
            G2_row,
            *b_rows,
            *named_den,
            *sigma_rows,
            label="eq:factors",
        )
        if f_N != 0:
            say(
                "Taking out the constant $N$ (the direct term of $G_2$) rewrites $G_2$ with the "
                "remainder's numerator coefficients $c_k$ (descending powers of $z$), as "
                f"{cite('Eq.', 'G2_rewritten')} does; so $N$ is the same in every realization:"
            )
        else:
            say(
                "$G_2$ is strictly proper, its direct term $N = 0$ (the compensator's "
                "relative degree exceeds the net delay by one); its numerator's coefficients "
                "$c_k$ (descending powers of $z$):"
            )
        rewritten = rf"N + N\,\frac{{{remainder}}}{{{den}}}" if f_N != 0 else None
        display(
            ("N", f_N if SH.fits("G_2(z)", L.to_latex(f_N)) else SH.quotient_tex(f_N)),
            ("G_2(z)", rewritten or rf"\frac{{{remainder}}}{{{den}}}"),
            *zip(map(L.to_latex, c), f_coeffs, strict=True),
            label="eq:G2rewritten",
        )
        say(f"$G_3 G_2 G_1 = G$ proved: {'yes' if res.verified else 'NO'}.")
        show("g1g3_structures", _G1G3_CAPTION)

        # 7. realizations
        add(Heading("Realizations of $G_2$"))
        say(
            "A realization $(F, H, M, N)$ of $G_2$ satisfies "
            f"$M (zI - F)^{{-1}} H + N = G_2(z)$ {cite('Eq.', 'realization')}; each one below "
            "is checked exactly, symbolically and with the numbers used in the simulations "
            "(the optimal gains, $C = 1$ on every section, and for the general one random "
            f"$\\epsilon$ and a random full-rank $P$ drawn from seed {res.seed})."
        )
        for name in [k for k in res.realizations if not _is(k, "takes_transform")]:
            rec = res.realizations[name]
            add(Heading(f"{REALIZERS[name].title.capitalize()} form", 2))
            mats, short = SH.compact(rec.symbolic, f, c, (f_N, f_coeffs))
            if short:
                names[name] = {**SH.renamed(rec.symbolic, dict(mats)), L.to_latex(f_N): "N"}
            display(*((k, SH.factored(m)) for k, m in mats), label=f"eq:{name}")
            where = " Entries $N c_k$ use the $c_k$ of the rewritten $G_2$." if short else ""
            paper = f" For $T = 2$ this is {cite('Eq.', name)}." if _is(name, "paper") else ""
            say(MIMO.check_text(rec) + where + paper)
        if "general" in res.realizations:
            rec = res.realizations["general"]
            add(Heading("General realization", 2))
            P = rec.P
            say(
                "Any invertible $P$ transforms the controllable canonical form $(F_c, H_c, M_c, N)$ "
                "into another realization of the same $G_2$ (for $T = 2$ the paper's "
                f"{cite('Eq.', 'general_realization')}):"
            )
            display(
                ("F", r"P^{-1} F_c P"),
                ("H", r"P^{-1} H_c"),
                ("M", r"M_c P"),
                ("P", "P" if P is None else P if P.free_symbols else SH.num(P)),
                label="eq:general",
            )
            say(MIMO.check_text(rec))
            values = ", ".join(
                f"${L.to_latex(sp.Symbol(k))} = {L.number(v)}$"
                for k, v in sorted(rec.values.items())
            )
            say(f"With the seeded numbers ({values}):")
            display(
                *((k, SH.num(getattr(rec.numeric, k))) for k in "FHMN"),
                ("P", SH.num(rec.P_numeric)),
                label="eq:general-numeric",
            )

    # 8. delay graph and compatibility
    add(Heading("Delay graph and compatibility"))
    spec = res.spec
    if spec.graph_given:
        named = ", ".join(f"v{i + 1} = {v.replace('_', ' ')}" for i, v in enumerate(spec.vertices))
        edges = "; ".join(
            f"{a.replace('_', ' ')} to {b.replace('_', ' ')}: {d}" for a, b, d in spec.edges
        )
        graph_text = (
            f"The delay graph is the model file's: {res.graph.n} vertices ({named}; the sensor "
            f"first, the actuator last) and edges with their delays in steps ({edges})"
        )
    else:
        graph_text = (
            "The delay graph has one vertex per stage (sensor side, one relay per further unit "
            f"delay, the actuator), {res.graph.n} in all"
        )
    say(
        graph_text + f"{see('delay_graph')}; $E_{{ij}}$ is the smallest delay from vertex $i$ "
        f"to vertex $j$ ($\\infty$: no path; {cite('Def.', 'delay_graph')}, and "
        f"{cite('Eq.', 'E')} for the paper's graph). A delay assignment puts every signal "
        "of a structure at a vertex, the controller's input at the sensor and its output at "
        "the actuator; the structure is compatible when some assignment has $\\tilde E \\ge E$ "
        f"entry by entry {cite('Defs.', 'delay_assignment', 'compatible_structure')}."
    )
    show("delay_graph", _GRAPH_CAPTION)
    display(("E", res.graph.E), label="eq:E")
    add(_READINGS)
    put(MS.theorem(res))
    for name, crec in res.circuits.items():
        verdict = crec.compatibility
        add(Heading(_title(name), 2))
        if verdict.ok:
            say(
                f"Compatible (decided by {verdict.method}); the delays between the vertices "
                "under the witness assignment, in both readings:"
            )
            put(_e_tilde(res.graph.E, verdict.assignment, name))
            where = "; ".join(
                f"$v_{{{v}}}$: {MS.counted(len(verdict.assignment.signals_at(v)), 'signal')}"
                for v in range(1, res.graph.n + 1)
            )
            say(f"Signals per vertex: {where}. The checker's witness:")
            add(Verbatim(_ascii(verdict.reason)))
        else:
            say(f"Not compatible (decided by {verdict.method}). The reason:")
            add(Verbatim(_ascii(verdict.reason)))
        show(f"structure_{name}", f"Structure: {_title(name)}{_PAPER_STRUCTURE.get(name, '')}.")

    # 9. circuits
    add(Heading("Neurons and circuits"))
    say(
        f"A neuron (the stylized neuron of {cite('Fig.', 'neural_circuit')}) is an adder that "
        "sums two or more terms (the output sum included); a "
        "single term through delays is an axon with a synaptic weight; a loop through the "
        "neuron's own output is its self-dynamics. The closed loop was simulated with "
        f"{_count_text(res)} of each circuit; the largest relative departure of the "
        f"{x0} and {u0} traces from the optimal controller's is in the last column."
    )
    rows = tuple(
        (
            _title(k),
            str(c.circuit.n_neurons),
            "-" if c.g2_neurons is None else str(c.g2_neurons),
            str(len(c.circuit.synapses)),
            "yes" if c.compatibility.ok else "no",
            str(c.firing.count),
            SH.fmt(c.firing.max_deviation, 2),
        )
        for k, c in res.circuits.items()
    )
    add(Table(_CIRCUIT_COLUMNS, rows))
    for name, crec in res.circuits.items():
        add(Heading(_title(name), 2))
        if _is(name, "takes_transform") and crec.circuit.free_symbols - set(f.G.free_symbols):
            circuit, what = crec.firing.circuits[0], "its first simulated realization"
            say(f"The neurons of {what} (the symbolic weights are rational in $P$):")
        else:
            circuit = crec.circuit
            say("The neurons, their self-dynamics and synapses:")
        rows = [tuple(eq.split(" = ", 1)) for eq in circuit.equations(digits=6)]
        put(SH.display(SH.named_weights(rows, names.get(name, {})), f"eq:circuit-{name}"))
        placed = [
            f"${signal_tex(n.name)}$ at $v_{{{n.vertex}}}$"
            for n in crec.circuit.neurons
            if n.vertex
        ]
        if placed:
            say("Where the neurons sit on the delay graph: " + ", ".join(placed) + ".")
        show(
            f"circuit_{name}",
            f"Circuit, {_title(name)}{_WHICH.get(name, '')}: neurons as "
            "circles with their self-dynamics, synapses as arrows with "
            f"weights{_PAPER_CIRCUIT.get(name, '')}.",
        )

    # 10. simulations
    add(Heading("Simulations: the same behaviour, different firing"))
    say(
        f"Every realization gives the {x0} and {u0} traces of the optimal controller "
        "(to rounding), while the neurons of $G_2$ fire differently, as "
        f"{cite('Sec.', 'simulations')} shows for its circuits. Peak firing "
        "(change from equilibrium, spikes/s) per neuron and realization; the spread is "
        "the largest difference between two realizations' traces at any one step:"
    )
    for name, crec in res.circuits.items():
        fp = crec.firing
        add(Heading(_title(name), 2))
        put(_firing_table(fp))
        show(
            f"firing_{name}",
            f"Firing of the neurons, {_title(name)}: "
            f"{MS.counted(fp.count, 'realization')}, the same {x0} "
            f"traces{_PAPER_FIRING.get(name, '')}.",
        )
    put(MS.nonlinear(res, figure))
    put(MS.longest(res))
    if res.atlas is not None:
        from symctl.report.atlas import paper_blocks

        put(paper_blocks(res, shown))
    if getattr(res, "spiking_cost", None) is not None:
        from symctl.report import spiking

        put(spiking.paper_blocks(res, shown))
    add(References(REFERENCES))
    return blocks


def _remainder(res) -> tuple[sp.Expr, list[sp.Expr], list[tuple[str, str]]]:
    r"""``N``, the :math:`c_k` of the :math:`G_2` the realizations realize, and the rows defining
    the :math:`\sigma_k` of an abbreviated :math:`G_2`."""
    f = res.factors
    if not getattr(res, "abbreviated", False):
        return f.N, f.remainder_coeffs, []
    N, c = remainder(res.G2_symbolic)
    d = len(f.poles)
    groups = [f.sensor_eps, f.actuator_eps]
    args = ", ".join(_range_tex(g) for g in groups if g)
    rows = [
        (r"\sigma_k", rf"e_k\left({args}\right),\ k = 1, \dots, {d}"),
        (
            None,
            r"\qquad \text{(so that } \prod (z - \epsilon) = "
            rf"\sum_{{k=0}}^{{{d}}} (-1)^k \sigma_k\, z^{{{d}-k}},\ \sigma_0 = 1)",
        ),
    ]
    return N, c, rows


def _range_tex(symbols) -> str:
    """``epsilon_{1,1}, ..., epsilon_{1,5}`` (all of them when few or not consecutive)."""
    ix = SH.indexed(symbols)
    if ix is None or len(symbols) <= 3:
        return ", ".join(L.to_latex(x) for x in symbols)
    return rf"{L.to_latex(symbols[0])}, \dots, {L.to_latex(symbols[-1])}"


def _firing_table(fp) -> list[DocumentBlock]:
    """Peak firing per neuron and realization: as many realizations as the page is wide."""
    summ = fp.summary()
    for shown in range(fp.count, 0, -1):
        rows = tuple(
            (
                f"${signal_tex(n)}$",
                *(SH.fmt(v) for v in summ.peak[:shown, i]),
                SH.fmt(summ.trace_spread[i]),
            )
            for i, n in enumerate(summ.neurons)
        )
        head = ("neuron", *(f"#{i + 1}" for i in range(shown)), "spread")
        if 0.75 * LF.table_width(head, rows) <= LF.TABLE_WIDTH or shown == 1:
            break
    note = (
        []
        if shown == fp.count
        else [
            Text(
                f"The first {shown} of the {fp.count} realizations (all of them in results.json, "
                "peak_firing); the spread is over all of them:"
            )
        ]
    )
    return [*note, Table(head, rows)]


def _title(circuit: str) -> str:
    """The circuit's title with its transfer functions as math: ``$G_3 G_2 G_1$, general $G_2$``."""
    title = re.sub(r"\bG([123])\b", r"$G_\1$", circuit_specs()[circuit].title)
    return title.replace("$ $", " ")


_WHICH = {"general": " (its first simulated realization)"}


def _is(name: str, flag: str) -> bool:
    """Whether the circuit ``name`` is a registered realizer with ``flag`` set."""
    return name in REALIZERS and getattr(REALIZERS[name], flag)


def _count_text(res) -> str:
    counts = {c.firing.count for c in res.circuits.values() if not _is(c.name, "controller")}
    n = max(counts) if counts else 1
    return f"{n} random realizations (the IFP controller has one)"


POLE_ZERO_TOL = 1e-6  # smaller poles are written as 0 (a multiple pole at 0 splits by rounding)


def _pole(p: complex) -> str:
    if abs(p) < POLE_ZERO_TOL:
        return "0"
    if abs(p.imag) < 1e-12:
        return L.number(p.real)
    sign = "+" if p.imag > 0 else "-"
    return f"{L.number(p.real)} {sign} {L.number(abs(p.imag))}\\,i"
