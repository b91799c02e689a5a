"""ltca.cylindrical: the loaded tooth contact analysis of cylindrical pairs (spur, helical, internal).

``model`` (the pair from a case), ``tca`` (unloaded TCA, separation field), ``loaded_model`` (fidelity, both
bodies' compliance once), ``contact_cells`` and ``loaded`` (the contact of one position), ``results`` and
``report`` (dataset, summary, plots), ``run`` (``ltca run`` / ``ltca tca``).

Imports geometry, fem, and ltca.case / ltca.errors / ltca.results; no other analysis subpackage.
"""
