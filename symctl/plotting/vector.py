"""Vector files of a figure, PDF and SVG: no date and a fixed salt, so the same figure writes
the same bytes. Each font is cut once per process to the glyphs of Latin, Greek,
punctuation, arrows and operators, and each figure's subset cut from that (8 ms, instead
of matplotlib reading the whole font for each figure: 0.1 s).
"""

from __future__ import annotations

import contextlib
import functools
import io
import os
from pathlib import Path

from symctl.errors import ParameterError

__all__ = ["VECTOR_FORMATS", "write_vector"]

VECTOR_FORMATS = ("pdf", "svg")  # what write_vector writes (by the file's suffix)

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
    """Save ``fig`` as a vector PDF (TrueType: text stays text) or SVG (glyphs as paths) by the
    suffix of ``path``, without a date.

    Raises
    ------
    ParameterError
        ``path`` ends in neither ``.pdf`` nor ``.svg``.
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
_UNREAD = ["GSUB", "GPOS", "GDEF", "kern", "MATH", "FFTM"]  # a PDF places text glyph by glyph


def _cut(source, gids, face: int = 0):
    """``(font, glyph index map)``: the font ``source`` (path or file) cut to ``gids(font)``."""
    from fontTools import subset

    options = subset.Options(glyph_names=True, recommended_glyphs=True)  # as matplotlib
    options.drop_tables += _UNREAD
    options.font_number = face
    font = subset.load_font(source, options)
    subsetter = subset.Subsetter(options=options)
    subsetter.populate(gids=gids(font))
    subsetter.subset(font)
    return font, subsetter.glyph_index_map


@functools.lru_cache(maxsize=16)
def _base_font(path: str, face: int) -> tuple[bytes, dict[int, int]]:
    """The font ``path`` cut down to :data:`_BASE_CODES`, and its glyph index map."""

    def base(font):
        cmap = font.getBestCmap()
        return {font.getGlyphID(cmap[c]) for c in _BASE_CODES if c in cmap}

    font, index = _cut(path, base, face)
    data = io.BytesIO()
    try:
        font.save(data, reorderTables=False)
    finally:
        font.close()  # the font file read from the path
    return data.getvalue(), dict(index)


@contextlib.contextmanager
def _fast_subsets():
    """Matplotlib's PDF font subsets (``_backend_pdf_ps.get_glyphs_subset`` of 3.11) cut from
    :func:`_base_font` while the block runs; with another matplotlib, nothing is replaced."""
    from matplotlib.backends import _backend_pdf_ps as pdf_ps

    own = getattr(pdf_ps, "get_glyphs_subset", None)
    results = getattr(pdf_ps, "SubsetResults", None)
    if own is None or results is None:  # pragma: no cover - another matplotlib
        yield
        return

    def get_glyphs_subset(fontfile, glyphs):
        glyphs = set(glyphs)
        try:
            data, first = _base_font(os.fspath(fontfile), getattr(fontfile, "face_index", 0))
        except Exception:  # a font fontTools cannot cut down (matplotlib's subset says why)
            return own(fontfile, glyphs)
        if not glyphs <= first.keys():  # a glyph beyond the base set
            return own(fontfile, glyphs)
        # no new timestamp: the same bytes
        font, second = _cut(io.BytesIO(data), lambda _: {first[g] for g in glyphs})
        return results(font, {g: second[first[g]] for g in glyphs})._as_cm()

    pdf_ps.get_glyphs_subset = get_glyphs_subset
    try:
        yield
    finally:
        pdf_ps.get_glyphs_subset = own
