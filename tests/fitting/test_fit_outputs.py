"""fit on a controller fed by measured outputs: the LQG compensator of a forearm that senses its angle."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from symctl import MuscleModel, augment, circuit_firing, fit, load_model, lqg_tf, lqr_gains
from symctl.design.kalman import kalman_gains
from symctl.errors import SymctlError, SymctlTypeError

FOREARM = Path(__file__).resolve().parents[2] / "examples" / "forearm_lqg.toml"


def test_the_compensators_circuit_is_fitted_exactly_from_the_measured_output():
    from symctl.derivation.pipeline import _kalman

    model = load_model(FOREARM)
    gains = lqr_gains(
        augment(model.plant, model.sensor_delay, model.actuator_delay, model.Q, model.R)
    )
    kf, _ = _kalman(model, gains.system)
    s = gains.system
    fp = circuit_firing("controllable", gains, kalman=kf, count=1, rng=3)
    rec = {n: np.asarray(fp.firing[n])[0] for n in ("G2.x8", "G2.y")}
    G = lqg_tf(s, kf.C, gains=gains, kalman=kf)
    res = fit(
        rec,
        G,
        plant=s.plant,
        outputs=kf.C,
        sensor_delay=s.sensor_delay,
        actuator_delay=s.actuator_delay,
        circuit="controllable",
        C=1,
        bootstrap=0,
        starts=2,
    )
    assert res.proof  # the fitted circuit realizes the compensator exactly
    for name, trace in rec.items():
        assert res.residuals[name] < 1e-9 * np.sqrt(np.mean(trace**2))


def test_outputs_need_a_transfer_function_and_the_plants_width():
    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    with pytest.raises(SymctlTypeError, match="outputs"):
        fit({"G2.y": np.zeros(50)}, gains, sensor_delay=1, actuator_delay=1, outputs=[[1]])
    kf = kalman_gains(gains.system, C=[[1]], W=0.1, V=0.01)
    G = lqg_tf(gains.system, [[1]], gains=gains, kalman=kf)
    with pytest.raises(SymctlError, match="outputs"):
        fit(
            {"G2.y": np.zeros(50)},
            G,
            plant=gains.system.plant,
            outputs=[[1, 0]],
            sensor_delay=1,
            actuator_delay=1,
        )


def test_symctl_fit_on_such_a_model_fits_its_compensator(tmp_path):
    from symctl.cli import main
    from symctl.derivation.pipeline import _kalman
    from symctl.fitting.traces import Traces

    model = load_model(FOREARM)
    gains = lqr_gains(
        augment(model.plant, model.sensor_delay, model.actuator_delay, model.Q, model.R)
    )
    kf, _ = _kalman(model, gains.system)
    fp = circuit_firing("controllable", gains, kalman=kf, count=1, rng=3)
    rec = {n: np.asarray(fp.firing[n])[0] for n in ("G2.x8", "G2.y")}
    t = np.arange(rec["G2.y"].size) * float(gains.system.plant.dt)
    data = Traces(t, rec).to_csv(tmp_path / "data.csv")
    args = ["fit", str(data), "--model", str(FOREARM), "--circuit", "controllable", "--C", "1"]
    assert main([*args, "--bootstrap", "0", "--no-figures", "--out", str(tmp_path / "out")]) == 0
    out = json.loads((tmp_path / "out" / "fit.json").read_text())
    assert out["exact"] is True and max(out["residuals"].values()) < 1e-9
