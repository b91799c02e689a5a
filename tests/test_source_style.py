"""The source says what, not when: no product module or test cites an issue, a source-file seed or a session.

A docstring or comment cites a paper by author, year and equation, never a tracker or a work log; a test is named
after what it checks. Scanned: every ``.py`` file under ``geometry/``, ``fem/``, ``ltca/``, ``tests/`` and ``tools/``
(whole text: docstrings, comments and messages alike), and the test file and function names. Runs in milliseconds.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("geometry", "fem", "ltca", "tests", "tools")

#: what a citation of the project's history looks like, matched on the lower-cased text, with a name for the failure
#: message and the characters that must not precede a match (a word boundary, and for "#NN" no HTML entity "&#13;",
#: URL fragment "/#12" or "##"). Each pattern starts with a literal so that the scan takes milliseconds.
PATTERNS = {
    "issue number": (re.compile(r"issues?\s+#?\d+"), r"\w"),
    "'#NN' reference": (re.compile(r"#\d{1,4}\b"), r"[\w&#/]"),
    "seed number": (re.compile(r"seeds?[\s_-]*0\d\d\b|seeds/\d{3}"), r"\w"),
    "session number": (re.compile(r"sessions?\s+\d+"), r"\w"),
    "test named after an issue": (re.compile(r"def\s+test\w*issue"), r"\w"),
}


def _sources() -> list[Path]:
    """The scanned files; this one is left out (it spells out the citations it looks for)."""
    here = Path(__file__).resolve()
    return sorted(p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py") if p.resolve() != here)


def citations(text: str) -> list[tuple[int, str, str]]:
    """(line number, pattern name, matched text) of every history citation in ``text``."""
    low = text.lower()
    found = []
    for name, (rx, not_after) in PATTERNS.items():
        for m in rx.finditer(low):
            if m.start() == 0 or not re.match(not_after, low[m.start() - 1]):
                found.append((low.count("\n", 0, m.start()) + 1, name, text[m.start():m.end()]))
    return sorted(found)


@pytest.mark.parametrize("text", [
    "see issue 18", "Issues 11, 18", "(issue #13)", "fixed in #13.", "as in seed 000", "Seed 004 Eq. 3",
    "shared/seeds/003_*.txt", "the seed-002 method", "searched in sessions 9-11", "def test_issue12_why():",
])
def test_citations_are_found(text):
    assert citations(text), text


@pytest.mark.parametrize("text", [
    'color="#1f77b4"', "c = '#ff0000'", "# 1. first item", "&#13;", "url/#12", "rng = default_rng(seed=3)",
    "SEED = SatelliteSeed()", "scope='session'", "Cao et al. 2008, Eq. 8", "ISO 6336-3:2006", "a tissue 3 mm thick",
])
def test_legitimate_text_passes(text):
    assert not citations(text), citations(text)


def test_no_history_citations_in_the_source():
    sources = _sources()
    assert len(sources) > 100, "the package folders were not found"
    bad = [f"{p.relative_to(ROOT)}:{line}: {name}: {hit!r}"
           for p in sources for line, name, hit in citations(p.read_text(encoding="utf-8"))]
    bad += [f"{p.relative_to(ROOT)}: test file named after an issue" for p in sources if "issue" in p.stem.lower()]
    assert not bad, "history belongs in commit messages and the changelog:\n" + "\n".join(bad)
