"""The shipped examples: each runs through symctl derive, and the muscle is symctl paper."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from symctl import derive, derive_paper, load_model, longest_delay, nonlinear_check
from symctl.cli import main
from symctl.model.presets import muscle_text
from symctl.report.spec import PAPER

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
NAMES = (
    "muscle",
    "oculomotor",
    "pendulum",
    "antagonist",
    "spinal_transcortical",
    "forearm",
    "forearm_lqg",
    "oculomotor_position",
)


def test_every_example_is_shipped_and_listed():
    assert sorted(p.stem for p in EXAMPLES.glob("*.toml")) == sorted(NAMES)


def test_the_packaged_muscle_preset_is_the_example_file():
    assert muscle_text() == (EXAMPLES / "muscle.toml").read_text()


def test_the_muscle_file_holds_the_papers_numbers():
    m = load_model(EXAMPLES / "muscle.toml")
    values = {str(k): float(v) for k, v in m.ode.params.items()}
    assert values == {"tau": PAPER.tau, "f_max": PAPER.f_max, "r_bar": PAPER.r_bar}
    assert (m.dt, m.sensor_delay, m.actuator_delay) == (PAPER.Ts, 1, 1)
    assert (m.seed, m.realizations) == (PAPER.seed, PAPER.realizations)


def test_symctl_derive_on_the_muscle_file_writes_byte_identical_results_to_symctl_paper(tmp_path):
    a, b = tmp_path / "paper", tmp_path / "derive"
    assert main(["paper", "--out", str(a), "--no-figures", "--no-pdf"]) == 0
    assert (
        main(["derive", str(EXAMPLES / "muscle.toml"), "--out", str(b), "--no-figures", "--no-pdf"])
        == 0
    )
    paper, derived = (json.loads((d / "results.json").read_text()) for d in (a, b))
    # the same model: only the file's name (the preset's, the example's) tells them apart
    assert paper["model"]["file"].pop("path") != derived["model"]["file"].pop("path")
    assert paper == derived


@pytest.mark.parametrize("name", NAMES)
def test_derive_check_accepts_every_example(name, capsys):
    assert main(["derive", "--check", str(EXAMPLES / f"{name}.toml")]) == 0
    assert ": ok:" in capsys.readouterr().out


@pytest.fixture(scope="module")
def results():
    return {name: derive(EXAMPLES / f"{name}.toml") for name in NAMES if name != "muscle"}


@pytest.mark.parametrize("name", [n for n in NAMES if n != "muscle"])
def test_every_example_derives_a_proved_stabilizing_controller(results, name):
    res = results[name]
    data = json.loads(json.dumps(res.to_dict(), allow_nan=False))
    assert data["controller"]["proved"] is True
    assert data["closed_loop"]["spectral_radius"] < 1
    assert data["model"]["name"] == name
    assert set(data) >= {"parameters", "plant", "gains", "controller", "simulation", "model"}


def test_the_oculomotor_plant_is_second_order_with_its_pulse_on_the_velocity(results):
    res = results["oculomotor"]
    assert res.plant.n == 2 and res.spec.disturbance[0] == (1,)
    # seconds rounded to steps of 5 ms: 10 ms is 2 steps, 5 ms is 1
    assert (res.spec.sensor_delay, res.spec.actuator_delay) == (2, 1)
    assert res.skipped is not None and "2 states" in res.skipped
    # the plant is linear: the nonlinear loop is the linear one to the ODE tolerance
    assert float(np.max(res.nonlinear.relative_deviation)) < 1e-8


def test_the_pendulum_finds_its_longest_delay_and_the_next_one_fails(results):
    res = results["pendulum"]
    L = res.longest
    assert L is not None and L.limited and L.longest is not None
    assert L.stabilized[-1] is False and all(L.stabilized[:-1])
    # re-run the failing delay by hand: the nonlinear loop does not come back
    spec = res.spec
    unit = spec.disturbance_signal() / spec.disturbance[1]
    from symctl import augment, lqr_gains

    T = L.longest + 1
    gains = lqr_gains(augment(spec.plant, 0, T, Q=spec.Q, R=spec.R))
    chk = nonlinear_check(
        spec.ode, gains, [spec.disturbance[1]], steps=spec.steps, disturbance=unit, fail="mark"
    )
    assert not chk.final_deviation[0] <= L.tolerance


def test_a_linear_plant_is_stabilized_at_every_delay():
    m = load_model(EXAMPLES / "oculomotor.toml")
    res = longest_delay(m.ode, Q=m.Q, R=m.R, max_delay=4, steps=60)
    assert res.stabilized == (True,) * 4 and not res.limited


def test_the_antagonist_pair_runs_end_to_end_with_two_inputs(results):
    res = results["antagonist"]
    assert res.plant.m == 2 and res.G.shape == (2, 4) and res.proved
    assert res.factors.channels == (4, 2) and bool(res.factors.verify())
    assert set(res.circuits) == {"general", "controllable", "observable"}
    for rec in res.realizations.values():
        assert rec.check_symbolic.ok and rec.check_numeric.ok
    for c in res.circuits.values():
        assert c.compatibility.ok and c.firing.max_deviation < 1e-9
    assert "IFP" in res.skipped
    # one receptor per measured state, one muscle per input: theorem 3 decides it exactly
    assert res.graph.sensors == (1, 2, 3, 4) and res.graph.actuators == (6, 7)
    theorem = res.to_dict()["delay_graph"]["theorem"]
    assert theorem["compatible"] and theorem["method"].startswith("theorem 3")
    assert {p["label"] for p in theorem["parts"]} == {
        f"G[{i},{j}]" for i in (1, 2) for j in (1, 2, 3, 4)
    }
    placed = res.circuits["controllable"].compatibility.assignment.vertex_of
    assert [placed[s] for s in res.circuits["controllable"].structure.inputs] == [1, 2, 3, 4]
    assert res.spec.ode.equilibrium_method.startswith("exact")
    eq = res.to_dict()["plant"]["equilibrium"]["states"]
    assert eq["theta"] == 0 and math.isclose(eq["f_flex"], eq["f_ext"])


def _exact_or_large(res) -> bool:
    """Every coefficient of G(z) is exactly 0 or above rounding (no 1e-16 left by floats)."""
    data = res.to_dict()["controller"]
    values = np.ravel(np.array(data["numerator"], dtype=float)).tolist() + data["denominator"]
    return all(v == 0 or abs(v) > 1e-12 for v in values)


def _silent(res) -> list[str]:
    """The neurons that never fire in any circuit's simulations (peak below 1e-9 of the largest)."""
    out = []
    for name, rec in res.circuits.items():
        peaks = {k: float(np.nanmax(np.abs(v))) for k, v in rec.firing.firing.items()}
        top = max(peaks.values())
        out += [f"{name}: {k}" for k, p in peaks.items() if p <= 1e-9 * top]
    return out


def test_the_antagonist_controller_is_reduced_to_its_minimal_order(results):
    res = results["antagonist"]
    red = res.reduction
    assert not red and (red.order, red.minimal_order) == (4, 2) and res.G.order == 2
    assert red.never_driven == ("r_flex + r_ext",) and red.unseen == ("f_flex + f_ext",)
    assert "r_flex + r_ext moves only f_flex + f_ext, which the cost never sees" in red.reason
    data = res.to_dict()["reduction"]
    assert (data["order"], data["minimal_order"], data["reason"]) == (4, 2, red.reason)
    assert data["ties"]["K_{0,21}"] == "-K_{0,11}"
    assert _exact_or_large(res)
    assert _silent(res) == []  # before: the observable circuit's x1..x4 (the pole at 0)


def test_a_two_input_forearm_is_reduced_because_both_inputs_use_one_column():
    res = derive(Path(__file__).resolve().parents[1] / "data" / "forearm_two_inputs.toml")
    red = res.reduction
    assert (red.order, red.minimal_order) == (12, 6) and res.G.order == 6
    assert red.never_driven == ("u_flex + u_ext",)
    assert "the inputs act on the plant through the same column of B" in red.reason
    assert _exact_or_large(res)
    assert _silent(res) == []  # before: 12 of the observable circuit's 26 G2 neurons


@pytest.mark.parametrize("name", ["oculomotor", "pendulum", "spinal_transcortical"])
def test_a_minimal_controller_is_reported_as_it_was(results, name):
    res = results[name]
    assert res.reduction and "reduction" not in res.to_dict()


def test_the_two_pathway_graph_is_checked_beyond_chains(results):
    res = results["spinal_transcortical"]
    assert res.spec.vertices == ("receptor", "spinal", "cortex", "muscle")
    assert not res.graph.is_chain
    assert {k: bool(c.compatibility) for k, c in res.circuits.items()} == {
        "ifp": False,
        "general": True,
        "controllable": True,
        "observable": True,
        "pathways": True,
    }
    # the same circuits as the paper's muscle on a chain: only the graph differs
    paper = derive_paper()
    for k in ("general", "controllable", "observable"):
        assert res.circuits[k].circuit.n_neurons == paper.circuits[k].circuit.n_neurons
    # the theorem decides it exactly, and the pathways circuit uses both loops
    theorem = res.to_dict()["delay_graph"]["theorem"]
    assert theorem["compatible"] and theorem["scope"] == "all realizations"
    assert [p["path"] for p in theorem["parts"]] == [[1, 2, 4], [1, 3, 2, 4]]
    rec = res.circuits["pathways"]
    assert rec.firing.max_deviation < 1e-9 and rec.g2_neurons >= 2
    cortex = {n.name for n in rec.circuit.neurons if n.vertex == 3}
    assert any(name.startswith("P2.G2.") for name in cortex)  # the long part's G2 in cortex
    assert "pathways" not in paper.circuits and paper.pathways.ok  # a unit chain: no extra circuit


@pytest.mark.parametrize("name", ["pendulum", "spinal_transcortical"])
def test_examples_write_their_documents_with_their_own_names(tmp_path, name):
    out = tmp_path / name
    assert (
        main(
            [
                "derive",
                str(EXAMPLES / f"{name}.toml"),
                "--out",
                str(out),
                "--no-pdf",
                "--no-figures",
            ]
        )
        == 0
    )
    tex = (out / "derivation.tex").read_text()
    spec = load_model(EXAMPLES / f"{name}.toml")
    assert spec.title.split(":")[0] in tex
    assert spec.descriptions[spec.signal_names[0][0]] in tex


@pytest.mark.usefixtures("uncached_derive")
def test_a_foreign_exception_in_derive_is_one_line_naming_the_model_file(
    tmp_path, capfd, monkeypatch
):
    def boom(*_a, **_k):
        raise ValueError("singular matrix")

    monkeypatch.setattr("symctl.derivation.pipeline.lqr_gains", boom)
    path = EXAMPLES / "pendulum.toml"
    assert main(["derive", str(path), "--out", str(tmp_path / "o"), "--no-pdf"]) == 2
    err = capfd.readouterr().err.strip()
    assert (
        err
        == f"symctl: error: the LQR step failed on the model file {path}: ValueError: singular matrix"
    )
    assert list(tmp_path.iterdir()) == []


def test_derive_refuses_a_bad_file_in_one_line_with_exit_2(tmp_path, capfd):
    bad = tmp_path / "bad.toml"
    bad.write_text(
        (EXAMPLES / "pendulum.toml").read_text().replace('rhs = "omega"', 'rhs = "omegaa"')
    )
    assert main(["derive", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capfd.readouterr().err.strip()
    assert err.startswith(f"symctl: error: {bad}:") and "states[0].rhs" in err and "\n" not in err


def test_a_model_file_builds_only_the_circuits_it_asks_for(tmp_path):
    text = (EXAMPLES / "muscle.toml").read_text()
    text = text.replace(
        'build = ["ifp", "general", "controllable", "observable"]', 'build = ["observable"]'
    )
    res = derive(text)
    assert list(res.circuits) == ["observable"] and list(res.realizations) == ["observable"]
    data = res.to_dict()
    assert list(data["circuits"]) == ["observable"] and data["model"]["circuits_built"] == [
        "observable"
    ]
    names = res.figure_names()
    assert "firing_observable" in names and not any(n.endswith("_general") for n in names)
    assert (
        derive_paper().circuits["observable"].circuit.n_neurons
        == res.circuits["observable"].circuit.n_neurons
    )


@pytest.mark.parametrize("name", ["forearm_lqg", "oculomotor_position"])
def test_the_examples_that_measure_a_position_only_derive_the_lqg_compensator(results, name):
    res = results[name]
    assert res.spec.C.shape == (1, 2) and res.kalman is not None
    assert res.proved and res.verified and res.G.shape == (1, 1)
    assert res.circuits and all(c.firing.max_deviation <= 1e-9 for c in res.circuits.values())
    assert res.variance.z_score < 4 and "estimation" in res.to_dict()
