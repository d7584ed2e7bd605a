"""The options of the commands that write a derivation: --figures, --formats, --pdf, --jobs.

Shared by ``symctl paper`` and ``symctl derive`` (:mod:`symctl.cli`). ``--formats`` is
checked when the command line is read, before any work: a bad value is one line and
exit 2, naming the option.

>>> from symctl.cli import main
>>> main(["paper", "--formats", "pdf,jpg"])
2
"""

from __future__ import annotations

import click

__all__ = ["writing_options"]


def _formats(ctx, param, value) -> tuple[str, ...]:
    from symctl.report.figures import figure_formats

    return figure_formats(value, "--formats")


def writing_options(command):
    """The options of a command that writes a derivation: --figures, --formats, --pdf, --jobs."""
    for option in reversed(
        (
            click.option(
                "--figures/--no-figures", default=True, show_default=True, help="Write the figures."
            ),
            click.option(
                "--formats",
                default="pdf,png",
                show_default=True,
                callback=_formats,
                help="The figures' formats, comma-separated, among pdf, png and svg "
                "(derivation.tex includes the PDFs, report.md shows the PNGs).",
            ),
            click.option(
                "--pdf/--no-pdf",
                default=True,
                show_default=True,
                help="Compile derivation.pdf (when pdflatex is installed).",
            ),
            click.option(
                "--jobs",
                type=click.IntRange(min=1),
                default=None,
                help="Processes drawing the figures [default: CPUs, at most 4].",
            ),
        )
    ):
        command = option(command)
    return command
