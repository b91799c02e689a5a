"""ltca.bevel: spiral bevel gears. ``case`` reads a [bevel] case; ``run`` synthesises the pinion from the
contact-path angle and TE targets, runs the TCA of both flanks (``ltca tca``) and the stage benchmark.
The bevel loaded analysis will come here.

Imports geometry (geometry.bevel) and ltca.case / ltca.errors; no other analysis subpackage.
"""
