"""ltca.verify: checks of the analyses against references: ``validate`` (Hertz, ISO 6336-1, kinematic
identities), ``calculix`` and ``crosscheck`` (the same pair solved by CalculiX), ``bevel_ccx`` and
``bevel_calculix`` (the spiral bevel pair by CalculiX on independent whole members), ``whole_gear``
and ``whole_check`` (whole gears with every tooth), ``planetary_whole`` (the satellite in its internal
central wheel), ``convergence`` (fidelity ladder), ``bench`` (cold wall time per stage).

Imports geometry, fem (fem.calculix, fem.solids, fem.compliance), ltca.case / ltca.errors / ltca.results and the
analyses it checks (ltca.cylindrical, ltca.planetary); no analysis imports it.
"""
