"""Output folders that a stop cannot corrupt: checked before the work, locked, written atomically, with a status.

- :func:`check_out_dir`: ``--out`` must be (or become) a writable folder, checked before any FE work.
- :class:`RunDir`: a lock file naming the process (a second run on the same folder exits 2 naming it), a
  ``run.json`` with status ``running`` / ``complete`` / ``interrupted`` / ``failed`` and the times, stale results of
  an earlier run removed at a fresh start, and the status set however the run ends (SIGTERM and Ctrl-C:
  ``interrupted``; an exception, a full disk included: ``failed``; SIGKILL leaves ``running`` with a dead pid,
  read back as ``interrupted``).
- :func:`atomic_path`, :func:`write_json_atomic`: every file goes to a temporary name and is renamed into place,
  so no truncated file ever carries a final name.
- :func:`write_netcdf_atomic`: a dataset serialised to netCDF in memory and written as bytes (the HDF5 library is
  never handed a file on a disk that can fill: its write errors abort the process), after a free-space check.
- :class:`PositionStore`: each finished position kept as a pickle (atomic) plus one JSON line, so ``--resume``
  takes them over and computes only the rest.
Imports nothing of ours but :mod:`ltca.errors`.
"""
from __future__ import annotations

import contextlib
import datetime as _dt
import errno
import hashlib
import json
import math
import os
import pickle
import signal
import socket
from pathlib import Path
from typing import Any, Iterator

from .errors import CaseError

__all__ = ["check_out_dir", "RunDir", "atomic_path", "write_json_atomic", "write_bytes_atomic", "write_netcdf_atomic",
           "netcdf_bytes", "check_free_space", "PositionStore", "finite_json", "read_status", "OUTPUTS", "staging",
           "signature_of", "write_json"]


#: results of ``ltca run`` that a fresh start removes (stale results of an earlier run)
OUTPUTS = ("summary.json", "results.nc", "te.png", "load_sharing.png", "bearing_pattern.png", "root_stress.png",
           "pinion_loaded.vtu", "gear_loaded.vtu", "positions.jsonl", "te_unloaded.png", "te_ptp.png",
           "te_harmonics.png", "report.html", "bearing_pattern_diameter.png", "paraview.pvd", "load_sharing.csv",
           "torques.csv", "case.toml")
#: name patterns of results that a fresh start removes too (the ParaView series' parts)
OUTPUT_GLOBS = ("paraview_*.vtu", "bearing_pattern_*Nm.vtu", "bearing_pattern_*Nm.png")
LOCK = ".ltca.lock"
STATUS = "run.json"


def _now() -> str:
    return _dt.datetime.now().astimezone().isoformat(timespec="seconds")


def finite_json(x: Any) -> Any:
    """The data with every NaN/inf float replaced by None (strict JSON; NaN is not JSON)."""
    if isinstance(x, float):
        return x if math.isfinite(x) else None
    if isinstance(x, dict):
        return {str(k): finite_json(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [finite_json(v) for v in x]
    if hasattr(x, "item") and getattr(x, "ndim", 1) == 0:      # numpy scalars
        return finite_json(x.item())
    return x


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success it is flushed to disk and renamed to ``path``, on any
    error it is removed (a full disk never leaves a truncated file under the final name)."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    try:
        yield tmp
        with open(tmp, "rb") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise


def check_free_space(path: str | Path, n_bytes: int) -> None:
    """Raise ``OSError(ENOSPC)`` naming ``path`` when its file system has less room than ``n_bytes`` in whole
    blocks plus one block (counted as an unprivileged user sees it: ``f_bavail``)."""
    folder = Path(path).parent
    try:
        st = os.statvfs(folder)
    except OSError:
        return                   # no statistics (a special file system): the write itself is the check
    free, block = st.f_bavail * st.f_frsize, max(st.f_frsize, 512)
    if -(-n_bytes // block) * block + block > free:       # whole blocks, and one for the directory entry
        raise OSError(errno.ENOSPC, f"No space left on device ({n_bytes / 1e6:.3f} MB to write, "
                      f"{free / 1e6:.3f} MB free)", str(path))


def write_bytes_atomic(path: str | Path, data: bytes | memoryview) -> None:
    """``data`` written to a temporary name beside ``path`` (after a free-space check), flushed, renamed into place;
    a full disk at any point raises ``OSError(ENOSPC)`` and leaves nothing under ``path``."""
    check_free_space(path, len(data))
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            view = memoryview(data)
            while view:          # a short write (a disk filling meanwhile) is an error, never a truncated file
                n = fh.write(view)
                if not n:
                    raise OSError(errno.ENOSPC, "No space left on device (short write)", str(path))
                view = view[n:]


def netcdf_bytes(ds, encoding: dict | None = None) -> bytes:
    """A dataset as the bytes of a netCDF-4 (HDF5) file, built in memory by h5netcdf.

    Under a Dask distributed client (a study's), xarray would guard the write with a distributed lock named after
    the target, which an in-memory target cannot be: the write runs on the synchronous scheduler (the data are in
    memory already)."""
    try:
        import dask
        scheduler = dask.config.set(scheduler="synchronous")
    except ImportError:              # xarray without dask
        scheduler = contextlib.nullcontext()
    with scheduler:
        return bytes(ds.to_netcdf(engine="h5netcdf", encoding=encoding or {}))


def write_netcdf_atomic(path: str | Path, ds, encoding: dict | None = None) -> int:
    """A dataset written as netCDF-4 to ``path``: serialised in memory, then written with
    :func:`write_bytes_atomic` (free-space check, temporary name, rename). Returns the size in bytes.

    The HDF5 library never writes to the disk itself: on a full disk its error handling aborts the process
    (a segmentation fault) instead of raising; here a full disk is an ``OSError(ENOSPC)`` like any other."""
    data = netcdf_bytes(ds, encoding)
    write_bytes_atomic(path, data)
    return len(data)


def write_json_atomic(path: str | Path, data: Any) -> None:
    """Strict JSON (NaN/inf as null), written atomically."""
    write_bytes_atomic(path, json.dumps(finite_json(data), indent=2, allow_nan=False).encode())


def write_json(path: str | Path, data: Any) -> None:
    """JSON as Python writes it (NaN kept), written atomically."""
    write_bytes_atomic(path, json.dumps(data, indent=2).encode())


def check_out_dir(out: str | Path, option: str = "--out") -> Path:
    """Make sure ``out`` is a folder we can write, before any work; CaseError (exit 2) otherwise."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        what = "the results" if option == "--out" else "it"
        raise CaseError(option, str(out), f"a folder for {what}, not an existing file")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CaseError(option, str(out), f"a folder that can be created ({exc.strerror})") from None
    probe = out / f".write-probe-{os.getpid()}"
    try:
        with open(probe, "wb") as fh:
            fh.write(b"x" * 4096)
            fh.flush()
            os.fsync(fh.fileno())
    except OSError as exc:
        raise CaseError(option, str(out), f"a writable folder ({exc.strerror})") from None
    finally:
        with contextlib.suppress(OSError):
            probe.unlink()
    return out


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def read_status(out: str | Path) -> dict | None:
    """run.json of a folder, with a ``running`` status of a dead process read as ``interrupted``."""
    p = Path(out) / STATUS
    try:
        st = json.loads(p.read_text())
    except (OSError, ValueError):
        return None
    if st.get("status") == "running" and st.get("host") == socket.gethostname() and not _alive(int(st.get("pid", 0))):
        st["status"] = "interrupted"
    return st


class _Terminated(BaseException):
    """SIGTERM, turned into an exception so that the status and the lock are written on the way out."""


class RunDir:
    """Context manager around one run writing into ``out``: lock, status, stale results, signal handling.

    ``signature`` identifies the work (case file hash and the settings that change results): ``--resume`` is
    refused when it differs from the interrupted run's."""

    def __init__(self, out: str | Path, command: str, signature: dict, resume: bool = False):
        self.out = check_out_dir(out)
        self.command, self.signature, self.resume = command, signature, resume
        self.lock = self.out / LOCK
        self.status: dict = {}
        self.taken_over = 0

    # -- lock
    def _acquire(self) -> None:
        info = {"pid": os.getpid(), "host": socket.gethostname(), "started": _now(), "command": self.command}
        for _ in range(2):
            try:
                fd = os.open(self.lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
            except FileExistsError:
                try:
                    other = json.loads(self.lock.read_text())
                except (OSError, ValueError):
                    other = {}
                if other.get("host") == socket.gethostname() and other.get("pid") and not _alive(int(other["pid"])):
                    with contextlib.suppress(OSError):
                        self.lock.unlink()       # stale lock of a killed run
                    continue
                raise CaseError("--out", str(self.out), f"a folder no other run is writing: locked by {self.lock} "
                                f"(pid {other.get('pid', '?')} on {other.get('host', '?')} since "
                                f"{other.get('started', '?')}); wait for it, or delete the lock if that process is "
                                "gone") from None
            with os.fdopen(fd, "w") as fh:
                fh.write(json.dumps(info))
            return
        raise CaseError("--out", str(self.out), f"a lock file {self.lock} that can be replaced")

    def _release(self) -> None:
        with contextlib.suppress(OSError):
            if json.loads(self.lock.read_text()).get("pid") == os.getpid():
                self.lock.unlink()

    # -- status
    def set(self, **kw) -> None:
        self.status.update(kw, updated=_now())
        write_json_atomic(self.out / STATUS, self.status)

    def _set_final(self, **kw) -> None:
        """The closing status, also on a disk with no block left: written atomically if it can be, else over the
        existing run.json in place (its block is reused; the run is over, so no reader sees a mix)."""
        try:
            self.set(**kw)
        except OSError:
            data = json.dumps(finite_json(self.status), indent=2, allow_nan=False).encode()
            with open(self.out / STATUS, "r+b") as fh:
                fh.truncate(0)
                fh.write(data)
                fh.flush()
                os.fsync(fh.fileno())

    def __enter__(self) -> "RunDir":
        self._acquire()
        try:
            prev = read_status(self.out)
            if self.resume:
                if prev is None:
                    raise CaseError("--resume", str(self.out), "a folder with the run.json of an earlier run")
                if prev.get("signature") != self.signature:
                    changed = sorted(k for k in set(self.signature) | set(prev.get("signature", {}))
                                     if self.signature.get(k) != prev.get("signature", {}).get(k))
                    raise CaseError("--resume", str(self.out), f"the same case and settings as the earlier run "
                                    f"(changed: {', '.join(changed)}); start afresh without --resume")
                for name in OUTPUTS:     # the final files are rebuilt; only positions are taken over
                    if name != "positions.jsonl":
                        with contextlib.suppress(OSError):
                            (self.out / name).unlink()
            else:
                stale = [self.out / n for n in OUTPUTS] + [p for g in OUTPUT_GLOBS for p in self.out.glob(g)]
                for path in stale:       # stale results of an earlier run
                    with contextlib.suppress(OSError):
                        path.unlink()
                PositionStore.clear(self.out)
            self.status = {"status": "running", "command": self.command, "pid": os.getpid(),
                           "host": socket.gethostname(), "started": _now(), "signature": self.signature,
                           "resumed_from": prev.get("status") if (self.resume and prev) else None}
            self.set()
        except BaseException:
            self._release()
            raise
        self._old_term = signal.getsignal(signal.SIGTERM)
        with contextlib.suppress(ValueError):           # only in the main thread
            signal.signal(signal.SIGTERM, self._on_term)
        return self

    @staticmethod
    def _on_term(signum, frame):
        raise _Terminated()

    def __exit__(self, typ, exc, tb) -> bool:
        with contextlib.suppress(ValueError):
            signal.signal(signal.SIGTERM, self._old_term)
        try:
            if typ is None:
                self.set(status="complete", finished=_now())
            elif issubclass(typ, (KeyboardInterrupt, _Terminated)):
                self._set_final(status="interrupted", finished=_now(), error="interrupted (resume with --resume)")
            else:
                with contextlib.suppress(OSError):
                    self._set_final(status="failed", finished=_now(), error=f"{typ.__name__}: {str(exc)[:300]}")
        except OSError:
            pass
        finally:
            self._release()
        if typ is not None and issubclass(typ, _Terminated):
            raise KeyboardInterrupt from None
        return False


def signature_of(case_path: str | Path, **settings) -> dict:
    """What identifies a run's results: the case file's bytes and the settings that change them."""
    digest = hashlib.sha256(Path(case_path).read_bytes()).hexdigest()
    return {"case_sha256": digest, **{k: v for k, v in settings.items()}}


class PositionStore:
    """Finished positions of ``ltca run``: ``positions/<torque>_<index>.pkl`` (atomic) and ``positions.jsonl``."""

    DIR = "positions"

    def __init__(self, out: str | Path):
        self.out = Path(out)
        self.dir = self.out / self.DIR
        self.dir.mkdir(exist_ok=True)
        self.log = self.out / "positions.jsonl"
        self.computed = 0
        self.taken_over = 0
        self.dirty = False       # positions taken over whose lines are not yet in the log

    @classmethod
    def clear(cls, out: Path) -> None:
        d = Path(out) / cls.DIR
        if d.is_dir():
            for p in d.glob("*.pkl"):
                with contextlib.suppress(OSError):
                    p.unlink()

    def _path(self, it: int, k: int) -> Path:
        return self.dir / f"t{it:03d}_p{k:06d}.pkl"

    def load(self, it: int, k: int):
        p = self._path(it, k)
        if not p.is_file():
            return None
        try:
            with open(p, "rb") as fh:
                return pickle.load(fh)
        except Exception:            # a file from an older program or damaged: compute the position again
            return None

    def save(self, it: int, k: int, result, line: dict) -> None:
        write_bytes_atomic(self._path(it, k), pickle.dumps(result, protocol=pickle.HIGHEST_PROTOCOL))
        self.append(line)

    def append(self, line: dict) -> None:
        """One JSON line, written by one write() of a whole line: never torn by another writer (the lock keeps
        those out), and a full disk makes it fail rather than half-write silently (it is then rewritten on resume)."""
        data = (json.dumps(finite_json(line), allow_nan=False) + "\n").encode()
        fd = os.open(self.log, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        try:
            n = os.write(fd, data)
            if n != len(data):
                raise OSError(28, "short write (disk full?)", str(self.log))
        finally:
            os.close(fd)

    def rewrite_log(self, lines: list[dict]) -> None:
        """The log of the positions taken over by --resume, in order (drops a torn last line)."""
        write_bytes_atomic(self.log, "".join(json.dumps(finite_json(x), allow_nan=False) + "\n"
                                             for x in lines).encode())


@contextlib.contextmanager
def staging(out: str | Path) -> Iterator[Path]:
    """A private folder inside ``out`` for files written by other libraries (netCDF, PNG, VTU) under their final
    names; on success each is flushed to disk and renamed into ``out``; on failure the folder is removed."""
    import shutil
    out = Path(out)
    stage = out / f".staging-{os.getpid()}"
    shutil.rmtree(stage, ignore_errors=True)
    stage.mkdir()
    try:
        yield stage
        for p in sorted(stage.iterdir()):
            with open(p, "rb") as fh:
                os.fsync(fh.fileno())
        for p in sorted(stage.iterdir()):
            os.replace(p, out / p.name)
    finally:
        shutil.rmtree(stage, ignore_errors=True)
