"""The commands' option plumbing: options stacked from one list, errors named by option."""

from __future__ import annotations

import contextlib
from pathlib import Path

import click

from symctl.errors import SymctlError

__all__ = ["Command", "options", "options_named", "progress_file", "shown", "writing_options"]


# library arguments named otherwise on the command line (used where the command has the option)
ALIASES = dict(dt="--ts", rng="--seed", Q="--q", R="--r", C="--C", circuits="--circuit")


@contextlib.contextmanager
def options_named(ctx: click.Context | None = None, aliases: dict = ALIASES):
    """Name the option as typed (``--f-max``), not the Python argument (``f_max``), in a symctl
    error whose message starts with arguments of the command of ``ctx`` (or of ``aliases``)."""
    params = ctx.command.params if ctx else []
    names = {p.name: p.opts[0] for p in params if isinstance(p, click.Option)}
    typed = set(names.values())
    names.update((k, v) for k, v in aliases.items() if ctx is None or v in typed)
    try:
        yield
    except SymctlError as exc:
        head, sep, rest = str(exc).partition(": ")
        args = head.split(", ")
        if not sep or not all(a in names for a in args):
            raise
        raise type(exc)(f"{', '.join(names[a] for a in args)}: {rest}") from exc


class Command(click.Command):
    """A command whose symctl errors name its options as typed (:func:`options_named`)."""

    def invoke(self, ctx: click.Context):
        with options_named(ctx):
            return super().invoke(ctx)


def shown(*decls, **kw):
    """A click option whose default ``--help`` shows."""
    return click.option(*decls, show_default=True, **kw)


def options(*decorators):
    """The click options ``decorators`` as one decorator, in the order listed."""

    def apply(command):
        for option in reversed(decorators):
            command = option(command)
        return command

    return apply


def _formats(ctx, param, value) -> tuple[str, ...]:
    from symctl.report.figures import figure_formats

    return figure_formats(value, "--formats")


writing_options = options(  # of symctl paper and derive (--formats checked before any work)
    shown("--figures/--no-figures", default=True, help="Write the figures."),
    shown(
        "--formats",
        default="pdf,png",
        callback=_formats,
        help="The figures' formats, comma-separated, among pdf, png and svg "
        "(derivation.tex includes the PDFs, report.md shows the PNGs).",
    ),
    shown(
        "--pdf/--no-pdf", default=True, help="Compile derivation.pdf (when pdflatex is installed)."
    ),
    click.option(
        "--jobs",
        type=click.IntRange(min=1),
        default=None,
        help="Processes drawing the figures [default: CPUs, at most 4].",
    ),
)


def workers_options(workers_help: str):
    """``--workers`` (local processes, 1 by default) and ``--scheduler`` (a dask address)."""
    return options(
        shown("--workers", type=click.IntRange(min=1), default=1, help=workers_help),
        click.option("--scheduler", default=None, help="Address of a dask.distributed scheduler."),
    )


def progress_file(out) -> Path:
    """``OUT.progress.jsonl``: the checkpoint from which an interrupted sweep into ``out`` resumes."""
    return Path(str(Path(out).absolute()) + ".progress.jsonl")
