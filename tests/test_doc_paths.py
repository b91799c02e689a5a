"""Every test file the documentation, the package, the tooling and the case files name by its path exists: the tests
mirror the package (``tests/geometry``, ``tests/fem``, ``tests/ltca``) and a moved test leaves no stale pointer.

The change log is history and is not scanned. Runs in milliseconds."""
from __future__ import annotations

import re

from fixtures.paths import ROOT

#: a test file named by its path from the repository root (wildcards are patterns, not files)
PATH = re.compile(r"tests/[\w/]*test_\w+\.py")
SCANNED = ("README.md", "docs", "geometry", "fem", "ltca", "tools", "cases", "tests")


def _texts():
    for top in SCANNED:
        root = ROOT / top
        files = [root] if root.is_file() else sorted(p for ext in ("*.md", "*.py", "*.toml") for p in root.rglob(ext))
        yield from files


def test_named_test_files_exist():
    files = list(_texts())
    assert len(files) > 100, "the repository's folders were not found"
    stale = [f"{p.relative_to(ROOT)}: {m.group(0)}" for p in files
             for m in PATH.finditer(p.read_text(encoding="utf-8")) if not (ROOT / m.group(0)).is_file()]
    assert not stale, "test files named by a path that does not exist:\n" + "\n".join(stale)
