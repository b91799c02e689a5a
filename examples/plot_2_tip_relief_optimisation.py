"""
Tip relief optimisation (FZG C14)
=================================

The linear tip relief of least loaded TE: :func:`ltca.design.optimise` searches the ``[design]`` variables of a
case (here the shipped ``fzg_c14_optimise``: the amount and the length of a tip relief on pinion and gear, the
flank pressure held below a limit) with a derivative-free optimiser, each candidate a loaded analysis on one
compliance computed once. The shipped case allows 20 candidates and maps the objective; this one is cut to a few
candidates, no map and two Harris torques, so that it runs in a short time.
"""
import json
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import ltca
from ltca.design import optimise

case = ltca.load_case("fzg_c14_optimise").with_values({
    "analysis.positions": 6, "design.max_evaluations": 6, "design.map_points": 0,
    "design.harris_torque_nm": [100.0, 200.0]})

with tempfile.TemporaryDirectory() as tmp:
    case_file = Path(tmp) / "case.toml"
    case_file.write_text(case.to_toml())
    found = optimise(str(case_file), str(Path(tmp) / "out"), progress=False, full_runs=False, workers=1)
    summary = found.summary
    history = [json.loads(line) for line in (found.out / "history.jsonl").read_text().splitlines() if line]

# %%
# The optimum beside the baseline (the case as written: no tip relief), and the search's candidates.
for v in summary["variables"]:
    print(f"{v['name']:22} ({v['unit']}): baseline {v['baseline']:6.2f}, optimum {v['optimum']:6.2f}")
base, best = summary["baseline"], summary["optimum"]
print(f"objective (loaded TE ptp at 200 N m): baseline {base['objective_arcsec']:.2f}, "
      f"optimum {best['objective_arcsec']:.2f} arcsec")
assert best["feasible"] and best["objective_arcsec"] < base["objective_arcsec"]

# %%
# Left: the loaded TE peak-to-peak against the torque (Harris map) of both designs; right: the objective of each
# candidate in the order the optimiser tried them.
harris = summary["harris"]
fig, (ax_h, ax_s) = plt.subplots(1, 2, figsize=(11, 4))
for name in ("baseline", "optimum"):
    ax_h.plot(harris["torque_nm"], harris[name], "o-", label=name)
ax_h.set(xlabel="pinion torque [N m]", ylabel="loaded TE peak-to-peak [arcsec]", title="Harris map")
ax_h.legend()
ax_h.grid(alpha=0.3)
tried = [h for h in history if h.get("role") in ("start", "search")]
n = range(1, len(tried) + 1)
ax_s.plot(n, [h["objective"] for h in tried], "-", color="0.6")
for feasible, marker, label in ((True, "o", "feasible"), (False, "x", "infeasible: a constraint violated")):
    ax_s.plot([k for k, h in zip(n, tried) if h["feasible"] == feasible],
              [h["objective"] for h in tried if h["feasible"] == feasible], marker, ls="none", label=label)
ax_s.set(xlabel="candidate", ylabel="loaded TE peak-to-peak [arcsec]", title="search history")
ax_s.legend()
ax_s.grid(alpha=0.3)
fig.tight_layout()
