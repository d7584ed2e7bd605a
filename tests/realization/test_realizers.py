"""The registry of realizers: names, titles, results with their transform, errors."""

from __future__ import annotations

import dataclasses

import pytest
import sympy as sp

from symctl import (
    MuscleModel,
    ParameterError,
    SymctlTypeError,
    augment,
    controllable_canonical,
    controller_tf,
    factor,
    general_realization,
    ifp_realization,
    lqr_gains,
    observable_canonical,
    random_realization,
    z,
)
from symctl.realization.realizers import (
    REALIZERS,
    RealizerResult,
    circuit_names,
    get_realizer,
    register,
    unregister,
)

G2 = factor(controller_tf(2)).G2


def test_registry_holds_the_five_realizers_with_titles_in_the_reports_order():
    assert list(REALIZERS) == ["ifp", "general", "controllable", "observable", "random"]
    assert circuit_names() == ("ifp", "general", "controllable", "observable")
    assert REALIZERS["controllable"].title == "controllable canonical"
    assert all(r.name == k and r.title and r.form for k, r in REALIZERS.items())
    assert [k for k, r in REALIZERS.items() if r.canonical] == ["controllable", "observable"]
    assert [k for k, r in REALIZERS.items() if r.paper] == list(circuit_names())
    assert [k for k, r in REALIZERS.items() if r.controller] == ["ifp"]
    assert REALIZERS["general"].form == "general"


def test_ifp_realizer_realizes_the_whole_controller_from_its_gains():
    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    result = REALIZERS["ifp"](gains)
    assert result.realization == ifp_realization(gains) and result.P == sp.eye(2)


def test_register_refuses_bad_realizers_by_name_and_unregister_keeps_the_built_ins():
    with pytest.raises(SymctlTypeError, match="realizer: expected a Realizer"):
        register("toy")
    for name in ("general", "pathways", "all", "Toy", "A3", "a b"):
        with pytest.raises(ParameterError, match="realizer: "):
            register(REALIZERS["controllable"].__class__(name, "toy"))
    with pytest.raises(ParameterError, match="'general' is built in"):
        unregister("general")
    with pytest.raises(ParameterError, match="'toy' is not a registered realizer"):
        unregister("toy")


def test_unknown_realizer_names_the_argument_and_the_value():
    with pytest.raises(ParameterError, match=r"kind: must be .*got 'diagonal'"):
        get_realizer("diagonal", "kind")
    with pytest.raises(ParameterError, match="base: must be 'controllable' or 'observable'"):
        general_realization(G2, sp.eye(2), base="general")


@pytest.mark.parametrize(
    ("name", "build"),
    [("controllable", controllable_canonical), ("observable", observable_canonical)],
)
def test_canonical_realizers_return_their_form_with_identity_transform(name, build):
    result = REALIZERS[name](G2)
    assert isinstance(result, RealizerResult)
    assert result.realization.F == build(G2).F and result.base is result.realization
    assert result.P == sp.eye(2) and result.Pinv == sp.eye(2)
    assert result.sys.equals(G2)


def test_general_realizer_carries_base_and_transform_and_inverts_only_numbers():
    P = sp.Matrix([[1, 2], [3, 5]])
    result = REALIZERS["general"](G2, P=P)
    assert result.realization.F == general_realization(G2, P).F
    assert result.base.F == controllable_canonical(G2).F
    assert result.P == P and result.Pinv == P.inv()
    assert result.realization.params["P"] == P
    symbolic = REALIZERS["general"](G2, P=sp.Matrix(2, 2, sp.symbols("p:4")))
    assert symbolic.Pinv is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.P = sp.eye(2)


def test_general_realizer_without_P_draws_it_from_rng():
    a = REALIZERS["general"](G2, rng=3)
    b = REALIZERS["general"](G2, rng=3)
    assert a.P == b.P and a.P.det() != 0


def test_random_realizer_is_random_realization():
    result = REALIZERS["random"](G2, 5)
    R = random_realization(G2, rng=5)
    assert result.realization.F == R.F and dict(result.realization.params) == dict(R.params)
    assert result.P == R.params["P"]
    assert not result.sys.free_symbols & {s for s in G2.free_symbols if s.name.startswith("eps")}


def test_a_static_G2_has_no_transform():
    result = REALIZERS["general"](3 + 0 * z, P=None)
    assert result.realization.n == 0 and result.P.shape == (0, 0)
