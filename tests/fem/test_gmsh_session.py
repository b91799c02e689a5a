"""A process that has meshed keeps its Python SIGTERM handler (gmsh's initialisation installs its own at the C level),
so ``ltca run`` still records an interrupted run when it is terminated after meshing, and it still ignores SIGPIPE
(gmsh sets it back to the default action, death), so a write to a closed pipe raises BrokenPipeError. Each check runs in a child
process: a lost handler kills the child, not the test session."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

from fixtures.paths import CASES, ROOT

ENV = {**os.environ, "PYTHONPATH": str(ROOT)}

_SESSIONS = """
import os, signal, sys, threading
from ltca.fem.solids import gmsh_session

def handled(signum, frame):
    print("handled", flush=True)
    sys.exit(7)

signal.signal(signal.SIGTERM, handled)
with gmsh_session():                        # opened and closed in the main thread
    pass
with gmsh_session():                        # a thread's session inside one of the main thread
    t = threading.Thread(target=lambda: gmsh_session().__enter__())
    t.start()
    t.join()
os.kill(os.getpid(), signal.SIGTERM)
signal.pause() if hasattr(signal, "pause") else None
"""


def test_python_sigterm_handler_survives_gmsh_sessions():
    done = subprocess.run([sys.executable, "-c", _SESSIONS], capture_output=True, text=True, env=ENV, timeout=120)
    assert done.returncode == 7 and "handled" in done.stdout, (done.returncode, done.stderr[-500:])


_PIPE = """
import os
from ltca.fem.solids import gmsh_session

with gmsh_session():
    pass
r, w = os.pipe()
os.close(r)
try:
    os.write(w, b"x")
except BrokenPipeError:
    print("raised", flush=True)
"""


def test_write_to_a_closed_pipe_raises_after_a_gmsh_session():
    done = subprocess.run([sys.executable, "-c", _PIPE], capture_output=True, text=True, env=ENV, timeout=120)
    assert done.returncode == 0 and "raised" in done.stdout, (done.returncode, done.stderr[-500:])


def test_sigterm_after_meshing_leaves_an_interrupted_run(tmp_path):
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "ltca.cli", "run", str(CASES / "fzg_c14.toml"), "--out", str(out),
           "--fidelity", "coarse", "--positions", "6"]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=ENV)
    t0, meshed = time.time(), 0
    for line in p.stderr:                    # the progress lines: both bodies meshed
        meshed += "meshed z=" in line
        if meshed == 2 or time.time() - t0 > 240:
            break
    p.send_signal(signal.SIGTERM)
    p.stderr.read()
    assert p.wait(timeout=120) == 130                  # the interrupted exit, not death by the signal (-15)
    # the status as written (a dead process's "running" would only be read back as interrupted)
    assert json.loads((out / "run.json").read_text())["status"] == "interrupted"
    assert not (out / "summary.json").exists()
