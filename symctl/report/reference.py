r"""The paper as a reference: its bibliography entry, and the numbers of its figures and equations.

The derivation cites the paper it implements as a paper cites another (``[1, Fig. 5]``).
The numbers were counted in the paper's LaTeX source (arXiv:2410.02555, ``ieeeconf``):
figures, equations and definitions in the order of their environments, sections by
the class's Roman numerals.

Examples
--------
>>> from symctl.report.reference import cite
>>> cite("Fig.", "cl_sims"), cite("Eq.", "transfer_fn"), cite()
('[@li2024, Fig. 5]', '[@li2024, Eq. (9)]', '[@li2024]')
"""

from __future__ import annotations

from types import MappingProxyType

from symctl.errors import ParameterError

__all__ = ["DEFINITIONS", "EQUATIONS", "FIGURES", "KEY", "REFERENCES", "SECTIONS", "cite"]

KEY = "li2024"
"""The citation key of the paper."""

REFERENCES = (
    (
        KEY,
        "J. S. Li, \u201cToward neuronal implementations of delayed optimal control,\u201d "
        "arXiv:2410.02555 [eess.SY], 2024.",
    ),
)
"""The bibliography of the derivation: ``(key, entry)`` pairs, in the order they are numbered."""

FIGURES = MappingProxyType(
    {
        "behavior_implementation": 1,
        "muscle_system": 2,  # left: the neuromuscular system; right: its delay graph
        "ol_sims": 3,  # open-loop response to a unit pulse
        "ifp_diagram": 4,  # the IFP controller's structure
        "cl_sims": 5,  # closed-loop response to a unit pulse disturbance
        "definitions": 6,
        "g1g3": 7,  # two structures of G1 and G3; the structure of G
        "neural_circuit": 8,  # the stylized neuron
        "full_diagram": 9,  # general realization of G2: structure, circuit, firing
        "ccr_diagram": 10,  # controllable canonical realization of G2
        "ocr_diagram": 11,  # observable canonical realization of G2
    }
)
"""The paper's figures: LaTeX label (without ``fig:``) to number."""

EQUATIONS = MappingProxyType(
    {
        "muscle": 1,
        "system": 2,
        "total_controller": 3,
        "cost": 4,
        "augmented_states": 5,
        "augmented_system": 6,
        "augmented_cost": 7,
        "ifp_controller": 8,
        "transfer_fn": 9,
        "realization": 10,  # x(t+1) = F x + H u, y = M x + N u
        "E": 11,  # the delay graph's matrix
        "factors": 12,  # G1, G3 and G2
        "sections": 13,  # the realization of G1 and G3
        "E_tilde": 14,  # the delay assignment matrix printed for G3 G2 G1
        "general_realization": 15,
        "G2_rewritten": 16,  # N + N (...)/(z^2 - K1 z - K2)
        "controllable": 17,
        "observable": 18,
    }
)
"""The paper's numbered equations: LaTeX label (or a name for an unlabelled one) to number."""

DEFINITIONS = MappingProxyType(
    {
        "structure": 1,
        "delay_graph": 2,
        "delay_assignment": 3,
        "delay_assignment_matrix": 4,
        "compatible_structure": 5,
        "compatible_controller": 6,
    }
)
"""The paper's definitions (Sec. IV-B), in order."""

SECTIONS = MappingProxyType(
    {
        "introduction": "I",
        "problem_setup": "II",
        "optimal_delayed_controller": "III",
        "compatibility": "IV",
        "microcircuits": "V",
        "simulations": "VI",
        "future_work": "VII",
    }
)
"""The paper's sections: LaTeX label (without ``sec:``) to Roman numeral."""

_KINDS = {
    "Fig.": FIGURES,
    "Figs.": FIGURES,
    "Eq.": EQUATIONS,
    "Eqs.": EQUATIONS,
    "Def.": DEFINITIONS,
    "Defs.": DEFINITIONS,
    "Sec.": SECTIONS,
    "Secs.": SECTIONS,
}


def cite(kind: str | None = None, *labels: str) -> str:
    """A citation of the paper in the document's prose markup, with a locator by label.

    Parameters
    ----------
    kind : {"Fig.", "Figs.", "Eq.", "Eqs.", "Def.", "Defs.", "Sec.", "Secs."}, optional
        What is cited; without it, the paper as a whole.
    *labels : str
        The paper's labels of what is cited (keys of :data:`FIGURES`,
        :data:`EQUATIONS`, :data:`DEFINITIONS` or :data:`SECTIONS`).

    Returns
    -------
    str
        ``[@li2024]`` or ``[@li2024, Fig. 5]`` (several labels joined by commas).

    Raises
    ------
    ParameterError
        An unknown ``kind`` or label.

    Examples
    --------
    >>> from symctl.report.reference import cite
    >>> cite("Figs.", "full_diagram", "ocr_diagram"), cite("Sec.", "simulations")
    ('[@li2024, Figs. 9, 11]', '[@li2024, Sec. VI]')
    """
    if kind is None:
        return f"[@{KEY}]"
    table = _KINDS.get(kind)
    if table is None:
        raise ParameterError(f"kind: one of {sorted(_KINDS)}, got {kind!r}")
    unknown = [x for x in labels if x not in table]
    if unknown or not labels:
        raise ParameterError(f"labels: the paper has no {kind} {unknown or 'without a label'}")
    numbers = [f"({table[x]})" if kind.startswith("Eq") else str(table[x]) for x in labels]
    return f"[@{KEY}, {kind} {', '.join(numbers)}]"
