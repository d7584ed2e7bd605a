"""A circuit drawing's colours and key: the sign of each weight, and what the marks mean.

Given ``signs_at`` (a number per symbol, or a range ``(lo, hi)``), :func:`weight_sign` is
``"+"`` or ``"-"`` only when so for *every* value (ranges by SymPy's
:class:`~sympy.calculus.accumulationbounds.AccumulationBounds`, which never claims a sign
some point lacks), ``"0"`` when zero, else ``"?"``.

>>> import sympy as sp
>>> from symctl.plotting.circuit_key import SignValues, weight_sign
>>> K0, K2, e1, C1 = sp.symbols("K_0 K_2 epsilon_1 C_1", real=True)
>>> at = SignValues.of({K0: -0.046, K2: -0.35, C1: 1, e1: (-0.9, 0.9)})
>>> weight_sign(K0 * (K2 + e1) / C1, at), weight_sign(K0 * (K2 - e1**2) / C1, at), weight_sign(-2)
('?', '+', '-')
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import sympy as sp

from symctl._util.display import latex
from symctl._util.validate import real_number, to_expr
from symctl.errors import ParameterError, SymctlTypeError
from symctl.plotting import style
from symctl.plotting.common import text_size

COLOURS = {  # of a synapse by its sign ("": a plain wire to an output)
    "+": style.EXCITATORY,
    "-": style.INHIBITORY,
    "?": style.SYMBOLIC,
    "0": "0.7",
    "": style.NEUTRAL,
}


def arrow_style(sign: str, colour, linestyle) -> dict:
    """A synapse's arrow: a bar for an inhibitory one, else a head; dashed when delayed."""
    head = "-[,widthB=0.55,lengthB=0" if sign == "-" else "-|>,head_length=0.55,head_width=0.3"
    look = {"arrowstyle": head, "mutation_scale": 8, "color": colour, "linestyle": linestyle}
    return {**look, "shrinkA": 0, "shrinkB": 0}


_SAMPLE = 0.24  # the width of a sample mark [in]
_GAP = 0.05  # between a mark and its text
_ITEM_GAP = 0.16  # between two items of a row


@dataclass(frozen=True)
class SignValues:
    """The values at which a drawing reads the signs of its symbolic weights: ``numbers`` a value
    per symbol, ``ranges`` a closed ``(lo, hi)`` per symbol that varies (build with :meth:`of`).
    """

    numbers: Mapping = field(default_factory=dict)
    ranges: Mapping = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "numbers", MappingProxyType(dict(self.numbers)))
        object.__setattr__(self, "ranges", MappingProxyType(dict(self.ranges)))

    def __hash__(self) -> int:
        return hash((tuple(self.numbers.items()), tuple(self.ranges.items())))

    def __bool__(self) -> bool:
        return bool(self.numbers or self.ranges)

    @classmethod
    def of(cls, values, argname: str = "signs_at", symbols=()) -> SignValues:
        """Check ``values``: a mapping of symbols (or their names among ``symbols``, never parsed) to
        real numbers or ranges ``(lo, hi)``, ``lo < hi``; errors name ``argname``.

        >>> from symctl.plotting.circuit_key import SignValues
        >>> SignValues.of({"x": (1, 0)}, symbols=__import__("sympy").symbols("x,"))
        Traceback (most recent call last):
        ...
        symctl.errors.ParameterError: signs_at: the range of x must have lo < hi, got (1, 0)
        """
        if values is None:
            return cls()
        if isinstance(values, SignValues):
            return values
        if not isinstance(values, Mapping):
            raise SymctlTypeError(
                f"{argname}: expected a mapping of symbols to numbers or (lo, hi) ranges, "
                f"got {type(values).__name__}"
            )
        names = {str(s): s for s in symbols}
        nums, ranges = {}, {}
        for key, value in values.items():
            sym = _symbol(key, names, argname)
            if isinstance(value, tuple | list) and len(value) == 2:
                lo, hi = (real_number(v, f"{argname}[{sym}]") for v in value)
                if not lo < hi:
                    raise ParameterError(
                        f"{argname}: the range of {sym} must have lo < hi, got {tuple(value)}"
                    )
                ranges[sym] = (lo, hi)
            elif isinstance(value, sp.Basic | numbers.Real) and not isinstance(value, bool):
                v = to_expr(value, f"{argname}[{sym}]")
                if not (v.is_number and v.is_real and v.is_finite):
                    raise ParameterError(f"{argname}[{sym}]: must be a finite real number, got {v}")
                nums[sym] = v
            else:
                raise SymctlTypeError(
                    f"{argname}[{sym}]: expected a real number or a (lo, hi) range, got {value!r}"
                )
        return cls(nums, ranges)


def _symbol(key, names: dict, argname: str) -> sp.Symbol:
    if isinstance(key, sp.Symbol):
        return key
    if isinstance(key, str):
        if key in names:
            return names[key]
        raise ParameterError(
            f"{argname}: no symbol named {key!r} (the symbols are: {', '.join(sorted(names))})"
        )
    raise SymctlTypeError(f"{argname}: a key must be a sympy Symbol or its name, got {key!r}")


def _sign_of_bounds(value) -> str:
    if isinstance(value, sp.AccumBounds):
        return "+" if value.min.is_positive else "-" if value.max.is_negative else "?"
    if value.is_zero:
        return "0"
    if value.is_positive:
        return "+"
    if value.is_negative:
        return "-"
    return "?"


def weight_sign(weight, at: SignValues | None = None) -> str:
    """``"+"``, ``"-"``, ``"0"`` or ``"?"``: the sign of ``weight`` for all the values ``at``
    (without, SymPy's sign from the assumptions).
    """
    w = to_expr(weight, "weight")
    if at:
        if at.numbers:
            w = w.xreplace(dict(at.numbers))
        left = {s: sp.AccumBounds(*at.ranges[s]) for s in w.free_symbols if s in at.ranges}
        if left and w.free_symbols <= set(left):
            try:
                return _sign_of_bounds(w.xreplace(left))
            except (TypeError, ValueError, ZeroDivisionError):  # e.g. a range through a pole
                return "?"
    return _sign_of_bounds(w)


@dataclass(frozen=True)
class Key:
    """What a drawing shows, for its key: the ``signs`` and ``delays`` of its synapses; whether
    weights (``labelled``) and self-dynamics (``bodies``) are written and a circle is ``empty``;
    its neurons' ``vertices`` and the graph's ``vertex_names``; the ``signs_at``; the count of
    ``synapses``; and the ``numbered`` neurons ``(number, name, vertex)``.
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
    """The LaTeX of the letters of ``symbols`` without their indices, in order, once each."""
    return list(dict.fromkeys(latex(sp.Symbol(str(s).split("_")[0])) for s in symbols))


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


_SIGN_TEXT = {
    "+": "excitatory",
    "-": "inhibitory",
    "?": "sign depends on the symbols",
    "0": "weight 0",
}


def key_items(key: Key) -> list[tuple[str, str]]:
    """The key's items ``(mark, text)``; marks ``"+"``, ``"-"``, ``"?"``, ``"0"``, ``"dashed"``,
    ``"neuron"`` or ``""`` (text alone).
    """
    items: list[tuple[str, str]] = []
    if key.empty:
        items.append(("neuron", "neuron (empty: no self-dynamics)"))
    items += [(sign, text) for sign, text in _SIGN_TEXT.items() if sign in key.signs]
    delays = {d for d in key.delays if d > 0}
    if delays:
        if max(delays) == 1:
            items.append(("dashed", "delayed one step"))
        elif key.labelled:
            items.append(("dashed", r"delayed one step, or $k$ where $z^{-k}$ is written"))
        else:
            items.append(("dashed", "delayed (one step or more)"))
    if key.vertices and not key.numbered:
        names = key.vertex_names or ()
        if len(names) >= max(key.vertices) and any(names[v - 1] != f"v{v}" for v in key.vertices):
            said = ", ".join(f"v{v} {names[v - 1].replace('_', ' ')}" for v in key.vertices)
            items.append(("", f"under a neuron: its vertex, {said}".replace("$", r"\$")))
        else:
            items.append(("", "under a neuron: its delay-graph vertex"))
    if key.signs_at and "?" in key.signs | {"+", "-"}:
        items.append(("", _signs_note(key.signs_at)))
    if not key.labelled and key.synapses:
        what = "weights" if key.bodies else "weights and self-dynamics"
        why = "too many or too long to set legibly at this size (Circuit.equations() lists them)"
        items.append(("", f"{what} not written: {why}"))
    if key.numbered:
        items.append(("", "neurons by number:"))
        items += [
            ("", f"{k} {name}" + (f" (v{v})" if v is not None else ""))
            for k, name, v in key.numbered
        ]
    return items


def draw_key_items(ax, items, x: float, y: float, room: float, size: float):
    """Draw ``items`` in rows from ``(x, y)`` down, no row wider than ``room``; returns the
    lowest ``y`` and the rightmost ``x`` drawn at."""
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
