"""Worker processes: how many a run may use (``usable_cpus``, ``local_jobs``), and what
every worker of furncheck's pools does first (``quiet_worker``)."""

from __future__ import annotations

import contextlib
import math
import os
import signal

CGROUP_FILES = ("/sys/fs/cgroup/cpu.max",
                ("/sys/fs/cgroup/cpu/cpu.cfs_quota_us", "/sys/fs/cgroup/cpu/cpu.cfs_period_us"))
"""Where a container's CPU quota is read: cgroup v2's ``cpu.max`` ('QUOTA PERIOD' or
'max PERIOD'), else cgroup v1's quota and period files (quota -1: none)."""


def usable_cpus() -> int:
    """The CPUs this process may keep busy: those it may run on (its affinity: ``taskset``,
    a runner's cpuset), at most a container's CPU quota rounded up (a GitLab or Kubernetes
    job given 2 CPUs on a 64-core host, where ``os.cpu_count()`` says 64); at least 1."""
    try:
        count = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):       # no affinity on this platform
        count = os.cpu_count() or 1
    quota = _cgroup_quota()
    if quota is not None:
        count = min(count, quota)
    return max(1, count)


def _cgroup_quota() -> int | None:
    """The container's CPU quota in whole CPUs (rounded up), None without one."""
    v2, (v1_quota, v1_period) = CGROUP_FILES
    try:
        with open(v2, encoding="ascii") as stream:
            quota, period = stream.read().split()[:2]
        if quota == "max":
            return None
        return math.ceil(int(quota) / int(period))
    except (OSError, ValueError):
        pass
    try:
        with open(v1_quota, encoding="ascii") as stream:
            quota = int(stream.read())
        with open(v1_period, encoding="ascii") as stream:
            period = int(stream.read())
    except (OSError, ValueError):
        return None
    return math.ceil(quota / period) if quota > 0 and period > 0 else None


def local_jobs(jobs: int | None) -> int:
    """How many processes a run on this machine uses for ``--jobs`` (None: the default):
    at most ``usable_cpus`` (more only compete for the same CPUs: 40 workers on 2 CPUs
    were slower than 2), all of them by default.  The output is the same for any count."""
    usable = usable_cpus()
    return usable if jobs is None else max(1, min(jobs, usable))


def quiet_worker() -> None:
    """A pool's initializer: Ctrl-C is left to the parent process.  The terminal sends it
    to the whole process group; a worker that took it printed a KeyboardInterrupt
    traceback from inside ``multiprocessing`` after the parent's own one-line 'Aborted!'.
    Ignoring it, each worker ends with its current task when the parent shuts the pool
    down.  SIGTERM ends a worker at once, as by default (a forked worker would otherwise
    inherit the command line's handler, which unwinds the parent's run)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def stop_pool(pool) -> None:
    """Shut a process pool down without waiting for its workers' tasks under way: the run
    was interrupted (or its reader stopped), their results would be thrown away, and
    waiting held an interrupted command for seconds (the interpreter's exit joins a
    pool's workers).  Its workers are terminated (``concurrent.futures`` has no public
    way before Python 3.14: its process table is read)."""
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        try:
            process.terminate()
        except (OSError, ValueError, AttributeError):
            pass
    pool.shutdown(wait=False, cancel_futures=True)


@contextlib.contextmanager
def process_pool(**options):
    """A ``ProcessPoolExecutor(**options)`` for a ``with`` block: shut down waiting for its
    tasks when the block ends, without waiting (``stop_pool``) when it is left by an
    exception (a signal: the command stops at once)."""
    from concurrent.futures import ProcessPoolExecutor

    pool = ProcessPoolExecutor(**options)
    try:
        yield pool
    except BaseException:
        stop_pool(pool)
        raise
    pool.shutdown(wait=True)
