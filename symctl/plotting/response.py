"""Figures of simulations, sampled signals as steps: a loop's state and input traces, and
the nonlinear plant's departure from the linear model.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from symctl._util.texnames import signal_tex
from symctl.plotting import style

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.neural.nonlinear import NonlinearCheck
    from symctl.neural.simulate import Response

__all__ = ["MARKERS_UP_TO", "MAX_PANELS", "UNKNOWN_UNIT", "nonlinear_plot", "response_plot"]

MAX_PANELS = 6  # most panels of signals in response_plot (beyond, the rest share the last)
MARKERS_UP_TO = 60  # samples are marked with dots on traces of up to this many samples

_MUSCLE = {"f": ("muscle force", "N"), "r": ("motor-neuron rate", "spikes/s")}
UNKNOWN_UNIT = "arb. unit"  # the unit when the model gives none ([1] says dimensionless)
_MARGINS = 0.75  # inches of a panel's row taken by the y-axis label and ticks (for legends)


def _signal(name: str, labels) -> tuple[str, str, str | None]:
    """(description, mathtext symbol without ``$``, unit) of ``delta_<x>`` or ``<x>``."""
    raw = name.removeprefix("delta_")
    what, unit = (_MUSCLE if labels is None else labels).get(raw, ("", ""))
    return what, signal_tex(raw), unit or None


def _state_tex(name: str) -> str:
    """A controller state's name as mathtext: ``gamma_1`` -> γ₁, ``delta_r[2]`` -> δ_r[2]."""
    base, _, index = name.partition("[")
    head, _, sub = base.partition("_")
    head = {"gamma": r"\gamma", "delta": r"\delta"}.get(head, head)
    tex = f"${head}_{{{sub}}}$" if sub else f"${head}$"
    return tex + (f"[{index}" if index else "")


def _bar(sym: str) -> str:
    """The operating point's symbol: the bar over the stem, not the index (``f_{flex}``)."""
    stem, sep, index = sym.partition("_")
    return rf"\bar{{{stem}}}{sep}{index}"


def _axis(quantity: str, unit: str | None) -> str:
    """``quantity [unit]``, :data:`UNKNOWN_UNIT` where the model gives no unit."""
    return style.axis_label(quantity, unit or UNKNOWN_UNIT)


def _amount(value: float, unit: str | None) -> str:
    """``43.86 N``; a count noun in the singular at one (``1 spike/s``, not ``1 spikes/s``)."""
    if unit is None:
        return f"{value:.4g}"
    head, sep, rest = unit.partition("/")
    if value == 1 and len(head) >= 4 and head.isalpha() and head.endswith("s"):
        unit = head[:-1] + sep + rest
    return f"{value:.4g} {unit}"


_LINE_COLOURS = tuple(c for c in style.PALETTE if c != "#F0E442")  # yellow is faint as a line


def _steps(ax, t, y, *, marked: bool, **kwargs):
    """A sampled signal, held over each step (a dot at each sample on short traces)."""
    if marked:
        kwargs.setdefault("marker", ".")
        kwargs.setdefault("markersize", 2.5)
    return ax.plot(t, y, drawstyle="steps-post", **kwargs)[0]


def _heading(ax, text: str, room: float) -> None:
    """The panel's heading: the axes' title, or with several traces their legend's, above."""
    handles, labels = ax.get_legend_handles_labels()
    if len(handles) < 2:
        ax.set_title(text, loc="left", fontsize=style.SMALL, pad=3)
        return
    style.legend_above(ax, handles, labels, room=room, heading=text)


def response_plot(
    res: Response,
    states: bool | None = None,
    labels=None,
    *,
    title: str | None = None,
    size: str | float = "column",
) -> Figure:
    r"""Each state and input against time (at most :data:`MAX_PANELS` panels, the rest sharing
    the last), then the controller's states (``states``; default: when there are any).

    Each panel shows a change from the operating point :math:`\bar x` (in the heading); a closed
    loop's disturbance dashed; with noise, the mean in a band of :math:`\pm 2` sd. ``labels``:
    ``name -> (description, unit)`` without ``delta_`` (default the muscle's); ``size`` as
    :func:`symctl.plotting.style.width`.

    >>> from symctl import open_loop_response
    >>> from symctl.plotting.response import response_plot
    >>> fig = response_plot(open_loop_response())   # open loop: no controller states
    >>> len(fig.axes), fig.axes[-1].get_xlabel()
    (2, 'time [s]')
    """
    states = res.states.shape[1] > 0 if states is None else states
    signals = [
        (res.delta_f, res.f_bar, res.state_names, i, True, res.delta_f_sd)
        for i in range(res.delta_f.shape[1])
    ]
    signals += [
        (res.delta_r, res.r_bar, res.input_names, i, False, res.delta_r_sd)
        for i in range(res.delta_r.shape[1])
    ]
    groups = [[s] for s in signals[: MAX_PANELS - 1]]
    if len(signals) >= MAX_PANELS:
        groups.append(signals[MAX_PANELS - 1 :])
    rows = len(groups) + (1 if states else 0)
    panel = 1.25 if rows <= 3 else 1.0
    fig = style.new_figure(size, min(0.55 + panel * rows, 9.0))
    room = style.width(size) - _MARGINS
    marked = res.t.size <= MARKERS_UP_TO
    with style.styled():
        axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
        for ax, group in zip(axes, groups, strict=False):
            _signal_panel(ax, group, res, labels, marked, room)
        if states:
            _controller_panel(axes[-1], res, labels, marked, room)
        axes[-1].set_xlabel(style.axis_label("time", res.time_unit))
        for ax in axes:
            ax.yaxis.set_major_locator(_locator())
    style.suptitle(fig, title)
    return fig


def _signal_panel(ax, group, res: Response, labels, marked: bool, room: float) -> None:
    """One state or input (its change; its operating point in the heading), or several."""
    units = []
    for j, (trace, _point, names, i, is_state, sd) in enumerate(group):
        what, sym, unit = _signal(names[i], labels)
        units.append(unit)
        if len(group) == 1:
            colour, label = style.PALETTE[0] if is_state else style.PALETTE[1], rf"$\delta {sym}$"
        else:
            colour = _LINE_COLOURS[j % len(_LINE_COLOURS)]
            label = rf"$\delta {sym}$ [{unit or '1'}]"
        _steps(ax, res.t, trace[:, i], marked=marked, color=colour, label=label)
        if sd is not None:
            runs = f"mean $\\pm$ 2 sd of {res.draws} noisy runs" if j == 0 else None  # once a panel
            style.band(ax, res.t, trace[:, i], sd[:, i], colour, runs)
        if is_state and res.kind == "closed loop" and res.w.shape[1] > i and res.w[:, i].any():
            per = f"{unit or UNKNOWN_UNIT}/step"
            look = {"ls": "--", "lw": 0.8, "color": style.NEUTRAL}
            ax.step(res.t, res.w[:, i], where="post", label=f"disturbance $w$ [{per}]", **look)
    ax.axhline(0, color="black", lw=0.5)
    if len(group) == 1:
        _trace, bar, names, i, *_ = group[0]
        ax.set_ylabel(_axis(rf"$\delta {sym}$", unit))
        head = f"{what} ${sym}$" if what else f"${sym}$"
        _heading(ax, rf"{head} (${_bar(sym)}$ = {_amount(float(bar[i]), unit)})", room)
    else:
        ax.set_ylabel(_axis("change", units[0] if len(set(units)) == 1 else "mixed units"))
        _heading(ax, "further signals (change from the operating point)", room)


def _locator():
    from matplotlib.ticker import MaxNLocator

    return MaxNLocator(nbins=4, steps=[1, 2, 2.5, 5, 10])


def _chain_tex(name: str, res: Response, labels) -> str:
    """A state of the delay chain as mathtext; ``delta_r[k]`` takes input k's symbol."""
    base, _, index = name.partition("[")
    if base != "delta_r":
        return _state_tex(name)
    i = int(index.rstrip("]")) - 1 if index else 0
    return rf"$\delta {_signal(res.input_names[i], labels)[1]}$"


def _controller_panel(ax, res: Response, labels, marked: bool, room: float) -> None:
    """The controller's states: the delay chain of the optimal controller, or a realization's."""
    count = res.states.shape[1]
    names = res.controller_state_names or tuple(f"x_{i + 1}" for i in range(count))
    chain = all(n.startswith(("gamma_", "delta_r")) for n in names)
    for i, name in enumerate(names):
        label = _chain_tex(name, res, labels) if chain else _state_tex(name)
        colour = _LINE_COLOURS[(2 + i) % len(_LINE_COLOURS)]
        _steps(ax, res.t, res.states[:, i], marked=marked, color=colour, lw=0.9, label=label)
        if res.states_sd is not None:
            style.band(ax, res.t, res.states[:, i], res.states_sd[:, i], colour)
    units = {_signal(n, labels)[2] for n in res.input_names}
    if chain and len(units) == 1:  # delayed copies of the input: the input's symbol and unit
        one = len(res.input_names) == 1
        what = rf"$\delta {_signal(res.input_names[0], labels)[1]}$" if one else "delayed input"
        ax.set_ylabel(_axis(what, units.pop()))
    elif chain:
        ax.set_ylabel(style.axis_label("delayed input", "mixed units"))
    else:  # a realization's states have the scale the realization gives them
        ax.set_ylabel(_axis("state", None))
    _heading(ax, "controller state: the delay chain" if chain else "controller state", room)


def _slope(amps: np.ndarray, dev: np.ndarray) -> float | None:
    """The least-squares slope of ``log dev`` against ``log amps`` (None: under two points)."""
    good = (amps > 0) & (dev > 0)
    if np.unique(amps[good]).size < 2:
        return None
    return float(np.polyfit(np.log(amps[good]), np.log(dev[good]), 1)[0])


def _near(bounds, chk: NonlinearCheck) -> list[tuple[float, str]]:
    """The ``bounds`` within a quarter of the traces' range of the traces."""
    values = np.concatenate([chk.f_linear.ravel(), chk.f_nonlinear.ravel()])
    values = values[np.isfinite(values)]
    if not values.size:
        return []
    lo, hi = float(values.min()), float(values.max())
    slack = 0.25 * (hi - lo)
    return [(float(v), text) for v, text in bounds if lo - slack <= v <= hi + slack]


def nonlinear_plot(
    chk: NonlinearCheck,
    labels=None,
    *,
    bounds=(),
    title: str | None = None,
    size: str | float = "text",
) -> Figure:
    r"""The first state's traces (nonlinear solid, linear dashed) and their largest gap against
    the pulse amplitude (log-log, with its fitted power law: about :math:`w^2`). ``bounds``:
    ``(value, legend text)`` of the first state to mark dotted (the muscle's :math:`f_\max`),
    left out when further than a quarter of the traces' range; the rest as :func:`response_plot`.

    >>> from symctl import nonlinear_check
    >>> from symctl.plotting.response import nonlinear_plot
    >>> fig = nonlinear_plot(nonlinear_check(amplitudes=[0.1, 1.0], steps=20))
    >>> [ax.get_xlabel() for ax in fig.axes]
    ['time [s]', 'pulse amplitude [N per step]']
    """
    from matplotlib.lines import Line2D

    x0 = chk.state_names[0]
    what, sym, unit = _signal(x0, labels)
    if labels is None and chk.units and chk.units[0]:
        unit = chk.units[0]
    fig = style.new_figure(size, 2.7)
    ok = np.isfinite(chk.max_deviation)
    per = f"{unit or UNKNOWN_UNIT} per step"
    with style.styled():
        ax1, ax2 = fig.subplots(1, 2, width_ratios=[1.5, 1])
        handles, texts = [], []
        for k, (a, lin, nl) in enumerate(
            zip(chk.amplitudes, chk.f_linear, chk.f_nonlinear, strict=True)
        ):
            colour = _LINE_COLOURS[k % len(_LINE_COLOURS)]
            handles.append(_steps(ax1, chk.t, nl, marked=False, color=colour, lw=1.1))
            _steps(ax1, chk.t, lin, marked=False, color=colour, lw=0.9, ls=(0, (3, 2)))
            texts.append(f"$w$ = {a:g} {per}")
        for value, text in _near(bounds, chk):
            ax1.axhline(value, color=style.NEUTRAL, lw=0.8, ls=":")
            handles.append(Line2D([], [], color=style.NEUTRAL, lw=0.8, ls=":"))
            texts.append(text)
        plant = "muscle" if labels is None else "plant"
        handles += [
            Line2D([], [], color=style.NEUTRAL, lw=1.1),
            Line2D([], [], color=style.NEUTRAL, lw=0.9, ls=(0, (3, 2))),
        ]
        texts += [f"nonlinear {plant}", "linear model"]
        ax1.set_xlabel(style.axis_label("time", "s"))
        ax1.set_ylabel(_axis(f"{what} ${sym}$" if what else f"${sym}$", unit))
        amps = np.abs(chk.amplitudes[ok])
        dev = chk.max_deviation[ok]
        handles.append(ax2.loglog(amps, dev, "o-", ms=3, color=style.PALETTE[0])[0])
        texts.append(rf"largest $|{sym}_\mathrm{{nl}} - {sym}_\mathrm{{lin}}|$")
        slope = _slope(amps, dev)
        if slope is not None:  # about 2 where the linearization is exact to first order
            guide = dev[-1] * (amps / amps[-1]) ** slope
            handles.append(ax2.loglog(amps, guide, color=style.NEUTRAL, lw=0.7, ls=":")[0])
            texts.append(rf"fit $\propto w^{{{slope:.2f}}}$")
        ax2.set_xlabel(style.axis_label("pulse amplitude", per))
        ax2.set_ylabel(_axis(rf"largest $|{sym}_\mathrm{{nl}} - {sym}_\mathrm{{lin}}|$", unit))
        ax2.grid(True, which="both", alpha=0.3)
        style.figure_legend(fig, handles, texts)
    style.suptitle(fig, title)
    return fig
