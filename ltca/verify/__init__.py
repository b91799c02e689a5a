"""ltca.verify: checks of the analyses against references: ``validate`` (Hertz, ISO 6336-1, kinematic
identities), ``calculix`` and ``crosscheck`` (the same pair solved by CalculiX), ``convergence`` (fidelity
ladder), ``bench`` (cold wall time per stage).

Imports geometry, fem (fem.calculix, fem.solids, fem.compliance), ltca.case / ltca.errors / ltca.results and the
analyses it checks (ltca.cylindrical); no analysis imports it.
"""
