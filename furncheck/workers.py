"""Worker processes: how many a run may use (``usable_cpus``, ``local_jobs``), and what
every worker of furncheck's pools does first (``quiet_worker``)."""

from __future__ import annotations

import contextlib
import math
import os
import signal

CGROUP_ROOT = "/sys/fs/cgroup"
"""Where the cgroup file systems are mounted: cgroup v2's ``cpu.max`` ('QUOTA PERIOD' or
'max PERIOD') in this process's own cgroup folder and each folder above it, else cgroup
v1's ``cpu/cpu.cfs_quota_us`` and ``cpu/cpu.cfs_period_us`` (quota -1: none)."""

CGROUP_SELF = "/proc/self/cgroup"
"""This process's cgroups: the v2 line '0::/path' names its folder below CGROUP_ROOT."""


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
    """The container's CPU quota in whole CPUs (rounded up), None without one: the least
    of the cgroup v2 limits on this process's cgroup and those above it (a job's limit
    may sit on a parent), else cgroup v1's."""
    quotas = [q for q in map(_quota_of_cpu_max, _cpu_max_files()) if q is not None]
    if quotas:
        return min(quotas)
    v1 = os.path.join(CGROUP_ROOT, "cpu")
    return _quota(_read(os.path.join(v1, "cpu.cfs_quota_us")),
                  _read(os.path.join(v1, "cpu.cfs_period_us")))


def _cpu_max_files() -> list[str]:
    """cgroup v2's ``cpu.max`` of this process's cgroup and of every cgroup above it."""
    own = ""
    for line in (_read(CGROUP_SELF) or "").splitlines():
        if line.startswith("0::"):
            own = line[3:].strip()
    folder = os.path.normpath(os.path.join(CGROUP_ROOT, own.lstrip("/")))
    files = []
    while True:
        files.append(os.path.join(folder, "cpu.max"))
        if os.path.normpath(folder) == os.path.normpath(CGROUP_ROOT) or \
                os.path.dirname(folder) == folder:
            return files
        folder = os.path.dirname(folder)


def _quota_of_cpu_max(path: str) -> int | None:
    fields = (_read(path) or "").split()
    return _quota(*fields[:2]) if len(fields) >= 2 else None


def _quota(quota: str | None, period: str | None) -> int | None:
    """ceil(quota / period) CPUs, None where there is no limit ('max', -1, 0, missing or
    not a number)."""
    try:
        quota_us, period_us = int(quota), int(period)
    except (TypeError, ValueError):
        return None
    if quota_us <= 0 or period_us <= 0:
        return None
    return math.ceil(quota_us / period_us)


def _read(path: str) -> str | None:
    try:
        with open(path, encoding="ascii", errors="replace") as stream:
            return stream.read()
    except OSError:
        return None


def local_jobs(jobs: int | None) -> int:
    """How many processes a run on this machine uses for ``--jobs`` (None: the default):
    at most ``usable_cpus`` (more only compete for the same CPUs: 40 workers on 2 CPUs
    were slower than 2), all of them by default.  The output is the same for any count."""
    usable = usable_cpus()
    return usable if jobs is None else max(1, min(jobs, usable))


def quiet_worker(parent: int | None = None) -> None:
    """A pool's initializer: Ctrl-C is left to the parent process.  The terminal sends it
    to the whole process group; a worker that took it printed a KeyboardInterrupt
    traceback from inside ``multiprocessing`` after the parent's own one-line 'Aborted!'.
    Ignoring it, each worker ends with its current task when the parent shuts the pool
    down.  SIGTERM ends a worker at once, as by default (a forked worker would otherwise
    inherit the command line's handler, which unwinds the parent's run).

    A worker ends with its parent (``parent``: its process id, given by the pool's
    maker): on Linux the kernel sends it SIGTERM when the parent dies (``prctl``'s
    PR_SET_PDEATHSIG), and one whose parent died before that was set ends at once.  A
    parent killed by SIGKILL (a CI job's timeout, the out-of-memory killer) runs no
    shutdown, and its workers sat blocked on their pipes for good."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if parent is not None:
        _end_with_parent(parent)


PR_SET_PDEATHSIG = 1
"""Linux's prctl option: the signal a process gets when its parent dies."""


def _end_with_parent(parent: int) -> None:
    """Have the kernel end this process with ``parent`` (Linux); elsewhere nothing."""
    import sys

    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
    except (OSError, AttributeError):       # no C library to ask: as before
        return
    if os.getppid() != parent:              # it died before we asked
        os._exit(1)


def pool_options() -> dict:
    """The initializer every furncheck pool runs in its workers (``quiet_worker``) and
    its argument, this process's id: ``ProcessPoolExecutor(**pool_options(), ...)``.
    For pools whose workers are forked by this process from its main thread, as all of
    furncheck's are (``get_context('fork')``): the kernel's signal follows the thread
    that forked, and a forkserver's workers have the server for their parent (each would
    end at once)."""
    return {"initializer": quiet_worker, "initargs": (os.getpid(),)}


def stop_pool(pool) -> None:
    """Shut a process pool down without waiting for its workers' tasks under way: the run
    was interrupted (or its reader stopped), their results would be thrown away, and
    waiting held an interrupted command for seconds (the interpreter's exit joins a
    pool's workers).  Its workers are terminated (``concurrent.futures`` has no public
    way before Python 3.14: its process table is read).  The run is over: what the pool's
    own threads raise as its workers go (a pipe to a terminated worker, seen on a loaded
    machine) is not printed over the command's one line."""
    import threading

    threading.excepthook = _quiet
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


def _quiet(arguments) -> None:
    """A ``threading.excepthook`` that prints nothing (``stop_pool``)."""
