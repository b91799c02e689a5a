"""Reading and writing REXS files in their three forms: XML (``.rexs``), JSON (``.rexsj``, often with a UTF-8
byte-order mark) and zipped (``.rexsz``: a zip archive holding one ``.rexs`` or ``.rexsj`` model and perhaps
external files), REXS 1.x and 2.0, into the one in-memory :class:`ltca.rexs.model.RexsModel`.

The structure follows the REXS specification (spec.rexs.info: model, relations with refs, components with
attributes, load spectrum with load cases; the JSON form names each value by its value type). Values are kept as
read so a model written again keeps every attribute it had.
"""
from __future__ import annotations

import io
import zipfile
from pathlib import Path

from .errors import RexsError
from .json_form import parse_json, to_json
from .model import RexsModel
from .xml_form import parse_xml, to_xml

__all__ = ["read_model", "write_model", "parse_xml", "parse_json", "to_xml", "to_json"]


def read_model(path: str | Path) -> RexsModel:
    """Read a ``.rexs`` (XML), ``.rexsj`` (JSON) or ``.rexsz`` (zip) file; the form is told by the content, not
    the name. A missing, unreadable or malformed file is a :class:`RexsError`."""
    p = Path(path)
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise RexsError(str(p), "-", f"cannot read the file ({exc.strerror or exc})", None) from None
    if data[:2] == b"PK":
        return _read_zip(data, str(p))
    return _parse_bytes(data, str(p))


def _parse_bytes(data: bytes, file: str) -> RexsModel:
    text = data.decode("utf-8-sig", errors="strict") if _utf8(data, file) else ""
    head = text.lstrip()[:1]
    if head == "<":
        return parse_xml(text, file)
    if head == "{":
        return parse_json(text, file)
    raise RexsError(file, "-", "not a REXS model: XML (<model ...>) or JSON ({\"model\": ...}) expected",
                    text[:40])


def _utf8(data: bytes, file: str) -> bool:
    try:
        data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise RexsError(file, "-", f"not UTF-8 text (byte {exc.start})", None) from None
    return True


def _read_zip(data: bytes, file: str) -> RexsModel:
    try:
        zf = zipfile.ZipFile(io.BytesIO(data))
    except zipfile.BadZipFile:
        raise RexsError(file, "-", "a broken zip archive (.rexsz)", None) from None
    names = [n for n in zf.namelist() if n.lower().endswith((".rexs", ".rexsj"))]
    if len(names) != 1:
        raise RexsError(file, "-", f"a .rexsz archive holds exactly one .rexs or .rexsj model; found {names}", None)
    model = _parse_bytes(zf.read(names[0]), f"{file}:{names[0]}")
    model.inner, model.form, model.file = model.form, "zip", file
    model.extra["zip_member"] = names[0]
    model.extra["zip_others"] = {n: zf.read(n) for n in zf.namelist() if n != names[0]}
    return model


def write_model(model: RexsModel, path: str | Path, bom: bool = True) -> Path:
    """Write the model in the form it was read (XML, JSON with a byte-order mark when ``bom``, or zipped with the
    archive's other members kept). Returns the path written."""
    p = Path(path)
    inner = model.inner if model.form == "zip" else model.form
    body = (to_json(model).encode("utf-8") if inner == "json" else to_xml(model).encode("utf-8"))
    if inner == "json" and bom:
        body = b"\xef\xbb\xbf" + body
    if model.form == "zip":
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
            zf.writestr(model.extra.get("zip_member", "model.rexs" if inner == "xml" else "model.rexsj"), body)
            for n, b in model.extra.get("zip_others", {}).items():
                zf.writestr(n, b)
        body = buf.getvalue()
    tmp = p.with_name(p.name + ".tmp")
    tmp.write_bytes(body)
    tmp.replace(p)
    return p
