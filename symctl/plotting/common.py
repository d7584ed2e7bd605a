"""Pieces shared by every drawing: a pyplot-free figure, the text measure, wrapped lines, the key."""

from __future__ import annotations

from functools import lru_cache

__all__ = ["figure_and_axes", "fit_to_drawing", "key_columns", "text_outline", "text_size", "wrap"]


@lru_cache(maxsize=4096)
def text_size(text: str, size: float) -> tuple[float, float]:
    """Width and height in inches of ``text`` set at ``size`` points (mathtext allowed).

    The box of its glyph outlines (:func:`text_outline`). Cached: every drawing
    measures the same keys and headings again (an atlas overview measured its key
    nine times, two thirds of its drawing time).
    """
    _, (x0, y0, x1, y1) = text_outline(text, size)
    return (x1 - x0) / 72, (y1 - y0) / 72


def text_outline(text: str, size: float):
    """``(path, (x0, y0, x1, y1))``: the glyph outlines of ``text`` at ``size`` points and their box.

    The path is in points, its origin on the baseline at the left (``None`` for text
    without ink). The box is that of the outlines' vertices: TrueType outlines have
    their on- and off-curve points at the curves' extrema, so it is the outlines' box
    (to a thousandth of a point) without ``Path.get_extents``, which walks every
    Bezier segment in Python (three quarters of the drawing time of a circuit with a
    key of long weights). Math text is typeset at ``size`` itself (matplotlib's
    ``TextPath`` typesets it at 100 points and scales it down), so that drawing the
    same text later finds it typeset (:func:`_share_math_parses` shares the cache).
    """
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
    (measured widths times ``scale``: drawn text runs a few percent wider); one may overflow.

    >>> from symctl.plotting.common import wrap
    >>> wrap("a few words to wrap".split(), 0.5, 7, scale=1.04)
    ['a few', 'words to', 'wrap']
    """
    lines: list[str] = []
    for item in items:
        if lines and scale * text_size(lines[-1] + sep + item, size)[0] <= room:
            lines[-1] += sep + item
        else:
            lines.append(item)
    return lines


def key_columns(widths, room: float, gap: float) -> list[list[int]]:
    """The key's lines (indices) in the most columns, ``gap`` apart and each as wide as its widest
    line, that fit ``room`` (the first ones hold ``ceil(len / n)`` lines; else one column).

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


_MATH_PARSES = 4096
"""How many typeset math strings one process keeps (:func:`_share_math_parses`)."""


def _share_math_parses() -> None:
    """Let every renderer of this process share one cache of typeset math text.

    Matplotlib typesets a ``$...$`` string (a pyparsing parse, about 10 ms) once per
    string, resolution, font and *renderer*, in a cache of 50: each Agg renderer
    (every text measure at another size) starts empty, and a figure with more than 50
    math labels evicts its own entries between measuring and drawing them. Typesetting
    was 40% of the time of drawing the report's figures. The result depends only on
    the string, resolution, font, antialiasing, hinting and output kind, which this
    cache keys on; it is installed once, and not at all if matplotlib's private
    method has another form.
    """
    import functools

    from matplotlib import mathtext

    method = mathtext.MathTextParser.__dict__.get("_parse_cached")
    typeset = getattr(method, "__wrapped__", None)
    if typeset is None or getattr(method, "_symctl", False):
        return
    parsers: dict = {}

    @functools.lru_cache(_MATH_PARSES)
    def shared(kind, s, dpi, prop, antialiased, flags):
        return typeset(parsers[kind], s, dpi, prop, antialiased, flags)

    def parse_cached(self, s, dpi, prop, antialiased, load_glyph_flags):
        parsers.setdefault(self._output_type, self)
        return shared(self._output_type, s, dpi, prop, antialiased, load_glyph_flags)

    parse_cached._symctl = True
    mathtext.MathTextParser._parse_cached = parse_cached
