"""A structure's equations, one per adder and per delayed state, as SymPy or as LaTeX."""

from __future__ import annotations

import sympy as sp

from symctl._util.display import latex
from symctl._util.texnames import signal_tex

__all__ = ["structure_equations", "structure_latex"]


def _symbol_name(name: str) -> str:
    return name.replace(" ", "").replace("^-1", "d_")


def structure_equations(S) -> list[sp.Eq]:
    r"""One equation per adder and delay, with the gains written into them.

    >>> from symctl import ifp_structure
    >>> from symctl.compatibility.equations import structure_equations
    >>> structure_equations(ifp_structure(2))[-1]
    Eq(mu(t), K_0*x(t) + K_1*gamma(t) + K_2*u(t))
    """
    t = sp.Symbol("t", integer=True)

    def value(name, time):
        block = S.blocks[name]
        if block.kind == "gain":
            gain = block.gain if block.gain is not None else sp.Symbol(_symbol_name(name))
            return gain * value(block.inputs[0], time)
        return sp.Function(_symbol_name(name))(time)

    out = []
    for name, block in S.blocks.items():
        if block.kind == "delay":
            rhs = value(block.inputs[0], t - block.steps)
        elif block.kind == "sum":
            rhs = sp.Add(*(value(s, t) for s in block.inputs))
        else:
            continue
        out.append(sp.Eq(sp.Function(_symbol_name(name))(t), rhs, evaluate=False))
    return out


def _branch_term(name: str) -> bool:
    return name.rpartition(".")[2].startswith("z^-")


def structure_latex(S) -> str:
    r"""The equations of ``S`` as an ``aligned`` block for a reader: readable names, the part as a
    superscript, delayed branch terms written into the adder they feed (a state reads as its
    recursion).

    >>> from symctl import ifp_structure
    >>> from symctl.compatibility.equations import structure_latex
    >>> for row in structure_latex(ifp_structure(2)).split(r" \\ "):
    ...     print(row)
    \begin{aligned}\gamma(t) &= \mu(t - 1)
    u(t) &= \gamma(t - 1)
    \mu(t) &= K_{0} x(t) + K_{1} \gamma(t) + K_{2} u(t)\end{aligned}
    """

    def terms(name: str, lag: int) -> list[str]:
        block = S.blocks[name]
        if block.kind == "gain":
            inner = terms(block.inputs[0], lag)
            if block.gain is None:
                gain = signal_tex(name)
            else:
                gain = latex(block.gain)
                if isinstance(block.gain, sp.Add):
                    gain = rf"\left({gain}\right)"
            if gain == "1":
                return inner
            if gain == "-1":
                return ["-" + t for t in inner]
            return [f"{gain} {t}" for t in inner]
        if block.kind == "delay" and _branch_term(name):
            return terms(block.inputs[0], lag + block.steps)
        return [signal_tex(name) + ("(t)" if lag == 0 else f"(t - {lag})")]

    rows = []
    for name, block in S.blocks.items():
        if block.kind == "sum":
            rhs = [t for src in block.inputs for t in terms(src, 0)]
        elif block.kind == "delay" and not _branch_term(name):
            rhs = terms(block.inputs[0], block.steps)
        else:
            continue
        body = " + ".join(rhs).replace("+ -", "- ")
        rows.append(f"{signal_tex(name)}(t) &= {body}")
    return r"\begin{aligned}" + r" \\ ".join(rows) + r"\end{aligned}"
