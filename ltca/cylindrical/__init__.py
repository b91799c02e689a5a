"""ltca.cylindrical: the loaded tooth contact analysis of cylindrical pairs (spur, helical, internal).

``model`` (the pair from a case), ``tca`` (unloaded TCA, separation field), ``loaded_model`` (fidelity, both
bodies' compliance once), ``flank_lattice`` (cells on the developed flank along the contact line), ``cell_clip``
(cells clipped to the flanks that touch), ``contact_cells`` and ``loaded`` (the contact of one position),
``edges`` (flank pressure and edge contact kept apart), ``results`` and ``report`` (dataset, summary, plots),
``run`` (``ltca run`` / ``ltca tca``).

Imports geometry, fem, and ltca.case / ltca.errors / ltca.results; no other analysis subpackage.
"""
