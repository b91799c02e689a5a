"""ltca.planetary: the eccentric planetary satellite of Kapitonov et al. 2014 in its central wheel.

``case`` reads a ``[satellite]`` case (the satellite, its three forming tools, the central wheel, supports,
torques as fractions of the ISO 6336-3 rated torque); ``model`` forms the satellite, cuts the wheel and
places both as a cylindrical pair model at the eccentricity; ``loaded`` chooses every tooth pair that can
close, computes both whole bodies' compliance (satellite held at its bearing seat, wheel at its housing rim)
and solves the multi-pair contact with the cylindrical chain; ``analysis`` plans and executes the loaded run
(for :mod:`ltca.kinds.planetary`) and computes the unloaded gaps; ``report`` writes its tables and plots;
``run`` holds the commands ``ltca forming`` and ``ltca tca`` of such a case (their console).

May import: geometry (geometry.satellite and the cylindrical geometry), fem, ltca.case, ltca.errors,
ltca.results, ltca.cylindrical. Imported by ltca.cli, ltca.core and ltca.kinds (the run), ltca.console and
ltca.verify (its CalculiX check).
"""
