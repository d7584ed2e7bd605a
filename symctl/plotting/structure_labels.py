r"""The text of a structure drawing: signal names, gain values, the key, the ends.

What :func:`symctl.plotting.structure.draw_structure` writes, apart from where it
goes (no matplotlib here):

* **Signals** are named once each, by their part when the structure is a series
  connection: the state :math:`x_1` of :math:`G_2` is :math:`x^{\mathrm{G2}}_1`, not
  the same :math:`x_1` as :math:`G_1`'s and :math:`G_3`'s. Adders and delayed states
  are named; the delayed branch terms ``z^-1 F[1,2]`` (one dot each) are not.
* **Gains** show their value (numbers to 3 significant digits,
  :func:`~symctl.plotting.circuit_labels.weight_tex`) when it is short
  (:data:`LONG_GAIN` visible characters,
  :func:`~symctl.plotting.circuit_labels.visible_length`); a long one shows the name of
  its matrix entry (``G2.F[1,2]`` is :math:`F_{12}`), and the key under the drawing
  lists its value, as a circuit drawing lists its long weights. Entries of equal value
  share one line of the key.
* **Ends**: the input arrows and output arrows carry the controller's names of its
  input and output (by default the signals' own names; the report passes the plant's,
  so every structure of one controller names them alike).

>>> from symctl import Structure, controllable_canonical, controller_tf, factor
>>> from symctl.plotting.structure_labels import structure_text
>>> f = factor(controller_tf(2))
>>> text = structure_text(Structure.from_factorization(f, controllable_canonical(f.G2)))
>>> text.names["G1.x1"], text.names["G2.x1"], text.gains["G2.M[1]"]
('x^{\\mathrm{G1}}_{1}', 'x^{\\mathrm{G2}}_{1}', 'M_{1}')
>>> text.key_lines()[0]
'M_{1} = \\frac{K_{0} \\left(K_{2} + \\epsilon_{1} \\epsilon_{3}\\right)}{C_{1} C_{3}}'
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

__all__ = [
    "LONG_GAIN",
    "StructureText",
    "end_labels",
    "gain_name",
    "is_branch_term",
    "part_tex",
    "signal_label",
    "structure_text",
]

LONG_GAIN = 10
r"""A gain whose LaTeX shows more characters than this is drawn by the name of its entry,
its value in the key. Ten characters at 7 points are about 0.45 inch, a box that still
leaves room for a neighbouring column on a 6.9-inch page (:math:`\frac{K_0}{C_1 C_3}`
shows six)."""

_ENTRY = re.compile(r"([A-Za-z]+)\[(\d+)(?:,(\d+))?\]")
_NAME = re.compile(r"[A-Za-z]+(\d+|_\{[^{}]*\}|_[A-Za-z0-9]+)?")


def is_branch_term(name: str) -> bool:
    """Whether ``name`` is a delayed branch term (``G2.z^-1 F[1,2]``): a dot, not a named signal.

    >>> from symctl.plotting.structure_labels import is_branch_term
    >>> is_branch_term("G2.z^-1 F[1,2]"), is_branch_term("G2.x1")
    (True, False)
    """
    return name.rpartition(".")[2].startswith("z^-")


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
    sup = "^{" + part_tex(part) + "}"
    stem, sep, index = base.partition("_")
    if _NAME.fullmatch(local):
        return f"{stem}{sup}{sep}{index}"
    return f"{{{base}}}{sup}"


def part_tex(part: str) -> str:
    r"""A part's name in roman, without mathtext's space after a dot.

    >>> from symctl.plotting.structure_labels import part_tex
    >>> print(part_tex("P1.G2"))
    \mathrm{P1.\!G2}
    """
    return r"\mathrm{" + part.replace(".", r".\!") + "}"


def gain_name(name: str) -> str | None:
    r"""The short LaTeX name of a gain block: its matrix entry (``F[1,2]`` -> :math:`F_{12}`).

    Indices are run together when every one is a single digit, else separated by a
    comma; a block named like a signal (``K0``) is set as one; ``None`` for any other
    name.

    >>> from symctl.plotting.structure_labels import gain_name
    >>> gain_name("G2.F[1,2]"), gain_name("G2.M[10,2]"), gain_name("N"), gain_name("K0")
    ('F_{12}', 'M_{10,2}', 'N', 'K_{0}')
    """
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
    r"""What a structure drawing writes (LaTeX without ``$``).

    Attributes
    ----------
    gains : mapping of str to str
        Each gain block's text: its value, or the short name listed in the key.
    names : mapping of str to str
        The name written at each named signal (inputs, adders, delayed states); an input
        or output whose arrow (:attr:`ends`) carries the same name is not named twice.
    ends : mapping of str to str
        The label at the arrow into each input and out of each output.
    key : tuple of (str, str)
        ``(names, value)`` of each long gain value (names joined by ``=``).
    """

    gains: Mapping[str, str] = field(default_factory=dict)
    names: Mapping[str, str] = field(default_factory=dict)
    ends: Mapping[str, str] = field(default_factory=dict)
    key: tuple[tuple[str, str], ...] = ()

    def __post_init__(self) -> None:
        for attr in ("gains", "names", "ends"):
            object.__setattr__(self, attr, MappingProxyType(dict(getattr(self, attr))))

    def key_lines(self) -> list[str]:
        r"""The key as LaTeX lines, ``name = value``.

        >>> from symctl.plotting.structure_labels import StructureText
        >>> StructureText(key=(("F_{12}", r"\frac{a}{b}"),)).key_lines()
        ['F_{12} = \\frac{a}{b}']
        """
        return [f"{names} = {value}" for names, value in self.key]


def end_labels(S: Structure, labels: Mapping[str, str] | None = None) -> dict[str, str]:
    r"""The arrow labels of the inputs and outputs: ``labels`` where given, else the signal's.

    What the block diagram and the overview of ``S`` write at its ends (LaTeX without
    ``$``), inputs first.

    Parameters
    ----------
    S : Structure
    labels : mapping of str to str, optional
        LaTeX labels by input or output signal name.

    Returns
    -------
    dict of str to str

    Raises
    ------
    ParameterError
        ``labels`` names a signal that is no input or output.
    SymctlTypeError
        ``labels`` is not a mapping of non-empty strings.

    Examples
    --------
    >>> from symctl import ifp_structure
    >>> from symctl.plotting.structure_labels import end_labels
    >>> end_labels(ifp_structure(2)), end_labels(ifp_structure(2), {"x": "f"})
    ({'x': 'x', 'u': 'u'}, {'x': 'f', 'u': 'u'})
    """
    if labels is None:
        labels = {}
    if not isinstance(labels, Mapping):
        raise SymctlTypeError(
            f"labels: expected a mapping of input/output signal names to labels, got {labels!r}"
        )
    ends = {}
    for name in (*S.inputs, *S.outputs):
        ends[name] = signal_label(name)
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
    r"""The text of the drawing of ``S`` (see the module text for the rules).

    Parameters
    ----------
    S : Structure
    labels : mapping of str to str, optional
        LaTeX labels of the arrows into the inputs and out of the outputs, by signal
        name (default: the signals' own names).

    Returns
    -------
    StructureText

    Raises
    ------
    ParameterError
        ``labels`` names a signal that is no input or output.
    SymctlTypeError
        ``labels`` is not a mapping of strings.

    Examples
    --------
    >>> from symctl import ifp_structure
    >>> from symctl.plotting.structure_labels import structure_text
    >>> text = structure_text(ifp_structure(2), {"x": "f", "u": "r"})
    >>> dict(text.ends), dict(text.names)
    ({'x': 'f', 'u': 'r'}, {'x': 'x', 'gamma': '\\gamma', 'u': 'u', 'mu': '\\mu'})
    >>> dict(structure_text(ifp_structure(2)).names)  # u is named at its arrow
    {'gamma': '\\gamma', 'mu': '\\mu'}
    """
    if not isinstance(S, Structure):
        raise SymctlTypeError(f"S: expected a Structure, got {type(S).__name__}")
    ends = end_labels(S, labels)
    names = {}
    for name, block in S.blocks.items():
        if block.kind == "gain" or is_branch_term(name):
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
            gains[name] = gain_name(name) or ""
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
            short[n] = stem + "^{" + part_tex(part) + "}_" + index
        gains[n] = short[n]
    by_value: dict[str, list[str]] = {}
    for n, tex in long_values.items():
        if tex is not None:
            by_value.setdefault(tex, []).append(short[n])
    key = tuple((" = ".join(group), tex) for tex, group in by_value.items())
    return StructureText(gains, names, ends, key)
