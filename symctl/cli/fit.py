"""``symctl fit``: a circuit of the controller fitted to recorded firing rates."""

from __future__ import annotations

from pathlib import Path

import click
from rich.console import Console

from symctl.cli.options import Command, options, shown, workers_options
from symctl.cli.progress import Steps, say

__all__ = ["fit_command"]

_console = Console()


@click.command("fit", cls=Command)
@click.argument("data", metavar="DATA", type=click.Path(dir_okay=False))
@options(
    click.option(
        "--model",
        "model_file",
        metavar="MODEL.toml",
        help="The plant and penalties [default: the paper's muscle model].",
    ),
    click.option(
        "--circuit",
        help="A circuit of G2 in the realizers' registry (general, controllable, observable, "
        "...), an atlas class A1..A5, all, or several separated by commas [default: the data's, "
        "else general].",
    ),
    click.option(
        "--sensor-delay",
        type=int,
        help="Sensor sections [default: the data's, else the model's, else 1].",
    ),
    click.option(
        "--actuator-delay",
        type=int,
        help="Actuator sections [default: the data's, else the model's, else 1].",
    ),
    click.option(
        "--C", "C", type=float, help="Fix every section gain C to this value [default: fitted]."
    ),
    shown(
        "--starts",
        type=click.IntRange(min=1),
        default=8,
        help="Starting points of the least-squares fit.",
    ),
    shown("--seed", "rng", type=int, default=0, help="Seed of the starts and the bootstrap."),
    shown(
        "--bootstrap",
        type=click.IntRange(min=0),
        default=200,
        help="Refits behind the 95% intervals and prediction bands (0: none).",
    ),
    workers_options("Local processes running the starts and refits (the atlas's dask path)."),
    shown("--figures/--no-figures", default=True, help="Write the figure (fit.pdf, .svg, .png)."),
    shown("--out", default="out/fit", help="Output folder."),
)
def fit_command(
    data, model_file, circuit, sensor_delay, actuator_delay, figures, out, **fitting
) -> None:
    """Fit a circuit of the controller to the firing rates recorded in DATA (CSV or NPZ).

    Writes fit.json, predictions.csv (every neuron's trace), report.md and the figure
    (fit.pdf, fit.svg, fit.png) into OUT. The data format is in docs/fitting.md."""
    from symctl.fitting.fit import fit
    from symctl.report.fit import write_fit
    from symctl.report.output import OutputFolder

    gains, G, C, tr = _fit_inputs(data, model_file, sensor_delay, actuator_delay)
    ds, da = gains.system.sensor_delay, gains.system.actuator_delay
    controller = {"G": gains}
    if G is not None:  # a model that measures some states: its LQG compensator
        controller = {"G": G, "plant": gains.system.plant, "outputs": C}
    classes = (circuit or tr.meta.get("circuit") or "general").split(",")
    classes = [c.strip() for c in classes]
    with OutputFolder(out, "--out") as folder, Steps(_console) as steps:
        steps.start(f"fitting {', '.join(classes)} ({fitting['starts']} starts)")
        res = fit(
            tr.traces,
            **controller,
            sensor_delay=ds,
            actuator_delay=da,
            circuit=classes if len(classes) > 1 else classes[0],
            disturbance=1.0 if tr.disturbance is None else tr.disturbance,
            steps=tr.steps,
            **fitting,
            progress=steps.part,
        )
        steps.start("writing")
        written = write_fit(res, folder.staging, figures=figures, source=str(data))
    worst = max(res.residuals.values())
    say(
        _console,
        f"fitted {len(res.data)} neurons with the {res.circuit_class} circuit "
        f"(exact realization of G: {res.exact}); largest RMS residual {worst:.3g}",
    )
    say(_console, f"wrote {out}/: " + ", ".join(p.name for p in folder.final(written)))


def _fit_inputs(data, model_file, sensor_delay, actuator_delay):
    """The controller of :func:`model_controller` (delays from the options, DATA's header or the
    model) and the traces of DATA."""
    from symctl.errors import ParameterError
    from symctl.fitting.traces import read_traces

    tr = read_traces(Path(data))
    ds, da = (
        _meta_int(v, key, tr) if v is None else v
        for v, key in ((sensor_delay, "sensor_delay"), (actuator_delay, "actuator_delay"))
    )
    gains, G, C = model_controller(model_file, ds, da)
    Ts = gains.system.plant.dt
    if Ts is not None:
        dt = float(tr.t[1] - tr.t[0])
        if abs(dt - float(Ts)) > 1e-6 * float(Ts):
            raise ParameterError(
                f"DATA: its time step is {dt:g}, the plant's sampling time {float(Ts):g}"
            )
    return gains, G, C, tr


def model_controller(model_file, sensor_delay, actuator_delay):
    """``(gains, G, C)``: the optimal gains of MODEL.toml (or of the paper's muscle model,
    Q = R = 1, one step each way), and for a model that measures some states or through noise
    its LQG compensator G(z) and output matrix C (else None, None). Delays left None are the
    model's."""
    from symctl.design.augment import augment
    from symctl.design.lqr import lqr_gains

    model, plant, Q, R, (ds, da) = _model(model_file)
    ds = ds if sensor_delay is None else sensor_delay
    da = da if actuator_delay is None else actuator_delay
    gains = lqr_gains(augment(plant, ds, da, Q=Q, R=R))
    if model is None or model.C is None:
        return gains, None, None
    from symctl.derivation.pipeline import _kalman
    from symctl.design.kalman import lqg_tf

    kalman, _ = _kalman(model, gains.system)
    return gains, lqg_tf(gains.system, model.C, gains=gains, kalman=kalman), model.C


def model_parts(model_file):
    """``(plant, Q, R, (sensor_delay, actuator_delay))`` of MODEL.toml, or the paper's muscle."""
    return _model(model_file)[1:]


def _model(model_file):
    """``(model or None, plant, Q, R, (sensor_delay, actuator_delay))`` as :func:`model_parts`."""
    from symctl.design.plant import MuscleModel
    from symctl.model.modelfile import load_model

    if model_file is None:
        return None, MuscleModel(), 1, 1, (1, 1)
    m = load_model(Path(model_file))
    return m, m.plant, m.Q, m.R, (m.sensor_delay, m.actuator_delay)


def _meta_int(value, key, tr):
    from symctl.errors import ParameterError

    text = tr.meta.get(key)
    if text is None:
        return None
    if not text.strip().isdigit():
        raise ParameterError(f"DATA: header line '{key}: {text[:40]}' is not a whole number")
    return int(text)
