"""report/results: PaperResults and its records are frozen values, its figures public."""

from __future__ import annotations

import dataclasses

import pytest

from symctl import PaperResults, derive_paper
from symctl.errors import ParameterError
from symctl.report.results import CircuitRecord, RealizationRecord


@pytest.fixture(scope="module")
def res() -> PaperResults:
    return derive_paper(realizations=1)


def test_paper_results_and_records_are_frozen(res):
    rec, circuit = res.realizations["general"], res.circuits["general"]
    for obj, field in ((res, "seed"), (rec, "name"), (circuit, "name")):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(obj, field, None)


def test_the_mappings_inside_are_read_only(res):
    with pytest.raises(TypeError):
        res.circuits["ifp"] = None
    with pytest.raises(TypeError):
        res.realizations["general"] = None
    with pytest.raises(TypeError):
        res.realizations["general"].values["C_1"] = 2


def test_a_record_equals_and_hashes_as_its_copy(res):
    rec = res.realizations["observable"]
    copy = RealizationRecord(**{f.name: getattr(rec, f.name) for f in dataclasses.fields(rec)})
    assert copy == rec and hash(copy) == hash(rec) and copy.values is not rec.values
    other = dataclasses.replace(rec, values={**rec.values, "C_1": 2})
    assert other != rec
    c = res.circuits["ifp"]
    assert dataclasses.replace(c) == c and hash(dataclasses.replace(c)) == hash(c)
    assert isinstance(c, CircuitRecord) and dataclasses.replace(c, name="x") != c


def test_paper_results_compare_by_their_fields(res):
    assert dataclasses.replace(res) == res
    assert dataclasses.replace(res, seed=res.seed + 1) != res


def test_figures_are_reached_by_name(res):
    names = res.figure_names()
    assert names[:3] == ["open_loop", "closed_loop", "delay_graph"] and "nonlinear" in names
    simplified = [n for n in names if n.startswith("simplified_")]
    assert names[-1 - len(simplified)] == "atlas_overview" and len(simplified) == 2
    assert len(names) == 6 + 3 * len(res.circuits) + len(simplified)  # g1g3_structures too
    fig = res.figure("firing_ifp")
    assert type(fig).__name__ == "Figure" and fig.get_axes()
    with pytest.raises(ParameterError, match="name: no figure 'firing_nothing'"):
        res.figure("firing_nothing")


def test_write_without_figures_lists_what_it_wrote(res, tmp_path):
    steps = []
    written = res.write(tmp_path / "new", figures=False, pdf=False, progress=steps.append)
    assert [p.name for p in written] == ["results.json", "derivation.tex", "report.md"]
    assert all(p.exists() for p in written) and steps == ["documents"]
    assert "![" not in (tmp_path / "new" / "report.md").read_text()


def test_long_mimo_factors_are_written_as_products_of_their_sections():
    # a 1 x 2 controller at T = 4 + 4: over a common denominator G1 has 18,000 characters
    from types import SimpleNamespace

    import sympy as sp

    from symctl import augment, controller_tf, factor
    from symctl.derivation.load import parse_saved
    from symctl.report.results import factor_texts

    f = factor(controller_tf(augment(([[0.9, 0.1], [0, 0.8]], [[0], [0.1]]), 4, 4)), 4, 4)
    texts = factor_texts(SimpleNamespace(factors=f, G2_symbolic=f.G2_symbolic, abbreviated=True))
    assert len(texts["G1"]) < 300 and len(texts["G3"]) < 150 and len(texts["G2"]) < 800
    g1 = parse_saved(texts["G1"][2:].split("], [")[0].split(", 0")[0], {}, "G1")
    assert sp.cancel(g1 - f.sensor_sections[0].expr) == 0
    assert texts["G2"].count("(z - epsilon_") == 2 * 8
