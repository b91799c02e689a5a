"""REXS, the gear industry's exchange format (FVA): gear stages in as cylindrical or bevel cases, results out as
REXS result components.

    model.py     the in-memory model: components, attributes with units, relations, load cases
    io.py        reading and writing a file in its form: XML (.rexs, xml_form.py), JSON (.rexsj, json_form.py), zip (.rexsz)
    units.py     declared units -> mm, deg, N m, MPa
    train.py     a stage's related components (flanks, tools, material, shaft) and the torques through the train
    stages.py    cylindrical stages (and the sun-planet / planet-ring pairs of a planetary stage) -> case dicts
    bevel_stage.py  bevel stages -> the blank of a bevel case
    results.py   our results -> REXS result attributes and components
    schema.py    a checker of attribute ids, units and value types against the REXS 2.0.0 schema
    errors.py    RexsError (a CaseError: exit status 2 from the command line)

    >>> rx = ltca.rexs.read("gearbox.rexs")
    >>> [s.id for s in rx.stages]; case = rx.stage(19)     # a validated CylindricalCase
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..case import parse_case
from .errors import RexsError
from .io import read_model, write_model
from .model import RexsModel
from .stages import StageInfo, Unmapped, stage_case_dict, stage_infos

__all__ = ["read", "export_results", "RexsImport", "StageInfo", "Unmapped", "RexsError", "read_model", "write_model"]


@dataclass(frozen=True)
class RexsImport:
    """A REXS file read: the model, its stages, and every attribute no stage's case represents.

    ``unmapped`` lists, for the whole model, each attribute of a stage's components the case cannot hold (with the
    reason) and each attribute of every component no stage reads (shafts, bearings, lubricant, ...)."""
    path: str
    model: RexsModel
    stages: tuple[StageInfo, ...]
    unmapped: tuple[Unmapped, ...] = field(repr=False)
    mapped: frozenset[tuple[int, str]] = field(repr=False, default=frozenset())

    def info(self, stage_id: int) -> StageInfo:
        for s in self.stages:
            if s.id == int(stage_id):
                return s
        raise RexsError("model", "stage", f"no stage {stage_id}; the stages are "
                        f"{[s.id for s in self.stages]}", stage_id, self.path)

    def stage_dict(self, stage_id: int, torque_nm: float | list[float] | None = None) -> dict:
        """The case dict of a stage, as a TOML case file gives it (``ltca.case.to_toml`` writes it)."""
        return stage_case_dict(self.model, int(stage_id), self.info(stage_id), torque_nm)[0]

    def stage_unmapped(self, stage_id: int) -> tuple[Unmapped, ...]:
        """The attributes of the stage's components its case cannot represent."""
        return tuple(stage_case_dict(self.model, int(stage_id), self.info(stage_id), 1.0)[1])

    def stage(self, stage_id: int, torque_nm: float | list[float] | None = None):
        """The stage as a validated :class:`ltca.cases.Case` (every check of a TOML case applies):
        ``ltca.run(ltca.rexs.read(path).stage(3))``."""
        from ..cases import case_from_data
        return case_from_data(self.stage_dict(stage_id, torque_nm), file=self.path)

    def stage_record(self, stage_id: int, torque_nm: float | list[float] | None = None):
        """The stage's typed record (internal units) as :meth:`stage` validates it: a
        :class:`ltca.case.CylindricalCase`, or for a bevel stage its bevel record."""
        if self.info(stage_id).kind == "cylindrical":
            return parse_case(self.stage_dict(stage_id, torque_nm), file=self.path)
        return self.stage(stage_id, torque_nm).record


def read(path: str | Path) -> RexsImport:
    """Read a REXS model (``.rexs``, ``.rexsj`` or ``.rexsz``; REXS 1.x or 2.0) and map its cylindrical stages."""
    model = read_model(path)
    infos = tuple(stage_infos(model))
    unmapped, read_ids, mapped = [], set(), set()
    for s in infos:
        try:
            _, um, ids = stage_case_dict(model, s.id, s, list(s.torques_nm) or 1.0)
        except RexsError as exc:                # that stage is refused when asked for; the others still import
            unmapped.append(Unmapped(s.id, model.components[s.id].type, "-", None, None, f"not mappable: {exc}"))
            continue
        unmapped += [u for u in um if u.attribute != "torque"]
        read_ids |= ids
        left = {(u.component, u.attribute) for u in um}
        mapped |= {(c, a) for c in ids for a in model.components[c].attributes if (c, a) not in left}
    for c in model.of_type("external_load"):       # the torques reach the stages' load keys
        for a in ("torque_around_u_axis", "defines_torque"):
            if c.has(a) and any(s.torques_nm for s in infos):
                mapped.add((c.id, a))
    seen = {(u.component, u.attribute) for u in unmapped}
    unmapped = [u for i, u in enumerate(unmapped) if (u.component, u.attribute) not in
                {(v.component, v.attribute) for v in unmapped[:i]}]
    for c in model.components.values():
        if c.id in read_ids:
            continue
        for a in c.attributes.values():
            if (c.id, a.id) not in seen and (c.id, a.id) not in mapped:
                unmapped.append(Unmapped(c.id, c.type, a.id, a.value if not hasattr(a.value, "tag") else "<coded>",
                                         a.unit, f"{c.type} is not part of a gear pair's case"))
    for lc in model.load_cases:
        for c in lc.components.values():
            for a in c.attributes.values():
                if not (c.type == "external_load" and a.id == "torque_around_u_axis"):
                    unmapped.append(Unmapped(c.id, c.type, a.id, a.value, a.unit,
                                             f"load case {lc.id}: only the torques are mapped"))
    return RexsImport(str(path), model, infos, tuple(unmapped), frozenset(mapped))


def export_results(path: str | Path, stage_id: int, run_dir: str | Path, out: str | Path,
                   torque_nm: float | None = None) -> Path:
    """Write the results of ``ltca run`` (``run_dir``/results.nc, the torque ``torque_nm`` or the first) of stage
    ``stage_id`` of the REXS model ``path`` into that model, saved as ``out`` in the form it was read."""
    import xarray as xr

    from .results import results_from_dataset, write_results
    rx = read(path)
    info = rx.info(stage_id)
    case = rx.stage(stage_id)
    nc = Path(run_dir) / "results.nc"
    if not nc.is_file():
        raise RexsError(str(run_dir), "results.nc", "missing: the output folder of `ltca run` expected", None)
    with xr.open_dataset(nc) as ds:
        res = results_from_dataset(ds.load(), case, torque_nm)
    write_results(rx.model, int(stage_id), info.pinion, info.gear, res, case.gear.teeth / case.pinion.teeth)
    return write_model(rx.model, out)
