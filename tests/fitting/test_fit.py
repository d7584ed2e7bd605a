"""symctl.fit: circuits fitted to recorded firing rates."""

from __future__ import annotations

import inspect
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp
from helpers import bounded, examples
from hypothesis import given, settings
from hypothesis import strategies as st

import symctl
from symctl import (
    DimensionError,
    MuscleModel,
    NotRealizableError,
    ParameterError,
    SymctlTypeError,
    Traces,
    augment,
    check_realization,
    closed_loop_response,
    controller_tf,
    fit,
    identifiability,
    lqr_gains,
    read_traces,
    synthetic_traces,
)
from symctl.cli import main
from symctl.compatibility.structure import Structure
from symctl.fitting.fitmodel import TraceModel
from symctl.neural.circuit import Circuit
from symctl.neural.firing import _drive

CALL_BUDGET = 3_000_000  # about 280,000 calls
GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
G = controller_tf(GAINS.system).subs(GAINS.substitutions(exact=True))
KW = {"sensor_delay": 1, "actuator_delay": 1}
STEPS = 80


@pytest.fixture(scope="module")
def hidden():
    return synthetic_traces(GAINS, **KW, rng=3, steps=STEPS)


def _theta(model, rng):
    k = model.n_sections
    eps = [sp.Rational(int(v), 100) for v in rng.integers(-80, 80, k)]
    cs = [sp.Rational(int(v), 10) for v in rng.integers(5, 20, k)] if model.C is None else [1] * k
    n = model.order
    Q = sp.Matrix(n, n, lambda i, j: sp.Rational(int(rng.integers(-20, 20)), 10) + 3 * (i == j))
    vals = [
        *eps,
        *(cs if model.C is None else []),
        *(list(Q) if model.circuit == "general" else []),
    ]
    return np.array([float(v) for v in vals]), eps, cs, Q


@pytest.mark.parametrize(
    ("circuit", "delays"),
    [(c, d) for c in ("general", "controllable", "observable") for d in ((1, 1), (2, 1))]
    + [("A4", (1, 1))],  # the atlas of order 2 is for T = 2
)
def test_trace_model_equals_the_circuit_driven_by_the_loop(circuit, delays):
    gains = lqr_gains(augment(MuscleModel(), *delays))
    tf = controller_tf(gains.system).subs(gains.substitutions(exact=True))
    cls = inspect.unwrap(symctl.fit).__globals__["_circuit_arg"](circuit)[0]
    model = TraceModel.build(tf, *delays, cls)
    theta, eps, cs, Q = _theta(model, np.random.default_rng(1))
    fs = model.factorization(eps, cs)
    circ = Circuit.from_structure(Structure.from_factorization(fs, model.realize(fs, Q)))
    u = closed_loop_response(gains, steps=40).delta_f[:, 0]
    ref = _drive(circ, u)
    vals, _ = model.traces(theta, u)
    for n in circ.neurons:
        assert np.max(np.abs(vals[n.name] - ref[n.name])) < 1e-12


@pytest.mark.parametrize("C", [None, 1.0])
def test_analytic_jacobian_matches_central_differences(C):
    model = TraceModel.build(G, 1, 1, "general", C)
    theta, *_ = _theta(model, np.random.default_rng(2))
    u = closed_loop_response(GAINS, steps=40).delta_f[:, 0]
    vals, jacs = model.traces(theta, u)
    for j in range(theta.size):
        h = 1e-6
        up, down = theta.copy(), theta.copy()
        up[j] += h
        down[j] -= h
        vp, vm = model.traces(up, u)[0], model.traces(down, u)[0]
        for n in vals:
            fd = (vp[n] - vm[n]) / (2 * h)
            assert np.max(np.abs(fd - jacs[n][:, j])) < 1e-6 * max(1.0, np.max(np.abs(fd)))


def test_noiseless_fit_recovers_the_hidden_circuit_and_its_unrecorded_neurons(hidden):
    rec = ["G2.x1", "G2.x2", "G2.y"]
    res = fit(hidden.select(rec).traces, GAINS, **KW, C=1, steps=STEPS)
    assert res.exact and bool(check_realization(res.realization, G))
    for name, value in res.params.items():
        assert abs(float(value) - float(hidden.hidden[name])) < 1e-5
    pred = res.predict()
    for n in ("G1.x1", "G3.x1"):
        assert res.neuron_identifiable[n]
        scale = np.sqrt(np.mean(hidden.traces[n] ** 2))
        assert np.sqrt(np.mean((pred[n] - hidden.traces[n]) ** 2)) < 1e-5 * scale
    assert max(res.residuals.values()) < 1e-5
    assert all(se is not None for se in res.stderr.values())


def test_behaviour_cannot_drift_the_fitted_circuit_gives_the_optimal_loop(hidden):
    res = fit(hidden.select(["G1.x1", "G2.y"]).traces, GAINS, **KW, starts=2, steps=STEPS)
    ref = closed_loop_response(GAINS, steps=STEPS)
    got = symctl.simulate_realization(MuscleModel(), res.realization, steps=STEPS)
    assert np.max(np.abs(got.delta_r - ref.delta_r)) < 1e-12
    assert np.max(np.abs(res.predict()["G3.x1"] - ref.delta_r[:, 0])) < 1e-12


def test_fitted_realization_agrees_with_scipy_dlsim(hidden):
    from scipy.signal import dlsim

    res = fit(hidden.select(["G1.x1", "G2.x1"]).traces, GAINS, **KW, C=1, starts=2, steps=STEPS)
    F, H, M, N = (
        np.array(m, dtype=float)
        for m in (res.realization.F, res.realization.H, res.realization.M, res.realization.N)
    )
    u = closed_loop_response(GAINS, steps=STEPS).delta_f[:, 0]
    _, y, x = dlsim((F, H, M, N, 0.01), u)
    assert np.max(np.abs(y[:, 0] - res.predict()["G3.x1"])) < 1e-12
    assert np.max(np.abs(x[:, 0] - res.predict()["G1.x1"])) < 1e-12  # G1's state first


@pytest.mark.slow
@settings(max_examples=examples(6), deadline=None)
@given(
    seed=st.integers(0, 10**6),
    recorded=st.sets(st.sampled_from(["G1.x1", "G2.x1", "G2.x2", "G2.y"]), min_size=1),
    circuit=st.sampled_from(["general", "controllable", "observable"]),
    noise=st.sampled_from([0.0, 0.05]),
)
def test_every_fitted_realization_realizes_G_exactly(seed, recorded, circuit, noise):
    data = synthetic_traces(GAINS, **KW, rng=seed, steps=30, noise=noise)
    if circuit == "controllable":
        recorded = recorded - {"G2.x1"} or {"G2.y"}
    res = fit(
        data.select(sorted(recorded)).traces,
        GAINS,
        **KW,
        circuit=circuit,
        starts=2,
        rng=seed,
        steps=30,
    )
    assert res.exact and bool(check_realization(res.realization, G, "exact"))
    assert all(isinstance(v, sp.Rational) for v in res.params.values())


def test_identifiability_per_neuron_set_is_the_rank_of_the_sensitivity():
    a, b = identifiability([["G1.x1", "G2.x1", "G2.y"], ["G2.x1", "G2.x2", "G2.y"]], GAINS, **KW)
    assert (a.rank, a.n_params, b.rank) == (6, 8, 7)
    assert not a.neurons["G2.x2"] and not a.params["Pinv[2,1]"] and a.params["Pinv[1,1]"]
    assert not b.params["C_1"] and not b.neurons["G1.x1"] and b.neurons["G3.x1"]
    (c,) = identifiability([["G1.x1", "G2.x1", "G2.y"]], GAINS, **KW, circuit="observable")
    assert c.rank == c.n_params == 4 and c.neurons["G2.x2"]  # no P to hide behind


def test_unidentifiable_parameters_have_no_standard_error(hidden):
    res = fit(hidden.select(["G1.x1", "G2.x1", "G2.y"]).traces, GAINS, **KW, starts=2, steps=STEPS)
    assert res.stderr["Pinv[2,2]"] is None and not res.identifiable["Pinv[2,2]"]
    assert res.stderr["epsilon_1"] is not None and not res.neuron_identifiable["G2.x2"]
    assert "not identifiable" in res.table()


def test_across_classes_the_best_fit_is_kept(hidden):
    res = fit(
        hidden.select(["G2.x1", "G2.y"]).traces,
        GAINS,
        **KW,
        circuit=["observable", "general"],
        C=1,
        starts=2,
        steps=STEPS,
    )
    assert res.circuit_class == "general" == res.alternatives[0][0]
    assert len(res.alternatives) == 2 and res.alternatives[0][1] <= res.alternatives[1][1]


@pytest.mark.slow
def test_all_classes_skip_those_that_cannot_take_the_data(hidden):
    res = fit(
        hidden.select(["G2.x1", "G2.y"]).traces,
        GAINS,
        **KW,
        circuit="all",
        C=1,
        starts=2,
        steps=STEPS,
    )
    skipped = dict(res.skipped)
    assert "controllable" in skipped and "no such neuron" in skipped["controllable"]
    fitted = {a[0] for a in res.alternatives}
    assert {"general", "observable", "A4"} <= fitted and not fitted & set(skipped)
    with pytest.raises(ParameterError, match="no class can take these traces: controllable"):
        fit(hidden.select(["G2.x1"]).traces, GAINS, **KW, circuit=["controllable"] * 2, steps=STEPS)


def test_dale_signs_hold_on_the_fitted_circuit(hidden):
    res = fit(
        hidden.select(["G2.y", "G1.x1"]).traces,
        GAINS,
        **KW,
        C=1,
        starts=4,
        signs={"G2.x1": "+", "G2.x2": "-"},
        steps=STEPS,
    )
    assert all(sp.sign(s.weight) > 0 for s in res.circuit.neuron("G2.x1").axon)
    assert all(sp.sign(s.weight) < 0 for s in res.circuit.neuron("G2.x2").axon)


@pytest.mark.slow
def test_two_excitatory_state_neurons_are_impossible_with_complex_poles(hidden):
    # F12 F21 > 0 makes F's eigenvalues real; the paper's controller has complex poles
    with pytest.raises(ParameterError, match="no start of 2 gave a circuit that meets the signs"):
        fit(
            hidden.select(["G2.y", "G1.x1"]).traces,
            GAINS,
            **KW,
            C=1,
            starts=2,
            signs={"G2.x1": "+", "G2.x2": "+"},
            steps=STEPS,
        )
    with pytest.raises(ParameterError, match=r"signs\['G2.x7'\]: no such neuron"):
        fit(hidden.select(["G2.y"]).traces, GAINS, **KW, signs={"G2.x7": "+"}, steps=STEPS)
    with pytest.raises(ParameterError, match="expected '\\+' or '-'"):
        fit(hidden.select(["G2.y"]).traces, GAINS, **KW, signs={"G2.x1": 1}, steps=STEPS)


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    ("traces", "options", "error", "match"),
    [
        (
            {"G2.y": np.zeros(STEPS - 1)},
            {},
            DimensionError,
            r"traces\['G2.y'\]: has 79 samples.*80",
        ),
        ({"G2.y": np.r_[np.zeros(STEPS - 1), np.nan]}, {}, ParameterError, r"not finite.*step 79"),
        (
            {"G2.x9": np.zeros(STEPS)},
            {},
            ParameterError,
            r"traces\['G2.x9'\]: no such neuron.*G2.x1",
        ),
        ({"G2.y": np.zeros(STEPS)}, {"steps": 4}, DimensionError, "has 80 samples"),
        ({"G2.y": np.ones(3)}, {"steps": 3}, ParameterError, "3 samples for 8 parameters"),
        ({"G2.y": np.zeros(STEPS)}, {"circuit": "A7"}, NotRealizableError, "class A7 cannot"),
        ({"G2.y": np.zeros(STEPS)}, {"circuit": "A99"}, ParameterError, "no atlas class 'A99'"),
        ({"G2.y": np.zeros(STEPS)}, {"circuit": "diagonal"}, ParameterError, "circuit: expected"),
        ({"G2.x2": np.zeros(STEPS)}, {"circuit": "A1"}, ParameterError, "no such neuron in the A1"),
        ("G2.y", {}, SymctlTypeError, "traces: expected a mapping"),
        ({"G2.y": "1,2"}, {}, SymctlTypeError, r"traces\['G2.y'\]: expected an array"),
        ({}, {}, ParameterError, "no recorded neuron"),
        ({"G2.y": np.zeros(STEPS)}, {"starts": 0}, ParameterError, "starts: must be"),
        ({"G2.y": np.zeros(STEPS)}, {"C": 0}, ParameterError, "C: must be a finite nonzero"),
        ({"G2.y": np.zeros(STEPS)}, {"sensor_delay": 0}, ParameterError, "at least one section"),
    ],
)
def test_bad_input_is_a_clear_error_naming_it(traces, options, error, match):
    kw = {**KW, "steps": STEPS, **options}
    with pytest.raises(error, match=match):
        fit(traces, GAINS, **kw)


def test_one_class_functions_refuse_a_list_or_all():
    with pytest.raises(ParameterError, match="circuit: identifiability takes one class"):
        identifiability([["G2.y"]], GAINS, **KW, circuit="all")
    with pytest.raises(ParameterError, match="circuit: synthetic_traces takes one class"):
        synthetic_traces(GAINS, **KW, circuit=["general"])
    with pytest.raises(ParameterError, match="sensor_delay: must be an integer >= 1"):
        synthetic_traces(GAINS, sensor_delay=0, actuator_delay=1)
    with pytest.raises(ParameterError, match="noise: expected a number in"):
        synthetic_traces(GAINS, **KW, noise=-1)


def test_the_paper_fit_of_3_neurons_500_steps_is_exact_within_a_bounded_work():
    data = synthetic_traces(GAINS, **KW, rng=5, steps=500, noise=0.01)
    with bounded(CALL_BUDGET):
        res = fit(data.select(["G2.x1", "G2.x2", "G2.y"]).traces, GAINS, **KW, steps=500)
    assert res.exact


def test_G_must_be_gains_or_a_numeric_tf_with_its_plant():
    with pytest.raises(SymctlTypeError, match="G: expected Gains"):
        fit({"G2.y": np.zeros(50)}, "K0/z**2", **KW)
    with pytest.raises(ParameterError, match="G: must be numeric"):
        fit({"G2.y": np.zeros(50)}, controller_tf(2), **KW, plant=MuscleModel())
    data = synthetic_traces(GAINS, **KW, rng=1, steps=40)
    res = fit(
        data.select(["G2.y", "G1.x1"]).traces, G, **KW, plant=MuscleModel(), steps=40, starts=2
    )
    assert res.exact and max(res.residuals.values()) < 1e-6


# ---------------------------------------------------------------- data files
def test_csv_and_npz_readers_round_trip(tmp_path, hidden):
    path = hidden.to_csv(tmp_path / "a.csv")
    back = read_traces(path)
    assert back.meta["circuit"] == "general" and back.neurons == hidden.neurons
    assert all(np.array_equal(back.traces[n], hidden.traces[n]) for n in hidden.neurons)
    assert np.array_equal(back.disturbance, hidden.disturbance)
    np.savez(
        tmp_path / "b.npz",
        t=hidden.t,
        disturbance=hidden.disturbance,
        circuit=np.array("observable"),
        **{"G2.y": hidden.traces["G2.y"]},
    )
    npz = read_traces(tmp_path / "b.npz")
    assert npz.meta["circuit"] == "observable" and npz.neurons == ("G2.y",)


@pytest.mark.parametrize(
    ("text", "error", "match"),
    [
        ("G2.y\n1\n2\n", ParameterError, "no time column 't'"),
        ("t\n0\n0.01\n", ParameterError, "no neuron column"),
        ("t,G2.y\n0,1\n0.01,abc\n", ParameterError, "row 2, column 'G2.y': not a number"),
        ("t,G2.y\n0,1\n0.01\n", DimensionError, "row 2 has 1 values"),
        ("t,G2.y\n0,1\n0.01,nan\n", ParameterError, "'G2.y' is not finite"),
        ("t,G2.y\n0,1\n0.01,1\n0.05,1\n", ParameterError, "equal steps"),
        ("t,G2.y,G2.y\n0,1,1\n0.01,1,1\n", ParameterError, "repeats a column"),
        ("t,G2.y\n0,__import__('os')\n0.01,1\n", ParameterError, "not a number"),
    ],
)
def test_bad_data_files_are_refused_naming_the_problem(tmp_path, text, error, match):
    path = tmp_path / "d.csv"
    path.write_text(text)
    with pytest.raises(error, match=match):
        read_traces(path)


def test_read_traces_refuses_other_files(tmp_path):
    with pytest.raises(ParameterError, match="no such file"):
        read_traces(tmp_path / "none.csv")
    (tmp_path / "x.txt").write_text("t\n")
    with pytest.raises(ParameterError, match=r"expected a \.csv or \.npz"):
        read_traces(tmp_path / "x.txt")
    with pytest.raises(SymctlTypeError, match="path: expected a file name"):
        read_traces(3)
    assert Traces(np.arange(2.0), {"G2.y": [0, 1]}).steps == 2


# ---------------------------------------------------------------- CLI
def test_cli_fit_writes_its_files(tmp_path, hidden, capsys):
    data = hidden.select(["G1.x1", "G2.x1", "G2.y"]).to_csv(tmp_path / "d.csv")
    out = tmp_path / "out"
    assert main(["fit", str(data), "--out", str(out), "--starts", "2", "--no-figures"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["fit.json", "predictions.csv", "report.md"]
    line = capsys.readouterr().out
    assert "general circuit (exact realization of G: True)" in line
    pred = read_traces(out / "predictions.csv")
    assert set(pred.neurons) == {"G1.x1", "G2.x1", "G2.x2", "G2.y", "G3.x1"}
    # the folder of an earlier fit is replaced, like an earlier run of symctl paper
    assert main(["fit", str(data), "--out", str(out), "--starts", "2"]) == 0
    assert sorted(p.name for p in out.iterdir()) == [
        "fit.json",
        "fit.pdf",
        "fit.png",
        "fit.svg",
        "predictions.csv",
        "report.md",
    ]


@pytest.mark.parametrize(
    ("column", "args", "match"),
    [
        ("G2.x1", ["--circuit", "A7"], "class A7 cannot realize"),
        ("G2.x9", [], r"traces\['G2.x9'\]: no such neuron"),
        ("G2.x1", ["--model", "examples/oculomotor.toml"], "time step"),
    ],
)
def test_cli_fit_bad_input_is_one_line_exit_2_and_writes_nothing(
    tmp_path, capsys, hidden, column, args, match
):
    data = Traces(hidden.t, {column: hidden.traces["G2.x1"]}, hidden.disturbance)
    path = data.to_csv(tmp_path / "d.csv")
    out = tmp_path / "out"
    assert main(["fit", str(path), "--out", str(out), *args]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("symctl: error:")
    assert __import__("re").search(match, err) and not out.exists()


def test_cli_fit_nan_in_the_data_is_one_line(tmp_path, capsys):
    path = tmp_path / "d.csv"
    path.write_text("t,G2.y\n0,1\n0.01,nan\n")
    assert main(["fit", str(path), "--out", str(tmp_path / "o")]) == 2
    assert "'G2.y' is not finite" in capsys.readouterr().err


def test_the_shipped_example_dataset_fits(tmp_path):
    tr = read_traces("examples/data/paper_fit.csv")
    res = fit(tr.traces, GAINS, **KW, disturbance=tr.disturbance, steps=tr.steps, starts=2)
    assert res.exact and max(res.residuals.values()) < 0.02
    assert not res.neuron_identifiable["G2.x2"] and res.neuron_identifiable["G3.x1"]


@pytest.mark.slow
def test_starts_and_refits_on_a_local_dask_cluster_give_the_serial_fit(tmp_path):
    # a child process, as the atlas's dask test: dask's workers leave a resource tracker
    code = (
        "import symctl\n"
        "from symctl import MuscleModel, augment, lqr_gains, synthetic_traces\n"
        "g = lqr_gains(augment(MuscleModel(), 1, 1))\n"
        "d = synthetic_traces(g, sensor_delay=1, actuator_delay=1, rng=3, steps=60)\n"
        "kw = dict(sensor_delay=1, actuator_delay=1, C=1, starts=4, steps=60, bootstrap=40)\n"
        "tr = d.select(['G2.x1', 'G2.y']).traces\n"
        "a = symctl.fit(tr, g, workers=2, **kw)\n"
        "b = symctl.fit(tr, g, workers=1, **kw)\n"
        "print(a.exact, dict(a.params) == dict(b.params), dict(a.intervals) == dict(b.intervals))\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=240, check=True
    )
    assert run.stdout.strip().splitlines()[-1] == "True True True"  # the bootstrap too
