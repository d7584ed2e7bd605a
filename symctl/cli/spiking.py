"""``symctl spiking``: what spikes cost each circuit of a model's controller (or the paper's)."""

from __future__ import annotations

from pathlib import Path

import click
from rich.console import Console

from symctl.cli.options import Command, options, progress_file, shown, workers_options
from symctl.cli.progress import Steps, say

__all__ = ["spiking_command"]

_console = Console()


def _sizes(ctx, param, value: str) -> tuple[int, ...]:
    try:
        sizes = tuple(int(x) for x in value.split(",") if x.strip())
    except ValueError:
        raise click.BadParameter(
            f"expected whole numbers separated by commas, got {value!r}"
        ) from None
    from symctl.spiking.nengo_export import MAX_POPULATION

    if not sizes or not all(1 <= n <= MAX_POPULATION for n in sizes):
        raise click.BadParameter(f"expected sizes from 1 to {MAX_POPULATION:,}, got {value!r}")
    return sizes


@click.command("spiking", cls=Command)
@click.argument("model_file", metavar="[MODEL.toml]", required=False, default=None)
@options(
    shown(
        "--neurons",
        default="10,100,1000",
        callback=_sizes,
        help="Neurons per population, separated by commas (each 1 to 10,000).",
    ),
    shown("--seeds", type=click.IntRange(min=1), default=10, help="Seeds per size."),
    click.option(
        "--circuit",
        help="Circuits, separated by commas: the model's named circuits and atlas classes "
        "[default: all of them].",
    ),
    workers_options("Local processes running the simulations (the atlas's dask path)."),
    shown("--figures/--no-figures", default=True, help="Write the figure (PDF, PNG)."),
    shown("--out", default="out/spiking", help="Output folder."),
)
def spiking_command(model_file, circuit, figures, out, **sweep) -> None:
    """Run every circuit of the controller as spiking populations and price it in neurons.

    The controller is the optimal one of MODEL.toml (default: the paper's muscle
    model). Writes spiking.json, spiking.md (the table, cheapest first) and the
    figure spiking_cost into OUT. Finished runs go to OUT.progress.jsonl, so an
    interrupted sweep resumes where it stopped."""
    from symctl.derivation.pipeline import derive, derive_paper
    from symctl.model.modelfile import load_model
    from symctl.report.output import OutputFolder
    from symctl.report.spiking import write_spiking
    from symctl.spiking.cost import spiking_cost

    names = None if circuit is None else [c.strip() for c in circuit.split(",") if c.strip()]
    checkpoint = progress_file(out)
    with OutputFolder(out, "--out") as folder, Steps(_console) as steps:
        steps.start("derivation")
        res = derive_paper() if model_file is None else derive(load_model(Path(model_file)))
        steps.start("spiking sweep")

        def progress(done, total):
            steps.part(f"{done} of {total} runs")

        cost = spiking_cost(res, circuits=names, **sweep, checkpoint=checkpoint, progress=progress)
        steps.start("writing")
        written = write_spiking(cost, folder.staging, figures=figures)
    checkpoint.unlink(missing_ok=True)
    say(_console, cost.finding())
    say(_console, f"wrote {out}/: " + ", ".join(p.name for p in folder.final(written)))
