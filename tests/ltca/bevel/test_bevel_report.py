"""``report.html`` of a bevel ``ltca run``: written by the kind's write step, self-contained (no external URL, no
script, every image embedded), our results beside the ISO 10300 Method B1 nominal figures of every torque
(the same numbers as :func:`ltca.bevel.iso10300.iso10300_b1`, hand-checked in
tests/ltca/bevel/test_bevel_iso10300.py), and
opened in a real headless Chromium where one is installed. One coarse run at 35 and 175 N m, 4 positions."""
from __future__ import annotations

import json
import re
import shutil
import subprocess

import pytest

from fixtures.paths import ROOT

CASE = ROOT / "cases" / "spiral_bevel_cao2008.toml"
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
PLOT_IDS = ("te", "bearing_pattern", "load_sharing")


@pytest.fixture(scope="module")
def bevel_run(tmp_path_factory):
    from ltca.driver import run_to_dir
    out = tmp_path_factory.mktemp("bevel") / "o"
    head = run_to_dir(str(CASE), str(out), fidelity="coarse", positions=4, torques=[35.0, 175.0], progress=False)
    return out, head


@pytest.mark.slow
def test_bevel_report_is_self_contained_with_iso10300(bevel_run):
    from ltca import load_case
    from ltca.bevel.iso10300 import iso10300_b1
    from ltca.geometry.bevel.blank import design_blank
    out, head = bevel_run
    html = (out / "report.html").read_text(encoding="utf-8")
    srcs = re.findall(r'src="([^"]*)"', html)
    assert len(srcs) == len(PLOT_IDS) and all(s.startswith("data:image/png;base64,") for s in srcs)
    assert "<script" not in html and "http://" not in html and "https://" not in html and "<link rel=\"st" not in html
    for pid in PLOT_IDS:
        assert f'id="plot-{pid}"' in html
    for text in ("ISO 10300 Method B1", "sigma_H0", "sigma_F0", "Z_M-B", "Z_LS", "Y_BS", "Y_Fa", "b_eff = 0.85 b",
                 "l_bm", "Timings", "case file", "Every position converged"):
        assert text in html, text
    # summary.json carries the comparison; its ISO figures are iso10300_b1's of the case's blank at each torque
    saved = json.loads((out / "summary.json").read_text())
    rows = saved["iso10300"]
    assert len(rows) == 6 and {r["torque_nm"] for r in rows} == {35.0, 175.0}
    case = load_case(str(CASE)).record
    bl = design_blank(case.basic)
    for t in (35.0, 175.0):
        by = {r["quantity"].split(",")[0].split(" vs")[0]: r for r in rows if r["torque_nm"] == t}
        rec = next(r for r in saved["torques"] if r["torque_nm"] == t)
        h = by["peak flank pressure (interior)"]
        # the edge radius the run used comes from the cutters; sigma_H0 does not depend on it
        assert h["reference"] == pytest.approx(iso10300_b1(bl, t, case.young, case.poisson).sigma_H0, rel=1e-12)
        assert h["ours"] == rec["max_flank_pressure_mpa"]
        assert f"{h['reference']:.1f}" in html and f"{h['ours']:.1f}" in html
        for member in ("pinion", "gear"):
            f = by[f"{member} root stress"]
            assert f["ours"] == rec["max_root_stress_mpa"][member] and f"{f['reference']:.1f}" in html
            assert 100 < f["reference"] * 175.0 / t < 300          # ~180 MPa at 175 N m (hand calculation)
    print("\n" + "\n".join(f"{r['torque_nm']:g} N m {r['quantity']}: LTCA {r['ours']:.1f}, ISO {r['reference']:.1f} "
                           f"MPa (ratio {r['ratio']:.3f})" for r in rows))


@pytest.mark.slow
@pytest.mark.skipif(CHROMIUM is None, reason="headless Chromium missing: apt-get install -y chromium")
def test_bevel_report_in_headless_chromium(bevel_run, tmp_path):
    out, _ = bevel_run
    page = out / "report.html"
    probe = tmp_path / "probe.html"
    probe.write_text(page.read_text(encoding="utf-8").replace("</body>", """<script>
window.addEventListener("load", () => { const w = Array.from(document.images).map(i => i.naturalWidth);
document.body.setAttribute("data-widths", w.join(",")); });</script></body>"""), encoding="utf-8")
    args = [CHROMIUM, "--headless", "--disable-gpu", "--no-sandbox", "--enable-logging=stderr", "--v=0",
            "--virtual-time-budget=5000", f"--user-data-dir={tmp_path / 'profile'}", "--dump-dom"]
    for target in (page, probe):
        r = subprocess.run(args + [target.as_uri()], capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr[-2000:]
        console = [line for line in r.stderr.splitlines() if "CONSOLE" in line or "Uncaught" in line]
        assert not console, console
        assert r.stdout.count('<img id="plot-') == len(PLOT_IDS)
    widths = [int(w) for w in re.search(r'data-widths="([0-9,]*)"', r.stdout).group(1).split(",")]
    assert len(widths) == len(PLOT_IDS) and min(widths) > 300
