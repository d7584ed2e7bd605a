r"""The figures of spiking populations: a loop's force, rates and raster, and what spikes
cost each circuit (:meth:`SpikingResponse.plot <symctl.spiking.loop.SpikingResponse.plot>`,
:meth:`SpikingCost.plot <symctl.spiking.cost.SpikingCost.plot>`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from symctl._util.texnames import signal_tex
from symctl.plotting import style

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.spiking.cost import SpikingCost
    from symctl.spiking.loop import SpikingResponse

RASTER_NEURONS = 20  # neurons per population the raster shows (the first ones)


def spiking_plot(res: SpikingResponse, *, size: str | float = "text") -> Figure:
    r"""Force (spiking solid, linear dashed), each neuron's rate change, and a spike raster of the
    first :data:`RASTER_NEURONS` neurons of each population (none when exact).

    >>> import symctl
    >>> from symctl.plotting.spiking import spiking_plot
    >>> res = symctl.derive_paper()
    >>> r = symctl.spiking_response(res.gains, res.circuits["ifp"].firing.circuits[0], n_neurons=20)
    >>> [ax.get_ylabel() for ax in spiking_plot(r).axes]
    ['$\\delta f$ [N]', 'rate change [spikes/s]', 'neuron']
    """
    fig = style.new_figure(size, 5.0)
    dashed = (0, (3, 2))
    with style.styled():
        force, rates, raster = fig.subplots(3, 1, sharex=True)
        force.step(res.t, res.delta_f[:, 0], where="post", color=style.PALETTE[0], label="spiking")
        linear = res.delta_f_linear[:, 0]
        force.step(res.t, linear, where="post", color=style.NEUTRAL, ls=dashed, label="linear")
        force.set_ylabel(style.axis_label(r"$\delta f$", "N"))
        force.set_title(
            f"force, {res.n_neurons or 'exact'} neurons per population "
            f"(RMS deviation {res.deviation:.3g})",
            loc="left",
        )
        force.legend(loc="upper right")
        for k, (name, trace) in enumerate(res.firing.items()):
            colour = style.cycle(k)
            rates.step(res.t, trace, where="post", color=colour, label=f"${signal_tex(name)}$")
            rates.step(res.t, res.firing_linear[name], where="post", color=colour, ls=dashed)
        rates.set_ylabel(style.axis_label("rate change", "spikes/s"))
        rates.legend(loc="upper right", ncol=3)
        row = 0
        for k, spikes in enumerate(res.spikes.values()):
            for i in range(min(RASTER_NEURONS, spikes.shape[1])):
                times = np.flatnonzero(spikes[:, i]) * res.dt
                raster.plot(times, np.full(times.shape, row), "|", ms=3, color=style.cycle(k))
                row += 1
        raster.set_ylabel("neuron")
        raster.set_xlabel(style.axis_label("time", "s"))
    return fig


def spiking_cost_plot(cost: SpikingCost, *, size: str | float = "text") -> Figure:
    """Median deviation against neurons per population (a line per circuit, tolerances dotted),
    and each circuit's neurons in all against its spikes per second at the first tolerance
    (marker area: its firing amplitude; circuits no size brings within it left out).

    >>> import symctl
    >>> from symctl.plotting.spiking import spiking_cost_plot
    >>> cost = symctl.spiking_cost(symctl.derive_paper(), circuits=["ifp"], neurons=(10, 30), seeds=1)
    >>> len(spiking_cost_plot(cost).axes)
    2
    """
    fig = style.new_figure(size, 3.2)
    key = f"{100 * cost.tolerances[0]:g}%"
    with style.styled():
        curves, price = fig.subplots(1, 2)
        for k, name in enumerate(cost.circuits):
            median = np.median(cost.deviation[k], axis=1)
            curves.plot(cost.neurons, median, "o-", ms=3, color=style.cycle(k), label=name)
        for tol in cost.tolerances:
            curves.axhline(tol, color=style.NEUTRAL, ls=":", lw=0.8)
        curves.set(xscale="log", yscale="log", xlabel="neurons per population")
        curves.set_ylabel("deviation from the linear loop")
        curves.legend(fontsize="x-small", ncol=2)
        peak = max(cost.peak) or 1.0
        for row in cost.table():
            k = cost.circuits.index(row["circuit"])
            total, spikes = row[f"neurons@{key}"], row[f"spikes@{key}"]
            if np.isfinite(total) and np.isfinite(spikes):
                area = 10 + 90 * row["peak"] / peak
                price.scatter(total, spikes, s=area, color=style.cycle(k), alpha=0.8)
                price.annotate(row["circuit"], (total, spikes), fontsize="x-small")
        price.set(xscale="log", yscale="log", xlabel=f"neurons in all (within {key})")
        price.set_ylabel("spikes per second")
        price.margins(x=0.2, y=0.15)  # room for the names beside the markers
        for ax in (curves, price):
            _plain_log_ticks(ax)
    return fig


def _plain_log_ticks(ax) -> None:
    """Plain numbers on both log axes; minor ticks at 2 and 5 labelled on an axis under two decades."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    plain = FuncFormatter(lambda v, _: f"{v:,.0f}" if v >= 1 else f"{v:g}")
    for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        axis.set_major_formatter(plain)
        few = lo > 0 and hi / lo < 100
        axis.set_minor_locator(LogLocator(base=10, subs=(2.0, 5.0) if few else "auto"))
        axis.set_minor_formatter(plain if few else NullFormatter())
