"""ltca: the analyses of gear pairs, one subpackage per analysis, with the case reader, the command line and the
generic results writer at the top.

    case.py, errors.py   case files (TOML schema, validation, units) and the user-facing errors
    results.py           result files written atomically (generic; no analysis imports here)
    cli.py               the ``ltca`` command (imports every analysis, lazily)
    cylindrical/         loaded TCA of cylindrical pairs (model, tca, compliance set-up, contact, results, run)
    bevel/               spiral bevel case, pinion synthesis and TCA
    drivetrain/          deflection budgets, backlash, machine-chain ratio errors
    verify/              validation, CalculiX cross-check, convergence, bench

Imports geometry and fem, never the other way. Inside ltca: the top-level modules other than cli import no
subpackage; drivetrain and verify may import cylindrical; no import circle (tests/test_layout.py).
"""
__version__ = "0.1.0"
