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

A pair that exits 2 is run again with the value its message names (:func:`suggestions`: the value a bevel design
limit found to work, the largest shaft angle, or the nearest end of a field's range) written into its case; a
message of that run naming another value is applied in turn, up to ``--rounds`` (3) rounds.  "Suggested value
works": that case runs with both commands.

    nice -n 5 python3 tools/bevel_sweep.py --pairs 32 --out /tmp/bevel_sweep
writes ``sweep.csv`` and ``sweep.md`` (the table and the counts) to ``--out``.  On a busy machine
``--suggested-tca-only`` re-runs the suggested cases by ``ltca tca`` alone, and ``--run-suggested`` (same
``--out``) then adds their ``ltca run``.
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
_NUM = r"(-?[0-9.]+(?:e[-+]?[0-9]+)?)"
#: a bevel design limit (ltca.bevel.limits.WorkingValue.words): "'field' = v unit is out of reach ...: w unit works"
_WORKS = re.compile(rf"'([a-z_.]+)' = {_NUM} \S+ is out of reach for this blank: {_NUM} \S+ works")
#: a case field out of its range or past a derived bound: "field 'f' = v: a number in [lo, hi]" / ": at most x"
_RANGE = re.compile(rf"field '([a-z_.]+)' = {_NUM}: a number in [\[(]{_NUM}, {_NUM}[\])]")
_BOUND = re.compile(rf"field '([a-z_.]+)' = {_NUM}: at (most|least) {_NUM}")


def suggestions(message: str) -> dict[str, float]:
    """The case values an exit-2 message names as working: ``{dotted field: value}`` (empty if it names none)."""
    out = {f: float(w) for f, _, w in _WORKS.findall(message)}
    for f, v, lo, hi in _RANGE.findall(message):
        out[f] = min(max(float(v), float(lo)), float(hi))
    for f, _, _, x in _BOUND.findall(message):
        out[f] = float(x)
    return out


def with_values(text: str, values: dict[str, float]) -> str:
    """The case text with each dotted field set (``bevel.working.path_angle_deg`` -> its line in [bevel.working])."""
    for field, v in values.items():
        table, key = field.rsplit(".", 1)
        head = text.index(f"[{table}]\n")
        end = text.find("\n[", head + 1)
        end = len(text) if end < 0 else end
        part, n = re.subn(rf"(?m)^{key} = .*$", f"{key} = {v!r}", text[head:end])
        if n != 1:
            raise KeyError(f"{field} is not in the case")
        text = text[:head] + part + text[end:]
    return text


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
    return {"status": status, "message": msg[:2000], "field": m.group(1) if m else "",
            "traceback": "Traceback" in err, "warning": bool(re.search(r"Warning\b|warnings.warn", err)),
            "seconds": round(time.perf_counter() - t0, 1)}


def _both(case: Path, out: Path, tag: str, timeout: float, skip_run_if=None) -> tuple[dict, dict]:
    """``ltca tca`` and ``ltca run`` (coarse, 5 positions) of one case file; ``run`` is left out (its status None)
    where ``skip_run_if(tca result)`` is true."""
    tca = _run(["tca", str(case), "--out", str(out / f"tca_{tag}")], timeout)
    if skip_run_if is not None and skip_run_if(tca):
        return tca, {"status": None, "message": "", "field": "", "traceback": False, "warning": False, "seconds": 0.0}
    run = _run(["run", str(case), "--out", str(out / f"run_{tag}"), "--fidelity", "coarse", "--positions", "5",
                "--quiet"], timeout)
    return tca, run


def _bad(r: dict) -> bool:
    return bool(r["traceback"] or r["warning"])


def sweep(n: int, out: Path, timeout: float = 900.0, progress=print, only=None, rounds: int = 3,
          suggested_run: bool = True) -> list[dict]:
    """Run the first ``n`` pairs of :func:`grid` (or those of them whose index is in ``only``) into ``out``; a pair
    that exits 2 again with the values its messages name, up to ``rounds`` rounds (``suggested_run`` False: those
    re-runs with ``ltca tca`` alone, the synthesis and unloaded TCA; their run status is then None)."""
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for g in grid(n):
        if only and g["i"] not in only:
            continue
        text = CASE.format(**g)
        case = out / f"pair_{g['i']:02d}.toml"
        case.write_text(text)
        tca, run = _both(case, out, f"{g['i']:02d}", timeout)
        row = {k: g[k] for k in ("i", "z1", "z2", "beta", "sigma", "cutter_factor")}
        row.update({f"tca_{k}": v for k, v in tca.items()})
        row.update({f"run_{k}": v for k, v in run.items()})
        row["agree"] = (tca["status"] == 0 and run["status"] == 0) or (tca["status"] == 2 and run["status"] == 2)
        row.update(suggested="", suggested_rounds=0, suggested_works="", suggested_run="", suggested_message="",
                   suggested_bad=False)
        applied: dict[str, float] = {}
        t2, r2 = tca, run
        for k in range(1, rounds + 1):
            new = suggestions(t2["message"] if t2["status"] == 2 else r2["message"])
            if not new or t2["status"] not in (0, 2) or r2["status"] not in (0, 2, None) or \
                    (t2["status"] == 0 and r2["status"] == 0):
                break
            applied.update(new)
            sug = out / f"pair_{g['i']:02d}_suggested_{k}.toml"
            sug.write_text(with_values(text, applied))
            # a re-run whose tca names a further value goes to the next round without its run (both commands give
            # the same message: the first pass shows it)
            t2, r2 = _both(sug, out, f"{g['i']:02d}_s{k}", timeout,
                           lambda t, k=k: not suggested_run or (k < rounds and t["status"] == 2
                                                                 and bool(suggestions(t["message"]))))
            row.update(suggested=", ".join(f"{f} = {v:g}" for f, v in applied.items()), suggested_rounds=k,
                       suggested_works=t2["status"] == 0 and r2["status"] in (0, None),
                       suggested_run=r2["status"],
                       suggested_message=(t2["message"] or r2["message"])[:300],
                       suggested_bad=row["suggested_bad"] or _bad(t2) or _bad(r2))
        rows.append(row)
        progress(f"{g['i']:2d} z {g['z1']}/{g['z2']} beta {g['beta']:.0f} Sigma {g['sigma']:.0f} "
                 f"rc/Am {g['cutter_factor']:.2f}: tca {tca['status']} run {run['status']} "
                 f"{tca['field'] or run['field']} {'TRACEBACK' if tca['traceback'] or run['traceback'] else ''}"
                 f"{'WARNING' if tca['warning'] or run['warning'] else ''} ({tca['seconds'] + run['seconds']:.0f} s)"
                 + (f"; suggested {row['suggested']}: {'runs' if row['suggested_works'] else 'fails'}"
                    if row["suggested"] else ""))
        _write(rows, out)
    return rows


def _write(rows: list[dict], out: Path) -> None:
    with open(out / "sweep.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    ok = sum(r["tca_status"] == 0 and r["run_status"] == 0 for r in rows)
    named = sum(r["agree"] and r["tca_status"] == 2 and bool(r["tca_field"]) for r in rows)
    valued = sum(r["agree"] and r["tca_status"] == 2 and bool(r["suggested"]) for r in rows)
    works = [r for r in rows if r["suggested"] and r["suggested_works"]]
    first = sum(r["suggested_rounds"] == 1 for r in works)
    bad = sum(r["tca_traceback"] or r["run_traceback"] or r["tca_warning"] or r["run_warning"] or r["suggested_bad"]
              for r in rows)
    lines = [(f"pairs {len(rows)}: run {ok}, exit 2 naming a field {named} (and a value {valued}), disagree "
              f"{sum(not r['agree'] for r in rows)}, traceback or warning {bad} (also in the re-runs)"),
             f"suggested value works: {len(works)} of {valued} (with the first suggestion {first}, "
             f"{len(works) - first} after more rounds; `ltca tca` and `ltca run` both "
             f"{sum(r['suggested_run'] == 0 for r in works)}, `ltca tca` alone "
             f"{sum(r['suggested_run'] is None for r in works)})", "",
             "| # | z1/z2 | spiral deg | shaft deg | rc/Am | tca | run | field / message | suggested | works (tca, run) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['i']} | {r['z1']}/{r['z2']} | {r['beta']:.1f} | {r['sigma']:.1f} | {r['cutter_factor']:.2f} | "
                     f"{r['tca_status']} | {r['run_status']} | {(r['tca_message'] or r['run_message'])[:400]} | "
                     f"{r['suggested']} | {'' if not r['suggested'] else 'yes' if r['suggested_works'] else 'no'}"
                     f"{'' if not r['suggested'] else ' (run not re-run)' if r['suggested_run'] is None else ''} |")
    (out / "sweep.md").write_text("\n".join(lines) + "\n")


def _read(out: Path) -> list[dict]:
    """The rows of ``out/sweep.csv`` with their types (statuses int, flags bool, ``""`` run status None)."""
    def typed(k: str, v: str):
        if v in ("True", "False"):
            return v == "True"
        if k in ("i", "z1", "z2", "suggested_rounds") or (k.endswith("_status") and v.lstrip("-").isdigit()):
            return int(v)
        if k in ("beta", "sigma", "cutter_factor") or k.endswith("_seconds"):
            return float(v)
        if k == "suggested_run":
            return int(v) if v.lstrip("-").isdigit() else None
        return v
    with open(out / "sweep.csv", newline="") as fh:
        return [{k: typed(k, v) for k, v in r.items()} for r in csv.DictReader(fh)]


def run_suggested(out: Path, timeout: float = 900.0, progress=print) -> list[dict]:
    """``ltca run`` of each suggested case whose ``ltca tca`` ran in a sweep with ``suggested_run=False``: the
    rows' run status and "works" updated, ``sweep.csv`` and ``sweep.md`` written again."""
    rows = _read(out)
    for r in rows:
        if not (r["suggested"] and r["suggested_works"] and r["suggested_run"] is None):
            continue
        k = r["suggested_rounds"]
        run = _run(["run", str(out / f"pair_{r['i']:02d}_suggested_{k}.toml"), "--out",
                    str(out / f"run_{r['i']:02d}_s{k}"), "--fidelity", "coarse", "--positions", "5", "--quiet"],
                   timeout)
        r.update(suggested_run=run["status"], suggested_works=run["status"] == 0,
                 suggested_bad=r["suggested_bad"] or _bad(run))
        if run["status"] != 0:
            r["suggested_message"] = run["message"][:300]
        progress(f"{r['i']:2d}: run with {r['suggested']}: {run['status']} ({run['seconds']:.0f} s)")
        _write(rows, out)
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=32)
    ap.add_argument("--out", default="bevel_sweep")
    ap.add_argument("--only", type=int, nargs="*", help="run only these pair indices")
    ap.add_argument("--rounds", type=int, default=3, help="re-runs with the values the messages name")
    ap.add_argument("--suggested-tca-only", action="store_true",
                    help="re-run a pair with the suggested values by `ltca tca` alone (no FE run)")
    ap.add_argument("--run-suggested", action="store_true",
                    help="only `ltca run` the suggested cases of an earlier --suggested-tca-only sweep in --out")
    a = ap.parse_args(argv)
    if a.run_suggested:
        rows = run_suggested(Path(a.out))
    else:
        rows = sweep(a.pairs, Path(a.out), only=a.only, rounds=a.rounds, suggested_run=not a.suggested_tca_only)
    print((Path(a.out) / "sweep.md").read_text())
    return 0 if all(not (r["tca_traceback"] or r["run_traceback"]) for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
