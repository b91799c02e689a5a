"""fem.calculix: the CalculiX cross-check's FE side. ``deck`` writes the input deck of meshed bodies in
contact (C3D10, rigid-body drive, penalty contact); ``run`` runs ``ccx`` and reads its results back.

Imports fem.solids (the mesh record) only; nothing of ltca.
"""
