"""Tooth-periodic compliance (:mod:`ltca.fem.periodic`): the centre tooth's unit loads stand for every loaded tooth's.

Checked on a small mapped bevel pinion body of the shipped pair, whose fine teeth are exact turned copies: against
the same body loaded on every loaded tooth, the blocks loaded at the centre tooth are the same solves (equal to
round-off), the others differ only by what lies beyond the fine teeth (the far sector, at most a tooth nearer), and the
root stresses turned back from the centre tooth agree; the Voigt turn is checked against the tensor rotation.
"""

import numpy as np
import pytest

from ltca.fem.bevel_compliance import BevelComplianceSpec, bevel_compliance
from ltca.fem.periodic import periodic_offsets, turn_z, voigt_turn


def test_voigt_turn_is_the_tensor_rotation():
    rng = np.random.default_rng(1)
    s = rng.normal(size=(3, 3))
    s = s + s.T
    a = 0.7
    Q = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1.0]])
    voigt = ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))
    turned = Q @ s @ Q.T
    assert voigt_turn(a) @ [s[i, j] for i, j in voigt] == pytest.approx([turned[i, j] for i, j in voigt], abs=1e-14)
    assert turn_z(np.array([1.0, 0.0, 2.0]), a) == pytest.approx(Q @ [1.0, 0.0, 2.0], abs=1e-15)


def test_offsets_need_the_neighbours_meshed():
    centre, off = periodic_offsets((-1, 0, 1), (-2, -1, 0, 1, 2))
    assert centre == 0 and off.tolist() == [-2, -1, 0, 1, 2]
    assert periodic_offsets((-1, 0, 1), (-1, 0, 1, 2)) is None     # tooth -2 not meshed
    assert periodic_offsets((-1, 1), (-2, -1, 0, 1, 2)) is None     # not consecutive
    assert periodic_offsets((0,), (-1, 0, 1)) is None


@pytest.fixture(scope="module")
def both(bevel_pair, tmp_path_factory):
    from ltca.bevel.loaded_model import member_flanks
    fl, off, shift = member_flanks(bevel_pair, "pinion")
    z = bevel_pair.blank.pinion.z
    out = {}
    for periodic in (True, False):
        spec = BevelComplianceSpec("concave", (-1, 0, 1), (-2, -1, 0, 1, 2), (5, 6), 0.5, 206000.0, 0.3,
                                   divisions=(10, 6, 4, 3, 2, 12), support=("seat", 9.0), periodic=periodic)
        body = bevel_compliance(fl["concave"], fl["convex"], z, off, shift, spec, tmp_path_factory.mktemp("mesh"))
        out[periodic] = body.without_solver()
    return out


def test_centre_loads_are_the_same_solves(both):
    per, full = both[True], both[False]
    m = 5 * 6
    # reads at every loaded tooth under the centre tooth's loads: the same solves and half-space parts either way
    # (symmetrised alike where both blocks come from the centre column)
    assert per.C[m:2 * m, m:2 * m] == pytest.approx(full.C[m:2 * m, m:2 * m], rel=1e-9, abs=1e-12 * abs(full.C).max())
    centre = full.root_stress[:, :, m:2 * m]
    assert per.root_stress[:, :, m:2 * m] == pytest.approx(centre, abs=1e-9 * abs(centre).max())


def test_other_teeth_loads_agree_with_their_own_solves(both):
    per, full = both[True], both[False]
    scale = np.abs(np.diag(full.C)).max()
    # a load on tooth -1 or +1 against the centre tooth's turned onto it: the fine teeth are turned copies, so only
    # what lies beyond the fine teeth differs (measured 0.08 % of the largest diagonal term)
    assert np.abs(per.C - full.C).max() < 0.003 * scale
    # the root stresses in the body frame, turned back from the centre tooth (measured 0.3 % of the largest)
    assert np.abs(per.root_stress - full.root_stress).max() < 0.01 * np.abs(full.root_stress).max()
    f = np.ones(per.C.shape[0])
    assert per.root_max(f) == pytest.approx(full.root_max(f), rel=0.01)


@pytest.fixture(scope="module")
def spur(fzg_model):
    """A coarse FZG pinion body loaded both ways: its gmsh mesh is not a turned copy from tooth to tooth."""
    import dataclasses

    from ltca.fem.compliance import ComplianceSpec, body_compliance
    base = ComplianceSpec(teeth=(-2, -1, 0, 1, 2), loaded=(-1, 0, 1), side=+1, r_range=fzg_model.pinion_range(),
                          grid=(5, 4), face_width=14.0, r_bore=fzg_model.r_bore1, h_flank=2.0, h_body=7.2, depth=1.5,
                          young=206000.0, poisson=0.3, root_points=(2, 2))
    return {periodic: body_compliance(fzg_model.pinion, dataclasses.replace(base, periodic=periodic)).without_solver()
            for periodic in (True, False)}


def test_cylindrical_body_periodic_against_every_tooth_loaded(spur):
    """Cylindrical tooth k is tooth 0 turned by -k 2 pi / z: the centre tooth's loads are the same solves; the other
    teeth's blocks and root stresses differ by the difference of two unstructured meshes. Measured on this coarse
    body: compliance 0.6 % of the largest diagonal term, root stresses 5 % of the largest (the fillet mesh); a turn
    the wrong way (the tooth ahead read for the tooth behind): root stresses 53 %, a tooth's largest 139 %."""
    per, full = spur[True], spur[False]
    m = 5 * 4
    scale = np.abs(np.diag(full.C)).max()
    assert np.abs(per.C[:, m:2 * m] - full.C[:, m:2 * m]).max() < 1e-3 * scale
    assert np.abs(per.C - full.C).max() < 0.01 * scale
    assert np.abs(per.root_stress - full.root_stress).max() < 0.15 * np.abs(full.root_stress).max()
    f = np.ones(per.C.shape[0])
    assert per.root_max(f) == pytest.approx(full.root_max(f), rel=0.1)
