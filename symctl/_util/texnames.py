r"""The one spelling of a signal name in LaTeX, for diagrams, tables and documents.

>>> from symctl._util.texnames import signal_tex
>>> signal_tex("gamma2"), signal_tex("G2.x1"), signal_tex("G2.x1", part=False)
('\\gamma_{2}', '{x_{1}}^{\\mathrm{G2}}', 'x_{1}')
>>> signal_tex("epsilon_{1,2}"), signal_tex("u")
('\\epsilon_{1,2}', 'u')
"""

from __future__ import annotations

import re

GREEK = frozenset(
    "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi pi rho sigma "
    "tau upsilon phi chi psi omega".split()
)

_NAME = re.compile(r"([A-Za-z]+)(?:(\d+)|_\{([^{}]*)\}|_([A-Za-z0-9]+))?")


def signal_tex(name: str, *, part: bool = True) -> str:
    r"""LaTeX (without ``$``) of a signal or neuron name: ``G2.x1`` is ``{x_{1}}^{\mathrm{G2}}``.

    A stem and an index become a subscript, a Greek stem a Greek letter; the part before
    a dot a roman superscript (dropped with ``part=False``); any other name is roman.
    """
    prefix, _, short = name.rpartition(".")
    match = _NAME.fullmatch(short)
    if match:
        stem, digits, braced, plain = match.groups()
        index = digits or braced or plain
        stem = "\\" + stem if stem in GREEK else stem
        label = f"{stem}_{{{index}}}" if index else stem
    else:
        label = short if short.isalnum() else rf"\mathrm{{{short}}}"
    if prefix and part:
        return rf"{{{label}}}^{{\mathrm{{{prefix}}}}}"  # braced: the part follows the index
    return label
