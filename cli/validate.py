"""``furncheck validate PATH...``: check designs, write one report, exit 0 / 1 / 2.

The command is thin: collect the design files, run ``furncheck.check.check_file`` on each
(in worker processes for a catalog), render the ``BatchReport`` with the chosen reporter,
write it, and exit with ``BatchReport.return_code``.  Every input gets a report entry,
also a missing path or a file of another type (``check_file`` says what is wrong), so one
bad file never hides the verdicts on the others.
"""

from __future__ import annotations

import math
import os
from pathlib import Path, PurePath

import click

from furncheck.cli.output import MODEL_OPTION, check_output, fail, write_output
from furncheck.report import REPORTERS, render
from furncheck.result import BatchReport, DesignReport

DESIGN_SUFFIXES = (".yaml", ".yml", ".json")
"""Extensions of design files found when a PATH is a directory (case-insensitive)."""

PARALLEL_MIN_FILES = 8
"""Fewer files than this are checked in-process: starting workers would cost more."""

CHUNKS_PER_WORKER = 4
"""Work is handed to each worker in about this many chunks (balance vs. overhead)."""


@click.command()
@click.argument("paths", metavar="PATH...", nargs=-1, required=True)
@click.option("--format", "fmt", type=click.Choice(list(REPORTERS)), default="text",
              show_default=True, help="Report format.")
@click.option("-o", "--output", metavar="FILE", default=None,
              help="Write the report to FILE instead of standard output ('-': stdout).")
@click.option("-j", "--jobs", type=click.IntRange(min=1), default=None,
              help=f"Worker processes, used from {PARALLEL_MIN_FILES} files on.  "
                   "[default: all cores]")
@click.option("--views", "views_dir", metavar="DIR", default=None,
              help="Also write a view of each design there, DIR/<name>-view.png (needs "
                   "the export extra).")
@MODEL_OPTION
def validate(paths: tuple[str, ...], fmt: str, output: str | None, jobs: int | None,
             views_dir: str | None, model: str | None) -> None:
    """Check the designs in PATH... (files, or directories searched recursively for
    .yaml, .yml and .json files; hidden files and folders are skipped).

    Exit code 0: every design valid; 1: some design invalid; 2: some input could not be
    read or is ill-formed (its entry in the report says why), or a usage error.
    """
    check_output(output)
    if views_dir is not None:
        _check_views_dir(views_dir)
    sources = collect_sources(paths)
    to_check = [source for source in sources if isinstance(source, str)]
    checked = iter(check_all(to_check, jobs if jobs is not None else (os.cpu_count() or 1),
                             model))
    batch = BatchReport(tuple(source if isinstance(source, DesignReport) else next(checked)
                              for source in sources))
    try:
        document = render(batch, fmt)
    except Exception as error:  # a reporter bug must not become a traceback
        fail(f"internal error while writing the {fmt} report: {type(error).__name__}: {error}")
    write_output(document, output)
    if views_dir is not None:
        from furncheck.export.catalog import write_catalog_views

        try:
            write_catalog_views(batch.reports, views_dir, model)
        except OSError as error:
            fail(f"cannot write views to {views_dir}: {error.strerror or error}")
    click.get_current_context().exit(batch.return_code)


def _check_views_dir(views_dir: str) -> None:
    """Fail before any work when ``--views DIR`` cannot be written or drawn."""
    from furncheck.export.folders import pictures_missing, prepare_out_dir

    problem = prepare_out_dir(views_dir)
    if problem:
        fail(f"cannot write views to {views_dir}: {problem}")
    missing = pictures_missing()
    if missing is not None:
        fail(f"cannot write views: {missing}")


# --- collecting files -----------------------------------------------------------------------

def collect_sources(paths: tuple[str, ...] | list[str]) -> list[str | DesignReport]:
    """The files to check, in order: each PATH as given, or a directory's design files.

    A directory without design files becomes an error report in its place.  A file named
    twice (or also found in a named directory) is checked once, at its first place.
    """
    sources: list[str | DesignReport] = []
    seen: set[str] = set()
    for given in paths:
        if os.path.isdir(given):
            files, unreadable = find_design_files(given)
            sources.extend(_error_report(folder, f"{folder}: cannot read this directory: {why}")
                           for folder, why in unreadable)
            if not files and not unreadable:
                sources.append(_error_report(
                    given, f"{given}: no design files ({', '.join(DESIGN_SUFFIXES)}) "
                           f"in this directory"))
        else:
            files = [given]
        for file in files:
            key = os.path.normcase(os.path.abspath(file))
            if key not in seen:
                seen.add(key)
                sources.append(file)
    return sources


def find_design_files(directory: str) -> tuple[list[str], list[tuple[str, str]]]:
    """(design files under ``directory``, sorted; [(unreadable folder, reason)]).

    Searches recursively, skips names starting with '.', does not follow symlinked
    folders.  Paths are ``directory`` joined with the relative path, normalized.
    """
    files: list[str] = []
    unreadable: list[tuple[str, str]] = []

    def on_error(error: OSError) -> None:
        unreadable.append((os.path.normpath(error.filename or directory),
                           error.strerror or str(error)))

    for folder, subfolders, names in os.walk(directory, onerror=on_error):
        subfolders[:] = sorted(name for name in subfolders if not name.startswith("."))
        files.extend(os.path.normpath(os.path.join(folder, name)) for name in names
                     if not name.startswith(".")
                     and os.path.splitext(name)[1].lower() in DESIGN_SUFFIXES)
    files.sort(key=lambda file: PurePath(file).parts)
    unreadable.sort()
    return files, unreadable


# --- checking -------------------------------------------------------------------------------

def check_all(paths: list[str], jobs: int, model: str | None = None) -> list[DesignReport]:
    """``check_one`` of every path, in order; in ``jobs`` worker processes for many files.

    The result is the same either way; if worker processes cannot be started at all the
    files are checked in this process.
    """
    if jobs > 1 and len(paths) >= PARALLEL_MIN_FILES:
        reports = _check_in_workers(paths, jobs, model)
        if reports is not None:
            return reports
    return [check_one(path, model) for path in paths]


def check_one(path: str, model: str | None = None) -> DesignReport:
    """``check_file(path, model)``, with any unexpected exception turned into an error
    report."""
    try:
        from furncheck.check import check_file  # heavy (numpy, scipy): imported on use

        report = check_file(path, model)
    except Exception as error:
        return _error_report(path, f"internal error: {type(error).__name__}: {error}")
    if not isinstance(report, DesignReport):
        return _error_report(path, f"internal error: the checker returned a "
                                   f"{type(report).__name__}, not a DesignReport")
    return report


def _check_in_workers(paths: list[str], jobs: int,
                      model: str | None = None) -> list[DesignReport] | None:
    """Reports from a process pool, or None when the pool cannot be started."""
    from concurrent.futures import ProcessPoolExecutor

    try:  # import the checker once here: forked workers then start with it loaded
        import furncheck.check  # noqa: F401
    except Exception:  # noqa: BLE001 - check_one turns the same failure into error entries
        pass
    workers = min(jobs, len(paths))
    chunksize = max(1, math.ceil(len(paths) / (workers * CHUNKS_PER_WORKER)))
    try:
        pool = ProcessPoolExecutor(max_workers=workers)
    except (OSError, NotImplementedError, ImportError):  # no multiprocessing here
        return None
    reports: list[DesignReport] = []
    with pool:
        try:
            for report in pool.map(check_one, paths, [model] * len(paths),
                                   chunksize=chunksize):
                reports.append(report)
        except Exception as error:  # a worker died (BrokenProcessPool) or could not reply
            reason = f"internal error: a checking process failed ({type(error).__name__})"
            reports.extend(_error_report(path, reason) for path in paths[len(reports):])
    return reports


# --- small helpers --------------------------------------------------------------------------

def _error_report(path: str, message: str) -> DesignReport:
    return DesignReport(design=path, name=Path(path).stem or path, valid=None, error=message)
