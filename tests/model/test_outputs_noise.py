"""Model files that measure some states, through noise: [[outputs]] expr and [noise]."""

from __future__ import annotations

import pytest
import sympy as sp

from symctl import ModelFileError, load_model
from symctl.cli import main

ARM = """\
[model]
name = "arm"

[parameters]
I = { value = 0.06, unit = "kg*m**2" }
k = { value = 1.0, unit = "N*m" }
b = { value = 0.2, unit = "N*m*s" }
r = { value = 0.02, unit = "m" }
L0 = { value = 0.3, unit = "m" }
sigma = 0.01

[[states]]
name = "theta"
unit = "rad"
rhs = "omega"
equilibrium = 0

[[states]]
name = "omega"
unit = "rad/s"
rhs = "(u - k * theta - b * omega) / I"
equilibrium = 0

[[inputs]]
name = "u"
unit = "N*m"

[sampling]
Ts = { value = 5, unit = "ms" }
"""


def _load(extra: str):
    return load_model(ARM + extra)


def _err(extra: str) -> ModelFileError:
    with pytest.raises(ModelFileError) as info:
        _load(extra)
    assert "\n" not in str(info.value)
    return info.value


def test_an_expression_output_is_linearized_at_the_equilibrium_with_parameters():
    m = _load('[[outputs]]\nname = "length"\nexpr = "L0 - r*sin(theta)"\nunit = "m"\n')
    assert m.C == sp.ImmutableMatrix([[-sp.Rational(1, 50), 0]])
    assert m.outputs == (("length", "L0 - r*sin(theta)"),) and m.noise == {}


def test_every_state_measured_without_noise_is_the_full_state_design():
    both = '[[outputs]]\nname = "omega"\n\n[[outputs]]\nname = "a"\nstate = "theta"\n'
    assert _load(both).C is None and _load("").C is None


def test_one_state_measured_gives_its_row_and_default_covariances():
    m = _load('[[outputs]]\nname = "a"\nstate = "theta"\n')
    assert m.C == sp.ImmutableMatrix([[1, 0]]) and m.noise == {}
    full = _load("[noise]\nsensor = [0.1, 0.2]\n")
    assert full.C == sp.eye(2) and full.noise["process"] == sp.eye(2)
    assert full.noise["sensor"] == sp.diag(sp.Rational(1, 10), sp.Rational(1, 5))


def test_noise_takes_numbers_diagonals_matrices_and_parameters():
    m = _load(
        '[[outputs]]\nname = "a"\nexpr = "theta"\n\n[noise]\nmotor = 0.5\nsensor = "sigma**2"\n'
    )
    assert m.noise["sensor"] == sp.ImmutableMatrix([[sp.Rational(1, 10000)]])
    assert m.noise["process"] == sp.zeros(2) and m.noise["motor"] == sp.ImmutableMatrix(
        [[sp.Rational(1, 2)]]
    )
    m = _load("[noise]\nprocess = [[1, 0.5], [0.5, 1]]\n")
    assert m.noise["process"][0, 1] == sp.Rational(1, 2)


@pytest.mark.parametrize(
    ("extra", "field", "problem"),
    [
        ('[[outputs]]\nname = "a"\nexpr = "theta"\nunit = "m"\n', "outputs[0].unit", "contradicts"),
        ('[[outputs]]\nname = "a"\nexpr = "theta"\nstate = "omega"\n', "outputs[0]", "not both"),
        ('[[outputs]]\nname = "a"\nexpr = "theta + sigma*u"\n', "outputs[0].expr", "feedthrough"),
        ('[[outputs]]\nname = "a"\nexpr = "theta + q"\n', "outputs[0].expr", "'q' is not"),
        ('[[outputs]]\nname = "a"\nexpr = "__import__"\n', "outputs[0].expr", ""),
        ("[noise]\nprocess = [[1, 2], [0, 1]]\n", "noise.process", "symmetric"),
        ("[noise]\nprocess = [1, -1]\n", "noise.process", "positive semidefinite"),
        ("[noise]\nsensor = [1, 0]\n", "noise.sensor", "singular"),
        ("[noise]\nsensor = [1, 2, 3]\n", "noise.sensor", "a diagonal of 2 entries"),
        ("[noise]\nmotor = [[1, 0], [0, 1]]\n", "noise.motor", "must be 1 x 1"),
        ("[noise]\nsensors = 1\n", "noise.sensors", "did you mean 'sensor'"),
    ],
)
def test_bad_outputs_and_noise_are_one_line_naming_the_field(extra, field, problem):
    err = _err(extra)
    assert err.field == field and problem in str(err) and err.line is not None


def test_outputs_that_leave_an_unstable_mode_unseen_are_refused():
    unstable = ARM.replace('rhs = "(u - k * theta - b * omega)', 'rhs = "(u - b * omega)')
    with pytest.raises(ModelFileError, match="undetectable") as info:
        load_model(unstable + '[[outputs]]\nname = "a"\nexpr = "omega"\n')
    assert info.value.field == "outputs"
    assert load_model(unstable + '[[outputs]]\nname = "a"\nexpr = "theta"\n').C is not None


def test_the_cli_exits_2_on_a_bad_noise_table(tmp_path, capsys):
    path = tmp_path / "arm.toml"
    path.write_text(ARM + "[noise]\nsensor = 0\n")
    assert main(["derive", "--check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "arm.toml:" in err and "noise.sensor: singular" in err


def test_forearm_angle_only_gives_a_proved_compensator_that_factors_along_the_delays():
    from pathlib import Path

    from symctl import augment, factor, lqr_gains
    from symctl.design.kalman import kalman_gains, lqg_tf, prove_lqg_tf

    text = (Path(__file__).resolve().parents[2] / "examples" / "forearm.toml").read_text()
    outputs = '[[outputs]]\nname = "angle"\nexpr = "theta"\nunit = "rad"\n\n'
    noise = "[noise]\nprocess = [1e-6, 1e-4]\nmotor = 1e-4\nsensor = 1e-4\n\n"
    m = load_model(text.replace("[sampling]", outputs + noise + "[sampling]"))
    s = augment(m.plant, m.sensor_delay, m.actuator_delay, m.Q, m.R)
    kf = kalman_gains(s, m.C, m.noise["process"], m.noise["sensor"], motor=m.noise["motor"])
    G = lqg_tf(s, m.C)
    assert s.T == 6 and G.shape == (1, 1) and G.order == 8 and G.relative_degree == 7
    assert prove_lqg_tf(s, m.C, G)
    assert factor(G, m.sensor_delay, m.actuator_delay).verify()
    numeric = lqg_tf(s, gains=lqr_gains(s), kalman=kf)
    assert not numeric.free_symbols and max(abs(numeric.poles())) < 1


def test_derive_runs_a_model_that_estimates_its_state_and_writes_its_estimation(tmp_path):
    import json

    path = tmp_path / "arm.toml"
    path.write_text(ARM + '[[outputs]]\nname = "a"\nexpr = "theta"\n')
    out = tmp_path / "out"
    assert main(["derive", str(path), "--out", str(out), "--no-figures", "--no-pdf"]) == 0
    data = json.loads((out / "results.json").read_text())
    assert data["controller"]["proved"] is True
    assert data["estimation"]["form"] == "predictor" and data["estimation"]["L_names"]
