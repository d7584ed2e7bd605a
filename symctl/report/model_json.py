"""The ``plant`` and ``model`` entries of ``results.json`` (written by :mod:`symctl.report.results`)."""

from __future__ import annotations

from symctl.report.results import _matrix as float_rows
from symctl.report.results import _model_json as model
from symctl.report.results import _plant_json as plant

__all__ = ["float_rows", "model", "plant"]
