"""PNG files, RGB when the figure is opaque: ``pdflatex`` copies an RGB PNG into the PDF as it
is but splits an RGBA one into a soft mask (4.5 of the 4.7 s of a MIMO report's PDF)."""

from __future__ import annotations

from pathlib import Path

__all__ = ["render_pdf", "write_png"]


def write_png(fig, path: Path | str, *, dpi: float, metadata: dict | None = None) -> Path:
    """Save ``fig`` as a PNG at ``dpi`` (rendered by Agg as :meth:`Figure.savefig` does), RGB when
    every pixel is opaque, with the text chunks ``metadata`` (``None`` values left out).

    >>> import tempfile
    >>> from pathlib import Path
    >>> from matplotlib.figure import Figure
    >>> from symctl.plotting.png import write_png
    >>> fig = Figure(figsize=(2, 1))
    >>> fig.patch.set_alpha(0.5)   # a translucent background keeps its alpha channel
    >>> with tempfile.TemporaryDirectory() as out:
    ...     write_png(fig, Path(out) / "a.png", dpi=50).read_bytes()[25]
    6
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    canvas, scale = fig.canvas, fig.dpi
    try:  # render at dpi as savefig does, on an Agg canvas that reports the pixel size
        fig.dpi = dpi
        rgba, size = FigureCanvasAgg(fig).print_to_buffer()
    finally:
        fig.dpi = scale
        fig.set_canvas(canvas)
    return _save(Image.frombuffer("RGBA", size, rgba, "raw", "RGBA", 0, 1), path, dpi, metadata)


def render_pdf(
    pdf: Path | str, path: Path | str, *, dpi: float, metadata: dict | None = None
) -> Path:
    """As :func:`write_png`, from the first page of the PDF file ``pdf`` rendered by PDFium
    (milliseconds, where matplotlib would draw the figure anew).

    >>> import tempfile
    >>> from pathlib import Path
    >>> from matplotlib.figure import Figure
    >>> from PIL import Image
    >>> from symctl.plotting.png import render_pdf
    >>> from symctl.plotting.vector import write_vector
    >>> with tempfile.TemporaryDirectory() as out:
    ...     pdf = write_vector(Figure(figsize=(2, 1)), Path(out) / "a.pdf")
    ...     png = render_pdf(pdf, Path(out) / "a.png", dpi=50)
    ...     Image.open(png).size, png.read_bytes()[25]
    ((100, 50), 2)
    """
    import pypdfium2

    document = pypdfium2.PdfDocument(str(pdf))
    try:  # transparent where the PDF draws nothing: an opaque figure comes out RGB
        bitmap = document[0].render(scale=dpi / 72, fill_color=(255, 255, 255, 0))
        image = bitmap.to_pil().convert("RGBA")
    finally:
        document.close()
    return _save(image, path, dpi, metadata)


def _save(image, path: Path | str, dpi: float, metadata: dict | None) -> Path:
    """Write the RGBA ``image`` as a PNG, RGB when it is opaque."""
    import numpy as np
    from PIL import PngImagePlugin

    path = Path(path)
    if (np.asarray(image)[..., 3] == 255).all():
        image = image.convert("RGB")
    info = PngImagePlugin.PngInfo()
    for key, value in (metadata or {}).items():
        if value is not None:
            info.add_text(key, value)
    image.save(path, format="png", pnginfo=info, dpi=(dpi, dpi))
    return path
