"""A gear body meshed in a child Python process while the caller goes on.

gmsh meshes on one core and is not thread-safe: two bodies cannot be meshed at once in one process, and a mesh
made in a thread beside the solver takes a core from the factorisation. A child interpreter meshes the second body
of a pair on the core the first body's mesher leaves idle. The child imports only numpy, gmsh and the body builder
(about 0.2 s), reads the pickled :class:`~ltca.fem.solids.gear_body.GearBodySpec` from its stdin, meshes it with
:func:`~ltca.fem.solids.gear_body.build_gear_body` (the same options, one gmsh thread: the same mesh as in the
parent) and writes the pickled :class:`~ltca.fem.solids.mesh_record.BodyMesh` to its stdout; anything the mesher
itself prints goes to stderr.

A child that cannot be started or that fails is not an error of the run: the body is then meshed in the calling
process, where a meshing error is raised as it would be without a child. A child still running when the job is
cancelled (an interrupted run) is killed.
"""
from __future__ import annotations

import logging
import os
import pickle
import subprocess
import sys
import threading
from pathlib import Path

from .cache import load_cached
from .gear_body import GearBodySpec, build_gear_body
from .mesh_record import BodyMesh

__all__ = ["BodyMeshJob"]

log = logging.getLogger(__name__)

#: the directory holding the ``ltca`` package (a source checkout's root or site-packages), put first on the child's
#: search path so that it imports the very code of its parent
_HERE = Path(__file__).resolve()
_ROOT = str(_HERE.parents[2] if (_HERE.parents[2] / "ltca").is_dir() else _HERE.parents[3])
_CHILD = ("import sys; sys.path.insert(0, sys.argv[1]); "
          "from ltca.fem.solids.mesh_job import _child_main; _child_main()")


class BodyMeshJob:
    """A gear body being meshed in a child process (module docstring).

    Parameters
    ----------
    spec : GearBodySpec
        The body to mesh.
    cache_dir : path, optional
        Mesh cache directory, as for :func:`~ltca.fem.solids.gear_body.build_gear_body`: a cached body is loaded
        at once, without a child; a body meshed by the child is stored there by it.
    """

    def __init__(self, spec: GearBodySpec, cache_dir=None) -> None:
        self.spec, self.cache_dir = spec, cache_dir
        self._mesh: BodyMesh | None = load_cached(cache_dir, "body", spec.spec_hash)
        self._proc: subprocess.Popen | None = None
        self._out: tuple[bytes, bytes] = (b"", b"")
        self._reader: threading.Thread | None = None
        if self._mesh is not None:
            return
        try:
            self._proc = subprocess.Popen([sys.executable, "-c", _CHILD, _ROOT], stdin=subprocess.PIPE,
                                          stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        except OSError as exc:
            log.warning("meshing z=%d in this process: no child process (%s)", spec.z, exc)
            return
        self._reader = threading.Thread(target=self._communicate, name="ltca-mesh-job", daemon=True)
        self._reader.start()

    def _communicate(self) -> None:
        try:
            self._out = self._proc.communicate(pickle.dumps((self.spec, self.cache_dir)))
        except (OSError, ValueError) as exc:       # the child killed meanwhile (cancel)
            self._out = (b"", str(exc).encode())

    def result(self) -> BodyMesh:
        """The meshed body: the child's, or meshed here if the child could not deliver it."""
        if self._mesh is not None:
            return self._mesh
        if self._reader is not None:
            self._reader.join()
            out, err = self._out
            if self._proc.returncode == 0 and out:
                self._mesh = pickle.loads(out)
                return self._mesh
            tail = err.decode(errors="replace").strip().splitlines()[-1:] or ["no message"]
            log.warning("meshing z=%d in this process: the child process exited with %s (%s)", self.spec.z,
                        self._proc.returncode, tail[0])
        self._mesh = build_gear_body(self.spec, cache_dir=self.cache_dir)
        return self._mesh

    def cancel(self) -> None:
        """Kill the child if it is still running (nothing happens after :meth:`result`)."""
        if self._proc is not None and self._proc.poll() is None:
            self._proc.kill()
            if self._reader is not None:
                self._reader.join()


def _child_main() -> None:
    """The child's side: spec from stdin, mesh to stdout (C-level output of the mesher redirected to stderr)."""
    out = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)
    spec, cache_dir = pickle.load(sys.stdin.buffer)
    mesh = build_gear_body(spec, cache_dir=cache_dir)
    out.write(pickle.dumps(mesh, protocol=pickle.HIGHEST_PROTOCOL))
    out.close()
