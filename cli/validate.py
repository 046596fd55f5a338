"""``furncheck validate PATH...``: check designs, write one report, exit 0 / 1 / 2.

The command is thin: collect the design files, check each and make its part of the
report with the chosen reporter (``furncheck.batch``: in worker processes for a large
catalog), write the parts as they come, in input order, and exit with the summary's
return code.  Every input gets a report entry, also a missing path or a file of another
type (``check_file`` says what is wrong), so one bad file never hides the verdicts on the
others.
"""

from __future__ import annotations

import os
from pathlib import Path, PurePath

import click

from furncheck.batch import entries
from furncheck.cli.output import MODEL_OPTION, check_output, fail, write_chunks
from furncheck.report import FORMAT_MODULES, reporter
from furncheck.report.entries import Summary
from furncheck.result import DesignReport

DESIGN_SUFFIXES = (".yaml", ".yml", ".json")
"""Extensions of design files found when a PATH is a directory (case-insensitive)."""


@click.command()
@click.argument("paths", metavar="PATH...", nargs=-1, required=True)
@click.option("--format", "fmt", type=click.Choice(list(FORMAT_MODULES)), default="text",
              show_default=True, help="Report format.")
@click.option("-o", "--output", metavar="FILE", default=None,
              help="Write the report to FILE instead of standard output ('-': stdout).")
@click.option("-j", "--jobs", type=click.IntRange(min=1), default=None,
              help="Processes checking designs; a catalog that takes less than about "
                   "0.2 s is checked in one.  [default: all cores]")
@MODEL_OPTION
def validate(paths: tuple[str, ...], fmt: str, output: str | None, jobs: int | None,
             model: str | None) -> None:
    """Check the designs in PATH... (files, or directories searched recursively for
    .yaml, .yml and .json files; hidden files and folders are skipped).

    Exit code 0: every design valid; 1: some design invalid; 2: some input could not be
    read or is ill-formed (its entry in the report says why), or a usage error.
    """
    check_output(output)
    sources = collect_sources(paths)
    summary = Summary()
    parts = reporter(fmt).document(
        summary.add(entry) for entry in entries(
            sources, fmt, jobs if jobs is not None else (os.cpu_count() or 1), model))
    try:
        write_chunks(parts, output)
    except click.exceptions.Exit:
        raise
    except Exception as error:  # a reporter bug must not become a traceback
        fail(f"internal error while writing the {fmt} report: {type(error).__name__}: {error}")
    click.get_current_context().exit(summary.return_code)


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


# --- small helpers --------------------------------------------------------------------------

def _error_report(path: str, message: str) -> DesignReport:
    return DesignReport(design=path, name=Path(path).stem or path, valid=None, error=message)
