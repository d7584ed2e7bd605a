"""Sphinx configuration of symctl's documentation site (``make docs``).

The site is built offline: MathJax is served from the site itself (a copy of the
``django-static-mathjax`` package's files), and nothing is fetched from the network
at build or view time. The pages that depend on the code are written at build time
by the local extension ``docs/_ext/symctl_site.py``: the API reference (from
``symctl.__all__``), the derivations and the gallery (``symctl paper`` run into
``docs/generated/runs/``), and the notebooks (executed by myst-nb).
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent / "_ext"))

import symctl

project = "symctl"
author = "symctl contributors"
copyright = "symctl contributors"
release = version = symctl.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_nb",
    "symctl_site",
]

# Sources: committed pages in docs/, the rest written by symctl_site into docs/generated/.
exclude_patterns = ["_build", "generated/runs", "**.ipynb_checkpoints"]
templates_path = ["_templates"]

# MyST: $...$ and $$...$$ math in Markdown pages and notebooks.
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3
# MathJax typesets math elements, and the notebooks' HTML outputs (python-control's reprs hold
# $$...$$), as Jupyter does; the rest of a page is left alone
myst_mathjax_classes = "tex2jax_process|mathjax_process|math|output_area|text_html"

# Notebooks: executed at build time, each in a temporary folder (they write files).
nb_execution_mode = "force"
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_in_temp = True
nb_merge_streams = True
nb_render_markdown_format = "myst"  # Markdown outputs with their tables and $...$ math

# API reference: autosummary pages from numpydoc docstrings.
autosummary_generate = True
autodoc_typehints = "none"  # the numpydoc Parameters sections give the types
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

# Math: MathJax 3 from the site's own _static folder, never from a CDN.
mathjax_path = "mathjax/tex-mml-chtml.js"
# An undefined TeX command is an error (MathJax's noundefined would draw it in red as text),
# so that the browser check (tests/docs) finds it.
mathjax3_config = {"tex": {"tags": "none", "packages": {"[-]": ["noundefined"]}}}

html_theme = "pydata_sphinx_theme"
html_title = "symctl"
html_static_path = ["generated/static"]
html_theme_options = {
    "navigation_depth": 2,
    "header_links_before_dropdown": 4,
    "show_toc_level": 2,
    "navbar_end": ["theme-switcher"],
    "footer_start": ["copyright"],
    "footer_end": [],
    "secondary_sidebar_items": ["page-toc"],
}
html_show_sourcelink = False
html_last_updated_fmt = None
html_context = {"default_mode": "light"}  # the reader's switch can change it
