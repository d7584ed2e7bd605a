"""Circuit.to_nest: the retimed rate network, and what NEST cannot express."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import need_spiking

from symctl import Circuit, MissingDependencyError, ParameterError, Structure
from symctl.neural.firing import _drive
from symctl.spiking.nest_export import nest_response

nest = need_spiking("nest")


def _loop(delay_b: int) -> Circuit:
    """a = 0.5 b(t-1) + u and b = 0.3 a(t - delay_b) + u: two neurons, one loop."""
    blocks = {
        "u": ("input",),
        "bd": ("delay", ("b",)),
        "ga": ("gain", ("bd",), 0.5),
        "a": ("sum", ("ga", "u")),
        "gb": ("gain", ("ad" if delay_b else "a",), 0.3),
        "b": ("sum", ("gb", "u")),
    }
    if delay_b:
        blocks["ad"] = ("delay", ("a",))
    return Circuit.from_structure(Structure(blocks, "u", "b"))


def test_a_delay_free_synapse_is_retimed_not_dropped():
    c = _loop(1)
    net = c.to_nest()
    assert net.lags["output b"] > net.lags["b"]  # the output sum b -> output (delay 0)
    u = np.r_[1.0, np.zeros(9), -2.0, np.zeros(9)]
    got, ref = nest_response(c, u), _drive(c, u)
    for name in ref:
        np.testing.assert_allclose(got[name], ref[name], rtol=0, atol=1e-12)


def test_a_loop_with_fewer_delays_than_neurons_is_refused():
    with pytest.raises(ParameterError, match="circuit: a loop has fewer unit delays"):
        _loop(0).to_nest()


def test_without_nest_the_error_says_how_to_install(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "nest", None)
    with pytest.raises(MissingDependencyError, match=r"pip install symctl\[spiking\]"):
        _loop(1).to_nest()
