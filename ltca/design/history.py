"""The search history of ``ltca optimise``: every evaluated candidate, kept so that a killed run resumes.

``history.jsonl`` holds one JSON line per finished candidate (the start, each search point, each map point) and per
Harris curve, rewritten atomically after each (:func:`ltca.outputs.write_bytes_atomic`: a kill leaves the file of
the last finished candidate, never a torn one). ``--resume`` reads it back; the search is deterministic (the same
start, the same optimiser, the same function values), so it replays through the candidates on file without
computing them and goes on from the last finished one.
"""
from __future__ import annotations

import json
from pathlib import Path

from ..outputs import finite_json, write_bytes_atomic
from .problem import Evaluation, Measures, score
from .schema import DesignSpec

__all__ = ["History", "FILE"]

FILE = "history.jsonl"


def _key(kind: str, values: dict, extra=()) -> str:
    return json.dumps([kind, sorted((k, float(v)) for k, v in values.items()), list(extra)])


class History:
    """Finished candidates of one optimisation folder, in the order they finished.

    Parameters
    ----------
    out : Path
        The optimisation folder.
    spec : DesignSpec
        The design table (to score records read back).
    resume : bool
        Read the candidates of an interrupted run; otherwise start empty (an earlier file is replaced).
    """

    def __init__(self, out: str | Path, spec: DesignSpec, resume: bool = False):
        self.path = Path(out) / FILE
        self.spec = spec
        self.records: list[dict] = []
        self._index: dict[str, dict] = {}
        self.taken_over = 0          # candidates and curves found on file by this run
        self._on_file: set[str] = set()
        if resume and self.path.is_file():
            for line in self.path.read_text().splitlines():
                try:
                    rec = json.loads(line)
                except ValueError:
                    break            # a torn line cannot happen with atomic rewrites, but an edited file can
                self._keep(rec)
                self._on_file.add(rec["key"])
        else:
            self.path.unlink(missing_ok=True)

    def _keep(self, rec: dict) -> None:
        self.records.append(rec)
        self._index.setdefault(rec["key"], rec)

    def _taken(self, key: str) -> None:
        if key in self._on_file:
            self._on_file.discard(key)
            self.taken_over += 1

    def _write(self) -> None:
        text = "".join(json.dumps(finite_json(r), allow_nan=False) + "\n" for r in self.records)
        write_bytes_atomic(self.path, text.encode())

    # ------------------------------------------------------------------------------------------ candidates
    def evaluation(self, values: dict, role: str, compute) -> Evaluation:
        """The candidate at ``values``: from the file when it was finished before, else ``compute(values)``
        (a :class:`Measures`), scored, recorded under ``role`` (start, search, map) and written."""
        key = _key("candidate", values)
        rec = self._index.get(key)
        if rec is not None:
            self._taken(key)
            return self._evaluation(rec)
        m = compute(values)
        ev = score(self.spec, values, m)
        rec = {"key": key, "n": len(self.records), "role": role, "values": ev.values,
               "te_ptp_arcsec": list(m.te_ptp_arcsec), "flank_pressure_mpa": list(m.flank_pressure_mpa),
               "edge_share": m.edge_share, "objective": ev.objective, "pressure_violation": ev.pressure_violation,
               "edge_violation": ev.edge_violation, "feasible": ev.feasible, "seconds": m.seconds, "cycles": m.cycles,
               "edge_margin_mm": m.edge_margin_mm, "failure": m.failure}
        self._keep(rec)
        self._write()
        return ev

    def _evaluation(self, rec: dict) -> Evaluation:
        nan = float("nan")
        margin = rec.get("edge_margin_mm")
        m = Measures(tuple(nan if x is None else x for x in rec["te_ptp_arcsec"]),
                     tuple(nan if x is None else x for x in rec["flank_pressure_mpa"]), rec["edge_share"],
                     rec["seconds"], rec["cycles"], float("inf") if margin is None else margin, rec.get("failure", ""))
        return score(self.spec, rec["values"], m)

    def curve(self, values: dict, torques_nm, compute) -> list[float]:
        """A Harris curve (TE peak-to-peak, arcsec, at ``torques_nm``) of a design, from the file or computed."""
        key = _key("harris", values, torques_nm)
        rec = self._index.get(key)
        if rec is not None:
            self._taken(key)
        else:
            rec = {"key": key, "n": len(self.records), "role": "harris", "values": dict(values),
                   "torque_nm": list(torques_nm), "te_ptp_arcsec": list(compute(values, torques_nm))}
            self._keep(rec)
            self._write()
        return list(rec["te_ptp_arcsec"])

    def has(self, values: dict, torques_nm=None) -> bool:
        """Whether the candidate at ``values`` (or its Harris curve at ``torques_nm``) is on file."""
        key = _key("candidate", values) if torques_nm is None else _key("harris", values, torques_nm)
        return key in self._index

    def candidates(self, role: str | None = None) -> list[dict]:
        """The candidate records (optionally of one role), in the order they finished."""
        return [r for r in self.records if r["role"] != "harris" and (role is None or r["role"] == role)]
