"""fem.solids: the solids of the gears, meshed.

Solids of every gear type are built here from geometry records and returned as one mesh record
(:class:`SegmentMesh`: nodes, quadratic tetrahedra, named facet groups) that the compliance path
(:mod:`fem.compliance`) consumes. Today: the tooth segment of a cylindrical gear (spur, helical, external
or internal) from its generated transverse outline (:class:`SegmentSpec`), optionally refined around
contact lines (:mod:`fem.solids.refinement`); the bevel builder comes next, behind the same record.

Imports numpy and gmsh only (and geometry); nothing else of fem, nothing of ltca.
"""
from .refinement import ContactLine, build_refined_segment, facets_near_lines
from .segment import build_segment
from .session import gmsh_session
from .spec import SegmentMesh, SegmentSpec

__all__ = ["SegmentSpec", "SegmentMesh", "build_segment", "gmsh_session", "ContactLine", "build_refined_segment",
           "facets_near_lines"]
