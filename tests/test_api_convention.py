"""One convention across the API: ``rng``, ``dt``, verdicts; the old spellings still work and warn."""

from __future__ import annotations

import inspect
import json

import numpy as np
import pytest
import sympy as sp
from helpers import examples
from hypothesis import given, settings
from hypothesis import strategies as st

import symctl
from symctl import (
    DelayGraph,
    DiscretePlant,
    MuscleModel,
    ODEModel,
    Realization,
    augment,
    check_compatibility,
    check_realization,
    circuit_firing,
    controller_compatibility,
    controller_tf,
    derive_paper,
    discretize,
    ifp_structure,
    load_model,
    loop_stability,
    lqr_gains,
    nonlinear_check,
    synthetic_traces,
    z,
)
from symctl._util.serial import decode, encode
from symctl.errors import ParameterError, SymctlTypeError

GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
KW = dict(sensor_delay=1, actuator_delay=1)

RNG_FUNCTIONS = (
    "circuit_firing",
    "circuits_for",
    "closed_loop_response",
    "dale_atlas",
    "derive_paper",
    "fit",
    "identifiability",
    "monte_carlo",
    "simulate_batch",
    "simulate_realization",
    "structure_firing",
    "synthetic_traces",
)


@pytest.mark.parametrize("name", RNG_FUNCTIONS)
def test_randomness_is_rng_in_every_public_function(name):
    params = inspect.signature(getattr(symctl, name)).parameters
    assert "rng" in params and "seed" not in params
    assert params["rng"].default == 0  # reproducible by default, as before


def test_every_public_parameter_is_named_rng_not_seed():
    for name in symctl.__all__:
        obj = getattr(symctl, name)
        if inspect.isfunction(obj):
            assert "seed" not in inspect.signature(obj).parameters, name


def test_the_old_seed_keyword_warns_and_draws_the_same_numbers():
    new = circuit_firing("controllable", GAINS, count=2, rng=5)
    with pytest.warns(DeprecationWarning, match="'seed' is deprecated.*'rng'"):
        old = circuit_firing("controllable", GAINS, count=2, seed=5)
    assert old.params == new.params
    np.testing.assert_array_equal(old.firing["G2.x2"], new.firing["G2.x2"])
    a = synthetic_traces(GAINS, **KW, rng=3, steps=20)
    with pytest.warns(DeprecationWarning):
        b = synthetic_traces(GAINS, **KW, seed=3, steps=20)
    np.testing.assert_array_equal(a.traces["G2.y"], b.traces["G2.y"])


def test_an_int_rng_is_the_generator_of_that_seed():
    a = circuit_firing("general", GAINS, count=2, rng=7)
    b = circuit_firing("general", GAINS, count=2, rng=np.random.default_rng(7))
    assert a.params == b.params


def test_derive_paper_takes_rng_and_dt_and_its_old_keywords_warn():
    with (
        pytest.warns(DeprecationWarning, match="'seed'"),
        pytest.raises(ParameterError, match="rng"),
    ):
        derive_paper(seed=-1)
    with pytest.warns(DeprecationWarning, match="'Ts'"), pytest.raises(ParameterError, match="dt"):
        derive_paper(Ts=-1)


def test_giving_a_new_name_and_its_old_one_is_refused():
    with pytest.raises(SymctlTypeError, match="give 'rng' only"):
        circuit_firing("ifp", GAINS, rng=1, seed=1)
    with pytest.raises(SymctlTypeError, match="give 'dt' only"):
        MuscleModel(dt=0.01, Ts=0.01)


def test_the_sampling_time_is_dt_and_Ts_still_works_with_a_warning():
    plant = DiscretePlant([[1]], [[1]], dt=0.1)
    with pytest.warns(DeprecationWarning, match="DiscretePlant: 'Ts'"):
        assert DiscretePlant([[1]], [[1]], Ts=0.1) == plant
    with pytest.warns(DeprecationWarning):
        assert plant.Ts == plant.dt == sp.Float(0.1)
    with pytest.warns(DeprecationWarning):
        assert MuscleModel(Ts=0.02) == MuscleModel(dt=0.02)
    with pytest.warns(DeprecationWarning):
        assert MuscleModel().Ts == 0.01
    x, u = sp.symbols("x u", real=True)
    with pytest.warns(DeprecationWarning):
        old = ODEModel([x], [u], [-x + u], {}, Ts=0.1)
    assert old == ODEModel([x], [u], [-x + u], {}, dt=0.1) and old.dt == 0.1
    with pytest.warns(DeprecationWarning):
        assert discretize([[-1]], [[1]], Ts=1) == discretize([[-1]], [[1]], dt=1)


def test_a_model_files_sampling_time_is_dt_in_python():
    model = load_model("examples/muscle.toml")
    with pytest.warns(DeprecationWarning, match="Model: 'Ts'"):
        assert model.Ts == model.dt == 0.01


def test_the_proof_type_is_public_and_keeps_its_old_import_path():
    from symctl._util.proof import Proof as Old

    assert "Proof" in symctl.__all__ and symctl.Proof is Old
    proof = symctl.prove_controller_tf(augment(MuscleModel(), 1, 1))
    assert isinstance(proof, symctl.Proof) and proof.verdict is True and proof.method


def _verdicts():
    structure = ifp_structure(2)
    G = controller_tf(GAINS.system).subs(GAINS.substitutions(exact=True))
    yield check_realization(Realization([[2]], [[1]], [[1]], 0), 1 / (z - 3))
    yield check_realization(Realization([[3]], [[1]], [[1]], 0), 1 / (z - 3))
    yield check_compatibility(structure, DelayGraph.chain([0]))
    yield controller_compatibility(controller_tf(2), DelayGraph.chain([1, 2]))
    yield loop_stability(MuscleModel().plant(), GAINS)
    yield nonlinear_check(amplitudes=[0.1], steps=20)
    yield symctl.dale(G, circuit="controllable", timeout=10)
    yield symctl.prove_controller_tf(GAINS.system)
    yield symctl.factor(controller_tf(2), 1, 1).verify()
    yield symctl.identifiability([["G2.y"]], GAINS, **KW, C=1)[0]


@pytest.mark.parametrize("result", list(_verdicts()), ids=lambda r: type(r).__name__)
def test_every_verdict_is_truthy_by_its_verdict_with_method_and_evidence(result):
    assert isinstance(result, symctl.proof.Verdict)
    assert result.verdict in (True, False, None)
    assert bool(result) is bool(result.verdict)
    assert isinstance(result.method, str) and result.method
    result.evidence  # noqa: B018 (present, whatever it holds)


def test_the_old_verdict_fields_are_the_verdict():
    r = check_compatibility(ifp_structure(2), DelayGraph.chain([0]))
    assert r.ok is r.verdict is True and r.evidence is r.assignment
    bad = check_realization(Realization([[2]], [[1]], [[1]], 0), 1 / (z - 3))
    assert bad.ok is bad.verdict is False and bad.evidence is bad.counterexample


# ---- to_dict / from_dict


def _results():
    structure = ifp_structure(2)
    yield GAINS
    yield check_realization(Realization([[2]], [[1]], [[1]], 0), 1 / (z - 3))
    yield check_compatibility(structure, DelayGraph.chain([0]))
    yield controller_compatibility(controller_tf(2), DelayGraph.chain([1, 1]))
    yield loop_stability(MuscleModel().plant(), GAINS)
    yield nonlinear_check(amplitudes=[0.1], steps=20)
    yield symctl.prove_controller_tf(GAINS.system)
    yield symctl.factor(controller_tf(2), 1, 1)
    yield symctl.closed_loop_response(GAINS, steps=20)
    noise = symctl.Noise(process=0.1, sensor=[0.01], signal_dependent=0.1)
    yield noise
    yield symctl.closed_loop_response(GAINS, steps=20, noise=noise, draws=3)
    yield symctl.monte_carlo(GAINS, noise=noise, count=10, steps=20)
    yield circuit_firing("general", GAINS, count=2, steps=20, noise=noise, noise_draws=3)
    fp = circuit_firing("general", GAINS, count=2, rng=1, steps=20)
    yield fp
    yield fp.summary()
    yield synthetic_traces(GAINS, **KW, rng=1, steps=20)
    yield symctl.identifiability([["G2.y"]], GAINS, **KW, C=1)[0]
    yield symctl.longest_delay(None, max_delay=1, steps=30)
    yield symctl.get_realizer("general")(symctl.factor(controller_tf(2), 1, 1).G2, rng=0)


@pytest.mark.parametrize("result", list(_results()), ids=lambda r: type(r).__name__)
def test_every_result_round_trips_through_a_json_dict(result):
    data = result.to_dict()
    back = type(result).from_dict(json.loads(json.dumps(data)))
    assert type(back) is type(result) and back.to_dict() == data
    if type(result).__eq__ is not object.__eq__ and not isinstance(result, symctl.Response):
        assert back == result


def test_from_dict_refuses_another_type_and_foreign_classes():
    data = GAINS.to_dict()
    with pytest.raises(ParameterError, match="not a Proof"):
        symctl.Proof.from_dict(data)
    with pytest.raises(ParameterError, match="not a symctl module"):
        symctl.Gains.from_dict({**data, "@module": "os"})
    with pytest.raises(ParameterError, match="not a SymPy class"):
        decode({"@sympy": "__import__", "args": []})
    with pytest.raises(ParameterError, match="tagged SymPy tree"):  # text is never parsed
        decode({"@sympy": "ImmutableDenseMatrix", "shape": [1, 1], "args": ["x**2"]})


_leaves = st.one_of(
    st.integers(-(10**30), 10**30).map(sp.Integer),
    st.fractions(max_denominator=10**6).map(lambda f: sp.Rational(f.numerator, f.denominator)),
    st.floats(allow_nan=False, allow_infinity=False).map(sp.Float),
    st.sampled_from((*sp.symbols("K_0 K_1 epsilon_1", real=True), sp.Symbol("x"), sp.pi)),
)
_symbols = st.sampled_from((*sp.symbols("K_0 K_1 epsilon_1", real=True), sp.Symbol("x")))
_exprs = st.recursive(  # sums, products, small powers and exponentials: no huge numbers
    _leaves,
    lambda e: st.one_of(
        st.tuples(e, e).map(lambda p: sp.Add(*p, evaluate=False)),
        st.tuples(e, e).map(lambda p: sp.Mul(*p, evaluate=False)),
        st.tuples(e, st.integers(0, 3)).map(lambda p: sp.Pow(p[0], p[1], evaluate=False)),
        # negative powers of a symbol only: 0**-1 (an unevaluated zoo) makes SymPy divide by 0
        st.tuples(_symbols, st.integers(-2, -1)).map(lambda p: sp.Pow(*p, evaluate=False)),
        e.map(lambda x: sp.exp(x, evaluate=False)),
    ),
    max_leaves=6,
)


@settings(max_examples=examples(60), deadline=None)
@given(_exprs)
def test_exact_expressions_round_trip_unchanged(expr):
    back = decode(json.loads(json.dumps(encode(expr))))
    assert back == expr and sp.srepr(back) == sp.srepr(expr)


@settings(max_examples=examples(40), deadline=None)
@given(
    st.lists(st.floats(allow_nan=False), min_size=1, max_size=6),
    st.lists(st.complex_numbers(allow_nan=False, allow_infinity=False), max_size=3),
)
def test_arrays_and_complex_numbers_round_trip_unchanged(values, roots):
    arr = np.array(values)
    back = decode(json.loads(json.dumps(encode(arr))))
    np.testing.assert_array_equal(back, arr)
    assert decode(json.loads(json.dumps(encode(tuple(roots))))) == tuple(roots)


def test_paper_results_to_json_is_the_deprecated_name_of_to_dict():
    res = derive_paper()
    with pytest.warns(DeprecationWarning, match="'to_json'.*'to_dict'"):
        assert res.to_json() == res.to_dict()


# ---- names of one concept only


def test_fit_names_the_similarity_entries_pinv_and_q_still_reads_them():
    data = synthetic_traces(GAINS, **KW, rng=3, steps=40)
    res = symctl.fit(data.select(["G2.x1", "G2.y"]).traces, GAINS, **KW, C=1, starts=2, steps=40)
    assert "Pinv[1,1]" in res.params and not any(k.startswith("Q[") for k in res.params)
    with pytest.warns(DeprecationWarning, match="'Q\\[1,1\\]' is deprecated.*'Pinv\\[1,1\\]'"):
        assert res.params["Q[1,1]"] == res.params["Pinv[1,1]"]
    with pytest.warns(DeprecationWarning):
        assert res.identifiable["Q[2,1]"] == res.identifiable["Pinv[2,1]"]
    rows = symctl.identifiability([["G2.x1", "G2.y"]], GAINS, **KW, C=1)
    with pytest.warns(DeprecationWarning):
        assert rows[0].params["Q[1,2]"] == rows[0].params["Pinv[1,2]"]


def test_an_atlas_round_trips_through_its_json_dict():
    A = symctl.atlas(2, workers=1)
    back = symctl.Atlas.from_dict(json.loads(json.dumps(A.to_dict())))
    assert back == A and back.to_dict() == A.to_dict()
    assert [c.label for c in back.classes] == [c.label for c in A.classes]


def test_no_public_signature_names_a_type_that_is_not_public():
    results = {"get_realizer": symctl.Realizer, "prove_controller_tf": symctl.Proof}
    for name, cls in results.items():
        annotation = inspect.signature(getattr(symctl, name)).return_annotation
        assert annotation == cls.__name__ and cls.__name__ in symctl.__all__
