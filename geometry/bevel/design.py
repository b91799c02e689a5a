"""Three-control-point design of the pinion (Cao et al. 2008) and the blank-offset redesign.

Control points: M0 (phi1 = 0, the mean contact point of :mod:`ltca.geometry.bevel.synthesis`) and M1, M2 at the
transfer points phi1 = -+pi/z1, one mesh cycle apart.  The parabola TE = (m21/2) phi1^2 puts the gear at
TE(M1) = TE(M2) = -te_magnitude.  Our scheme, equivalent in its unknowns to the paper's but solved on the
generated surfaces rather than on the head-cutter surfaces:

* inner problem, for given modified-roll coefficients (C, D): the local synthesis at M0
  (:func:`ltca.geometry.bevel.synthesis.local_synthesis`) gives point radius, Sr1, q1, XG1, Em1, XB1, ratio of
  roll and blade angle so that eta2, m21 and the ellipse axis hold exactly at M0 (C enters the second
  order through the roll acceleration, D does not);
* outer problem: Newton on (C, D) so that the continuous-tangency TCA of the generated pair passes
  through M1 and M2 with the parabola's gear angles (two equations, two unknowns; Cao et al. 2008 Eq. 8 fits C, D
  through the same two points).

The path stays straight to second order through M0 (its tangent is eta2); its deviation from the straight
line over the cycle is measured, not imposed (:func:`cycle_metrics`).

Blank-offset redesign (Cao et al. 2008 sec. 3): Em1 fixed (e.g. 0 mm); the local synthesis now takes point
radius, XG1 and C as its unknowns (eta2 and m21 still hold at M0), and the outer Newton runs on (ellipse
axis used at M0, D) so that TE(M1) = TE(M2) = -te_magnitude again, starting from the first design: the
TE magnitude is kept, the ellipse axis at M0 moves (reported), the path gains a small curvature (reported),
as in the paper.  (Fixing Em1 and solving the local synthesis for point radius and XG1 alone is nearly
singular on the test pairs.)
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from .blank import BevelBlank
from .machine import FlankCut, MemberCut
from .synthesis import FlankTarget, mean_contact, synthesis_at
from .tca import RAD_PER_ARCSEC, Assembly, BevelPair, ContactError, TCAResult, contact_path, tca

__all__ = ["path_line", "cycle_metrics", "control_point_design", "synthesize_flank", "synthesize_pinion"]


def path_line(L: np.ndarray, Rn: np.ndarray, blank: BevelBlank) -> tuple[float, float]:
    """Least-squares line of contact points in the gear axial section.

    Parameters
    ----------
    L, Rn : ndarray (m,)
        The points' coordinates in the gear axial section, mm (:func:`ltca.geometry.bevel.tca.tca`'s ``gear_L``,
        ``gear_Rn``, or the separation field's).
    blank : BevelBlank

    Returns
    -------
    angle_deg : float
        The line's direction from the gear's root-cone line, positive towards the top (eta2 of Cao et al. 2008).
    straightness_mm : float
        Largest distance of the points from the line.
    """
    X = np.stack([L, Rn], 1)
    X = X - X.mean(0)
    _, _, vt = np.linalg.svd(X, full_matrices=False)
    d = vt[0] if vt[0, 0] >= 0 else -vt[0]
    return float(np.rad2deg(np.arctan2(d[1], d[0]) - blank.gear.dedendum_angle)), float(np.max(np.abs(X @ vt[1])))


def cycle_metrics(r: TCAResult, blank: BevelBlank) -> dict:
    """Headline figures of one TCA over the mesh cycle |phi1| <= pi/z1 around M0.

    Returns
    -------
    dict
        ``te_amplitude_arcsec`` (magnitude of the least-squares parabola at phi1 = +-pi/z1),
        ``te_transfer_arcsec`` (TE at the two transfer points), ``te_r2`` (R^2 of the parabola fit),
        ``path_angle_deg`` (least-squares line of the path in the gear axial section, from the root-cone
        line, positive towards the top), ``path_straightness_mm`` (largest distance of the path points from
        that line), ``ellipse_major_mm`` at M0, ``contact_ratio`` (of the TCA run as given).
    """
    half = 0.5 * r.cycle
    sel = np.abs(r.phi1) <= half * (1 + 1e-9)
    p, te = r.phi1[sel], r.te[sel]
    if sel.sum() < 5:
        raise ValueError("the TCA result covers fewer than 5 positions of the cycle")
    c = np.polyfit(p, te, 2)
    fit = np.polyval(c, p)
    r2 = 1.0 - np.sum((te - fit) ** 2) / max(np.sum((te - te.mean()) ** 2), 1e-300)
    angle, straightness = path_line(r.gear_L[sel], r.gear_Rn[sel], blank)
    i0 = int(np.argmin(np.abs(r.phi1)))
    return dict(te_amplitude_arcsec=float(-c[0] * half ** 2 / RAD_PER_ARCSEC),
                te_transfer_arcsec=[float(te[0] / RAD_PER_ARCSEC), float(te[-1] / RAD_PER_ARCSEC)],
                te_r2=float(r2),
                path_angle_deg=angle, path_straightness_mm=straightness,
                ellipse_major_mm=float(r.major[i0]), contact_ratio=r.contact_ratio)


def _pair(blank: BevelBlank, gear: MemberCut, fc: FlankCut) -> BevelPair:
    return BevelPair(blank, gear, MemberCut("pinion", blank.pinion.z, fc, fc))


def control_point_design(blank: BevelBlank, gear: MemberCut, pinion_side: str, target: FlankTarget,
                         blank_offset: float | None = None, start: tuple[float, float] = (0.0, 0.0),
                         guess: FlankCut | None = None, tol_arcsec: float = 1e-3, max_iter: int = 20) -> tuple[FlankCut, dict]:
    """Pinion flank settings with modified roll from the control points M0, M1, M2 (module docstring).

    Parameters
    ----------
    blank, gear : the blank and the given gear settings
    pinion_side : ``"concave"`` or ``"convex"``
    target : FlankTarget
    blank_offset : None (Em1 from the synthesis) or the fixed Em1, mm (redesign)
    start : initial (C, D), 1/rad and 1/rad^2 (the first design's values for a redesign)
    guess : FlankCut, optional
        Start of the local synthesis (the first design for a redesign).
    tol_arcsec : float
        Tolerance on TE at M1 and M2, arcsec.

    Returns
    -------
    FlankCut, dict
        Settings and diagnostics: ``C``, ``D``, ``blank_offset`` (mm), ``iterations``, ``te_residual_arcsec``, ``metrics``
        (:func:`cycle_metrics` of the final design), ``synthesis`` (local-synthesis diagnostics).

    Raises
    ------
    ContactError
        If the contact leaves the flank before a transfer point (target infeasible for this blank).
    """
    if tol_arcsec <= 0:
        raise ValueError(f"tol_arcsec = {tol_arcsec!r} is outside the allowed range (0, inf)")

    if pinion_side not in ("concave", "convex"):
        raise ValueError(f"pinion_side = {pinion_side!r}: allowed 'concave' or 'convex'")
    gear_side = "convex" if pinion_side == "concave" else "concave"
    mc = mean_contact(blank, gear.flank(gear_side))                 # M0 is the gear's: the same at every step
    last = {}

    def evaluate(cd):
        tg, c = (replace(target, major_axis=cd[0]), start[0]) if fixed else (target, cd[0])
        fc, info = synthesis_at(blank, mc, pinion_side, tg, blank_offset, (c, cd[1]), None,
                                 last.get("fc", guess), 1e-12)
        last["fc"] = fc
        phi1, _, te, stops = contact_path(_pair(blank, gear, fc), pinion_side, Assembly(), steps_per_cycle=4,
                                          max_cycles=0.5)
        if len(phi1) != 5:
            raise ContactError(f"{pinion_side} pinion flank: the contact path leaves the flank before the "
                               f"transfer points ({stops}); reduce the path length (te_magnitude, eta2) "
                               f"or the ellipse axis")
        F = (np.array([te[0], te[-1]]) + target.te_magnitude) / RAD_PER_ARCSEC
        return fc, info, F

    fixed = blank_offset is not None
    # unknowns: (C, D); redesign: (ellipse axis used at M0, D) -- C then comes from the local synthesis
    x = np.array([target.major_axis if fixed else start[0], start[1]], dtype=float)
    h = np.array([0.01 if fixed else 1e-3, 1e-2])
    it = 0
    for it in range(1, max_iter + 1):
        fc, info, F = evaluate(x)
        if np.max(np.abs(F)) < tol_arcsec:
            break
        J = np.empty((2, 2))
        for j in range(2):
            xp = x.copy()
            xp[j] += h[j]
            J[:, j] = (evaluate(xp)[2] - F) / h[j]
        dx = np.linalg.solve(J, -F)
        x = x + dx * min(1.0, 0.5 * x[0] / abs(dx[0])) if fixed else x + dx
    else:
        raise ContactError(f"{pinion_side} pinion flank: the control-point design did not converge (TE "
                           f"error at M1, M2 {F} arcsec after {max_iter} iterations)")
    r = tca(_pair(blank, gear, fc), pinion_side, Assembly(), steps_per_cycle=16, max_cycles=0.5)
    return fc, dict(C=float(fc.machine.modified_roll_c), D=float(x[1]), blank_offset=float(fc.machine.blank_offset), iterations=it, te_residual_arcsec=F.tolist(),
                    metrics=cycle_metrics(r, blank), synthesis=info)


def synthesize_flank(blank: BevelBlank, gear: MemberCut, pinion_side: str, target: FlankTarget,
                     blank_offset: float | None = None, max_iter: int = 20) -> tuple[FlankCut, dict]:
    """One pinion flank by the control-point design, then, with ``blank_offset`` a number, the redesign at that Em1
    started from it (Cao et al. 2008 sec. 3); the flanks of a pinion are independent of each other.  ``max_iter``:
    Newton iterations of each design (:func:`control_point_design`).

    Returns
    -------
    FlankCut, dict
        The flank's settings and ``{"design": info, "redesign": info or None}`` (:func:`control_point_design`).
    """
    fc, info = control_point_design(blank, gear, pinion_side, target, max_iter=max_iter)
    info2 = None
    if blank_offset is not None:
        fc, info2 = control_point_design(blank, gear, pinion_side, target, blank_offset, (info["C"], info["D"]), fc,
                                         max_iter=max_iter)
    return fc, dict(design=info, redesign=info2)


def synthesize_pinion(blank: BevelBlank, gear: MemberCut, targets: dict[str, FlankTarget],
                      blank_offset: float | None = None) -> tuple[MemberCut, dict]:
    """Both pinion flanks by the control-point design; with ``blank_offset`` a number, first the free
    design, then the redesign at that Em1 started from it (Cao et al. 2008 sec. 3).

    Parameters
    ----------
    targets : {"concave": FlankTarget, "convex": FlankTarget}
        Pinion concave = working flank of Cao et al. 2008 (drives the gear convex), convex = coast.

    Returns
    -------
    MemberCut, dict
        The pinion cut and ``{side: {"design": info, "redesign": info or None}}``.
    """
    if set(targets) != {"concave", "convex"}:
        raise ValueError(f"targets = {sorted(targets)!r}: give both 'concave' and 'convex'")
    cuts, infos = {}, {}
    for side, tg in targets.items():
        cuts[side], infos[side] = synthesize_flank(blank, gear, side, tg, blank_offset)
    return MemberCut("pinion", blank.pinion.z, cuts["concave"], cuts["convex"]), infos
