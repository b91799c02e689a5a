"""Re-evaluate ours on a frozen bevel CalculiX reference: ``python3 -m tools.calculix_refs.recompare_bevel FILE NOTE``.

After a change of our model, our figures at the frozen file's rows are computed again; CalculiX's are kept as
frozen (gmsh's meshes of the same solids differ by some nodes between runs, so a rerun is a new ladder of 15-35 min
per rung). Each row's ``ours`` and its deviations are replaced, and ``recompared`` records when and why (NOTE).
"""
from __future__ import annotations

import datetime
import json
import sys
from pathlib import Path
from types import SimpleNamespace

from ltca.verify.bevel_calculix import bevel_model, compare, ours_at, within_bounds

__all__ = ["recompare", "main"]


def recompare(frozen: str, note: str) -> list[dict]:
    """Our figures at the rows of the frozen reference ``frozen`` again, CalculiX's kept; the file is rewritten with
    ``note`` under ``recompared``. Returns the new rows."""
    path = Path(frozen)
    rec = json.loads(path.read_text())
    case, lm, t_comp = bevel_model(rec["case"])
    rows = []
    for r in rec["rows"]:
        o = ours_at(lm, r["phi1"], rec["torque_nm"])
        c = r["ccx"]
        ccx = SimpleNamespace(theta_arcsec=c["theta"], p_interior=c["p_interior"],
                              share={int(k): v for k, v in c["share"].items()})
        e = compare(o, ccx)
        rows.append({**r, "ours": o, **e, "ok": within_bounds(e)})
    rec["rows"] = rows
    rec["compliance_wall_s"] = t_comp
    rec.setdefault("recompared", []).append({"date": datetime.date.today().isoformat(), "note": note})
    path.write_text(json.dumps(rec, indent=1, default=float) + "\n")
    return rows


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) < 2 or not Path(argv[0]).is_file():
        print("usage: python3 -m tools.calculix_refs.recompare_bevel FILE NOTE (FILE: a frozen bevel reference)",
              file=sys.stderr)
        return 2
    for row in recompare(argv[0], " ".join(argv[1:])):
        print(f"{row['fraction']:.3f}: TE {row['te_err_pct']:+.2f} %, share {row['share_err']:.3f}, "
              f"p {row['p_err_pct']:+.2f} %, ok {row['ok']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
