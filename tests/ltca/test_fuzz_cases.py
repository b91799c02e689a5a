"""Seeded fuzz of every shipped case file: >= 300 mutations per run through each command's validation
and, where cheap, the geometry and the unloaded TCA (``ltca tca --positions 3``), ``ltca chain`` and ``ltca budget``
(without its backlash pair, which costs seconds). Fails on any traceback (exit 1), any hang over 20 s and any exit 0
whose outputs hold NaN/inf or lie outside physical bounds. The count per outcome is printed (``-s``).

A second seeded fuzz gives every validated command-line option of every command values good and bad (NaN, inf,
negative, huge, not a number, empty, files that are not folders or not JSON), the commands' work replaced by a stub:
a valid value passes, an invalid one ends in exit 2 with one line (``LTCA_FUZZ_OPTIONS`` values, default 240)."""
from __future__ import annotations

import contextlib
import io
import json
import math
import os
import random
import signal
from collections import Counter
from pathlib import Path

import pytest
import tomllib

from fixtures.paths import CASES
from fixtures.toml_text import dumps
from ltca.cli import main

SEED = int(os.environ.get("LTCA_FUZZ_SEED", 12))
N_MUTATIONS = int(os.environ.get("LTCA_FUZZ_N", 340))
HANG_S = 20


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


@pytest.mark.heavy
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


# ----------------------------------------------------------------------------------- command-line options #
def _num(lo, hi, lo_open=False):
    def ok(text):
        try:
            v = float(text)
        except ValueError:
            return False
        return math.isfinite(v) and (v > lo if lo_open else v >= lo) and v <= hi
    return ok


def _int(lo, hi):
    def ok(text):
        try:
            v = int(text)
        except ValueError:
            return False
        return lo <= v <= hi
    return ok


VALUES = ["nan", "inf", "-inf", "-1", "0", "1", "3", "2.5", "100", "1e6", "1e400", "99999999999", "abc", "",
          "-0.0", "0x10", "1_000", "  7 "]
N_OPTIONS = int(os.environ.get("LTCA_FUZZ_OPTIONS", 240))


def _option_table(tmp: Path) -> list[tuple[str, list[str], str, callable, list[str]]]:
    """(command, argv before the option, option, valid(text), extra values) of every validated option."""
    fzg, study = str(CASES / "fzg_c14.toml"), str(CASES.parent / "studies" / "fzg_torque_misalignment.toml")
    afile = tmp / "afile"
    afile.write_text("x")
    notjson = tmp / "bad.json"
    notjson.write_text("{")
    goodjson = tmp / "good.json"
    goodjson.write_text('{"positions": []}')
    paths = [str(afile), str(tmp / "cache_dir"), str(notjson), str(goodjson), str(tmp / "missing.json")]
    valid_dir = lambda t: t != str(afile) and t not in ("",)      # noqa: E731
    return [
        ("run", [fzg], "--positions", _int(1, 2000), []),
        ("run", [fzg], "--torque", _num(1e-3, 1e6), []),
        ("run", [fzg], "--max-output-gb", _num(0, 1e4, lo_open=True), []),
        ("run", [fzg], "--paraview-steps", _int(0, 100000), []),
        ("run", [fzg], "--cache", valid_dir, paths[:2]),
        ("tca", [fzg], "--positions", _int(1, 2000), []),
        ("study", [study], "--workers", _int(1, 256), []),
        ("study", [study], "--scheduler", lambda t: False, ["tcp://", "tcp://a b:1", "tcp://127.0.0.1:0",
                                                           "tcp://[::1:80", "x" * 600]),
        ("optimise", [str(CASES / "fzg_c14_optimise.toml")], "--workers", _int(1, 256), []),
        ("bench", [fzg], "--repeat", _int(1, 1000), []),
        ("validate", ["--reference", "calculix"], "--threads", _int(1, 256), []),
        ("validate", ["--reference", "calculix"], "--level", _int(0, 8), []),
        ("validate", ["--reference", "calculix"], "--band", _num(0, 1e4, lo_open=True), []),
        ("validate", ["--reference", "calculix"], "--torque", _num(0, 1e6, lo_open=True), []),
        ("validate", ["--reference", "calculix"], "--positions", _num(-360, 360), []),
    ]


def test_fuzz_command_line_options(tmp_path, monkeypatch, capsys):
    """Seeded: random values for every validated option of every command, the command's work replaced by a stub
    (only the validation runs). A valid value must pass (exit 0), an invalid one must end in exit 2 with one line;
    no traceback, no silent acceptance of NaN, inf, negative or absurd values."""
    import ltca.cli as cli
    monkeypatch.chdir(tmp_path)          # a relative --cache value ("0", "abc") is a folder made in the cwd
    for name in ("_cmd_run", "_cmd_tca", "_cmd_study", "_cmd_optimise", "_cmd_bench", "_cmd_validate"):
        monkeypatch.setattr(cli, name, lambda a: 0)
    rng = random.Random(SEED)
    table = _option_table(tmp_path)
    counts: Counter = Counter()
    failures = []
    for i in range(N_OPTIONS):
        cmd, head, opt, valid, extra = table[i % len(table)]
        value = rng.choice(VALUES + extra)
        argv = [cmd, *head, opt, value] + ([] if cmd == "bench" else ["--out", str(tmp_path / f"o{i}")])
        status, out, err = _run(argv)
        ok = valid(value)
        lines = err.strip().splitlines()
        if status == 0:
            counts["exit 0"] += 1
            if not ok:
                failures.append(f"{opt} {value!r}: accepted (exit 0)")
        elif status == 2:
            counts["exit 2"] += 1
            if ok:
                failures.append(f"{opt} {value!r}: refused although valid: {err.strip()[:200]}")
            if len(lines) != 1 or "Traceback" in err:
                failures.append(f"{opt} {value!r}: exit 2 message not one line: {err[:300]!r}")
        else:
            counts[f"exit {status}"] += 1
            failures.append(f"{opt} {value!r}: exit {status}: {err[-400:]!r}")
    with capsys.disabled():
        print(f"\noption fuzz (seed {SEED}, {N_OPTIONS} values over {len(table)} options): {dict(counts)}")
    assert not failures, "\n".join(failures[:20])
