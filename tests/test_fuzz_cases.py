"""Seeded fuzz of every shipped case file: >= 300 mutations per run through each command's validation
and, where cheap, the geometry and the unloaded TCA (``ltca tca --positions 3``), ``ltca chain`` and ``ltca budget``
(without its backlash pair, which costs seconds). Fails on any traceback (exit 1), any hang over 20 s and any exit 0
whose outputs hold NaN/inf or lie outside physical bounds. The count per outcome is printed (``-s``)."""
from __future__ import annotations

import contextlib
import io
import json
import math
import os
import random
import signal
import tomllib
from collections import Counter
from pathlib import Path


from conftest import CASES
from ltca.cli import main

SEED = int(os.environ.get("LTCA_FUZZ_SEED", 12))
N_MUTATIONS = int(os.environ.get("LTCA_FUZZ_N", 340))
HANG_S = 20


# ------------------------------------------------------------------------------------ a small TOML writer #
def _val(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_val(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_val(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def dumps(doc: dict, prefix: str = "") -> str:
    lines, tables, arrays = [], [], []
    for k, v in doc.items():
        key = json.dumps(k)
        if isinstance(v, dict) and v and all(isinstance(x, (dict, list)) or True for x in v.values()):
            tables.append((key, v))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            arrays.append((key, v))
        else:
            lines.append(f"{key} = {_val(v)}")
    out = "\n".join(lines) + "\n"
    for key, v in tables:
        name = f"{prefix}{key}"
        out += f"\n[{name}]\n" + dumps(v, name + ".")
    for key, v in arrays:
        name = f"{prefix}{key}"
        for item in v:
            out += f"\n[[{name}]]\n" + dumps(item, name + ".")
    return out


# -------------------------------------------------------------------------------------------- mutations #
def _paths(x, path=()):
    """Every (container, key) of the document: leaves and tables alike."""
    if isinstance(x, dict):
        for k, v in x.items():
            yield x, k, path + (k,)
            yield from _paths(v, path + (k,))
    elif isinstance(x, list):
        for i, v in enumerate(x):
            if isinstance(v, (dict, list)):
                yield from _paths(v, path + (i,))
            else:
                yield x, i, path + (i,)


KINDS = ["delete", "string", "table", "list", "bool", "zero", "negative", "tiny", "huge", "nan", "inf", "-inf",
         "unknown_key", "unknown_table", "nested", "non_utf8", "scale_up", "scale_down", "float_for_int"]


def mutate(text: str, rng: random.Random) -> tuple[str, bytes]:
    doc = tomllib.loads(text)
    kind = rng.choice(KINDS)
    if kind == "non_utf8":
        b = text.encode()
        i = rng.randrange(len(b))
        return kind, b[:i] + rng.choice([b"\xff", b"\xc3\x28", b"\xe2\x82", b"\x80\x80"]) + b[i:]
    if kind == "nested":
        depth = rng.choice([12, 200, 3000])
        return kind, (text + f"\n[fuzz_nest]\nv = {'[' * depth}1{']' * depth}\n").encode()
    spots = list(_paths(doc))
    cont, key, path = rng.choice(spots)
    v = cont[key]
    num = isinstance(v, (int, float)) and not isinstance(v, bool)
    if kind == "delete":
        del cont[key]
    elif kind == "unknown_key":
        tables = [c for c, k, p in spots if isinstance(c, dict)] + [doc]
        rng.choice(tables)["fuzz_key"] = 1.0
    elif kind == "unknown_table":
        tables = [c[k] for c, k, p in spots if isinstance(c[k], dict)] + [doc]
        rng.choice(tables)["fuzz_table"] = {"a": 1}
    else:
        new = {"string": "x", "table": {"a": 1}, "list": [1, 2], "bool": True, "zero": 0,
               "negative": -v if num else -1, "tiny": 1e-300, "huge": 1e300, "nan": float("nan"),
               "inf": float("inf"), "-inf": float("-inf"),
               "scale_up": v * 1000 if num else v, "scale_down": v / 1000 if num else v,
               "float_for_int": float(v) if isinstance(v, int) and not isinstance(v, bool) else 16.5}[kind]
        cont[key] = new
    return kind, dumps(doc).encode()


# --------------------------------------------------------------------------------------- bounds of output #
def _finite(x) -> bool:
    if isinstance(x, float):
        return math.isfinite(x)
    if isinstance(x, dict):
        return all(_finite(v) for v in x.values())
    if isinstance(x, list):
        return all(_finite(v) for v in x)
    return True


def _check_tca_summary(path: Path) -> str | None:
    head = json.loads(path.read_text(), parse_constant=lambda c: float(c))   # NaN would parse: caught below
    if not _finite(head):
        return "NaN/inf in summary.json"
    if not 1.0 <= head["contact_ratio_transverse"] + head["contact_ratio_overlap"] <= 10:
        return f"contact ratio {head['contact_ratio_transverse']}"
    if not 0 <= head["te_unloaded_ptp_arcsec"] < 3600:
        return f"TE ptp {head['te_unloaded_ptp_arcsec']}"
    return None


def _check_text(out: str) -> str | None:
    low = out.lower()
    for bad in (" nan", "nan ", " inf", "e+1", "e+2", "e+3"):
        if bad in low:
            return f"absurd number in output ({bad.strip()})"
    return None


def _command(kind: str, path: Path, outdir: Path) -> tuple[list[str], callable]:
    if kind == "cyl":
        return ["tca", str(path), "--positions", "3", "--out", str(outdir)], lambda o: _check_tca_summary(
            outdir / "summary.json")
    if kind == "bevel":
        return ["bevel-validate", str(path)], lambda o: None
    if kind == "forming":                      # the planetary case: its reader and the three forming methods
        return ["forming", str(path), "--out", str(outdir)], _check_text
    return [kind, str(path)], _check_text


class _Hang(Exception):
    pass


def _alarm(signum, frame):
    raise _Hang()


def _run(argv: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        if argv[0] == "bevel-validate":      # the bevel TCA costs 15 s: the fuzz goes through its validation
            from ltca.bevel.case import load_bevel_case
            from ltca.errors import CaseError
            try:
                load_bevel_case(argv[1])
                status = 0
            except CaseError as exc:
                print(f"ltca tca: error: {exc}", file=err)
                status = 2
            except Exception as exc:     # noqa: BLE001
                from ltca.cli import _unexpected
                status = _unexpected("tca", exc)
        else:
            try:
                status = main(argv)
            except SystemExit as exc:    # argparse
                status = int(exc.code or 0)
    return status, out.getvalue(), err.getvalue()


def _bases() -> list[tuple[str, str, str]]:
    out = []
    for p in sorted(CASES.glob("*.toml")):
        text = p.read_text()
        doc = tomllib.loads(text)
        if "bevel" in doc:
            out.append((p.name, "bevel", text))
        elif "member" in doc:
            doc.pop("backlash", None)          # the backlash pair runs a TCA of a revolution: seconds
            out.append((p.name, "budget", dumps(doc)))
        elif "chain" in doc:
            out.append((p.name, "chain", text))
        elif "satellite" in doc:
            out.append((p.name, "forming", text))
        else:
            out.append((p.name, "cyl", text))
    return out


def test_fuzz_shipped_cases(tmp_path, capsys):
    rng = random.Random(SEED)
    bases = _bases()
    counts: Counter = Counter()
    failures = []
    old = signal.signal(signal.SIGALRM, _alarm)
    try:
        for i in range(N_MUTATIONS):
            name, kind, text = bases[i % len(bases)]
            how, data = mutate(text, rng)
            path = tmp_path / f"m{i:04d}.toml"
            path.write_bytes(data)
            argv, check = _command(kind, path, tmp_path / f"o{i:04d}")
            signal.alarm(HANG_S)
            try:
                status, out, err = _run(argv)
            except _Hang:
                failures.append(f"{name} {how}: hang > {HANG_S} s")
                counts["hang"] += 1
                continue
            finally:
                signal.alarm(0)
            if status == 0:
                bad = check(out)
                if bad:
                    failures.append(f"{name} {how}: exit 0 with {bad}")
                    counts["exit 0, absurd output"] += 1
                else:
                    counts["exit 0"] += 1
            elif status == 2:
                line = err.strip().splitlines()
                if len(line) != 1 or "Traceback" in err or len(line[0]) > 600:
                    failures.append(f"{name} {how}: exit 2 message not one short line: {err[:300]!r}")
                counts["exit 2"] += 1
            elif status == 3:
                counts["exit 3"] += 1
            else:
                counts[f"exit {status} (traceback)"] += 1
                failures.append(f"{name} {how}: exit {status}: {err[-600:]!r}")
    finally:
        signal.signal(signal.SIGALRM, old)
    with capsys.disabled():
        print(f"\nfuzz (seed {SEED}, {N_MUTATIONS} mutations of {len(bases)} case files): {dict(counts)}")
    assert sum(counts.values()) >= 300
    assert not failures, "\n".join(failures[:20])
