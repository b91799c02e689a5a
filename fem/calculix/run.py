"""Running the CalculiX solver ``ccx`` on a deck of :mod:`ltca.fem.calculix.deck` and reading its results back.

The results read are the rotation of the driven axis (``*NODE PRINT`` of the rotation node), the total
reaction at the fixed nodes, the total contact force of each pair (``*CONTACT PRINT``, from ``job.dat``)
and the contact pressure and opening at the slave nodes (``*CONTACT FILE``, last ``CONTACT`` block of
``job.frd``) (CalculiX 2.20; G. Dhondt, *CalculiX CrunchiX User's Manual*); with a deck's stress output,
the nodal stresses (last ``STRESS`` block of ``job.frd``).

Units: mm, N, MPa, rad.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["CcxResult", "read_results", "read_nodal_stress", "run_ccx", "ccx_path", "CCX_INSTALL", "CcxNotFound",
           "CcxFailed"]

CCX_INSTALL = "apt-get update && apt-get install -y calculix-ccx"


class CcxNotFound(RuntimeError):
    """The CalculiX solver ``ccx`` is not on the PATH."""

    def __init__(self) -> None:
        super().__init__(f"CalculiX (command 'ccx') is not installed; install it with: {CCX_INSTALL}")


class CcxFailed(RuntimeError):
    """ccx ran but did not produce a converged result; the message ends with the tail of its log."""


def ccx_path() -> str:
    """Absolute path of ``ccx``; raises :class:`CcxNotFound` (with the install command) if missing."""
    exe = shutil.which("ccx")
    if exe is None:
        raise CcxNotFound()
    return exe


def run_ccx(inp: str | os.PathLike, threads: int = 2, timeout: float = 3600.0) -> float:
    """Run ``ccx`` on the deck ``inp`` (``job.inp`` -> ``job.dat``, ``job.frd``) in its folder.

    Returns the wall time in s. Raises :class:`CcxFailed` with the tail of the log if ccx stops
    without finishing the job (no convergence, bad input)."""
    exe = ccx_path()
    inp = Path(inp)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), CCX_NPROC_EQUATION_SOLVER=str(threads),
               CCX_NPROC_RESULTS=str(threads))
    t0 = time.perf_counter()
    with open(inp.with_suffix(".log"), "w") as log:
        proc = subprocess.run([exe, "-i", inp.stem], cwd=inp.parent, env=env, stdout=log, stderr=subprocess.STDOUT,
                              timeout=timeout)
    wall = time.perf_counter() - t0
    text = inp.with_suffix(".log").read_text(errors="replace")
    if proc.returncode != 0 or "Job finished" not in text or "*ERROR" in text:
        tail = "\n".join(text.splitlines()[-15:])
        raise CcxFailed(f"ccx failed on {inp} (exit {proc.returncode}):\n{tail}")
    return wall


@dataclass
class CcxResult:
    """What a contact deck gives back (mm, N, MPa, rad).

    rotation : rotation of the driven axis about +z, rad (counter-clockwise positive)
    pair_force : contact pair name -> total contact force vector on the slave, N (3,), last increment
    fixed_reaction : total reaction force at the fixed nodes, N (3,)
    contact_nodes : (k,) CalculiX ids of slave nodes with contact output; contact_pressure (k,) MPa;
    contact_opening : (k,) mm (negative = penetration)
    """
    rotation: float
    pair_force: dict
    fixed_reaction: np.ndarray
    contact_nodes: np.ndarray
    contact_pressure: np.ndarray
    contact_opening: np.ndarray
    wall: float = 0.0
    extra: dict = field(default_factory=dict)

    @property
    def max_pressure(self) -> float:
        return float(self.contact_pressure.max()) if self.contact_pressure.size else 0.0


_FLOAT = re.compile(r"[-+]?\d*\.\d+(?:[EeDd][-+]?\d+)?")


def _dat_blocks(text: str) -> list[tuple[str, list[list[float]]]]:
    """The .dat file as (header line, numeric rows) blocks, last increment last."""
    blocks: list[tuple[str, list[list[float]]]] = []
    for line in text.splitlines():
        s = line.strip()
        if not s:
            continue
        if s[0].isalpha():
            blocks.append((s, []))
        elif blocks:
            blocks[-1][1].append([float(v.replace("D", "E")) for v in s.split()])
    return blocks


def _frd_block(frd: str | os.PathLike, name: str) -> list[str]:
    """The node lines (`` -1`` records) of the last result block ``name`` (``CONTACT``, ``STRESS``, ...) of a
    ``.frd`` file."""
    rows: list[str] = []
    current = None
    with open(frd, errors="replace") as fh:
        for line in fh:
            if line.startswith(" -4"):
                current = line.split()[1]
                if current == name:
                    rows = []
            elif current == name and line.startswith(" -1"):
                rows.append(line)
            elif line.startswith(" -3"):
                current = None
    return rows


def _frd_contact(frd: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Slave node ids, opening and pressure of the last CONTACT block of a .frd file."""
    rows = _frd_block(frd, "CONTACT")
    if not rows:
        return np.zeros(0, int), np.zeros(0), np.zeros(0)
    ids = [int(re.match(r"\s*(\d+)", line[3:13]).group(1)) for line in rows]
    v = np.array([[float(x) for x in _FLOAT.findall(line[13:])] for line in rows])
    return np.array(ids), v[:, 0], v[:, 3]


def read_nodal_stress(frd: str | os.PathLike) -> tuple[np.ndarray, np.ndarray]:
    """Node ids (k,) and stresses (k, 6), MPa, of the last ``STRESS`` block of a ``.frd`` file.

    CalculiX writes the components SXX, SYY, SZZ, SXY, SYZ, SZX (nodal values: extrapolated from the
    integration points, averaged over the elements at the node); they are returned in the Voigt order
    xx, yy, zz, yz, xz, xy of :func:`ltca.fem.compliance.principal_max`. Empty arrays when there is no block."""
    rows = _frd_block(frd, "STRESS")
    if not rows:
        return np.zeros(0, int), np.zeros((0, 6))
    v = np.array([[float(line[13 + 12 * i:25 + 12 * i]) for i in range(6)] for line in rows])
    return np.array([int(line[3:13]) for line in rows]), v[:, [0, 1, 2, 4, 5, 3]]


def read_results(job: str | os.PathLike, rot_node: int, pairs: tuple[str, ...]) -> CcxResult:
    """Read the results of the deck written by :func:`write_deck` from ``job.dat`` and ``job.frd``."""
    job = Path(job)
    blocks = _dat_blocks(job.with_suffix(".dat").read_text(errors="replace"))
    rotation, reaction, forces, slave = np.nan, np.full(3, np.nan), {}, None
    for head, rows in blocks:
        h = head.lower()
        if h.startswith("displacements") and "nrot" in h:
            row = next(r for r in rows if int(r[0]) == rot_node)
            rotation = row[3]
        elif h.startswith("total force") and "nfix" in h and rows:
            reaction = np.array(rows[-1][-3:])
        elif h.startswith("statistics for slave set"):
            slave = head.split()[4].rstrip(",")
        elif h.startswith("total surface force") and slave is not None and rows:
            name = next((p for p in pairs if f"S{p}".upper() == slave.upper()), None)
            if name is not None:
                forces[name] = np.array(rows[0][:3])
    ids, opening, pressure = _frd_contact(job.with_suffix(".frd"))
    return CcxResult(float(rotation), forces, reaction, ids, pressure, opening)
