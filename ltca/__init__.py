"""ltca: finite-element loaded tooth contact analysis of gear pairs (cylindrical, spiral bevel, planetary).

A library first; the ``ltca`` command is a thin layer over it::

    import ltca
    case = ltca.load_case("fzg_c14").with_values({"assembly.lead_misalignment_um": 10.0})
    result = ltca.run(case, torques_nm=[100.0, 200.0])
    result.dataset.ltca.plot_te(ax=ax)
    result.figures[0].te_loaded_ptp_arcsec

Layers: ``ltca.geometry`` (tooth surfaces, kinematics) <- ``ltca.fem`` (meshes, elasticity, compliance, contact)
<- the rest of ``ltca`` (cases, analyses, results, command line). In the repository the two lower layers are the
folders ``geometry/`` and ``fem/`` beside ``ltca/``; the installer maps them to ``ltca.geometry`` and ``ltca.fem``
(setup.py ``package_dir``), and in a source checkout this package's search path reaches them (below). Inside ltca:

    cases.py       the case layer: one Case record for every kind, load_case, with_values
    core.py        run(case) for every gear kind (each kind supplies plan / execute / result / write)
    results.py     LoadedResult, the one result vocabulary, open_result
    accessor.py    plots on a result's dataset (``ds.ltca``)
    driver.py      the run folder of ``ltca run``: lock, run.json, resume, files, console tables
    cli.py         the ``ltca`` command
    cylindrical/, bevel/, planetary/   the gear kinds; drivetrain/, design/, study/, verify/ the other commands
"""
from pathlib import Path as _Path

__version__ = "0.1.0"

_HERE = _Path(__file__).resolve().parent
# A source checkout (tests, editable install): geometry/ and fem/ sit beside ltca/; installed, they are inside it.
if not (_HERE / "geometry").is_dir() and (_HERE.parent / "geometry" / "__init__.py").is_file() \
        and (_HERE.parent / "fem" / "__init__.py").is_file() and (_HERE.parent / "pyproject.toml").is_file():
    __path__.append(str(_HERE.parent))

__all__ = ["Case", "load_case", "run", "tca", "LoadedResult", "TcaResult", "TorqueFigures", "open_result",
           "__version__"]

_LAZY = {"Case": "cases", "load_case": "cases", "run": "core", "tca": "core", "TcaResult": "core",
         "LoadedResult": "results",
         "TorqueFigures": "results", "open_result": "results"}


def __getattr__(name: str):
    """The public API, imported on first use (``ltca --help`` does not import xarray or gmsh)."""
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module 'ltca' has no attribute {name!r}")
