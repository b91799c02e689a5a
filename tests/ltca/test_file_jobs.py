"""The file jobs of a run: written in order by a second process, errors raised in the caller, a serial fallback."""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

import ltca.file_jobs as fj


def _pid_into(path: Path) -> None:
    Path(path).write_text(str(os.getpid()))


def test_jobs_run_in_order_in_another_process(tmp_path):
    a, b, pid = tmp_path / "a.txt", tmp_path / "b.txt", tmp_path / "pid.txt"
    with fj.BackgroundFiles() as jobs:
        jobs.submit(Path.write_text, a, "first")
        jobs.submit(shutil.copyfile, a, b)          # needs the first job done
        jobs.submit(_pid_into, pid)
        jobs.wait()
    assert b.read_text() == "first"
    assert int(pid.read_text()) != os.getpid()


def test_wait_raises_a_jobs_error_once_every_job_has_stopped(tmp_path):
    after = tmp_path / "after.txt"
    with fj.BackgroundFiles() as jobs:
        jobs.submit(int, "not a number")
        jobs.submit(Path.write_text, after, "written")
        with pytest.raises(ValueError, match="not a number"):
            jobs.wait()
        assert after.read_text() == "written"
        jobs.wait()                                  # the failed jobs are not raised twice


def test_a_killed_writer_is_an_error_that_says_so():
    with fj.BackgroundFiles() as jobs:
        jobs.submit(os._exit, 3)
        with pytest.raises(RuntimeError, match="stopped unexpectedly"):
            jobs.wait()


def test_serial_fallback_where_no_process_can_start(tmp_path, monkeypatch):
    def refuse(*args, **kwargs):
        raise OSError("no processes here")
    monkeypatch.setattr(fj, "BackgroundFiles", refuse)
    jobs = fj.start_background(("ltca.vtu",))
    assert type(jobs) is fj.FileJobs
    jobs.submit(Path.write_text, tmp_path / "now.txt", "at once")
    assert (tmp_path / "now.txt").read_text() == "at once"      # written before wait
    with pytest.raises(ValueError):
        jobs.submit(int, "x")
