"""Sharing the DOFs of a ``range`` among processes: forked worker processes (``--jobs``)
or a Dask cluster (``--scheduler``, ``furncheck.cluster``).

Every DOF's search is independent of the others, so the ranges are the same however the
DOFs are shared.  The DOFs are dealt out in shares (``shares``): tasks of at most
DOFS_PER_TASK DOFs, at least two per worker, the DOFs of each kind in turn.
"""

from __future__ import annotations

import gc
import multiprocessing
import time
from concurrent.futures.process import BrokenProcessPool
from typing import TYPE_CHECKING

from furncheck.dofs import DOF_KINDS, Dof
from furncheck.workers import pool_options, process_pool

if TYPE_CHECKING:
    from furncheck.ranges.finder import DofRange, RangeFinder

PARALLEL_MIN_DOFS = 16
"""Fewer DOFs than this are searched in this process: starting workers would cost more."""

PARALLEL_AFTER = 1.0
"""CPU seconds: with ``jobs`` > 1 samples of the first two shares of the DOFs are searched
in this process, and the rest goes to worker processes only if it would take at least
this much work here (at the second sample's CPU time per DOF); else it is searched here
too."""

SAMPLE_STRIDE = 4
"""The samples searched here before the workers start: every SAMPLE_STRIDE-th DOF of each
of the first two shares when they are full tasks (DOFS_PER_TASK DOFs; smaller shares are
searched whole, as their pace is the noisier).  A share holds DOFs of every kind in turn,
so a stride keeps them mixed; the smaller the samples, the less of the work waits for
them on one core."""

DOFS_PER_TASK = 16
"""DOFs per task of a worker process: a task's DOFs are searched together (the more, the
larger the batches of evaluations); small tasks balance the uneven DOFs."""


def ranges_shared(finder: RangeFinder, dofs: list[Dof], jobs: int) -> list[DofRange]:
    """The ranges of ``dofs`` in shares for ``jobs`` workers.  A sample of each of the
    first two shares (every SAMPLE_STRIDE-th DOF of full tasks) is searched here, the first's (which
    also pays for what every search shares) and then the second's; the rest (those two
    shares' other DOFs and the other shares) in worker processes when it is worth it at
    the second sample's pace per DOF (``RangeFinder.ranges``), else here."""
    shared = shares(dofs, jobs)
    stride = SAMPLE_STRIDE if len(shared[1]) >= DOFS_PER_TASK else 1
    samples = [share[::stride] for share in shared[:2]]
    rest = [[n for k, n in enumerate(share) if k % stride] for share in shared[:2]]
    rest = [share for share in rest + shared[2:] if share]
    found: list[DofRange | None] = [None] * len(dofs)
    pace = 0.0
    for sample in samples:
        start = time.process_time()
        for n, dof_range in zip(sample, finder.search([dofs[n] for n in sample])[0]):
            found[n] = dof_range
        pace = (time.process_time() - start) / max(len(sample), 1)
    done = None
    if len(rest) > 1 and pace * sum(map(len, rest)) >= PARALLEL_AFTER:
        done = ranges_in_workers(finder, [[dofs[n] for n in share] for share in rest], jobs)
    if done is None and rest:
        together = [n for share in rest for n in share]
        done = [finder.search([dofs[n] for n in together])[0]]
        rest = [together]
    for share, ranges in zip(rest, done or ()):
        for n, dof_range in zip(share, ranges):
            found[n] = dof_range
    return found


def ranges_in_workers(finder: RangeFinder, tasks: list[list[Dof]],
                      jobs: int) -> list[list[DofRange]] | None:
    """The ranges of each task's DOFs, from min(``jobs``, tasks) forked worker processes
    (which inherit ``finder``); None when processes cannot be forked here."""
    global _WORKER_FINDER
    try:
        context = multiprocessing.get_context("fork")
    except ValueError:          # no fork on this platform
        return None
    _WORKER_FINDER = finder
    # The workers inherit this process's objects; frozen, the garbage collector leaves
    # them alone in the workers and does not copy their memory pages by touching them
    # (measured: a tenth of the cabinet's work in the workers).
    gc.freeze()
    try:
        with process_pool(max_workers=min(jobs, len(tasks)), mp_context=context,
                          **pool_options()) as pool:
            done = list(pool.map(_ranges_of, tasks))
    except (OSError, BrokenProcessPool):
        return None
    finally:
        gc.unfreeze()
        _WORKER_FINDER = None
    finder.evaluations += sum(evaluations for _, evaluations in done)
    return [ranges for ranges, _ in done]


def ranges_on_cluster(finder: RangeFinder, dofs: list[Dof], client) -> list[DofRange]:
    """The ranges of ``dofs``, every share (dealt out for the cluster's worker threads)
    searched on the Dask cluster of ``client`` (``furncheck.cluster``)."""
    from furncheck.cluster import cluster_ranges, worker_threads

    shared = shares(dofs, worker_threads(client))
    done = cluster_ranges(client, finder.design, finder.locked_names,
                          [[dofs[n] for n in share] for share in shared])
    found: list[DofRange | None] = [None] * len(dofs)
    for share, (ranges, evaluations) in zip(shared, done):
        finder.evaluations += evaluations
        for n, dof_range in zip(share, ranges):
            found[n] = dof_range
    return found


def shares(dofs: list[Dof], workers: int) -> list[list[int]]:
    """The indices of ``dofs`` in shares for ``workers``: tasks of at most DOFS_PER_TASK
    DOFs, at least two per worker, the DOFs of each kind dealt out in turn (DOFs of one
    kind are alike in cost: rotations cost most)."""
    count = min(len(dofs), max(2 * workers, -(-len(dofs) // DOFS_PER_TASK)))
    order = sorted(range(len(dofs)), key=lambda n: (DOF_KINDS.index(dofs[n].kind), n))
    return [order[k::count] for k in range(count)]


_WORKER_FINDER: RangeFinder | None = None
"""The finder whose DOFs a forked worker process searches (set while its pool runs)."""


def _ranges_of(dofs: list[Dof]) -> tuple[list[DofRange], int]:
    """In a worker process: the ranges of ``dofs`` and the evaluations they took."""
    return _WORKER_FINDER.search(dofs)
