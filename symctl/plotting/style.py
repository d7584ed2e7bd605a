"""The house style of every figure: print sizes, fonts, a colour-blind-safe palette, units.

Widths are a journal's column (3.4 in), two columns (7.0 in) and the text width of
``derivation.pdf`` (499 pt), where a figure is included at its natural size; no text is
set below :data:`MIN_FONT`; the palette is Okabe and Ito's ("Color Universal Design",
J*Fly, 2002), distinguishable with every common form of colour blindness; every axis
names its unit; legends never cover data.

>>> from symctl.plotting import style
>>> style.width("column"), style.width("double"), style.width(5)
(3.4, 7.0, 5.0)
>>> style.axis_label("force change δf", "N"), style.axis_label("deviation", None)
('force change δf [N]', 'deviation [1]')
"""

from __future__ import annotations

from contextlib import contextmanager

from symctl.errors import ParameterError

COLUMN = 3.4  # one column of a two-column journal page [in]
DOUBLE = 7.0  # two columns [in]
TEXT_WIDTH = 499.0 / 72.27  # the text width of derivation.pdf: 11pt article, letter, 2 cm margins
FONT_SIZE = 8.0  # axis and tick labels, node labels of diagrams [pt]
SMALL = 7.0  # legends, keys and annotations [pt]
BAND_ALPHA = 0.22  # opacity of a band of mean +- 2 sd
TITLE = 8.5  # panel titles [pt]
MIN_FONT = 6.0  # no text of a figure is set smaller [pt], at the size it is printed
PNG_DPI = 200  # resolution of the PNG files (the PDF and SVG are vector)
FORMATS = ("pdf", "svg", "png")  # the formats a figure can be written in, in this order
PALETTE = (  # Okabe and Ito's, in the order lines take it (yellow, pale on white, late)
    "#0072B2",  # blue
    "#D55E00",  # vermillion
    "#009E73",  # bluish green
    "#CC79A7",  # reddish purple
    "#E69F00",  # orange
    "#56B4E9",  # sky blue
    "#F0E442",  # yellow
    "#000000",  # black
)
EXCITATORY, INHIBITORY, SYMBOLIC = PALETTE[0], PALETTE[1], PALETTE[3]  # a synapse's sign
NEUTRAL = "0.25"  # wires, outlines and text that carry no sign (dark grey)
SENSOR, ACTUATOR = PALETTE[2], PALETTE[4]  # the ends of a delay graph
_WIDTHS = {"column": COLUMN, "double": DOUBLE, "text": TEXT_WIDTH}


def width(size: str | float) -> float:
    """A figure width in inches: ``"column"``, ``"double"``, ``"text"`` or a number.

    Raises
    ------
    ParameterError
        ``size`` is an unknown name or not a positive finite number.
    """
    if isinstance(size, str):
        if size not in _WIDTHS:
            raise ParameterError(f"size: {size!r} is not one of {sorted(_WIDTHS)} or a number")
        return _WIDTHS[size]
    if isinstance(size, bool) or not isinstance(size, int | float) or not 0 < size < 100:
        raise ParameterError(f"size: {size!r} is not a width in inches (0 < size < 100)")
    return float(size)


def cycle(k: int) -> str:
    """The ``k``-th line colour (the palette, repeating)."""
    return PALETTE[k % len(PALETTE)]


def band(ax, t, mean, sd, color: str, label: str | None = None):
    r"""The spread of noisy runs about their mean, :math:`\pm 2` sd, held over each step."""
    lo, hi = mean - 2 * sd, mean + 2 * sd
    return ax.fill_between(t, lo, hi, step="post", color=color, alpha=BAND_ALPHA, lw=0, label=label)


def axis_label(quantity: str, unit: str | None) -> str:
    """``"quantity [unit]"``; a dimensionless quantity says so (``[1]``)."""
    return f"{quantity} [{unit or '1'}]"


def rc() -> dict:
    """The matplotlib ``rcParams`` of the style."""
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
    """A context in which figures are made and drawn in the house style."""
    import matplotlib as mpl

    from symctl.plotting.common import _share_math_parses

    _share_math_parses()
    with mpl.rc_context(rc()):
        yield


def new_figure(size: str | float = "text", height: float | None = None, **kwargs):
    """A pyplot-free, constrained figure of the style's width and ``height`` inches (default 0.62
    of the width)."""
    from matplotlib.figure import Figure

    w = width(size)
    h = 0.62 * w if height is None else width(height)
    kwargs.setdefault("layout", "constrained")
    with styled():
        return Figure(figsize=(w, h), **kwargs)


def neuron_grid(fig, n: int, cols: int, time_label: str) -> list:
    """``n`` panels of firing rates in rows of ``cols`` sharing the time axis (its ticks only
    under the lowest panel of each column), the spare cells removed."""
    rows = -(-n // cols)
    axes = fig.subplots(rows, cols, sharex=True, squeeze=False).ravel()
    for k, ax in enumerate(axes):
        if k < n:
            ax.xaxis.set_tick_params(labelbottom=k + cols >= n)
        else:
            ax.remove()
    fig.supxlabel(time_label, fontsize=FONT_SIZE)
    fig.supylabel(axis_label("firing-rate change", "spikes/s"), fontsize=FONT_SIZE)
    return list(axes[:n])


def suptitle(fig, title: str | None) -> None:
    """A heading over ``fig`` when ``title`` is given."""
    if title:
        fig.suptitle(title, fontsize=TITLE)


def legend_below(ax, handles=None, labels=None, *, ncol: int | None = None, title=None):
    """A legend under ``ax``, outside its data, in up to 4 columns."""
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    ncol = max(1, min(len(handles), 4)) if ncol is None else ncol
    kw = {"loc": "upper center", "bbox_to_anchor": (0.5, -0.22), "fontsize": SMALL}
    return ax.legend(handles, labels, ncol=ncol, title=title, frameon=False, **kw)


_HANDLE = 2.0 + 0.8  # matplotlib's handlelength + handletextpad [em]
_SPACING = 2.0  # columnspacing [em]
_PAD = 2 * (0.5 + 0.4)  # borderaxespad + borderpad, both sides, at their defaults [em]
_KEY = {"fontsize": SMALL, "title_fontsize": SMALL, "frameon": False}  # every legend's text


def legend_width(labels, ncol: int, *, size: float = SMALL) -> float:
    """Width [in] of a legend of ``labels`` in ``ncol`` columns, as matplotlib lays it out (the
    first ``len(labels) % ncol`` columns one entry longer, each as wide as its longest label)."""
    import numpy as np

    from symctl.plotting.common import text_size

    labels = list(labels)
    if not labels:
        return 0.0
    ncol = max(1, min(int(ncol), len(labels)))
    columns = np.array_split(np.arange(len(labels)), ncol)
    widths = [max(text_size(labels[k], size)[0] for k in col) for col in columns]
    em = size / 72.0
    # TextPath measures the outlines; drawn text runs a few percent wider
    return 1.06 * sum(widths) + em * (_HANDLE * ncol + _SPACING * (ncol - 1) + _PAD)


def legend_columns(labels, room: float, *, size: float = SMALL) -> int:
    """The most columns (at least 1) in which a legend of ``labels`` fits ``room`` inches."""
    labels = list(labels)
    for ncol in range(len(labels), 1, -1):
        if legend_width(labels, ncol, size=size) <= room:
            return ncol
    return 1


def legend_above(ax, handles=None, labels=None, *, room: float, heading: str | None = None):
    """A legend above ``ax`` from its left end, in as many columns as fit ``room`` inches, titled
    ``heading`` (the panel's heading and key in one block over the data)."""
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    place = {"loc": "lower left", "bbox_to_anchor": (0.0, 1.0), "alignment": "left"}
    pads = {"borderaxespad": 0.1, "borderpad": 0.1}
    ncols = legend_columns(labels, room)
    return ax.legend(handles, labels, ncols=ncols, title=heading, **place, **pads, **_KEY)


def figure_legend(fig, handles, labels, *, title: str | None = None):
    """One legend under the whole figure, centred, in as many columns as fit its width."""
    ncols = legend_columns(labels, float(fig.get_size_inches()[0]) - 0.1)
    return fig.legend(handles, labels, loc="outside lower center", ncols=ncols, title=title, **_KEY)
