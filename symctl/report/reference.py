r"""The paper as a reference: its bibliography entry, and the numbers of its figures and equations
(counted in its LaTeX source, arXiv:2410.02555)."""

from __future__ import annotations

from types import MappingProxyType

from symctl.errors import ParameterError

__all__ = ["DEFINITIONS", "EQUATIONS", "FIGURES", "KEY", "REFERENCES", "SECTIONS", "cite"]

KEY = "li2024"  # the citation key of the paper

REFERENCES = (  # the bibliography: (key, entry) pairs, numbered in this order
    (
        KEY,
        "J. S. Li, \u201cToward neuronal implementations of delayed optimal control,\u201d "
        "arXiv:2410.02555 [eess.SY], 2024.",
    ),
)

FIGURES = MappingProxyType(  # the paper's figures: LaTeX label (without fig:) to number
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


def _numbered(labels: str, numbers=None) -> MappingProxyType:
    """The labels (separated by spaces) to their numbers, by default 1, 2, ..."""
    names = labels.split()
    return MappingProxyType(dict(zip(names, numbers or range(1, len(names) + 1), strict=True)))


EQUATIONS = _numbered(  # the numbered equations: label (or a name) to number
    "muscle system total_controller cost augmented_states augmented_system augmented_cost "
    "ifp_controller transfer_fn realization E factors sections E_tilde general_realization "
    "G2_rewritten controllable observable"
)
DEFINITIONS = _numbered(  # the definitions of Sec. IV-B, in order
    "structure delay_graph delay_assignment delay_assignment_matrix compatible_structure "
    "compatible_controller"
)
SECTIONS = _numbered(  # LaTeX label (without sec:) to Roman numeral
    "introduction problem_setup optimal_delayed_controller compatibility microcircuits "
    "simulations future_work",
    ("I", "II", "III", "IV", "V", "VI", "VII"),
)

_TABLES = {"Fig": FIGURES, "Eq": EQUATIONS, "Def": DEFINITIONS, "Sec": SECTIONS}
_KINDS = {f"{word}{s}.": table for word, table in _TABLES.items() for s in ("", "s")}


def cite(kind: str | None = None, *labels: str) -> str:
    """A citation of the paper in the prose markup: ``[@li2024]`` without ``kind``, else
    ``[@li2024, Fig. 5]`` for ``kind`` one of "Fig.", "Eq.", "Def.", "Sec." (or plural) and the
    paper's ``labels`` (keys of :data:`FIGURES`, :data:`EQUATIONS`, :data:`DEFINITIONS`,
    :data:`SECTIONS`); ParameterError for an unknown kind or label."""
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
