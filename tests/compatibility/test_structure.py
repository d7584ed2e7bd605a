"""Structures: realizations, series, the IFP controller, same structure, drawings, errors."""

from __future__ import annotations

import matplotlib
import pytest
import sympy as sp

from symctl import (
    DimensionError,
    ParameterError,
    SymctlTypeError,
    controllable_canonical,
    controller_tf,
    factor,
    general_realization,
    observable_canonical,
    z,
)
from symctl.compatibility.structure import Block, Structure, ifp_structure, same_structure
from symctl.realization.realization import first_order_realization
from symctl.symbols import gain_symbols

matplotlib.use("Agg")

F = factor(controller_tf(2))
G2 = F.G2
G1 = first_order_realization(F.sensor_eps[0], F.sensor_C[0])
G3 = first_order_realization(F.actuator_eps[0], F.actuator_C[0])


def test_ifp_structure_is_the_papers_equations():
    K0, K1, K2 = gain_symbols(2)
    S = ifp_structure(2)
    t = sp.Symbol("t", integer=True)
    eqs = {str(e.lhs): e.rhs for e in S.equations()}
    mu, gamma, x, u = (sp.Function(n) for n in ("mu", "gamma", "x", "u"))
    assert eqs["gamma(t)"] == mu(t - 1)
    assert eqs["u(t)"] == gamma(t - 1)
    assert sp.expand(eqs["mu(t)"] - (K0 * x(t) + K1 * gamma(t) + K2 * u(t))) == 0
    assert (S.count("gain"), S.count("sum"), S.count("delay")) == (3, 1, 2)


@pytest.mark.parametrize("T", [1, 2, 3, 5])
def test_ifp_structure_has_T_delays_and_T_plus_1_gains_for_any_T(T):
    S = ifp_structure(T)
    assert S.count("delay") == T
    assert S.count("gain") == T + 1
    assert S.delay_distances("mu")["u"] == T


@pytest.mark.parametrize("T", [0, -1, 1.5, True])
def test_ifp_structure_refuses_bad_T(T):
    with pytest.raises(ParameterError, match="T"):
        ifp_structure(T)


def test_branch_delays_put_one_delay_on_every_term_of_a_section():
    S = Structure.from_realization(G1)
    assert S.count("delay") == 2 and S.count("sum") == 1
    assert S.inputs == ("u",) and S.outputs == ("x1",)  # y = x: no block
    state = Structure.from_realization(G1, delays="state")
    assert state.count("delay") == 1
    assert not same_structure(S, state)


def test_zero_entries_make_no_block_and_unit_gains_are_wires():
    R = controllable_canonical(G2)  # F = [[0, 1], [K2, K1]], H = [0, 1]
    S = Structure.from_realization(R)
    assert "F[1,1]" not in S.blocks and "H[1]" not in S.blocks
    assert S.blocks["x1"] == Block("delay", ("x2",))  # x1(t) = x2(t - 1)
    assert "F[1,2]" not in S.blocks  # a unit gain is a plain wire


def test_papers_remark_swapping_observable_states_keeps_the_structure():
    R = observable_canonical(G2)
    swapped = R.similar([[0, 1], [1, 0]])
    assert [e != 0 for e in R.F] != [e != 0 for e in swapped.F]
    assert same_structure(Structure.from_realization(R), Structure.from_realization(swapped))


def test_canonical_and_general_realizations_have_different_structures():
    ccr = Structure.from_realization(controllable_canonical(G2))
    ocr = Structure.from_realization(observable_canonical(G2))
    gen = Structure.from_realization(general_realization(G2, [[2, 1], [1, 1]]))
    assert not same_structure(ccr, ocr)
    assert not same_structure(ccr, gen) and not same_structure(ocr, gen)


def test_gain_values_do_not_change_the_structure():
    a = Structure.from_realization(controllable_canonical((3 * z + 2) / (z**2 - z / 3 - 2)))
    b = Structure.from_realization(controllable_canonical((5 * z + 7) / (z**2 + 2 * z - 4)))
    assert same_structure(a, b)


def test_series_connects_outputs_to_inputs_and_labels_parts():
    S = Structure.series(G1, controllable_canonical(G2), G3)
    assert S.inputs == ("G1.u",) and S.outputs == ("G3.x1",)
    assert {b.part for b in S.blocks.values()} == {"G1", "G2", "G3"}
    assert "G2.u" not in S.blocks  # G2's input is G1's output
    assert S.blocks["G2.N"].inputs == ("G1.x1",)
    assert S.delay_distances("G1.u")["G3.x1"] == 2
    nested = Structure.series(Structure.series(G1, G3), G3, names=["A", "B"])
    assert nested.outputs == ("B.x1",)


def test_series_refuses_bad_parts():
    with pytest.raises(ParameterError, match="parts"):
        Structure.series()
    with pytest.raises(SymctlTypeError, match="parts"):
        Structure.series(G1, "G2")
    with pytest.raises(ParameterError, match="names"):
        Structure.series(G1, G3, names=["A", "A"])
    two = Structure({"a": ("input",), "b": ("input",), "s": ("sum", ("a", "b"))}, ["a", "b"], "s")
    with pytest.raises(DimensionError, match="parts"):
        Structure.series(G1, two)


def test_mimo_realization_has_one_signal_per_input_and_output():
    from symctl import Realization

    R = Realization([[0, 1], [2, 3]], [[1, 0], [0, 2]], [[1, 0], [1, 1]], [[0, 0], [0, 0]])
    S = Structure.from_realization(R)
    assert S.inputs == ("u1", "u2") and S.outputs == ("x1", "y2")
    with pytest.raises(DimensionError):
        _ = S.input


@pytest.mark.parametrize(
    ("blocks", "inputs", "outputs", "match"),
    [
        ({"u": ("input",), "g": ("gain", ("u", "u"), 2)}, "u", "g", "gain"),
        ({"u": ("input",), "g": ("magic", ("u",))}, "u", "g", "kind"),
        ({"u": ("input",), "g": ("gain", ("v",), 2)}, "u", "g", "not a signal"),
        ({"u": ("input",), "s": ("sum", ("u", "t")), "t": ("gain", ("s",), 2)}, "u", "s", "loop"),
        ({"u": ("input",), "v": ("input",)}, "u", "v", "inputs"),
        ({"u": ("input",)}, "u", "y", "outputs"),
    ],
)
def test_structure_refuses_malformed_blocks(blocks, inputs, outputs, match):
    with pytest.raises(ParameterError, match=match):
        Structure(blocks, inputs, outputs)


def test_structure_refuses_wrong_types():
    with pytest.raises(SymctlTypeError, match="blocks"):
        Structure([("u", "input")], "u", "u")
    with pytest.raises(SymctlTypeError, match="R"):
        Structure.from_realization(G2)
    with pytest.raises(ParameterError, match="delays"):
        Structure.from_realization(G1, delays="middle")
    with pytest.raises(SymctlTypeError, match="a"):
        same_structure(G1, ifp_structure())


def test_delay_loops_are_allowed_but_algebraic_loops_are_not():
    ok = Structure({"u": ("input",), "s": ("sum", ("u", "d")), "d": ("delay", ("s",))}, "u", "s")
    assert ok.count("delay") == 1
    with pytest.raises(ParameterError, match="algebraic loop"):
        Structure({"u": ("input",), "s": ("sum", ("u", "g")), "g": ("gain", ("s",), 2)}, "u", "s")


def test_drawings_render_to_png_and_svg(tmp_path):
    for S in (ifp_structure(2), Structure.series(G1, controllable_canonical(G2), G3)):
        fig = S.draw()
        fig.savefig(tmp_path / "s.png", dpi=60)
        fig.savefig(tmp_path / "s.svg")
        assert (tmp_path / "s.png").stat().st_size > 1000
        assert "<svg" in (tmp_path / "s.svg").read_text()
    with pytest.raises(ParameterError, match="max_signals"):
        ifp_structure(2).draw(max_signals=3)


def test_latex_and_repr():
    S = ifp_structure(2)
    assert r"\mu" in S.latex() and S._repr_latex_().startswith("$")
    assert "7 signals" in repr(S)


def _drawn(S):
    """The figure of ``S`` rendered by Agg, its gain texts and its box extents (pixels)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = S.draw()
    FigureCanvasAgg(fig).draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    texts = [t for t in ax.texts if (t.get_gid() or "").startswith("gain:")]
    boxes = {
        p.get_gid(): p.get_window_extent(renderer)
        for p in ax.patches
        if (p.get_gid() or "").startswith(("gain:", "sum:"))
    }
    return fig, texts, boxes, renderer


@pytest.mark.parametrize(
    "S",
    [
        *(ifp_structure(T) for T in (2, 3, 4)),
        Structure.series(G1, controllable_canonical(G2), G3),
        Structure.series(G1, observable_canonical(G2), G3),
        Structure.series(G1, general_realization(G2, [[2, 1], [1, 1]]), G3),
        Structure.from_realization(general_realization(G2, [[2, 1], [1, 1]]), delays="state"),
    ],
    ids=["ifp2", "ifp3", "ifp4", "ccr", "ocr", "general", "general-state"],
)
def test_drawing_shows_each_gain_value_once_in_its_own_box_and_no_boxes_overlap(S):
    import itertools

    from matplotlib.figure import Figure

    from symctl.plotting.circuit_labels import visible_length, weight_tex
    from symctl.plotting.structure_labels import LONG_GAIN, structure_text

    fig, texts, boxes, renderer = _drawn(S)
    assert isinstance(fig, Figure)
    gains = {n: b.gain for n, b in S.blocks.items() if b.kind == "gain"}
    assert sorted(t.get_gid().removeprefix("gain:") for t in texts) == sorted(gains)
    key = dict(structure_text(S).key)
    for text in texts:
        name = text.get_gid().removeprefix("gain:")
        value = weight_tex(gains[name])
        if visible_length(value) <= LONG_GAIN:  # short values are always shown
            assert text.get_text() == f"${value}$"
        else:  # a long one by a short name, its value in the key
            shown = text.get_text().strip("$")
            assert any(shown in names.split(" = ") and v == value for names, v in key.items())
        inside = text.get_window_extent(renderer).expanded(1, 1).padded(-1)
        box = boxes[text.get_gid()]
        assert box.x0 <= inside.x0 and inside.x1 <= box.x1, name
        assert box.y0 <= inside.y0 and inside.y1 <= box.y1, name
    assert len([b for b in boxes if b.startswith("gain:")]) == len(gains)
    for (a, box_a), (b, box_b) in itertools.combinations(boxes.items(), 2):
        assert not box_a.overlaps(box_b), (a, b)


def test_drawing_puts_the_input_left_of_the_output_and_scales_the_figure():
    small, large = ifp_structure(2).draw(), ifp_structure(6).draw()
    assert large.get_figwidth() > small.get_figwidth()
    assert large.get_figheight() > small.get_figheight()
    ax = small.axes[0]
    dots = {p.get_gid(): p.center for p in ax.patches if (p.get_gid() or "").startswith("signal:")}
    assert dots["signal:x"][0] < dots["signal:u"][0]
    assert any(t.get_text().startswith("Controller structure") for t in ax.texts)


def test_drawing_is_deterministic():
    def layout(fig):
        return [(p.get_gid(), tuple(p.get_window_extent().bounds)) for p in fig.axes[0].patches]

    S = Structure.series(G1, observable_canonical(G2), G3)
    assert layout(S.draw()) == layout(S.draw())


def test_structure_module_loads_no_drawing_code():
    """Drawing is a delegation: importing the structure module loads neither plotting nor matplotlib."""
    import subprocess
    import sys

    code = (
        "import sys, symctl.compatibility.structure; "
        "print(sorted(m for m in sys.modules if m.startswith(('matplotlib', 'symctl.plotting'))))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_structures_are_values():
    assert ifp_structure(2) == ifp_structure(2) and hash(ifp_structure(2)) == hash(ifp_structure(2))
    assert ifp_structure(2) != ifp_structure(3)
    a = Structure({"u": ("input",), "g": ("gain", ("u",), 2)}, "u", "g")
    b = Structure({"g": Block("gain", ["u"], sp.Integer(2)), "u": Block("input")}, ["u"], ["g"])
    assert a == b and hash(a) == hash(b)  # normalised: order, lists, gain values
    assert a != Structure({"u": ("input",), "g": ("gain", ("u",), 3)}, "u", "g")
    assert len({ifp_structure(2), ifp_structure(2), a, b}) == 2
    with pytest.raises(TypeError):
        a.blocks["h"] = Block("gain", ("u",), 1)
    with pytest.raises(AttributeError):
        a.inputs = ("v",)


def test_the_structure_graph_is_frozen():
    import networkx as nx

    g = ifp_structure(2).graph
    with pytest.raises(nx.NetworkXError):
        g.add_edge("x", "u")
    with pytest.raises(TypeError):
        ifp_structure(2).signal_graph.index["x"] = 5


def test_structure_size_is_bounded(monkeypatch):
    import symctl.compatibility.structure as structure_module

    monkeypatch.setattr(structure_module, "MAX_SIGNALS", 3)
    blocks = {"u": Block("input"), **{f"g{k}": Block("gain", ("u",), 1) for k in range(3)}}
    with pytest.raises(ParameterError, match="blocks: a structure has at most 3 signals, got 4"):
        Structure(blocks, ["u"], ["g0"])
