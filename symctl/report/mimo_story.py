r"""The factorization (per channel) and realizations (block forms) of a MIMO controller, as blocks."""

from __future__ import annotations

import re

import sympy as sp

from symctl import latex as L
from symctl._util.display import descending_latex
from symctl.realization.realizers import REALIZERS
from symctl.report import matrixview as MV
from symctl.report import shorthand as SH
from symctl.report.document import DocumentBlock, Heading, Text

__all__ = ["check_text", "factorization", "realizations", "reduction"]


def reduction(res) -> list[DocumentBlock]:
    """The paragraph on a controller that is not minimal: by how much, why, and the ties."""
    r = res.reduction
    if r is None or r:
        return []
    signals = sorted((*res.names[0], *res.names[1]), key=len, reverse=True)
    name = "(?:" + "|".join(map(re.escape, signals)) + ")"
    term = rf"(?:\d+(?:/\d+)? )?{name}"
    combination = re.compile(rf"-?{term}(?: [+-] {term})*")

    def tex(text: str) -> str:  # each signed sum of signals as inline math
        return combination.sub(lambda m: f"${_combination_tex(m.group())}$", text)

    ties = ", ".join(f"${L.to_latex(k)} = {L.to_latex(v)}$" for k, v in r.relations.items())
    return [
        Text(
            f"This controller is not minimal: its {r.order} states (the past commands) "
            f"realize a transfer function of McMillan degree {r.minimal_order} (decided by "
            f"{r.method}). Why: {tex(r.reason)}. The controller keeps "
            + " and ".join(tex(c) for c in r.never_driven)
            + f" at zero, so {r.order - r.minimal_order} of its states are never reached. "
            "The optimal gains satisfy ties with rational coefficients (proved in "
            f"symctl.realization.reduction): {ties}. The gains above are the tied ones, "
            "computed exactly from the free ones, and $G(z)$ is the minimal controller: "
            "the power of $z$ common to its denominator and numerators is divided out. "
            "Everything below is built from it."
        )
    ]


def _combination_tex(text: str) -> str:
    """A signed sum of signal names (``u_flex + u_ext``) as LaTeX."""
    return re.sub(r"[A-Za-z]\w*", lambda m: L.to_latex(sp.Symbol(m.group())), text)


def factorization(res) -> list[DocumentBlock]:
    """Section 6 for a MIMO controller: per-channel sections, G2, the proof."""
    f = res.factors
    m, p = f.channels
    xs, us = res.names
    rows = [
        (rf"g_{{{side},{k + 1}}}(z)", SH.sections_tex(c, e))
        for side, channels in zip((1, 3), f.section_channels, strict=True)
        for k, (e, c) in enumerate(channels)
    ]
    blocks: list[DocumentBlock] = [
        Heading("Factorization $G = G_3 G_2 G_1$"),
        Text(
            f"The controller maps the {m} measured signal{'s' * (m != 1)} "
            f"({', '.join(xs) if res.kalman is None else '$y$'}) to the {p} "
            f"inputs ({', '.join(us)}). Each measured signal $j$ crosses the sensor delay "
            "through its own first-order sections $g_{1,j}$, each input $i$ the actuator delay "
            "through its own $g_{3,i}$: $G_1 = \\operatorname{diag}_j g_{1,j}$, "
            "$G_3 = \\operatorname{diag}_i g_{3,i}$, and "
            "$(G_2)_{ij} = G_{ij} / (g_{3,i}\\, g_{1,j})$ keeps the common denominator of $G$:"
        ),
    ]
    if res.skipped:
        blocks.append(Text("Not built here: " + res.skipped.replace("_", r"\_") + "."))
    if rows:
        blocks += SH.eq(*rows, label="eq:sections")
    N2 = f.G2.num_matrix
    if res.abbreviated:  # each entry's zeros as products (expanded: 2^d terms)
        entries = [(rf"(N_2)_{{{i}{j}}}", _entry_tex(f, i, j)) for (i, j), _ in f.entry_poles]
    elif MV.show_matrix("N_2(z)", N2).full:
        entries = [("N_2(z)", N2)]
    else:  # too wide for the line: each entry in descending powers of z, broken over lines
        entries = [
            (rf"(N_2)_{{{i + 1}{j + 1}}}", descending_latex(N2[i, j]))
            for i in range(N2.rows)
            for j in range(N2.cols)
            if N2[i, j] != 0
        ]
    blocks += SH.eq(
        ("G_2(z)", r"\frac{1}{d(z)}\, N_2(z)"),
        ("d(z)", descending_latex(f.G2.den)),
        *entries,
        label="eq:factors",
    )
    blocks.append(
        Text(
            f"$G_3 G_2 G_1 = G$ proved entry by entry: {'yes' if res.verified else 'NO'} "
            "(each $g_{3,i} (G_2)_{ij} g_{1,j} = G_{ij}$ as a polynomial identity)."
        )
    )
    return blocks


def check_text(rec) -> str:
    """The sentence on a realization's two checks, symbolic and numeric."""
    sym, num = rec.check_symbolic, rec.check_numeric
    return (
        f"Realizes $G_2$, symbolically: {'yes' if sym.ok else 'NO'} ({sym.method}); "
        f"with the numbers: {'yes' if num.ok else 'NO'} ({num.method})."
    )


def _entry_tex(f, i: int, j: int) -> str:
    r"""Entry :math:`(i, j)` of :math:`N_2` (from 1), its sections' zeros as products."""
    (e1, c1), (e3, c3) = f.section_channels[0][j - 1], f.section_channels[1][i - 1]
    gain = f.G.num_matrix[i - 1, j - 1] / sp.Mul(*c1, *c3)
    zeros = " ".join(SH.zeros_tex(e, product=True) for e in (e1, e3) if e)
    return f"{SH.quotient_tex(gain)}\\, {zeros}"


def realizations(res) -> list[DocumentBlock]:
    """Section 7 for a MIMO controller: the block canonical forms (and their transforms), checked."""
    blocks: list[DocumentBlock] = [
        Heading("Realizations of $G_2$"),
        Text(
            "A realization $(F, H, M, N)$ of the matrix $G_2$ satisfies "
            "$M (zI - F)^{-1} H + N = G_2(z)$. The block controllable form has $n m$ states "
            "(one block of $m$ per power of $z$), the block observable form $n p$, for "
            "$n = \\deg d$; each is checked exactly, in symbols and with the numbers of the "
            f"simulations (the optimal gains, $C = 1$, random $\\epsilon$ from seed {res.seed})."
        ),
    ]
    for name, rec in res.realizations.items():
        blocks.append(Heading(f"{REALIZERS[name].title.capitalize()} form", 2))
        states = rec.numeric.F.shape[0]
        blocks.append(Text(f"{states} states. {check_text(rec)} With the numbers:"))
        blocks += SH.eq(*((k, SH.num(getattr(rec.numeric, k))) for k in "FHMN"), label=f"eq:{name}")
    return blocks
