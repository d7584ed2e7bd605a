r"""The text of a structure drawing: signal names, gain values, the key, the ends; no matplotlib.

Signals are named once each, by their part (:math:`x^{\mathrm{G2}}_1`); a gain shows its
value when at most :data:`LONG_GAIN` characters, else its entry's name (``G2.F[1,2]`` is
:math:`F_{12}`), the key listing the value.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from symctl._util.texnames import signal_tex
from symctl.compatibility.structure import Structure
from symctl.errors import ParameterError, SymctlTypeError
from symctl.plotting.circuit_labels import visible_length, weight_tex

__all__ = ["LONG_GAIN", "StructureText", "end_labels", "signal_label", "structure_text"]

LONG_GAIN = 10  # a gain showing more characters is drawn by its entry's name (0.45 in at 7 pt)

_ENTRY = re.compile(r"([A-Za-z]+)\[(\d+)(?:,(\d+))?\]")
_NAME = re.compile(r"[A-Za-z]+(\d+|_\{[^{}]*\}|_[A-Za-z0-9]+)?")


def signal_label(name: str) -> str:
    r"""LaTeX (no ``$``) of a signal, its part as a superscript: ``G2.x1`` -> :math:`x^{\mathrm{G2}}_1`.

    >>> from symctl.plotting.structure_labels import signal_label
    >>> signal_label("G2.x1"), signal_label("gamma"), signal_label("G1.2.u")
    ('x^{\\mathrm{G2}}_{1}', '\\gamma', 'u^{\\mathrm{G1.\\!2}}')
    """
    part, _, local = name.rpartition(".")
    base = signal_tex(local, part=False)
    if not part:
        return base
    sup = "^{" + _part_tex(part) + "}"
    stem, sep, index = base.partition("_")
    if _NAME.fullmatch(local):
        return f"{stem}{sup}{sep}{index}"
    return f"{{{base}}}{sup}"


def _part_tex(part: str) -> str:
    """A part's name in roman, without mathtext's space after a dot."""
    return r"\mathrm{" + part.replace(".", r".\!") + "}"


def _gain_name(name: str) -> str | None:
    """A gain's matrix entry (``F[1,2]``: ``F_{12}``), a signal-like name as a signal, or None."""
    local = name.rpartition(".")[2]
    entry = _ENTRY.fullmatch(local)
    if entry:
        stem, i, j = entry.groups()
        index = [i] if j is None else [i, j]
        sep = "" if all(len(k) == 1 for k in index) else ","
        return f"{stem}_{{{sep.join(index)}}}"
    if _NAME.fullmatch(local):
        return signal_tex(local, part=False)
    return None


@dataclass(frozen=True, eq=False)
class StructureText:
    """What a structure drawing writes (LaTeX without ``$``): ``gains`` each gain's text, ``names``
    the name at each named signal, ``ends`` the labels of the inputs' and outputs' arrows, and
    ``key`` the ``(names, value)`` of each long gain value.
    """

    gains: Mapping[str, str] = field(default_factory=dict)
    names: Mapping[str, str] = field(default_factory=dict)
    ends: Mapping[str, str] = field(default_factory=dict)
    key: tuple[tuple[str, str], ...] = ()

    def __post_init__(self) -> None:
        for attr in ("gains", "names", "ends"):
            object.__setattr__(self, attr, MappingProxyType(dict(getattr(self, attr))))

    def key_lines(self) -> list[str]:
        """The key as LaTeX lines, ``name = value``."""
        return [f"{names} = {value}" for names, value in self.key]


def end_labels(S: Structure, labels: Mapping[str, str] | None = None) -> dict[str, str]:
    """The arrow labels (LaTeX) of the inputs, then outputs: ``labels`` where given, else the signal's."""
    labels = {} if labels is None else labels
    if not isinstance(labels, Mapping):
        raise SymctlTypeError(
            f"labels: expected a mapping of input/output signal names to labels, got {labels!r}"
        )
    ends = {name: signal_label(name) for name in (*S.inputs, *S.outputs)}
    for name, text in labels.items():
        if name not in ends:
            raise ParameterError(
                f"labels: {name!r} is not an input or output of the structure; "
                f"they are {sorted(ends)}"
            )
        if not isinstance(text, str) or not text:
            raise SymctlTypeError(f"labels[{name!r}]: expected a non-empty string, got {text!r}")
        ends[name] = text
    return ends


def structure_text(S: Structure, labels: Mapping[str, str] | None = None) -> StructureText:
    r"""The text of the drawing of ``S`` (see the module text); ``labels`` as for :func:`end_labels`."""
    if not isinstance(S, Structure):
        raise SymctlTypeError(f"S: expected a Structure, got {type(S).__name__}")
    ends = end_labels(S, labels)
    names = {}
    for name, block in S.blocks.items():
        if block.kind == "gain" or name.rpartition(".")[2].startswith("z^-"):  # a branch term
            continue
        label = signal_label(name)
        if ends.get(name) != label:
            names[name] = label
    gains, long_values = {}, {}
    for name, block in S.blocks.items():
        if block.kind != "gain":
            continue
        tex = weight_tex(block.gain) if block.gain is not None else None
        if tex is not None and visible_length(tex) <= LONG_GAIN:
            gains[name] = tex
        else:
            gains[name] = _gain_name(name) or ""
            long_values[name] = tex
    # short names: one per entry, the part added where two parts share one; w_k for the rest
    short = {n: gains[n] for n in long_values}
    clash = {t for t in short.values() if list(short.values()).count(t) > 1}
    numbered = 0
    for n in long_values:
        part = S.blocks[n].part
        if not short[n] or (short[n] in clash and not part):
            numbered += 1
            short[n] = f"w_{{{numbered}}}"
        elif short[n] in clash:
            stem, _, index = short[n].partition("_")
            short[n] = stem + "^{" + _part_tex(part) + "}_" + index
        gains[n] = short[n]
    by_value: dict[str, list[str]] = {}
    for n, tex in long_values.items():
        if tex is not None:
            by_value.setdefault(tex, []).append(short[n])
    key = tuple((" = ".join(group), tex) for tex, group in by_value.items())
    return StructureText(gains, names, ends, key)
