"""symctl.latex: LaTeX export of every derived object, with the paper's symbol names."""

from __future__ import annotations

import math
import re
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from symctl import (
    Circuit,
    DelayGraph,
    MuscleModel,
    Structure,
    augment,
    check_compatibility,
    controllable_canonical,
    controller_tf,
    factor,
    ifp_structure,
    lqr_gains,
)
from symctl import latex as L
from symctl.errors import ParameterError, SymctlTypeError
from symctl.symbols import delta_f, delta_r, epsilon_1, gain_symbols, r_bar


def _derived_objects():
    model = MuscleModel()
    aug = augment(model, 1, 1)
    f = factor(controller_tf(2))
    S = Structure.from_factorization(f, controllable_canonical(f.G2))
    graph = DelayGraph.chain([1, 1])
    verdict = check_compatibility(S, graph)
    return {
        "model": model,
        "linearization": model.linearize_symbolic(),
        "plant": model.discrete_symbolic(),
        "augmented": aug,
        "gains": lqr_gains(aug),
        "G": controller_tf(aug),
        "factorization": f,
        "realization": controllable_canonical(f.G2),
        "graph": graph,
        "assignment": verdict.assignment,
        "compatible": verdict,
        "not compatible": check_compatibility(ifp_structure(2), graph),
        "circuit": Circuit.from_structure(S, verdict),
    }


def test_paper_symbol_names_are_used():
    tex = L.to_latex(delta_r - delta_f / (1 + r_bar) + epsilon_1)
    assert r"\delta_r" in tex and r"\delta_f" in tex and r"\bar{r}" in tex
    assert r"\epsilon_{1}" in tex
    assert L.to_latex(sp.Symbol("epsilon_{3,2}")) == r"\epsilon_{3,2}"


def test_equation_and_align_environments_with_labels():
    K0, K1, K2 = gain_symbols(2)
    eq = L.equation("G(z)", K0 / (sp.Symbol("z") ** 2 - K1 * sp.Symbol("z") - K2), label="eq:G")
    assert eq.startswith(r"\begin{equation}") and eq.endswith(r"\end{equation}")
    assert r"\label{eq:G}" in eq and "K_{0}" in eq
    al = L.align([sp.Eq(delta_r, K0 * delta_f), ("y", 2)], labels=["eq:a", "eq:b"])
    assert al.count(r"\label") == 2 and al.count("&=") == 2
    assert r"\begin{align}" in al and r"\\" in al
    star = L.align([("a", 1)], numbered=False)
    assert r"\begin{align*}" in star and r"\label" not in star


def test_every_derived_object_exports():
    for name, obj in _derived_objects().items():
        pairs = L.equations(obj)
        assert pairs, name
        tex = L.export(obj, label=f"eq:{name.replace(' ', '-')}")
        assert tex.startswith(r"\begin{"), name
        assert tex.count(r"\begin{") == tex.count(r"\end{"), name
    f = _derived_objects()["factorization"]
    assert [lhs for lhs, _ in L.equations(f)] == ["G_1(z)", "G_2(z)", "G_3(z)", "N"]
    assert [lhs for lhs, _ in L.equations(controllable_canonical(f.G2))] == list("FHMN")


def test_numbers_and_arrays():
    assert L.number(1.5e-7) == r"1.5 \times 10^{-7}"
    assert L.number(-math.inf) == r"-\infty"
    assert L.number(math.nan) == r"\mathrm{NaN}"
    E = DelayGraph.chain([1, 1]).E
    assert L.to_latex(E) == (
        r"\begin{bmatrix}0 & 1 & 2 \\ \infty & 0 & 1 \\ \infty & \infty & 0\end{bmatrix}"
    )
    assert L.to_latex(sp.Float(0.123456789) * epsilon_1) == r"0.123457 \epsilon_{1}"


@given(st.floats(allow_nan=False, allow_infinity=False, width=64))
def test_number_reads_back_to_six_significant_digits(x):
    text = L.number(x)
    m = re.fullmatch(r"(-?[\d.]+)(?: \\times 10\^\{(-?\d+)\})?", text)
    assert m, text
    value = float(m.group(1)) * 10.0 ** int(m.group(2) or 0)
    assert value == pytest.approx(x, rel=1e-5, abs=1e-300)


def test_bad_arguments_name_themselves():
    with pytest.raises(ParameterError, match="label"):
        L.equation("a", 1, label="bad label}")
    with pytest.raises(ParameterError, match="labels"):
        L.align([("a", 1), ("b", 2)], labels=["x"])
    with pytest.raises(ParameterError, match="rows"):
        L.align([])
    with pytest.raises(ParameterError, match="name"):
        L.export(MuscleModel().discrete_symbolic(), name="X")
    with pytest.raises(SymctlTypeError, match="obj"):
        L.to_latex(object())
    with pytest.raises(ParameterError, match="digits"):
        L.to_latex(1.0, digits=0)
    with pytest.raises(ParameterError, match="packages"):
        L.document("x", packages=["evil}"])


def test_a_document_of_every_derived_object_compiles_with_pdflatex(tmp_path, pdflatex):
    parts = [L.export(obj) for obj in _derived_objects().values()]
    parts.append(L.align([("x", np.array([[1.0, 2.0]]))], labels=["eq:x"]))
    (tmp_path / "all.tex").write_text(L.document(parts, title="All objects"))
    run = subprocess.run(
        [pdflatex, "-interaction=nonstopmode", "-halt-on-error", "all.tex"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=False,
    )
    assert run.returncode == 0, run.stdout[-2000:]
    assert (tmp_path / "all.pdf").stat().st_size > 1000


def test_importing_latex_loads_no_derived_class():
    code = (
        "import sys, symctl.latex; "
        "print(sorted(m for m in sys.modules if m.startswith('symctl.') "
        "and m.split('.')[1] not in ('latex', 'errors', 'symbols', '_util')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_a_subclass_of_a_derived_type_exports_as_its_base():
    class Named(DelayGraph):
        pass

    g = DelayGraph.chain([1, 1])
    named = Named(g.E)
    assert L.equations(named) == L.equations(g)
