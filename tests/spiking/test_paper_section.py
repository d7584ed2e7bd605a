"""``symctl paper --spiking``: the cost section, its figure and results.json's ``spiking``."""

from __future__ import annotations

import dataclasses
import json

from helpers import need_spiking

import symctl.spiking.cost as cost_module
from symctl.cli import main

need_spiking("nengo")


def test_paper_spiking_adds_the_section_the_figure_and_the_json(tmp_path, monkeypatch):
    full = cost_module.spiking_cost
    seen = {}

    def small(res, **kw):  # the full sweep takes minutes: two circuits, two sizes, one seed
        seen.update(kw)
        return full(res, circuits=["ifp", "A17"], neurons=(10, 100), seeds=1, **kw)

    monkeypatch.setattr(cost_module, "spiking_cost", small)
    out = tmp_path / "paper"
    args = ["paper", "--spiking", "--no-pdf", "--formats", "png", "--out", str(out)]
    assert main(args) == 0
    assert seen["workers"] == 1 and seen["checkpoint"].name == "paper.progress.jsonl"
    report = (out / "report.md").read_text()
    assert "## What spikes cost each circuit" in report and "spiking_cost.png" in report
    assert (out / "spiking_cost.png").exists()
    data = json.loads((out / "results.json").read_text())
    assert data["spiking"]["neurons"] == [10, 100]
    assert data["spiking"]["finding"] in report.replace("\n", " ")


def test_without_spiking_the_derivation_has_no_cost(derived_T2):
    assert derived_T2.spiking_cost is None
    assert "spiking" not in derived_T2.to_dict()
    assert "spiking_cost" not in derived_T2.figure_names()
    c = cost_module.spiking_cost(derived_T2, circuits=["ifp"], neurons=(10,), seeds=1)
    res = dataclasses.replace(derived_T2, spiking_cost=c)
    assert res.figure_names()[-1] == "spiking_cost"
    assert len(res.figure("spiking_cost").axes) == 2
