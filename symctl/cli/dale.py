"""``symctl dale``: Dale's law for the controller of a model (or the paper's), on the terminal. It
writes nothing: ``--json`` prints the verdicts for scripts."""

from __future__ import annotations

import itertools
import json
from collections.abc import Mapping

import click
from rich.console import Console

from symctl.cli.options import Command, options, shown, workers_options
from symctl.cli.progress import Steps, say

__all__ = ["dale_command"]

_console = Console()


@click.command("dale", cls=Command)
@click.argument("model_file", metavar="[MODEL.toml]", required=False, default=None)
@options(
    click.option(
        "--circuit",
        help="Circuits to decide, separated by commas: circuits of G2 in the realizers' registry "
        "(general, controllable, observable, ...) or atlas labels A1, A2, ... of G2's order "
        "[default: every circuit of G2 in the registry].",
    ),
    click.option("--sensor-delay", type=int, help="[default: the model's, else 1]"),
    click.option("--actuator-delay", type=int, help="[default: the model's, else 1]"),
    shown(
        "--timeout",
        type=float,
        default=30.0,
        help="Seconds for each circuit's decision, every stage included (--ei: for each "
        "circuit searched; --atlas: for each search).",
    ),
    click.option("--ei", is_flag=True, help="Also find the cheapest E/I circuit (interneurons)."),
    click.option(
        "--atlas",
        "atlas_table",
        is_flag=True,
        help="Instead: the E/I table of the order-2 atlas (every, some or never).",
    ),
    shown(
        "--samples",
        type=click.IntRange(min=0),
        default=24,
        help="Sampled controllers per class (--atlas).",
    ),
    workers_options("Local processes (--atlas; the atlas's dask path)."),
    click.option("--json", "as_json", is_flag=True, help="Print JSON instead of text."),
)
def dale_command(
    model_file, circuit, sensor_delay, actuator_delay, ei, atlas_table, samples, as_json, **run
) -> None:
    """Decide whether the circuits of the controller can have every neuron E or I.

    The controller is the optimal one of MODEL.toml (default: the paper's muscle
    model, Q = R = 1); for a model that measures some states, or through noise, its LQG
    compensator of the measured outputs. Each verdict is a witness verified exactly, a z3 proof that
    none exists, or "not decided"."""
    from symctl.cli.fit import model_controller
    from symctl.dalelaw.dale import dale
    from symctl.dalelaw.dale_atlas import dale_atlas
    from symctl.dalelaw.interneurons import ei_circuit

    gains, G, _ = model_controller(model_file, sensor_delay, actuator_delay)
    delays = {
        "sensor_delay": gains.system.sensor_delay,
        "actuator_delay": gains.system.actuator_delay,
    }
    ctrl, kw = (gains, {}) if G is None else (G, delays)  # the compensator needs its delays
    if atlas_table:
        with Steps(_console) as steps:
            steps.start("the E/I table of the order-2 atlas")
            decided = itertools.count(1)

            def progress(label):
                steps.part(f"{next(decided)} classes decided, last {label}")

            T = dale_atlas(2, samples=samples, G=ctrl, **kw, **run, progress=progress)
        if as_json:
            fields = ("verdict", "controller", "sampled", "exists")
            rows = [{"class": r.label} | _fields(r, fields) for r in T.rows]
            say(_console, json.dumps({"order": 2, "samples": samples, "rows": rows}, indent=1))
        else:
            say(_console, T.table())
        return
    from symctl.realization.realizers import circuit_names

    s = gains.system
    circuit = ",".join(circuit_names(whole=False)) if circuit is None else circuit
    circuits = [_circuit(c.strip(), s) for c in circuit.split(",") if c.strip()]
    if not circuits:
        raise click.BadParameter("name at least one circuit", param_hint="--circuit")
    timeout = run["timeout"]
    with Steps(_console) as steps:
        results = []
        for k, c in enumerate(circuits, start=1):
            steps.start(f"dale {getattr(c, 'label', c)} ({k} of {len(circuits)})")
            results.append(dale(ctrl, **kw, circuit=c, timeout=timeout, progress=steps.part))
        e = None
        if ei:
            steps.start("cheapest E/I circuit")
            e = ei_circuit(ctrl, **kw, timeout=timeout, progress=steps.part)
    if as_json:
        fields = ("circuit", "feasible", "realizes", "signs", "method", "reason")
        out = {"circuits": [_fields(r, fields) for r in results]}
        if e is not None:
            fields = ("circuit", "neurons", "minimum", "cost", "interneurons")
            out["ei_circuit"] = _fields(e, fields)
        say(_console, json.dumps(out, indent=1))
        return
    word = {True: "E/I", False: "none (proved)", None: "not decided"}
    what = "" if G is None else "the LQG compensator of the measured outputs; "
    say(
        _console,
        f"controller: {what}sensor delay {s.sensor_delay}, actuator delay {s.actuator_delay}",
    )
    for r in results:
        signs = ", ".join(f"{k} {v}" for k, v in r.signs.items())
        say(_console, f"{r.circuit:>12}: {word[r.feasible]}" + (f"  [{signs}]" if signs else ""))
        say(_console, f"{'':>14}{r.reason}")
    if e is not None:
        say(
            _console,
            f"cheapest E/I circuit: {e.circuit}, {e.neurons} neurons (the fewest without "
            f"Dale's law: {e.minimum}; Dale's law costs {e.cost})",
        )
        say(_console, e.table())


def _fields(result, names) -> dict:
    """The attributes ``names`` of a result, as JSON values."""
    values = (getattr(result, k) for k in names)
    return {k: dict(v) if isinstance(v, Mapping) else v for k, v in zip(names, values, strict=True)}


def _circuit(name: str, system):
    """A circuit name, or an atlas label of G2's order (1 or 2)."""
    from symctl.errors import ParameterError
    from symctl.realization.realizers import circuit_names

    if name in circuit_names(whole=False):
        return name
    if not (name[:1] == "A" and name[1:].isdigit()):
        raise ParameterError(
            f"--circuit: {name!r} is not {', '.join(circuit_names(whole=False))} or an atlas label"
        )
    from symctl.circuitatlas.atlas import atlas
    from symctl.design.controller import controller_tf

    order = controller_tf(system).order  # G2 has G's order (the sections cancel nothing)
    if order > 2:
        raise ParameterError(
            f"--circuit: atlas labels are for G2 of order 1 or 2, this controller's is {order}"
        )
    classes = {c.label: c for c in atlas(order, workers=1).classes}
    if name not in classes:
        raise ParameterError(f"--circuit: the order-{order} atlas has no class {name!r}")
    return classes[name]
