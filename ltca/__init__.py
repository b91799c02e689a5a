"""ltca: finite-element loaded tooth contact analysis of gear pairs (cylindrical, spiral bevel, planetary).

A library first; the ``ltca`` command is a thin layer over it::

    import ltca
    case = ltca.load_case("fzg_c14").with_values({"assembly.lead_misalignment_um": 10.0})
    result = ltca.run(case, torques_nm=[100.0, 200.0])
    result.dataset.ltca.plot_te(ax=ax)
    result.figures[0].te_loaded_ptp_arcsec

Layers: ``geometry`` (tooth surfaces, kinematics) <- ``fem`` (meshes, elasticity, compliance, contact) <- ``ltca``
(cases, analyses, results, command line). Inside ltca:

    cases.py       the case layer: one Case record for every kind, load_case, with_values
    core.py        run(case) for every gear kind (each kind supplies plan / execute / result / write)
    results.py     LoadedResult, the one result vocabulary, open_result
    accessor.py    plots on a result's dataset (``ds.ltca``)
    driver.py      the run folder of ``ltca run``: lock, run.json, resume, files, console tables
    cli.py         the ``ltca`` command
    cylindrical/, bevel/, planetary/   the gear kinds; drivetrain/, design/, study/, verify/ the other commands
"""
__version__ = "0.1.0"

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
