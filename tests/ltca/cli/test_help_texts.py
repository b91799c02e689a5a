"""Help texts: every option of every command has a help; no source-file jargon ("seed" and a three-digit
number) in the README or --help; the CalculiX times of --help are the README's."""
from __future__ import annotations

import argparse
import re

from fixtures.paths import ROOT

README = (ROOT / "docs" / "guide" / "commands.md").read_text(encoding="utf-8")


def _helps():
    from ltca.cli import build_parser
    p = build_parser()
    sub = next(a for a in p._actions if isinstance(a, argparse._SubParsersAction))
    return p, sub.choices


def test_every_option_has_help():
    _, commands = _helps()
    missing = [f"{name} {a.option_strings or a.dest}" for name, c in commands.items() for a in c._actions
               if a.help is None]
    assert not missing, missing


def test_no_seed_jargon_and_calculix_times_agree():
    p, commands = _helps()
    text = p.format_help() + "".join(c.format_help() for c in commands.values())
    flat = " ".join(text.split())
    assert not re.search(r"seed[ -]?0\d\d", README + flat, re.I)
    # the whole-gear CalculiX check: the same minutes per position in the README and in --help
    readme = re.search(r"(\d+-\d+) min per CalculiX run", README).group(1)
    assert f"({readme} min per CalculiX run" in flat
    # the check on our body
    assert "5-15 min per position on 2 cores" in README and "5-15 min per position on 2 cores" in flat


def test_every_option_of_the_tooling_has_help():
    """The scripts of tools/calculix_refs (maintainer tooling, not installed) document every option too."""
    import importlib
    missing = []
    for script in ("freeze_whole", "merge_whole", "freeze_bevel", "freeze_planetary", "ladder_cylindrical"):
        parser = importlib.import_module(f"tools.calculix_refs.{script}").build_parser()
        missing += [f"{script} {a.option_strings or a.dest}" for a in parser._actions if a.help is None]
    assert not missing, missing
