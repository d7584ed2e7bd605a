r"""The fit figure: data against fit for the recorded neurons, predictions for the others;
:meth:`FitResult.plot <symctl.fitting.fit.FitResult.plot>` delegates here."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from symctl._util.texnames import signal_tex
from symctl._util.validate import positive_int
from symctl.plotting import style

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.fitting.fit import FitResult

__all__ = ["SETTLED", "fit_plot"]

SETTLED = 0.01  # a trace has settled once within this fraction of its peak: the axis ends

_PANEL_HEIGHT = 1.15  # a row of panels with its headings [in]


def _neuron_tex(name: str) -> str:
    """``G2.x1`` -> :math:`x_1^{G2}`, as in the circuit diagrams."""
    prefix, _, short = name.rpartition(".")
    return f"${signal_tex(short)}^{{\\mathrm{{{prefix}}}}}$" if prefix else f"${signal_tex(name)}$"


def _window(t: np.ndarray, traces) -> float | None:
    """Where the time axis ends: a quarter after the last trace settles; None: the whole data."""
    last = 0.0
    for y in traces:  # |y|, NaN and infinities as 0 (neither peak nor busy)
        y = np.nan_to_num(np.abs(np.asarray(y, dtype=float)), nan=0.0, posinf=0.0)
        busy = np.flatnonzero(y > SETTLED * y.max())
        if busy.size:
            last = max(last, float(t[busy[-1]]))
    span = float(t[-1] - t[0])
    end = t[0] + 1.25 * (last - t[0]) + 0.05 * span
    return None if end >= t[0] + 0.8 * span else end


def fit_plot(
    result: FitResult, ncols: int = 3, *, title: str | None = None, size: str | float = "text"
) -> Figure:
    """One panel per neuron (``ncols`` a row): data and fit (recorded), prediction (unrecorded),
    with their bands; ``title`` and ``size`` as :func:`~symctl.plotting.response.response_plot`."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    ncols = positive_int(ncols, "ncols")
    pred = result.predict()
    names = list(pred)
    cols = min(ncols, len(names))
    rows = -(-len(names) // cols)
    fig = style.new_figure(size, 0.75 + _PANEL_HEIGHT * rows)
    t = np.asarray(result.t, dtype=float)
    end = _window(t, [*pred.values(), *result.data.values()])
    # grey data, blue fit, green prediction, vermillion where the data pin nothing down
    data_c, fit_c, pred_c, lost_c = style.NEUTRAL, *(style.PALETTE[k] for k in (0, 2, 1))
    used = set()
    with style.styled():
        grid = fig.subfigures(1, 1)  # its axis labels, then the figure's legend below it
        shown = "" if end is None else f" (to {end:.2g} s; later, every trace stays settled)"
        axes = style.neuron_grid(grid, len(names), cols, style.axis_label("time", "s") + shown)
        for ax, name in zip(axes, names, strict=True):
            ok = bool(result.neuron_identifiable[name])
            color = fit_c if name in result.data else pred_c if ok else lost_c
            lo, hi = pred.lower[name], pred.upper[name]
            if np.all(np.isfinite(lo)):
                used.add(3)
                ax.fill_between(t, lo, hi, color=color, alpha=0.3, lw=0, step="post")
            ax.plot(t, pred[name], color=color, lw=1.2, drawstyle="steps-post")
            if name in result.data:
                ax.plot(t, result.data[name], ".", ms=2.5, color=data_c, zorder=3)
                head = "recorded"
                used.update((0, 1))
            else:
                used.add(2 if ok else 4)
                head = "predicted" if ok else "predicted; not identifiable"
            if ok and not result.neuron_determined[name]:
                head += "; not determined by these data"
            ax.set_title(f"{_neuron_tex(name)} ({head})", fontsize=style.SMALL, pad=2)
            ax.axhline(0, color="black", lw=0.5)
        if end is not None:
            axes[0].set_xlim(t[0] - 0.02 * (end - t[0]), end)
        handles = [
            Line2D([], [], ls="", marker=".", ms=4, color=data_c),
            Line2D([], [], color=fit_c),
            Line2D([], [], color=pred_c),
            Patch(color=pred_c, alpha=0.3, lw=0),
            Line2D([], [], color=lost_c),
        ]
        texts = ["data", "fit", "prediction", f"{pred.level:.0%} band"]
        texts.append("prediction, not identifiable")
        keep = sorted(used)
        style.figure_legend(fig, [handles[i] for i in keep], [texts[i] for i in keep])
    style.suptitle(fig, title)
    return fig
