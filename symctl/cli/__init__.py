"""The ``symctl`` command (orchestration only: the math lives in the library)."""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
import warnings
from pathlib import Path

import click
from rich.console import Console
from rich.table import Table

from symctl._util.parse import parse_matrix
from symctl.cli.dale import dale_command
from symctl.cli.fit import fit_command
from symctl.cli.options import (
    Command,
    options,
    progress_file,
    shown,
    workers_options,
    writing_options,
)
from symctl.cli.progress import Steps, say
from symctl.cli.spiking import spiking_command
from symctl.cli.summary import summary
from symctl.errors import SymctlError
from symctl.report.spec import PAPER

__all__ = ["main", "run"]

_console = Console()


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="symctl")
def cli() -> None:
    """Derive, check and simulate neural implementations of delayed optimal controllers."""


cli.command_class = Command  # errors name the options as typed
cli.add_command(fit_command)  # symctl fit (symctl/cli/fit.py)
cli.add_command(dale_command)  # symctl dale (symctl/cli/dale.py)
cli.add_command(spiking_command)  # symctl spiking (symctl/cli/spiking.py)


@cli.command()
@options(
    shown("--tau", type=float, default=PAPER.tau, help="Muscle time constant [s]."),
    shown("--f-max", type=float, default=PAPER.f_max, help="Maximum force [N]."),
    shown("--r-bar", type=float, default=PAPER.r_bar, help="Equilibrium firing rate [spikes/s]."),
    shown("--ts", "dt", type=float, default=PAPER.Ts, help="Sampling time [s]."),
    shown("--sensor-delay", type=int, default=PAPER.sensor_delay, help="Sensor delay [steps]."),
    shown(
        "--actuator-delay", type=int, default=PAPER.actuator_delay, help="Actuator delay [steps]."
    ),
    shown(
        "--q", "q_text", default="1", help="State penalty Q: a number or a matrix such as '[[1]]'."
    ),
    shown("--r", "r_text", default="1", help="Input penalty R: a number or a matrix."),
    shown("--seed", "rng", type=int, default=PAPER.seed, help="Seed for the random realizations."),
    shown(
        "--realizations",
        type=click.IntRange(min=1),
        default=PAPER.realizations,
        help="Random realizations simulated per circuit.",
    ),
    shown(
        "--out",
        default="out/paper",
        help="Output folder: new, empty, or an earlier run's (replaced when the run is complete).",
    ),
    writing_options,
    click.option(
        "--spiking",
        is_flag=True,
        help="Add the section on what spikes cost each circuit: 3 sizes x 10 seeds of every "
        "circuit in nengo (minutes; needs pip install symctl[spiking]).",
    ),
    workers_options("Local processes running the --spiking sweep (the atlas's dask path)."),
)
def paper(q_text, r_text, out, spiking, workers, scheduler, **params) -> None:
    """Run the paper's derivation and write it into OUT.

    Writes results.json, derivation.tex (and derivation.pdf), report.md and the
    figures (PDF and PNG; SVG with --formats pdf,png,svg)."""
    writing = {k: params.pop(k) for k in _WRITING}
    try:
        params.update(Q=parse_matrix(q_text, "--q"), R=parse_matrix(r_text, "--r"))
    except _NUMERICAL as exc:
        exc._symctl_step = "options"
        raise
    sweep = dict(workers=workers, scheduler=scheduler, checkpoint=progress_file(out))

    def derivation(progress, early):
        import dataclasses

        from symctl.derivation.pipeline import derive_paper

        res = derive_paper(progress=progress, early=early, **params)
        if not spiking:
            return res
        from symctl.spiking.cost import spiking_cost

        progress("spiking")
        return dataclasses.replace(res, spiking_cost=spiking_cost(res, **sweep))

    _written(out, derivation, **writing)
    sweep["checkpoint"].unlink(missing_ok=True)


_WRITING = ("figures", "formats", "pdf", "jobs")  # the writing_options' parameters


@cli.command("derive")
@click.argument("model_file", metavar="MODEL.toml", type=click.Path(dir_okay=False))
@click.option("--out", default=None, help="Output folder [default: out/<model name>].")
@click.option(
    "--check", is_flag=True, default=False, help="Validate the model file and exit; run nothing."
)
@writing_options
def derive_command(model_file, out, check, **writing) -> None:
    """Run the whole derivation on your own system, described in MODEL.toml.

    The same pipeline and outputs as `symctl paper` (which is this command on
    examples/muscle.toml): results.json, derivation.tex (and .pdf), report.md and
    the figures, titled with the model's names and units. The model file's
    format is in docs/model-file.md. With --check the file is only read and
    checked."""
    from symctl.derivation.pipeline import derive
    from symctl.model.modelfile import load_model

    model = load_model(Path(model_file))
    for note in model.notes:
        say(_console, f"note: {note}")
    if check:
        say(_console, _check_line(model))
        return
    try:
        folder = out if out is not None else f"out/{model.name}"
        _written(
            folder,
            lambda progress, early: derive(model, progress=progress, early=early),
            **writing,
        )
    except _NUMERICAL as exc:  # named with the model file (main's one-line message)
        with contextlib.suppress(AttributeError):
            exc._symctl_inputs = f"the model file {model_file}"
        raise


def _check_line(model) -> str:
    xs, us = model.signal_names
    kind = "ODE" if model.ode is not None else "discrete plant"
    graph = (
        f"a delay graph of {len(model.vertices)} vertices"
        if model.graph_given
        else "the chain of the delays"
    )
    return (
        f"{model.path}: ok: {model.name!r}, {kind} with states {', '.join(xs)} and inputs "
        f"{', '.join(us)}, Ts = {model.dt:g} s, delays {model.sensor_delay} + "
        f"{model.actuator_delay} steps, {graph}; circuits {', '.join(model.circuits)}"
    )


def _drawings(ctx, param, value: str) -> int | None:
    if value == "all":
        return None
    if not value.isdigit():
        raise click.BadParameter("must be a number >= 0 or 'all'")
    return int(value)


@cli.command("atlas")
@options(
    click.option(
        "--order", type=int, required=True, help="Order n of G2 (1 to 4; 1-3 exhaustive)."
    ),
    shown(
        "--delays",
        type=click.Choice(["branch", "state"]),
        default="branch",
        help="Where the structure's unit delays sit.",
    ),
    click.option(
        "--max-size",
        type=int,
        default=None,
        help="Largest pattern size searched [default: all for orders 1-3, 3n for order 4].",
    ),
    click.option("--workers", type=int, help="Worker processes [default: every local core]."),
    click.option(
        "--scheduler",
        help="Address of a running dask.distributed scheduler [default: a local cluster].",
    ),
    shown(
        "--drawings",
        default="24",
        callback=_drawings,
        help="Classes drawn one by one (the sparsest first), or 'all'.",
    ),
    click.option(
        "--max-neurons",
        type=int,
        help="Decide only patterns whose circuits have at most this many neurons "
        "[default: all for orders 1-3, 3 for order 4].",
    ),
    shown("--out", default="out/atlas", help="Output folder."),
    shown("--pdf/--no-pdf", default=True, help="Compile atlas.pdf."),
)
def atlas_command(order, drawings, out, pdf, **search) -> None:
    """Find every minimal circuit class of order-N controllers and write the atlas into OUT.

    Writes atlas.json, atlas.md, atlas.tex (and atlas.pdf), an overview figure and
    one drawing per class. Finished patterns go to OUT.progress.jsonl as the
    search runs, so an interrupted run resumes where it stopped."""
    from symctl.circuitatlas.atlas import atlas as find_atlas
    from symctl.report.atlas import write_atlas
    from symctl.report.output import OutputFolder

    checkpoint = progress_file(out)
    with OutputFolder(out, "--out") as folder, Steps(_console) as steps:
        steps.start("search")

        def progress(size, done, total):
            steps.part(f"size {size}: {done} of {total}")

        A = find_atlas(order, checkpoint=checkpoint, progress=progress, **search)
        written = write_atlas(A, folder.staging, drawings=drawings, pdf=pdf, progress=steps.start)
    checkpoint.unlink(missing_ok=True)
    _atlas_summary(A)
    _wrote(Path(out), folder.final(written), pdf)


def _atlas_summary(A) -> None:
    s = A.stats
    _console.print(
        f"order {A.order}: {s['patterns']} patterns, {s['canonical']} up to permutation, "
        f"{s['minimal']} minimal, {s['full_rank']} of full rank; {len(A.classes)} circuit classes, "
        f"{len(A.universal_classes)} universal, {len(A.conjectured_classes)} conjectured, "
        f"{s['undecided']} undecided ({s['seconds']:g} s)"
    )
    table = Table(title=f"circuit classes of order {A.order} (the first 15)")
    cols = ("class", "neurons", "synapses", "branches", "pattern F | H | M", "universal", "method")
    for col in cols:
        table.add_column(col)
    for row, c in zip(A.table()[:15], A.classes, strict=False):
        counts = (str(row[k]) for k in ("class", "neurons", "synapses", "branches"))
        table.add_row(*counts, c.representatives[0].text, row["universal"], row["method"])
    _console.print(table)


def _written(out, derivation, **kw) -> None:
    """Derive (``derivation(progress, early)``) and write into ``out``, checked and staged first;
    the circuits' figures are drawn while the derivation goes on past them."""
    from symctl.report.figures import start_figures
    from symctl.report.output import OutputFolder
    from symctl.report.results import write_files
    from symctl.report.workers import FigureWorkers

    workers = FigureWorkers(kw["jobs"] if kw["figures"] else 1)  # ready when they are needed
    drawn = []

    def early(part) -> None:
        drawn.append(start_figures(part, folder.staging, workers, formats=kw["formats"]))

    with OutputFolder(out, "--out") as folder, workers, Steps(_console, lines=True) as steps:
        res = derivation(steps.start, early if kw["figures"] else None)
        written = write_files(
            res,
            folder.staging,
            progress=steps.start,
            parts=steps.part,
            workers=workers,
            drawn=drawn[0] if drawn else None,
            **kw,
        )
    summary(res, _console)
    _wrote(Path(out), folder.final(written), kw.get("pdf", False))


def _wrote(out: Path, written: list[Path], pdf: bool) -> None:
    docs = [p.name for p in written if p.stem in ("results", "derivation", "report")]
    drawn = [p for p in written if p.name not in docs]
    figures = sorted({p.stem for p in drawn})
    line = f"wrote {out}/: " + ", ".join(docs)
    if figures:
        kinds = ", ".join(dict.fromkeys(p.suffix[1:].upper() for p in drawn))  # as written
        line += f", {len(figures)} figures ({kinds}): " + ", ".join(figures)
    say(_console, line)
    if pdf and not any(n.endswith(".pdf") for n in docs):
        say(
            _console,
            "note: pdflatex not found, the PDF was not compiled (install TeX Live's "
            "texlive-latex-base)",
        )


# the options each step of derive_paper depends on: named when NumPy or SciPy fails in it
_STEP_OPTIONS = {
    "options": "--q, --r",
    "plant": "--tau, --f-max, --r-bar, --ts",
    "delays": "--sensor-delay, --actuator-delay, --q, --r",
    "LQR": "--q, --r, --tau, --f-max, --r-bar, --ts, --sensor-delay, --actuator-delay",
    "G(z)": "--sensor-delay, --actuator-delay",
    "factorization": "--sensor-delay, --actuator-delay",
    "simulation": "--seed, --realizations, --sensor-delay, --actuator-delay",
    "realizations": "--seed, --sensor-delay, --actuator-delay",
    "compatibility": "--sensor-delay, --actuator-delay, --tau, --f-max",
    "closed loop": "--tau, --f-max, --r-bar, --ts, --sensor-delay, --actuator-delay",
    "nonlinear": "--tau, --f-max, --r-bar, --ts, --sensor-delay, --actuator-delay",
    "figures": "--jobs, --out",
    "documents": "--out",
    "pdflatex": "--pdf, --out",
}
# foreign exceptions that bad input values cause in NumPy, SciPy or SymPy: exit 2, as bad input
_NUMERICAL = (ArithmeticError, MemoryError, RecursionError, TypeError, ValueError)


class _Signalled(BaseException):
    """SIGINT or SIGTERM, raised in the main thread so that every ``finally`` and ``with`` runs."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def _on_signal(signum, _frame) -> None:
    for sig in (signal.SIGINT, signal.SIGTERM):  # one is enough: the cleanup is not interrupted
        signal.signal(sig, signal.SIG_IGN)
    raise _Signalled(signum)


def _error(text: str) -> None:
    click.echo(text.splitlines()[0] if text.strip() else text, err=True)


def _warned(caught: list) -> None:
    """NumPy, SciPy and symctl warnings of a successful run as one line on stderr."""
    seen = list(dict.fromkeys(f"{w.category.__name__}: {w.message}" for w in caught))
    if seen:
        more = f" (and {len(seen) - 1} other warnings)" if len(seen) > 1 else ""
        _error(f"symctl: warning: {seen[0]}{more}; check the results")


def main(argv: list[str] | None = None) -> int:
    """Run the ``symctl`` command on ``argv`` (default ``sys.argv[1:]``); returns its exit code.

    Exit codes: 0 on success; 2 on bad input (named by option, or by step and the options it
    reads); 1 on an internal error or when aborted; 130 on SIGINT and 143 on SIGTERM, which stop
    the run cleanly, ``--out`` as it was. Only single lines reach stderr (an error, a successful
    run's warnings, an interruption); ``SYMCTL_TRACEBACK=1`` shows an unexpected exception's traceback.

    >>> from symctl.cli import main
    >>> main(["paper", "--realizations", "0"])
    2
    """
    handlers = {}
    if threading.current_thread() is threading.main_thread():
        handlers = {sig: signal.signal(sig, _on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            code = _run_cli(argv)
        if code == 0:
            _warned(caught)
        return code
    except _Signalled as sig:
        name = signal.Signals(sig.signum).name
        _error(f"symctl: interrupted by {name}; nothing written, --out left as it was")
        return 128 + sig.signum
    except Exception as exc:  # the last resort: one line, not a traceback
        if os.environ.get("SYMCTL_TRACEBACK"):
            raise
        _error(
            f"symctl: internal error: {type(exc).__name__}: {_first_line(exc)} (a bug in symctl: "
            "please report it; SYMCTL_TRACEBACK=1 shows the traceback)"
        )
        return 1
    finally:
        for sig, handler in handlers.items():
            signal.signal(sig, handler)


def _run_cli(argv: list[str] | None) -> int:
    try:
        cli.main(args=argv, prog_name="symctl", standalone_mode=False)
    except click.exceptions.Abort:
        _error("symctl: aborted")
        return 1
    except click.ClickException as exc:
        _error(f"symctl: error: {exc.format_message()}")
        return 2
    except SymctlError as exc:  # type errors included
        _error(f"symctl: error: {exc}")
        return 2
    except OSError as exc:  # writing into --out failed (it is left as it was)
        _error(f"symctl: error: --out: {exc}")
        return 2
    except _NUMERICAL as exc:
        step = getattr(exc, "_symctl_step", None)
        inputs = getattr(exc, "_symctl_inputs", None)  # symctl derive: the model file
        known = step in _STEP_OPTIONS or (inputs is not None and step is not None)
        if not known or os.environ.get("SYMCTL_TRACEBACK"):
            raise  # not in a step that user input drives: the last resort in main
        where = "reading" if step == "options" else f"the {step} step failed on"
        _error(
            f"symctl: error: {where} {inputs or _STEP_OPTIONS[step]}: {type(exc).__name__}: "
            f"{_first_line(exc)}"
        )
        return 2
    return 0


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return text.splitlines()[0] if text else "(no message)"


def run() -> None:  # pragma: no cover - console-script wrapper
    """The console script ``symctl``: exits with :func:`main`'s code, once every file is closed
    and the output flushed, without the interpreter's teardown (which frees the derivation's
    SymPy objects one by one: 0.2 s idle, 1 s on a loaded machine)."""
    code = main()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
