"""PNG files, RGB when the figure is opaque: ``pdflatex`` copies an RGB PNG into the PDF as it
is but splits an RGBA one into a soft mask (4.5 of the 4.7 s of a MIMO report's PDF)."""

from __future__ import annotations

from pathlib import Path

__all__ = ["render_pdf", "write_png"]


def write_png(fig, path: Path | str, *, dpi: float, metadata: dict | None = None) -> Path:
    """Save ``fig`` as a PNG at ``dpi`` (rendered by Agg as :meth:`Figure.savefig` does), RGB when
    every pixel is opaque, with the text chunks ``metadata`` (``None`` values left out).
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
