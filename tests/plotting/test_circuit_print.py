"""Circuit drawings at their printed size: the paper's circuits at T = 2 and T = 6, and a MIMO one.

Each figure is drawn once (module fixtures) and checked as a reviewer reads it: no wider than
the derivation's text, no text under 6 pt, no two texts overlapping
(:func:`symctl.plotting.legibility.legibility`), no curve through a neuron or a neuron's name,
the arrow heads and bars at one neuron apart, no "0" for a neuron without self-dynamics, the
signs in the style's colours, and a key that says what the dashes mean.
"""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest
from matplotlib.colors import to_hex

matplotlib.use("Agg")

from symctl import (
    Circuit,
    DelayGraph,
    MuscleModel,
    Structure,
    augment,
    check_compatibility,
    circuit_firing,
    controllable_canonical,
    controller_tf,
    factor,
    ifp_structure,
    lqr_gains,
    observable_canonical,
)
from symctl.plotting import layered, style
from symctl.plotting.circuit import draw_circuit, drawn
from symctl.plotting.circuit_layout import DOT, Measures
from symctl.plotting.legibility import legibility

EPS = (-0.9, 0.9)


def placed(S: Structure, steps: int) -> Circuit:
    """The circuit of ``S`` at the vertices of the chain sensor -> ... -> muscle."""
    return Circuit.from_structure(S, check_compatibility(S, DelayGraph.chain([1] * steps)))


def signs_at(c: Circuit, gains) -> dict:
    """The report's values: the gains, C = 1 and every epsilon in (-0.9, 0.9)."""
    values = {k: v for k, v in gains.substitutions().items() if k in c.free_symbols}
    for s in c.free_symbols - set(values):
        values[s] = EPS if str(s).startswith("epsilon") else 1
    return values


def general(gains, steps: int) -> Circuit:
    """The first simulated realization of the general circuit, placed on the chain."""
    return placed(circuit_firing("general", gains, count=1).circuits[0].structure, steps)


@pytest.fixture(scope="module")
def circuits(mimo_factorization):
    g2, g6 = (lqr_gains(augment(MuscleModel(), d, d)) for d in (1, 3))
    f2, f6 = factor(controller_tf(2)), factor(controller_tf(6), 3, 3)
    # the report's T = 6 form: G2 in sigma, the sums of products of the epsilons
    obs6 = Structure.from_factorization(f6, observable_canonical(f6.abbreviated()))
    ctrl6 = Structure.from_factorization(f6, controllable_canonical(f6.abbreviated()))
    out = {
        "ifp": (Circuit.from_structure(ifp_structure(2)), g2),
        "general": (general(g2, 2), g2),
        "observable6": (placed(obs6, 6), g6),
        "controllable6": (placed(ctrl6, 6), g6),  # six synapses x6 -> y, z^-1 .. z^-5
        "general6": (general(g6, 6), g6),
    }
    for kind, realize in (
        ("controllable", controllable_canonical),
        ("observable", observable_canonical),
    ):
        out[kind] = (placed(Structure.from_factorization(f2, realize(f2.G2)), 2), g2)
    f = mimo_factorization
    mimo = Structure.from_factorization(f, controllable_canonical(f.G2))
    out["mimo"] = (Circuit.from_structure(mimo), None)
    return out


@pytest.fixture(scope="module")
def figures(circuits):
    figs = {}
    for name, (c, gains) in circuits.items():
        figs[name] = draw_circuit(c, signs_at=signs_at(c, gains) if gains else None)
    return figs


NAMES = [
    "ifp",
    "general",
    "controllable",
    "observable",
    "observable6",
    "controllable6",
    "general6",
    "mimo",
]


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_the_drawing_is_legible_at_its_printed_size(figures, name):
    leg = legibility(figures[name], page_width=style.TEXT_WIDTH)
    assert leg, f"{name}: {leg}"


@pytest.mark.parametrize("name", NAMES)
def test_no_curve_runs_through_a_neuron_or_a_text_and_arrow_ends_are_apart(figures, name):
    d = drawn(figures[name].axes[0])
    lay, m = d.layout, d.measures
    texts = lay.boxes(Measures(m.radius, m.name, m.tag, {}, m.end))
    nodes = list(lay.pos)
    # (less the margin a curve keeps from a circle: inside it, not grazing it)
    circles = layered.Obstacles.of(
        [(lay.pos[n], lay.radius.get(n, DOT) - layered.CLEAR) for n in nodes], [], nodes
    )
    around = layered.Obstacles.of(
        [(lay.pos[n], lay.radius.get(n, DOT)) for n in nodes],
        list(texts.values()),
        nodes,
        [key for _, key in texts],
    )
    # a drawing whose weights are written passes no text either (a curve of a fan of
    # synapses between the same two neurons may graze a sibling's weight, not another's);
    # a dense one (its weights not written, dozens of synapses between neighbours) may
    # graze a name, never pass through a circle
    strict = d.key.labelled
    weights = {k: box for (kind, k), box in lay.boxes(m).items() if kind == "label"}
    for arc in lay.arcs:
        ends = {arc.source, arc.target}
        assert layered.hits(arc.points(), around if strict else circles, ends) == 0, (name, arc)
        if not strict:
            continue
        others = [
            box for k, box in weights.items() if {lay.arcs[k].source, lay.arcs[k].target} != ends
        ]
        assert layered.hits(arc.points(), layered.Obstacles.of([], others), ends) == 0, (name, arc)
    for n in lay.radius:
        ends = [np.array(a.path[-1]) for a in lay.arcs if a.target == n]
        gaps = [np.hypot(*(p - q)) for i, p in enumerate(ends) for q in ends[i + 1 :]]
        assert min(gaps, default=1.0) >= 0.9 * layered.PORT_GAP or not strict, (name, n)


@pytest.mark.parametrize("name", NAMES)
def test_a_neuron_without_self_dynamics_shows_no_zero(figures, circuits, name):
    ax = figures[name].axes[0]
    lay = drawn(ax).layout
    centres = {lay.pos[n.name] for n in circuits[name][0].neurons if not n.self_terms}
    for t in ax.texts:
        if tuple(t.get_position()) in centres:
            assert t.get_text().strip() not in ("0", "$0$"), name


def test_a_long_chain_is_cut_into_bands_of_the_page(figures):
    for name in ("observable6", "general6"):
        lay = drawn(figures[name].axes[0]).layout
        assert len(set(lay.band.values())) >= 2 and lay.width <= style.TEXT_WIDTH
        assert figures[name].get_size_inches()[0] <= style.TEXT_WIDTH


def test_every_placed_neuron_is_tagged_with_its_vertex(figures, circuits):
    for name in ("general", "controllable", "observable", "observable6"):
        texts = [t.get_text() for t in figures[name].axes[0].texts]
        tags = [t for t in texts if t.startswith("v") and t[1:].isdigit()]
        c = circuits[name][0]
        assert sorted(tags) == sorted(f"v{n.vertex}" for n in c.neurons), name


def _colours(fig) -> dict[str, set[str]]:
    """The colours of the synapse arrows by their ends, ``"a->b"``."""
    out: dict[str, set[str]] = {}
    for p in fig.axes[0].patches + fig.axes[0].artists:
        gid = p.get_gid() or ""
        if gid.startswith("synapse:"):
            out.setdefault(gid[8:], set()).add(to_hex(p.get_edgecolor()))
    return out


def test_signs_are_coloured_where_the_values_decide_them(figures, circuits):
    colours = _colours(figures["controllable"])
    exc, inh, sym = (to_hex(c) for c in (style.EXCITATORY, style.INHIBITORY, style.SYMBOLIC))
    assert colours["G1.x1->G2.y"] == {inh}  # K_0 / (C_1 C_3) < 0 at the gains and C = 1
    assert colours["G2.x2->G2.y"] == {sym}  # w_1, w_2 change sign with epsilon
    assert colours["G1.x1->G2.x2"] == {exc}  # 1
    texts = " ".join(t.get_text() for t in figures["controllable"].axes[0].texts)
    assert "colours: the signs at the given $K$" in texts and "[−0.9, 0.9]" in texts
    unsigned = _colours(draw_circuit(circuits["controllable"][0]))
    assert unsigned["G1.x1->G2.y"] == {sym}  # without values the sign depends on K and C


def test_the_key_says_what_dashes_mean(figures):
    one = " ".join(t.get_text() for t in figures["controllable"].axes[0].texts)
    assert "delayed one step" in one and "z^{-k}" not in one
    ifp = [t.get_text() for t in figures["ifp"].axes[0].texts]
    assert r"$K_{0}$" in ifp and r"$z^{-2}$" in ifp  # weight 1, two steps, to the output
    assert any("or $k$ where $z^{-k}$ is written" in t for t in ifp)


def test_title_is_drawn_only_when_given(circuits):
    c = circuits["ifp"][0]
    plain = [t.get_text() for t in draw_circuit(c).axes[0].texts]
    titled = [t.get_text() for t in draw_circuit(c, title="The IFP controller").axes[0].texts]
    assert "The IFP controller" in titled and set(titled) - set(plain) == {"The IFP controller"}


def test_the_paper_circuits_write_every_weight(figures):
    for name in ("ifp", "general", "controllable", "observable", "observable6", "controllable6"):
        assert drawn(figures[name].axes[0]).key.labelled, name


def test_a_dense_circuit_says_its_weights_are_not_written(figures):
    texts = " ".join(t.get_text() for t in figures["general6"].axes[0].texts)
    assert drawn(figures["general6"].axes[0]).key.labelled or "not written" in texts
