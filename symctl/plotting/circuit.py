"""Rendering of a circuit drawing at its printed size: layout from
:mod:`~symctl.plotting.circuit_layout` (texts measured here first), text from
:mod:`~symctl.plotting.circuit_labels`, colours from :mod:`~symctl.plotting.circuit_key`.
"""

from __future__ import annotations

import math
import re
import weakref
from functools import lru_cache
from typing import TYPE_CHECKING, NamedTuple

from matplotlib.patches import Circle, FancyArrowPatch, PathPatch
from matplotlib.path import Path
from matplotlib.transforms import Affine2D, ScaledTranslation

from symctl._util.texnames import signal_tex
from symctl.plotting import style
from symctl.plotting.circuit_key import (
    COLOURS,
    Key,
    SignValues,
    arrow_style,
    draw_key_items,
    key_items,
    weight_sign,
)
from symctl.plotting.circuit_labels import circuit_text, display_text, visible_length
from symctl.plotting.circuit_layout import (
    DOT,
    MIN_GAP,
    MIN_RADIUS,
    NAME_GAP,
    CircuitLayout,
    Measures,
    circuit_layout,
)
from symctl.plotting.common import (
    figure_and_axes,
    fit_to_drawing,
    heading,
    key_columns,
    text_outline,
    text_size,
)

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.neural.circuit import Circuit

__all__ = ["COLOURS", "Drawn", "draw_circuit", "drawn"]

NAME = style.FONT_SIZE  # names of neurons, inputs and outputs, and self-dynamics [pt]
SMALL = style.SMALL  # weights, vertex tags and the key [pt]
_KEY_GAP = 0.3  # between two columns of the key of long values [in]
_WEIGHT_STYLE = {
    "ha": "center",
    "va": "center",
    "fontsize": SMALL,
    "bbox": {"boxstyle": "square,pad=0.05", "fc": "white", "ec": "none"},
    "zorder": 3,
}
_NAME_STYLE = {"ha": "center", "va": "bottom", "fontsize": NAME, "color": "0.1", "zorder": 3}
_TAG_STYLE = {"ha": "center", "va": "top", "fontsize": SMALL, "color": "0.35", "zorder": 3}
_TAG_STYLE["style"] = "italic"
_LINE = 0.8  # synapse lines [pt]
_KEY_ROOM = 4.6  # a key under a narrow drawing may be this wide [in]
_BODY_WIDE = 0.55  # a self-dynamics wider than this [in] is set on two lines
MAX_LABELS = 80  # a circuit of more synapses is drawn without its weights
MAX_KEY = 2.5  # the tallest key of long weights [in]; a longer one: no weights written


@lru_cache(maxsize=8192)
def _extent(text: str, size: float) -> tuple[float, float]:
    """Width and height [in] of ``text`` at ``size`` points as drawn (the box legibility checks)."""
    global _RULER
    if _RULER is None:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        fig = Figure(dpi=72)
        _RULER = (fig, FigureCanvasAgg(fig).get_renderer())
    fig, renderer = _RULER
    t = fig.text(0, 0, text, fontsize=size)
    box = t.get_window_extent(renderer)
    t.remove()
    return box.width / 72, box.height / 72


_RULER = None
_DRAWN: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # axes -> its Drawn


class Drawn(NamedTuple):
    """What :func:`draw_circuit` drew into an axes: its key, layout and text sizes."""

    key: Key
    layout: CircuitLayout
    measures: Measures


def drawn(ax) -> Drawn | None:
    """The key, layout and measures of the circuit drawn into ``ax`` (None: no circuit)."""
    return _DRAWN.get(ax)


# how much a drawing writes, from everything to numbered circles (the first that fits):
# (weights, self-dynamics, names and tags, least gap between columns [in])
_LEVELS = (
    (True, "full", True, MIN_GAP),
    (True, "full", True, 0.7 * MIN_GAP),
    (False, "full", True, MIN_GAP),
    (False, "compact", True, MIN_GAP),
    (False, "", True, MIN_GAP),
    (False, "", False, 0.12),
)


def _measure(c: Circuit, text, level: tuple) -> tuple[Measures, dict]:
    """The sizes of the drawing's texts (inches) and the strings drawn, at ``level``."""
    labelled, bodies, named, _ = level
    if named:
        compact = bodies == "compact"
        body = {n.name: _body(text.bodies[n.name], compact) if bodies else "" for n in c.neurons}
    else:  # each circle holds its number, the key its name
        body = {n.name: str(k) for k, n in enumerate(c.neurons, start=1)}
    inner = NAME if named and bodies == "full" else SMALL
    radius = {}
    for name, s in body.items():
        w, h = _extent(s, inner) if s else (0.0, 0.0)
        inside = math.hypot(w, h) / 2 + 0.02  # the text's corners inside the circle
        radius[name] = max(MIN_RADIUS if named else 0.0, inside)
    names = {n.name: f"${signal_tex(n.name)}$" for n in c.neurons} if named else {}
    tags = {n.name: f"v{n.vertex}" for n in c.neurons if n.vertex is not None and named}
    ends = {u: f"${signal_tex(u)}$" for u in c.inputs}
    for o in c.outputs:
        ends["out", o.target] = "output" if o.target == o.source else f"${signal_tex(o.target)}$"
    weights = {s: display_text(t) for s, t in text.weights.items()} if labelled else {}

    def size(s: str, pt: float, pad: float = 0.0) -> tuple[float, float]:
        w, h = _extent(s, pt)
        return w + 2 * pad, h + 2 * pad

    m = Measures(
        radius,
        {k: size(v, NAME) for k, v in names.items()},
        {k: size(v, SMALL) for k, v in tags.items()},
        {k: size(v, SMALL, 0.02) for k, v in weights.items()},
        {k: size(v, NAME) for k, v in ends.items()},
    )
    if named:  # (numbered circles of a hairball stay small)
        m = m.with_room_for_ends(c)
    return m, dict(body=body, name=names, tag=tags, end=ends, weight=weights, inner=inner)


def draw_circuit(
    c: Circuit,
    ax=None,
    *,
    title: str | None = None,
    vertex_names=None,
    signs_at=None,
    width: float | str = "text",
    key: bool = True,
) -> Figure:
    """Draw the circuit at its printed size: neurons as circles, synapses as arrows.

    A circle holds the neuron's self-dynamics, its name above and its vertex ``v<k>`` below;
    a synapse carries its weight (long ones as :math:`w_k`, listed under the drawing) and its
    sign's colour (excitatory blue with a head, inhibitory vermillion with a bar, purple when
    it depends on symbols), dashed when delayed. Weights that cannot all be set legibly are
    left out, and the key says so.

    Parameters
    ----------
    c : Circuit
    ax : matplotlib Axes, optional
        Draw into it (one data unit is one inch); by default a new figure of printed size.
    title : str, optional
        A heading above the drawing (default none).
    vertex_names : sequence of str, optional
        The delay graph's vertex names, :math:`v_1` first: the key says which is which.
    signs_at : mapping, optional
        A number per symbol or a range ``(lo, hi)`` for one that varies: a weight is coloured
        by its sign only when that holds for all of them.
    width : float or {"text", "column", "double"}
        The widest the drawing may be [in] (default the derivation's text width).
    key : bool
        Draw the key under the drawing (a grid of drawings may share one).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    SymctlTypeError, ParameterError
        ``signs_at`` or ``width`` of the wrong type or value.

    Examples
    --------
    >>> from symctl import Circuit, DelayGraph, Structure, check_compatibility
    >>> from symctl import controllable_canonical, controller_tf, factor
    >>> from symctl.plotting.circuit import draw_circuit
    >>> from symctl.symbols import gain_symbols
    >>> S = Structure.from_factorization(f := factor(controller_tf(2)), controllable_canonical(f.G2))
    >>> c = Circuit.from_structure(S, check_compatibility(S, DelayGraph.chain([1, 1])))
    >>> K0, K1, K2 = gain_symbols(2)
    >>> fig = draw_circuit(c, title="G2", vertex_names=["sensor", "nervous_system", "muscle"],
    ...                    signs_at={K0: -0.046, K1: -0.58, K2: -0.35})
    >>> sorted(t.get_text() for t in fig.axes[0].texts if t.get_text().startswith("v"))
    ['v2', 'v2', 'v2', 'v3']
    >>> fig.axes[0].texts[-1].get_text()   # the title, drawn last, above the drawing
    'G2'
    """
    page = style.width(width)
    symbols = c.free_symbols
    at = SignValues.of(signs_at, "signs_at", symbols)
    text = circuit_text(c)
    # weights written if they fit; else none (a dense circuit); then no self-dynamics;
    # then numbered circles, their names in the key
    legible = _key_fits([v for k, v in text.key if k[0] == "w"], page)
    levels = [lv for lv in _LEVELS if (legible and len(text.weights) <= MAX_LABELS) or not lv[0]]
    for level in levels:
        m, strings = _measure(c, text, level)
        lay = circuit_layout(c, measures=m, width=page, gap=level[3])
        if lay.narrow and lay.labelled:
            break
    named = level[2]
    fig, ax, own = figure_and_axes(ax)
    signs = {}
    for arc in lay.arcs:
        s = arc.synapse
        sign = weight_sign(s.weight, at) if s is not None else ""
        signs[id(arc)] = sign
        _draw_arc(ax, arc, sign, s is not None and s.delay > 0)
        if arc.label is not None and s in strings["weight"]:
            colour = COLOURS[sign] if sign in "+-" else "0.2"
            ax.text(*arc.label, strings["weight"][s], **_WEIGHT_STYLE, color=colour)
    for n in c.neurons:
        x, y = lay.pos[n.name]
        r = lay.radius[n.name]
        ax.add_patch(
            Circle((x, y), r, fc="#f4f4f4", ec="black", lw=0.8, zorder=2, gid=f"neuron:{n.name}")
        )
        if strings["body"][n.name]:
            body = strings["body"][n.name]
            ax.text(x, y, body, ha="center", va="center", fontsize=strings["inner"], zorder=3)
        if named:
            ax.text(x, y + r + NAME_GAP, strings["name"][n.name], **_NAME_STYLE)
        if n.name in strings["tag"]:
            ax.text(x, y - r - NAME_GAP, strings["tag"][n.name], **_TAG_STYLE)
    for node, label in strings["end"].items():
        if node not in lay.pos:
            continue
        x, y = lay.pos[node]
        ax.add_patch(Circle((x, y), DOT, fc="black", lw=0, zorder=2))
        right = isinstance(node, tuple)  # an output: its label on the right
        side = {"ha": "left" if right else "right", "va": "center", "fontsize": NAME, "zorder": 3}
        ax.text(x + (0.07 if right else -0.07), y, label, **side)

    x_lo, x_hi, y_lo, y_hi = lay.bounds
    room = max(x_hi - x_lo, min(page, _KEY_ROOM))
    numbered = tuple((k, f"${signal_tex(n.name)}$", n.vertex) for k, n in enumerate(c.neurons, 1))
    said = Key(
        signs=frozenset(signs.values()),
        delays=frozenset(s.delay for s in (a.synapse for a in lay.arcs) if s is not None),
        labelled=bool(strings["weight"]),
        bodies=named and any(strings["body"].values()),
        empty=named and not all(strings["body"].values()) and any(strings["body"].values()),
        vertices=tuple(sorted({n.vertex for n in c.neurons if n.vertex is not None})),
        vertex_names=tuple(vertex_names) if vertex_names is not None else None,
        signs_at=at,
        synapses=len(c.synapses),
        numbered=() if named else numbered,
    )
    _DRAWN[ax] = Drawn(said, lay, m)
    y = y_lo - 0.06
    items = key_items(said) if key else []
    y, right = draw_key_items(ax, items, x_lo + 0.02, y, room - 0.04, SMALL)
    lines = [  # the keys of the long values drawn
        line
        for (label, _), line in zip(text.key, text.key_lines(), strict=True)
        if key and (strings["weight"] if label.startswith("w") else said.bodies)
    ]
    key_lo, key_hi = _draw_key(ax, lines, x_lo + 0.02, y - 0.04, room - 0.04)
    y_lo = min(y, key_lo) - 0.03
    x_hi = max(x_hi, key_hi, right + 0.03)
    if title:  # wrapped to the drawing (or the page, for a narrow one)
        room = max(x_hi - x_lo, min(page, _KEY_ROOM)) - 0.04
        top, right = heading(ax, title, x_lo + 0.02, y_hi + 0.04, room, style.TITLE)
        x_hi, y_hi = max(x_hi, right + 0.04), top + 0.03
    return fit_to_drawing(fig, ax, own, x_lo, x_hi, y_lo, y_hi)


def _shown(tex: str) -> int:
    r"""The characters ``tex`` shows across: a ``\frac{a}{b}`` as the longer of ``a`` and ``b``."""
    out, k = 0, 0
    while True:
        at = tex.find(r"\frac{", k)
        if at < 0:
            return out + visible_length(tex[k:])
        out += visible_length(tex[k:at])
        parts, end = [], at + len(r"\frac")
        for _ in range(2):  # the two brace groups
            depth, start = 0, end
            for j in range(end, len(tex)):
                depth += {"{": 1, "}": -1}.get(tex[j], 0)
                if depth == 0:
                    end = j + 1
                    break
            parts.append(tex[start + 1 : end - 1])
        out += max(_shown(q) for q in parts)
        k = end


def _key_fits(values: list[str], room: float) -> bool:
    """Whether a key of these values fits ``room`` and :data:`MAX_KEY`, from the characters shown."""
    em = SMALL / 72
    lines = [part for v in values for part in _broken(f"w = {v}", room)]
    widths = [0.55 * em * (_shown(v) + 2) for v in lines]
    if any(w > room for w in widths):
        return False
    tall = [(2.6 if "frac" in v else 1.4) * em + 0.06 for v in lines]
    rows = len(key_columns(widths, room, _KEY_GAP)[0]) if widths else 0
    return rows * max(tall, default=0.0) <= MAX_KEY


def _draw_arc(ax, arc, sign: str, delayed: bool) -> None:
    """One synapse (or output wire) along its path: colour by sign, dashed when delayed."""
    look = arrow_style(sign, COLOURS[sign], (0, (3.0, 1.8)) if delayed else "-")
    target = arc.target[1] if isinstance(arc.target, tuple) else arc.target
    path, gid = Path(arc.path, arc.codes), f"synapse:{arc.source}->{target}"
    # add_artist, not add_patch: its data limits would walk the curves once more
    ax.add_artist(FancyArrowPatch(path=path, lw=_LINE, zorder=1, gid=gid, **look))


def _draw_key(ax, lines: list[str], x: float, y: float, room: float) -> tuple[float, float]:
    """The key's ``label = value`` lines from ``(x, y)`` down in columns fitting ``room``, drawn as
    the glyph outlines that measured them (gid ``key:w1``, ...); its lowest ``y`` and rightmost ``x``.
    """
    if not lines:
        return y, x
    names = [re.sub(r"\\mathrm|[^A-Za-z0-9]", "", line.partition(" = ")[0]) for line in lines]
    broken = [
        (name, part)
        for name, line in zip(names, lines, strict=True)
        for part in _broken(line, room)
    ]
    names, lines = [n for n, _ in broken], [p for _, p in broken]
    outlines = [text_outline(display_text(line), SMALL) for line in lines]
    sizes = [((x1 - x0) / 72, (y1 - y0) / 72) for _, (x0, y0, x1, y1) in outlines]
    columns = key_columns([w for w, _ in sizes], room, _KEY_GAP)
    nrows = len(columns[0])
    anchor = ax.figure.dpi_scale_trans + ScaledTranslation(x, y, ax.transData)
    lefts = [0.0]
    for col in columns:
        lefts.append(lefts[-1] + max(sizes[k][0] for k in col) + _KEY_GAP)
    top = 0.0
    for r in range(nrows):
        row = [(c, col[r]) for c, col in enumerate(columns) if r < len(col)]
        for c, k in row:
            path, (x0, _, _, y1) = outlines[k]
            if path is None:
                continue
            place = Affine2D().translate(-x0, -y1).scale(1 / 72).translate(lefts[c], top)
            name = names[k]  # a line broken in two: both parts keyed by its name
            ax.add_artist(  # not add_patch: its data limits would walk every glyph's curves
                PathPatch(
                    path, transform=place + anchor, fc="black", lw=0, zorder=3, gid=f"key:{name}"
                )
            )
        top -= max(sizes[k][1] for _, k in row) + 0.06
    return y + top - 0.02, x + lefts[-1] - _KEY_GAP + 0.02


def _terms(tex: str) -> list[str]:
    """``tex`` cut before each of its outermost ``+`` and ``-`` signs."""
    parts, depth, start = [], 0, 0
    for k, ch in enumerate(tex):
        depth += {"{": 1, "}": -1, "(": 1, ")": -1}.get(ch, 0)
        if depth == 0 and ch in "+-" and k > 0 and tex[k - 1] == " ":
            parts.append(tex[start:k])
            start = k
    parts.append(tex[start:])
    return parts


def _body(tex: str, compact: bool = False) -> str:
    """A neuron's self-dynamics as drawn: two lines when one makes a large circle (``compact``: always)."""
    if not tex:
        return ""
    one = display_text(tex)
    terms = _terms(tex)
    if compact and len(terms) == 1 and r"\,z^" in tex:
        weight, _, lag = tex.rpartition(r"\,")
        return display_text(weight) + "\n" + display_text(lag)
    if len(terms) < 2 or (text_size(one, NAME)[0] <= _BODY_WIDE and not compact):
        return one
    half = sum(visible_length(t) for t in terms) / 2
    seen, cut = 0, 1
    for k, t in enumerate(terms[:-1], start=1):
        seen += visible_length(t)
        cut = k
        if seen >= half:
            break
    first, second = "".join(terms[:cut]).strip(), "".join(terms[cut:]).strip()
    return display_text(first) + "\n" + display_text(second)


def _broken(line: str, room: float) -> list[str]:
    """A key line too wide for ``room`` broken before its outermost signs, continuations indented."""
    em = SMALL / 72

    def wide(tex: str) -> bool:
        return 0.55 * em * (_shown(tex) + 2) > room

    if not wide(line):
        return [line]
    parts = _terms(line)
    out = [parts[0]]
    for part in parts[1:]:
        if wide(out[-1] + part):
            out.append(r"\quad " + part)
        else:
            out[-1] += part
    return out
