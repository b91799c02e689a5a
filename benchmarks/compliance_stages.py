"""Where a loaded analysis spends its time, body by body, beside the figures it computes.

Runs one case through :func:`ltca.run` (nothing written) and prints, for each FE body, its size (nodes, tets, dofs,
and the points of its loaded flank grids) and the seconds of
each compliance stage (mesh, assembly, factorisation, set-up of loads and read-outs, the unit-load solves, the
half-space part), then the contact time and the loaded TE and flank peak of every torque. With ``--against`` a
summary.json of another run (another version of the code, another solver) is read and the differences of those
figures are printed beside them. ``--no-mkl`` hides pypardiso, as on a machine where MKL is not available.

    python benchmarks/compliance_stages.py cases/fzg_c14.toml
    python benchmarks/compliance_stages.py cases/fzg_c14.toml --no-mkl --against out/summary.json

Not installed with the package; prints, asserts nothing.
"""
from __future__ import annotations

import argparse
import json
import logging
import sys
import time


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("case")
    ap.add_argument("--positions", type=int)
    ap.add_argument("--torque", type=float, nargs="+", help="pinion torques, N m")
    ap.add_argument("--fidelity")
    ap.add_argument("--no-mkl", action="store_true", help="make pypardiso unimportable")
    ap.add_argument("--against", help="summary.json of another run: print the differences of its figures")
    args = ap.parse_args(argv)
    if args.no_mkl:
        sys.modules["pypardiso"] = None
    logging.basicConfig(level=logging.INFO, format="  %(name)s: %(message)s")
    t_start = time.perf_counter()
    import ltca
    from ltca.fem import compliance

    bodies = []
    inner = compliance.flank_compliance

    def timed(spec, mesh, *a, **k):
        out = inner(spec, mesh, *a, **k)
        bodies.append((len(mesh.nodes), len(mesh.tets), out.n_dofs, out.C.shape[0],
                       out.factorization.method if out.factorization is not None else "-", dict(out.timings)))
        return out

    from ltca.fem import bevel_compliance
    compliance.flank_compliance = timed
    bevel_compliance.flank_compliance = timed
    t0 = time.perf_counter()
    res = ltca.run(args.case, positions=args.positions, torques_nm=args.torque, fidelity=args.fidelity)
    t_run = time.perf_counter() - t0
    stages = ("mesh", "assembly", "factorisation", "setup", "solves", "half-space")
    print(f"{'body':>4} {'nodes':>7} {'tets':>7} {'dofs':>7} {'grid':>5} {'solver':>8} "
          + " ".join(f"{s:>13}" for s in stages) + f" {'sum':>7}")
    for i, (nn, nt, nd, nl, meth, t) in enumerate(bodies):
        print(f"{i:4d} {nn:7d} {nt:7d} {nd:7d} {nl:5d} {meth:>8} " + " ".join(f"{t.get(s, 0):13.2f}" for s in stages)
              + f" {sum(t.get(s, 0) for s in stages):7.2f}")
    other = None
    if args.against:
        with open(args.against) as f:
            other = json.load(f)
    rows = res.summary.get("torques") or [res.summary]
    ref_rows = (other.get("torques") or [other]) if other else [None] * len(rows)
    print(f"{'torque':>8} {'TE ptp':>10} {'flank peak':>11}" + ("  dTE ptp [%]  dpeak [%]" if other else ""))
    for row, ref in zip(rows, ref_rows):
        te, pk = row["te_loaded_ptp_arcsec"], row["max_flank_pressure_mpa"]
        line = f"{row['torque_nm']:8.1f} {te:10.4f} {pk:11.2f}"
        if ref is not None:
            line += (f"  {100 * (te / ref['te_loaded_ptp_arcsec'] - 1):11.4f} "
                     f"{100 * (pk / ref['max_flank_pressure_mpa'] - 1):10.4f}")
        print(line)
    print(f"run {t_run:.1f} s, process so far {time.perf_counter() - t_start:.1f} s; "
          f"timings {json.dumps(res.timings)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
