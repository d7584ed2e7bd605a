"""A realizer added in one place reaches every table of circuits: the example of docs/extending.md.

The page's Python blocks run here as written: the first defines and registers the realizer,
the second uses it. The realizer stays registered for this module only.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from symctl import MuscleModel, augment, check_realization, controller_tf, factor, lqr_gains
from symctl.cli import main
from symctl.model.modelfile import load_model
from symctl.model.presets import muscle_text
from symctl.realization.realizers import REALIZERS, circuit_names, unregister
from symctl.report.output import _foreign

PAGE = Path(__file__).resolve().parent.parent / "docs" / "extending.md"
BUILD = 'build = ["ifp", "general", "controllable", "observable"]'


def _blocks() -> list[str]:
    return re.findall(r"```python\n(.*?)```", PAGE.read_text(), re.S)


@pytest.fixture(scope="module")
def page():
    """The namespace of the page's examples, run in order; the realizer removed afterwards."""
    assert "reversed" not in REALIZERS
    ns: dict = {}
    try:
        for block in _blocks():
            exec(compile(block, str(PAGE), "exec"), ns)
        yield ns
    finally:
        if "reversed" in REALIZERS:
            unregister("reversed")
    assert "reversed" not in REALIZERS and "reversed" not in circuit_names()


def test_the_page_example_is_about_fifteen_lines_and_is_in_the_docs_toctree():
    first = _blocks()[0].strip().splitlines()
    assert len([line for line in first if line.strip()]) <= 16
    assert "\nextending\n" in (PAGE.parent / "index.md").read_text()


def test_the_realizer_joins_the_registry_after_the_others_and_realizes_G2(page):
    assert circuit_names() == ("ifp", "general", "controllable", "observable", "reversed")
    G2 = factor(controller_tf(2)).G2
    R, C = REALIZERS["reversed"](G2).realization, REALIZERS["controllable"](G2).realization
    assert R.F == C.F[::-1, ::-1] and R.H == C.H[::-1, :] and R.M == C.M[:, ::-1]
    assert check_realization(R, G2).ok


def test_the_page_claims_hold(page):
    fp = page["circuit_firing"]("reversed", page["gains"], count=2)
    assert fp.neurons == ("G2.x1", "G2.y")
    res = page["res"]
    assert list(res.circuits) == ["ifp", "reversed"] and list(res.realizations) == ["reversed"]
    assert res.circuits["reversed"].compatibility.ok


def test_model_files_accept_it_and_build_it_by_default(page):
    from symctl.model import schema

    assert schema.CIRCUIT_KINDS[-1] == "reversed"
    assert load_model(muscle_text().replace(BUILD, 'build = ["reversed"]')).circuits == (
        "reversed",
    )
    assert load_model(muscle_text().replace(BUILD, "")).circuits[-1] == "reversed"


def test_firing_the_report_spec_dale_and_the_fits_list_it(page):
    import symctl
    from symctl.dalelaw import signs
    from symctl.fitting import fitmodel
    from symctl.fitting.fitargs import _circuit_arg
    from symctl.neural import firing
    from symctl.report import spec

    assert firing.KINDS[-1] == "reversed"
    assert spec.CIRCUITS[-2:] == ("reversed", "pathways")
    assert spec.CIRCUIT_SPECS["reversed"].title == "G3 G2 G1, reversed controllable G2"
    assert signs.NAMED[-1] == "reversed" and fitmodel.FIXED_CLASSES[-1] == "reversed"
    assert _circuit_arg("reversed") == ["reversed"]
    gains = lqr_gains(augment(MuscleModel(), 1, 1))
    assert symctl.dale(gains, circuit="reversed").circuit == "reversed"


@pytest.mark.slow  # a second derivation and four Dale decisions
def test_symctl_derive_and_dale_write_and_print_it(page, tmp_path, capsys):
    model = tmp_path / "m.toml"
    model.write_text(muscle_text().replace(BUILD, 'build = ["reversed"]'))
    out = tmp_path / "out"
    assert main(["derive", str(model), "--out", str(out), "--no-figures", "--no-pdf"]) == 0
    printed = capsys.readouterr().out
    assert "reversed: F = " in printed and "│ reversed │" in printed
    data = json.loads((out / "results.json").read_text())
    assert list(data["circuits"]) == ["reversed"]
    assert list(data["factorization"]["realizations"]) == ["reversed"]
    tex = (out / "derivation.tex").read_text()
    (out / "circuit_reversed.pdf").write_bytes(b"%PDF")
    assert "Reversed controllable form" in tex and "reversed controllable $G_2$" in tex
    assert _foreign(out) == []  # a second run may replace the folder: every file is symctl's
    assert main(["dale", "--json", "--timeout", "10"]) == 0
    circuits = [c["circuit"] for c in json.loads(capsys.readouterr().out)["circuits"]]
    assert circuits == ["general", "controllable", "observable", "reversed"]
