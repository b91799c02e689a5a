"""Tooth errors of a workpiece: single pitch deviations and the tooth position errors they add up to.

A cutting machine's indexing error (ltca.chain, Nguyen et al. 2020) bounds the single pitch deviation f_pt of
every pitch; the teeth must close the circle, so the deviations sum to zero over a revolution. The
cumulative sum gives each tooth's position error (ISO 1328-1: cumulative pitch deviation F_p,k), which is
what the separation field consumes (``FlankModification.pitch_errors``).
"""
from __future__ import annotations

import numpy as np

__all__ = ["worst_case_pitch_deviations", "random_pitch_deviations", "tooth_positions"]


def worst_case_pitch_deviations(teeth: int, bound: float, pattern: str = "alternating") -> np.ndarray:
    """Worst-case single pitch deviations f_pt,k (mm) that close over one revolution.

    Parameters
    ----------
    teeth : int
        Workpiece teeth (>= 2).
    bound : float
        Largest |f_pt|, mm (e.g. :func:`pitch_deviation_bound`).
    pattern : {"alternating", "half"}
        "alternating": +b, -b, ... (largest tooth-to-tooth jump 2b; 0 on the last tooth if z is odd);
        "half": +b on the first z//2 pitches, -b on the next z//2 (largest cumulative pitch error
        z//2 b, once-per-revolution content).

    Returns
    -------
    ndarray (teeth,)
        Pitch deviations, mm; their sum is zero (the teeth close the circle).
    """
    if teeth < 2 or bound < 0:
        raise ValueError(f"need teeth >= 2 and bound >= 0, got {teeth}, {bound}")
    k = np.arange(teeth)
    if pattern == "alternating":
        dev = bound * np.where(k % 2 == 0, 1.0, -1.0)
    elif pattern == "half":
        dev = bound * np.where(k < teeth // 2, 1.0, -1.0)
    else:
        raise ValueError(f"pattern must be 'alternating' or 'half', got {pattern!r}")
    if teeth % 2:
        dev[-1] = 0.0
    return dev


def random_pitch_deviations(teeth: int, bound: float, seed: int, draws: int = 1) -> np.ndarray:
    """Seeded random pitch deviations within +/- bound whose sum over a revolution is zero.

    Each draw starts uniform in [-bound, bound] (numpy ``default_rng(seed)``); the closing error is
    then spread evenly over the pitches that still have room, with clipping, until it vanishes.

    Returns
    -------
    ndarray (draws, teeth)
        Pitch deviations, mm; ``cumsum`` along axis 1 is the cumulative pitch error, 0 at the end.
    """
    if teeth < 2 or bound < 0 or draws < 1:
        raise ValueError(f"need teeth >= 2, bound >= 0, draws >= 1, got {teeth}, {bound}, {draws}")
    dev = np.random.default_rng(seed).uniform(-bound, bound, (draws, teeth))
    for _ in range(100):
        excess = dev.sum(axis=1, keepdims=True)
        if np.all(np.abs(excess) <= 1e-15 * max(bound, 1e-300) * teeth):
            break
        room = np.where(excess > 0, dev > -bound, dev < bound)
        dev = np.clip(dev - excess / np.maximum(room.sum(axis=1, keepdims=True), 1) * room,
                      -bound, bound)
    dev -= dev.mean(axis=1, keepdims=True)          # rounding residue, ~1e-16 of the bound
    return dev


def tooth_positions(deviations: np.ndarray) -> np.ndarray:
    """Tooth position errors (mm, mean removed) from single pitch deviations (mm) of a revolution.

    Tooth 0 is the reference; tooth k sits at sum(f_pt[:k]) from its nominal place (ISO 1328-1 F_p,k).
    ``deviations`` (..., z) must close (sum to zero along the last axis to 1e-9 of their scale)."""
    d = np.asarray(deviations, float)
    if np.any(np.abs(d.sum(axis=-1)) > 1e-9 * max(np.abs(d).max(), 1e-300) * d.shape[-1]):
        raise ValueError("deviations: the single pitch deviations must sum to zero over the revolution")
    pos = np.concatenate([np.zeros(d.shape[:-1] + (1,)), np.cumsum(d, axis=-1)[..., :-1]], axis=-1)
    return pos - pos.mean(axis=-1, keepdims=True)
