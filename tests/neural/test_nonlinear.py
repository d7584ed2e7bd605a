"""The linear controller around the nonlinear muscle: a second-order departure, accurate integration."""

from __future__ import annotations

import numpy as np
import pytest

from symctl import MuscleModel, nonlinear_check, pulse

MODEL = MuscleModel()


def test_nonlinear_check_departs_quadratically_and_integrates_accurately():
    chk = nonlinear_check(amplitudes=[1e-3, 1e-2, 1e-1, 1.0, 10.0], steps=40)
    assert np.all(np.diff(chk.max_deviation) > 0)
    ratio = chk.max_deviation[1:4] / chk.max_deviation[:3]
    np.testing.assert_allclose(ratio, 100, rtol=0.1)  # second order in the amplitude
    assert chk.relative_deviation[0] < 1e-4
    # the exact solution with r held constant: f_inf + (f - f_inf) exp(-Ts/tau)
    decay = np.exp(-MODEL.dt / MODEL.tau)
    w = pulse(40)[:, 0]
    for i, amp in enumerate(chk.amplitudes):
        f_inf = MODEL.f_max / (1 + np.exp(-chk.r_nonlinear[i, :-1]))
        nxt = f_inf + (chk.f_nonlinear[i, :-1] - f_inf) * decay + amp * w[:-1]
        np.testing.assert_allclose(chk.f_nonlinear[i, 1:], nxt, rtol=1e-9)
    assert "relative" in chk.table()


def test_nonlinear_check_arrays_read_only():
    chk = nonlinear_check(amplitudes=[0.1, 1.0], steps=12)
    for name in ("amplitudes", "t", "f_linear", "f_nonlinear", "r_nonlinear", "max_deviation"):
        assert not getattr(chk, name).flags.writeable, name
    with pytest.raises(ValueError, match="read-only"):
        chk.relative_deviation[0] = 0.0
