"""Result files of any analysis, written atomically (the generic writer; each analysis builds its own
records, e.g. :mod:`ltca.cylindrical.results`). Imports nothing of ours."""
from __future__ import annotations

import json
from pathlib import Path

__all__ = ["write_json"]


def write_json(path: Path, data: dict) -> None:
    """Write JSON atomically (temporary file, then rename)."""
    tmp = Path(str(path) + ".tmp")
    tmp.write_text(json.dumps(data, indent=2))
    tmp.replace(path)
