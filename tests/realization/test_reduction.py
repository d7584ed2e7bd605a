"""The delayed controller's minimality, decided exactly, and the ties that make it not minimal."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symctl import MuscleModel, SymctlTypeError, augment, controller_tf, lqr_gains
from symctl.realization.minimal import minimal_realization
from symctl.realization.reduction import ControllerReduction, controller_reduction
from symctl.symbols import z

PLANT = ([[0.9, 0.0], [0.1, 0.8]], [[1.0, -1.0], [0.0, 0.0]])
"""Two inputs through the same column of B, with opposite signs."""

SUM_UNSEEN = (
    [[0.9, 0.05, -0.05], [0.0, 0.6, 0.0], [0.0, 0.0, 0.6]],
    [[0.0, 0.0], [0.5, 0.0], [0.0, 0.5]],
)
"""The antagonist's shape: two forces whose difference moves the first state; their sum is seen
by no cost on the first state alone."""


def _reduced(plant, T=(1, 1), Q=None):
    system = augment(plant, *T, Q=Q)
    gains = lqr_gains(system)
    reduction, tied = controller_reduction(system, gains)
    return system, gains, reduction, tied


def test_two_inputs_through_one_column_are_found_not_minimal_with_the_reason():
    _, _, red, _ = _reduced(PLANT)
    assert not red and red.verdict is False
    assert (red.order, red.minimal_order) == (4, 2)
    assert red.never_driven == ("u_1 + u_2",)
    assert "the same column of B" in red.reason and red.reason.startswith("u_1 + u_2 moves no")


def test_a_force_sum_the_cost_never_sees_is_found_with_its_reason():
    _, _, red, _ = _reduced(SUM_UNSEEN, Q=np.diag([1.0, 0.0, 0.0]))
    assert (red.order, red.minimal_order) == (4, 2)
    assert red.unseen == ("x_2 + x_3",) and red.never_driven == ("u_1 + u_2",)
    assert "moves only x_2 + x_3, which the cost never sees" in red.reason


def test_the_tied_gains_are_exact_and_leave_the_others_as_the_lqr_gave_them():
    _, gains, red, tied = _reduced(PLANT, T=(2, 1))
    values = tied.substitutions(exact=True)
    for k, expr in red.relations.items():  # every tie holds exactly for the gains used
        assert values[k] == expr.subs(values)
    free = set(values) - set(red.relations)
    old = gains.substitutions()
    assert all(tied.substitutions()[k] == old[k] for k in free)
    assert np.max(np.abs(tied.K - gains.K)) < 1e-12  # the ties hold to rounding already
    # a multiple pole at 0 splits by the square root of the rounding error
    assert np.allclose(np.sort_complex(tied.poles), np.sort_complex(gains.poles), atol=1e-4)


def test_the_reduced_controller_has_exact_zeros_and_the_minimal_order():
    system, gains, red, tied = _reduced(PLANT, T=(2, 1))
    full = controller_tf(system).subs(gains.substitutions())
    small = red.reduce(controller_tf(system)).subs(tied.substitutions())
    assert full.order == 6 and small.order == red.minimal_order == 3
    # before: the float gains leave coefficients of about 1e-16 where the exact ones are 0
    assert any(0 < abs(float(c)) < 1e-12 for c in full.den_coeffs())
    for c in (
        *small.den_coeffs(),
        *(c for i in range(2) for j in range(2) for c in small.num_coeffs(i, j)),
    ):
        assert c == 0 or abs(float(c)) > 1e-12
    # the same transfer function, to rounding: equal Markov parameters
    a, b = full.markov(8), small.markov(8)
    assert all(
        np.allclose(np.array(x, float), np.array(y, float), atol=1e-12)
        for x, y in zip(a, b, strict=True)
    )


def test_the_minimal_order_is_the_mcmillan_degree_of_the_reduced_controller():
    system, _, red, tied = _reduced(PLANT, T=(1, 2))
    G = red.reduce(controller_tf(system)).subs(tied.substitutions(exact=True))
    assert G.den == sp.expand(G.den) and sp.degree(G.den, z) == red.minimal_order
    from symctl.realization.realizers import REALIZERS

    R = REALIZERS["observable"](G).realization
    assert minimal_realization(R).n == red.minimal_order


def test_a_minimal_controller_is_kept_as_it_is():
    system = augment(MuscleModel(), 1, 1)
    gains = lqr_gains(system)
    red, same = controller_reduction(system, gains)
    assert red and red.minimal and (red.order, red.minimal_order) == (2, 2)
    assert same is gains and not red.relations and red.reason == ""
    G = controller_tf(system)
    assert red.reduce(G) is G


def test_the_verdict_round_trips_through_a_dict():
    _, _, red, _ = _reduced(PLANT)
    back = ControllerReduction.from_dict(red.to_dict())
    assert back == red and dict(back.relations) == dict(red.relations)
    assert back.method == red.method and "McMillan degree 2 of 4" in back.evidence


def test_other_types_are_refused_by_name():
    with pytest.raises(SymctlTypeError, match="system, gains"):
        controller_reduction("system", None)
