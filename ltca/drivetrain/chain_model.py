"""Transmission-ratio error of a machine's kinematic chains (Nguyen et al. 2020) and its tooth errors.

Source: Nguyen Tho Son, Nguyen Van Mui, Le Thanh Son, J. Science & Technology (HaUI) 56(4), 2020,
pp. 48-52, Gleason-system generator Modul ZFTKK250X5. Method (Sect. 3):

* n: revolutions of each element during one cycle (from the chain's kinematics);
* zk = frac(n) z, the "odd teeth" passed beyond whole revolutions;
* F = fi' if zk = 0 else fi' + zk fp, with fp = Fpr / z (kinematic error fi', cumulative pitch error
  Fpr, um, by accuracy grade);
* angle error dphi = 2 F / D (rad, D pitch diameter) reported in deg;
* rotation band n 360 +/- dphi; the paper adds the dphi of the elements before it on the same shaft
  (this is what its nmax/nmin columns show, e.g. Table 3: Z72 720.14 = 720 + 0.067 + 0.061 + 0.016);
* per mesh (driver -> driven) ratio max = rot_max(driven)/rot_min(driver), min the other way round;
* chain ratio max/min = products; error = i_max - i_min, in percent of the nominal ratio;
  workpiece angle error = error * input rotation; pitch error = that angle * r, r = mn z / (2 cos beta)
  (mean pitch radius; the paper calls it the "normal" pitch error, Tables 4 and 6).

The paper's own arithmetic departs from these rules in places; a case can give the printed value of
zk, fp or F (and ``turns_factor``) per element to reproduce its tables, and ``honour_printed=False``
recomputes everything by the rules (see the case file and tests/ltca/drivetrain/test_chain.py for each departure).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["DEG", "LINKS", "ChainElement", "Chain", "ChainEvaluation", "evaluate_chain",
           "pitch_deviation_bound", "RollRatioError", "roll_ratio_error"]

DEG = np.pi / 180.0
LINKS = ("input", "mesh", "shaft")


@dataclass(frozen=True)
class ChainElement:
    """One gear (or worm, or rack-driven pinion) of a kinematic chain.

    Parameters
    ----------
    name : str
    teeth : int
        z (starts k for a worm).
    pitch_diameter : float
        D in dphi = 2F/D, mm.
    link : {"input", "mesh", "shaft"}
        "input": the first element (rotation given); "mesh": driven by the previous element;
        "shaft": on the previous element's shaft (same rotation, errors add).
    fi, Fpr : float, optional
        Kinematic error fi' and cumulative pitch error Fpr, um.
    F, zk, fp : float, optional
        Printed values of the paper that override the rule (um, teeth, um).
    turns_factor : bool
        Paper's Table 7 quirk: dphi computed from F times the element's revolutions.
    """
    name: str
    teeth: int
    pitch_diameter: float
    link: str
    fi: float | None = None
    Fpr: float | None = None
    F: float | None = None
    zk: float | None = None
    fp: float | None = None
    turns_factor: bool = False


@dataclass(frozen=True)
class Chain:
    """A kinematic chain and what it must produce.

    Parameters
    ----------
    name : str
    kind : {"indexing", "envelope"}
    input_turn_deg : float
        Rotation of the first element in one cycle, deg (720 for the indexing rack stroke, the
        cradle swing for the envelope chain).
    required_ratio : float
        Workpiece turns per input turn the chain must give (1/(zp n_in) indexing, zd/zp envelope).
    elements : tuple of ChainElement
    reference_radius : float
        Workpiece mean pitch radius mn zp / (2 cos beta), mm.
    closure_tolerance : float
        Allowed |i_nominal / i_required - 1|.
    """
    name: str
    kind: str
    input_turn_deg: float
    required_ratio: float
    elements: tuple
    reference_radius: float
    closure_tolerance: float = 1e-6


@dataclass(frozen=True)
class ChainEvaluation:
    """Per-element table and chain ratio error (Nguyen et al. 2020 Tables 3-9 layout).

    Arrays per element: ``turns`` (rev), ``zk``, ``fp`` (um), ``F`` (um), ``dphi`` (deg, own),
    ``rot_max``, ``rot_min`` (deg). Per mesh: ``pairs``, ``ratio_max``, ``ratio_min``, ``ratio_nom``.
    Chain: ``i_max``, ``i_min``, ``i_nom``, ``i_required``; ``error`` = i_max - i_min;
    ``error_percent``; ``angle_error_deg`` = error * input rotation; ``pitch_error_um`` at the
    reference radius.
    """
    chain: Chain
    turns: np.ndarray
    zk: np.ndarray
    fp: np.ndarray
    F: np.ndarray
    dphi: np.ndarray
    rot_max: np.ndarray
    rot_min: np.ndarray
    pairs: tuple
    ratio_max: np.ndarray
    ratio_min: np.ndarray
    ratio_nom: np.ndarray
    i_max: float
    i_min: float
    i_nom: float
    i_required: float
    honour_printed: bool

    @property
    def error(self) -> float:
        return self.i_max - self.i_min

    @property
    def error_percent(self) -> float:
        return self.error / self.i_nom * 100.0

    @property
    def angle_error_deg(self) -> float:
        return self.error * self.chain.input_turn_deg

    @property
    def pitch_error_um(self) -> float:
        return self.angle_error_deg * DEG * self.chain.reference_radius * 1e3

    @property
    def closure(self) -> float:
        """i_nominal / i_required - 1 (the change-gear approximation, a systematic ratio error)."""
        return self.i_nom / self.i_required - 1.0

    def table(self) -> str:  # noqa: C901
        """Plain text: per element, per mesh, and the chain summary."""
        c = self.chain
        out = [f"chain {c.name} ({c.kind}), input {c.input_turn_deg:g} deg"
               + ("" if self.honour_printed else ", recomputed by the rules"),
               f"{'element':<10}{'z':>5}{'D/mm':>8}{'n/rev':>11}{'zk':>8}{'fp/um':>8}{'F/um':>8}"
               f"{'dphi/deg':>10}{'max/deg':>13}{'min/deg':>13}"]
        for k, e in enumerate(c.elements):
            out.append(f"{e.name:<10}{e.teeth:>5d}{e.pitch_diameter:>8.1f}{self.turns[k]:>11.4f}"
                       f"{self.zk[k]:>8.2f}{_given(self.fp[k], 8, 3)}{self.F[k]:>8.2f}{self.dphi[k]:>10.4f}"
                       f"{self.rot_max[k]:>13.2f}{self.rot_min[k]:>13.2f}")
        if not np.all(np.isfinite(self.fp)):
            out.append("fp '-': the source gives only F for these elements (its fi' and Fpr are lost), so the pitch "
                       "error fp = Fpr / z is unknown; F is used as printed")
        out.append(f"{'mesh':<20}{'largest':>12}{'smallest':>12}{'theoretical':>12}")
        for p, a, b, t in zip(self.pairs, self.ratio_max, self.ratio_min, self.ratio_nom):
            out.append(f"{p:<20}{a:>12.5f}{b:>12.5f}{t:>12.5f}")
        out += [f"chain ratio: largest {self.i_max:.9g}, smallest {self.i_min:.9g}, "
                f"theoretical {self.i_nom:.9g}, required {self.i_required:.9g}",
                f"ratio error {self.error:.6g} = {self.error_percent:.4f} %; closure "
                f"{self.closure:+.3e}"]
        if c.kind == "indexing":
            out.append(f"workpiece angle error {self.angle_error_deg:.7f} deg; pitch error at "
                       f"r = {c.reference_radius:.3f} mm: {self.pitch_error_um:.4f} um")
        else:
            out.append(f"roll-ratio factor {self.i_nom / self.i_required:.7f} "
                       f"({self.i_min / self.i_required:.7f} .. {self.i_max / self.i_required:.7f})")
        return "\n".join(out)


def evaluate_chain(chain: Chain, honour_printed: bool = True) -> ChainEvaluation:
    """Ratio error of a kinematic chain by the method of Nguyen et al. (2020) (see module docstring).

    Parameters
    ----------
    chain : Chain
    honour_printed : bool
        Use the printed zk, fp, F and the turns-factor quirk where the case gives them (reproduces
        the paper); False recomputes zk = frac(n) z, fp = Fpr / z, F by the rule, no quirk.

    Returns
    -------
    ChainEvaluation
    """
    els = chain.elements
    z = np.array([e.teeth for e in els], float)
    dia = np.array([e.pitch_diameter for e in els], float)
    mesh = np.array([e.link == "mesh" for e in els])
    step = np.ones(len(els))
    step[1:] = np.where(mesh[1:], z[:-1] / z[1:], 1.0)          # driven turns per driver turn
    turns = chain.input_turn_deg / 360.0 * np.cumprod(step)
    zk_rule = np.round((turns - np.floor(turns)) * z, 9)        # frac(n) z, exact zero kept
    zk, fp, F = np.empty(len(els)), np.empty(len(els)), np.empty(len(els))
    factor = np.ones(len(els))
    for k, e in enumerate(els):
        zk[k] = e.zk if (honour_printed and e.zk is not None) else zk_rule[k]
        fp[k] = e.fp if (honour_printed and e.fp is not None) else (
            e.Fpr / e.teeth if e.Fpr is not None else np.nan)
        if honour_printed and e.F is not None:
            F[k] = e.F
        elif e.fi is None or e.Fpr is None:
            raise ValueError(f"element {e.name!r} of chain {chain.name!r}: fi and Fpr are needed "
                             "to recompute F (the paper prints only F for it)")
        else:
            F[k] = e.fi if zk[k] == 0 else e.fi + zk[k] * fp[k]
        if honour_printed and e.turns_factor:
            factor[k] = turns[k]
    dphi = 2.0 * F * 1e-3 * factor / dia / DEG                    # deg
    acc = dphi.copy()                                             # errors add along a shaft
    for k in range(1, len(els)):
        if not mesh[k]:
            acc[k] += acc[k - 1]
    rot = turns * 360.0
    rmax, rmin = rot + acc, rot - acc
    idx = np.flatnonzero(mesh)
    ratio_max = rmax[idx] / rmin[idx - 1]
    ratio_min = rmin[idx] / rmax[idx - 1]
    ratio_nom = rot[idx] / rot[idx - 1]
    pairs = tuple(f"{els[k - 1].name}/{els[k].name}" for k in idx)
    return ChainEvaluation(chain, turns, zk, fp, F, dphi, rmax, rmin, pairs, ratio_max, ratio_min,
                           ratio_nom, float(np.prod(ratio_max)), float(np.prod(ratio_min)),
                           float(np.prod(ratio_nom)), chain.required_ratio, honour_printed)


# ---------------------------------------------------------------- into the teeth

def pitch_deviation_bound(ev: ChainEvaluation) -> float:
    """Bound of a single pitch deviation of the workpiece, mm: half the indexing band.

    The paper's pitch error (20.64 um for z1, 30.46 um for z2) is the full band i_max - i_min of one
    indexing step measured at the mean pitch radius, so one pitch lies within +/- half of it.
    """
    return 0.5 * ev.pitch_error_um * 1e-3


@dataclass(frozen=True)
class RollRatioError:
    """Roll-ratio factors of the generation, actual / required ratio of the envelope chain.

    Attributes
    ----------
    nominal : float
        From the change gears (e.g. 0.745193 for 0.745356 in Nguyen et al. 2020).
    low, high : float
        Bounds from the chain's error band.
    """
    nominal: float
    low: float
    high: float


def roll_ratio_error(ev: ChainEvaluation) -> RollRatioError:
    """Factor on the ratio of roll that the TCA/LTCA applies to the generation of the workpiece."""
    req = ev.i_required
    return RollRatioError(ev.i_nom / req, ev.i_min / req, ev.i_max / req)


def _given(v: float, width: int, digits: int) -> str:
    """A table cell: '-' for a value the case does not give (not 'nan')."""
    return f"{'-':>{width}}" if not np.isfinite(v) else f"{v:>{width}.{digits}f}"
