"""A plain wire y = u: the delay graph decides, not "u at two vertices"."""

from __future__ import annotations

import pytest
import sympy as sp

from symctl import Block, DelayGraph, Realization, Structure, check_compatibility

CLASS = "6"

k = sp.Symbol("k")

# realizations whose output is the input itself: N = 1 and M = 0 (or no states)
PLAIN_WIRES = {
    "N=1, no states": Realization([], [], [], [[1]]),
    "N=1, M=0, one state": Realization([[sp.Rational(1, 2)]], [[1]], [[0]], [[1]]),
    "N=1, M=0, two states": Realization([[0, 1], [0, 0]], [[0], [1]], [[0, 0]], [[1]]),
}
# graphs with E_1N = 0 (a plain wire fits) and with E_1N > 0 (it does not)
ZERO_DELAY = {
    "chain [0]": DelayGraph.chain([0]),
    "chain [0, 0]": DelayGraph.chain([0, 0]),
    "complete, zeros": DelayGraph([[0, 0], [0, 0]]),
}
POSITIVE_DELAY = {
    "chain [1]": DelayGraph.chain([1]),
    "chain [0, 1]": DelayGraph.chain([0, 1]),
    "chain [2, 3]": DelayGraph.chain([2, 3]),
}


@pytest.mark.parametrize("R", PLAIN_WIRES.values(), ids=PLAIN_WIRES)
def test_plain_wire_output_is_a_signal_of_its_own(R):
    S = Structure.from_realization(R)
    assert S.outputs == ("y",) and S.inputs == ("u",)
    assert S.blocks["y"] == Block("gain", ("u",), 1)


@pytest.mark.parametrize("R", PLAIN_WIRES.values(), ids=PLAIN_WIRES)
@pytest.mark.parametrize("graph", ZERO_DELAY.values(), ids=ZERO_DELAY)
def test_plain_wire_is_compatible_when_E_1N_is_zero(R, graph):
    result = check_compatibility(Structure.from_realization(R), graph)
    assert result.ok, result.reason


@pytest.mark.parametrize("R", PLAIN_WIRES.values(), ids=PLAIN_WIRES)
@pytest.mark.parametrize("graph", POSITIVE_DELAY.values(), ids=POSITIVE_DELAY)
def test_plain_wire_is_incompatible_when_E_1N_is_positive(R, graph):
    result = check_compatibility(Structure.from_realization(R), graph)
    assert not result.ok
    assert "both an input" not in str(result.reason)


def test_a_scaled_wire_keeps_its_gain_signal():
    S = Structure.from_realization(Realization([], [], [], [[k]]))
    assert S.outputs == ("y",) and S.blocks["y"].gain == k


def test_mimo_plain_wires_each_get_their_own_output():
    S = Structure.from_realization(Realization([], [], sp.zeros(2, 0), sp.eye(2)))
    assert S.outputs == ("y1", "y2")
    assert S.blocks["y1"].inputs == ("u1",) and S.blocks["y2"].inputs == ("u2",)


def test_hand_built_output_equal_to_an_input_says_how_to_fix_it():
    S = Structure({"u": Block("input")}, ["u"], ["u"])
    result = check_compatibility(S, DelayGraph.chain([0]))
    assert not result.ok and "signal of its own" in str(result.reason)
