"""ltca.verify: checks of the analyses against references: ``validate`` (Hertz, ISO 6336-1, kinematic
identities), ``calculix`` and ``crosscheck`` (the same pair solved by CalculiX), ``bevel_ccx`` and
``bevel_calculix`` (the spiral bevel pair by CalculiX on independent whole members, issue 13), ``whole_gear``
and ``whole_check`` (whole gears with every tooth, issue 11), ``planetary_whole`` (the satellite in its internal
central wheel, issue 15), ``convergence`` (fidelity ladder), ``bench`` (cold wall time per stage).

Imports geometry, fem (fem.calculix, fem.solids, fem.compliance), ltca.case / ltca.errors / ltca.results and the
analyses it checks (ltca.cylindrical, ltca.planetary); no analysis imports it.
"""
