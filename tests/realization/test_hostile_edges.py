"""Wrong answers at the edges (issue 12, class 6): sampling times, float inputs, hidden modes."""

from __future__ import annotations

import pytest
import sympy as sp

from symctl import DiscreteTF, Realization
from symctl.errors import ParameterError
from symctl.symbols import z

CLASS = "6"

T = sp.Symbol("T", positive=True)

# (dt of the first operand, dt of the second, the dt the product keeps or None when refused)
DT_REFUSED = [
    (sp.Rational(1, 10), sp.Rational(1, 2)),
    (0.1, 0.5),
    (0.01, 0.02),
    (T, sp.Rational(1, 100)),
    (T, 2 * T),
]
DT_COMBINED = [
    (None, sp.Rational(1, 10), sp.Rational(1, 10)),
    (sp.Rational(1, 10), None, sp.Rational(1, 10)),
    (None, None, None),
    (0.01, sp.Rational(1, 100), 0.01),
    (T, T, T),
]


@pytest.mark.parametrize(("dt1", "dt2"), DT_REFUSED)
def test_tf_product_refuses_incompatible_sampling_times(dt1, dt2):
    with pytest.raises(ParameterError, match="other: incompatible sampling times"):
        DiscreteTF(1, z - sp.Rational(1, 2), dt=dt1) * DiscreteTF(1, z, dt=dt2)


@pytest.mark.parametrize(("dt1", "dt2", "dt"), DT_COMBINED)
def test_tf_product_combines_equal_or_unspecified_sampling_times(dt1, dt2, dt):
    G = DiscreteTF(1, z - sp.Rational(1, 2), dt=dt1) * DiscreteTF(1, z, dt=dt2)
    assert G.dt == (None if dt is None else sp.sympify(dt))


def _first(dt):
    return Realization([[sp.Rational(1, 2)]], [[1]], [[1]], 0, dt)


@pytest.mark.parametrize(("dt1", "dt2"), DT_REFUSED)
def test_series_refuses_incompatible_sampling_times_naming_the_part(dt1, dt2):
    with pytest.raises(ParameterError, match=r"parts\[2\]: incompatible sampling times"):
        Realization.series(_first(dt1), _first(dt1), _first(dt2))


@pytest.mark.parametrize(("dt1", "dt2", "dt"), DT_COMBINED)
def test_series_combines_equal_or_unspecified_sampling_times(dt1, dt2, dt):
    R = Realization.series(_first(dt1), _first(dt2))
    assert R.dt == (None if dt is None else sp.sympify(dt))
