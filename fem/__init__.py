"""fem: the finite-element side, by concept. Imports geometry only, never ltca.

    solids/     gear solids meshed by gmsh (whole cylindrical bodies, bevel members), one mesh record (BodyMesh)
    elastic     P2 tetrahedral elasticity: stiffness assembly, boundary conditions
    solver      sparse factorisation (PARDISO, CHOLMOD or SuperLU)
    loads       patch loads on flank facets
    readout     displacement and stress read-out at points
    compliance  influence matrices on flank grids, root-stress influence
    halfspace   half-space (Boussinesq) near field
    contact     the complementarity solve with torque balance
    calculix/   CalculiX deck writer and runner (the cross-check)
    background  a call in a daemon thread, its value or exception handed back (the pair's two bodies)
"""
