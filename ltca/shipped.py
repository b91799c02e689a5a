"""The case and study files shipped with ltca, found by name.

A case argument is a path to a TOML file or the name of a shipped case: its file stem (``"fzg_c14"``) or its
path under the case folder without the suffix (``"crosscheck/fzg_c14_bore20"``). The shipped files live in the
repository's ``cases/`` and ``studies/`` folders, installed as the package data ``ltca/cases`` and
``ltca/studies`` (``setup.py``); in a source checkout or an editable install they are read from the repository.
"""
from __future__ import annotations

from pathlib import Path

from .errors import CaseError

__all__ = ["case_path", "shipped_cases", "study_path", "shipped_studies", "cases_dir", "studies_dir"]

_HERE = Path(__file__).resolve().parent


def _data_dir(name: str) -> Path:
    """``ltca/<name>`` of an installed package, else the repository's ``<name>/`` beside the package."""
    for d in (_HERE / name, _HERE.parent / name):
        if d.is_dir():
            return d
    return _HERE / name


def cases_dir() -> Path:
    """The folder of the shipped case files."""
    return _data_dir("cases")


def studies_dir() -> Path:
    """The folder of the shipped study files."""
    return _data_dir("studies")


def _names(root: Path) -> list[str]:
    return sorted(p.relative_to(root).with_suffix("").as_posix() for p in root.rglob("*.toml"))


def shipped_cases() -> list[str]:
    """Names of the shipped cases (``"fzg_c14"``, ``"crosscheck/fzg_c14_bore20"``, ...), sorted."""
    return _names(cases_dir())


def shipped_studies() -> list[str]:
    """Names of the shipped study files (``"fzg_torque_misalignment"``, ...), sorted."""
    return _names(studies_dir())


def _resolve(name_or_path: str | Path, root: Path, names: list[str], field: str, what: str) -> Path:
    p = Path(name_or_path).expanduser()
    if p.is_file():
        return p
    key = Path(name_or_path).as_posix().removesuffix(".toml")
    for prefix in (f"{root.name}/", f"ltca/{root.name}/"):
        key = key.removeprefix(prefix)
    if key in names:
        return root / f"{key}.toml"
    stems = [n for n in names if n.rsplit("/", 1)[-1] == key]
    if len(stems) == 1:
        return root / f"{stems[0]}.toml"
    raise CaseError(field, str(name_or_path), f"an existing {what} file or the name of a shipped {what}: "
                    + ", ".join(names))


def case_path(name_or_path: str | Path) -> Path:
    """The case file of a path or of a shipped case's name.

    Parameters
    ----------
    name_or_path : str or Path
        A path to an existing file (returned as given), else a shipped case: its stem (``"fzg_c14"``), its name
        under the case folder (``"crosscheck/fzg_c14_bore20"``), with or without ``.toml`` and a leading
        ``cases/``.

    Returns
    -------
    Path
        The file.

    Raises
    ------
    CaseError
        Neither a file nor a shipped case; the message lists the shipped names.
    """
    return _resolve(name_or_path, cases_dir(), shipped_cases(), "CASE", "case")


def study_path(name_or_path: str | Path) -> Path:
    """The study file of a path or of a shipped study's name (as :func:`case_path`)."""
    return _resolve(name_or_path, studies_dir(), shipped_studies(), "STUDY", "study")
