"""ltca.cylindrical: the loaded tooth contact analysis of cylindrical pairs (spur, helical, internal).

``model`` (the pair from a case), ``tca`` (unloaded TCA, separation field), ``loaded_model`` (fidelity, both
bodies' compliance once), ``flank_lattice`` (cells on the developed flank along the contact line), ``cell_clip``
(cells clipped to the flanks that touch), ``contact_cells`` and ``loaded`` (the contact of one position),
``edges`` (flank pressure and edge contact kept apart), ``results`` and ``report`` (dataset, summary, plots),
``derived`` (diameters, contact ratios, SAP/EAP), ``iso6336`` (ISO 6336 and Hertz references), ``pattern``
(bearing pattern against diameter, striping), ``paraview`` (the ``paraview.pvd`` series), ``html_report``
(``report.html``), ``run`` (``ltca run`` / ``ltca tca``).

Imports geometry, fem, and ltca.case / ltca.errors / ltca.results; no other analysis subpackage.
"""
