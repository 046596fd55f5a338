"""Checking a catalog: each design checked and its part of the report made in one step
(``entry_of``), in worker processes when the work is large enough, the entries handed back
in input order as they are done (``entries``), ready to be written out one by one.

How many processes (``--jobs N``, default: all cores).  Starting a worker costs about as
much as checking a few small designs, so the files are checked in this process first.
Once the designs after the first (which also pays for the imports) have taken
PARALLEL_AFTER seconds of CPU time, and the files left would take as much again at their
average, the rest go to min(N, files left) worker processes; a small catalog is therefore
never split.  (CPU time measures the work, whatever else the machine is running.)  The
workers are forked where the platform can (they then start with everything this process
has imported), and each task is a run of consecutive files of about TASK_SECONDS of
work.  Which process checks a file changes nothing in the report:
the output is the same for every N.
"""

from __future__ import annotations

import gc
import math
import time
from collections.abc import Iterator, Sequence
from pathlib import Path

from furncheck.report import reporter
from furncheck.report.entries import Entry
from furncheck.result import DesignReport

PARALLEL_AFTER = 0.1
"""CPU seconds of checking in this process (after the first design) before worker
processes are started for the rest, if the rest would take as much again.  Starting two
forked workers and handing them their tasks costs 20 to 40 ms of wall time on an idle
2-core machine: from 0.1 s of work left, two processes are faster than one."""

TASK_SECONDS = 0.1
"""About this much work (at the average time per design so far) is handed to a worker in
one task: a few ms of overhead per task, and the report flows in pieces of this size."""

TASKS_PER_WORKER = 4
"""At least this many tasks per worker, so that uneven designs still balance."""


def entries(sources: Sequence[str | DesignReport], fmt: str, jobs: int,
            model: str | None = None) -> Iterator[Entry]:
    """The entries of format ``fmt`` of ``sources`` (a path to check, or a report already
    made, such as an unreadable folder's), in order, as they are done; the paths checked in
    up to ``jobs`` processes (see the module docstring)."""
    paths = [source for source in sources if isinstance(source, str)]
    checked = _checked(paths, fmt, jobs, model)
    for source in sources:
        yield entry_of_report(source, fmt) if isinstance(source, DesignReport) \
            else next(checked)


def check_one(path: str, model: str | None = None) -> DesignReport:
    """``check_file(path, model)``, with any unexpected exception turned into an error
    report."""
    try:
        from furncheck.check import check_file  # heavy (numpy): imported on use

        report = check_file(path, model)
    except Exception as error:
        return error_report(path, f"internal error: {type(error).__name__}: {error}")
    if not isinstance(report, DesignReport):
        return error_report(path, f"internal error: the checker returned a "
                                  f"{type(report).__name__}, not a DesignReport")
    return report


def entry_of(path: str, fmt: str, model: str | None = None) -> Entry:
    """The design at ``path`` checked (``check_one``) and its entry made."""
    return entry_of_report(check_one(path, model), fmt)


def entry_of_report(report: DesignReport, fmt: str) -> Entry:
    """The entry of ``report`` in format ``fmt``.  Should the reporter fail on it, the
    entry is an error entry saying so, and the batch goes on."""
    module = reporter(fmt)
    try:
        return Entry.of(report, module.piece(report))
    except Exception as error:  # noqa: BLE001 - a reporter bug must not end the batch
        failed = error_report(report.design, f"internal error while writing the {fmt} "
                                             f"report: {type(error).__name__}: {error}")
        return Entry.of(failed, module.piece(failed))


def error_report(path: str, message: str) -> DesignReport:
    """The report of an input that could not be checked."""
    return DesignReport(design=path, name=Path(path).stem or path, valid=None, error=message)


# --- in this process, then in workers -------------------------------------------------------

def _checked(paths: list[str], fmt: str, jobs: int, model: str | None) -> Iterator[Entry]:
    """``entry_of`` of every path, in order: in this process, the rest in workers once the
    work has shown itself large enough (module docstring)."""
    start = None
    for k, path in enumerate(paths):
        if start is not None and jobs > 1:
            spent, left = time.process_time() - start, len(paths) - k
            average = spent / (k - 1) if k > 1 else 0.0
            if spent >= PARALLEL_AFTER and average * left >= PARALLEL_AFTER and left >= 2:
                yield from entries_in_workers(paths[k:], fmt, jobs, model, average)
                return
        yield entry_of(path, fmt, model)
        if start is None:
            start = time.process_time()


def entries_in_workers(paths: list[str], fmt: str, jobs: int, model: str | None = None,
                       average: float = 0.0) -> Iterator[Entry]:
    """``entry_of`` of every path, in order, from min(``jobs``, paths) worker processes, in
    tasks of consecutive paths of about TASK_SECONDS at ``average`` seconds per design;
    in this process if no worker can be started.  A worker that dies leaves error
    entries for the paths it had not given back."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    workers = max(1, min(jobs, len(paths)))
    size = max(1, math.ceil(len(paths) / (workers * TASKS_PER_WORKER)))
    if average > 0.0:
        size = min(size, max(1, round(TASK_SECONDS / average)))
    tasks = [paths[k:k + size] for k in range(0, len(paths), size)]
    try:
        context = multiprocessing.get_context("fork")
    except ValueError:          # no fork here: the platform's way (workers import anew)
        context = None
    gc.freeze()     # the workers leave this process's objects alone (no copied pages)
    try:
        pool = ProcessPoolExecutor(max_workers=workers, mp_context=context)
    except (OSError, NotImplementedError, ImportError):  # no multiprocessing here
        gc.unfreeze()
        yield from (entry_of(path, fmt, model) for path in paths)
        return
    given, finished = 0, False
    try:
        try:
            for done in pool.map(_entries_of_task, tasks, [fmt] * len(tasks),
                                 [model] * len(tasks)):
                given += len(done)
                yield from done
        except Exception as error:  # a worker died (BrokenProcessPool), or cannot reply
            reason = f"internal error: a checking process failed ({type(error).__name__})"
            for path in paths[given:]:
                yield entry_of_report(error_report(path, reason), fmt)
        finished = True
    finally:        # left early (the reader stopped): the tasks not started are dropped
        pool.shutdown(wait=finished, cancel_futures=not finished)
        gc.unfreeze()


def _entries_of_task(paths: list[str], fmt: str, model: str | None) -> list[Entry]:
    """In a worker: the entries of one task's paths."""
    return [entry_of(path, fmt, model) for path in paths]
