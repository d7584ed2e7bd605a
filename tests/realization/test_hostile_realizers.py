"""random_realization refuses bad seeds, ranges and values with symctl errors."""

from __future__ import annotations

import numpy as np
import pytest

from symctl import (
    ParameterError,
    SymctlError,
    SymctlTypeError,
    controller_tf,
    factor,
    general_realization,
    random_realization,
)

CLASS = "5"

G2 = factor(controller_tf(2)).G2

BAD = {
    "rng=-1": ({"rng": -1}, ParameterError, "rng"),
    "rng=-2**70": ({"rng": -(2**70)}, ParameterError, "rng"),
    "rng=1.5": ({"rng": 1.5}, SymctlTypeError, "rng"),
    "rng='0'": ({"rng": "0"}, SymctlTypeError, "rng"),
    "rng=True": ({"rng": True}, SymctlTypeError, "rng"),
    "eps_range=(1, -1)": ({"eps_range": (1, -1)}, ParameterError, "eps_range"),
    "eps_range=(nan, 1)": ({"eps_range": (float("nan"), 1)}, ParameterError, "eps_range"),
    "eps_range=(-inf, 1)": ({"eps_range": (float("-inf"), 1)}, ParameterError, "eps_range"),
    "eps_range=(-1e300, 1e300)": ({"eps_range": (-1e300, 1e300)}, ParameterError, "eps_range"),
    "eps_range=1": ({"eps_range": 1}, SymctlTypeError, "eps_range"),
    "eps_range=(1, 2, 3)": ({"eps_range": (1, 2, 3)}, SymctlTypeError, "eps_range"),
    "eps_range=('a', 1)": ({"eps_range": ("a", 1)}, SymctlTypeError, "eps_range"),
    "values=[1]": ({"values": [1]}, SymctlTypeError, "values"),
    "values='K_0'": ({"values": "K_0"}, SymctlTypeError, "values"),
    "values={'K_9': 1}": ({"values": {"K_9": 1}}, ParameterError, "K_9"),
    "values={'K_0': nan}": ({"values": {"K_0": float("nan")}}, ParameterError, "K_0"),
    "values={'K_0': '1/0'}": ({"values": {"K_0": "1/0"}}, SymctlError, "K_0"),
    "values={1: 2}": ({"values": {1: 2}}, SymctlTypeError, "key"),
}


@pytest.mark.parametrize(("options", "error", "named"), BAD.values(), ids=BAD.keys())
def test_random_realization_refuses_bad_arguments_naming_them(options, error, named):
    options = {"rng": 0, **options}
    with pytest.raises(error, match=named):
        random_realization(G2, **options)


def test_general_realization_refuses_a_negative_seed_through_its_realizer():
    from symctl.realization.realizers import REALIZERS

    with pytest.raises(ParameterError, match="rng"):
        REALIZERS["general"](G2, rng=-1)
    assert general_realization(G2, np.eye(2)).n == 2


def test_values_by_name_and_text_are_substituted():
    R = random_realization(G2, 0, values={"K_0": "1/2", "C_1": 1, "C_3": "1"})
    assert {s.name for s in R.free_symbols} == {"K_1", "K_2"}


@pytest.mark.parametrize("eps_range", [(-1.5, 0.5), (-0.5, 1.0), (1.0, 2.0)])
def test_random_realization_refuses_hidden_unstable_sections(eps_range):
    from symctl import controller_tf, factor, random_realization

    with pytest.raises(ParameterError, match=r"eps_range: .* has \|epsilon\| >= 1"):
        random_realization(factor(controller_tf(2)).G2, rng=0, eps_range=eps_range)
