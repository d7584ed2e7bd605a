r"""The firing-pattern figure (the paper's Figs. 9-11): one panel per neuron of :math:`G_2`;
:meth:`FiringPatterns.plot <symctl.neural.firing.FiringPatterns.plot>` delegates here."""

from __future__ import annotations

from typing import TYPE_CHECKING

from symctl._util.texnames import signal_tex
from symctl._util.validate import positive_int
from symctl.plotting import style
from symctl.plotting.response import _LINE_COLOURS as _COLOURS
from symctl.plotting.response import UNKNOWN_UNIT, _locator, _steps

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.neural.firing import FiringPatterns

__all__ = ["firing_plot"]

PANEL_HEIGHT = 1.05  # a row of neuron panels with their headings [in]


def _tex(name: str, *, part: bool = True) -> str:
    return f"${signal_tex(name, part=part)}$"


def _state(fp, labels) -> tuple[str, str, str | None]:
    """(description, mathtext symbol without ``$``, unit) of the plant's first state."""
    if labels is None:
        return "muscle force", "f", "N"
    raw = fp.reference.state_names[0].removeprefix("delta_")
    what, unit = labels.get(raw, ("", ""))
    return what, signal_tex(raw), unit or None


def firing_plot(
    fp: FiringPatterns,
    ncols: int = 3,
    labels=None,
    *,
    title: str | None = None,
    size: str | float = "text",
) -> Figure:
    r"""One panel per neuron of :math:`G_2` (one line per realization), the plant's state on top;
    with noise, each line the mean of the noisy runs in a band of :math:`\pm 2` sd.

    Parameters
    ----------
    fp : FiringPatterns
        The result of :func:`~symctl.neural.firing.circuit_firing`.
    ncols : int
        Neuron panels per row.
    labels : mapping of str to (str, str), optional
        ``name -> (description, unit)`` of the plant's state and input (names without
        ``delta_``); default the muscle's (force f [N], rate r).
    title : str, optional
        A heading over the figure (default none).
    size : {"column", "double", "text"} or float
        The printed width (:func:`symctl.plotting.style.width`).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ParameterError
        ``ncols`` is not an integer >= 1.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, circuit_firing, lqr_gains
    >>> from symctl.plotting.firing import firing_plot
    >>> fp = circuit_firing("observable", lqr_gains(augment(MuscleModel(), 1, 1)), count=2)
    >>> [ax.get_title() for ax in firing_plot(fp, ncols=2).axes][1:]
    ['neuron $x_{1}$', 'neuron $x_{2}$', 'neuron $y$']
    """
    from symctl.realization.realizers import REALIZERS

    ncols = positive_int(ncols, "ncols")
    names = fp.neurons
    cols = max(1, min(int(ncols), len(names)))
    rows = -(-len(names) // cols)
    width = style.width(size)
    labels_ = [fp.legend_label(i) for i in range(fp.count)]
    entries = len(labels_) + 1
    legend_rows = -(-entries // style.legend_columns([*labels_, "optimal controller"], width))
    height = 1.45 + PANEL_HEIGHT * rows + 0.16 * legend_rows + 0.3
    fig = style.new_figure(size, height)
    unit_t = fp.reference.time_unit
    with style.styled():
        top_fig, grid_fig = fig.subfigures(2, 1, height_ratios=[1.1, PANEL_HEIGHT * rows + 0.3])
        top = top_fig.subplots()
        colours = [_COLOURS[i % len(_COLOURS)] for i in range(fp.count)]
        lines = [
            _steps(top, fp.t, fp.f_bar + fp.delta_f[i], marked=False, color=c, lw=1.2)
            for i, c in enumerate(colours)
        ]
        if fp.delta_f_sd is not None:  # the same in every realization: one band
            style.band(top, fp.t, fp.f_bar + fp.delta_f[0], fp.delta_f_sd[0], _COLOURS[0])
        reference = fp.f_bar + fp.reference.delta_f[:, 0]
        optimal = _steps(
            top, fp.t, reference, marked=False, color="black", lw=0.9, ls=(0, (1, 1.5))
        )
        what, sym, unit = _state(fp, labels)
        top.set_ylabel(style.axis_label(f"${sym}$", unit or UNKNOWN_UNIT))
        top.set_xlabel(style.axis_label("time", unit_t))
        head = f"{what} ${sym}$" if what else f"${sym}$"
        dev = max(fp.max_deviation, 1e-16)
        if fp.kind in REALIZERS and REALIZERS[fp.kind].controller:  # the IFP controller
            head += ": one realization, the optimal controller's delay chain"
        elif fp.draws:
            head += (
                f": the same in every realization and the optimal loop (to {dev:.0e}); "
                f"mean $\\pm$ 2 sd of {fp.draws} noisy runs"
            )
        else:
            head += (
                f" in every realization and with the optimal controller: the same, "
                f"to {dev:.0e} relative (and so is the input)"
            )
        top.set_title(head, loc="left", fontsize=style.SMALL, pad=3)
        axes = grid_fig.subplots(rows, cols, sharex=True, squeeze=False)
        for k, name in enumerate(names):
            ax = axes[k // cols, k % cols]
            for i, colour in enumerate(colours):
                _steps(ax, fp.t, fp.firing[name][i], marked=False, lw=1.0, color=colour)
                if fp.firing_sd is not None:
                    style.band(ax, fp.t, fp.firing[name][i], fp.firing_sd[name][i], colour)
            ax.axhline(0, color="black", lw=0.5)
            part = name.rpartition(".")[0]  # "P1.G2" for a part of a parallel decomposition
            where = f" ({part.partition('.')[0]})" if "." in part else ""
            ax.set_title(f"neuron {_tex(name, part=False)}{where}", fontsize=style.SMALL, pad=2)
            ax.yaxis.set_major_locator(_locator())
            # a panel with none below it shows the time ticks (the last row may be short)
            ax.xaxis.set_tick_params(labelbottom=k + cols >= len(names))
        for k in range(len(names), rows * cols):
            axes[k // cols, k % cols].remove()
        grid_fig.supxlabel(style.axis_label("time", unit_t), fontsize=style.FONT_SIZE)
        grid_fig.supylabel(
            style.axis_label("firing-rate change", "spikes/s"), fontsize=style.FONT_SIZE
        )
        style.figure_legend(
            fig, [*lines, optimal], [*labels_, "optimal controller"], title="realization"
        )
    if title:
        fig.suptitle(title, fontsize=style.TITLE)
    return fig
