r"""Prose of a document: escaped for LaTeX, its citations and references, wrapped lines.

Outside the inline math (``$...$``), :func:`tex_text` escapes LaTeX's special characters
and :func:`markdown_text` numbers two marks: ``[@key]`` or ``[@key, locator]`` cites the
bibliography, ``[#fig:name]``, ``[#tab:label]`` or ``[#eq:label]`` refers to a figure, a
captioned table or a display. A space before a mark becomes a tie in LaTeX."""

from __future__ import annotations

import re
import textwrap

__all__ = ["MARK", "VERBATIM_LINE", "markdown_lines", "markdown_text", "tex_text", "verbatim_lines"]

_SPECIAL = {
    "\\": r"\textbackslash{}",
    "&": r"\&",
    "%": r"\%",
    "#": r"\#",
    "_": r"\_",
    "{": r"\{",
    "}": r"\}",
    "~": r"\textasciitilde{}",
    "^": r"\textasciicircum{}",
    "/": r"\slash{}",  # a line may break after a slash (a file's path in prose), at a small cost
}


MARK = re.compile(
    r"\[@(?P<key>[A-Za-z][\w:.\-]*)(?:,\s*(?P<loc>[^\]$]+))?\]"
    r"|\[#(?P<ref>(?:fig|tab|eq):[A-Za-z0-9:._\-]+)\]"
)  # a citation [@key, locator] or a reference [#fig:name] in prose (outside math)


def _escape(text: str) -> str:
    return "".join(_SPECIAL.get(ch, ch) for ch in text)


def _tex_mark(m: re.Match) -> str:
    if m["ref"] is not None:
        return (r"\eqref" if m["ref"].startswith("eq:") else r"\ref") + f"{{{m['ref']}}}"
    loc = f"[{_escape(m['loc'].strip())}]" if m["loc"] else ""
    return rf"\cite{loc}{{{m['key']}}}"


def _tex_prose(text: str) -> str:
    """Prose outside math: escaped, its marks as LaTeX (tied to the word before them)."""
    out, last = [], 0
    for m in MARK.finditer(text):
        before = _escape(text[last : m.start()])
        out.append(before[:-1] + "~" if before.endswith(" ") else before)
        out.append(_tex_mark(m))
        last = m.end()
    out.append(_escape(text[last:]))
    return "".join(out)


def _outside_math(text: str, change) -> str:
    """``text`` with ``change`` applied to its prose, the parts outside ``$...$``."""
    parts = text.split("$")
    return "$".join(change(part) if k % 2 == 0 else part for k, part in enumerate(parts))


def tex_text(text: str) -> str:
    r"""Prose for LaTeX: escaped outside ``$...$``, its marks as ``\cite``/``\ref``, the math kept."""
    return _outside_math(text, _tex_prose)


def markdown_text(text: str, numbers: dict[str, int]) -> str:
    """Prose for Markdown: its marks as the ``numbers`` of their keys (``??`` unknown)."""

    def mark(m: re.Match) -> str:
        if m["ref"] is not None:
            n = numbers.get(m["ref"])
            shown = "??" if n is None else str(n)
            return f"({shown})" if m["ref"].startswith("eq:") else shown
        n = numbers.get(m["key"])
        loc = f", {m['loc'].strip()}" if m["loc"] else ""
        return f"[{'??' if n is None else n}{loc}]"

    return _outside_math(text, lambda prose: MARK.sub(mark, prose))


VERBATIM_LINE = 96  # characters of a line of preformatted (footnotesize typewriter) text


def verbatim_lines(text: str) -> list[str]:
    """Preformatted text wrapped at :data:`VERBATIM_LINE` characters, continuations indented."""
    out = []
    for line in text.splitlines():
        indent = " " * (len(line) - len(line.lstrip()))
        out += textwrap.wrap(line, VERBATIM_LINE, subsequent_indent=indent + "    ") or [""]
    return out


def markdown_lines(text: str) -> list[str]:
    """Prose as lines of at most about 100 characters, never breaking inside ``$...$``."""
    if len(text) <= 100:
        return [text]
    words = _outside_math(text, lambda prose: prose.replace(" ", "\0")).split("\0")
    lines = [""]
    for w in words:
        if lines[-1] and len(lines[-1]) + 1 + len(w) > 100:
            lines.append(w)
        else:
            lines[-1] = f"{lines[-1]} {w}" if lines[-1] else w
    return lines
