"""Save and load: every public value pickles and comes back equal; results.json loads back."""

from __future__ import annotations

import inspect
import json
import pickle
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

import symctl
from symctl import (
    DiscreteTF,
    MuscleModel,
    ParameterError,
    Realization,
    augment,
    derive,
    load_results,
    lqr_gains,
    z,
)
from symctl.model.presets import muscle
from symctl.model.saved import model_from_dict

PUBLIC_CLASSES = sorted(
    name
    for name in symctl.__all__
    if inspect.isclass(getattr(symctl, name)) and not issubclass(getattr(symctl, name), Exception)
)
ERRORS = sorted(
    name
    for name in symctl.__all__
    if inspect.isclass(getattr(symctl, name)) and issubclass(getattr(symctl, name), Exception)
)


def _walk(obj, found: dict, depth: int = 0, seen=None) -> None:
    """Every public value inside ``obj`` (fields, items), the first of each class."""
    seen = set() if seen is None else seen
    if id(obj) in seen or depth > 6:
        return
    seen.add(id(obj))
    name = type(obj).__name__
    if type(obj).__module__.startswith("symctl") and name in PUBLIC_CLASSES:
        found.setdefault(name, obj)
    if hasattr(obj, "__dataclass_fields__"):
        for f in obj.__dataclass_fields__:
            _walk(getattr(obj, f, None), found, depth + 1, seen)
    elif isinstance(obj, tuple | list):
        for x in obj[:6]:
            _walk(x, found, depth + 1, seen)
    elif hasattr(obj, "values") and callable(obj.values) and not isinstance(obj, np.ndarray):
        for x in list(obj.values())[:8]:
            _walk(x, found, depth + 1, seen)


@pytest.fixture(scope="module")
def values(derived_T2) -> dict:
    """One value of every public class: from the paper's derivation, the rest made small."""
    found: dict = {}
    _walk(derived_T2, found)
    gains = derived_T2.gains
    circuit = derived_T2.circuits["observable"].circuit
    F = np.zeros((2, 1, 1))
    H = np.array([-0.01, -0.03]).reshape(2, 1, 1)
    data = symctl.synthetic_traces(gains, sensor_delay=1, actuator_delay=1, rng=3)
    rec = {n: data.traces[n] for n in ("G2.x1", "G2.x2", "G2.y")}
    G = -sp.Rational(1, 20) / (z**2 + z / 2 + sp.Rational(1, 3))
    made = {
        "MuscleModel": lambda: MuscleModel(),
        "Linearization": lambda: MuscleModel().linearize_symbolic(),
        "Neuron": lambda: circuit.neurons[0],
        "Synapse": lambda: circuit.synapses[0],
        "CircuitSystem": lambda: circuit.as_linear_system(),
        "FiringSummary": lambda: derived_T2.circuits["general"].firing.summary(),
        "RealizerResult": lambda: symctl.get_realizer("general")(derived_T2.factors.G2),
        "BatchResponse": lambda: symctl.simulate_batch(MuscleModel(), F, H, np.ones((2, 1, 1)), F),
        "LoopStability": lambda: symctl.loop_stability(
            MuscleModel(), Realization([[0]], [[-0.05]], [[1]], 0)
        ),
        "DelaySearch": lambda: symctl.longest_delay(None, max_delay=1, steps=30),
        "Traces": lambda: data,
        "FitResult": lambda: symctl.fit(rec, gains, sensor_delay=1, actuator_delay=1, C=1),
        "Identifiability": lambda: symctl.identifiability(
            [["G2.y"]], gains, sensor_delay=1, actuator_delay=1, C=1
        )[0],
        "DaleResult": lambda: symctl.dale(gains, circuit="general"),
        "EICircuit": lambda: symctl.ei_circuit(
            G, sensor_delay=1, actuator_delay=1, circuits=["observable"]
        ),
        "Pattern": lambda: next(iter(derived_T2.atlas.classes)).pattern,
        "DaleTable": lambda: symctl.dale_atlas(2, samples=2, classes=["A1"]),
        "SavedDerivation": lambda: symctl.SavedDerivation(derived_T2.to_dict(), derived_T2.spec),
        "Realizer": lambda: symctl.get_realizer("controllable"),
        "Proof": lambda: derived_T2.verified,
        "Noise": lambda: symctl.Noise(process=0.1, sensor=[[0.02]], signal_dependent=0.1),
        "MonteCarlo": lambda: symctl.monte_carlo(
            gains, noise=symctl.Noise(process=0.1), count=4, steps=10
        ),
        "KalmanGains": lambda: symctl.kalman_gains(gains.system, C=[[1]], W=0.1, V=0.01),
    }
    if _has_nengo():  # the spiking extra
        ifp = derived_T2.circuits["ifp"].firing.circuits[0]
        made["SpikingResponse"] = lambda: symctl.spiking_response(gains, ifp, n_neurons=5)
        made["SpikingCost"] = lambda: symctl.spiking_cost(
            derived_T2, circuits=["ifp"], neurons=(5,), seeds=1
        )
    for name, make in made.items():
        if name not in found:
            found[name] = make()
    found["Derivation"] = derived_T2
    return found


SPIKING = {"SpikingResponse", "SpikingCost"}  # made only with the spiking extra


def _has_nengo() -> bool:
    try:
        import nengo  # noqa: F401
    except ImportError:
        return False
    return True


def test_every_public_class_has_a_value_here(values):
    extra = set() if _has_nengo() else SPIKING
    assert set(PUBLIC_CLASSES) - {"PaperResults"} - extra <= set(values)


@pytest.mark.parametrize("name", [n for n in PUBLIC_CLASSES if n != "PaperResults"])
def test_every_public_value_pickles_and_loads_equal(values, name):
    if name in SPIKING and name not in values:
        pytest.skip("pip install symctl[spiking]")
    value = values[name]
    loaded = pickle.loads(pickle.dumps(value))
    assert type(loaded) is type(value)
    assert loaded == value
    try:
        expected = hash(value)
    except TypeError:  # a value with a mutable-looking field is not hashed; equal is enough
        return
    assert hash(loaded) == expected


@pytest.mark.parametrize("name", ERRORS)
def test_every_error_pickles_with_its_message(name):
    cls = getattr(symctl, name)
    exc = cls("x: a message") if name != "ModelFileError" else cls("a problem", path="m.toml")
    loaded = pickle.loads(pickle.dumps(exc))
    assert type(loaded) is cls and str(loaded) == str(exc)


coefficient = st.integers(-9, 9).map(lambda k: sp.Rational(k, 4))


@settings(max_examples=examples(25))
@given(num=st.lists(coefficient, min_size=1, max_size=3), den=st.lists(coefficient, max_size=3))
def test_a_transfer_function_pickles_equal(num, den):
    G = DiscreteTF(
        sp.Poly(num, z).as_expr(), sp.Poly([1, *den], z).as_expr(), dt=sp.Rational(1, 100)
    )
    assert pickle.loads(pickle.dumps(G)) == G


@settings(max_examples=examples(8))
@given(
    tau=st.sampled_from([0.01, 0.02, 0.05, 0.3]),
    delays=st.tuples(st.integers(0, 3), st.integers(1, 3)),
    seed=st.integers(0, 2**32 - 1),
    q=st.sampled_from([1, 2.5, [[3]]]),
)
def test_a_model_saved_as_json_or_pickle_loads_equal(tau, delays, seed, q):
    m = muscle().replace(tau=tau, sensor_delay=delays[0], actuator_delay=delays[1], seed=seed, Q=q)
    assert model_from_dict(json.loads(json.dumps(m.to_dict()))) == m
    assert pickle.loads(pickle.dumps(m)) == m
    assert hash(pickle.loads(pickle.dumps(m))) == hash(m)


@settings(max_examples=examples(10))
@given(st.lists(st.floats(-2, 2), min_size=3, max_size=3))
def test_gains_pickle_equal_for_any_weights(q):
    Q = [[1 + abs(q[0])]]
    gains = lqr_gains(augment(MuscleModel(), 1, 1, Q=Q, R=[[1 + abs(q[1])]]))
    assert pickle.loads(pickle.dumps(gains)) == gains


SAVE = textwrap.dedent(
    """
    import pickle, sys
    from symctl import derive_paper
    res = derive_paper(realizations=2, seed=5)
    res.write(sys.argv[1] + "/paper", figures=False, pdf=False)
    with open(sys.argv[1] + "/derivation.pickle", "wb") as f:
        pickle.dump(res, f)
    """
)


@pytest.fixture(scope="module")
def saved_elsewhere(tmp_path_factory):
    """A derivation written and pickled by another process."""
    folder = tmp_path_factory.mktemp("saved")
    subprocess.run([sys.executable, "-c", SAVE, str(folder)], check=True, timeout=600)
    return folder


def test_a_derivation_pickled_in_one_process_loads_equal_in_another(saved_elsewhere):
    here = derive(muscle().replace(realizations=2, seed=5))
    with open(saved_elsewhere / "derivation.pickle", "rb") as f:
        loaded = pickle.load(f)
    assert loaded == here
    assert loaded.to_dict() == here.to_dict()


def test_results_json_written_in_one_process_loads_its_objects_in_another(saved_elsewhere):
    saved = load_results(saved_elsewhere / "paper" / "results.json")
    here = derive(muscle().replace(realizations=2, seed=5))
    assert saved.model == here.spec
    assert saved.derive() is here
    assert np.array_equal(saved.K, here.gains.K)  # the numbers, exactly (JSON keeps a float)
    assert np.array_equal(saved.poles, here.gains.poles)
    assert saved.G_symbolic == here.G_symbolic  # the symbolic objects, exact
    for k in ("G1", "G2", "G3"):
        assert sp.cancel(saved.factors[k] - getattr(here.factors, k).expr) == 0, k
    for name, rec in here.realizations.items():
        for key in "FHMN":
            assert saved.realizations[name]["symbolic"][key] == getattr(rec.symbolic, key)
    sim = saved.simulation  # the figures' data
    assert np.array_equal(sim["t"], here.closed_loop.t)
    assert np.array_equal(sim["closed_loop"]["delta_f"], here.closed_loop.delta_f[:, 0])
    peaks = here.circuits["general"].firing.summary().peak
    assert np.array_equal(saved.peak_firing["general"]["G2.x1"], peaks[:, 0], equal_nan=True)
    assert saved == load_results(saved_elsewhere / "paper")  # the folder reads the same


def test_a_matrix_controller_loads_its_symbolic_objects(derived_oculomotor, tmp_path):
    derived_oculomotor.write(tmp_path / "o", figures=False, pdf=False)
    saved = load_results(tmp_path / "o")
    assert saved.G_symbolic == derived_oculomotor.G_symbolic
    G2 = derived_oculomotor.factors.G2
    assert (saved.factors["G2"] - G2.num_matrix / G2.den).applyfunc(sp.cancel).is_zero_matrix
    # the same derivation again: the cached one, or (evicted by other tests) an equal one
    from symctl.report.results import results_json

    assert results_json(saved.derive()) == results_json(derived_oculomotor)


def test_an_expression_beyond_the_parser_bounds_is_read_in_pieces():
    from symctl._util.parse import MAX_OPERATORS
    from symctl.derivation.load import parse_saved

    K = sp.symbols("K_0:300", real=True)
    e = sum((k - i) ** 2 / (i + 1) for i, k in enumerate(K)) * K[0] - K[1] ** 3
    text = sp.sstr(e)
    assert sum(text.count(c) for c in "+-*/(") > MAX_OPERATORS  # one call would refuse it
    assert parse_saved(text, {}, "e") == e


@pytest.mark.parametrize(
    ("content", "word"),
    [("{", "is not JSON"), ("[]", "is not a results.json"), ('{"gains": 1}', "lacks")],
)
def test_load_results_refuses_what_is_not_a_results_json(tmp_path, content, word):
    path = tmp_path / "results.json"
    path.write_text(content)
    with pytest.raises(ParameterError, match=word):
        load_results(path)


def test_saved_text_is_parsed_never_evaluated(tmp_path, derived_T2):
    data = derived_T2.to_dict()
    data["controller"]["symbolic"]["denominator"] = "__import__('os').system('x')"
    path = tmp_path / "results.json"
    path.write_text(json.dumps(data))
    saved = load_results(path)  # the numbers load; the text is parsed when asked for
    with pytest.raises(symctl.ParseError):
        _ = saved.G_symbolic


@pytest.mark.parametrize(
    "transform",
    [
        {"of": "controllable", "P": [[1, 0], [0, 1]]},  # not text: refused by the parser
        {"of": "nowhere", "P": [["1", "0"], ["0", "1"]]},
        {"of": "controllable", "P": "eye(2)"},
        {"of": "controllable", "P": [["1", "0"], ["0", "0"]]},  # singular
        {"of": "controllable", "P": [["1"]]},  # the wrong shape
    ],
)
def test_a_written_transform_is_read_back_or_refused_by_name(tmp_path, derived_T2, transform):
    data = derived_T2.to_dict()
    symbolic = data["factorization"]["realizations"]["general"]["symbolic"]
    symbolic.update(F=None, H=None, M=None, transform=transform)
    path = tmp_path / "results.json"
    path.write_text(json.dumps(data))
    with pytest.raises(symctl.SymctlError, match="general"):
        _ = load_results(path).realizations


def test_a_transform_is_multiplied_out_on_loading(tmp_path, derived_T2):
    data = derived_T2.to_dict()
    symbolic = data["factorization"]["realizations"]["general"]["symbolic"]
    symbolic.update(
        F=None, H=None, M=None, transform={"of": "controllable", "P": [["2", "1"], ["1", "1"]]}
    )
    path = tmp_path / "results.json"
    path.write_text(json.dumps(data))
    got = load_results(path).realizations["general"]["symbolic"]
    base = derived_T2.realizations["controllable"].symbolic
    P = sp.Matrix([[2, 1], [1, 1]])
    for k, expected in (("F", P.inv() * base.F * P), ("H", P.inv() * base.H), ("M", base.M * P)):
        assert (got[k] - expected).applyfunc(sp.cancel).is_zero_matrix
