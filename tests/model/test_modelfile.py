"""Model files: what they hold, and every bad field refused in one line naming file, line and field."""

from __future__ import annotations

import re
import textwrap

import numpy as np
import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from symctl import ModelFileError, ParameterError, SymctlError, load_model
from symctl.model.schema import FIELDS
from symctl.model.source import key_lines

BASE = """\
[model]
name = "leaky"

[parameters]
k = { value = 2.0, unit = "1/s" }

[[states]]
name = "x"
unit = "N"
rhs = "-k*x + u"

[[inputs]]
name = "u"
unit = "N/s"
equilibrium = 1.0

[sampling]
Ts = 0.1
"""


def _with(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def _err(text: str) -> ModelFileError:
    with pytest.raises(ModelFileError) as info:
        load_model(text)
    err = info.value
    assert "\n" not in str(err)
    return err


def test_a_small_model_file_gives_its_exact_equilibrium_and_plant():
    m = load_model(BASE)
    k = sp.Symbol("k", positive=True)
    assert m.ode.x_eq[0] == 1 / k
    assert m.ode.equilibrium_method.startswith("exact")
    assert m.plant.A[0, 0] == sp.exp(-sp.Rational(1, 5))
    assert sp.simplify(m.plant.B[0, 0] - (1 - sp.exp(-sp.Rational(1, 5))) / 2) == 0
    assert (m.sensor_delay, m.actuator_delay, m.T) == (1, 1, 2)
    assert m.graph.chain_delays == (1, 1)
    assert m.units == {"k": "1/s", "x": "N", "u": "N/s"}


def test_a_malformed_toml_file_names_its_line():
    err = _err(BASE + "\n[delays\nsensor = 1\n")
    assert err.line == BASE.count("\n") + 2 and "not valid TOML" in str(err)


@pytest.mark.parametrize(
    ("old", "new", "field", "near"),
    [
        ("Ts = 0.1", "Tz = 0.1", "sampling.Tz", "Ts"),
        ('rhs = "-k*x + u"', 'rsh = "-k*x + u"', "states[0].rsh", "rhs"),
        ("[sampling]", "[sampling]\n[delay]\nsensor = 1\n[sampling2]", "delay", "delays"),
    ],
)
def test_an_unknown_key_is_refused_with_the_nearest_valid_key(old, new, field, near):
    err = _err(_with(BASE, old, new))
    assert err.field == field and f"did you mean {near!r}" in str(err)
    assert err.line is not None


def test_an_equation_that_names_an_undefined_symbol_names_the_field_and_line():
    err = _err(_with(BASE, '"-k*x + u"', '"-k2*x + u"'))
    assert err.field == "states[0].rhs" and err.line == 10 and "'k2'" in str(err)


def test_an_unknown_state_in_the_disturbance_is_refused():
    text = BASE + '\n[simulation.disturbance]\nstate = "y"\n'
    err = _err(text)
    assert err.field == "simulation.disturbance.state" and "'y' is not a state" in str(err)


def test_a_point_that_is_not_an_equilibrium_is_refused():
    text = _with(BASE, 'rhs = "-k*x + u"', 'rhs = "-k*x + u"\nequilibrium = 3')
    err = _err(text)
    assert "not an equilibrium" in str(err) and err.field.startswith("states")


def test_several_equilibria_and_none_are_refused_with_a_hint():
    several = _with(_with(BASE, '"-k*x + u"', '"-x**2 + u"'), 'unit = "N"\n', "")
    several = several.replace('unit = "N/s"\n', "")
    assert "several equilibria" in str(_err(several))
    none = several.replace('"-x**2 + u"', '"-x**2 - u"')
    assert "no equilibrium" in str(_err(none))
    guessed = several.replace('name = "x"\n', 'name = "x"\nguess = -2.0\n')
    assert float(load_model(guessed).ode.x_bar[0]) == pytest.approx(-1.0)


def test_text_in_the_file_is_never_evaluated(tmp_path):
    marker = tmp_path / "pwned"
    evil = f"__import__('os').system('touch {marker}')"
    for field in ('"-k*x + u"', "1.0"):
        text = _with(BASE, field, repr(evil).replace("'", '"') if field != "1.0" else f'"{evil}"')
        with pytest.raises(SymctlError):
            load_model(text)
    assert not marker.exists()


def test_an_equilibrium_in_the_wrong_unit_is_refused():
    text = _with(BASE, 'rhs = "-k*x + u"', 'rhs = "-k*x + u"\nequilibrium = "1/k"')
    err = _err(text)
    assert err.field == "states[0].equilibrium" and "has unit [s]" in str(err)


def test_units_that_contradict_each_other_are_refused():
    err = _err(_with(BASE, 'unit = "1/s"', 'unit = "s"'))  # k*x in N s, not N/s
    assert err.field == "states[0].rhs" and "unit" in str(err)
    err = _err(BASE + '\n[[outputs]]\nname = "x"\nunit = "m"\n')
    assert err.field == "outputs[0].unit" and "contradicts" in str(err)
    err = _err(_with(BASE, "Ts = 0.1", 'Ts = { value = 0.1, unit = "N" }'))
    assert err.field == "sampling.Ts.unit" and "not a unit of time" in str(err)


def test_a_unit_the_checker_cannot_read_is_never_an_error_where_it_is_not_given():
    text = _with(_with(BASE, 'unit = "1/s"', 'description = "a rate"'), 'unit = "N/s"\n', "")
    assert load_model(text).units == {"x": "N"}


def test_delays_in_seconds_round_up_to_steps_and_say_so():
    text = BASE + "\n[delays]\nsensor = { seconds = 0.25 }\nactuator = { seconds = 0.2 }\n"
    m = load_model(text)
    assert (m.sensor_delay, m.actuator_delay) == (3, 2)
    assert len(m.notes) == 1 and "rounded up to 3 steps" in m.notes[0]


def test_sampling_time_in_milliseconds_is_converted():
    m = load_model(_with(BASE, "Ts = 0.1", 'Ts = { value = 100, unit = "ms" }'))
    assert m.dt == pytest.approx(0.1)


GRAPH = """
[delay_graph]
sensor = "a"
actuator = "c"
[[delay_graph.vertices]]
name = "a"
[[delay_graph.vertices]]
name = "b"
[[delay_graph.vertices]]
name = "c"
[[delay_graph.edges]]
from = "a"
to = "b"
steps = 1
[[delay_graph.edges]]
from = "b"
to = "c"
steps = 1
"""


def test_a_delay_graph_is_ordered_sensor_first_and_actuator_last():
    m = load_model(BASE + GRAPH.replace('sensor = "a"', 'sensor = "a"').replace("", ""))
    assert m.vertices == ("a", "b", "c") and m.graph_given
    assert m.graph.E.tolist() == [[0, 1, 2], [np.inf, 0, 1], [np.inf, np.inf, 0]]


def test_a_delay_graph_whose_sensor_or_actuator_is_missing_is_refused():
    err = _err(BASE + GRAPH.replace('sensor = "a"', 'sensor = "retina"'))
    assert err.field == "delay_graph.sensor" and "'retina' is not a vertex" in str(err)
    assert err.line == BASE.count("\n") + 3
    err = _err(BASE + GRAPH.replace('actuator = "c"', 'actuator = "arm"'))
    assert err.field == "delay_graph.actuator"
    err = _err(BASE + GRAPH.replace('from = "b"\nto = "c"', 'from = "b"\nto = "a"'))
    assert "no path from" in str(err) and err.field == "delay_graph.edges"


def test_outputs_may_leave_states_unmeasured_then_the_model_has_C():
    text = _with(BASE, "[sampling]", '[[outputs]]\nname = "y"\nstate = "x"\n\n[sampling]')
    assert load_model(text).outputs == (("y", "x"),)
    two = _with(
        BASE, "[[inputs]]", '[[states]]\nname = "v"\nrhs = "-v"\nequilibrium = 0\n\n[[inputs]]'
    )
    two = _with(two, 'rhs = "-k*x + u"', 'rhs = "-k*x + u"\nequilibrium = 0.5')
    assert load_model(two + '\n[[outputs]]\nname = "x"\n').C == sp.ImmutableMatrix([[1, 0]])


def test_a_discrete_plant_as_a_transfer_function_is_realized():
    text = textwrap.dedent("""\
        [model]
        name = "tf"
        [discrete]
        numerator = [0.5]
        denominator = [1, -0.9]
        [sampling]
        Ts = 0.01
    """)
    m = load_model(text)
    assert m.ode is None and m.plant.n == 1
    assert m.plant.A[0, 0] == sp.Rational(9, 10)
    improper = text.replace("numerator = [0.5]", "numerator = [1, 0.5]")
    assert "strictly proper" in str(_err(improper))


def test_a_plant_that_no_delayed_controller_can_stabilize_is_refused(tmp_path, capfd):
    text = textwrap.dedent("""\
        [model]
        name = "stuck"
        [discrete]
        A = [[1.2, 0], [0, 0.5]]
        B = [[0], [1]]
        [sampling]
        Ts = 0.01
    """)
    err = _err(text)
    assert err.field == "discrete" and "1.2" in str(err) and "not reachable" in str(err)
    path = tmp_path / "stuck.toml"
    path.write_text(text)
    from symctl.cli import main

    assert main(["derive", "--check", str(path)]) == 2
    line = capfd.readouterr().err.strip()
    assert line.startswith(f"symctl: error: {path}:3: discrete:") and "\n" not in line
    assert load_model(text.replace("[[0], [1]]", "[[1], [1]]")).plant.n == 2


def test_a_missing_sampling_time_or_name_is_refused():
    assert _err(BASE.replace("[sampling]\nTs = 0.1\n", "")).field == "sampling"
    assert "name" in str(_err(BASE.replace('name = "leaky"\n', "")))


@pytest.mark.parametrize(
    ("old", "new", "field"),
    [
        ("Ts = 0.1", "Ts = -0.1", "sampling.Ts"),
        ("Ts = 0.1", 'Ts = "0.1"', "sampling.Ts"),
        ("value = 2.0", "value = inf", "parameters.k.value"),
        ('name = "x"', 'name = "exp"', "states[0].name"),
        ('name = "x"', 'name = "k"', "states[0].name"),
    ],
)
def test_bad_values_name_their_field(old, new, field):
    assert _err(_with(BASE, old, new)).field == field


def test_the_net_delay_is_bounded_and_positive():
    assert _err(BASE + "\n[delays]\nsensor = 0\nactuator = 0\n").field == "delays"
    assert _err(BASE + "\n[delays]\nsensor = 15\nactuator = 15\n").field == "delays"


def test_a_huge_file_is_refused_before_parsing(tmp_path):
    path = tmp_path / "huge.toml"
    path.write_text("# " + "x" * 1_100_000)
    with pytest.raises(ModelFileError, match="larger than"):
        load_model(path)


def test_every_field_of_the_schema_is_documented():
    from pathlib import Path

    doc = (Path(__file__).resolve().parents[2] / "docs" / "model-file.md").read_text()
    for section, keys in FIELDS.items():
        for key in keys:
            if key.startswith("<"):
                continue
            assert re.search(rf"`{re.escape(key)}`", doc), f"{section}.{key} is not documented"


def test_model_file_errors_are_parameter_errors():
    assert issubclass(ModelFileError, ParameterError)


_KEY = st.from_regex(r"[a-z][a-z0-9_]{0,8}", fullmatch=True)


@settings(max_examples=examples(60), deadline=None)
@given(
    st.dictionaries(_KEY, st.dictionaries(_KEY, st.integers(0, 9), max_size=4), max_size=4),
    st.integers(0, 3),
)
def test_key_lines_finds_the_line_of_every_key(doc, blank):
    lines, expected = [], {}
    for table, keys in doc.items():
        lines += [""] * blank + [f"[{table}]"]
        expected[table] = len(lines)
        for key, value in keys.items():
            lines.append(f"{key} = {value}")
            expected[f"{table}.{key}"] = len(lines)
    found = key_lines("\n".join(lines))
    assert {k: found[k] for k in expected} == expected


def test_sensor_and_actuator_lists_give_one_vertex_per_channel():
    two = _with(
        BASE, "[[inputs]]", '[[states]]\nname = "v"\nrhs = "-v + u"\nequilibrium = 1\n\n[[inputs]]'
    )
    two = _with(two, 'rhs = "-k*x + u"', 'rhs = "-k*x + u"\nequilibrium = 0.5')
    graph = (
        GRAPH.replace('sensor = "a"', 'sensor = ["a", "b"]')
        .replace('from = "a"\nto = "b"', 'from = "a"\nto = "c"')
        .replace('[[delay_graph.vertices]]\nname = "c"', '[[delay_graph.vertices]]\nname = "c"')
    )
    m = load_model(two + graph)
    assert m.vertices == ("a", "b", "c") and m.graph.sensors == (1, 2) and m.graph.actuators == (3,)
    # two sensors for one measured state, a vertex twice, one vertex at both ends
    err = _err(BASE + graph)
    assert err.field == "delay_graph.sensor" and "2 sensor vertices for 1 measured state" in str(
        err
    )
    err = _err(two + GRAPH.replace('sensor = "a"', 'sensor = ["a", "a"]'))
    assert err.field == "delay_graph.sensor[1]" and "appears twice" in str(err)
    err = _err(two + GRAPH.replace('sensor = "a"', 'sensor = ["a", "c"]'))
    assert "both a sensor and an actuator" in str(err)
    err = _err(two + GRAPH.replace('sensor = "a"', "sensor = []"))
    assert err.field == "delay_graph.sensor" and "empty list" in str(err)


@pytest.mark.slow
def test_without_sensor_delay_the_controller_sits_after_the_sensor_not_at_it():
    from symctl import derive

    m = load_model(BASE + "\n[delays]\nsensor = 0\nactuator = 2\n")
    assert m.graph.chain_delays == (0, 1, 1) and m.vertices == ("v1", "v2", "v3", "v4")
    res = derive(m)
    where = {n.name: n.vertex for n in res.circuits["controllable"].circuit.neurons}
    assert {v for name, v in where.items() if name.startswith("G2.")} == {2}
    assert where["G3.2.x1"] == 4


@pytest.mark.slow
def test_max_wire_delay_asks_for_unit_wires():
    from symctl import derive

    axon = GRAPH.replace('from = "a"\nto = "b"\nsteps = 1', 'from = "a"\nto = "b"\nsteps = 2')
    axon = axon.replace('from = "b"\nto = "c"\nsteps = 1', 'from = "b"\nto = "c"\nsteps = 0')
    free = derive(load_model(BASE + axon))
    assert free.pathways.ok and "pathways" in free.circuits  # one wire of 2 steps crosses a -> b
    unit = load_model(BASE + axon.replace('actuator = "c"', 'actuator = "c"\nmax_wire_delay = 1'))
    assert unit.max_wire_delay == 1
    res = derive(unit)
    assert not res.pathways.ok and "at most 1 step" in res.pathways.reason
    assert "pathways" not in res.circuits
    err = _err(BASE + axon.replace('actuator = "c"', 'actuator = "c"\nmax_wire_delay = 0'))
    assert err.field == "delay_graph.max_wire_delay"
