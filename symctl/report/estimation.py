r"""What an estimating controller (the delayed LQG compensator) measures and estimates: its
section and its ``results.json`` entry."""

from __future__ import annotations

import numpy as np

from symctl.report import shorthand as SH
from symctl.report.document import DocumentBlock, Heading, Table, Text
from symctl.report.model_story import names_tex

__all__ = ["estimation_json", "estimation_section"]

FORM = "predictor"  # the compensator's form in a derivation (docs/guide/noise.md says why)


def _poles(values) -> list[list[float]]:
    return [[float(np.real(p)), float(np.imag(p))] for p in values]


def _plant_poles(kf) -> np.ndarray:
    """The filter's poles on the plant, :math:`\\operatorname{eig}(A - LC)` (the others are 0)."""
    return np.linalg.eigvals(SH.num(kf.system.plant.A) - kf.L[: kf.system.n] @ SH.num(kf.C))


def estimation_json(res) -> dict:
    """The ``estimation`` entry of ``results.json`` (only for a model with a Kalman filter)."""
    kf, mc, cl = res.kalman, res.variance, res.closed_loop
    n = kf.system.n
    cost = {"measured": mc.cost, "standard_error": mc.cost_se, "predicted": mc.predicted_cost}
    return {
        "form": FORM,
        "C": SH.num(kf.C).tolist(),
        "outputs": [name for name, _ in res.spec.outputs],
        "W": kf.W.tolist(),
        "V": kf.V.tolist(),
        "L": kf.L[:n].tolist(),
        "L_names": [str(s) for s in kf.substitutions()],
        "P": kf.P[:n, :n].tolist(),
        "estimator_poles": _poles(_plant_poles(kf)),
        "closed_loop_poles": _poles([*res.gains.poles, *_plant_poles(kf)]),
        "variance": {
            "states": list(mc.state_names),
            "predicted": mc.predicted_covariance.tolist(),
            "measured": mc.covariance.tolist(),
            "standard_error": mc.covariance_se.tolist(),
            "cost": cost,
            "loops": mc.count,
            "steps": mc.steps,
            "burn_in": mc.burn_in,
        },
        "bands": {
            "draws": cl.draws,
            "delta_f_sd": cl.delta_f_sd.tolist() if cl.delta_f_sd is not None else None,
            "delta_r_sd": cl.delta_r_sd.tolist() if cl.delta_r_sd is not None else None,
        },
    }


def estimation_section(res) -> list[DocumentBlock]:
    """The section "What the controller measures and estimates" (none without a filter)."""
    kf, mc = res.kalman, res.variance
    if kf is None:
        return []
    s, n = kf.system, kf.system.n
    xs = res.names[0]
    C = SH.num(kf.C)
    seen = [x for j, x in enumerate(xs) if np.any(C[:, j])]
    intro = Text(
        f"The controller does not read the whole state: it measures $y = C x + v$, "
        f"{kf.p} output{'s' * (kf.p != 1)} of {names_tex(seen)}, through sensor noise $v$ "
        "of covariance $V$, while a process noise of covariance $W$ (the motor noise "
        "$W_u$ entering as $B W_u B^\\top$) drives the plant. A delayed Kalman filter "
        "estimates the augmented state from the delayed measurements (the sensor delay "
        "moved to the actuator side, as for the gains, the measurement arriving at step "
        "$t$ is that of $x(t)$ on the controller's clock), in predictor form: "
        "$\\hat\\chi(t+1) = \\tilde A \\hat\\chi(t) + \\tilde B \\mu(t) + \\tilde L "
        "(y(t) - \\tilde C \\hat\\chi(t))$, $\\tilde C = [C\\ 0]$, and the optimal gains act "
        "on the estimate, $\\mu(t) = K \\hat\\chi(t)$. The delay chain holds the controller's "
        "own past commands, known without noise, so $\\tilde L = [L;\\ 0]$ with $L = A P "
        "C^\\top (C P C^\\top + V)^{-1}$ the plant's Kalman gain, $P$ the solution of the "
        "dual Riccati equation. $G(z)$ above is this compensator from $y$ to the command, "
        + (
            "its gains $K$ and $L$ kept symbolic. "
            if s.m == 1
            else "its gains $K$ and $L$ their exact values (the symbolic form is too large). "
        )
        + "In the compensator's own state space "
        f"{n + s.T * s.m} neurons would hold $\\hat\\chi$: {n} estimate {names_tex(xs)}, "
        f"{s.T * s.m} the delayed commands. "
        "Every circuit below realizes the same $G(z)$ and is driven by $y$: its neurons "
        "of $G_2$ hold these estimates in other coordinates (a change of basis of "
        "$\\hat\\chi$, the sections' states folded in), so they fire differently and "
        "behave the same."
    )
    poles = ", ".join(f"{complex(p):.4g}".strip("()") for p in _plant_poles(kf))
    kalman = SH.eq(
        ("C", C),
        ("W", kf.W),
        ("V", kf.V),
        ("L", kf.L[:n]),
        (r"\operatorname{eig}(A - L C)", rf"\{{{poles}\}}"),
        label="eq:kalman",
    )
    separation = Text(
        "Separation: the loop of plant and compensator has the regulator's poles "
        "$\\operatorname{eig}(\\tilde A + \\tilde B K)$, the filter's $\\operatorname{eig}"
        f"(A - LC)$ and ${s.T * s.m}$ at 0 (the known delay chain). Under the noise the "
        "loop settles to a stationary covariance, predicted by the discrete Lyapunov "
        f"equation and measured over {mc.count} noisy loops of {mc.steps} steps "
        f"(the first {mc.burn_in} left out; mean $\\pm$ standard error):"
    )
    rows = [
        (f"var {names_tex([x])}", f"{v:.4g} ± {e:.2g}", f"{p:.4g}")
        for x, v, e, p in zip(
            xs,
            np.diag(mc.covariance),
            np.diag(mc.covariance_se),
            np.diag(mc.predicted_covariance),
            strict=True,
        )
    ]
    rows.append(("cost per step", f"{mc.cost:.4g} ± {mc.cost_se:.2g}", f"{mc.predicted_cost:.4g}"))
    gap = Text(
        f"The largest gap between measured and predicted is {mc.z_score:.2f} standard "
        "errors. The closed-loop figure shows the mean of the noisy loops in a band of "
        "$\\pm 2$ standard deviations."
    )
    skipped = res.skipped and res.G.is_siso and res.factors is not None  # else said with G2
    return [
        Heading("What the controller measures and estimates"),
        intro,
        *kalman,
        separation,
        Table(("", "measured", "predicted"), tuple(rows)),
        gap,
        *([Text("Not built here: " + res.skipped + ".")] if skipped else []),
    ]
