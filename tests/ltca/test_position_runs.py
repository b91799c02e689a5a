"""The positions of a torque in runs side by side (ltca.position_runs): warm starts along each run, positions taken
over from a store, the log in position order, errors handed to the caller; and on a real pair, the same contact
whether the cycle is solved in one run or two."""
from __future__ import annotations

import json
import threading
import time

import numpy as np
import pytest

from ltca.outputs import PositionStore
from ltca.position_runs import solve_positions, thread_count


def _chain(calls: list):
    """A solve whose result records the warm start it was given."""
    def solve(k, warm):
        calls.append(k)
        return {"k": k, "from": None if warm is None else warm["k"]}
    return solve


def _line(k: int, res: dict) -> dict:
    assert res["k"] == k
    return {"k": k}


@pytest.mark.parametrize("threads", [1, 2, 3])
def test_each_run_is_warm_started_along_itself(threads):
    calls: list = []
    out = solve_positions(7, _chain(calls), _line, threads=threads)
    assert [r["k"] for r in out] == list(range(7))
    runs = [list(ks) for ks in np.array_split(np.arange(7), threads)]
    firsts = {ks[0] for ks in runs}
    for r in out:
        assert r["from"] == (None if r["k"] in firsts else r["k"] - 1)
    assert sorted(calls) == list(range(7))


def test_start_gives_the_first_position_of_each_run():
    out = solve_positions(4, lambda k, warm: {"k": k, "from": warm["k"]}, _line, threads=2,
                          start=lambda k: {"k": -10 - k})
    assert [r["from"] for r in out] == [-10, 0, -12, 2]


def test_runs_overlap_in_time():
    """Two runs whose solves release the GIL (a sleep here) take about the time of one."""
    def solve(k, warm):
        time.sleep(0.05)
        return {"k": k}
    t0 = time.perf_counter()
    solve_positions(8, solve, _line, threads=2)
    assert time.perf_counter() - t0 < 0.05 * 8 * 0.75


def test_taken_over_positions_are_not_solved_and_the_log_ends_in_order(tmp_path):
    store = PositionStore(tmp_path)
    for k in (1, 4):
        store.save(0, k, {"k": k, "from": "old"}, {"k": k})
    with open(store.log, "ab") as fh:       # the interrupted run's torn last line
        fh.write(b'{"k": 9')
    calls: list = []
    lines = [{"earlier": True}]
    out = solve_positions(6, _chain(calls), _line, store=store, lines=lines, threads=2)
    assert sorted(calls) == [0, 2, 3, 5]
    assert out[1]["from"] == "old" and out[2]["from"] == 1 and out[5]["from"] == 4
    assert (store.computed, store.taken_over) == (4, 2)
    log = [json.loads(x) for x in store.log.read_text().splitlines()]
    assert log == [{"earlier": True}] + [{"k": k} for k in range(6)]
    assert lines == log
    assert [store.load(0, k)["k"] for k in range(6)] == list(range(6))


def test_an_error_in_one_run_stops_the_other_and_reaches_the_caller():
    solved: list = []
    lock = threading.Lock()

    def solve(k, warm):
        if k == 4:
            raise ValueError("position 4")
        time.sleep(0.02)
        with lock:
            solved.append(k)
        return {"k": k}
    with pytest.raises(ValueError, match="position 4"):
        solve_positions(40, solve, _line, threads=2)
    assert len(solved) < 39            # the first run stopped after its current position


def test_thread_count_is_bounded():
    assert 1 <= thread_count() <= 2
    assert thread_count(1) == 1


def test_two_runs_give_the_contact_of_one(fzg_lm):
    """A run's first position solved without a warm start gives what the warm-started loop gives."""
    from ltca.cylindrical.loop import analyse, cycle_rolls
    rolls = cycle_rolls(8, 16)
    one = analyse(fzg_lm, rolls, 200e3, threads=1)
    two = analyse(fzg_lm, rolls, 200e3, threads=2)
    for a, b in zip(one, two):
        assert b.theta == pytest.approx(a.theta, rel=1e-12, abs=0.0)
        np.testing.assert_allclose(b.force, a.force, rtol=0, atol=1e-9 * a.force.max())
