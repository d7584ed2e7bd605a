"""Pieces shared by every drawing: a pyplot-free figure, the text measure, wrapped lines, the key."""

from __future__ import annotations

from functools import lru_cache


@lru_cache(maxsize=4096)
def text_size(text: str, size: float) -> tuple[float, float]:
    """Width and height in inches of ``text`` at ``size`` points: its outlines' box, cached."""
    _, (x0, y0, x1, y1) = text_outline(text, size)
    return (x1 - x0) / 72, (y1 - y0) / 72


def text_outline(text: str, size: float):
    """``(path, (x0, y0, x1, y1))``: the glyph outlines of ``text`` at ``size`` points (origin on
    the baseline, ``None`` without ink) and their box (TrueType puts vertices at the extrema)."""
    from matplotlib import cbook
    from matplotlib.font_manager import FontProperties
    from matplotlib.path import Path

    if not text.strip():  # no ink (a path cannot be empty)
        return None, (0.0, 0.0, 0.0, 0.0)
    verts, codes = _to_path(size).get_text_path(
        FontProperties(size=size), text, ismath=cbook.is_math_text(text)
    )
    path = Path(verts, codes)
    points = path.vertices if path.codes is None else path.vertices[path.codes != Path.CLOSEPOLY]
    if not len(points):
        return None, (0.0, 0.0, 0.0, 0.0)
    (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    return path, (float(x0), float(y0), float(x1), float(y1))


@lru_cache(maxsize=16)
def _to_path(size: float):
    """Matplotlib's text-to-outline converter working at ``size`` points (not its 100)."""
    from matplotlib.textpath import TextToPath

    _share_math_parses()  # what it typesets, the drawing finds (also before any figure is made)
    converter = TextToPath()
    converter.FONT_SCALE = size
    return converter


def figure_and_axes(ax):
    """``(fig, ax, own)``: a new pyplot-free figure filling one axes, or the caller's axes."""
    from matplotlib.figure import Figure

    if ax is None:
        fig = Figure()
        return fig, fig.add_axes((0, 0, 1, 1)), True
    return ax.figure, ax, False


def fit_to_drawing(fig, ax, own: bool, x_lo: float, x_hi: float, y_lo: float, y_hi: float):
    """The axes show ``[x_lo, x_hi] x [y_lo, y_hi]`` at one inch per data unit, without frame;
    a figure of the drawing's own (``own``) is sized to it. Returns ``fig``."""
    ax.set_xlim(x_lo, x_hi)
    ax.set_ylim(y_lo, y_hi)
    ax.set_aspect("equal")
    ax.axis("off")
    if own:
        fig.set_size_inches(x_hi - x_lo, y_hi - y_lo)
    return fig


def wrap(items, room: float, size: float, sep: str = " ", scale: float = 1.06) -> list[str]:
    """``items`` joined by ``sep`` into lines no wider than ``room`` inches at ``size`` points
    (widths times ``scale``: drawn text runs a few percent wider); one may overflow."""
    lines: list[str] = []
    for item in items:
        if lines and scale * text_size(lines[-1] + sep + item, size)[0] <= room:
            lines[-1] += sep + item
        else:
            lines.append(item)
    return lines


def heading(ax, title: str, x: float, y: float, room: float, size: float):
    """``title`` wrapped to ``room`` inches in lines above ``y`` from ``x``, at ``size`` points;
    returns their top and right end."""
    lines = wrap(title.split(" "), room, size, scale=1.04)
    step = size / 72 * 1.3
    top = y + step * len(lines)
    for k, line in enumerate(lines):
        ax.text(x, top - k * step, line, ha="left", va="top", fontsize=size)
    return top, x + max(1.04 * text_size(line, size)[0] for line in lines)


def key_columns(widths, room: float, gap: float) -> list[list[int]]:
    """The key's lines (indices) in the most columns, ``gap`` apart and each as wide as its widest
    line, that fit ``room``; else one column.

    >>> from symctl.plotting.common import key_columns
    >>> key_columns([1.0, 1.0, 1.0], room=2.5, gap=0.3), key_columns([3.0, 1.0], 2.5, 0.3)
    ([[0, 1], [2]], [[0, 1]])
    """
    for n in range(len(widths), 1, -1):
        rows = -(-len(widths) // n)
        columns = [list(range(k, min(k + rows, len(widths)))) for k in range(0, len(widths), rows)]
        total = sum(max(widths[k] for k in col) for col in columns) + gap * (len(columns) - 1)
        if total <= room:
            return columns
    return [list(range(len(widths)))]


def _share_math_parses() -> None:
    """Let every renderer share one cache of typeset math text: matplotlib's cache of 50 per
    renderer evicts a large figure's labels between measuring and drawing (40% of the figure time).
    """
    import functools

    from matplotlib import mathtext

    method = mathtext.MathTextParser.__dict__.get("_parse_cached")
    typeset = getattr(method, "__wrapped__", None)
    if typeset is None or getattr(method, "_symctl", False):
        return
    parsers: dict = {}

    @functools.lru_cache(4096)
    def shared(kind, s, dpi, prop, antialiased, flags):
        return typeset(parsers[kind], s, dpi, prop, antialiased, flags)

    def parse_cached(self, s, dpi, prop, antialiased, load_glyph_flags):
        parsers.setdefault(self._output_type, self)
        return shared(self._output_type, s, dpi, prop, antialiased, load_glyph_flags)

    parse_cached._symctl = True
    mathtext.MathTextParser._parse_cached = parse_cached
