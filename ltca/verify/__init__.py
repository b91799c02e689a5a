"""ltca.verify: checks of the analyses against references: ``validate`` (Hertz, ISO 6336-1, kinematic
identities), ``bevel_check`` (the bevel analytic checks), ``calculix`` and ``crosscheck`` (the same pair solved by
CalculiX on our body), ``whole_gear`` and ``whole_check`` (whole gears with every tooth), ``bevel_ccx`` and
``bevel_calculix`` (the spiral bevel pair by CalculiX on independent whole members), ``planetary_whole`` (the
satellite in its internal central wheel), ``convergence`` (fidelity ladder), ``bench`` (cold wall time per stage).

A CalculiX check here is one run per position, the user's cross-check of their own pair. CalculiX's refinement
ladders, the frozen references the tests compare with, and their merge and re-evaluation are maintainer tooling in
the repository's ``tools/calculix_refs`` (not installed), which imports this package, never the reverse.

Imports geometry, fem (fem.calculix, fem.solids, fem.compliance), ltca.case / ltca.errors / ltca.results and the
analyses it checks (ltca.cylindrical, ltca.planetary, ltca.bevel); no analysis imports it.
"""
