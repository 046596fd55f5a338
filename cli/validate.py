"""``furncheck validate PATH...``: check designs, write one report, exit 0 / 1 / 2.

The command is thin: read the options (command line over ``[tool.furncheck]``:
``furncheck.config``), collect the design files (``furncheck.scan``), run
``furncheck.check.check_file`` on each that the result cache (``furncheck.cache``) does not
hold (in worker processes for a catalog), render the ``BatchReport`` with the chosen
reporter, write it, and exit with ``BatchReport.return_code``.  Every input gets a report
entry, also a missing path or a file of another type (``check_file`` says what is wrong),
so one bad file never hides the verdicts on the others.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Callable

import click

from furncheck.cli.output import (
    MODEL_OPTION,
    check_output,
    config_or_fail,
    fail,
    write_output,
)
from furncheck.report import REPORTERS, render
from furncheck.result import BatchReport, DesignReport

PARALLEL_MIN_FILES = 8
"""Fewer files than this are checked in-process: starting workers would cost more."""

CHUNKS_PER_WORKER = 4
"""Work is handed to each worker in about this many chunks (balance vs. overhead)."""

PROGRESS_MIN_FILES = 50
"""A progress bar is shown on a terminal's stderr from this many files to check on."""

STDIN = "-"
"""The PATH that stands for a design on standard input (``furncheck.scan.STDIN``)."""

STDIN_NAME = "<stdin>"
"""How reports name a design read from standard input without ``--stdin-filename``."""


@click.command()
@click.argument("paths", metavar="PATH...", nargs=-1, required=True)
@click.option("--format", "fmt", type=click.Choice(list(REPORTERS)), default=None,
              help="Report format.  [default: text]")
@click.option("-o", "--output", metavar="FILE", default=None,
              help="Write the report to FILE instead of standard output ('-': stdout); "
                   "the old FILE stays whole until the new report replaces it.")
@click.option("-j", "--jobs", type=click.IntRange(min=1), default=None,
              help=f"Worker processes, used from {PARALLEL_MIN_FILES} files on.  "
                   "[default: all cores]")
@click.option("--views", "views_dir", metavar="DIR", default=None,
              help="Also write a view of each design there, DIR/<name>-view.png (needs "
                   "the export extra).")
@click.option("--html", "html_file", metavar="FILE", default=None,
              help="Also write a report page of the whole run there: a sortable, "
                   "filterable table of the designs (verdict, worst utilization, "
                   "violations, a view of each) and their details; one self-contained "
                   "file that opens offline.")
@MODEL_OPTION
@click.option("--exclude", "excludes", metavar="GLOB", multiple=True,
              help="Leave out what this gitignore pattern matches in directory scans, "
                   "relative to the current folder (repeatable), e.g. --exclude drafts.")
@click.option("--skip-non-designs", is_flag=True, default=None,
              help="Leave out named files without a top-level 'furncheck' key too, as "
                   "directory scans do (for hooks that pass every changed file).")
@click.option("--cache/--no-cache", "use_cache", default=None,
              help="Reuse the results of unchanged designs.  [default: --cache]")
@click.option("--cache-dir", metavar="DIR", default=None,
              help="Where results are cached.  [default: $FURNCHECK_CACHE_DIR, else the "
                   "user cache directory, e.g. ~/.cache/furncheck]")
@click.option("--stdin-filename", metavar="NAME", default=None,
              help="The name reports give a design read from '-' (standard input); its "
                   "extension picks YAML or JSON.  [default: <stdin>, format by content]")
def validate(paths: tuple[str, ...], fmt: str | None, output: str | None, jobs: int | None,
             views_dir: str | None, html_file: str | None, model: str | None,
             excludes: tuple[str, ...],
             skip_non_designs: bool | None,
             use_cache: bool | None, cache_dir: str | None,
             stdin_filename: str | None) -> None:
    """Check the designs in PATH... (files, '-' for standard input, or directories
    searched recursively for .yaml, .yml and .json files with a top-level 'furncheck'
    key; hidden files and folders, what .gitignore files ignore and --exclude patterns
    are left out; a file named here is always checked).  Options also come from
    [tool.furncheck] in the nearest pyproject.toml; the command line wins.

    Exit code 0: every design valid; 1: some design invalid; 2: some input could not be
    read or is ill-formed (its entry in the report says why), or a usage error.
    """
    from furncheck.ignores import patterns
    from furncheck.scan import ScanOptions, collect

    config = config_or_fail(paths)
    fmt = fmt or config.format or "text"
    model = model or config.model
    jobs = jobs or config.jobs or os.cpu_count() or 1
    check_output(output)
    if html_file is not None:
        check_output(html_file)
    if views_dir is not None:
        _check_views_dir(views_dir)
    scan_options = ScanOptions(
        excludes=tuple(rule for rule in (
            patterns(excludes, os.curdir, "--exclude") if excludes else None,
            patterns(config.exclude, config.folder, config.path) if config.exclude else None)
            if rule is not None),
        skip_non_designs=bool(skip_non_designs or config.skip_non_designs))
    collected = collect(paths, scan_options)
    if collected.skipped:
        click.echo(f"furncheck: skipped {collected.skipped} "
                   f"file{'s' if collected.skipped != 1 else ''} without a top-level "
                   f"'furncheck' key (not designs)", err=True)
    cache = None
    if use_cache if use_cache is not None else config.cache is not False:
        cache = open_cache(cache_dir or config.cache_dir, model)
    sources = [_check_stdin(stdin_filename, model, cache) if source == STDIN else source
               for source in collected.sources]
    to_check = [source for source in sources if isinstance(source, str)]
    checked = iter(check_paths(to_check, jobs, model, cache))
    batch = BatchReport(tuple(source if isinstance(source, DesignReport) else next(checked)
                              for source in sources))
    if cache is not None and cache.unwritable:
        click.echo(f"furncheck: results not cached: {cache.unwritable}", err=True)
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
    if html_file is not None:
        from furncheck.export.catalog import write_catalog_page

        try:
            write_catalog_page(batch.reports, html_file)
        except OSError as error:
            fail(f"cannot write the report page {html_file}: {error.strerror or error}")
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


def open_cache(directory: str | None, model: str | None):
    """The result cache in ``directory`` (default: the user cache directory) for runs in
    ``model``."""
    from furncheck.cache import ResultCache, default_directory

    return ResultCache(directory or default_directory(), {"model": model})


def check_paths(paths: list[str], jobs: int, model: str | None, cache) -> list[DesignReport]:
    """``check_all`` of ``paths``, through ``cache`` when there is one, with a progress bar
    for the files that are checked (not those read from the cache)."""
    from furncheck.cache import check_with_cache

    def check_many(some: list[str]) -> list[DesignReport]:
        bar = _progress_bar(len(some))
        if bar is None:
            return check_all(some, jobs, model)
        with bar:
            return check_all(some, jobs, model, lambda: bar.update(1))

    if cache is None:
        return check_many(paths)
    return list(check_with_cache(paths, cache, check_many))


def _progress_bar(total: int):
    """A click progress bar on stderr for ``total`` files to check when stderr is a
    terminal and they are at least PROGRESS_MIN_FILES, else None."""
    if total < PROGRESS_MIN_FILES or not _is_terminal(sys.stderr):
        return None
    return click.progressbar(length=total, label="checking", file=sys.stderr,
                             show_pos=True, show_percent=False)


def _is_terminal(stream) -> bool:
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


def _check_stdin(name: str | None, model: str | None, cache) -> DesignReport:
    """The report of the design on standard input (cached like a file's)."""
    from furncheck.check import check_data
    from furncheck.scan import error_report

    data = sys.stdin.buffer.read()
    source = name or STDIN_NAME
    suffix = os.path.splitext(source)[1].lower()
    fmt = {".json": "json", ".yaml": "yaml", ".yml": "yaml"}.get(suffix)
    if fmt is None:
        fmt = "json" if data.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"{") else "yaml"
    key = cache.key(source, data) if cache is not None else None
    report = cache.get(key, source) if cache is not None else None
    if report is None:
        try:
            report = check_data(data, source, fmt, model)
        except Exception as error:
            return error_report(source, f"internal error: {type(error).__name__}: {error}")
        if cache is not None:
            cache.put(key, report)
    return report


# --- checking -------------------------------------------------------------------------------

def check_all(paths: list[str], jobs: int, model: str | None = None,
              on_result: Callable[[], object] | None = None) -> list[DesignReport]:
    """``check_one`` of every path, in order; in ``jobs`` worker processes for many files.
    ``on_result`` is called as each report arrives (a progress bar).

    The result is the same either way; if worker processes cannot be started at all the
    files are checked in this process.
    """
    if jobs > 1 and len(paths) >= PARALLEL_MIN_FILES:
        reports = _check_in_workers(paths, jobs, model, on_result)
        if reports is not None:
            return reports
    reports = []
    for path in paths:
        reports.append(check_one(path, model))
        if on_result is not None:
            on_result()
    return reports


def check_one(path: str, model: str | None = None) -> DesignReport:
    """``check_file(path, model)``, with any unexpected exception turned into an error
    report."""
    from furncheck.scan import error_report

    try:
        from furncheck.check import check_file  # heavy (numpy, scipy): imported on use

        report = check_file(path, model)
    except Exception as error:
        return error_report(path, f"internal error: {type(error).__name__}: {error}")
    if not isinstance(report, DesignReport):
        return error_report(path, f"internal error: the checker returned a "
                                   f"{type(report).__name__}, not a DesignReport")
    return report


def _check_in_workers(paths: list[str], jobs: int, model: str | None = None,
                      on_result: Callable[[], object] | None = None
                      ) -> list[DesignReport] | None:
    """Reports from a process pool, or None when the pool cannot be started."""
    from concurrent.futures import ProcessPoolExecutor

    from furncheck.scan import error_report

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
                if on_result is not None:
                    on_result()
        except Exception as error:  # a worker died (BrokenProcessPool) or could not reply
            reason = f"internal error: a checking process failed ({type(error).__name__})"
            reports.extend(error_report(path, reason) for path in paths[len(reports):])
    return reports

