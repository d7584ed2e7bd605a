r"""The firing-pattern figure (the paper's Figs. 9-11): one panel per neuron of :math:`G_2`;
:meth:`FiringPatterns.plot <symctl.neural.firing.FiringPatterns.plot>` delegates here."""

from __future__ import annotations

from typing import TYPE_CHECKING

from symctl._util.texnames import signal_tex
from symctl._util.validate import positive_int
from symctl.plotting import style
from symctl.plotting.response import _LINE_COLOURS as _COLOURS
from symctl.plotting.response import UNKNOWN_UNIT, _locator, _signal, _steps

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.neural.firing import FiringPatterns

__all__ = ["firing_plot"]

PANEL_HEIGHT = 1.05  # a row of neuron panels with their headings [in]


def firing_plot(
    fp: FiringPatterns,
    ncols: int = 3,
    labels=None,
    *,
    title: str | None = None,
    size: str | float = "text",
) -> Figure:
    r"""One panel per neuron of :math:`G_2` (a line per realization, ``ncols`` panels a row), the
    plant's state on top; with noise, each line the mean in a band of :math:`\pm 2` sd.
    ``labels``, ``title`` and ``size`` as :func:`~symctl.plotting.response.response_plot`.

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
        what, sym, unit = _signal(fp.reference.state_names[0], labels)
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
        axes = style.neuron_grid(grid_fig, len(names), cols, style.axis_label("time", unit_t))
        for ax, name in zip(axes, names, strict=True):
            for i, colour in enumerate(colours):
                _steps(ax, fp.t, fp.firing[name][i], marked=False, lw=1.0, color=colour)
                if fp.firing_sd is not None:
                    style.band(ax, fp.t, fp.firing[name][i], fp.firing_sd[name][i], colour)
            ax.axhline(0, color="black", lw=0.5)
            part = name.rpartition(".")[0]  # "P1.G2" for a part of a parallel decomposition
            where = f" ({part.partition('.')[0]})" if "." in part else ""
            tex = signal_tex(name, part=False)
            ax.set_title(f"neuron ${tex}${where}", fontsize=style.SMALL, pad=2)
            ax.yaxis.set_major_locator(_locator())
        style.figure_legend(
            fig, [*lines, optimal], [*labels_, "optimal controller"], title="realization"
        )
    style.suptitle(fig, title)
    return fig
