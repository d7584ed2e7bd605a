r"""The house style of every figure: print sizes, fonts, a colour-blind-safe palette, units.

One module decides how a symctl figure looks, so that a figure put into a paper is
legible at the size it is printed and every figure reads alike:

* **Sizes.** :data:`COLUMN` (one column of a two-column journal, 3.4 in) and
  :data:`DOUBLE` (two columns, 7.0 in) are the widths a figure is drawn at;
  :data:`TEXT_WIDTH` is the text width of ``derivation.pdf`` (499 pt), where a figure is
  included at its natural size, never scaled down. :func:`width` reads a size by name.
* **Fonts.** :data:`FONT_SIZE` for tick and axis labels, :data:`SMALL` for keys and
  legends, :data:`TITLE` for panel titles; nothing is set below :data:`MIN_FONT` (6 pt
  printed), which the tests check on the drawn figures.
* **Colours.** :data:`PALETTE` is Okabe and Ito's eight colours, distinguishable with
  every common form of colour blindness; :data:`EXCITATORY`, :data:`INHIBITORY`,
  :data:`SYMBOLIC` mark a synapse's sign, :data:`SENSOR` and :data:`ACTUATOR` the ends
  of a delay graph. :func:`cycle` gives line colours in order.
* **Axes.** :func:`axis_label` writes ``quantity [unit]``: every axis carries its unit.
  :func:`legend_below` puts a legend under its axes, :func:`legend_above` over them
  (under the panel's heading), :func:`figure_legend` under the whole figure: where it
  never covers data, in as many columns as :func:`legend_columns` finds room for.
* **Files.** A figure is written in some of :data:`FORMATS` (vector PDF and SVG, and a
  PNG at :data:`PNG_DPI` for the screen).

:func:`rc` is the matplotlib ``rcParams`` of the style; :func:`new_figure` makes a
pyplot-free figure under it.

References
----------
.. [1] M. Okabe and K. Ito, "Color Universal Design (CUD): how to make figures and
   presentations that are friendly to colorblind people", J*Fly, 2002.
   https://jfly.uni-koeln.de/color/

Examples
--------
>>> from symctl.plotting import style
>>> style.width("column"), style.width("double"), style.width(5)
(3.4, 7.0, 5.0)
>>> style.axis_label("force change δf", "N")
'force change δf [N]'
>>> fig = style.new_figure("column", 2.0)
>>> [round(float(v), 2) for v in fig.get_size_inches()]
[3.4, 2.0]
"""

from __future__ import annotations

from contextlib import contextmanager

from symctl.errors import ParameterError

__all__ = [
    "ACTUATOR",
    "COLUMN",
    "DOUBLE",
    "EXCITATORY",
    "FONT_SIZE",
    "FORMATS",
    "INHIBITORY",
    "MIN_FONT",
    "NEUTRAL",
    "PALETTE",
    "PNG_DPI",
    "SENSOR",
    "SMALL",
    "SYMBOLIC",
    "TEXT_WIDTH",
    "TITLE",
    "axis_label",
    "cycle",
    "figure_legend",
    "legend_above",
    "legend_below",
    "legend_columns",
    "legend_width",
    "new_figure",
    "rc",
    "styled",
    "width",
]

COLUMN = 3.4
"""Width of a one-column figure [in] (a column of a two-column journal page)."""
DOUBLE = 7.0
"""Width of a two-column figure [in] (the full width of a two-column journal page)."""
TEXT_WIDTH = 499.0 / 72.27
"""Text width of ``derivation.pdf`` [in]: 11pt article on letter paper, 2 cm margins (499 pt)."""

FONT_SIZE = 8.0
"""Axis and tick labels, node labels of diagrams [pt]."""
SMALL = 7.0
"""Legends, keys and annotations [pt]."""
TITLE = 8.5
"""Panel titles [pt]."""
MIN_FONT = 6.0
"""No text of a figure is set smaller [pt], at the size it is printed."""

PNG_DPI = 200
"""Resolution of the PNG files [dots per inch] (the PDF and SVG are vector)."""
FORMATS = ("pdf", "svg", "png")
"""The formats a figure can be written in, in the order they are written."""

PALETTE = (
    "#0072B2",  # blue
    "#D55E00",  # vermillion
    "#009E73",  # bluish green
    "#CC79A7",  # reddish purple
    "#E69F00",  # orange
    "#56B4E9",  # sky blue
    "#F0E442",  # yellow
    "#000000",  # black
)
"""Okabe and Ito's colour-blind-safe palette, in the order lines take it (yellow, pale on
white, comes late)."""

EXCITATORY = PALETTE[0]
"""A positive synapse (blue)."""
INHIBITORY = PALETTE[1]
"""A negative synapse (vermillion)."""
SYMBOLIC = PALETTE[3]
"""A synapse whose sign depends on symbols (reddish purple)."""
NEUTRAL = "0.25"
"""Wires, outlines and text that carry no sign (dark grey)."""
SENSOR = PALETTE[2]
"""The sensor vertices of a delay graph (bluish green)."""
ACTUATOR = PALETTE[4]
"""The actuator vertices of a delay graph (orange)."""

_WIDTHS = {"column": COLUMN, "double": DOUBLE, "text": TEXT_WIDTH}


def width(size: str | float) -> float:
    """A figure width in inches: ``"column"``, ``"double"``, ``"text"`` or a number.

    Parameters
    ----------
    size : {"column", "double", "text"} or float
        A named print width, or inches.

    Returns
    -------
    float

    Raises
    ------
    ParameterError
        ``size`` is an unknown name or not a positive finite number.

    Examples
    --------
    >>> from symctl.plotting.style import width
    >>> width("text") > width("column")
    True
    """
    if isinstance(size, str):
        if size not in _WIDTHS:
            raise ParameterError(f"size: {size!r} is not one of {sorted(_WIDTHS)} or a number")
        return _WIDTHS[size]
    if isinstance(size, bool) or not isinstance(size, int | float) or not 0 < size < 100:
        raise ParameterError(f"size: {size!r} is not a width in inches (0 < size < 100)")
    return float(size)


def cycle(k: int) -> str:
    """The ``k``-th line colour (the palette, repeating).

    Examples
    --------
    >>> from symctl.plotting.style import PALETTE, cycle
    >>> cycle(0) == PALETTE[0], cycle(len(PALETTE)) == PALETTE[0]
    (True, True)
    """
    return PALETTE[k % len(PALETTE)]


BAND_ALPHA = 0.22
"""Opacity of the band of noisy runs (:func:`band`)."""


def band(ax, t, mean, sd, color: str, label: str | None = None):
    r"""The spread of noisy runs about their mean, :math:`\pm 2` sd, held over each step."""
    return ax.fill_between(
        t,
        mean - 2 * sd,
        mean + 2 * sd,
        step="post",
        color=color,
        alpha=BAND_ALPHA,
        lw=0,
        label=label,
    )


def axis_label(quantity: str, unit: str | None) -> str:
    """``"quantity [unit]"``; a dimensionless quantity says so (``[1]``).

    Examples
    --------
    >>> from symctl.plotting.style import axis_label
    >>> axis_label("time", "s"), axis_label("deviation", None)
    ('time [s]', 'deviation [1]')
    """
    return f"{quantity} [{unit or '1'}]"


def rc() -> dict:
    """The matplotlib ``rcParams`` of the style.

    Examples
    --------
    >>> from symctl.plotting.style import FONT_SIZE, rc
    >>> rc()["font.size"] == FONT_SIZE
    True
    """
    from cycler import cycler

    return {
        "font.size": FONT_SIZE,
        "axes.titlesize": TITLE,
        "axes.labelsize": FONT_SIZE,
        "xtick.labelsize": SMALL,
        "ytick.labelsize": SMALL,
        "legend.fontsize": SMALL,
        "legend.title_fontsize": SMALL,
        "legend.frameon": False,
        "figure.titlesize": TITLE,
        "axes.prop_cycle": cycler(color=list(PALETTE)),
        "axes.linewidth": 0.6,
        "axes.spines.top": False,
        "axes.spines.right": False,
        "axes.grid": True,
        "grid.linewidth": 0.4,
        "grid.alpha": 0.5,
        "lines.linewidth": 1.0,
        "lines.markersize": 3.5,
        "xtick.major.width": 0.6,
        "ytick.major.width": 0.6,
        "xtick.major.size": 2.5,
        "ytick.major.size": 2.5,
        "mathtext.fontset": "dejavusans",
        "pdf.fonttype": 42,  # TrueType in the PDF: text stays text, editable and searchable
        "svg.fonttype": "none",
        "savefig.bbox": None,
    }


@contextmanager
def styled():
    """A context in which figures are made and drawn in the house style.

    Examples
    --------
    >>> from matplotlib import rcParams
    >>> from symctl.plotting.style import FONT_SIZE, styled
    >>> with styled():
    ...     rcParams["font.size"] == FONT_SIZE
    True
    """
    import matplotlib as mpl

    from symctl.plotting.common import _share_math_parses

    _share_math_parses()
    with mpl.rc_context(rc()):
        yield


def new_figure(size: str | float = "text", height: float | None = None, **kwargs):
    """A pyplot-free figure of the style's width (see :func:`width`) and ``height`` inches.

    ``height`` defaults to 0.62 of the width. The figure has a constrained layout, so
    labels and legends are fitted inside it. Keywords go to
    :class:`matplotlib.figure.Figure`.

    Examples
    --------
    >>> from symctl.plotting.style import new_figure
    >>> float(new_figure("double").get_size_inches()[0])
    7.0
    """
    from matplotlib.figure import Figure

    w = width(size)
    h = 0.62 * w if height is None else width(height)
    kwargs.setdefault("layout", "constrained")
    with styled():
        return Figure(figsize=(w, h), **kwargs)


def legend_below(ax, handles=None, labels=None, *, ncol: int | None = None, title=None):
    """A legend under ``ax``, outside its data, in as many columns as fit.

    Examples
    --------
    >>> from symctl.plotting.style import legend_below, new_figure
    >>> fig = new_figure("column", 2.0)
    >>> ax = fig.add_subplot()
    >>> _ = ax.plot([0, 1], [0, 1], label="a")
    >>> legend_below(ax).get_texts()[0].get_text()
    'a'
    """
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    if ncol is None:
        ncol = max(1, min(len(handles), 4))
    return ax.legend(
        handles,
        labels,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.22),
        ncol=ncol,
        title=title,
        fontsize=SMALL,
        frameon=False,
    )


_HANDLE = 2.0 + 0.8  # matplotlib's handlelength + handletextpad [em]
_SPACING = 2.0  # columnspacing [em]
_PAD = 2 * (0.5 + 0.4)  # borderaxespad + borderpad, both sides, at their defaults [em]


def legend_width(labels, ncol: int, *, size: float = SMALL) -> float:
    """Width [in] of a legend of ``labels`` in ``ncol`` columns, as matplotlib lays it out.

    Matplotlib fills the columns in order, the first ``len(labels) % ncol`` of them
    with one entry more than the others. Each column is as wide as its longest label
    (measured as drawn, mathtext included) plus the handle; the columns are separated
    as matplotlib separates them.

    Examples
    --------
    >>> from symctl.plotting.style import legend_width
    >>> legend_width(["a", "b"], 2) > legend_width(["a", "b"], 1)
    True
    """
    from symctl.plotting.common import text_size

    labels = list(labels)
    if not labels:
        return 0.0
    ncol = max(1, min(int(ncol), len(labels)))
    rows, large = divmod(len(labels), ncol)
    sizes = [rows + 1] * large + [rows] * (ncol - large)
    widths, start = [], 0
    for count in sizes:
        widths.append(max(text_size(t, size)[0] for t in labels[start : start + count]))
        start += count
    em = size / 72.0
    # TextPath measures the outlines; drawn text runs a few percent wider
    return 1.06 * sum(widths) + em * (_HANDLE * ncol + _SPACING * (ncol - 1) + _PAD)


def legend_columns(labels, room: float, *, size: float = SMALL, most: int | None = None) -> int:
    """The most columns (at least 1) in which a legend of ``labels`` fits ``room`` inches.

    Examples
    --------
    >>> from symctl.plotting.style import legend_columns
    >>> legend_columns(["short", "labels"], 3.0), legend_columns(["x" * 60, "y" * 60], 3.0)
    (2, 1)
    """
    labels = list(labels)
    top = max(1, min(len(labels), most or len(labels)))
    for ncol in range(top, 1, -1):
        if legend_width(labels, ncol, size=size) <= room:
            return ncol
    return 1


def legend_above(ax, handles=None, labels=None, *, room: float, heading: str | None = None):
    """A legend in the row above ``ax``, from its left end, at most ``room`` inches wide.

    ``heading``, the panel's short heading, is the legend's title, set on the left above
    the entries: a panel with several traces has its heading and key in one block over
    the data, never on it. The legend takes as many columns as fit ``room`` (the
    panel's width) and grows upward; the figure's constrained layout makes space.

    Examples
    --------
    >>> from symctl.plotting.style import legend_above, new_figure
    >>> fig = new_figure("column", 2.0)
    >>> ax = fig.add_subplot()
    >>> _ = ax.plot([0, 1], [0, 1], label="a")
    >>> _ = ax.plot([0, 1], [1, 0], label="b")
    >>> legend = legend_above(ax, room=2.0, heading="two lines")
    >>> legend._ncols, legend.get_title().get_text()
    (2, 'two lines')
    """
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    return ax.legend(
        handles,
        labels,
        loc="lower left",
        bbox_to_anchor=(0.0, 1.0),
        ncols=legend_columns(labels, room),
        title=heading,
        alignment="left",
        fontsize=SMALL,
        title_fontsize=SMALL,
        frameon=False,
        borderaxespad=0.1,
        borderpad=0.1,
    )


def figure_legend(fig, handles, labels, *, title: str | None = None, most: int | None = None):
    """One legend under the whole figure, centred, in as many columns as fit its width.

    Examples
    --------
    >>> from symctl.plotting.style import figure_legend, new_figure
    >>> fig = new_figure("column", 2.0)
    >>> ax = fig.add_subplot()
    >>> lines = ax.plot([0, 1], [0, 1], [0, 1], [1, 0])
    >>> figure_legend(fig, lines, ["up", "down"])._ncols
    2
    """
    room = float(fig.get_size_inches()[0]) - 0.1
    ncol = legend_columns(labels, room, most=most)
    return fig.legend(
        handles,
        labels,
        loc="outside lower center",
        ncols=ncol,
        title=title,
        fontsize=SMALL,
        title_fontsize=SMALL,
        frameon=False,
    )
