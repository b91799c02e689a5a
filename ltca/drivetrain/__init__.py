"""ltca.drivetrain: drive-train deflection budgets (``budget*``, Wang et al.), backlash curves (``backlash``) and the
ratio errors of a cutting machine's kinematic chains (``chain*``, Nguyen et al. 2020): the ``ltca budget`` and
``ltca chain`` commands.

Imports geometry, ltca.case / ltca.errors, and ltca.cylindrical (the budget's backlash uses the cylindrical
double-flank TCA); no other analysis subpackage.
"""
