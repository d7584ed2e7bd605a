"""Circuit drawings: long weights as short labels with a key, short ones written out."""

from __future__ import annotations

import subprocess
import sys

import pytest
import sympy as sp
from matplotlib.backends.backend_agg import FigureCanvasAgg

from symctl import Circuit, Structure, controllable_canonical, ifp_structure
from symctl.plotting.circuit import draw_circuit
from symctl.plotting.circuit_labels import (
    LONG_SELF,
    LONG_WEIGHT,
    circuit_text,
    display_text,
    visible_length,
    weight_tex,
)
from symctl.realization.realization import first_order_realization

a, b = sp.symbols("a b")
LONG = sum(sp.symbols("k1:6")) / (a + b)  # \frac{k_{1} + ... + k_{5}}{a + b}: 16 shown
LONGER = sum(sp.symbols("k1:10")) / (a + b)  # 29 shown: too long for a circle too


def chain(*sections) -> Circuit:
    """The circuit of first-order sections ``(epsilon, C)`` in series."""
    return Circuit.from_structure(
        Structure.series(*(first_order_realization(e, C) for e, C in sections))
    )


def product(count: int) -> sp.Expr:
    """``x_1 x_2 ... x_count``: its LaTeX shows exactly ``2 * count`` characters."""
    return sp.Mul(*sp.symbols(f"x_1:{count + 1}"))


def key_gids(fig) -> list[str]:
    return [p.get_gid() for p in fig.axes[0].patches if (p.get_gid() or "").startswith("key:")]


def test_a_long_weight_gets_a_key_entry_and_a_short_one_does_not():
    c = chain((a, LONG), (b, sp.Symbol("C_1")))
    text = circuit_text(c)
    (long_syn,) = [s for s in text.weights if s.weight == LONG]
    (short_syn,) = [s for s in text.weights if s.weight == sp.Symbol("C_1")]
    assert text.weights[long_syn] == "w_{1}"
    assert text.weights[short_syn] == "C_{1}"
    assert text.key_lines() == [r"w_{1} = \frac{k_{1} + k_{2} + k_{3} + k_{4} + k_{5}}{a + b}"]
    assert key_gids(draw_circuit(c)) == ["key:w1"]
    assert key_gids(draw_circuit(chain((a, sp.Symbol("C_1"))))) == []


def test_the_threshold_is_long_weight_visible_characters():
    assert visible_length(sp.latex(product(LONG_WEIGHT // 2))) == LONG_WEIGHT
    at = circuit_text(chain((a, product(LONG_WEIGHT // 2))))
    over = circuit_text(chain((a, product(LONG_WEIGHT // 2 + 1))))
    assert at.key == () and len(over.key) == 1
    # a self-dynamics may be twice as long: it sits in its own circle, which grows
    assert LONG_SELF == 2 * LONG_WEIGHT
    two_lags = circuit_text(Circuit.from_structure(ifp_structure(2)))
    assert two_lags.key == () and two_lags.bodies["mu"] == r"K_{1}\,z^{-1} + K_{2}\,z^{-2}"
    assert circuit_text(chain((LONG, 1))).key == ()
    assert [label for label, _ in circuit_text(chain((LONGER, 1))).key] == [r"\mathrm{self}_{1}"]


def test_equal_long_values_share_one_label_and_one_key_entry():
    c = chain((LONGER, LONG), (LONGER, LONG))  # long self-dynamics and weights, twice each
    text = circuit_text(c)
    assert sorted(set(text.bodies.values())) == [r"\mathrm{self}_{1}"]
    assert sorted(set(text.weights.values())) == ["w_{1}"]
    assert [label for label, _ in text.key] == [r"\mathrm{self}_{1}", "w_{1}"]
    assert key_gids(draw_circuit(c)) == ["key:self1", "key:w1"]


def test_labels_are_numbered_from_one_in_the_order_of_the_neurons():
    longs = [LONG * k for k in (2, 3, 5)]
    c = chain(*((a, w) for w in longs))
    text = circuit_text(c)
    by_target = {s.target: tex for s, tex in text.weights.items()}
    assert [by_target[n.name] for n in c.neurons] == ["w_{1}", "w_{2}", "w_{3}"]
    assert [label for label, _ in text.key] == ["w_{1}", "w_{2}", "w_{3}"]


def test_numbers_are_set_as_text_with_a_minus_sign_and_symbols_as_mathtext():
    assert display_text("-0.75") == "\N{MINUS SIGN}0.75"
    assert display_text("1e+03") == "1e+03"
    assert display_text("K_{1}") == "$K_{1}$"
    fig = draw_circuit(chain((sp.Rational(1, 2), sp.Rational(-3, 4))))
    texts = {t.get_text() for t in fig.axes[0].texts}
    assert "\N{MINUS SIGN}0.75" in texts and r"$0.5\,z^{-1}$" in texts


def test_the_key_is_inside_the_figure_under_the_drawing():
    c = chain((a, LONG), (b, LONG * 2), (a, LONG * 3), (b, LONG * 5))
    fig = draw_circuit(c)
    renderer = FigureCanvasAgg(fig).get_renderer()
    page = fig.bbox
    circles = [p for p in fig.axes[0].patches if (p.get_gid() or "").startswith("neuron:")]
    lowest = min(p.get_window_extent(renderer).y0 for p in circles)
    keys = [p for p in fig.axes[0].patches if (p.get_gid() or "").startswith("key:")]
    assert len(keys) == 4
    for p in keys:
        box = p.get_window_extent(renderer)
        assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0, p.get_gid()
        assert box.y1 < lowest, p.get_gid()


@pytest.mark.slow
def test_a_mimo_controllable_form_keys_its_four_equal_self_dynamics_once(mimo_factorization):
    f = mimo_factorization
    c = Circuit.from_structure(Structure.from_factorization(f, controllable_canonical(f.G2)))
    text = circuit_text(c)
    selfs = [n.name for n in c.neurons if text.bodies[n.name] == r"\mathrm{self}_{1}"]
    assert len(selfs) == 4  # the four G2 neurons that hold the denominator's lags
    labels = [label for label, _ in text.key]
    assert labels[0] == r"\mathrm{self}_{1}" and r"\mathrm{self}_{2}" not in labels
    assert labels[1:] == [f"w_{{{k}}}" for k in range(1, len(labels))]
    # every long weight on a synapse is in the key, every short one is written out
    for s, tex in text.weights.items():
        shown = tex.split(r"\,z^")[0]
        assert (shown in dict(text.key)) == (visible_length(weight_tex(s.weight)) > LONG_WEIGHT)
    # forty long weights are too many to list under a printed drawing: none is written,
    # the self-dynamics' key is (broken over lines to fit the page)
    fig = draw_circuit(c)
    assert set(key_gids(fig)) == {"key:self1"}
    assert any("weights not written" in t.get_text() for t in fig.axes[0].texts)


@pytest.mark.slow
def test_the_labels_are_chosen_without_matplotlib():
    code = (
        "import sys\n"
        "from symctl import Circuit, ifp_structure\n"
        "from symctl.plotting.circuit_labels import circuit_text\n"
        "circuit_text(Circuit.from_structure(ifp_structure(3)))\n"
        "assert 'matplotlib' not in sys.modules, 'matplotlib was imported'\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
