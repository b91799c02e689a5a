"""fem.solids: the solids of the gears, meshed.

Solids of every gear type are built here from geometry records and returned as one mesh record
(:class:`BodyMesh`, :mod:`ltca.fem.solids.mesh_record`: nodes, quadratic tetrahedra, named facet groups) that the
compliance path (:mod:`ltca.fem.compliance`) consumes. Cylindrical gears (spur, helical, external or internal): the
whole gear body (:class:`GearBodySpec`, :mod:`ltca.fem.solids.gear_body`: 360 deg rim, web and hub, held at the bore or
the outer rim), optionally refined around contact lines (:mod:`ltca.fem.solids.refinement`); spiral bevel members
(:mod:`ltca.fem.solids.bevel_body`); the independent whole-gear solids of the CalculiX cross-check
(:mod:`ltca.fem.solids.full_gear`, :mod:`ltca.fem.solids.bevel_occ`), which :mod:`ltca.fem.solids.step` also writes as
STEP files. The shared gmsh steps (fresh model, size field,
meshing and read-back) are :mod:`ltca.fem.solids.gmsh_mesh`, the plane geometry of transverse sections
:mod:`ltca.fem.solids.planar`; :mod:`ltca.fem.solids.mesh_job` meshes a gear body in a child process.

Imports numpy and gmsh only (and geometry); nothing else of fem, nothing of ltca.
"""
from .gear_body import GearBodySpec, build_gear_body
from .mesh_record import BodyMesh
from .refinement import ContactLine, build_refined_body, facets_near_lines
from .session import gmsh_session

__all__ = ["GearBodySpec", "build_gear_body", "BodyMesh", "gmsh_session", "ContactLine", "build_refined_body",
           "facets_near_lines"]
