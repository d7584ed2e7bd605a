r"""The atlas as documents: ``atlas.json``, ``atlas.md``, ``atlas.tex``/``.pdf`` and drawings."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import sympy as sp

from symctl._util.validate import callable_or_none
from symctl.report.document import Graphic, Heading, References, Table, Text
from symctl.report.output import write_json
from symctl.report.reference import REFERENCES, cite

__all__ = ["DRAWINGS", "atlas_blocks", "paper_blocks", "paper_realizations", "write_atlas"]

DRAWINGS = 24  # classes drawn one by one by default (the sparsest first)

OVERVIEW_MAX = 24  # universal classes on the overview figure (the sparsest first)

TABLE_ROWS = 60  # classes in the documents' table (atlas.json lists every class)
_COLUMNS = ("class", "neurons", "synapses", "branches", "pattern (F / H / M)", "verdict", "method")
_CANDIDATE_COLUMNS = ("class", "pattern (F / H / M)", r"$\epsilon$", "kind", "neurons", "synapses")
_CANDIDATE_COLUMNS += ("compatible",)


def paper_realizations(A) -> dict:
    """The classes of the paper's three realizations of a generic order-n G2, by name."""
    from symctl.circuitatlas.pattern import Pattern
    from symctl.realization.realizers import REALIZERS
    from symctl.symbols import z

    n = A.order
    a = sp.symbols(f"a_0:{n}")
    c = sp.symbols(f"c_0:{n}")
    G2 = 1 + sum(c[i] * z**i for i in range(n)) / (z**n + sum(a[i] * z**i for i in range(n)))
    dense = Pattern(n, (1 << (n * n + 2 * n)) - 1)
    forms = [r for r in REALIZERS.values() if r.paper and not r.controller]
    out = {}
    for r in sorted(forms, key=lambda r: not r.canonical):  # the canonical forms first
        try:
            pattern = dense if r.takes_transform else Pattern.of(r(G2).realization)
            out[r.form] = A.find(pattern)
        except Exception:
            continue
    return out


def _claim(A) -> list:
    ours = paper_realizations(A)
    universal = A.universal_classes
    sparse = min((c.representatives[0].size for c in universal), default=None)
    sparsest = [c for c in universal if c.representatives[0].size == sparse]
    where = ", ".join(f"the {k} one is {c.label}" for k, c in ours.items())
    conjectured = A.conjectured_classes
    text = (
        f"At order {A.order} there are {len(universal)} universal circuit classes, each "
        f"proved (minimal circuits that implement almost every order-{A.order} controller), "
        f"{len(sparsest)} of them with the fewest nonzero entries ({sparse}). "
        f"Among them, {where}."
    )
    if conjectured:
        text += (
            f" Another {len(conjectured)} classes are only conjectured universal: they have "
            "real realizations at sampled controllers of every pole region, which is not a proof."
        )
    if A.order == 2:
        text += (
            f" The paper's abstract {cite()} says that for any second-order controller there are three "
            "minimal circuit configurations. Counted as circuit classes, the number is "
            f"{len(universal)}, not three. The paper's three (controllable canonical, observable "
            "canonical, general) are three of these classes: the two canonical ones have the "
            "fewest entries and the general one is the dense pattern. The statement holds for "
            "the three realizations the paper drew, not for every circuit."
        )
    return [Heading("The paper's claim, checked", 2), Text(text)]


def _scope(A) -> list:
    s = A.stats
    if not s.get("skipped"):
        return []
    return [
        Text(
            f"Not exhaustive: of the {s['canonical']} pattern orbits of sizes {s['sizes'][0]} to "
            f"{s['sizes'][1]}, the {s['skipped']} whose circuits have more than "
            f"{s['max_neurons']} neurons were skipped, so the classes below are the sparsest "
            f"ones (at most {s['max_neurons']} neurons) among patterns of at most "
            f"{s['sizes'][1]} entries."
        )
    ]


def atlas_blocks(A, drawn=()) -> list:
    """The document: definitions, counts, the paper's claim, the classes, their evidence."""
    s = A.stats
    methods = Counter((c.status, c.evidence.method) for c in A.classes)
    sizes = f"{s['sizes'][0]}..{s['sizes'][1]}" + ("" if s["complete"] else " (not exhaustive)")
    counts = {
        "patterns": s["patterns"],
        "orbits": s["canonical"],
        "minimal": s["minimal"],
        "full rank": s["full_rank"],
        "classes": len(A.classes),
        "universal": len(A.universal_classes),
        "conjectured": len(A.conjectured_classes),
        "undecided": s["undecided"],
        "sizes": sizes,
        "seconds": f"{s['seconds']:g}",
    }
    blocks = [
        Heading(f"The circuit atlas of order {A.order}"),
        Text(
            "A pattern is the set of nonzero entries of $(F, H, M)$ in a realization of an "
            f"order-{A.order} $G_2$ with $N \\ne 0$. Its circuit is read off the "
            f"{A.delays}-delay structure with symctl's neuron rule; patterns with isomorphic "
            "circuits (neurons, synapses with their delays, self-dynamics, input and output) form "
            "a circuit class. A class is universal when one of its patterns realizes almost every "
            "real order-$n$ $G_2$ (complex poles, real poles of either sign, any numerator). Only "
            "patterns whose generic realization is minimal are kept."
        ),
        Table(tuple(counts), (tuple(map(str, counts.values())),)),
        *_scope(A),
        *_claim(A),
        Heading("How each verdict was reached", 2),
        Table(
            ("verdict", "method", "classes"),
            tuple((v, m, str(k)) for (v, m), k in sorted(methods.items())),
        ),
        Text(
            "closed form: entries as rational functions of $G_2$'s coefficients, proved exactly "
            "against the symbolic $G_2$; odd degree: the generic fibre (a Groebner basis over "
            "$\\mathbb{Q}(a, c)$ in shape position) has an odd number of points, so a real "
            "one always exists; lifted: contains a proved universal pattern; "
            "conjectured: real realizations proved to exist (an exact count or a Krawczyk test) "
            "at every sampled $G_2$ of every region of poles and zeros, or contains such a "
            "pattern: evidence, "
            "not proof, so not counted as universal; rank: generic rank below $2n$; real "
            "eigenvalues: $F$ block triangular with too many odd blocks; real zeros: "
            "$M \\operatorname{adj}(zI - F) H$ factors into odd-degree factors in $z$ that force "
            "real zeros, so numerators with complex zeros are missed; counterexample: a sampled "
            "generic $G_2$ (the generic number of simple complex realizations) with no real "
            "realization, exactly."
        ),
        Heading("The classes", 2),
        Table(
            _COLUMNS,
            tuple(
                (
                    c.label,
                    str(c.n_neurons),
                    str(c.n_synapses),
                    str(c.n_branches),
                    c.representatives[0].text.replace("|", "/"),
                    c.status,
                    c.evidence.method,
                )
                for c in A.classes[:TABLE_ROWS]
            ),
        ),
    ]
    if len(A.classes) > TABLE_ROWS:
        blocks.append(
            Text(f"The first {TABLE_ROWS} of {len(A.classes)} classes; atlas.json lists them all.")
        )
    if drawn:
        blocks.append(Heading("Drawings", 2))
        blocks.append(
            Graphic(
                "atlas_overview",
                f"The classes of order {A.order} proved universal, sparsest first."
                if A.universal_classes
                else f"The first classes of order {A.order}.",
            )
        )
        if A.universal_classes and A.conjectured_classes:
            blocks.append(
                Graphic(
                    "atlas_conjectured",
                    f"Classes of order {A.order} conjectured universal (not proved), sparsest "
                    "first.",
                )
            )
        for label in drawn:
            c = next(x for x in A.classes if x.label == label)
            blocks.append(
                Graphic(
                    f"class_{label}",
                    f"{label}: {c.n_neurons} neurons, {c.n_synapses} synapses, "
                    f"{c.status} ({c.evidence.method}).",
                )
            )
    blocks.append(References(REFERENCES))
    return blocks


def write_atlas(A, out, *, drawings: int | None = DRAWINGS, pdf: bool = True, progress=None):
    """Write atlas.json, atlas.md, atlas.tex (and .pdf when ``pdf`` and ``pdflatex``) and the
    drawings of the first ``drawings`` classes (None: all) into the folder ``out``; returns the
    paths. ``progress`` gets each step's name before it runs (``"drawing class_A1"``,
    ``"documents"``, ``"pdf"``)."""
    from symctl.report.document import compile_pdf, write_markdown, write_tex
    from symctl.report.figures import save

    out = Path(out)
    step = callable_or_none(progress, "progress") or (lambda _name: None)
    written = [write_json(out / "atlas.json", A.to_dict(), indent=1)]
    chosen = A.classes if drawings is None else A.classes[:drawings]
    drawn = []
    if chosen:
        step("drawing atlas_overview")
        overview = A.universal_classes[:OVERVIEW_MAX] or A.classes[:OVERVIEW_MAX]
        from symctl.plotting.atlas import draw_classes

        written += save(draw_classes(A, overview), out, "atlas_overview")
        if A.universal_classes and A.conjectured_classes:
            step("drawing atlas_conjectured")
            written += save(
                draw_classes(A, A.conjectured_classes[:OVERVIEW_MAX]), out, "atlas_conjectured"
            )
        for c in chosen:
            step(f"drawing class_{c.label}")
            written += save(c.draw(), out, f"class_{c.label}")
            drawn.append(c.label)
    step("documents")
    blocks = atlas_blocks(A, drawn)
    title = f"The circuit atlas of order {A.order}"
    written.append(write_markdown(blocks, out / "atlas.md", title=title))
    tex = write_tex(blocks, out / "atlas.tex", title=title)
    written.append(tex)
    if pdf:
        step("pdf")
        made = compile_pdf(tex)
        if made is not None:
            written.append(made)
    return written


def claim_json(A) -> dict:
    """The order-n count and where the paper's three realizations sit (results.json ``atlas``)."""
    return {
        "order": A.order,
        "classes": len(A.classes),
        "universal": len(A.universal_classes),
        "universal_labels": [c.label for c in A.universal_classes],
        "conjectured": len(A.conjectured_classes),
        "paper": {k: c.label for k, c in paper_realizations(A).items()},
    }


def candidates_json(candidates) -> list | None:
    """One item per circuit class that realizes the paper's controller."""
    if candidates is None:
        return None
    return [
        {
            "class": c.circuit_class.label,
            "pattern": c.circuit_class.representatives[0].text,
            "degenerate": c.degenerate,
            "eps": [float(e) for e in c.eps],
            "neurons": c.n_neurons,
            "synapses": c.n_synapses,
            "compatible": c.compatible,
            "check": c.check.method,
        }
        for c in candidates
    ]


def paper_blocks(res, shown) -> list:
    """The atlas section of ``symctl paper``: the order-2 count, the drawings, this controller's classes."""
    from symctl.report.figures import simplified

    A = res.atlas
    blocks = [Heading("The circuit atlas"), *_claim(A)[1:]]

    def figure(name: str, caption: str) -> None:
        if name in shown:
            blocks.append(Graphic(name, caption))

    blocks.append(
        Text(
            f"The order-2 atlas has {len(A.classes)} circuit classes of minimal realizations in all "
            f"({len(A.universal_classes)} universal; the others realize a lower-dimensional set "
            "of $G_2$, or miss a region of them). The command symctl atlas writes every class "
            "with its evidence, for orders 1 to 4; order 3 is new: see the README."
        )
    )
    figure("atlas_overview", "The universal circuit classes of order 2, sparsest first.")
    cands = res.candidates
    if cands is None:
        blocks.append(
            Text(
                f"This controller's $G_2$ has order {res.system.T}; the command symctl atlas "
                f"with that order lists its classes."
            )
        )
        return blocks
    blocks.append(Heading("The circuits of this controller", 2))
    blocks.append(
        Text(
            "Every class of the atlas that realizes this controller's $G_2$ for some section poles "
            "$\\epsilon$, with the whole controller $G_3 G_2 G_1$ checked on the delay graph. "
            "Generic classes use the seeded $\\epsilon$ shown; degenerate ones need special "
            "$\\epsilon$, found by Gauss-Newton and certified by the Krawczyk test: they are the "
            f"paper's simplified circuits {cite('Sec.', 'microcircuits')} (for example "
            "$K_2 + \\epsilon_1\\epsilon_3 = 0$ drops an axon branch of the controllable canonical "
            "circuit)."
        )
    )
    blocks.append(
        Table(
            _CANDIDATE_COLUMNS,
            tuple(
                (
                    c.circuit_class.label,
                    c.circuit_class.representatives[0].text.replace("|", "/"),
                    ", ".join(f"{float(e):.4g}" for e in c.eps),
                    "special $\\epsilon$" if c.degenerate else "generic",
                    str(c.n_neurons),
                    str(c.n_synapses),
                    {True: "yes", False: "no", None: "-"}[c.compatible],
                )
                for c in cands
            ),
        )
    )
    for c in simplified(cands):
        figure(
            f"simplified_{c.circuit_class.label}",
            f"A simplified circuit {cite('Sec.', 'microcircuits')}: class {c.circuit_class.label} at "
            f"$\\epsilon = ({', '.join(f'{float(e):.4g}' for e in c.eps)})$, "
            f"{c.n_neurons} neurons.",
        )
    return blocks
