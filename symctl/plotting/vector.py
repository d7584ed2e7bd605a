"""Vector files of a figure, PDF and SVG: text kept as text (PDF), the same bytes every time.

Matplotlib writes a PDF with its creation date and an SVG with ids salted by a random
number, so the same figure written twice differs. :func:`write_vector` writes both
with no date and a fixed salt. The PDF embeds its fonts as TrueType (text stays
searchable and sharp at any zoom; ``pdflatex`` includes it as it is); the SVG draws
its glyphs as paths, so it looks the same in a browser that lacks the font.

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
    with mpl.rc_context(_RC):
        fig.savefig(path, format=fmt, metadata=_METADATA[fmt])
    return path
