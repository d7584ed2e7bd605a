"""``symctl spiking``: the cost table, the figure and spiking.json, end to end; bad input."""

from __future__ import annotations

import json

import pytest
from helpers import need_spiking

from symctl.cli import main

need_spiking("nengo")


def test_spiking_writes_the_table_the_figure_and_the_json(tmp_path, capsys):
    out = tmp_path / "run"
    args = ["spiking", "--neurons", "10,100", "--seeds", "2", "--circuit", "ifp,A17"]
    assert main([*args, "--out", str(out)]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == ["spiking.json", "spiking.md", "spiking_cost.pdf", "spiking_cost.png"]
    data = json.loads((out / "spiking.json").read_text())
    assert data["neurons"] == [10, 100] and data["seeds"] == 2
    assert sorted(r["circuit"] for r in data["circuits"]) == ["A17", "ifp"]
    assert data["atlas_classes"] == ["A17"]
    assert "| circuit | populations |" in (out / "spiking.md").read_text()
    assert data["finding"] in capsys.readouterr().out
    assert not (tmp_path / "run.progress.jsonl").exists()  # removed when the sweep is done


def test_spiking_runs_a_model_files_controller(tmp_path):
    out = tmp_path / "run"
    args = ["spiking", "examples/muscle.toml", "--neurons", "10", "--seeds", "1"]
    assert main([*args, "--circuit", "ifp", "--no-figures", "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["spiking.json", "spiking.md"]


@pytest.mark.parametrize(
    ("args", "word"),
    [
        (["--neurons", "10,ten"], "--neurons"),
        (["--neurons", "0,10"], "--neurons"),
        (["--neurons", "10,20000"], "--neurons"),
        (["--neurons", ","], "--neurons"),
        (["--seeds", "0"], "--seeds"),
        (["--circuit", "nobody", "--neurons", "10", "--seeds", "1"], "--circuit"),
        (["--workers", "0"], "--workers"),
        (["no-such-model.toml"], "no-such-model"),
        (["BAD"], "bad.toml"),
    ],
)
def test_spiking_bad_input_is_one_line_and_exit_2(tmp_path, capsys, args, word):
    bad = tmp_path / "bad.toml"
    bad.write_text("[model\nname = 3\n")
    args = [str(bad) if a == "BAD" else a for a in args]
    assert main(["spiking", *args, "--out", str(tmp_path / "never")]) == 2
    err = capsys.readouterr().err
    assert word in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "never").exists()
