"""The console's summary of a derivation (``symctl paper``, ``derive``), read off its objects."""

from __future__ import annotations

import contextlib

from rich.console import Console
from rich.table import Table

__all__ = ["summary"]


def summary(res, console: Console) -> None:
    """Print the summary of a :class:`~symctl.derivation.Derivation`, read off its objects."""
    import sympy as sp  # imported here, as every heavy import of the CLI: `symctl --help` is fast

    from symctl.report.results import controller_coeffs, factor_texts

    spec, ode, G = res.spec, res.model, res.G

    def out(text: str) -> None:
        head, sep, rest = text.partition("|")
        if sep:
            console.print(head, style="bold", end="", markup=False)
            text = rest
        console.print(text, markup=False, soft_wrap=True)

    out(f"Plant|  {spec.name} (linearized, zero-order hold)")
    states = res.names[0]
    if ode is not None:
        for name, value, e in zip(states, ode.x_bar.tolist(), ode.x_eq, strict=True):
            unit = f" {spec.unit(name)}" if spec.unit(name) else ""
            text = sp.sstr(e)
            shown = "" if _is_number(text, value) else f"{text} = "
            out(f"  {name}_bar = {shown}{value:.6g}{unit}")
    sym = res.plant_symbolic
    sym_A, sym_B = (sp.sstr(sym.A[0, 0]), sp.sstr(sym.B[0, 0])) if sym is not None else ("", "")
    out(f"  A = {sym_A + ' = ' if sym_A else ''}{_fmt(res.plant.A)}")
    out(f"  B = {sym_B + ' = ' if sym_B else ''}{_fmt(res.plant.B)}")
    s = res.system
    out(f"Augmented system|  (T = {s.T}): chi = [{', '.join(s.state_names)}]")
    out(f"  A~ = {_fmt(s.A)}\n  B~ = {_fmt(s.B)}\n  Q~ = {_fmt(s.Q)}")
    names = [str(k) for k in res.gains.substitutions()]
    out("Gains|  mu = K chi, K = [" + ", ".join(names) + "]")
    out(f"  K = {_fmt(res.gains.K)}")
    out("Controller|  G(z): measured states -> inputs")
    out(f"  G(z) = {_long(str(res.G_symbolic), 'controller')}")
    numerator, denominator = controller_coeffs(G)
    out(f"  numerator {_fmt(numerator)}, denominator {_fmt(denominator)}")
    out(f"  relative degree {G.relative_degree}; derivation proved: {bool(res.proved)}")
    red = res.reduction
    if red is not None and not red:
        out(f"  not minimal, reduced from {red.order} to {red.minimal_order} states: {red.reason}")
    L = res.longest
    if L is not None:
        tried = f"every T up to {L.delays[-1]} (the largest tried)"
        found = f"T = {L.longest} steps" if L.limited else tried
        out(f"Longest delay|  that still stabilizes the nonlinear plant: {found}")
    if res.factors is None:
        out(f"Not derived|  {res.skipped}")
        _summary_table(res, console)
        return
    f = factor_texts(res)
    out("Factorization|  G = G3 G2 G1")
    none = {"G1": " (no sensor delay)", "G3": " (no actuator delay)"}
    g1, g3 = (f"{k} = {_long(f[k], 'factorization')}{none[k] * (f[k] == '1')}" for k in none)
    out(f"  {g1},  {g3}")
    out(f"  G2 = {_long(f['G2'], 'factorization')}")
    N = f["N"] if isinstance(f["N"], str) else f"({len(f['N'])} x {len(f['N'][0])})"
    out(f"  N = {_long(N, 'factorization')};  G3 G2 G1 == G proved: {bool(res.verified)}")
    from symctl.realization.realizers import REALIZERS

    for name, rec in res.realizations.items():
        sym, num = rec.check_symbolic, rec.check_numeric
        size = rec.numeric.F.shape[0]
        small = size <= 3
        F = ", ".join("[" + ", ".join(map(sp.sstr, row)) + "]" for row in rec.symbolic.F.tolist())
        dense = name in REALIZERS and REALIZERS[name].takes_transform  # F in a symbolic P
        shown = "P^-1 F_c P" if dense else f"[{F}]"
        shown = shown if small or dense else f"({size} x {size})"
        numeric = _fmt(rec.numeric.F) if small else f"({size} x {size}, in results.json)"
        out(
            f"  {name:>12}: F = {shown}; F(seed {res.seed}) = "
            f"{numeric}; realizes G2, symbolic ({sym.method}): {sym.ok}, "
            f"numeric ({num.method}): {num.ok}"
        )
    _summary_table(res, console)
    _circuit_table(res, console)


def _summary_table(res, console) -> None:
    table = Table(title="summary")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    spec, ode = res.spec, res.model
    if ode is not None:
        for name, value in zip(res.names[0], ode.x_bar.tolist(), strict=True):
            unit = f" [{spec.unit(name)}]" if spec.unit(name) else ""
            table.add_row(f"{name}_bar{unit}", f"{value:.4f}")
    for label, M in (("A", res.plant.A), ("B", res.plant.B)):
        table.add_row(label, f"{float(M[0, 0]):.6f}" if M.shape[0] == 1 else _fmt(M))
    for name, value in res.gains.substitutions().items():
        table.add_row(str(name), f"{value:.6f}")
    table.add_row("spectral radius", f"{res.gains.spectral_radius:.6f}")
    console.print(table)


def _circuit_table(res, console) -> None:
    circuits = Table(title="circuits (closed loop against the optimal controller)")
    for head in ("circuit", "neurons", "in G2", "compatible", "realizations", "max deviation"):
        circuits.add_column(head, justify="left" if head == "circuit" else "right")
    for name, c in res.circuits.items():
        g2 = c.g2_neurons
        circuits.add_row(
            name,
            str(c.circuit.n_neurons),
            "-" if g2 is None else str(g2),
            "yes" if c.compatibility.ok else "no",
            str(len(c.firing.params)),
            f"{c.firing.max_deviation:.1e}",
        )
    console.print(circuits)


SUMMARY_TEXT, SUMMARY_MATRIX = 240, 8  # the console's longest formula, largest matrix in full


def _fmt(values) -> str:
    """Numbers (or a SymPy matrix of them) to 6 significant digits: a 1 x 1 matrix as its entry,
    a large one by its size."""
    import numpy as np

    arr = np.asarray(values.evalf() if hasattr(values, "evalf") else values, dtype=float)
    if arr.size == 1:
        return f"{arr.item():.6g}"
    if max(arr.shape) > SUMMARY_MATRIX:
        return "(" + " x ".join(map(str, arr.shape)) + ", in results.json)"
    text = np.array2string(
        arr, max_line_width=10_000, separator="  ", formatter={"float_kind": lambda v: f"{v:.6g}"}
    )
    return text.replace("\n", "")


def _long(text: str, where: str) -> str:
    """A formula for the console, or its length when longer than ``SUMMARY_TEXT``."""
    return (
        text if len(text) <= SUMMARY_TEXT else f"({len(text):,} characters; results.json, {where})"
    )


def _is_number(text: str, value: float) -> bool:
    """Whether a symbolic value's text is just its number (``0`` for 0.0): not printed twice."""
    with contextlib.suppress(ValueError):
        return float(text) == value
    return False
