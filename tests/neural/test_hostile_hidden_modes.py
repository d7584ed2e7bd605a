"""Hidden modes: |epsilon| >= 1 gives the right G but an unstable loop."""

from __future__ import annotations

import pytest
import sympy as sp

from symctl import (
    MuscleModel,
    augment,
    closed_loop_response,
    controllable_canonical,
    controller_tf,
    factor,
    lqr_gains,
    observable_canonical,
    simulate_realization,
)
from symctl.errors import ParameterError
from symctl.neural.stability import loop_stability
from symctl.realization.realization import controller_realization
from symctl.symbols import C_1, C_3, epsilon_1, epsilon_3

CLASS = "6"

GAINS = lqr_gains(augment(MuscleModel(), 1, 1))
FACTORS = factor(controller_tf(2), 1, 1)

# (epsilon_1, epsilon_3): each has a section with |epsilon| >= 1
UNSTABLE_EPS = [
    (sp.Rational(3, 2), sp.Rational(1, 5)),
    (sp.Rational(1, 5), -2),
    (1, sp.Rational(1, 2)),
    (-1, sp.Rational(1, 2)),
    (sp.Rational(-5, 4), sp.Rational(5, 4)),
]
REALIZERS = [controllable_canonical, observable_canonical]


def _controller(e1, e3, realizer=controllable_canonical):
    values = {**GAINS.substitutions(), epsilon_1: e1, epsilon_3: e3, C_1: 1, C_3: 1}
    f = FACTORS.subs(values)
    return controller_realization(f, realizer(f.G2))


@pytest.mark.parametrize("realizer", REALIZERS, ids=lambda r: r.__name__)
@pytest.mark.parametrize(("e1", "e3"), UNSTABLE_EPS)
def test_simulation_refuses_a_hidden_unstable_mode_naming_it(e1, e3, realizer):
    R = _controller(e1, e3, realizer)
    worst = max(abs(float(e1)), abs(float(e3)))
    with pytest.raises(ParameterError, match=r"R: .*unstable eigenvalue .*hidden") as info:
        simulate_realization(MuscleModel(), R)
    assert f"spectral radius {worst:.6g}" in str(info.value)


@pytest.mark.parametrize(("e1", "e3"), UNSTABLE_EPS)
def test_closed_loop_response_refuses_a_hidden_unstable_mode(e1, e3):
    with pytest.raises(ParameterError, match="hidden from the transfer function"):
        closed_loop_response(_controller(e1, e3), MuscleModel())


@pytest.mark.parametrize(("e1", "e3"), UNSTABLE_EPS)
def test_loop_stability_flags_the_hidden_mode(e1, e3):
    result = loop_stability(MuscleModel(), _controller(e1, e3))
    assert not result
    assert result.hidden
    assert result.spectral_radius >= 1 - 1e-9  # a mode at -1 is computed as 0.9999999999999998
    assert any(abs(lam - complex(float(e))) < 1e-9 for lam in result.unstable for e in (e1, e3))
    assert "hidden" in str(result)


@pytest.mark.parametrize("eps", [(sp.Rational(1, 2), sp.Rational(-1, 3)), (0, 0)])
def test_stable_sections_pass_and_simulate(eps):
    R = _controller(*eps)
    result = loop_stability(MuscleModel(), R)
    assert result and not result.unstable and not result.hidden
    assert simulate_realization(MuscleModel(), R).delta_r.shape == (50, 1)


def test_a_controller_that_does_not_stabilize_is_not_called_hidden():
    from symctl import Realization

    result = loop_stability(MuscleModel(), Realization([[0]], [[-1]], [[1]], 0))
    assert not result and not result.hidden
    with pytest.raises(ParameterError, match="does not stabilize"):
        simulate_realization(MuscleModel(), Realization([[0]], [[-1]], [[1]], 0))


@pytest.mark.parametrize(
    "eps",
    [(1.5,), (-1,), (0.5, 1.0), (sp.Rational(3, 2),), (0.2, -1.01), (sp.I * sp.Rational(6, 5),)],
)
def test_require_stable_sections_refuses_hidden_unstable_poles(eps):
    from symctl.realization.check import require_stable_sections

    with pytest.raises(ParameterError, match=r"eps_range: .*epsilon\| >= 1"):
        require_stable_sections(eps, "eps_range")


@pytest.mark.parametrize("eps", [(-0.9, 0.9), (0,), (sp.Rational(999, 1000),), (epsilon_1, 0.5)])
def test_require_stable_sections_lets_stable_and_symbolic_poles_through(eps):
    from symctl.realization.check import require_stable_sections

    require_stable_sections(eps, "eps_range")


@pytest.mark.parametrize(("e1", "e3"), [*UNSTABLE_EPS, (sp.Rational(1, 2), sp.Rational(-1, 3))])
def test_circuit_loop_stability_matches_its_realization(e1, e3):
    from symctl import Circuit, Structure

    R = _controller(e1, e3)
    circuit = Circuit.from_structure(Structure.from_realization(R))
    by_circuit = loop_stability(MuscleModel(), circuit)
    by_realization = loop_stability(MuscleModel(), R)
    assert bool(by_circuit) == bool(by_realization)
    assert by_circuit.spectral_radius == pytest.approx(by_realization.spectral_radius, rel=1e-9)
    assert bool(by_circuit.hidden) == bool(by_realization.hidden)
