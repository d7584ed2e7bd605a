r"""The key under a circuit drawing: what its marks mean, only those the drawing shows.

>>> from symctl.plotting.circuit_key import Key, key_items
>>> [text for _, text in key_items(Key(signs=frozenset("+-"), delays=frozenset({0, 1})))]
['excitatory', 'inhibitory', 'delayed one step']
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from symctl._util.display import latex
from symctl.plotting import style
from symctl.plotting.circuit_signs import SignValues
from symctl.plotting.common import text_size

__all__ = ["COLOURS", "Key", "draw_key_items", "key_items", "stems"]

COLOURS = {
    "+": style.EXCITATORY,
    "-": style.INHIBITORY,
    "?": style.SYMBOLIC,
    "0": "0.7",
    "": style.NEUTRAL,
}
"""The colour of a synapse by its sign (``""``: a plain wire to an output)."""


def arrow_style(sign: str, colour, linestyle) -> dict:
    """A synapse's arrow: a bar for an inhibitory one, else a head; dashed when delayed."""
    head = "-[,widthB=0.55,lengthB=0" if sign == "-" else "-|>,head_length=0.55,head_width=0.3"
    look = {"arrowstyle": head, "mutation_scale": 8, "color": colour, "linestyle": linestyle}
    return {**look, "shrinkA": 0, "shrinkB": 0}


_SAMPLE = 0.24  # the width of a sample mark [in]
_GAP = 0.05  # between a mark and its text
_ITEM_GAP = 0.16  # between two items of a row


@dataclass(frozen=True)
class Key:
    """What a drawing shows, for its key.

    Attributes
    ----------
    signs, delays : frozenset
        The signs of its synapses (``"+"``, ``"-"``, ``"?"``, ``"0"``; ``""`` a wire) and
        their delays.
    labelled, bodies, empty : bool
        The weights are written; the self-dynamics are written; some circle is empty.
    vertices, vertex_names : tuple
        The delay-graph vertices of its neurons, and the graph's vertex names (or None).
    signs_at : SignValues
        The values its signs were read at.
    synapses : int
        How many synapses it has.
    numbered : tuple of (int, str, int or None)
        The neurons drawn as numbered circles: number, name (mathtext) and vertex.
    """

    signs: frozenset = frozenset()
    delays: frozenset = frozenset()
    labelled: bool = True
    bodies: bool = True
    empty: bool = False
    vertices: tuple = ()
    vertex_names: tuple | None = None
    signs_at: SignValues = field(default_factory=SignValues)
    synapses: int = 0
    numbered: tuple = ()


def stems(symbols) -> list[str]:
    r"""The LaTeX of the letters of ``symbols`` without their indices, in order, once each.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl.plotting.circuit_key import stems
    >>> stems([*sp.symbols("K_0 K_1 epsilon_1"), sp.Symbol("C_{1,1}")])
    ['K', '\\epsilon', 'C']
    """
    out: list[str] = []
    for s in symbols:
        tex = latex(sp.Symbol(str(s).split("_")[0]))
        if tex not in out:
            out.append(tex)
    return out


def _number(v: float) -> str:
    return f"{v:g}".replace("-", "\N{MINUS SIGN}")


def _signs_note(at: SignValues) -> str:
    """``colours: the signs at the given K, at C = 1, for every ε in [−0.9, 0.9]``."""
    by_stem: dict[str, list] = {}
    for s, v in sorted(at.numbers.items(), key=lambda kv: str(kv[0])):
        by_stem.setdefault(stems([s])[0], []).append(v)
    given = [t for t, vs in by_stem.items() if len(set(vs)) > 1]
    equal = [(t, vs[0]) for t, vs in by_stem.items() if len(set(vs)) == 1]
    parts = []
    if given:
        parts.append("at the given " + ", ".join(f"${t}$" for t in given))
    parts += [f"at ${t}$ = {_number(float(v))}" for t, v in equal]
    ranges: dict[tuple, list] = {}
    for s, r in sorted(at.ranges.items(), key=lambda kv: str(kv[0])):
        ranges.setdefault(r, []).append(s)
    for (lo, hi), syms in ranges.items():
        names = ", ".join(f"${t}$" for t in stems(syms))
        parts.append(f"for every {names} in [{_number(lo)}, {_number(hi)}]")
    return "colours: the signs " + ", ".join(parts)


def key_items(key: Key) -> list[tuple[str, str]]:
    """The key's items ``(mark, text)``; marks ``"+"``, ``"-"``, ``"?"``, ``"0"``,
    ``"dashed"``, ``"neuron"`` or ``""`` (text alone).

    Examples
    --------
    >>> from symctl.plotting.circuit_key import Key, key_items
    >>> key_items(Key(signs=frozenset("?"), vertices=(2, 3), vertex_names=("s", "cord", "m")))
    [('?', 'sign depends on the symbols'), ('', 'under a neuron: its vertex, v2 cord, v3 m')]
    """
    items: list[tuple[str, str]] = []
    if key.empty:
        items.append(("neuron", "neuron (empty: no self-dynamics)"))
    if "+" in key.signs:
        items.append(("+", "excitatory"))
    if "-" in key.signs:
        items.append(("-", "inhibitory"))
    if "?" in key.signs:
        items.append(("?", "sign depends on the symbols"))
    if "0" in key.signs:
        items.append(("0", "weight 0"))
    delays = {d for d in key.delays if d > 0}
    if delays:
        if max(delays) == 1:
            items.append(("dashed", "delayed one step"))
        elif key.labelled:
            items.append(("dashed", r"delayed one step, or $k$ where $z^{-k}$ is written"))
        else:
            items.append(("dashed", "delayed (one step or more)"))
    if key.vertices and not key.numbered:
        names = key.vertex_names
        if (
            names
            and len(names) >= max(key.vertices)
            and any(names[v - 1] != f"v{v}" for v in key.vertices)
        ):
            said = ", ".join(f"v{v} {names[v - 1].replace('_', ' ')}" for v in key.vertices)
            items.append(("", f"under a neuron: its vertex, {said}".replace("$", r"\$")))
        else:
            items.append(("", "under a neuron: its delay-graph vertex"))
    if key.signs_at and "?" in key.signs | {"+", "-"}:
        items.append(("", _signs_note(key.signs_at)))
    if not key.labelled and key.synapses:
        what = "weights" if key.bodies else "weights and self-dynamics"
        items.append(
            (
                "",
                f"{what} not written: too many or too long to set legibly at this "
                "size (Circuit.equations() lists them)",
            )
        )
    if key.numbered:
        items.append(("", "neurons by number:"))
        items += [
            ("", f"{k} {name}" + (f" (v{v})" if v is not None else ""))
            for k, name, v in key.numbered
        ]
    return items


def draw_key_items(ax, items, x: float, y: float, room: float, size: float):
    """Draw ``items`` in rows from ``(x, y)`` down, no row wider than ``room``.

    Returns the lowest ``y`` and the rightmost ``x`` it drew at.
    """
    from matplotlib.patches import Circle, FancyArrowPatch

    if not items:
        return y, x
    widths = [
        (_SAMPLE + _GAP if mark else 0.0) + 1.04 * text_size(text, size)[0] for mark, text in items
    ]
    rows: list[list[int]] = [[]]
    used = 0.0
    for k, w in enumerate(widths):
        if rows[-1] and used + _ITEM_GAP + w > room:
            rows.append([])
            used = 0.0
        used += (_ITEM_GAP if rows[-1] else 0.0) + w
        rows[-1].append(k)
    line = max(size / 72 * 1.45, 0.13)
    right = x
    for row in rows:
        yc = y - line / 2
        cx = x
        for k in row:
            mark, text = items[k]
            if mark in ("+", "-", "?", "0", "dashed"):
                colour = COLOURS[mark] if mark != "dashed" else style.NEUTRAL
                dashes = (0, (3.0, 1.8)) if mark == "dashed" else "-"
                look = arrow_style(mark, colour, dashes)
                ax.add_artist(FancyArrowPatch((cx, yc), (cx + _SAMPLE, yc), lw=0.8, **look))
            elif mark == "neuron":
                ax.add_patch(Circle((cx + _SAMPLE / 2, yc), 0.05, fc="#f4f4f4", ec="black", lw=0.8))
            if mark:
                cx += _SAMPLE + _GAP
            ax.text(cx, yc, text, ha="left", va="center", fontsize=size, color="0.2")
            cx += widths[k] - ((_SAMPLE + _GAP) if mark else 0.0)
            right = max(right, cx)
            cx += _ITEM_GAP
        y -= line
    return y, right
