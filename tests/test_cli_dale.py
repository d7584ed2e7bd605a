"""``symctl dale``: the verdicts of the paper's controller on the terminal, JSON, bad input."""

from __future__ import annotations

import json

import pytest

from symctl.cli import main


def test_dale_prints_a_verdict_per_circuit(capsys):
    # a timeout far above the work (seconds), so that a loaded machine decides too
    assert main(["dale", "--timeout", "120"]) == 0
    out = capsys.readouterr().out
    assert "general: E/I" in out and "controllable: E/I" in out
    assert "observable: none (proved)" in out and "never with every neuron" in out


def test_dale_of_a_model_that_estimates_its_state_decides_its_lqg_compensator(capsys):
    # the forearm measured by its angle alone: the controller is the LQG compensator, 1 x 1
    # (the full-state gains would be 1 x 2, which Dale's law does not take)
    args = ["dale", "examples/forearm_lqg.toml", "--circuit", "controllable", "--timeout", "5"]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "the LQG compensator of the measured outputs; sensor delay 4" in out
    assert "controllable: " in out


@pytest.mark.slow
def test_dale_json_has_the_verdicts_signs_and_the_cheapest_circuit(capsys):
    assert main(["dale", "--circuit", "controllable,A10", "--ei", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    first, second = data["circuits"]
    assert first["circuit"] == "controllable" and first["feasible"] is True
    assert set(first["signs"].values()) <= {"+", "-"}
    assert second["circuit"] == "A10" and second["feasible"] is False
    assert second["realizes"] is False
    assert data["ei_circuit"]["cost"] == 0 and data["ei_circuit"]["neurons"] == 4


@pytest.mark.parametrize(
    ("args", "word"),
    [
        (["--circuit", "diagonal"], "--circuit"),
        (["--circuit", "A99"], "--circuit"),
        (["--circuit", " , "], "--circuit"),
        (["--timeout", "-1"], "--timeout"),
        (["--timeout", "nan"], "--timeout"),
        (["--sensor-delay", "-1"], "--sensor-delay"),
        (["examples/antagonist.toml"], "SISO"),
        (["no-such-model.toml"], "no-such-model"),
        (["--actuator-delay", "2", "--circuit", "A1"], "--circuit"),
    ],
)
def test_dale_bad_input_is_one_line_and_exit_2(capsys, args, word):
    assert main(["dale", *args]) == 2
    err = capsys.readouterr().err
    assert word in err and len(err.strip().splitlines()) == 1
