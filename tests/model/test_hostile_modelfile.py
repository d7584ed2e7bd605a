"""Hostile model files: any value in any field is a symctl error or a model, never a crash."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from helpers import examples
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from symctl import SymctlError, derive, load_model
from symctl.cli import main
from symctl.model.modelfile import read_model

MUSCLE = (Path(__file__).resolve().parents[2] / "examples" / "muscle.toml").read_text()

# every "key = value" line of the muscle file whose value is a plain scalar
FIELDS = [m.start(1) for m in re.finditer(r"^\w+ = (.+?)(?:\s+#.*)?$", MUSCLE, re.M)]

_VALUES = st.one_of(
    st.integers(-(10**30), 10**30),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(max_size=30),
    st.sampled_from(["__import__('os')", "1/0", "x**9**9", "exp(1000)", "f", "r", "[[1]]"]),
    st.lists(st.integers(-3, 3), max_size=3),
    st.booleans(),
)


def _toml(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return json.dumps(value)


@pytest.mark.slow
@settings(max_examples=examples(120), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(FIELDS), _VALUES)
def test_any_value_in_any_field_reads_or_is_refused_in_one_line(start, value):
    end = MUSCLE.index("\n", start)
    line_end = MUSCLE.rfind("#", start, end)
    stop = line_end if line_end != -1 else end
    text = MUSCLE[:start] + _toml(value) + MUSCLE[stop:]
    try:
        load_model(text)
    except SymctlError as err:
        assert "\n" not in str(err)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("old", "new"),
    [
        ('Ts = { value = 0.01, unit = "s" }', "Ts = 1e6"),  # exp(-Ts/tau) underflows to 0
        ('value = 0.02, unit = "s"', 'value = 1e-90, unit = "s"'),  # a zero controller
        ('value = 1.0, unit = "spikes/s"', 'value = 1e90, unit = "spikes/s"'),
    ],
)
def test_a_degenerate_controller_derives_with_a_note_instead_of_failing(old, new):
    res = derive(MUSCLE.replace(old, new))
    assert res.to_dict()["controller"]["proved"] is True
    assert any("no atlas circuits" in n for n in res.spec.notes)


def test_a_python_keyword_is_not_a_name():
    with pytest.raises(SymctlError, match="not a Python keyword"):
        load_model(MUSCLE.replace('name = "r"\n', 'name = "lambda"\n'))


def test_windows_line_endings_read_the_same():
    a, b = load_model(MUSCLE), load_model(MUSCLE.replace("\n", "\r\n"))
    assert a.plant == b.plant and a.lines == b.lines


def test_a_folder_or_a_missing_file_is_one_line(tmp_path):
    for path in (tmp_path, tmp_path / "missing.toml"):
        with pytest.raises(SymctlError, match="cannot read it"):
            load_model(path)


def test_a_huge_matrix_is_refused_before_any_work():
    rows = ", ".join("[" + ", ".join(["1"] * 30) + "]" for _ in range(30))
    text = f'[model]\nname = "big"\n[discrete]\nA = [{rows}]\nB = [[1]]\n[sampling]\nTs = 0.1\n'
    with pytest.raises(SymctlError, match="at most 20"):
        load_model(text)


def _discrete_mimo(n: int, m: int, T: int) -> str:
    import numpy as np

    rng = np.random.default_rng(0)
    A = (rng.normal(size=(n, n)) / np.sqrt(n) * 0.9).round(3).tolist()
    B = rng.normal(size=(n, m)).round(3).tolist()
    return (
        f'[model]\nname = "big"\n[discrete]\nA = {A}\nB = {B}\n[sampling]\nTs = 0.01\n'
        f"[delays]\nsensor = {T // 2}\nactuator = {T - T // 2}\n"
    )


@pytest.mark.slow
def test_mimo_circuits_are_bounded_in_size_and_say_what_they_leave_out():
    res = derive(_discrete_mimo(6, 3, 4))  # block forms of 72 states: no circuits
    assert res.circuits == {} and "up to 48 states" in res.skipped
    mid = derive(_discrete_mimo(3, 2, 3))  # 18 states: no dense general one, randomized checks
    assert set(mid.circuits) == {"controllable", "observable"} and "general" in mid.skipped
    methods = {rec.check_symbolic.method for rec in mid.realizations.values()}
    assert "randomized" in methods and all(
        r.check_numeric.method == "exact" for r in mid.realizations.values()
    )


RHS = '"f_max / (tau * (1 + exp(-r))) - f / tau"'


@pytest.mark.parametrize("name", ["E", "pi"])
def test_a_parameter_named_like_a_constant_is_refused_naming_the_constant(name):
    text = MUSCLE.replace("[parameters]\n", f"[parameters]\n{name} = 2.0\n")
    with pytest.raises(SymctlError, match=rf":\d+: parameters.{name}: '{name}' is the constant"):
        load_model(text)


def test_an_undeclared_E_is_eulers_number_with_a_note_saying_so():
    model = load_model(MUSCLE.replace(RHS, '"f_max / (tau * (1 + E**(-r))) - f / tau"'))
    assert model.plant == load_model(MUSCLE).plant
    assert any(n.startswith("states[0].rhs: E is Euler's number") for n in model.notes)
    assert not any("Euler" in n for n in load_model(MUSCLE).notes)


@pytest.mark.parametrize(
    "rhs, problem",
    [
        ("f_max / (tau * (1 + e**(-r))) - f / tau", "name 'e' is not allowed.*Euler's number is E"),
        (
            "f_max / (tau * (1 + exp(-r))) - f^2 / tau",
            r"'\^' is not a power .*; use \*\* for powers",
        ),
        ("f_max / (tau * (1 + exp(-r))) - k * f", "name 'k' is not allowed"),
    ],
)
def test_a_bad_name_or_a_caret_is_one_line_naming_file_line_and_field(rhs, problem):
    with pytest.raises(SymctlError, match=rf"^m.toml:\d+: states\[0\].rhs: {problem}"):
        read_model(MUSCLE.replace(RHS, f'"{rhs}"'), "m.toml")


TS = 'Ts = { value = 0.01, unit = "s" }'


@pytest.mark.parametrize("ts, word", [("5", "longer than"), ("1e-07", "under 1e-4 of")])
def test_a_bare_ts_far_from_the_fastest_time_constant_gets_a_note(tmp_path, capsys, ts, word):
    path = tmp_path / "m.toml"
    path.write_text(MUSCLE.replace(TS, f"Ts = {ts}"))
    assert main(["derive", "--check", str(path)]) == 0
    out = capsys.readouterr().out
    assert f"note: sampling.Ts: a number without a unit is in seconds, and Ts = {ts} s" in out
    assert f"{word} the plant's fastest time constant (0.02 s)" in out


@pytest.mark.parametrize("ts", ["0.01", "1e-5", '{ value = 5, unit = "s" }'])
def test_a_bare_ts_near_the_time_constants_or_one_with_a_unit_gets_no_note(ts):
    assert load_model(MUSCLE.replace(TS, f"Ts = {ts}")).notes == ()


def test_the_bare_ts_note_goes_when_the_api_replaces_the_sampling_time():
    model = load_model(MUSCLE.replace(TS, "Ts = 5"))
    assert model.notes and model.replace(dt=0.005).notes == ()
