r"""A document as a list of blocks, written as LaTeX, Markdown and PDF.

:func:`to_tex` and :func:`to_markdown` render the same blocks, so the two documents tell the
same story with the same numbers; prose holds inline math between ``$`` signs, citations and
references (:mod:`symctl.report.prose`)."""

from __future__ import annotations

import re
import shutil
import subprocess
import typing
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from symctl import latex as L
from symctl.errors import LatexError, SymctlTypeError
from symctl.report import longform as LF
from symctl.report.longform import MD_LINE, TABLE_MAX_ROWS
from symctl.report.prose import markdown_lines, markdown_text, tex_text, verbatim_lines

__all__ = [
    "BLOCKS",
    "PDFLATEX_TIMEOUT",
    "TITLE",
    "DocumentBlock",
    "Graphic",
    "Heading",
    "Math",
    "References",
    "Table",
    "Text",
    "Verbatim",
    "compile_pdf",
    "to_markdown",
    "to_tex",
    "write_markdown",
    "write_tex",
]

TITLE = "Toward neuronal implementations of delayed optimal control: the derivation"
AUTHOR = (
    r"Derived by symctl \\ \small with the method of Jing Shuang (Lisa) Li, \\ "
    r"\small\emph{Toward Neuronal Implementations of Delayed Optimal Control}"
)
PDFLATEX_TIMEOUT = 180  # seconds


@dataclass(frozen=True)
class Heading:
    """A section heading; ``level`` 1 is a section, 2 a subsection."""

    text: str
    level: int = 1


@dataclass(frozen=True)
class Text:
    """A paragraph; inline math between ``$`` signs."""

    text: str


@dataclass(frozen=True)
class Math:
    """One numbered display: rows ``(lhs, rhs)`` of LaTeX aligned at ``=`` (``lhs`` None: the
    row above continues); a ``breakable`` one may break across pages."""

    rows: tuple
    label: str
    breakable: bool = False


@dataclass(frozen=True)
class Table:
    """A table of prose cells; with a ``caption`` a numbered float (``[#tab:label]``)."""

    header: tuple
    rows: tuple
    caption: str = ""
    label: str = ""


@dataclass(frozen=True)
class Graphic:
    """A figure: LaTeX includes ``<name>.pdf`` at its natural size, Markdown ``<name>.png``."""

    name: str
    caption: str


@dataclass(frozen=True)
class Verbatim:
    """Preformatted text, shown as it is."""

    text: str


@dataclass(frozen=True)
class References:
    """The bibliography: ``(key, entry)`` pairs, numbered in this order (cited as ``[@key]``)."""

    entries: tuple


# any block of a document (not a structure's Block), and their types
DocumentBlock = Heading | Text | Math | Table | Graphic | Verbatim | References
BLOCKS = typing.get_args(DocumentBlock)


# \fitmath shrinks a display a little wider than the line (logged "symctl: shrunk"); one wider
# than SHRINK_MAX lines is left overfull. \fitgraphic and \symctlbarrier: see preamble.tex.
_PREAMBLE = Path(__file__).with_name("preamble.tex").read_text().rstrip("\n")
_PREAMBLE = _PREAMBLE.replace("<2\\linewidth", f"<{LF.SHRINK_MAX}\\linewidth")


def _row(lhs, rhs) -> str:
    """One row of an aligned display; ``lhs`` None: a continuation line."""
    return f"& {rhs}" if lhs is None else f"{lhs} &= {rhs}"


def _tex_math(b: Math) -> str:
    if b.breakable:
        rows = [
            _row(lhs, rhs) + ("" if k else rf" \label{{{b.label}}}") + (r" \notag" if k else "")
            for k, (lhs, rhs) in enumerate(b.rows)
        ]
        return "\n".join([r"\begin{align}", "  " + " \\\\\n  ".join(rows), r"\end{align}"])
    rows = r" \\ ".join(_row(lhs, rhs) for lhs, rhs in b.rows)
    body = rf"  \fitmath{{\begin{{aligned}}{rows}\end{{aligned}}}}"
    return "\n".join([r"\begin{equation}", body, rf"  \label{{{b.label}}}", r"\end{equation}"])


_WRAP = r">{\raggedright\arraybackslash}"  # a wrapped column


def _columns(b: Table, long: bool) -> tuple[str, str, str]:
    """The column spec, the font size and the environment of a table (tabularx when it wraps)."""
    wrap = LF.wrapped_columns(b.header, b.rows)
    if not wrap:
        wide = LF.table_width(b.header, b.rows) > LF.TABLE_WIDTH
        size = r"\footnotesize\setlength{\tabcolsep}{3pt}" if wide else r"\small"
        return "l" * len(b.header), size, "longtable" if long else "tabular"
    if not long:
        cols = "".join(_WRAP + "X" if j in wrap else "l" for j in range(len(b.header)))
        return cols, r"\small", "tabularx"
    # longtable cannot stretch columns: the wrapped ones share what the others leave
    widths = LF.column_widths(b.header, b.rows)
    others = sum(w for j, w in enumerate(widths) if j not in wrap) * _SMALL_UNIT_PT
    share = rf"\dimexpr(\linewidth-{others:.0f}pt-{2 * len(widths)}\tabcolsep)/{len(wrap)}\relax"
    cols = "".join(_WRAP + f"p{{{share}}}" if j in wrap else "l" for j in range(len(widths)))
    return cols, r"\small", "longtable"


_SMALL_UNIT_PT = 5.0  # points per unit of longform.cell_width at \small (4.4, rounded up)


def _tex_table(b: Table) -> str:
    long = len(b.rows) > TABLE_MAX_ROWS
    cols, size, env = _columns(b, long)
    width = r"{\linewidth}" if env == "tabularx" else ""
    body = [" & ".join(tex_text(c) for c in b.header) + r" \\ \hline"]
    body += [" & ".join(tex_text(c) for c in row) + r" \\" for row in b.rows]
    caption = rf"\caption{{{tex_text(b.caption)}}}" if b.caption else ""
    label = rf"\label{{tab:{b.label}}}" if b.caption and b.label else ""
    label += r"\vspace{0.5ex}" if b.caption and not long else ""
    if long:
        top = [rf"{caption}{label}\\"] if caption else []
        head = [rf"{{{size}", rf"\begin{{longtable}}{{{cols}}}", *top, r"\hline", body[0]]
        foot = [r"\endhead", r"\hline", r"\endfoot", *body[1:], r"\end{longtable}}"]
        return "\n".join(head + foot)
    table = [rf"\begin{{{env}}}{width}{{{cols}}}", r"\hline", *body, r"\hline", rf"\end{{{env}}}"]
    if caption:
        return "\n".join(
            [r"\begin{table}[htbp]\centering", caption + label, size, *table, r"\end{table}"]
        )
    return "\n".join([rf"\begin{{center}}{size}", *table, r"\end{center}"])


def _tex_references(b: References) -> str:
    items = [rf"\bibitem{{{key}}} {tex_text(text)}" for key, text in b.entries]
    return "\n".join(
        [r"\symctlbarrier", r"\begin{thebibliography}{9}", *items, r"\end{thebibliography}"]
    )


def _tex_block(b) -> str:
    if isinstance(b, Heading):
        command = rf"\{'sub' * (b.level - 1)}section{{{tex_text(b.text)}}}"
        return rf"\symctlbarrier{command}" if b.level == 1 else command
    if isinstance(b, Text):
        return tex_text(b.text)
    if isinstance(b, Math):
        return _tex_math(b)
    if isinstance(b, Table):
        return _tex_table(b)
    if isinstance(b, References):
        return _tex_references(b)
    if isinstance(b, Graphic):
        return "\n".join(
            [
                r"\begin{figure}[htbp]\centering",
                rf"\fitgraphic{{{b.name}.pdf}}",
                rf"\caption{{{tex_text(b.caption)}}}\label{{fig:{b.name}}}",
                r"\end{figure}",
            ]
        )
    return "\n".join(
        [r"{\footnotesize", r"\begin{verbatim}", *verbatim_lines(b.text), r"\end{verbatim}", "}"]
    )


def to_tex(blocks: Sequence[DocumentBlock], *, title: str = TITLE) -> str:
    r"""The blocks (instances of :data:`BLOCKS`) as a standalone LaTeX document for ``pdflatex``;
    ``title`` is prose. SymctlTypeError names an element that is not a block."""
    parts = [_tex_block(b) for b in _checked(blocks)]
    packages = [
        p
        for p in ("array", "longtable", "tabularx")
        if any(rf"\begin{{{p}}}" in part or (p == "array" and _WRAP in part) for part in parts)
    ]
    return L.document(
        parts, title=tex_text(title), author=AUTHOR, packages=packages, preamble=_PREAMBLE
    )


def _md_cell(text: str) -> str:
    return text.replace("|", r"\|")


def to_markdown(blocks: Sequence[DocumentBlock], *, title: str = TITLE) -> str:
    r"""The blocks as Markdown with ``$$`` math (numbered by ``\tag``) and the figures inline."""
    numbers = _numbers(_checked(blocks))

    def text(t: str) -> str:
        return markdown_text(t, numbers)

    out = [f"# {title}", ""]
    number = figure = table = 0
    for b in blocks:
        if isinstance(b, Heading):
            out += [f"{'#' * (b.level + 1)} {text(b.text)}", ""]
        elif isinstance(b, Text):
            out += [*markdown_lines(text(b.text)), ""]
        elif isinstance(b, Math):
            number += 1
            rows = [_row(lhs, rhs) for lhs, rhs in b.rows]
            one = r" \\ ".join(rows)
            line = rf"\begin{{aligned}}{one}\end{{aligned}}\tag{{{number}}}"
            if len(line) <= MD_LINE:
                out += ["$$", line, "$$", ""]
            else:
                body = [r + r" \\" for r in rows[:-1]] + rows[-1:]
                body = [line for r in body for line in _md_math_lines(r)]
                end = rf"\end{{aligned}}\tag{{{number}}}"
                out += ["$$", r"\begin{aligned}", *body, end, "$$", ""]
        elif isinstance(b, Table):
            if b.caption:
                table += 1
                out += [f"*Table {table}: {text(b.caption)}*", ""]
            out.append("| " + " | ".join(_md_cell(text(c)) for c in b.header) + " |")
            out.append("|" + "---|" * len(b.header))
            out += ["| " + " | ".join(_md_cell(text(c)) for c in row) + " |" for row in b.rows]
            out.append("")
        elif isinstance(b, Graphic):
            figure += 1
            caption = text(b.caption)
            alt = caption.replace("[", "(").replace("]", ")")  # an image's text has no brackets
            out += [f"![{alt}]({b.name}.png)", "", f"*Figure {figure}: {caption}*", ""]
        elif isinstance(b, References):
            out += ["## References", ""]
            out += [f"[{k}] {text(entry)}  " for k, (_, entry) in enumerate(b.entries, 1)]
            out.append("")
        else:
            out += ["```", *verbatim_lines(b.text), "```", ""]
    return "\n".join(out)


def _numbers(blocks: Sequence[DocumentBlock]) -> dict[str, int]:
    """The number of every figure, captioned table, display and reference, by its mark."""
    numbers: dict[str, int] = {}
    count = {"fig": 0, "tab": 0, "eq": 0}

    def number(kind: str, name: str) -> None:
        count[kind] += 1
        numbers.setdefault(f"{kind}:{name}", count[kind])

    for b in blocks:
        if isinstance(b, Graphic):
            number("fig", b.name)
        elif isinstance(b, Math):
            number("eq", b.label.removeprefix("eq:"))
        elif isinstance(b, Table) and b.caption:
            number("tab", b.label or f"table-{count['tab'] + 1}")
        elif isinstance(b, References):
            for k, (key, _) in enumerate(b.entries, 1):
                numbers.setdefault(key, k)
    return numbers


def _md_math_lines(row: str) -> list[str]:
    """A long row of display math as lines of about :data:`MD_LINE` characters, cut after ``\\\\``."""
    if len(row) <= MD_LINE:
        return [row]
    lines = [""]
    for piece in re.split(r"(?<=\\\\)(?!\\)", row):
        if lines[-1] and len(lines[-1]) + len(piece) > MD_LINE:
            lines.append(piece)
        else:
            lines[-1] += piece
    return lines


def _checked(blocks: Sequence) -> Sequence[DocumentBlock]:
    for i, b in enumerate(blocks):
        if not isinstance(b, BLOCKS):
            raise SymctlTypeError(
                f"blocks: element {i} is a {type(b).__name__}, not a block "
                f"({', '.join(t.__name__ for t in BLOCKS)})"
            )
    return blocks


def write_tex(blocks: Sequence[DocumentBlock], path: Path | str, *, title: str = TITLE) -> Path:
    r"""Write :func:`to_tex` of ``blocks`` to ``path``; returns the path."""
    path = Path(path)
    path.write_text(to_tex(blocks, title=title), encoding="utf-8")
    return path


def write_markdown(
    blocks: Sequence[DocumentBlock], path: Path | str, *, title: str = TITLE
) -> Path:
    r"""Write :func:`to_markdown` of ``blocks`` to ``path``; returns the path."""
    path = Path(path)
    path.write_text(to_markdown(blocks, title=title), encoding="utf-8")
    return path


def compile_pdf(tex: Path | str, *, pdflatex: str | None = None) -> Path | None:
    """Compile ``tex`` with ``pdflatex`` (by default the one on the PATH) next to it, twice when the
    log asks, leaving only the PDF; returns it, or None without ``pdflatex``.

    LatexError: ``pdflatex`` failed (its first error line is in the message), could not be run, or
    took longer than ``PDFLATEX_TIMEOUT`` seconds."""
    tex = Path(tex)
    exe = pdflatex or shutil.which("pdflatex")
    if exe is None:
        return None
    cmd = [exe, "-interaction=nonstopmode", "-halt-on-error", tex.name]
    log = tex.with_suffix(".log")
    passes = 2 if re.search(r"\\((eq)?ref|cite)\b", tex.read_text(errors="replace")) else 1
    for _ in range(passes):
        try:
            run = subprocess.run(
                cmd,
                cwd=tex.parent,
                capture_output=True,
                text=True,
                timeout=PDFLATEX_TIMEOUT,
                errors="replace",
            )
        except subprocess.TimeoutExpired:
            raise LatexError(
                f"pdflatex did not finish {tex.name} within {PDFLATEX_TIMEOUT} s"
            ) from None
        except OSError as exc:  # not executable, vanished
            raise LatexError(f"pdflatex could not run on {tex.name}: {exc}") from None
        text = log.read_text(errors="replace") if log.exists() else run.stdout
        if run.returncode != 0:
            first = next((ln for ln in text.splitlines() if ln.startswith("!")), "no error line")
            raise LatexError(f"pdflatex failed on {tex.name}: {first} (see {log.name})")
        if not re.search(r"Rerun to get", text):
            break
    for ext in (".aux", ".log", ".out"):
        tex.with_suffix(ext).unlink(missing_ok=True)
    return tex.with_suffix(".pdf")
