"""fem.solids: the solids of the gears, meshed.

Solids of every gear type are built here from geometry records and returned as one mesh record
(:class:`SegmentMesh`: nodes, quadratic tetrahedra, named facet groups) that the compliance path
(:mod:`fem.compliance`) consumes. Cylindrical gears (spur, helical, external or internal): the whole gear body
(:class:`GearBodySpec`, :mod:`fem.solids.gear_body`: 360 deg rim, web and hub, held at the bore or the outer
rim), and the tooth segment of a few teeth (:class:`SegmentSpec`), optionally refined around contact lines
(:mod:`fem.solids.refinement`); the bevel builder comes next, behind the same record.

Imports numpy and gmsh only (and geometry); nothing else of fem, nothing of ltca.
"""
from .gear_body import GearBodySpec, build_gear_body
from .refinement import ContactLine, build_refined_segment, facets_near_lines
from .segment import build_segment
from .session import gmsh_session
from .spec import SegmentMesh, SegmentSpec

__all__ = ["GearBodySpec", "build_gear_body", "SegmentSpec", "SegmentMesh", "build_segment", "gmsh_session", "ContactLine", "build_refined_segment",
           "facets_near_lines"]
