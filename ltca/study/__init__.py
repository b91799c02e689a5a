"""ltca.study: load-case and tolerance studies on Dask (``ltca study``).

A study names a base case and its variations (a full-factorial grid or named variants over any case keys, or
a Monte Carlo sample of ISO 1328-1 tooth errors); every variant runs at every torque of the study. Variants
whose FE bodies are the same share one compliance, computed once on a worker and handed on; each (variant,
torque) point is written as it finishes, and a rerun skips what is done.

    spec        the study file: validation, variants and their ids
    iso1328     ISO 1328-1:2013 flank tolerances of a class
    montecarlo  tooth errors drawn from a class, mapped onto case keys; checks of the draws
    tasks       the worker tasks: plan a variant (geometry key), compute a compliance, solve a point
    bevel_tasks the same for a bevel pair: one compliance per loaded flank, shared by every assembly error
    store       per-point netCDF files and the combined store (variant x torque x position)
    runner      the Dask client: LocalCluster or a scheduler address, progress, ETA
    report      summary CSV, Harris map, response surface, Monte Carlo histograms and CDFs

Imports ltca.case, ltca.errors, ltca.results, ltca.cylindrical, ltca.bevel, geometry and fem; only ltca.cli
imports it.
"""
from .runner import run_study
from .spec import Study, Variant
from .store import load_study

__all__ = ["Study", "Variant", "run_study", "load_study"]
