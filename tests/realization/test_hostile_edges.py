"""Wrong answers at the edges: sampling times, float inputs, hidden modes."""

from __future__ import annotations

import pytest
import sympy as sp

from symctl import (
    DiscreteTF,
    MuscleModel,
    Realization,
    augment,
    check_realization,
    controllable_canonical,
    controller_tf,
    factor,
    lqr_gains,
    observable_canonical,
    random_realization,
)
from symctl.errors import ParameterError
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3, z

CLASS = "6"

T = sp.Symbol("T", positive=True)

# (dt of the first operand, dt of the second, the dt the product keeps or None when refused)
DT_REFUSED = [
    (sp.Rational(1, 10), sp.Rational(1, 2)),
    (0.1, 0.5),
    (0.01, 0.02),
    (T, sp.Rational(1, 100)),
    (T, 2 * T),
]
DT_COMBINED = [
    (None, sp.Rational(1, 10), sp.Rational(1, 10)),
    (sp.Rational(1, 10), None, sp.Rational(1, 10)),
    (None, None, None),
    (0.01, sp.Rational(1, 100), 0.01),
    (T, T, T),
]


@pytest.mark.parametrize(("dt1", "dt2"), DT_REFUSED)
def test_tf_product_refuses_incompatible_sampling_times(dt1, dt2):
    with pytest.raises(ParameterError, match="other: incompatible sampling times"):
        DiscreteTF(1, z - sp.Rational(1, 2), dt=dt1) * DiscreteTF(1, z, dt=dt2)


@pytest.mark.parametrize(("dt1", "dt2", "dt"), DT_COMBINED)
def test_tf_product_combines_equal_or_unspecified_sampling_times(dt1, dt2, dt):
    G = DiscreteTF(1, z - sp.Rational(1, 2), dt=dt1) * DiscreteTF(1, z, dt=dt2)
    assert G.dt == (None if dt is None else sp.sympify(dt))


def _first(dt):
    return Realization([[sp.Rational(1, 2)]], [[1]], [[1]], 0, dt)


@pytest.mark.parametrize(("dt1", "dt2"), DT_REFUSED)
def test_series_refuses_incompatible_sampling_times_naming_the_part(dt1, dt2):
    with pytest.raises(ParameterError, match=r"parts\[2\]: incompatible sampling times"):
        Realization.series(_first(dt1), _first(dt1), _first(dt2))


@pytest.mark.parametrize(("dt1", "dt2", "dt"), DT_COMBINED)
def test_series_combines_equal_or_unspecified_sampling_times(dt1, dt2, dt):
    R = Realization.series(_first(dt1), _first(dt2))
    assert R.dt == (None if dt is None else sp.sympify(dt))


# ---------------------------------------------------------------- floating-point inputs


def _paper_float_G2():
    f = factor(controller_tf(2), 1, 1)
    gains = lqr_gains(augment(MuscleModel(), 1, 1)).substitutions()
    return f, gains, f.G2.subs(gains).subs({C_1: 1, C_3: 1})


def _float_cases():
    _, _, G2 = _paper_float_G2()
    R = random_realization(G2, rng=0)
    G2_eps = G2.subs({k: v for k, v in R.params.items() if k != "P"})
    return {
        "ccr-float-gains": (controllable_canonical(G2), G2),
        "ocr-float-gains": (observable_canonical(G2), G2),
        "paper-random-realization": (R, G2_eps),
        "float-pole": (Realization([[0.1]], [[1]], [[1]], 0), 1 / (z - sp.Rational(1, 10))),
        "float-gain-scalar": (
            Realization([[0.3]], [[1]], [[0.1 * (1 + 2**-52)]], 0),
            0.1 / (z - 0.3),
        ),
    }


FLOAT_CASES = list(_float_cases().items())


@pytest.mark.parametrize(("name", "case"), FLOAT_CASES, ids=[n for n, _ in FLOAT_CASES])
def test_float_inputs_get_a_numeric_verdict_beside_the_exact_one(name, case):
    R, G = case
    result = check_realization(R, G)
    assert result.floating
    assert result.max_relative_difference < 1e-14
    assert result.numeric_ok and result.rtol == 1e-9
    assert bool(result)
    text = str(result)
    assert "floating-point inputs" in text and "rtol" in text
    assert r"\approx" in result.latex() or "exact proof" in result.latex()


@pytest.mark.parametrize("method", ["exact", "randomized", "auto"])
def test_float_inputs_that_really_differ_are_refused_numerically(method):
    R = Realization([[0.5]], [[1]], [[1.0]], 0)
    result = check_realization(R, 1 / (z - 0.25), method, rng=1)
    assert result.floating and not result.ok and not result.numeric_ok and not result
    assert result.max_relative_difference > 0.1
    assert "differ" in str(result)


def test_exact_inputs_keep_the_exact_proof_and_no_numeric_fields():
    G = (z + 2) / (z**2 - z / 2)
    result = check_realization(controllable_canonical(G), G)
    assert result.ok and not result.floating
    assert result.max_relative_difference is None and result.numeric_ok is None
    assert str(result).startswith("realizes G: proved exactly")


@pytest.mark.parametrize("rtol", [0, -1, 1, 2, float("nan"), float("inf")])
def test_rtol_out_of_range_is_refused(rtol):
    with pytest.raises(ParameterError, match="rtol"):
        check_realization(Realization([[0.5]], [[1]], [[1]], 0), 1 / (z - 0.5), rtol=rtol)


def test_tight_rtol_turns_the_numeric_verdict():
    _, _, G2 = _paper_float_G2()
    result = check_realization(controllable_canonical(G2), G2, rtol=1e-300)
    assert not result and result.floating and not result.numeric_ok


FACTOR_VALUES = [
    {epsilon_1: 0.3, epsilon_3: -0.2, C_1: 1, C_3: 1},
    {epsilon_1: 0.631, epsilon_3: 0.247, C_1: 0.5, C_3: 2.0},
    {epsilon_1: sp.Rational(1, 3), epsilon_3: 0.1},
]


@pytest.mark.parametrize("values", FACTOR_VALUES)
def test_factorization_with_float_values_verifies_numerically(values):
    f, gains, _ = _paper_float_G2()
    proof = f.subs(gains).subs(values).verify()
    assert proof
    assert proof.method.startswith("floating-point coefficients")
    assert "rtol = 1e-09" in proof.method


def test_factorization_exact_proof_is_unchanged_for_exact_values():
    f = factor(controller_tf(2), 1, 1).subs({epsilon_1: sp.Rational(1, 3)})
    proof = f.verify()
    assert proof and proof.method.startswith("cross-multiplied")


@pytest.mark.slow
def test_notebook_02_shows_the_honest_verdict_for_the_paper_random_realization(tmp_path):
    from pathlib import Path

    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    path = Path(__file__).parents[2] / "notebooks" / "02_factorization_and_realizations.ipynb"
    nb = nbformat.read(path, as_version=4)
    nbclient.NotebookClient(
        nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    ).execute()
    shown = [
        str(data)
        for cell in nb.cells
        if cell.cell_type == "code" and "R.params.items()" in cell.source
        for out in cell.get("outputs", [])
        for data in out.get("data", {}).values()
    ]
    assert shown
    assert not any(r"\ne G(z)" in text for text in shown)
    assert any("floating-point inputs" in text for text in shown)
