"""Drawings of multi-step wires: an axon of k steps is labelled z^-k."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

from symctl import Block, Structure


def test_an_axon_of_k_steps_is_labelled_and_a_unit_delay_is_not():
    S = Structure(
        {
            "u": ("input",),
            "d": Block("delay", ("u",), steps=3),
            "e": Block("delay", ("d",)),
            "y": ("sum", ("e", "u")),
        },
        "u",
        "y",
    )
    fig = S.draw()
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert "$z^{-3}$" in texts and "$z^{-1}$" not in texts
    assert any("an axon of k steps" in t for t in texts)
