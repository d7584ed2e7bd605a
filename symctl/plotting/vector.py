"""Vector files of a figure, PDF and SVG: text kept as text (PDF), the same bytes every time.

Matplotlib writes a PDF with its creation date and an SVG with ids salted by a random
number, so the same figure written twice differs. :func:`write_vector` writes both
with no date and a fixed salt. The PDF embeds its fonts as TrueType (text stays
searchable and sharp at any zoom; ``pdflatex`` includes it as it is); the SVG draws
its glyphs as paths, so it looks the same in a browser that lacks the font.

Embedding a font means cutting it down to the glyphs the figure uses. Matplotlib reads
the whole font file for each figure and each font (DejaVu Sans: 6,000 glyphs and
their layout tables, about 0.1 s, two thirds of the time of a PDF);
:func:`write_vector` cuts each font once per process to the glyphs of Latin, Greek,
punctuation, arrows and mathematical operators, without the layout tables a PDF viewer
never reads (GSUB, GPOS, GDEF, kern, MATH), and then cuts each figure's subset from
that (8 ms). The glyphs embedded are the same outlines with the same hinting; a figure
needing a glyph outside that set gets matplotlib's own subset.

>>> import tempfile
>>> from pathlib import Path
>>> from matplotlib.figure import Figure
>>> from symctl.plotting.vector import write_vector
>>> fig = Figure(figsize=(2, 1))
>>> with tempfile.TemporaryDirectory() as out:
...     a = write_vector(fig, Path(out) / "a.pdf").read_bytes()
...     b = write_vector(fig, Path(out) / "b.pdf").read_bytes()
>>> a == b, a[:5]
(True, b'%PDF-')
"""

from __future__ import annotations

import contextlib
import functools
import io
import os
from pathlib import Path

from symctl.errors import ParameterError

__all__ = ["VECTOR_FORMATS", "write_vector"]

VECTOR_FORMATS = ("pdf", "svg")
"""The vector formats :func:`write_vector` writes (from the file's suffix)."""

_RC = {
    "svg.hashsalt": "symctl",  # the SVG's ids from a fixed salt, not a random one
    "svg.fonttype": "path",  # glyphs as paths: the same look without the font installed
    "pdf.fonttype": 42,  # TrueType: the text stays text
    "pdf.compression": 6,
}
_METADATA = {
    "pdf": {"Creator": "symctl (matplotlib)", "CreationDate": None, "ModDate": None},
    "svg": {"Date": None},
}


def write_vector(fig, path: Path | str) -> Path:
    """Save ``fig`` as a vector PDF or SVG (by the suffix of ``path``), without a date.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path : path
        The file to write, ending in ``.pdf`` or ``.svg``.

    Returns
    -------
    Path

    Raises
    ------
    ParameterError
        ``path`` has another suffix.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from matplotlib.figure import Figure
    >>> from symctl.plotting.vector import write_vector
    >>> with tempfile.TemporaryDirectory() as out:
    ...     b"<dc:date>" in write_vector(Figure(figsize=(2, 1)), Path(out) / "a.svg").read_bytes()
    False
    """
    import matplotlib as mpl

    path = Path(path)
    fmt = path.suffix.lstrip(".").lower()
    if fmt not in VECTOR_FORMATS:
        raise ParameterError(f"path: {str(path)!r} does not end in .pdf or .svg")
    with mpl.rc_context(_RC), _fast_subsets() if fmt == "pdf" else contextlib.nullcontext():
        fig.savefig(path, format=fmt, metadata=_METADATA[fmt])
    return path


_BASE_CODES = (
    *range(0x20, 0x7F),  # ASCII
    *range(0xA0, 0x180),  # Latin-1 and Latin Extended-A
    *range(0x300, 0x370),  # combining accents (a bar, a hat, a dot over a symbol)
    *range(0x391, 0x3CA),  # Greek
    *range(0x2010, 0x2070),  # punctuation, super- and subscripts
    *range(0x2190, 0x2300),  # arrows and mathematical operators
    *range(0xFB00, 0xFB07),  # the ligatures text layout makes (fi, fl, ...)
)
"""The characters whose glyphs each font is first cut down to (:func:`write_vector`)."""
_UNREAD = ["GSUB", "GPOS", "GDEF", "kern", "MATH", "FFTM"]
"""Tables of a font a PDF viewer never reads: text in a PDF is placed glyph by glyph."""


def _subset_options():
    from fontTools import subset

    options = subset.Options(glyph_names=True, recommended_glyphs=True)  # as matplotlib
    options.drop_tables += _UNREAD
    return options


@functools.lru_cache(maxsize=16)
def _base_font(path: str, face: int) -> tuple[bytes, dict[int, int]]:
    """The font ``path`` cut down to :data:`_BASE_CODES`, and its glyph index map."""
    from fontTools import subset

    options = _subset_options()
    options.font_number = face
    font = subset.load_font(path, options)
    cmap = font.getBestCmap()
    gids = {font.getGlyphID(cmap[c]) for c in _BASE_CODES if c in cmap}
    subsetter = subset.Subsetter(options=options)
    subsetter.populate(gids=gids)
    subsetter.subset(font)
    data = io.BytesIO()
    font.save(data, reorderTables=False)
    return data.getvalue(), dict(subsetter.glyph_index_map)


@contextlib.contextmanager
def _fast_subsets():
    """Matplotlib's PDF font subsets cut from :func:`_base_font` while the block runs.

    Replaces ``matplotlib.backends._backend_pdf_ps.get_glyphs_subset`` (matplotlib 3.11's
    signature: a font path and glyph indices, giving the subset font and the map of the
    indices); with another matplotlib, nothing is replaced.
    """
    from matplotlib.backends import _backend_pdf_ps as pdf_ps

    own = getattr(pdf_ps, "get_glyphs_subset", None)
    results = getattr(pdf_ps, "SubsetResults", None)
    if own is None or results is None:  # pragma: no cover - another matplotlib
        yield
        return

    def get_glyphs_subset(fontfile, glyphs):
        from fontTools import subset

        glyphs = set(glyphs)
        try:
            data, first = _base_font(os.fspath(fontfile), getattr(fontfile, "face_index", 0))
        except Exception:  # a font fontTools cannot cut down (matplotlib's subset says why)
            return own(fontfile, glyphs)
        if not glyphs <= first.keys():  # a glyph beyond the base set
            return own(fontfile, glyphs)
        options = _subset_options()
        font = subset.load_font(io.BytesIO(data), options)  # no new timestamp: the same bytes
        subsetter = subset.Subsetter(options=options)
        subsetter.populate(gids={first[g] for g in glyphs})
        subsetter.subset(font)
        second = subsetter.glyph_index_map
        return results(font, {g: second[first[g]] for g in glyphs})._as_cm()

    pdf_ps.get_glyphs_subset = get_glyphs_subset
    try:
        yield
    finally:
        pdf_ps.get_glyphs_subset = own
