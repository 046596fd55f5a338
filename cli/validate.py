"""``furncheck validate PATH...``: check designs, write one report, exit 0 / 1 / 2.

The command is thin: read the options (command line over ``[tool.furncheck]``:
``furncheck.config``), collect the design files (``furncheck.scan``), check each that the
result cache (``furncheck.cache``) does not hold and make its part of the report with the
chosen reporter (``furncheck.batch``: in worker processes for a large catalog), write the
parts as they come, in input order, and exit with the summary's return code.  Every input
gets a report entry, also a missing path or a file of another type (``check_file`` says
what is wrong), so one bad file never hides the verdicts on the others.
"""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING

import click

from furncheck.cli.output import (
    MODEL_OPTION,
    SCHEDULER_OPTION,
    STDIN,
    STDIN_FILENAME_OPTION,
    WholeNumber,
    check_apart,
    check_not_an_input,
    check_output,
    check_stdin_name,
    client_or_fail,
    config_or_fail,
    fail,
    make_folder,
    stdin_document,
    write_chunks,
)
from furncheck.report import FORMAT_MODULES
from furncheck.result import DesignReport

if TYPE_CHECKING:
    from furncheck.config import Config

PROGRESS_MIN_FILES = 50
"""A progress bar is shown on a terminal's stderr from this many files to check on, when
the report does not go to that terminal too."""

SKIPPED_SHOWN = 5
"""Files skipped as no designs named on stderr at most (then how many more): a design
file emptied or cut short by mistake is skipped as no design, and its name on that line
can be noticed, where a count alone would pass in silence."""


@click.command()
@click.argument("paths", metavar="PATH...", nargs=-1, required=True)
@click.option("--format", "fmt", type=click.Choice(list(FORMAT_MODULES)), default=None,
              help="Report format.  [default: text]")
@click.option("-o", "--output", metavar="FILE", default=None,
              help="Write the report to FILE instead of standard output ('-': stdout); "
                   "the old FILE stays whole until the new report replaces it.")
@click.option("-j", "--jobs", type=WholeNumber(1), default=None,
              help="Processes checking designs, at most the CPUs this run may use (its "
                   "affinity, a container's CPU quota); a catalog that takes less than "
                   "about 0.2 s is checked in one.  [default: all usable CPUs]")
@click.option("--views", "views_dir", metavar="DIR", default=None,
              help="Also write a view of each design there, DIR/<name>-view.png.")
@click.option("--html", "html_file", metavar="FILE", default=None,
              help="Also write a report page of the whole run there: a sortable, "
                   "filterable table of the designs (verdict, worst utilization, "
                   "violations, a view of each) and their details; one self-contained "
                   "file that opens offline.")
@MODEL_OPTION
@SCHEDULER_OPTION
@click.option("--exclude", "excludes", metavar="GLOB", multiple=True,
              help="Leave out what this gitignore pattern matches in directory scans, "
                   "relative to the current folder (repeatable), e.g. --exclude drafts; "
                   "a path typed to elsewhere (../drafts, an absolute path) is anchored "
                   "there.")
@click.option("--skip-non-designs/--no-skip-non-designs", default=None,
              help="Leave out named files without a top-level 'furncheck' key too, as "
                   "directory scans do (for hooks that pass every changed file).  "
                   "[default: 'skip-non-designs' of [tool.furncheck], else no]")
@click.option("--force-exclude/--no-force-exclude", default=None,
              help="Leave out named files that a directory scan would leave out too (a "
                   "hidden name on the way, .gitignore, --exclude, 'exclude' of "
                   "[tool.furncheck]), as directory scans do (for hooks that pass every "
                   "changed file; '-' by its --stdin-filename).  [default: "
                   "'force-exclude' of [tool.furncheck], else no]")
@click.option("--cache/--no-cache", "use_cache", default=None,
              help="Reuse the results of unchanged designs.  [default: --cache]")
@click.option("--cache-dir", metavar="DIR", default=None,
              help="Where results are cached.  [default: $FURNCHECK_CACHE_DIR, else "
                   "'cache-dir' of [tool.furncheck], else the user cache directory, e.g. "
                   "~/.cache/furncheck]")
@STDIN_FILENAME_OPTION
def validate(paths: tuple[str, ...], fmt: str | None, output: str | None, jobs: int | None,
             views_dir: str | None, html_file: str | None, model: str | None,
             scheduler: str | None, excludes: tuple[str, ...],
             skip_non_designs: bool | None, force_exclude: bool | None,
             use_cache: bool | None, cache_dir: str | None,
             stdin_filename: str | None) -> None:
    """Check the designs in PATH... (files, '-' for standard input, or directories
    searched recursively for .yaml, .yml and .json files with a top-level 'furncheck'
    key; hidden files and folders, what .gitignore files ignore and --exclude patterns
    are left out; a file named here is always checked).  Options also come from
    [tool.furncheck] in the nearest pyproject.toml; the command line wins.

    Exit code 0: every design valid; 1: some design invalid; 2: some input could not be
    read or is ill-formed (its entry in the report says why), a usage error, or a Dask
    cluster (--scheduler) that cannot be used.
    """
    from furncheck.batch import entries
    from furncheck.report import reporter
    from furncheck.report.entries import Summary
    from furncheck.scan import ScanOptions, collect

    config = config_or_fail(paths, stdin_filename)
    check_stdin_name(stdin_filename, paths)
    fmt = fmt or config.format or "text"
    model = model or config.model
    jobs = jobs or config.jobs      # None: all usable CPUs (``workers.local_jobs``)
    check_output(output)
    if html_file is not None:
        check_output(html_file, "the report page")
        check_apart(html_file, output, "the report page", "the report (-o)")
    if views_dir is not None:
        _check_views_dir(views_dir)
    caching = use_cache if use_cache is not None else config.cache is not False
    scanning = any(path != STDIN and os.path.isdir(path) for path in paths)
    # the cache's folder: where results go, and a folder no scan enters (with --no-cache
    # too: it holds no designs); not looked up (nor furncheck.cache imported, some 8 ms of
    # a cold start) for a run that neither caches nor scans
    cache_folder = _cache_folder(cache_dir, config) if caching or scanning else None
    scan_options = ScanOptions(
        excludes=_exclude_patterns(excludes, config),
        skip_non_designs=bool(config.skip_non_designs if skip_non_designs is None
                              else skip_non_designs),
        force_exclude=bool(config.force_exclude if force_exclude is None else force_exclude),
        unscanned=() if cache_folder is None else (os.path.abspath(cache_folder),),
        stdin_name=stdin_filename)
    collected = collect(paths, scan_options)
    check_not_an_input(output, collected.sources)
    if html_file is not None:
        check_not_an_input(html_file, collected.sources, "the report page")
    if collected.skipped:
        click.echo(f"furncheck: skipped {collected.skipped} "
                   f"file{'s' if collected.skipped != 1 else ''} without a top-level "
                   f"'furncheck' key (not designs)"
                   f"{collected.skipped_names(SKIPPED_SHOWN)}", err=True)
    if collected.force_excluded:
        count = collected.force_excluded
        click.echo(f"furncheck: left out {count} named file{'s' if count != 1 else ''} "
                   f"that a scan would leave out (--force-exclude)", err=True)
    cache = open_cache(cache_folder, model) if caching else None
    sources = [_check_stdin(stdin_filename, model, cache) if source == STDIN else source
               for source in collected.sources]
    summary = Summary()
    progress = _progress_bar if output not in (None, "-") or not _is_terminal(sys.stdout) \
        else None
    client = client_or_fail(scheduler)
    parts = reporter(fmt).document(
        summary.add(entry)
        for entry in entries(sources, fmt, jobs, model, cache, progress, client))
    try:
        write_chunks(parts, output)
    except click.exceptions.Exit:
        raise
    except Exception as error:  # a reporter bug must not become a traceback
        fail(f"internal error while writing the {fmt} report: {type(error).__name__}: {error}")
    finally:
        if client is not None:
            client.close()
    if output not in (None, "-"):       # the report went to a file: the log gets the count
        from furncheck.report.text import summary_line

        click.echo(f"furncheck: {summary_line(summary.as_dict())}; report written to "
                   f"{output}", err=True)
    if cache is not None and cache.unwritable and cache.lost:   # (a warm run lost none)
        click.echo(f"furncheck: results not cached: {cache.unwritable}", err=True)
    if views_dir is not None and _views_missing():  # the report and exit code are validate's
        views_dir = None
    if views_dir is not None or html_file is not None:
        _pictures(sources, model, views_dir, html_file, cache)
    click.get_current_context().exit(summary.return_code)


def _pictures(sources: list, model: str | None, views_dir: str | None,
              html_file: str | None, cache=None) -> None:
    """``--views DIR`` and ``--html FILE``: each design's report again (the report
    written above keeps only its text: with the result cache, the results the run just
    stored are read back, else the designs are checked once more here) and the pictures
    and page drawn from them."""
    from furncheck.batch import check_one
    from furncheck.export.catalog import write_catalog_page, write_catalog_views

    def report_of(path: str) -> DesignReport:
        key = cache.key_of(path) if cache is not None else None
        stored = cache.get(key, path) if key is not None else None
        return stored if stored is not None else check_one(path, model)

    reports = [source if isinstance(source, DesignReport) else report_of(source)
               for source in sources]
    if views_dir is not None:
        try:
            write_catalog_views(reports, views_dir, model)
        except OSError as error:
            fail(f"cannot write views to {views_dir}: {error.strerror or error}")
    if html_file is not None:
        try:
            make_folder(html_file)
            write_catalog_page(reports, html_file)
        except OSError as error:
            fail(f"cannot write the report page {html_file}: {error.strerror or error}")


def _check_views_dir(views_dir: str) -> None:
    """Fail before any work when ``--views DIR`` cannot be written."""
    from furncheck.export.folders import prepare_out_dir

    problem = prepare_out_dir(views_dir)
    if problem:
        fail(f"cannot write views to {views_dir}: {problem}")


def _views_missing() -> bool:
    """Whether views cannot be drawn here (``export.folders.pictures_missing``:
    matplotlib cannot be imported, not installed or broken), said on stderr: the designs
    are checked and reported all the same."""
    from furncheck.export.folders import pictures_missing

    missing = pictures_missing()
    if missing is not None:
        click.echo(f"furncheck: views not written: {missing}", err=True)
    return missing is not None


def _exclude_patterns(excludes: tuple[str, ...], config: Config) -> tuple:
    """The exclude patterns of --exclude (anchored at the current folder) and of the
    config's ``exclude`` (at its folder), a path typed to elsewhere anchored there
    (``ignores.exclude_patterns``); one that is no valid pattern is one line and exit 2
    (``ignores.PatternError``)."""
    if not excludes and not config.exclude:
        return ()
    from furncheck.ignores import PatternError, exclude_patterns

    try:
        return (*exclude_patterns(excludes, os.curdir, "--exclude", typed=True),
                *exclude_patterns(config.exclude, config.folder,
                                  f"{config.path}: [tool.furncheck] exclude"))
    except PatternError as error:
        fail(str(error))


def _cache_folder(option: str | None, config: Config) -> str:
    """The result cache's folder: --cache-dir, else $FURNCHECK_CACHE_DIR, else
    ``cache-dir`` of [tool.furncheck], else the user cache directory (a CI job's variable
    wins over the repository's file, as the command line does); '~' expanded in each."""
    from furncheck.cache import ENV_DIRECTORY, default_directory, expand_user

    chosen = option or os.environ.get(ENV_DIRECTORY) or config.cache_dir
    return expand_user(chosen) if chosen else default_directory()


def open_cache(directory: str, model: str | None):
    """The result cache in ``directory`` (``_cache_folder``) for runs in ``model``, its
    writability found out (``ResultCache.probe``)."""
    from furncheck.cache import ResultCache

    cache = ResultCache(directory, {"model": model})
    cache.probe()
    return cache


def _progress_bar(total: int):
    """A click progress bar on stderr for ``total`` files to check when stderr is a
    terminal and they are at least PROGRESS_MIN_FILES, else None; never in a CI job
    (``CI`` set, as GitHub Actions, GitLab CI and most runners set it: one given a
    terminal, ``docker run -t``, would log every frame) or on a dumb terminal."""
    if total < PROGRESS_MIN_FILES or not _is_terminal(sys.stderr):
        return None
    if os.environ.get("CI", "").lower() not in ("", "0", "false", "no") \
            or os.environ.get("TERM") == "dumb":
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
    from furncheck.errors import DesignError
    from furncheck.scan import error_report

    try:
        data, source, fmt = stdin_document(name)
    except DesignError as error:            # closed: the other files are still checked
        return error_report(error.file, str(error))
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
