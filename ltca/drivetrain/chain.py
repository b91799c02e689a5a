"""Transmission-ratio error of a machine's kinematic chains (Nguyen et al. 2020): the ``ltca chain`` command.

The method and the chains are in :mod:`ltca.drivetrain.chain_model`, the case file in :mod:`ltca.drivetrain.chain_case`;
their public names are importable from here as well.
"""
from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from ltca.drivetrain.chain_case import load_chain_case
from ltca.drivetrain.chain_model import (
    Chain,
    ChainElement,
    ChainEvaluation,
    RollRatioError,
    evaluate_chain,
    pitch_deviation_bound,
    roll_ratio_error,
)

__all__ = ["ChainElement", "Chain", "ChainEvaluation", "evaluate_chain", "ChainResult",
           "load_chain_case", "run_chain", "pitch_deviation_bound", "RollRatioError", "roll_ratio_error"]


@dataclass(frozen=True)
class ChainResult:
    """All chains of a case file, evaluated as printed and recomputed by the rules.

    Attributes
    ----------
    chains : tuple of ChainEvaluation
        With the paper's printed values (reproduces its tables).
    recomputed : tuple of ChainEvaluation or None
        By the rules (None where the case lacks fi', Fpr for some element).
    """
    chains: tuple
    recomputed: tuple

    def __getitem__(self, name: str) -> ChainEvaluation:
        for ev in self.chains:
            if ev.chain.name == name:
                return ev
        raise KeyError(name)


def _cell(v: float) -> str:
    """A CSV cell: empty for a value the case does not give (not 'nan')."""
    return f"{v:.6g}" if np.isfinite(v) else ""


def run_chain(case_path: str, out_dir: str | None) -> ChainResult:
    """CLI entry ``ltca chain CASE [--out DIR]``: print each chain's table; write CSVs into out_dir."""
    chains = load_chain_case(case_path)
    evs, rec = [], []
    for chain in chains:
        ev = evaluate_chain(chain)
        evs.append(ev)
        print(ev.table() + "\n")
        try:
            again = evaluate_chain(chain, honour_printed=False)
        except ValueError:
            again = None
        rec.append(again)
        if again is not None:
            print(f"  recomputed by the rules: {again.error_percent:.4f} %, "
                  f"pitch error {again.pitch_error_um:.3f} um\n")
    if out_dir:
        os.makedirs(out_dir, exist_ok=True)
        for ev in evs:
            cols = "element,teeth,D_mm,turns,zk,fp_um,F_um,dphi_deg,rot_max_deg,rot_min_deg"
            rows = [f"{e.name},{e.teeth},{e.pitch_diameter:g},{ev.turns[k]:.9g},{ev.zk[k]:.6g},"
                    f"{_cell(ev.fp[k])},{ev.F[k]:.6g},{ev.dphi[k]:.9g},{ev.rot_max[k]:.9g},"
                    f"{ev.rot_min[k]:.9g}" for k, e in enumerate(ev.chain.elements)]
            with open(os.path.join(out_dir, f"chain_{ev.chain.name}.csv"), "w") as fh:
                fh.write("\n".join([cols, *rows]) + "\n")
    return ChainResult(tuple(evs), tuple(rec))
