"""tools.calculix_refs: CalculiX's refinement ladders, the frozen references of ``tests/reference/*.json`` (freeze,
merge, re-evaluation of ours) and the convergence estimates the tests compare with; see README.md here.

Imports geometry, fem and ltca (the installed single-run checks of ``ltca.verify``); nothing installed imports it.
"""
