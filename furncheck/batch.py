"""Checking a catalog: each design checked and its part of the report made in one step
(``entry_of``), in worker processes when the work is large enough, the entries handed back
in input order as they are done (``entries``), ready to be written out one by one.

How many processes (``--jobs N``, default: all cores).  Starting a worker costs about as
much as checking a few small designs, so the files are checked in this process first.
Once the designs after the first (which also pays for the imports) have taken
PARALLEL_AFTER seconds of CPU time, and the files left would take as much again at their
average, the rest go to min(N, files left) worker processes; a small catalog is therefore
never split.  (CPU time measures the work whatever else the machine is running.)  The
workers are forked where the platform can (they then start with everything this process
has imported), and each task is a run of consecutive files of about TASK_SECONDS of work.
Which process checks a file changes nothing in the report: the output is the same for
every N.

With the result cache (``furncheck.cache``), only the files whose result is not stored are
checked (and counted above); the others' entries come from their stored piece of the
report in the format, or are made from their stored result.
"""

from __future__ import annotations

import contextlib
import gc
import math
import os
import time
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING

from furncheck.report import reporter
from furncheck.report.entries import Entry
from furncheck.result import DesignReport
from furncheck.scan import error_report
from furncheck.workers import local_jobs, stop_pool

if TYPE_CHECKING:
    from furncheck.cache import ResultCache

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


def entries(sources: Sequence[str | DesignReport], fmt: str, jobs: int | None,
            model: str | None = None, cache: ResultCache | None = None,
            progress: Progress | None = None, client=None) -> Iterator[Entry]:
    """The entries of format ``fmt`` of ``sources`` (a path to check, or a report already
    made, such as an unreadable folder's), in order, as they are done; the paths checked in
    up to ``jobs`` processes, at most the CPUs this run may use (``workers.local_jobs``;
    None: all of them; see the module docstring).

    With a ``cache`` (``furncheck.cache``): a path whose piece in ``fmt`` is stored gets
    it back as it is; one whose result is stored gets its piece made from it (and stored);
    the others are checked, and their results and pieces stored: on the Dask cluster of
    ``client`` when given (``furncheck.cluster``), else here.  ``progress(total)``
    (for the paths to check, when there are any) gives None or a context manager whose
    value has ``update(1)``, called as each is done (a click progress bar)."""
    paths = [source for source in sources if isinstance(source, str)]
    keys = [cache.key_of(path) for path in paths] if cache is not None else [None] * len(paths)
    stored = [_stored(cache, key, fmt) for key in keys]
    to_check = [(path, key) for path, key, kind in zip(paths, keys, stored) if kind is None]
    bar = progress(len(to_check)) if progress is not None and to_check else None
    with bar if bar is not None else contextlib.nullcontext() as shown:
        if client is not None:
            from furncheck.cluster import cluster_entries

            checked = cluster_entries(client, to_check, fmt, model, cache)
        else:
            checked = _checked(to_check, fmt, local_jobs(jobs), model, cache)
        if shown is not None:
            checked = _advancing(checked, shown)
        path_index = 0
        for source in sources:
            if isinstance(source, DesignReport):
                yield entry_of_report(source, fmt)
                continue
            key, kind = keys[path_index], stored[path_index]
            path_index += 1
            if kind is None:
                entry = next(checked)
                if cache is not None and cache.unwritable is not None and not entry.error:
                    cache.lost += 1     # (a worker's copy of the cache counted it there)
                yield entry
                continue
            entry = _from_cache(cache, source, key, kind, fmt)
            if entry is None:           # a damaged entry: checked here, stored again
                entry = entry_of(source, fmt, model, cache, key)
            yield entry


Progress = Callable[[int], "contextlib.AbstractContextManager | None"]
"""``progress(total)``: see ``entries``."""


def _stored(cache: ResultCache | None, key: str | None, fmt: str) -> str | None:
    """What the cache holds for ``key``: 'piece' (in ``fmt``), 'result', or None."""
    if cache is None or key is None:
        return None
    if os.path.isfile(cache.piece_path(key, fmt)):
        return "piece"
    if os.path.isfile(cache.entry_path(key)):
        return "result"
    return None


def _from_cache(cache: ResultCache, path: str, key: str, kind: str, fmt: str
                ) -> Entry | None:
    """The entry of ``path`` from its stored piece or result; None if that entry turns out
    damaged (the path is then checked again)."""
    if kind == "piece":
        fields = cache.get_piece(key, fmt)
        if fields is not None and any(fields[0] is v for v in (True, False, None)) \
                and type(fields[1]) is bool and reporter(fmt).is_piece(fields[2]):
            return Entry(*fields)           # (one of another shape: made again below)
    report = cache.get(key, path)
    if report is None:
        return None
    entry = entry_of_report(report, fmt)
    cache.put_piece(key, fmt, (entry.valid, entry.error, entry.piece))
    return entry


def _advancing(checked: Iterator[Entry], shown) -> Iterator[Entry]:
    for entry in checked:
        shown.update(1)
        yield entry


def check_one(path: str, model: str | None = None) -> DesignReport:
    """``check_file(path, model)``, with any unexpected exception turned into an error
    report."""
    def check() -> DesignReport:
        from furncheck.check import check_file  # heavy (numpy): imported on use

        return check_file(path, model)

    return guarded(path, check)


def guarded(source: str, check: Callable[[], DesignReport]) -> DesignReport:
    """``check()``, the report of the design ``source``; an unexpected exception, or
    something else than a report, turned into an error report saying so."""
    try:
        report = check()
    except Exception as error:
        return error_report(source, f"internal error: {type(error).__name__}: {error}")
    if not isinstance(report, DesignReport):
        return error_report(source, f"internal error: the checker returned a "
                                    f"{type(report).__name__}, not a DesignReport")
    return report


def entry_of(path: str, fmt: str, model: str | None = None,
             cache: ResultCache | None = None, key: str | None = None) -> Entry:
    """The design at ``path`` checked (``check_one``) and its entry made; with a ``cache``
    (and ``key``, the file's ``key_of`` before the check), its result and piece stored
    (``ResultCache.store``: only if the file did not change meanwhile)."""
    report = check_one(path, model)
    entry = entry_of_report(report, fmt)
    if cache is not None and cache.store(path, key, report):
        cache.put_piece(key, fmt, (entry.valid, entry.error, entry.piece))
    return entry


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




# --- in this process, then in workers -------------------------------------------------------

def _checked(items: list[tuple[str, str | None]], fmt: str, jobs: int, model: str | None,
             cache: ResultCache | None = None) -> Iterator[Entry]:
    """``entry_of`` of every (path, cache key), in order: in this process, the rest in
    workers once the work has shown itself large enough (module docstring)."""
    start = None
    for k, (path, key) in enumerate(items):
        if start is not None and jobs > 1:
            spent, left = time.process_time() - start, len(items) - k
            average = spent / (k - 1) if k > 1 else 0.0
            if spent >= PARALLEL_AFTER and average * left >= PARALLEL_AFTER and left >= 2:
                rest = items[k:]
                yield from entries_in_workers([path for path, _ in rest], fmt, jobs, model,
                                              average, cache, [key for _, key in rest])
                return
        yield entry_of(path, fmt, model, cache, key)
        if start is None:
            start = time.process_time()


def entries_in_workers(paths: list[str], fmt: str, jobs: int, model: str | None = None,
                       average: float = 0.0, cache: ResultCache | None = None,
                       keys: list[str | None] | None = None) -> Iterator[Entry]:
    """``entry_of`` of every path, in order, from min(``jobs``, paths) worker processes, in
    tasks of consecutive paths of about TASK_SECONDS at ``average`` seconds per design;
    in this process if no worker can be started.  A worker that dies leaves error
    entries for the paths it had not given back.  With a ``cache``, the workers store
    each result under its key of ``keys``."""
    keys = keys if keys is not None else [None] * len(paths)
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    from furncheck.workers import pool_options

    workers = max(1, min(jobs, len(paths)))
    size = max(1, math.ceil(len(paths) / (workers * TASKS_PER_WORKER)))
    if average > 0.0:
        size = min(size, max(1, round(TASK_SECONDS / average)))
    items = list(zip(paths, keys))
    tasks = [items[k:k + size] for k in range(0, len(items), size)]
    try:
        context = multiprocessing.get_context("fork")
    except ValueError:          # no fork here: the platform's way (workers import anew)
        context = None
    gc.freeze()     # the workers leave this process's objects alone (no copied pages)
    try:
        pool = ProcessPoolExecutor(max_workers=workers, mp_context=context,
                                   **pool_options())
    except (OSError, NotImplementedError, ImportError):  # no multiprocessing here
        gc.unfreeze()
        yield from (entry_of(path, fmt, model, cache, key) for path, key in items)
        return
    given, finished = 0, False
    try:
        try:
            for done in pool.map(_entries_of_task, tasks, [fmt] * len(tasks),
                                 [model] * len(tasks), [cache] * len(tasks)):
                given += len(done)
                yield from done
        except Exception as error:  # a worker died (BrokenProcessPool), or cannot reply
            reason = f"internal error: a checking process failed ({type(error).__name__})"
            for path in paths[given:]:
                yield entry_of_report(error_report(path, reason), fmt)
        finished = True
    finally:        # left early (the reader stopped, or a signal): nothing more is waited for
        if finished:
            pool.shutdown(wait=True)
        else:
            stop_pool(pool)
        gc.unfreeze()


def _entries_of_task(items: list[tuple[str, str | None]], fmt: str, model: str | None,
                     cache: ResultCache | None = None) -> list[Entry]:
    """In a worker: the entries of one task's (path, cache key) pairs."""
    return [entry_of(path, fmt, model, cache, key) for path, key in items]
