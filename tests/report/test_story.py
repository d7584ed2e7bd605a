"""report/story: the derivation as blocks, in the paper's order."""

from __future__ import annotations

import sympy as sp

from symctl import controllable_canonical, controller_tf, derive_paper, factor, observable_canonical
from symctl.latex import to_latex
from symctl.report.document import Graphic, Heading, Math
from symctl.report.spec import CIRCUIT_SPECS
from symctl.report.story import _compact, _remainder_poly, _remainder_symbols, story


def test_only_the_figures_written_get_a_graphic_block():
    res = derive_paper(realizations=1)
    none = story(res)
    assert not [b for b in none if isinstance(b, Graphic)]
    some = story(res, figures=["nonlinear", "circuit_general"])
    assert [b.name for b in some if isinstance(b, Graphic)] == ["circuit_general", "nonlinear"]


def test_the_augmented_state_is_the_systems_chi():
    res = derive_paper(realizations=1)
    (eq,) = [b for b in story(res) if isinstance(b, Math) and b.label == "eq:augmented"]
    assert eq.rows[0] == (r"\chi", to_latex(res.system.chi))


def test_circuit_headings_use_the_specs_titles():
    res = derive_paper(realizations=1)
    headings = {b.text for b in story(res) if isinstance(b, Heading)}
    assert {CIRCUIT_SPECS[name].title for name in res.circuits} <= headings


def test_long_realization_entries_are_written_as_N_c_k_and_mean_the_same():
    f = factor(controller_tf(4), 2, 2)
    c = _remainder_symbols(f)
    values = {sp.Symbol("N"): f.N, **dict(zip(c, f.remainder_coeffs, strict=True))}
    rewritten = f.N + f.N * _remainder_poly(c) / f.G2.den
    assert sp.cancel(rewritten.subs(values) - f.G2.expr) == 0
    for R in (controllable_canonical(f.G2), observable_canonical(f.G2)):
        rows, short = _compact(R, f, c)
        assert short
        for name, mat in rows:
            assert (mat.subs(values) - getattr(R, name)).applyfunc(sp.cancel).is_zero_matrix
        assert any(mat.has(sp.Symbol("N")) for _, mat in rows)


def test_the_delays_are_counted_in_words_not_step_s():
    from symctl.report.document import Text

    for ds, word in ((1, "$d_s = 1$ step and"), (2, "$d_s = 2$ steps and")):
        text = " ".join(b.text for b in story(derive_paper(sensor_delay=ds, realizations=1))
                        if isinstance(b, Text))  # fmt: skip
        assert "step(s)" not in text and word in text
