"""The positions of one torque, solved in runs of consecutive positions side by side: every kind's cycle loop.

A position is warm-started from the one before it. The cycle is cut into ``threads`` runs of consecutive positions,
each warm-started along itself from its own start, and the runs are solved by threads side by side. That pays where
a position's contact solve is numpy and LAPACK on arrays large enough to release the GIL for much of its time (the
cylindrical pairs: helical C14's 30 positions 3.4 s on one thread, 2.4 s on two), not where it is Python (the bevel
gap evaluation). A position's result does not depend on where its solve starts: the active-set solution of the
complementarity problem is unique, and the warm start only saves iterations.

Finished positions are kept as they finish (``store``): an interrupted run loses none, and a run resumed with the same
number of threads warm-starts every position from the same neighbour as the uninterrupted run. The log
``positions.jsonl`` gets a line per position as it finishes and is rewritten in position order when the runs
finished out of order or positions were taken over.
"""
from __future__ import annotations

import os
import threading
from typing import Any, Callable

import numpy as np

from .fem.background import Background

__all__ = ["solve_positions", "thread_count"]


def thread_count(limit: int = 2) -> int:
    """Threads for the positions of a run: the cores this process may use, at most ``limit``."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(int(limit), cores))


def solve_positions(n: int, solve: Callable[[int, Any], Any], line_of: Callable[[int, Any], dict], *, store=None,
                    it: int = 0, lines: list | None = None, threads: int = 1,
                    start: Callable[[int], Any] | None = None,
                    done: Callable[[int, Any], None] | None = None) -> list:
    """Every position ``k`` in ``range(n)`` of one torque: taken over from ``store`` or solved.

    Parameters
    ----------
    n : int
        Positions.
    solve : callable(k, warm) -> result
        Solves position k; ``warm`` is the result of position k - 1 of the same run, or ``start(k)`` at a run's
        first position.
    line_of : callable(k, result) -> dict
        Position k's log record (``positions.jsonl``).
    store : ltca.outputs.PositionStore, optional
        Keeps each finished position (torque index ``it``) and gives back those an interrupted run finished.
    lines : list, optional
        The log records of the run so far (earlier torques); this torque's are appended in position order. The
        records are made only with a ``store`` or ``lines``.
    threads : int
        Runs of consecutive positions solved side by side (1: the calling thread solves them in order).
    start : callable(k) -> warm, optional
        The warm start of a run's first position k (default None).
    done : callable(k, result), optional
        Called as each position finishes or is taken over (one at a time; progress).

    Returns
    -------
    list
        The results in position order.
    """
    logged = store is not None or lines is not None
    lines = [] if lines is None else lines
    old = [store.load(it, k) if store is not None else None for k in range(n)]
    results: list = list(old)
    records: list = [line_of(k, r) if r is not None else None for k, r in enumerate(old)]
    taken = sum(r is not None for r in old)
    if store is not None and taken:
        store.taken_over += taken
        store.dirty = True
    lock = threading.Lock()
    stop = threading.Event()
    computed = 0

    def keep(k: int, result) -> None:
        nonlocal computed
        with lock:
            if store is not None and store.dirty:   # the interrupted run's log without a torn last line
                store.rewrite_log(lines + [x for x in records if x is not None])
                store.dirty = False
            results[k] = result
            if logged:
                records[k] = line_of(k, result)
            if store is not None:
                store.save(it, k, result, records[k])
                store.computed += 1
            computed += 1
            if done is not None:
                done(k, result)

    def run(ks: np.ndarray) -> None:
        try:
            warm = start(int(ks[0])) if start is not None else None
            for k in ks.tolist():
                if stop.is_set():
                    return
                if old[k] is None:
                    keep(k, solve(k, warm))
                elif done is not None:
                    with lock:
                        done(k, old[k])
                warm = results[k]
        except BaseException:
            stop.set()          # the other runs end after their current position
            raise

    runs = [ks for ks in np.array_split(np.arange(n), max(1, min(int(threads), n))) if len(ks)]
    others = [Background(lambda ks=ks: run(ks), "ltca-positions") for ks in runs[1:]]
    try:
        if runs:
            run(runs[0])
    except BaseException:
        for t in others:
            t.join()
        raise
    for t in others:
        t.result()
    lines.extend(records)
    if store is not None and computed and (len(runs) > 1 or taken):
        store.rewrite_log(lines)            # finished out of order, or after positions taken over: in order
    return results
