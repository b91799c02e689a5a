"""What a frozen CalculiX reference records about how it was made, and the shared command-line runner of the
scripts of :mod:`tools.calculix_refs`.

``ccx_version`` names the CalculiX that solved it, ``command_line`` the command that regenerates it, ``finite``
turns a quantity not read (NaN) into JSON null; :func:`run` runs a script's work as ``ltca`` runs a subcommand:
bad arguments (``CaseError``) and a missing ``ccx`` end with exit status 2 and one message, no traceback.
"""
from __future__ import annotations

import argparse
import shlex
import subprocess
import sys
from typing import Callable

import numpy as np

__all__ = ["ccx_version", "command_line", "finite", "run"]


def ccx_version() -> str:
    """The first line of ``ccx -v`` that names the version."""
    from ltca.fem.calculix.run import ccx_path
    out = subprocess.run([ccx_path(), "-v"], capture_output=True, text=True, timeout=30).stdout
    return next((ln.strip() for ln in out.splitlines() if "Version" in ln), out.strip())


def command_line(module: str, argv: list[str]) -> str:
    """The command that regenerates a frozen reference, as typed: ``python3 -m <module> <argv>``."""
    return " ".join(["python3", "-m", module] + [shlex.quote(a) for a in argv])


def finite(v):
    """The record with NaN (a quantity not read) as null: strict JSON."""
    if isinstance(v, dict):
        return {k: finite(x) for k, x in v.items()}
    if isinstance(v, list):
        return [finite(x) for x in v]
    return None if isinstance(v, float) and not np.isfinite(v) else v


def run(parser: argparse.ArgumentParser, work: Callable[[argparse.Namespace], int], argv: list[str] | None) -> int:
    """Parse ``argv`` and run ``work``; a ``CaseError`` or a missing ``ccx`` prints one line and returns 2."""
    from ltca.fem.calculix.run import CcxNotFound
    from ltca.errors import CaseError
    a = parser.parse_args(argv)
    try:
        return work(a)
    except CaseError as exc:
        print(f"{parser.prog}: {exc}", file=sys.stderr)
        return 2
    except CcxNotFound as exc:
        print(f"{parser.prog}: {exc}", file=sys.stderr)
        return 2
