"""ltca.bevel: spiral bevel gears. ``case`` reads a [bevel] case; ``run`` synthesises the pinion from the
contact-path angle and TE targets, runs the TCA of both flanks (``ltca tca``) and the stage benchmark.
``analysis`` is the loaded analysis, ``results`` its dataset and files, ``iso10300`` the ISO 10300 Method B1
nominal stresses it is set beside in ``html_report`` (report.html).

Imports geometry (geometry.bevel) and ltca.case / ltca.errors; no other analysis subpackage.
"""
