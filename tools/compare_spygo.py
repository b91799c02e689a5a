"""Point-by-point comparison of the universal face-milling generator with SpyGO (independent open code).

SpyGO (public Python spiral bevel / hypoid generator, a 9-joint cradle kinematics as a product of
exponentials) is NOT a dependency of the project and nothing of it is copied here: this script imports it
from a checkout given by ``--spygo DIR`` (or the environment variable SPYGO_DIR) and runs it.  SpyGO needs
casadi, numba and scipy; its plotting modules import pyvista and its progress bar opens a Tk window, so the
script puts stand-ins for those two before importing it (they draw nothing that the comparison uses).

The pair is the 19/62 spiral bevel pair with a 95 deg shaft angle of SpyGO's example notebook
(``hypoid_test.ipynb``, cell 2: module 4.169 mm, face 36.83 mm, spiral 35 deg, cutter radius 95.25 mm,
left hand, generated gear); SpyGO designs its blank and settings sheet from those data.  Each variant
changes the settings sheet of one flank (tilt and swivel, each motion order in turn, a curved pinion blade,
a formate gear), SpyGO samples the flank at a (z, R) grid of its axial section, and our generator
(:mod:`ltca.geometry.bevel.generation`) is solved at the same (z, R).  The sheet is turned into physical joint
values with SpyGO's own scaling and sign tables (``DesignData.manage_machine_settings``), then into our
:class:`ltca.geometry.bevel.machine.MachineSettings` by the frame identity below, checked against SpyGO's own
forward kinematics at several roll angles before any flank is compared:

* SpyGO's machine x axis is our -z_m (the cradle axis), its y our y_m, its z our x_m; its work (gear) frame
  is our work body frame, its cradle joint our q + psi, its roll joint our phi.
* joint values -> ours: radial S = Sr, tilt = i, swivel = j, blank offset E = -Em, sliding base B = XB,
  machine centre to back = XG, root angle = gamma_m; each polynomial coefficient c_k of psi^k is our
  derivative a_k = k! c_k.
* SpyGO's normal points out of the blade, ours into it: compared as n_SpyGO = -n_ours.
* SpyGO's straight blade is an arc of radius 2e6 mm (its own approximation, at most 0.03 um off a line over
  the flank depth); ours is a line.

The formate variant uses SpyGO's kinematics and tool functions at zero roll (its formate sampling routine does
not run as published: it unpacks two values from a three-value return), solved here with scipy.

Writes the table to stdout and ``--out`` (JSON): per variant the settings in our vocabulary, the (z, R) grid
and SpyGO's points and normals, for :mod:`tests.test_bevel_universal`.
"""
from __future__ import annotations

import argparse
import copy
import json
import math
import os
import subprocess
import sys
import time
from unittest import mock

import numpy as np
from scipy.optimize import root

from ltca.geometry.bevel.cutter import HeadCutter
from ltca.geometry.bevel.generation import solve_axial_points, surface_state
from ltca.geometry.bevel.universal import blade_coordinates
from ltca.geometry.bevel.machine import FlankCut, MachineSettings

NOTEBOOK = dict(
    system=dict(HAND="Left", taper="Standard", hypoidOffset=0, gearGenType="generated"),
    module=4.169,
    cone=dict(SIGMA=95, a=0, z1=19, z2=62, b2=36.83, betam1=35, rc0=95.25, gearBaseThick=15, pinBaseThick=8),
    tooth=dict(alphaD=20, alphaC=20, falphalim=1, khap=1, khfp=1.25, xhm1=0.05, jen=0.1, xsmn=0.0649,
               thetaa2=None, thetaf2=None))
ROW = {"radial_motion": 0, "tilt_motion": 1, "swivel_motion": 2, "vertical_motion": 3, "helical_motion": 4}
SHEET_ROW = {0: "R", 1: "TLT", 2: "SW", 3: "V", 4: "H"}
ROLL_SHEET = ["RATIOROLL", "C2", "D6", "E24", "F120", "G720"]


def load_spygo(path: str):
    """Import SpyGO from ``path`` with stand-ins for its display-only imports; returns its modules."""
    sys.path.insert(0, path)
    for name in ("pyvista", "pyvistaqt", "vtk", "mayavi", "PyQt5"):
        sys.modules.setdefault(name, mock.MagicMock())
    import general_utils
    import hypoid  # noqa: F401
    core = sys.modules["hypoid.main.core"]
    core.Waitbar = general_utils.Waitbar = mock.MagicMock()
    return sys.modules["hypoid.main.core"], sys.modules["hypoid.main.geometry"], \
        sys.modules["hypoid.main.kinematics"], sys.modules["hypoid.main.data_structs"]


def example(core):
    """SpyGO's Hypoid object of the notebook's 19/62 pair (it designs the blank and settings)."""
    cone = dict(NOTEBOOK["cone"])
    cone["de2"] = cone["z2"] * NOTEBOOK["module"]
    cone["u"] = cone["z2"] / cone["z1"]
    return core.Hypoid().from_macro_geometry(dict(NOTEBOOK["system"]), dict(NOTEBOOK["tooth"]), cone)


def scaling(ds, member: str, hand: str) -> np.ndarray:
    """SpyGO's sheet -> joint scaling (factorial, degree and sign tables), shape (9, 8)."""
    c, s = ds.DesignData.manage_machine_settings(member, hand)
    return c * s


def joints(dd, ds, member: str, flank: str) -> np.ndarray:
    """Physical joint polynomials (9, 8) of a flank's sheet, as SpyGO's kinematics uses them."""
    M = np.array(dd.extract_machine_settings_matrix(member, flank), dtype=float)
    J = scaling(ds, member, dd.system_data.hand) * M
    J[6, 2:] *= M[6, 1]
    return J


def check_joints(dd, kin, ds, member: str, flank: str, J: np.ndarray) -> float:
    """Largest difference of SpyGO's casadi kinematics of the sheet and its numeric one of ``J``."""
    import casadi as ca
    ggt, _, _ = kin.casadi_machine_kinematics(member, dd.system_data.hand)
    ggt_num, _, _ = kin.machine_kinematics(J)
    M = np.array(dd.extract_machine_settings_matrix(member, flank), dtype=float)
    return max(float(np.max(np.abs(ca.DM(ggt(M, p)).full() - ggt_num(p)))) for p in (-0.3, -0.1, 0.0, 0.2, 0.35))


def ours(J: np.ndarray, cutter, flank: str, formate: bool = False) -> FlankCut:
    """Our flank cut from SpyGO's joint polynomials and cutter block (module docstring)."""
    fact = [math.factorial(k) for k in range(8)]

    def derivs(row, sign=1.0):
        a = [sign * J[row, k] * fact[k] for k in range(1, 7)]
        while a and a[-1] == 0.0:
            a.pop()
        return tuple(a)

    if not formate:
        assert J[5, 1] == 1.0 and not J[5, 2:].any(), "cradle joint must be q + psi"
        assert not J[7, 1:].any() and not J[8, 1:].any()
    m = J[6, 1]
    roll = dict() if formate else dict(ratio_of_roll=float(m), modified_roll_c=float(-J[6, 2] / m),
                                       modified_roll_d=float(-J[6, 3] / m), modified_roll_e=float(-J[6, 4] / m),
                                       modified_roll_f=float(-J[6, 5] / m), modified_roll_g=float(-J[6, 6] / m))
    ms = MachineSettings(radial_setting=float(J[0, 0]), cradle_angle=float(J[5, 0]), root_angle=float(J[8, 0]),
                         center_to_back=float(J[7, 0]), blank_offset=float(-J[3, 0]), sliding_base=float(J[4, 0]),
                         tilt=float(J[1, 0]), swivel=float(J[2, 0]),
                         radial_motion=derivs(0), tilt_motion=derivs(1), swivel_motion=derivs(2),
                         vertical_motion=derivs(3, -1.0), helical_motion=derivs(4), formate=formate,
                         **(dict(ratio_of_roll=0.0) if formate else roll))
    t = cutter
    rho = float(t.RHO) if str(t.TYPE).lower() == "curved" else float("inf")
    rem = {}
    if str(t.topremTYPE).lower() == "blended":
        rem.update(toprem_depth=float(t.topremDEPTH), toprem_radius=float(t.topremRADIUS))
    if str(t.flankremTYPE).lower() == "blended":
        rem.update(flankrem_depth=float(t.flankremDEPTH), flankrem_radius=float(t.flankremRADIUS))
    cu = HeadCutter(float(t.POINTRADIUS), math.radians(float(t.BLADEANGLE)),
                    "outside" if flank == "concave" else "inside", float(t.EDGERADIUS), profile_radius=rho, **rem)
    return FlankCut(ms, cu)


def settings_dict(fc: FlankCut) -> dict:
    """Our settings of a flank cut as plain JSON values (the stored reference rebuilds them; inf as "inf")."""
    import dataclasses

    def plain(obj):
        out = {}
        for f in dataclasses.fields(obj):
            v = getattr(obj, f.name)
            out[f.name] = list(v) if isinstance(v, tuple) else ("inf" if v == float("inf") else v)
        return out
    cu = plain(fc.cutter)
    cu.pop("part")
    return dict(machine=plain(fc.machine), cutter=cu)


def solve_ours(fc: FlankCut, z: np.ndarray, R: np.ndarray, x0: np.ndarray):
    """Our points and normals (n, 3) at the axial-section targets, from the guesses ``x0`` (n, 3)."""
    x, ok = solve_axial_points(fc, z, R, x0, tol=1e-11, max_iter=60)
    st = surface_state(fc, x[:, 0], x[:, 1], x[:, 2])
    return st.r_w, st.n_w, ok, x


def spygo_generated(geo, kin, dd, member, flank, z, R, trip):
    """SpyGO's points, normals and (csi, theta, phi) at (z, R), and its own residual there (mm): the axial
    section and the equation of meshing n . V p (its spatial twist), evaluated with its kinematics."""
    import casadi as ca
    p, n, t = geo.rz_sampling_casadi(R[None, :], z[None, :], dd, member, flank, trip[:, None, :])
    p, n, t = p[:3, 0, :].T, n[:3, 0, :].T, t[:, 0, :].T
    _, _, Vs = kin.casadi_machine_kinematics(member, dd.system_data.hand)
    M = np.array(dd.extract_machine_settings_matrix(member, flank), dtype=float)
    res = np.full(len(z), np.inf)
    for k in range(len(z)):
        if np.all(np.isfinite(p[k])):
            V = ca.DM(Vs(M, t[k, 2])).full()
            mesh = float(n[k] @ (V @ np.r_[p[k], 1.0])[:3])
            res[k] = max(abs(np.hypot(p[k, 0], p[k, 1]) - R[k]), abs(abs(p[k, 2]) - abs(z[k])), abs(mesh))
    return p, n, t, res


def spygo_generated_rem(kin, dd, member, flank, z, R, trip):
    """As :func:`spygo_generated` for a blade with toprem or flankrem: SpyGO's own sampling routine builds the
    blade without them, so its blade with them (``casadi_tool_fun(flank, toprem=True)``) and its kinematics are
    solved here for (csi, theta, phi) at (z, R) with casadi's Newton, the same three equations."""
    import casadi as ca
    ggt, _, Vs = kin.casadi_machine_kinematics(member, dd.system_data.hand)
    M = np.array(dd.extract_machine_settings_matrix(member, flank), dtype=float)
    pT, nT, _ = kin.casadi_tool_fun(flank, toprem=True, flankrem=True)
    # SpyGO's CutterField.extract_settings fails for a blended toprem (its toprem angle is left unassigned):
    # the ten-entry tool vector in its order, angles of the blended pieces 0, a straight blade its 2e6 mm arc
    t = getattr(getattr(dd, f"{member}_cutter_data"), flank)
    rho = float(t.RHO) if str(t.TYPE).lower() == "curved" else 2e6
    tool = np.array([t.POINTRADIUS, t.EDGERADIUS, rho, t.BLADEANGLE, t.topremDEPTH, t.topremRADIUS, 0.0,
                     t.flankremDEPTH, t.flankremRADIUS, 0.0], dtype=float)
    x = ca.SX.sym("x", 3)
    par = ca.SX.sym("p", 2)
    G = ggt(M, x[2])
    pg = G @ ca.vertcat(pT(tool, x[:2]), 1)
    ng = G @ ca.vertcat(nT(tool, x[:2]), 0)
    g = ca.vertcat(ca.sqrt(pg[0] ** 2 + pg[1] ** 2) - par[0], pg[2] - par[1], ng.T @ Vs(M, x[2]) @ pg)
    solve = ca.rootfinder("s", "newton", {"x": x, "p": par, "g": g}, {"error_on_fail": False, "abstol": 1e-13})
    gf = ca.Function("g", [x, par], [g, pg[:3], ng[:3]])
    P, N, T, res = [], [], [], []
    for zi, Ri, t0 in zip(z, R, trip.T):
        xs = np.array(solve(t0, [Ri, zi])).ravel()
        gv, pv, nv = (np.array(v).ravel() for v in gf(xs, [Ri, zi]))
        P.append(pv), N.append(nv), T.append(xs), res.append(float(np.max(np.abs(gv))))
    return np.array(P), np.array(N), np.array(T), np.array(res)


def spygo_formate(kin, dd, member, flank, z, R, trip):
    """SpyGO's tool and kinematics at zero roll, solved for (csi, theta) at (z, R) (module docstring)."""
    import casadi as ca
    ggt, _, _ = kin.casadi_machine_kinematics(member, dd.system_data.hand)
    M = np.array(dd.extract_machine_settings_matrix(member, flank), dtype=float)
    G = ca.DM(ggt(M, 0.0)).full()
    pT, nT, _ = kin.casadi_tool_fun(flank)
    tool = np.array(dd.extract_tool_settings(member, flank), dtype=float)

    def point(x):
        return G @ np.r_[ca.DM(pT(tool, x)).full().ravel(), 1.0]

    P, N, T, res = [], [], [], []
    for zi, Ri, g in zip(z, R, trip):
        def F(x):
            q = point(x)
            return [np.hypot(q[0], q[1]) - Ri, q[2] - zi]
        x = root(F, g[:2], method="lm", options=dict(xtol=1e-15, ftol=1e-15)).x
        P.append(point(x)[:3])
        N.append((G @ np.r_[ca.DM(nT(tool, x)).full().ravel(), 0.0])[:3])
        T.append([x[0], x[1], 0.0])
        res.append(float(np.max(np.abs(F(x)))))
    return np.array(P), np.array(N), np.array(T), np.array(res)


def variants(base_psi: float, R_mean: float):
    """(name, member, flank, edit) of each variant; ``edit(dd, ds)`` changes a copied sheet in place."""
    out = [(f"base {m} {f}", m, f, None) for m in ("gear", "pinion") for f in ("concave", "convex")]

    def set_joint(row, k, value):
        def edit(dd, ds, member, flank, w=1.0):
            value_w = w * value
            sc = scaling(ds, member, dd.system_data.hand)
            ms = getattr(getattr(dd, f"{member}_machine_settings"), flank)
            if row == 6:
                name, m = ROLL_SHEET[k - 1], ms.RATIOROLL
                setattr(ms, name, value_w / (sc[6, k] * m))
            else:
                setattr(ms, f"{SHEET_ROW[row]}{k}", value_w / sc[row, k])
        return edit

    def tilt_swivel(dd, ds, member, flank, w=1.0, tilt=1.0, swivel=30.0):
        ms = getattr(getattr(dd, f"{member}_machine_settings"), flank)
        ms.TILTANGLE, ms.SWIVELANGLE = tilt * w, swivel          # sheet degrees

    def curved(dd, ds, member, flank, w=1.0):
        t = getattr(getattr(dd, f"{member}_cutter_data"), flank)
        t.TYPE, t.RHO = "CURVED", 300.0 / w

    out.append(("tilt 0.3 deg, swivel 30 deg", "pinion", "concave",
                lambda dd, ds, member, flank, w=1.0: tilt_swivel(dd, ds, member, flank, w, 0.3, 30.0)))
    out.append(("tilt 1 deg, swivel 30 deg", "gear", "convex", tilt_swivel))
    for k in range(2, 7):
        out.append((f"modified roll order {k} ({ROLL_SHEET[k - 1]})", "pinion", "concave",
                    set_joint(6, k, -4e-4 / base_psi ** k)))
    for name, row, size in (("radial motion", 0, 0.05), ("vertical motion", 3, 0.05), ("helical motion", 4, 0.05),
                            ("modified tilt", 1, 5e-4)):
        for k in range(1, 7):
            out.append((f"{name} order {k}", "pinion", "concave" if k % 2 else "convex",
                        set_joint(row, k, size / base_psi ** k)))
    for k in range(1, 7):                                  # a swivel motion needs a tilted cutter
        sw = set_joint(2, k, 0.02 / base_psi ** k)

        def edit(dd, ds, member, flank, w=1.0, sw=sw):
            tilt_swivel(dd, ds, member, flank)
            sw(dd, ds, member, flank, w)
        out.append((f"modified swivel order {k} (tilt 1 deg)", "gear", "convex", edit))
    out.append(("curved blade rho 300 mm", "pinion", "convex", curved))

    def rems(dd, ds, member, flank, w=1.0):
        t = getattr(getattr(dd, f"{member}_cutter_data"), flank)
        t.topremTYPE, t.topremDEPTH, t.topremRADIUS = "BLENDED", 2.5, 25.0 / w
        t.flankremTYPE, t.flankremDEPTH, t.flankremRADIUS = "BLENDED", 6.0, 40.0 / w
    rems.rem = True
    out.append(("toprem and flankrem (blended)", "pinion", "concave", rems))
    out.append(("toprem and flankrem (blended)", "gear", "convex", rems))
    out.append(("formate gear", "gear", "concave", "formate"))
    out.append(("formate gear", "gear", "convex", "formate"))
    return out


def _spygo_flank(H, geo, kin, ds, base, member, flank, edit, z, R, trip, steps: int = 4):
    """SpyGO's flank of a variant; an edit is reached in ``steps`` continuation steps, each solve starting from
    the previous one's (csi, theta, phi) (SpyGO's Newton from the base flank's parameters alone does not always
    converge for a tilted cutter)."""
    formate = edit == "formate"
    dd = copy.deepcopy(base)
    if formate:
        ms = getattr(dd.gear_machine_settings, flank)
        J0 = joints(dd, ds, member, flank)
        ms.HORIZONTAL = J0[0, 0] * math.cos(J0[5, 0])       # the generated cut's cutter centre, no roll
        ms.VERTICAL = J0[0, 0] * math.sin(J0[5, 0])
        ms.RATIOROLL = 0.0
        dd.gear_common_data.gen_type = "formate"
        for k in ROLL_SHEET[1:]:
            setattr(ms, k, 0.0)
        return (dd,) + spygo_formate(kin, dd, member, flank, z, R, trip.T)
    if edit is None:
        return (dd,) + spygo_generated(geo, kin, dd, member, flank, z, R, trip)
    sample = spygo_generated_rem if getattr(edit, "rem", False) else spygo_generated
    for w in np.linspace(1.0 / steps, 1.0, steps):
        dd = copy.deepcopy(base)
        edit(dd, ds, member, flank, w)
        p, n, t, res = (spygo_generated_rem(kin, dd, member, flank, z, R, trip) if sample is spygo_generated_rem
                        else spygo_generated(geo, kin, dd, member, flank, z, R, trip))
        trip = np.where(np.isfinite(t.T) & (res < 1e-6)[None, :], t.T, trip)
    return dd, p, n, t, res


def SUBSET(n_prof: int, n_face: int) -> np.ndarray:
    """The stored nodes: every other profile row and face column of the grid (flattened column-major)."""
    m = np.zeros((n_prof, n_face), bool)
    m[::2, ::3] = True
    return m.ravel(order="F")


def run(spygo_dir: str, n_prof: int = 5, n_face: int = 7, tol: float = 1e-9) -> dict:
    """The comparison (module docstring); ``tol`` (mm) is the residual below which a SpyGO point counts."""
    core, geo, kin, ds = load_spygo(spygo_dir)
    from hypoid.main.utils import interpolated_triplets_zR
    t0 = time.time()
    H = example(core)
    base = H.designData
    rows, store, base_pts = [], [], {}
    for name, member, flank, edit in variants(0.25, 100.0):
        z, R = H.compute_zr_grid(member, flank, n_prof, n_face)
        z, R = z.ravel(order="F"), R.ravel(order="F")
        trip = interpolated_triplets_zR(H.interpTriplets.get_value(member, flank), z, R)
        trip[0] = np.maximum(trip[0] - 0.2, 0.03)
        formate = edit == "formate"
        dd, p_s, n_s, t_s, res = _spygo_flank(H, geo, kin, ds, base, member, flank, edit, z, R, trip)
        J = joints(dd, ds, member, flank)
        kin_dev = check_joints(dd, kin, ds, member, flank, J)
        fc = ours(J, getattr(getattr(dd, f"{member}_cutter_data"), flank), flank, formate)
        # SpyGO's tool is defined past its tip (csi < 0) too: a root there is not a cut point
        good = np.all(np.isfinite(p_s), axis=1) & (res < tol) & (t_s[:, 0] >= 0.0)
        x0 = blade_coordinates(fc, p_s[good], t_s[good, 2])
        p_o, n_o, ok, x = solve_ours(fc, z[good], R[good], x0)
        ok &= x[:, 0] >= fc.cutter.u_min - 1e-9
        dp = np.linalg.norm(p_o - p_s[good], axis=1)
        dn = np.linalg.norm(-n_o - n_s[good], axis=1)
        cu = fc.cutter
        if not cu.curved:           # ours with SpyGO's own stand-in for a straight blade (an arc of 2e6 mm)
            import dataclasses
            fa = FlankCut(fc.machine, dataclasses.replace(cu, profile_radius=2e6))
            p_a, n_a, _, _ = solve_ours(fa, z[good], R[good], x0)
            dpa = float(np.linalg.norm(p_a - p_s[good], axis=1).max() * 1e3)
            dna = float(np.linalg.norm(-n_a - n_s[good], axis=1).max())
        else:
            dpa, dna = float(dp.max() * 1e3), float(dn.max())
        key = (member, flank)
        if edit is None:
            base_pts[key] = (z, R, p_s)
        zb, Rb, pb = base_pts[key]
        change = float(np.max(np.linalg.norm(p_s[good] - pb[good], axis=1)) * 1e3) if edit is not None else 0.0
        if name.startswith("modified swivel"):            # measured against the tilted flank
            change = float(np.max(np.linalg.norm(p_s[good] - base_pts["tilt"][good], axis=1)) * 1e3)
        if name.startswith("tilt") and member == "gear":
            base_pts["tilt"] = p_s
        pieces = np.bincount(np.searchsorted(cu.chain[0], x[:, 0], side="right"), minlength=len(cu.chain[0]) + 1) \
            if cu.general else np.bincount((x[:, 0] >= 0).astype(int), minlength=2)
        rows.append(dict(variant=name, member=member, flank=flank, points=int(good.sum()), grid=len(z),
                         points_per_blade_piece=pieces.tolist(),
                         ours_converged=int(ok.sum()), max_point_dev_um=float(dp.max() * 1e3),
                         max_normal_dev=float(dn.max()), max_point_dev_um_rho2e6=dpa, max_normal_dev_rho2e6=dna,
                         change_from_base_um=change, kinematics_check=kin_dev,
                         spygo_max_residual_mm=float(res[good].max()),
                         psi_range=[float(t_s[good, 2].min()), float(t_s[good, 2].max())]))
        keep = good & SUBSET(n_prof, n_face)
        store.append(dict(variant=name, member=member, flank=flank, formate=formate, settings=settings_dict(fc),
                          z=z[keep].tolist(), R=R[keep].tolist(), spygo_points=p_s[keep].tolist(),
                          spygo_normals=n_s[keep].tolist(), spygo_psi=t_s[keep, 2].tolist()))
        print(f"{name:32s} {member:6s} {flank:7s} {good.sum():2d}/{len(z)} ok={ok.sum():2d} change {change:8.1f} um | "
              f"point {dp.max() * 1e3:8.5f} um normal {dn.max():.1e} | rho 2e6: {dpa:8.5f} um {dna:.1e} "
              f"(kin {kin_dev:.0e}) pieces {pieces.tolist()}", flush=True)
    commit = subprocess.run(["git", "-C", spygo_dir, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    return dict(provenance=dict(
        code="SpyGO (github haomjc/SpyGO, the hypoid package), run by tools/compare_spygo.py",
        spygo_commit=commit or "417ac9a (snapshot without git metadata)",
        pair="SpyGO example notebook hypoid_test.ipynb cell 2: 19/62 spiral bevel, shaft angle 95 deg, module 4.169 "
             "mm, face 36.83 mm, spiral 35 deg, cutter radius 95.25 mm, left hand; blank and settings designed by "
             "SpyGO (Hypoid.from_macro_geometry)",
        pieces="points_per_blade_piece: our nodes on the edge radius, then on each blade piece from the tip "
               "(toprem, blade, flankrem)",
        grid=f"SpyGO compute_zr_grid, {n_prof} x {n_face} over the active flank (the table); points kept where "
             f"SpyGO's own residual (axial section and equation of meshing) is below {tol} mm and its blade "
             "parameter is on the tool (csi >= 0); 'variants' stores every other row and every third column",
        normals="SpyGO's normal points out of the blade: n_SpyGO = -n_ours",
        straight_blade="SpyGO models a straight blade as an arc of radius 2e6 mm; *_rho2e6 columns: ours with "
                       "the same arc",
        seconds=round(time.time() - t0, 1)), table=rows, variants=store)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spygo", default=os.environ.get("SPYGO_DIR"), help="SpyGO checkout (its top folder)")
    ap.add_argument("--out", default=None, help="JSON file for the table and SpyGO's reference points")
    a = ap.parse_args()
    if not a.spygo:
        ap.error("--spygo DIR (or SPYGO_DIR) is required")
    res = run(a.spygo)
    if a.out:
        with open(a.out, "w") as f:
            json.dump(res, f)


if __name__ == "__main__":
    main()
