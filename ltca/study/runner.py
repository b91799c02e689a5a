"""Running a study on Dask.

A ``LocalCluster`` sized to the machine by default, or an existing cluster by its scheduler address; the same
code either way.

The client submits one plan task per unfinished variant; as each plan returns, the variant's geometry key
either finds a compliance already under way (a future), kept on disk from an earlier run (scattered to the
cluster), or submits the one compliance task of that geometry; the variant's points are then submitted with
the compliance future as an argument, so Dask hands the compliance to whichever worker solves them. The client
writes each point as it finishes (atomically, :class:`ltca.study.store.StudyStore`), so the result files
need no storage shared with the workers, a killed client loses nothing finished, and a rerun skips it. A task
on a worker that dies is rescheduled by Dask on another worker (``distributed.scheduler.allowed-failures``);
each point is written once, when its future first completes.

The runner does not know the gear kind: a variant's plan names the compliance each of its torques solves on
(:meth:`ltca.study.tasks.VariantPlan.compliance_key`; a bevel pair has one per loaded flank), the tasks do the
rest (:mod:`ltca.study.tasks`, :mod:`ltca.study.bevel_tasks`).

Imports ltca.errors and ltca.study (spec, store, tasks, report).
"""
from __future__ import annotations

import json
import os
import sys
import time
import uuid
from contextlib import contextmanager
from pathlib import Path

from ..errors import CaseError, ConvergenceError
from ..outputs import write_json
from .spec import Study, Variant
from .store import StudyStore
from .tasks import compute_compliance, plan_variant, solve_point, unwrap

__all__ = ["run_study", "local_cluster_size", "cluster_client"]


def local_cluster_size() -> int:
    """Workers of the default LocalCluster: the cores this process may use (one single-threaded worker each)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:                                   # not on Linux
        return max(1, os.cpu_count() or 1)


def check_scheduler_address(address: str) -> str:
    """Check ``--scheduler``: a Dask scheduler address such as ``tcp://127.0.0.1:8786`` (parsed by Dask).

    Raises :class:`~ltca.errors.CaseError` (exit status 2) otherwise.
    """
    from distributed.comm.addressing import parse_address, parse_host_port
    allowed = "the address of a running Dask scheduler, e.g. tcp://127.0.0.1:8786"
    if not isinstance(address, str) or not 0 < len(address) <= 500 or any(c.isspace() for c in address):
        raise CaseError("--scheduler", address, allowed)
    try:
        scheme, loc = parse_address(address)
        if scheme in ("tcp", "tls", "ws", "wss", "ucx"):
            host, port = parse_host_port(loc)
            if not host or port is None or not 0 < int(port) < 65536:
                raise ValueError(f"no host or port in {loc!r}")
    except (ValueError, TypeError) as exc:
        raise CaseError("--scheduler", address, f"{allowed} ({exc})") from None
    return address


@contextmanager
def cluster_client(scheduler: str | None = None, workers: int | None = None):
    """A ``distributed.Client`` of the cluster at ``scheduler``, or of a new LocalCluster.

    The LocalCluster has ``workers`` single-threaded worker processes (default :func:`local_cluster_size`), closed on exit.
    """
    from distributed import Client, LocalCluster
    if scheduler:
        check_scheduler_address(scheduler)
        try:
            client = Client(scheduler, timeout="30s")
        except (OSError, TimeoutError) as exc:
            raise CaseError("--scheduler", scheduler, "the address of a running Dask scheduler (none answered "
                            f"within 30 s: {' '.join(str(exc).split())[:200]})") from None
        try:
            yield client
        finally:
            client.close()
        return
    n = workers or local_cluster_size()
    # one task at a time per worker; BLAS / PARDISO threads as in ``ltca run`` (the contact solve limits its
    # BLAS to one thread itself), so that a lone compliance task still uses every core
    # the dashboard on a free port (":0"): the default port taken by another cluster is a warning on the console
    with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            Client(cluster) as client:
        yield client


class _Progress:
    """Variants done / total, points done / total and the ETA, on stderr."""

    def __init__(self, variants: list[Variant], torques, store: StudyStore, enabled: bool):
        self.left = {v.id: sum(not store.finished(v.id, t) for t in torques) for v in variants}
        self.n_var = len(variants)
        self.n_pts = len(variants) * len(torques)
        self.todo = sum(self.left.values())
        self.done_now = 0
        self.t0 = time.perf_counter()
        self.enabled = enabled
        self.say(f"{self.n_pts - self.todo} of {self.n_pts} points already done")

    def say(self, msg: str) -> None:
        if self.enabled:
            print(f"[study] {msg}", file=sys.stderr, flush=True)

    def point_done(self, vid: str) -> None:
        self.left[vid] -= 1
        self.done_now += 1
        el = time.perf_counter() - self.t0
        eta = el / self.done_now * (self.todo - self.done_now)
        v_done = sum(n == 0 for n in self.left.values())
        p_done = self.n_pts - self.todo + self.done_now
        self.say(f"variants {v_done}/{self.n_var}, points {p_done}/{self.n_pts}, elapsed {el:.0f} s, "
                 f"ETA {eta:.0f} s")


def _execute(client, study: Study, store: StudyStore, todo: dict, prog: _Progress, stats: dict) -> None:
    from distributed import as_completed
    token = uuid.uuid4().hex[:8]
    meta, compliance = {}, {}
    ac = as_completed()
    for v, torques in todo.values():
        f = client.submit(plan_variant, v.case, key=f"plan-{v.id}-{token}")
        meta[f.key] = ("plan", v, torques)
        ac.add(f)
    for f in ac:
        kind, obj, extra = meta.pop(f.key)
        if kind == "plan":
            vplan = unwrap(f.result())
            for t in extra:
                ckey = vplan.compliance_key(t)
                cf = compliance.get(ckey)
                if cf is None:
                    kept = store.load_compliance(ckey)
                    if kept is not None:
                        cf = client.scatter(kept, hash=False)
                        stats["compliance_loaded"] += 1
                        prog.say(f"geometry {ckey}: compliance kept from an earlier run")
                    else:
                        cf = client.submit(compute_compliance, obj.case, vplan, t, key=f"compliance-{ckey}-{token}",
                                           priority=10)        # before the remaining plans: points wait on it
                        meta[cf.key] = ("compliance", ckey, None)
                        ac.add(cf)
                    compliance[ckey] = cf
                pf = client.submit(solve_point, obj.case, vplan, cf, t, key=f"point-{obj.id}-T{t:g}-{token}",
                                   priority=5)
                meta[pf.key] = ("point", obj, t)
                ac.add(pf)
        elif kind == "compliance":
            comp = unwrap(f.result())
            store.save_compliance(obj, comp)
            stats["compliance_computed"] += 1
            stats["compliance_seconds"].append(round(comp.seconds, 3))
            prog.say(f"geometry {obj}: compliance computed in {comp.seconds:.1f} s (worker pid {comp.pid})")
        else:
            try:
                ds, head = unwrap(f.result())
            except ConvergenceError as exc:
                stats["failed"].append({"variant": obj.id, "torque_nm": extra, "error": str(exc)})
                prog.say(f"variant {obj.id} at {extra:g} N m: {exc}")
                continue
            store.write_point(ds, obj.id, extra, head)
            stats["points_computed"] += 1
            prog.point_done(obj.id)


def run_study(study: Study | str | Path, out: str | Path, scheduler: str | None = None, workers: int | None = None,
              progress: bool = True, plots: bool = True):
    """Run a study (or the rest of it) and return its combined store.

    Parameters
    ----------
    study : Study or path
        The study, or its TOML file.
    out : path
        Output directory: ``points/``, ``compliance/``, ``study.nc``, ``summary.csv``, plots, ``run.json``.
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:port``); default: a new LocalCluster.
    workers : int, optional
        Workers of the LocalCluster (default: the cores of this machine).
    progress : bool
        Variants done / total and the ETA on stderr.
    plots : bool
        Write the plots (the summary CSV is always written).

    Returns
    -------
    xarray.Dataset
        The study store (:func:`ltca.study.store.load_study`); ``attrs["run"]`` (JSON) counts what this run
        computed: points, compliances computed and kept, failed points.
    """
    t0 = time.perf_counter()
    study = study if isinstance(study, Study) else Study.from_toml(study)
    store = StudyStore(out)
    store.root.mkdir(parents=True, exist_ok=True)
    store.clean()
    variants = study.expand()
    todo = {}
    for v in variants:
        left = [t for t in study.torques if not store.finished(v.id, t)]
        if left:
            todo[v.id] = (v, left)
    prog = _Progress(variants, study.torques, store, progress)
    stats = {"points_total": len(variants) * len(study.torques),
             "points_skipped": len(variants) * len(study.torques) - sum(len(t) for _, t in todo.values()),
             "points_computed": 0, "compliance_computed": 0, "compliance_loaded": 0, "compliance_seconds": [],
             "failed": [], "scheduler": scheduler or "LocalCluster", "workers": None}
    if todo:
        with cluster_client(scheduler, workers) as client:
            stats["workers"] = len(client.scheduler_info()["workers"])
            prog.say(f"{len(todo)} variants to run on {stats['workers']} workers")
            _execute(client, study, store, todo, prog, stats)
    stats["wall_s"] = round(time.perf_counter() - t0, 3)
    ds = store.combine(study, variants)
    ds.attrs["run"] = json.dumps(stats)
    write_json(Path(out) / "run.json", stats)
    from .report import write_outputs
    write_outputs(ds, Path(out), study, plots=plots)
    prog.say(f"done in {stats['wall_s']:.1f} s: {stats['points_computed']} points computed, "
             f"{stats['points_skipped']} skipped, {stats['compliance_computed']} compliance(s) computed")
    return ds
