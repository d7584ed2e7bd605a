r"""The paper as a reference: its bibliography entry, and the numbers of its figures and equations
(counted in its LaTeX source, arXiv:2410.02555).
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
        name: k
        for k, name in enumerate(
            (
                "muscle system total_controller cost augmented_states augmented_system "
                "augmented_cost ifp_controller transfer_fn realization E factors sections E_tilde "
                "general_realization G2_rewritten controllable observable"
            ).split(),
            start=1,
        )
    }
)
"""The paper's numbered equations: LaTeX label (or a name for an unlabelled one) to number."""

DEFINITIONS = MappingProxyType(
    {
        name: k
        for k, name in enumerate(
            (
                "structure delay_graph delay_assignment delay_assignment_matrix "
                "compatible_structure compatible_controller"
            ).split(),
            start=1,
        )
    }
)
"""The paper's definitions (Sec. IV-B), in order."""

SECTIONS = MappingProxyType(
    dict(
        zip(
            (
                "introduction problem_setup optimal_delayed_controller compatibility "
                "microcircuits simulations future_work"
            ).split(),
            ("I", "II", "III", "IV", "V", "VI", "VII"),
            strict=True,
        )
    )
)
"""The paper's sections: LaTeX label (without ``sec:``) to Roman numeral."""

_KINDS = {
    f"{word}{s}.": table
    for word, table in (
        ("Fig", FIGURES),
        ("Eq", EQUATIONS),
        ("Def", DEFINITIONS),
        ("Sec", SECTIONS),
    )
    for s in ("", "s")
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
