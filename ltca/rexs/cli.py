"""``ltca import``: a REXS stage as a TOML case file, or the list of a model's stages (text for the terminal)."""
from __future__ import annotations

import collections
from pathlib import Path

from .errors import RexsError

__all__ = ["import_command", "stage_table"]


def stage_table(rx) -> list[str]:
    """Lines describing the stages of a :class:`ltca.rexs.RexsImport` and a count of its unmapped attributes."""
    m = rx.model
    lines = [f"{rx.path}: REXS {m.version} ({m.application_id or 'unknown'} {m.application_version or ''}), "
             f"{len(rx.stages)} stage(s)"]
    for s in rx.stages:
        p, g = m.components[s.pinion], m.components[s.gear]
        tq = ", ".join(f"{t:.6g}" for t in s.torques_nm) or "none (give --torque)"
        lines.append(f"  {s.kind} stage {s.id} {s.name or ''!r}: pinion {p.id} ({p.integer('number_of_teeth')} teeth), "
                     f"{'ring' if s.internal else 'gear'} {g.id} ({abs(g.integer('number_of_teeth'))} teeth)"
                     + (f", planetary stage {s.planetary}" if s.planetary is not None else "")
                     + f"; pinion torque {tq} N m")
    by_type = collections.Counter(u.component_type for u in rx.unmapped)
    lines.append(f"  not mapped: {len(rx.unmapped)} attribute(s): "
                 + ", ".join(f"{k} {v}" for k, v in sorted(by_type.items())))
    return lines


def import_command(file: str, stage: int | None, out: str | None, list_only: bool = False,
                   torque: list[float] | None = None) -> int:
    from ..case import to_toml
    from . import read
    rx = read(file)
    if list_only:
        print("\n".join(stage_table(rx)))
        return 0
    if stage is None:
        raise RexsError(file, "--stage", "missing: give the component id of a stage, one of "
                        f"{[s.id for s in rx.stages]} (ltca import FILE --list)", None, file)
    data = rx.stage_dict(stage, torque)
    rx.stage(stage, torque)                         # every check of a case file, before anything is written
    text = to_toml(data) + "\n"
    um = rx.stage_unmapped(stage)
    note = "".join(f"# not mapped: {u.component_type} {u.component} {u.attribute} = {u.value!r:.40} ({u.reason})\n"
                   for u in um)
    text = f"# imported by `ltca import` from {file}, {rx.model.component(stage).type} {stage}\n" + note + text
    if out is None:
        print(text, end="")
    else:
        Path(out).write_text(text, encoding="utf-8")
        print(f"wrote {out} (stage {stage}; {len(um)} attribute(s) of its components not mapped, listed in the file)")
    return 0
