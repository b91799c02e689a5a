"""``ltca chain`` prints no nan: the fp column of the envelope chains, whose source prints only F per
element (fi' and Fpr are lost, so fp = Fpr / z is unknown), shows '-' with a note, and the CSV leaves the cell
empty."""
from __future__ import annotations

import csv

import pytest

from fixtures.paths import CASES


def test_chain_prints_no_nan(tmp_path, capsys):
    from ltca.cli import main
    assert main(["chain", str(CASES / "chain_zftkk250.toml"), "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    assert "nan" not in text.lower() and "inf" not in text.lower().replace("information", "")
    assert "fp '-': the source gives only F" in text
    rows = [r for f in sorted(tmp_path.glob("chain_*.csv")) for r in csv.DictReader(f.open())]
    assert rows and not any("nan" in v.lower() for r in rows for v in r.values())
    env = [r for f in sorted(tmp_path.glob("chain_envelope_*.csv")) for r in csv.DictReader(f.open())]
    assert env and sum(r["fp_um"] == "" for r in env) >= 10
    # the indexing chains keep their numbers (guarded): L2 rack fp = 4.706 um
    idx = list(csv.DictReader((tmp_path / "chain_indexing_z1.csv").open()))
    assert float(idx[0]["fp_um"]) == pytest.approx(4.706, rel=1e-3)
