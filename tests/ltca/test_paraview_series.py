"""The ParaView series ``paraview.pvd`` of every gear kind, written by the one writer (:mod:`ltca.paraview`): the
PVD lists the asked number of steps with three parts each, meshio reads every part back, the flank pressure's
peak at each position is the solver's peak there, and the parts sit where the bodies are (the pressure surface
on the pinion body, its loaded bins on the gear body). The cylindrical series is checked in
tests/ltca/cylindrical/test_report_outputs.py, the planetary one in tests/ltca/planetary/test_planetary.py."""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest
from scipy.spatial import cKDTree

import ltca
from ltca.paraview import select_steps, stress_fields, write_series


def test_select_steps_spread_with_the_centre():
    assert select_steps(np.linspace(-1, 1, 5), None).tolist() == [0, 1, 2, 3, 4]
    assert select_steps(np.linspace(-1, 1, 5), 9).tolist() == [0, 1, 2, 3, 4]
    # two spread over 6 positions (first and last), plus the one nearest the centre
    assert select_steps(np.array([-0.5, -0.3, -0.1, 0.1, 0.35, 0.5]), 2, centre=0.3).tolist() == [0, 4, 5]


def test_stress_fields_of_a_uniaxial_and_a_shear_state():
    vm, p = stress_fields(np.array([[100.0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 50.0]]))
    assert vm == pytest.approx([100.0, 50.0 * np.sqrt(3)])
    assert p[0] == pytest.approx([100.0, 0, 0]) and p[1] == pytest.approx([50.0, 0, -50.0])


def test_writer_lists_every_part_of_every_step(tmp_path):
    quad = meshio.Mesh(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float), [("quad", np.array([[0, 1, 2, 3]]))],
                       cell_data={"contact_pressure_mpa": [np.array([7.0], np.float32)]})
    pv = write_series(tmp_path, ((t, [("a", quad), ("b", quad)]) for t in (0.0, 0.5)), "two steps")
    sets = ET.parse(pv["pvd"]).getroot().findall("./Collection/DataSet")
    assert [(s.get("timestep"), s.get("part"), s.get("name")) for s in sets] == [
        ("0", "0", "a"), ("0", "1", "b"), ("0.5", "0", "a"), ("0.5", "1", "b")]
    assert pv["files"] == 5 and pv["timesteps"] == [0.0, 0.5]
    back = meshio.read(tmp_path / sets[-1].get("file"))
    assert back.cell_data["contact_pressure_mpa"][0].tolist() == [7.0]


@pytest.fixture(scope="module")
def bevel_saved(tmp_path_factory):
    case = ltca.load_case("spiral_bevel_cao2008")
    res = ltca.run(case, fidelity="coarse", positions=4, torques_nm=[175.0])
    out = tmp_path_factory.mktemp("bevel_pv") / "o"
    res.save(out, report=False, paraview_steps=3)
    return res, out


@pytest.mark.heavy
def test_bevel_series(bevel_saved):
    res, out = bevel_saved
    sets = ET.parse(out / "paraview.pvd").getroot().findall("./Collection/DataSet")
    steps = sorted({float(s.get("timestep")) for s in sets})
    # 3 steps spread over the 4 positions (cycle -0.5, -0.25, 0, 0.25), the mean point among them
    assert steps == [-0.5, 0.0, 0.25] and len(sets) == 3 * len(steps)
    parts = {(float(s.get("timestep")), s.get("name")): out / s.get("file") for s in sets}
    ds = res.dataset.isel(torque=0)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["paraview"]["cycle"] == steps
    for c in steps:
        pin, gear, flank = (meshio.read(parts[(c, n)]) for n in ("pinion", "gear", "flank"))
        for m in (pin, gear):
            assert {"displacement_mm", "displacement_magnitude_um"} <= set(m.point_data)
            assert {"von_mises_mpa", "principal_stress_mpa"} <= set(m.cell_data)
            assert np.all(np.isfinite(m.cell_data["von_mises_mpa"][0]))
        p = flank.cell_data["contact_pressure_mpa"][0]
        solver = float(ds.max_pressure.sel(position=ds.position[np.argmin(np.abs(ds.cycle.values - c))]))
        assert float(p.max()) == pytest.approx(solver, rel=1e-6)      # float32 of the solver's peak
        # placed where the bodies are: the whole pressure surface on the pinion body as written (cut to the loaded
        # teeth; within a node spacing of its nodes, about 0.45 mm at this fidelity, 0.9 mm at most), its loaded
        # bins on the gear body too, the unloaded far off
        centres = flank.points[flank.cells_dict["quad"]].mean(axis=1)
        to_pinion = cKDTree(pin.points).query(centres)[0]
        assert np.median(to_pinion) < 0.6 and to_pinion.max() < 1.0
        to_gear = cKDTree(gear.points).query(centres)[0]
        assert np.median(to_gear[p > 0]) < 0.6 < np.median(to_gear[p == 0])
