"""
Spur pair: loaded TE and bearing pattern (FZG C14)
==================================================

The FZG C14 spur test pair (GEARpie's ``C14`` geometry, shipped as the case ``fzg_c14``) at two pinion torques:
the loaded transmission error over one mesh cycle and the bearing pattern, the largest contact pressure over the
cycle on the pinion flank.
"""
import matplotlib.pyplot as plt

import ltca

case = ltca.load_case("fzg_c14")
result = ltca.run(case, fidelity="coarse", positions=8, torques_nm=[100.0, 200.0])

# %%
# The headline figures per torque are typed (:class:`ltca.TorqueFigures`); the full fields are in
# ``result.dataset`` (an :class:`xarray.Dataset`, torque x position x ...).
for f in result.figures:
    print(f"{f.torque_nm:5.0f} N m: TE ptp {f.te_loaded_ptp_arcsec:5.1f} arcsec, "
          f"flank pressure {f.max_flank_pressure_mpa:6.0f} MPa, "
          f"mesh stiffness {f.mesh_stiffness_mean_n_per_mm_um:5.2f} N/(mm um)")
assert result.converged

# %%
# The loaded TE (the gear's lag behind its rigid position, positive) rises with the torque; the unloaded TE of
# the unmodified involute is zero. The pattern's colour scale stops at the flank peak: the sharp-edge peaks at
# the tip saturate.
fig, (ax_te, ax_pattern) = plt.subplots(1, 2, figsize=(11, 4))
result.dataset.ltca.plot_te(ax=ax_te)
result.dataset.ltca.plot_pattern(torque=200.0, ax=ax_pattern, vmax=result.at(200.0).max_flank_pressure_mpa)
fig.colorbar(ax_pattern.collections[0], ax=ax_pattern, label="contact pressure [MPa]")
fig.tight_layout()
