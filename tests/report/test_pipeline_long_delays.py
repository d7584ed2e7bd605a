"""derive_paper beyond EXPANDED_ZEROS_MAX sections: the abbreviated G2, proved, in results.json."""

from __future__ import annotations

import pytest
import sympy as sp

from symctl import derive_paper
from symctl._util.display import descending_str
from symctl.report.spec import EXPANDED_ZEROS_MAX
from symctl.symbols import gain_symbols


@pytest.fixture(scope="module")
def res():
    return derive_paper(sensor_delay=2, actuator_delay=EXPANDED_ZEROS_MAX - 1)


def test_long_delays_realize_the_abbreviated_G2_exactly(res):
    f = res.factors
    assert res.abbreviated and res.G2_symbolic == f.abbreviated()
    assert res.G2_symbolic.subs(f.sigma_values()).equals(f.G2)
    for rec in res.realizations.values():
        assert rec.check_symbolic and rec.check_symbolic.method.startswith("exact")
        assert rec.check_numeric
        assert not rec.symbolic.free_symbols & set(f.poles)  # the zeros enter as sigma only


def test_results_json_of_long_delays(res):
    f = res.factors
    j = res.to_dict()["factorization"]
    T = len(f.poles)
    assert list(j["abbreviations"]) == [f"sigma_{k}" for k in range(1, T + 1)]
    # the product form, nothing multiplied out (the symbol names hold braces: not parseable)
    assert all(f"(z - {p})" in j["G2"] for p in f.poles)
    assert j["G2"].endswith(f"/({descending_str(f.G.den)})")
    assert len(j["G2"]) < 40 * T + len(descending_str(f.G.den))
    K = gain_symbols(T)
    expected = [K[k] + (-1) ** k * s for k, s in enumerate(f.sigma, start=1)]
    assert j["remainder_coeffs"] == [sp.sstr(c) for c in expected]
    assert j["verified"] is True


def test_the_paper_case_is_not_abbreviated():
    res = derive_paper()
    assert not res.abbreviated and res.to_dict()["factorization"]["abbreviations"] == {}
