"""
Helical pair: lead misalignment
===============================

The helical C14-like pair (shipped case ``helical_c14``) aligned and with 20 um of lead misalignment in the plane
of action (``assembly.lead_misalignment_um``, ISO 6336's f_ma). The misalignment moves the bearing pattern to one
end of the face and raises the peak pressure; :meth:`ltca.Case.with_values` edits the case by its dotted keys, in
the file's units, and validates the copy.
"""
import tempfile

import matplotlib.pyplot as plt

import ltca

aligned = ltca.load_case("helical_c14")
misaligned = aligned.with_values({"assembly.lead_misalignment_um": 20.0})

# %%
# Both runs share one mesh cache folder: the misalignment does not change the gear bodies, so the second run
# reads the meshes the first one wrote.
with tempfile.TemporaryDirectory() as cache:
    results = {label: ltca.run(case, fidelity="coarse", positions=4, torques_nm=[200.0], cache=cache)
               for label, case in (("aligned", aligned), ("20 um misalignment", misaligned))}

for label, r in results.items():
    f = r.figures[0]
    print(f"{label:20}: TE ptp {f.te_loaded_ptp_arcsec:5.2f} arcsec, mean TE {f.te_loaded_mean_arcsec:5.1f} arcsec, "
          f"flank pressure {f.max_flank_pressure_mpa:5.0f} MPa")
assert results["20 um misalignment"].figures[0].max_flank_pressure_mpa > results["aligned"].figures[0].max_flank_pressure_mpa

# %%
# The bearing patterns on one colour scale (the larger flank peak). Each is the envelope of the contact lines
# of the positions run: four here, so the lines stand apart; the case's own 30 positions fill the flank.
top = max(r.figures[0].max_flank_pressure_mpa for r in results.values())
fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
for ax, (label, r) in zip(axes, results.items()):
    r.dataset.ltca.plot_pattern(ax=ax, vmax=top)
    ax.set_title(label)
fig.colorbar(axes[1].collections[0], ax=axes, label="contact pressure [MPa]")
