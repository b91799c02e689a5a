"""Units of REXS attributes converted to the units used inside (mm, N, MPa, rad; angles for case files in deg).

REXS declares a unit on every attribute (the schema fixes one unit per attribute; files written by older tools
use spellings such as ``°`` for ``deg`` or an empty unit for ``none``). A value is converted from the unit the file
declares to the unit of its dimension below; a unit we do not know, or of the wrong dimension, is an error.
"""
from __future__ import annotations

import math

__all__ = ["DIMENSIONS", "normalise_unit", "factor"]

#: spelling variants of a unit -> the schema's spelling
_ALIASES = {"°": "deg", "": "none", "-": "none", "1": "none", "µm": "mum", "μm": "mum", "um": "mum",
            "Nm": "N m", "N*m": "N m", "N/mm^2": "N / mm^2", "N/mm²": "N / mm^2", "1/min": "1 / min",
            "rpm": "1 / min"}

#: dimension -> {unit: factor to the dimension's base unit}
DIMENSIONS: dict[str, dict[str, float]] = {
    "length": {"mm": 1.0, "m": 1e3, "mum": 1e-3},                         # -> mm
    "angle": {"deg": 1.0, "rad": 180.0 / math.pi},                         # -> deg (case files take deg)
    "torque": {"N m": 1.0, "N mm": 1e-3, "kN m": 1e3},                     # -> N m
    "stress": {"N / mm^2": 1.0, "MPa": 1.0, "Pa": 1e-6, "kN / mm^2": 1e3},  # -> MPa
    "none": {"none": 1.0},
    "percent": {"%": 1.0},
    "speed": {"1 / min": 1.0},
}


def normalise_unit(unit: str | None) -> str:
    """The schema's spelling of a unit as a file declares it (``None`` and ``""`` are ``none``)."""
    u = (unit or "").strip()
    return _ALIASES.get(u, u)


def factor(unit: str | None, dimension: str) -> float | None:
    """Factor from ``unit`` to the base unit of ``dimension`` (mm, deg, N m, MPa, -); None when the unit is not
    one of that dimension."""
    return DIMENSIONS[dimension].get(normalise_unit(unit))
