"""derive_paper beyond EXPANDED_ZEROS_MAX sections: the abbreviated G2, proved, in results.json."""

from __future__ import annotations

import json
from pathlib import Path

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


FOREARM = Path(__file__).resolve().parents[1] / "data" / "forearm_long_delays.toml"


def test_a_forearm_at_T_8_writes_its_factors_as_products(tmp_path):
    # over a common denominator G1 has 18,000 characters here, and the MIMO G2 and its
    # realizations expanded have 2^8 monomials per coefficient: a 1.35 MB results.json
    from symctl import derive, load_model, load_results

    res = derive(load_model(FOREARM))
    assert res.abbreviated and res.system.T == 8
    res.write(tmp_path, figures=False, pdf=False)
    text = (tmp_path / "results.json").read_text()
    j = json.loads(text)["factorization"]
    assert len(j["G1"]) < 300 and len(j["G3"]) < 150 and len(j["G2"]) < 800
    assert len(j["abbreviations"]) == 2 * 8
    for name in ("controllable", "observable"):
        assert len(json.dumps(j["realizations"][name])) < 20_000
    # the dense general realization P^-1 F0 P (a drawn 16 x 16 P: 161 KB of 38-digit
    # rationals) is written as its base and P, and multiplied out again on loading
    general = j["realizations"]["general"]["symbolic"]
    assert general["F"] is None and general["transform"]["of"] == "controllable"
    assert len(text) < 200_000
    assert (tmp_path / "derivation.tex").stat().st_size < 60_000
    saved = load_results(tmp_path / "results.json")
    assert sp.cancel(saved.factors["G1"][1, 1] - res.factors.G1.expr[1, 1]) == 0
    loaded = saved.realizations["general"]["symbolic"]
    for k in "FHMN":
        assert loaded[k] == sp.ImmutableMatrix(getattr(res.realizations["general"].symbolic, k))


def test_a_small_general_realization_is_written_out(tmp_path):
    res = derive_paper(sensor_delay=2, actuator_delay=2)  # order 4: a drawn P, short texts
    general = res.to_dict()["factorization"]["realizations"]["general"]["symbolic"]
    assert "transform" not in general and all(general[k] for k in "FHM")
