"""Size guards: an estimate of the memory and disk a run needs, made before the work, and a refusal with a
clear message above a limit the user can raise (``--max-output-gb``). Imports nothing of ours but errors."""
from __future__ import annotations

from .errors import CaseError

__all__ = ["MAX_POSITIONS", "MAX_TOTAL_POSITIONS", "estimate_run_bytes", "check_run_size"]

MAX_POSITIONS = 2000            # per mesh cycle, as analysis.positions (also for --positions on the command line)
MAX_TOTAL_POSITIONS = 200_000   # positions x cycles x torques: about a day of contact solves
_LATTICE = 240                  # profile bins of the pressure lattice (ltca.cylindrical.results.MAX_LATTICE)
_TEETH = 5                      # pinion teeth in the loaded model, at most
_CELLS = 12_000                 # contact cells kept per position (pickle for --resume), an upper estimate


def estimate_run_bytes(n_positions: int, cycles: int, n_torques: int, slices: int) -> int:
    """Bytes of results.nc plus the kept positions (and about as much memory while the run lasts)."""
    per = _TEETH * _LATTICE * slices * 8 + _CELLS * 15 * 8
    return int(n_positions * cycles * n_torques * per)


def check_run_size(case, n_positions: int, fidelity: dict, max_output_gb: float = 2.0) -> None:
    total = n_positions * case.cycles * len(case.torques)
    if n_positions > MAX_POSITIONS:
        raise CaseError("--positions", n_positions, f"an integer in [1, {MAX_POSITIONS}] (as analysis.positions)")
    if total > MAX_TOTAL_POSITIONS:
        raise CaseError("analysis.cycles", case.cycles, f"positions x cycles x torques = {total} at most "
                        f"{MAX_TOTAL_POSITIONS}; lower analysis.positions, analysis.cycles or the torques")
    need = estimate_run_bytes(n_positions, case.cycles, len(case.torques), fidelity.get("slices", 20))
    if need > max_output_gb * 1e9:
        raise CaseError("analysis.positions", n_positions, f"a run within --max-output-gb {max_output_gb:g}: "
                        f"{total} positions need about {need / 1e9:.1f} GB of results and memory; lower "
                        "positions/cycles/torques or raise --max-output-gb")
