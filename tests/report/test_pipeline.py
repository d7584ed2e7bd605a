"""`symctl paper` end to end: results.json, derivation.tex/.pdf, report.md and the figures."""

from __future__ import annotations

import json
import re

import pytest

from symctl import cli
from symctl.cli import main
from symctl.derivation import pipeline
from symctl.report.figures import DEFAULT_FORMATS
from symctl.report.spec import CIRCUITS

FIGURES = (
    ["open_loop", "closed_loop", "delay_graph", "g1g3_structures", "nonlinear", "atlas_overview"]
    + [
        f"{kind}_{c}"
        for c in CIRCUITS
        if c != "pathways"  # the paper's chain of unit steps needs no circuit along pathways
        for kind in ("structure", "circuit", "firing")
    ]
    + ["simplified_A16", "simplified_A17"]
)  # the paper's simplified circuits (the atlas)


@pytest.fixture(scope="module")
def paper(tmp_path_factory):
    """One full run of ``symctl paper`` (figures and PDF): its folder and its console output."""
    out = tmp_path_factory.mktemp("paper")
    with (
        pytest.MonkeyPatch.context() as mp,  # computed here, as a fresh process does: its steps show
        cli._console.capture() as captured,  # leaves the console's stream as it was
    ):
        mp.setattr(
            pipeline, "_cached", lambda spec, progress: pipeline._derive(spec, progress.step)
        )
        assert main(["paper", "--out", str(out)]) == 0
    return out, captured.get()


def test_results_json_has_a_circuits_entry_per_circuit(paper):
    out, _ = paper
    data = json.loads((out / "results.json").read_text())
    circuits = data["circuits"]
    assert list(circuits) == ["ifp", "general", "controllable", "observable"]
    counts = {k: (c["neurons"]["count"], c["neurons"]["G2"]) for k, c in circuits.items()}
    assert counts == {
        "ifp": (1, None),
        "general": (5, 3),
        "controllable": (4, 2),
        "observable": (5, 3),
    }
    assert {k: c["compatible"] for k, c in circuits.items()} == {
        "ifp": False,
        "general": True,
        "controllable": True,
        "observable": True,
    }
    for name, c in circuits.items():
        assert 0 <= c["max_closed_loop_deviation"] < 1e-9, name
        assert len(c["realizations"]) == (1 if name == "ifp" else 4)
        if c["compatible"]:
            assert c["compatibility"]["E_tilde"] == [[0, 1, 2], [None, 0, 1], [None, None, 0]]
        else:
            assert (
                c["compatibility"]["E_tilde"] is None
                and "K0 -> mu" in (c["compatibility"]["reason"])
            )
    first = circuits["general"]["realizations"][0]
    assert set(first) == {"epsilon_1", "epsilon_3", "C_1", "C_3", "P"}
    assert -0.9 < first["epsilon_1"] < 0.9 and len(first["P"]) == 2
    # the numeric realization of the factorization is the first simulated one
    values = data["factorization"]["realizations"]["general"]["values"]
    assert values["epsilon_1"] == first["epsilon_1"]
    assert data["factorization"]["realizations"]["general"]["P"] == first["P"]
    assert data["delay_graph"]["E"] == [[0, 1, 2], [None, 0, 1], [None, None, 0]]
    sim = data["simulation"]
    assert len(sim["t"]) == len(sim["closed_loop"]["delta_f"]) == 50
    assert max(sim["closed_loop"]["disturbance"]) == 1.0


def test_every_figure_is_written_as_pdf_and_png_and_svg_only_on_request(paper):
    out, _ = paper
    for name in FIGURES:
        for ext in DEFAULT_FORMATS:
            path = out / f"{name}.{ext}"
            assert path.stat().st_size > 5000, path
        assert (out / f"{name}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert (out / f"{name}.pdf").read_bytes()[:5] == b"%PDF-"
    assert list(out.glob("*.svg")) == []


def test_derivation_tex_has_the_paper_order_and_numbers(paper):
    out, _ = paper
    tex = (out / "derivation.tex").read_text()
    assert tex.startswith(r"\documentclass") and tex.rstrip().endswith(r"\end{document}")
    assert not re.search(r"[\x00-\x08\x0b-\x1f]", tex)  # no control characters (e.g. "\f")
    labels = re.findall(r"\\label\{(eq:[^}]+)\}", tex)
    order = [
        "eq:muscle",
        "eq:linear",
        "eq:discrete",
        "eq:augmented",
        "eq:gains",
        "eq:G",
        "eq:factors",
        "eq:G2rewritten",
        "eq:controllable",
        "eq:observable",
        "eq:general",
        "eq:E",
        "eq:Etilde-general",
        "eq:circuit-ifp",
    ]
    assert [lab for lab in labels if lab in order] == order
    assert "43.8635" in tex and "0.606531" in tex and "4.64165" in tex
    assert r"K_{0}" in tex and r"\epsilon_{1}" in tex
    assert "Not compatible" in tex and tex.count(r"\fitgraphic{") == len(FIGURES)


def test_derivation_pdf_is_compiled(paper, pdflatex):
    out, _ = paper
    pdf = out / "derivation.pdf"
    assert pdf.read_bytes()[:5] == b"%PDF-" and pdf.stat().st_size > 100_000
    assert not (out / "derivation.log").exists() and not (out / "derivation.aux").exists()


def test_report_md_shows_the_figures_and_numbers_every_equation(paper):
    out, _ = paper
    md = (out / "report.md").read_text()
    shown = re.findall(r"!\[[^\]]*\]\(([^)]+)\.png\)", md)
    assert shown == [n for n in _reading_order(md) if n in FIGURES] and set(shown) == set(FIGURES)
    tags = [int(t) for t in re.findall(r"\\tag\{(\d+)\}", md)]
    assert tags == list(range(1, len(tags) + 1)) and len(tags) >= 20


def _reading_order(md: str) -> list[str]:
    return re.findall(r"\]\(([^)]+)\.png\)", md)


def test_console_shows_progress_and_summary_tables(paper):
    _, text = paper
    for step in ("plant", "LQR", "simulation", "figures", "documents"):
        assert re.search(rf"done\s+{step}\s+[\d.]+ s", text), step
    assert "summary" in text and "circuits" in text and "max deviation" in text
    assert "results.json" in text and "derivation.tex" in text and f"{len(FIGURES)} figures" in text


def test_every_file_of_a_full_run_is_one_an_earlier_run_may_leave(paper):
    # a second `make paper` into out/paper replaces the first run's folder: every name the
    # full run wrote (figures of the atlas section included) must be known as its own
    from symctl.report.output import _foreign

    out, _ = paper
    assert _foreign(out) == []
