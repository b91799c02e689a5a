"""Backlash curve from double-flank (drive and coast) unloaded TE, and the loaded TE curves.

Source: Wang Guangjian et al., Chinese Journal of Engineering, p. 1061 (seed 003): the continuous
backlash curve is the coast-side (back-side) TE minus the drive-side TE, both *unloaded*; under load the
two curves shift by the drive-train deformation delta_k (Eq. 20-21)::

    dphi_d^F = dphi_d - delta_k        (20)
    dphi_b^F = dphi_b + delta_k        (21)

so the loaded curves are separated by backlash + 2 delta_k, and the unloaded curves are recovered from
measured loaded ones by shifting them back. ``delta_k`` comes from :mod:`ltca.drivetrain.budget` (the total
deflection at the load, rad at the same shaft as the TE).

Sign convention: TE in rad of the driven member, drive flank in contact gives ``te_drive``, coast flank
``te_coast`` (coast TE >= drive TE when there is clearance).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["BacklashCurves", "backlash_curves", "unloaded_from_loaded", "plot_backlash"]

RAD_PER_ARCSEC = np.pi / (180.0 * 3600.0)


@dataclass(frozen=True)
class BacklashCurves:
    """Backlash and loaded TE curves over the roll angle.

    Attributes
    ----------
    roll_angle : ndarray (n,)
        Roll angle of the driving member, rad.
    te_drive, te_coast : ndarray (n,)
        Unloaded drive- and coast-side TE, rad.
    backlash : ndarray (n,)
        te_coast - te_drive, rad (circumferential backlash angle at the TE shaft).
    loaded_drive, loaded_coast : ndarray (n,)
        Eq. (20)-(21): te_drive - delta_k and te_coast + delta_k, rad.
    deflection : float
        delta_k, rad.
    """
    roll_angle: np.ndarray
    te_drive: np.ndarray
    te_coast: np.ndarray
    backlash: np.ndarray
    loaded_drive: np.ndarray
    loaded_coast: np.ndarray
    deflection: float

    @property
    def min_backlash(self) -> float:
        """Smallest backlash over the roll angle, rad (< 0 means the flanks interfere)."""
        return float(self.backlash.min())

    @property
    def loaded_hysteresis(self) -> np.ndarray:
        """Separation of the loaded curves, backlash + 2 delta_k, rad."""
        return self.loaded_coast - self.loaded_drive


def _curves(roll_angle, te_drive, te_coast) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    phi = np.asarray(roll_angle, float)
    d = np.asarray(te_drive, float)
    c = np.asarray(te_coast, float)
    if not (phi.ndim == d.ndim == c.ndim == 1 and phi.shape == d.shape == c.shape):
        raise ValueError(f"roll_angle, te_drive, te_coast must be 1-D of equal length, got "
                         f"{phi.shape}, {d.shape}, {c.shape}")
    return phi, d, c


def backlash_curves(roll_angle, te_drive, te_coast, deflection: float) -> BacklashCurves:
    """Backlash curve and loaded TE curves from unloaded double-flank TE (Eq. 20-21).

    Parameters
    ----------
    roll_angle : array_like (n,)
        Roll angle, rad.
    te_drive, te_coast : array_like (n,)
        Unloaded TE of the drive and coast flanks, rad.
    deflection : float
        Drive-train deflection delta_k at the load, rad (>= 0), e.g. ``BudgetResult.total[i]``.

    Returns
    -------
    BacklashCurves
    """
    phi, d, c = _curves(roll_angle, te_drive, te_coast)
    if not np.isfinite(deflection) or deflection < 0:
        raise ValueError(f"deflection must be a finite angle >= 0 rad, got {deflection!r}")
    return BacklashCurves(phi, d, c, c - d, d - deflection, c + deflection, float(deflection))


def unloaded_from_loaded(roll_angle, loaded_drive, loaded_coast,
                         deflection: float) -> BacklashCurves:
    """Invert Eq. (20)-(21): measured loaded curves shifted back by delta_k (the paper's Fig. 10)."""
    phi, d, c = _curves(roll_angle, loaded_drive, loaded_coast)
    return backlash_curves(phi, d + deflection, c - deflection, deflection)


def plot_backlash(curves: BacklashCurves, path: str, title: str = "") -> None:
    """Unloaded and loaded TE of both flanks and the backlash curve, in arcsec (PNG, Agg)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    deg = np.degrees(curves.roll_angle)
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 5.6))
    ax1.plot(deg, curves.te_drive / RAD_PER_ARCSEC, "C0-", label="drive, unloaded")
    ax1.plot(deg, curves.te_coast / RAD_PER_ARCSEC, "C1-", label="coast, unloaded")
    ax1.plot(deg, curves.loaded_drive / RAD_PER_ARCSEC, "C0--", label="drive, loaded (Eq. 20)")
    ax1.plot(deg, curves.loaded_coast / RAD_PER_ARCSEC, "C1--", label="coast, loaded (Eq. 21)")
    ax1.set_ylabel("TE / arcsec")
    ax1.legend(fontsize=7)
    ax2.plot(deg, curves.backlash / RAD_PER_ARCSEC, "k-", label="backlash = coast - drive")
    ax2.plot(deg, curves.loaded_hysteresis / RAD_PER_ARCSEC, "k:", label="loaded separation")
    ax2.set_xlabel("roll angle / deg")
    ax2.set_ylabel("backlash / arcsec")
    ax2.legend(fontsize=7)
    if title:
        ax1.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
