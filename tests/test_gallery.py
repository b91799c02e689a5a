"""Every script of the example gallery (``examples/plot_*.py``, the documentation's gallery) runs to its end.

Each runs as ``__main__`` in a fresh Python process (the Monte Carlo study starts Dask worker processes), with
the non-interactive matplotlib backend and this checkout first on the path, in an empty working folder. The scripts assert their own physics (convergence, the trend they
show); here they must exit 0 and draw at least one figure.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("plot_*.py"))

#: runs the script as ``__main__`` and then counts the figures it left open (sphinx-gallery draws those)
RUNNER = """
import runpy, sys
import matplotlib.pyplot as plt
runpy.run_path(sys.argv[1], run_name="__main__")
n = len(plt.get_fignums())
assert n > 0, "the example drew no figure"
print(f"figures: {n}")
"""


def test_the_gallery_has_an_example_per_capability():
    names = {p.stem.split("_", 2)[-1] for p in EXAMPLES}       # plot_<order>_<name>: the gallery's order
    assert {"spur_fzg_c14", "tip_relief_optimisation", "helical_misalignment", "spiral_bevel",
            "planetary_load_sharing", "monte_carlo"} <= names
    for p in EXAMPLES:
        text = p.read_text()
        assert text.startswith('"""'), f"{p.name}: a sphinx-gallery example starts with its title docstring"
        assert "import ltca" in text, f"{p.name}: examples use the public API"


@pytest.mark.heavy
@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(script: Path, tmp_path: Path):
    env = {**os.environ, "MPLBACKEND": "Agg",
           "PYTHONPATH": os.pathsep.join([str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])])}
    proc = subprocess.run([sys.executable, "-c", RUNNER, str(script)], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=1200)
    assert proc.returncode == 0, f"{script.name} failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    assert "figures: " in proc.stdout


def test_plot_pattern_draws_the_torque_asked_for():
    """``ds.ltca.plot_pattern``: the pattern of the nearest torque, flank position across, face (or height) up."""
    import numpy as np
    import xarray as xr

    import ltca.accessor  # noqa: F401  (registers ``ds.ltca``)
    from ltca.figures import subplots
    rng = np.random.default_rng(1)
    cyl = xr.Dataset({"pressure_envelope": (("torque", "flank_roll", "face"), rng.uniform(0, 1500, (2, 4, 3)))},
                     coords={"torque": [100.0, 200.0], "flank_roll": [5.0, 10.0, 15.0, 20.0], "face": [-5.0, 0, 5]})
    ax = cyl.ltca.plot_pattern(torque=190.0, ax=subplots()[1])
    mesh = ax.collections[0]
    want = cyl.pressure_envelope.sel(torque=200.0).values.T          # (face, flank_roll)
    assert np.array_equal(np.asarray(mesh.get_array()).reshape(want.shape), want)
    assert mesh.get_clim() == (0.0, float(want.max()))
    assert "200 N m" in ax.get_title()
    bevel = xr.Dataset({"pattern": (("torque", "Rn", "L"), rng.uniform(0, 1500, (1, 3, 5)))},
                       coords={"torque": [175.0], "Rn": [-1.0, 0.0, 1.0], "L": [70.0, 75, 80, 85, 90]})
    mesh = bevel.ltca.plot_pattern(ax=subplots()[1], vmax=900.0).collections[0]
    assert np.array_equal(np.asarray(mesh.get_array()).reshape(3, 5), bevel.pattern.values[0])
    assert mesh.get_clim() == (0.0, 900.0)
    with pytest.raises(ValueError, match="bearing pattern"):
        xr.Dataset({"te_loaded": ("torque", [1.0])}, coords={"torque": [1.0]}).ltca.plot_pattern()
