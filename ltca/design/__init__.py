"""Design optimisation driven by the LTCA (``ltca optimise``).

The ``[design]`` table (:mod:`.schema`), the problem and its backends (:mod:`.problem`, :mod:`.cylindrical`), the search (:mod:`.driver`), the history
(:mod:`.history`), the result files (:mod:`.report`) and figures (:mod:`.plots`).
"""
from __future__ import annotations

from .driver import OptimiseResult, optimise
from .schema import DesignSpec, parse_design

__all__ = ["optimise", "OptimiseResult", "DesignSpec", "parse_design"]
