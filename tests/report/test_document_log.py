"""derivation.tex compiles without a line or table in the margin: pdflatex's log, read.

Each case is compiled once (two passes, for the references), with every figure
the run writes replaced by a placeholder of one square inch: the test is about
the text's boxes (the figures have layout tests of their own, and change on their
own). A figure the document shows but the run does not write stops pdflatex
("File not found"), so missing figures fail too.
"""

from __future__ import annotations

import re
import subprocess
import zlib
from pathlib import Path

import pytest
from helpers import long_sums

from symctl import derive
from symctl.report.document import to_tex
from symctl.report.story import story

CASES = (
    "derived_T2",
    "derived_T6",
    "derived_oculomotor",
    "derived_T6 tall figures",
    "examples/antagonist.toml",
    "examples/pendulum.toml",
    "examples/spinal_transcortical.toml",
    "tests/data/forearm_two_inputs.toml",
)
"""Each case's results fixture or model file (every example: ``derived_T2`` is the muscle's);
"tall figures": every placeholder nearly the text's width and
two thirds of its height, as large as the T = 6 general circuit drawn at its printed size:
such a figure placed "here" left too little room for a display that cannot break (15 lines
made the page overfull; with DISPLAY_MAX_LINES = 16 this case fails)."""
ROOT = Path(__file__).resolve().parents[2]
TALL = (480, 480)
"""The tall placeholder [pt] (the text: 500 x 681 pt; ``\\fitgraphic`` scales a figure wider
than it or taller than it less four lines)."""

_PROBLEMS = {
    "overfull box": re.compile(r"^Overfull \\[hv]box.*$", re.M),
    "float too large": re.compile(r"^.*Float too large.*$", re.M),
    "undefined reference": re.compile(
        r"^LaTeX Warning: (Reference|Citation) .* undefined.*$", re.M
    ),
    "shrunk display": re.compile(r"^symctl: shrunk.*$", re.M),
    "error": re.compile(r"^! .*$", re.M),
}


def _png() -> bytes:
    """A white 72 x 72 pixel PNG (one inch at its default resolution)."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return len(data).to_bytes(4, "big") + body + zlib.crc32(body).to_bytes(4, "big")

    header = (72).to_bytes(4, "big") * 2 + bytes([8, 0, 0, 0, 0])  # 8-bit greyscale
    pixels = zlib.compress(b"".join(b"\x00" + b"\xff" * 72 for _ in range(72)))
    return (
        b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", pixels) + chunk(b"IEND", b"")
    )


def _pdf(width: int = 72, height: int = 72) -> bytes:
    """An empty PDF page, one inch square by default [pt]."""
    box = b"[0 0 %d %d]" % (width, height)
    objects = [
        b"<< /Type /Catalog /Pages 2 0 R >>",
        b"<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
        b"<< /Type /Page /Parent 2 0 R /MediaBox " + box + b" >>",
    ]
    out, offsets = bytearray(b"%PDF-1.4\n"), []
    for k, body in enumerate(objects, 1):
        offsets.append(len(out))
        out += b"%d 0 obj\n" % k + body + b"\nendobj\n"
    xref = len(out)
    out += b"xref\n0 %d\n0000000000 65535 f \n" % (len(objects) + 1)
    out += b"".join(b"%010d 00000 n \n" % o for o in offsets)
    out += b"trailer\n<< /Size %d /Root 1 0 R >>\nstartxref\n%d\n%%%%EOF\n" % (
        len(objects) + 1,
        xref,
    )
    return bytes(out)


@pytest.fixture(scope="module")
def logs(request, tmp_path_factory):
    """The pdflatex log of each case's derivation.tex (compiled on first use)."""
    done: dict[str, str] = {}

    def log(case: str, pdflatex: str) -> str:
        if case not in done:
            fixture, _, tall = case.partition(" ")
            if fixture.endswith(".toml"):  # a model file (every example; a two-input forearm)
                res, fixture = derive(ROOT / fixture), Path(fixture).stem
            else:
                res = request.getfixturevalue(fixture)
            out = tmp_path_factory.mktemp(fixture)
            for name in res.figure_names():  # what the run writes, in the formats pdflatex reads
                (out / f"{name}.png").write_bytes(_png())
                (out / f"{name}.pdf").write_bytes(_pdf(*TALL) if tall else _pdf())
            tex = to_tex(story(res, res.figure_names()), title=res.spec.title)  # as res.write does
            (out / "derivation.tex").write_text(tex)
            for _ in range(2):
                subprocess.run(
                    [pdflatex, "-interaction=nonstopmode", "-halt-on-error", "derivation.tex"],
                    cwd=out,
                    capture_output=True,
                    timeout=300,
                )
            done[case] = (out / "derivation.log").read_text(errors="replace")
        return done[case]

    return log


@pytest.mark.parametrize("case", CASES)
def test_the_derivation_compiles_with_nothing_in_the_margin(logs, case, pdflatex):
    log = logs(case, pdflatex)
    assert "Output written on derivation.pdf" in log, case
    found = {
        what: rx.findall(log) and [m.group(0) for m in rx.finditer(log)]
        for what, rx in _PROBLEMS.items()
    }
    assert not any(found.values()), {k: v[:5] for k, v in found.items() if v}


def test_the_log_check_finds_an_overfull_line(tmp_path, pdflatex):
    # the check above cannot pass by reading nothing: a line too long is reported
    (tmp_path / "bad.tex").write_text(
        "\\documentclass{article}\\begin{document}\\ref{nowhere} "
        + "x" * 200
        + "\n\\end{document}\n"
    )
    subprocess.run(
        [pdflatex, "-interaction=nonstopmode", "bad.tex"],
        cwd=tmp_path,
        capture_output=True,
        timeout=60,
    )
    log = (tmp_path / "bad.log").read_text(errors="replace")
    assert _PROBLEMS["overfull box"].search(log) and _PROBLEMS["undefined reference"].search(log)


def test_a_table_of_sums_wider_than_the_page_compiles_inside_it(tmp_path, pdflatex):
    """The two-input forearm's coefficients of a(z) overflowed the page by 261 pt."""
    (tmp_path / "derivation.tex").write_text(to_tex([long_sums()]))
    subprocess.run(
        [pdflatex, "-interaction=nonstopmode", "-halt-on-error", "derivation.tex"],
        cwd=tmp_path,
        capture_output=True,
        timeout=300,
    )
    log = (tmp_path / "derivation.log").read_text(errors="replace")
    assert "Output written on derivation.pdf" in log
    assert not _PROBLEMS["overfull box"].findall(log)
