r"""Long objects laid out so that every line fits the page, decided by size: the estimated printed
width of a line (:func:`width`, in glyphs of the 11 pt math font) and of a table; :func:`fit_rows`
breaks a display too wide. Matrices: :mod:`symctl.report.matrixview`."""

from __future__ import annotations

import re

__all__ = ["column_widths", "fit_rows", "height", "table_width", "width", "wrapped_columns"]

LINE_WIDTH = 72.0  # glyphs of one display line, left-hand side and equation number included
TABLE_WIDTH = 100.0  # of a table row at \small (table_width); a wider one is \footnotesize
WRAP_MIN = 12.0  # least width of a prose column that a table wider than TABLE_WIDTH wraps
MATRIX_MAX_ROWS = 12  # a matrix with more rows (or columns) is never written in full
MATRIX_MAX_COLUMNS = 12
PATTERN_TABLE_ROWS = 2.0  # a large matrix with at most this many table rows per row: its pattern
CORNER = 3  # leading rows and columns shown of a large dense matrix (then dots, then the last)
LARGE_DIGITS = 4  # significant digits in a large matrix (the full values are in results.json)
TERM_MAX_LINES = 12  # an equation broken into more lines keeps its first TERM_MAX_LINES - 1, last
DIAGONAL_MIN = 4  # a diagonal matrix of this size or more is written diag(d_1, ..., d_n)
VECTOR_MAX_ENTRIES = 6  # a longer vector is written as a list (v_1, ..., v_n) (or e_k)
DISPLAY_MAX_LINES = 8  # a display taller than this (lines, height) may break across pages
INDENT = r"\qquad "  # of a continuation line
TABLE_MAX_ROWS = 30  # a table with more rows is a longtable, which breaks across pages
MD_LINE = 300  # a Markdown display whose one-line form is longer gets a line per row
SHRINK_MAX = 2  # a display up to this many times the line is shrunk to fit; wider: overfull

_TOKEN = re.compile(r"\\[A-Za-z]+\*?|\\.|[{}^_&]|\s+|.", re.S)
_SPACE = {",": 0.35, ":": 0.45, ">": 0.45, ";": 0.55, "!": -0.35, " ": 0.6}
_ARG1 = frozenset(
    "text textrm mathrm mathbf mathit mathcal mathbb operatorname boldsymbol bar tilde "
    "hat dot ddot vec overline widetilde sqrt textit textbf underline mathsf".split()
)
_TEXT = frozenset("text textrm operatorname textit textbf".split())
_SILENT = frozenset(
    "displaystyle textstyle scriptstyle limits nolimits label notag nonumber tag".split()
)
_BINARY = frozenset(
    "times cdot ge geq le leq to in pm mp neq approx equiv mapsto rightarrow leftarrow "
    "subset cup cap setminus".split()
)
_WIDE = dict.fromkeys("cdots ldots dots ddots sum prod".split(), 2.6) | {
    "vdots": 1.0,
    "infty": 1.8,
    "qquad": 4.0,
    "quad": 2.0,
}
_MATRICES = {"smallmatrix": 0.6, "cases": 2.0, "aligned": 0.0, "split": 0.0}  # others 1.9
_GLYPH = dict.fromkeys(",;", 1.0) | dict.fromkeys("()[]|/", 0.8) | dict.fromkeys(".'", 0.5)
_BRACKETS = {"bmatrix": 1.6, "pmatrix": 1.6, "vmatrix": 1.2, "cases": 1.6}


class _Reader:
    """A cursor over the tokens of a LaTeX string."""

    def __init__(self, tex: str) -> None:
        self.tokens = _TOKEN.findall(tex)
        self.i = 0

    def next(self) -> str | None:
        while self.i < len(self.tokens):
            t = self.tokens[self.i]
            self.i += 1
            if not t.isspace():
                return t
        return None

    def group(self) -> str:
        """The text of the next argument: a braced group or one token."""
        t = self.next()
        if t != "{":
            return t or ""
        depth, out = 1, []
        while self.i < len(self.tokens):
            t = self.tokens[self.i]
            self.i += 1
            depth += t == "{"
            depth -= t == "}"
            if depth == 0:
                break
            out.append(t)
        return "".join(out)

    def environment(self, name: str) -> str:
        """The body up to the matching ``\\end{name}``."""
        depth, out = 1, []
        while self.i < len(self.tokens):
            t = self.tokens[self.i]
            self.i += 1
            if t in (r"\begin", r"\end"):
                j, arg = self.i, []
                while j < len(self.tokens) and self.tokens[j] != "}":
                    arg.append(self.tokens[j])
                    j += 1
                env = "".join(arg).lstrip("{")
                if env == name:
                    depth += 1 if t == r"\begin" else -1
                if depth == 0:
                    self.i = j + 1
                    break
            out.append(t)
        return "".join(out)


def _split_top(tex: str, sep: str) -> list[str]:
    """``tex`` split at ``sep`` (``&`` or ``\\\\``) outside braces and environments."""
    parts, cur, depth = [], [], 0
    for t in _TOKEN.findall(tex):
        if t == "{" or t == r"\begin":
            depth += 1
        elif t == "}" or t == r"\end":
            depth -= 1
        if depth == 0 and t == sep:
            parts.append("".join(cur))
            cur = []
            continue
        cur.append(t)
    parts.append("".join(cur))
    return parts


def _table_width(body: str, colsep: float, scale: float) -> float:
    rows = [_split_top(r, "&") for r in _split_top(body, "\\\\")]
    cols = max(len(r) for r in rows)
    widths = [max((width(r[j]) if j < len(r) else 0.0) for r in rows) for j in range(cols)]
    return scale * sum(widths) + colsep * cols


def width(tex: str) -> float:
    r"""The estimated printed width of display math (no ``$``) in glyphs of about 5.5 pt: a conservative
    estimate token by token (a fraction as its wider part, a matrix as its widest entries per
    column); with several lines, the widest."""
    lines = _split_top(tex, "\\\\")
    if len(lines) > 1:
        return max(width(line) for line in lines)
    r = _Reader(tex)
    total = 0.0
    while (t := r.next()) is not None:
        if t in "{}&" or t == "$":
            continue
        if t in ("^", "_"):
            total += 0.75 * width(r.group())
        elif t.startswith("\\"):
            name = t[1:]
            if name in ("frac", "dfrac", "tfrac", "binom"):
                total += max(width(r.group()), width(r.group())) + 0.4
            elif name in _TEXT:
                total += 0.95 * len(r.group())
            elif name in _ARG1:
                total += width(r.group()) + (0.9 if name == "sqrt" else 0.0)
            elif name in ("left", "right", "bigl", "bigr", "Bigl", "Bigr"):
                d = r.next() or ""
                total += 0.0 if d == "." else 0.8
            elif name == "begin":
                env = r.group().rstrip("*")
                body = r.environment(env)
                if env == "array":  # its column spec is the first group of the body
                    body = body.partition("}")[2]
                scale = 0.7 if env == "smallmatrix" else 1.0
                total += _table_width(body, _MATRICES.get(env, 1.9), scale)
                total += _BRACKETS.get(env, 0.0)
            elif name in _SILENT:
                if name in ("label", "tag"):
                    r.group()
            elif name in _WIDE:
                total += _WIDE[name]
            elif name in _BINARY:
                total += 2.5 if total else 1.2  # a leading one is an ordinary symbol
            elif len(name) == 1 and not name.isalpha():
                total += _SPACE.get(name, 0.8)  # \, \; \! \{ \} \| ...
            else:
                total += 1.2  # a Greek letter, \partial, ...
        elif t in "+-=<>":
            total += 2.5 if total else 1.0  # a leading sign is unary
        else:  # a capital 1.9, a digit 1.0, another letter 1.15
            total += _GLYPH.get(t, 1.9 if t.isupper() else 1.0 if t.isdigit() else 1.15)
    return total


def height(tex: str) -> int:
    """Lines of a display row: its rows (roughly), one more with a fraction."""
    rows = max(1, tex.count("\\\\") + 1 - tex.count(r"\begin{smallmatrix}"))
    return rows + (r"\frac" in tex)


def cell_width(text: str) -> float:
    """The width of a table cell (prose with inline math), in the units of :data:`TABLE_WIDTH`."""
    parts = text.split("$")
    return sum(len(p) if k % 2 == 0 else width(p) for k, p in enumerate(parts))


def column_widths(header, rows) -> list[float]:
    """The widest cell of each column of a table."""
    table = [header, *rows]
    columns = max(len(r) for r in table)
    return [max(cell_width(r[j]) for r in table if j < len(r)) for j in range(columns)]


def table_width(header, rows) -> float:
    """The width of a table: its widest cell per column plus the space between columns."""
    widest = column_widths(header, rows)
    return sum(widest) + 2.4 * len(widest)


def _breakable(cell: str) -> bool:
    """Whether a cell can wrap: a space outside its math, or a top-level + or - inside it."""
    parts = cell.split("$")
    return any(" " in part.strip() for part in parts[::2]) or any(
        len(_terms(part, "+-", commas=False)) > 1 for part in parts[1::2]
    )


def wrapped_columns(header, rows, budget: float = TABLE_WIDTH) -> tuple[int, ...]:
    """The columns a table wraps to fit ``budget``, widest first, until it fits; ``()`` when it fits
    as it is or cannot be made to. A column can wrap when each of its cells wider than
    :data:`WRAP_MIN` has a space outside math or a sum in its math."""
    widths = column_widths(header, rows)
    sep = 2.4 * len(widths)
    if sum(widths) + sep <= budget:
        return ()
    table = [header, *rows]
    can = [
        j
        for j in range(len(widths))
        if all(_breakable(r[j]) for r in table if j < len(r) and cell_width(r[j]) > WRAP_MIN)
    ]
    chosen: list[int] = []
    for j in sorted(can, key=lambda j: -widths[j]):
        if widths[j] <= WRAP_MIN:
            break
        chosen.append(j)
        if (
            sum(w for k, w in enumerate(widths) if k not in chosen) + WRAP_MIN * len(chosen) + sep
            <= budget
        ):
            return tuple(sorted(chosen))
    return ()


def _terms(tex: str, ops: str = "+-=", commas: bool = True) -> list[str]:
    """``tex`` cut before each top-level `` + ``, `` - ``, `` = `` (those in ``ops``) and after
    each top-level ``, `` (when ``commas``)."""
    out, cur, depth = [], "", 0
    tokens = _TOKEN.findall(tex)
    for k, t in enumerate(tokens):
        if t in ("{", r"\begin", r"\left"):
            depth += 1
        elif t in ("}", r"\end", r"\right"):
            depth -= 1
        at_top = depth == 0 and cur.strip()
        spaced = 0 < k < len(tokens) - 1 and tokens[k - 1].isspace() and tokens[k + 1].isspace()
        if at_top and t in ops and spaced:
            out.append(cur.rstrip())
            cur = t
            continue
        cur += t
        if commas and at_top and t == "," and k + 1 < len(tokens) and tokens[k + 1].isspace():
            out.append(cur)
            cur = ""
    if cur.strip():
        out.append(cur.strip())
    return [p.strip() for p in out if p.strip()]


def _pieces(tex: str, room: float) -> list[str]:
    """The items of a list (cut after its commas), an item too wide cut at its ``+ - =``."""
    items = _terms(tex, ops="")
    if len(items) == 1:
        return _terms(tex, commas=False)
    return [p for item in items for p in ([item] if width(item) <= room else _terms(item))]


def _elided(tex: str) -> str:
    return rf"\cdots\ \text{{(a term too long to print, {len(tex)} characters)}}"


def fit_rows(rows, budget: float = LINE_WIDTH) -> list[tuple[str | None, str]]:
    r"""Rows ``(lhs, rhs)`` of an aligned display, each broken to fit ``budget`` glyphs.

    A row too wide is cut at its top-level ``+``, ``-`` and ``,`` and packed greedily into
    continuation rows (``lhs`` None); a term wider than a line is elided with its length, and beyond
    :data:`TERM_MAX_LINES` lines the middle ones are counted, not shown."""
    rows = list(rows)
    lead = max((width(lhs) + 3.0 for lhs, _ in rows if lhs is not None), default=0.0)
    out: list[tuple[str | None, str]] = []
    for lhs, rhs in rows:
        if lead + width(rhs) <= budget:
            out.append((lhs, rhs))
            continue
        room = budget - lead - width(INDENT)  # of a continuation line; the first has more
        lines: list[str] = []
        for term in _pieces(rhs, room):
            if width(term) > room:
                term = _elided(term)
            free = room + (width(INDENT) if len(lines) == 1 else 0.0)
            if lines and width(lines[-1] + " " + term) <= free:
                lines[-1] += " " + term
            else:
                lines.append(term)
        if len(lines) > TERM_MAX_LINES:
            left = sum(len(_terms(x)) for x in lines[TERM_MAX_LINES - 2 : -1])
            lines = [
                *lines[: TERM_MAX_LINES - 2],
                rf"\cdots\ \text{{({left} terms not shown)}}",
                lines[-1],
            ]
        out.append((lhs, lines[0]))
        out += [(None, INDENT + line) for line in lines[1:]]
    return out
