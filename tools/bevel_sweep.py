"""Spiral bevel pairs over the design space real gear sets cover: each runs, or exits 2 naming what limits it.

The grid (a scrambled Halton sequence, fixed seed, so the same pairs every time): pinion teeth 6-40, ratio 1-6,
spiral angle 0-45 deg, shaft angle 60-120 deg, cutter radius 0.6-1.2 times the mean cone distance.  The other
data follow the pair: module 5 mm, face width 0.3 of the outer cone distance (at most 10 modules), pressure angle
20 deg, the synthesis targets of the shipped Cao et al. pair (path angles 22 / -14 deg, TE 8.25 / 11.25 arcsec)
with an ellipse of 0.2 face widths, and a pinion torque that loads the pair about as the shipped one.

Each pair is written as a case and run through the command line as a user would: ``ltca tca`` and ``ltca run``
(coarse fidelity, 5 positions, one torque), each in its own process.  A row records both exit statuses, the
first line of each error message, whether it names a case field (``bevel.``, ``mounting.``, ...), and whether a
traceback or a warning reached the console.  "Agree": both succeed, or both exit 2.

    nice -n 5 python3 tools/bevel_sweep.py --pairs 32 --out /tmp/bevel_sweep
writes ``sweep.csv`` and ``sweep.md`` (the table and the counts) to ``--out``.
"""
from __future__ import annotations

import argparse
import csv
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

CASE = """[case]
name = "sweep {i}"

[bevel]
pinion_teeth = {z1}
gear_teeth = {z2}
module_mm = {m}
face_width_mm = {b:.3f}
spiral_angle_deg = {beta:.2f}
pressure_angle_deg = 20.0
shaft_angle_deg = {sigma:.2f}
gear_hand = "right"
cutter_radius_mm = {rc:.3f}
taper = "standard"

[bevel.working]
path_angle_deg = 22.0
te_magnitude_arcsec = 8.25
ellipse_major_mm = {ell:.3f}

[bevel.coast]
path_angle_deg = -14.0
te_magnitude_arcsec = 11.25
ellipse_major_mm = {ell:.3f}

[load]
torque_nm = [{torque:.1f}]

[analysis]
positions = 5
fidelity = "coarse"
"""

FIELD = re.compile(r"\b((?:bevel|mounting|load|assembly|analysis)\.[a-z_.]+)")


def grid(n: int, seed: int = 7) -> list[dict]:
    """``n`` pairs over the ranges of the module docstring."""
    from scipy.stats import qmc
    u = qmc.Halton(d=5, scramble=True, seed=seed).random(n)
    out = []
    for i, (a, r, s, g, c) in enumerate(u):
        z1 = round(6 + a * 34)
        ratio = 1.0 + r * 5.0
        z2 = max(z1, round(z1 * ratio))
        sigma = 60.0 + g * 60.0
        S = np.radians(sigma)
        g2 = np.arctan2(np.sin(S), z1 / z2 + np.cos(S))
        m = 5.0
        A0 = m * z2 / (2 * np.sin(g2))
        b = min(0.3 * A0, 10 * m)
        rc = (0.6 + 0.6 * c) * (A0 - b / 2)
        torque = 350.0 * (b / 25.4) * (z1 * m / (12 * 5.08)) ** 2
        out.append({"i": i, "z1": z1, "z2": z2, "m": m, "b": b, "beta": 45.0 * s, "sigma": sigma, "rc": rc,
                    "ell": 0.2 * b, "torque": torque, "ratio": z2 / z1, "cutter_factor": 0.6 + 0.6 * c})
    return out


def _run(args: list[str], timeout: float) -> dict:
    env = dict(os.environ, PYTHONPATH=str(ROOT), MPLBACKEND="Agg")
    t0 = time.perf_counter()
    try:
        p = subprocess.run([sys.executable, "-m", "ltca.cli", *args], capture_output=True, text=True, env=env,
                           timeout=timeout, cwd=str(ROOT), check=False)
        status, err = p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        status, err = "timeout", ""
    lines = [ln for ln in err.splitlines() if ln.strip()]
    msg = next((ln for ln in lines if ln.startswith("ltca ")), lines[-1] if lines else "")
    m = FIELD.search(msg)
    return {"status": status, "message": msg[:300], "field": m.group(1) if m else "",
            "traceback": "Traceback" in err, "warning": bool(re.search(r"Warning\b|warnings.warn", err)),
            "seconds": round(time.perf_counter() - t0, 1)}


def sweep(n: int, out: Path, timeout: float = 900.0, progress=print, only=None) -> list[dict]:
    """Run the first ``n`` pairs of :func:`grid` (or those of them whose index is in ``only``) into ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for g in grid(n):
        if only and g["i"] not in only:
            continue
        case = out / f"pair_{g['i']:02d}.toml"
        case.write_text(CASE.format(**g))
        tca = _run(["tca", str(case), "--out", str(out / f"tca_{g['i']:02d}")], timeout)
        run = _run(["run", str(case), "--out", str(out / f"run_{g['i']:02d}"), "--fidelity", "coarse",
                    "--positions", "5", "--quiet"], timeout)
        row = {k: g[k] for k in ("i", "z1", "z2", "beta", "sigma", "cutter_factor")}
        row.update({f"tca_{k}": v for k, v in tca.items()})
        row.update({f"run_{k}": v for k, v in run.items()})
        row["agree"] = (tca["status"] == 0 and run["status"] == 0) or (tca["status"] == 2 and run["status"] == 2)
        rows.append(row)
        progress(f"{g['i']:2d} z {g['z1']}/{g['z2']} beta {g['beta']:.0f} Sigma {g['sigma']:.0f} "
                 f"rc/Am {g['cutter_factor']:.2f}: tca {tca['status']} run {run['status']} "
                 f"{tca['field'] or run['field']} {'TRACEBACK' if tca['traceback'] or run['traceback'] else ''}"
                 f"{'WARNING' if tca['warning'] or run['warning'] else ''} ({tca['seconds'] + run['seconds']:.0f} s)")
        _write(rows, out)
    return rows


def _write(rows: list[dict], out: Path) -> None:
    with open(out / "sweep.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    ok = sum(r["tca_status"] == 0 and r["run_status"] == 0 for r in rows)
    named = sum(r["agree"] and r["tca_status"] == 2 and bool(r["tca_field"]) for r in rows)
    bad = sum(r["tca_traceback"] or r["run_traceback"] or r["tca_warning"] or r["run_warning"] for r in rows)
    lines = [(f"pairs {len(rows)}: run {ok}, exit 2 naming a field {named}, disagree "
              f"{sum(not r['agree'] for r in rows)}, traceback or warning {bad}"), "",
             "| # | z1/z2 | spiral deg | shaft deg | rc/Am | tca | run | field / message |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['i']} | {r['z1']}/{r['z2']} | {r['beta']:.1f} | {r['sigma']:.1f} | {r['cutter_factor']:.2f} | "
                     f"{r['tca_status']} | {r['run_status']} | {(r['tca_message'] or r['run_message'])[:160]} |")
    (out / "sweep.md").write_text("\n".join(lines) + "\n")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=32)
    ap.add_argument("--out", default="bevel_sweep")
    ap.add_argument("--only", type=int, nargs="*", help="run only these pair indices")
    a = ap.parse_args(argv)
    rows = sweep(a.pairs, Path(a.out), only=a.only)
    print((Path(a.out) / "sweep.md").read_text())
    return 0 if all(not (r["tca_traceback"] or r["run_traceback"]) for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
