"""
Spiral bevel pair: synthesis, TCA and loaded TE
===============================================

The face-milled spiral bevel pair of Cao et al. (2008) (shipped case ``spiral_bevel_cao2008``): the pinion's
machine settings are synthesised from a contact-path angle and a parabolic unloaded TE, :func:`ltca.tca` gives the
unloaded analysis, and :func:`ltca.run` the loaded contact over one mesh cycle: loaded TE and the bearing pattern
on the gear flank.
"""
import matplotlib.pyplot as plt

import ltca

case = ltca.load_case("spiral_bevel_cao2008")
tca = ltca.tca(case)

# %%
# The synthesis meets its targets on both flanks: the contact-path angle and the parabolic unloaded TE.
for flank, f in tca.summary["flanks"].items():
    goal = f["targets"]
    print(f"{flank:8}: path angle {f['path_angle_deg']:6.2f} deg (target {goal['path_angle_deg']:g}), "
          f"unloaded TE {f['te_amplitude_arcsec']:5.2f} arcsec (target {goal['te_magnitude_arcsec']:g}), "
          f"contact ratio {f['contact_ratio']:.2f}")
    assert abs(f["path_angle_deg"] - goal["path_angle_deg"]) < 0.1

# %%
# The loaded analysis at one torque, coarse and with few positions to keep the example short.
result = ltca.run(case, fidelity="coarse", positions=5, torques_nm=[175.0])
f = result.figures[0]
print(f"{f.torque_nm:g} N m: loaded TE ptp {f.te_loaded_ptp_arcsec:.1f} arcsec (unloaded {f.te_unloaded_ptp_arcsec:.1f}),"
      f" flank pressure {f.max_flank_pressure_mpa:.0f} MPa, root stress pinion {f.max_root_stress_pinion_mpa:.0f} MPa")
assert result.converged

# %%
fig, (ax_te, ax_pattern) = plt.subplots(1, 2, figsize=(11, 4))
result.dataset.ltca.plot_te(ax=ax_te)
result.dataset.ltca.plot_pattern(ax=ax_pattern, vmax=f.max_flank_pressure_mpa)
fig.colorbar(ax_pattern.collections[0], ax=ax_pattern, label="contact pressure [MPa]")
fig.tight_layout()
