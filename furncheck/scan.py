"""Which files ``furncheck validate PATH...`` checks (contract section 4).

Each PATH is a file, ``-`` (a design on standard input) or a directory.  A file named on
the command line is always checked (whatever its name, ignore rules or content), unless
``skip_non_designs`` asks to leave out named files that are no designs too (for hooks
that pass every changed YAML file).  A directory is searched recursively for
``.yaml``, ``.yml`` and ``.json`` files, leaving out

- hidden files and folders (names starting with '.'),
- what ``.gitignore`` files ignore (in the tree and above it inside its repository), but
  for the files git tracks all the same (a design committed before a ``*.json`` line),
  and what an exclude pattern matches (``furncheck.ignores``),
- YAML/JSON files whose top level has no ``furncheck`` key: they are not designs
  (``furncheck.detect``; counted in ``Collected.skipped``).

Symlinked folders are followed, each folder once: a folder reached a second time (a loop,
or two links to one folder) is not searched again, and folders reached without a symlink
are searched before those reached through one (so a file is listed by its real path when
the tree has one), and a symlinked file whose target the scan finds too is listed by the
target's path.  Files are listed in path order; a file
reached twice (named twice, or named and found) is checked once, at its first place.
"""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass, field
from pathlib import Path, PurePath
from typing import TYPE_CHECKING

from furncheck import tolerances as tol
from furncheck.config import GIT_DIR
from furncheck.files import CACHEDIR_TAG, is_cache_tag
from furncheck.result import DesignReport

if TYPE_CHECKING:       # the ignore rules are read where a folder is scanned
    from furncheck.ignores import IgnoreRules, PatternFile

DESIGN_SUFFIXES = {".yaml": "yaml", ".yml": "yaml", ".json": "json"}
"""Extensions of the files a directory scan looks at (case-insensitive) -> format."""

STDIN = "-"
"""The PATH that stands for a design on standard input."""


@dataclass(frozen=True)
class ScanOptions:
    """How PATHs become files.  ``excludes``: exclude patterns, each anchored at its own
    folder; ``skip_non_designs``: also leave out named files without a top-level
    ``furncheck`` key; ``force_exclude``: also leave out named files that a scan would
    leave out (a hidden name, a .gitignore or an exclude pattern: a pre-commit hook,
    handed the changed files one by one, then skips what a CI run of the folder would);
    ``unscanned``: folders (absolute) a scan never enters besides (the result cache's,
    when it lies inside a scanned tree: its entries are no designs, and counting them
    made a warm run's stderr differ from a cold one's); ``stdin_name``: the path a design
    on standard input stands for (``--stdin-filename``: ``force_exclude`` leaves it out
    as it would leave out that file, without reading standard input)."""

    excludes: tuple[PatternFile, ...] = ()
    skip_non_designs: bool = False
    force_exclude: bool = False
    unscanned: tuple[str, ...] = ()
    stdin_name: str | None = None


@dataclass
class Collected:
    """The sources to check in order: a path, ``STDIN``, or a finished error report (a
    folder that cannot be read or holds no design); ``skipped``: how many YAML/JSON files
    were left out because they are no designs (each once, however many scans met it)."""

    sources: list[str | DesignReport] = field(default_factory=list)
    skipped_files: dict[str, str] = field(default_factory=dict)  # identity -> path first met
    force_excluded: int = 0         # named files left out (``force_exclude``)

    @property
    def skipped(self) -> int:
        return len(self.skipped_files)

    def skipped_names(self, shown: int) -> str:
        """The first ``shown`` files skipped as no designs and how many more: ': empty.yaml
        (empty), a.yaml, ci.yml and 3 more' ('' if none).  Those that are empty (blank,
        or comments alone: a design emptied by mistake, skipped as no design) come first,
        then the others, each sorted by the path it was first met by; a name that is not
        plain printable text, or holds ', ', is written quoted with its escapes (one line,
        whatever the file is called)."""
        found = sorted((not _blank(path), path) for path in self.skipped_files.values())
        if not found:
            return ""
        listed = ", ".join(_shown_name(path) + (" (empty)" if not filled else "")
                           for filled, path in found[:shown])
        more = len(found) - shown
        return f": {listed}" + (f" and {more} more" if more > 0 else "")


BLANK_BYTES = 4096
"""A skipped file is read to tell whether it is empty only up to this size."""


def _blank(path: str) -> bool:
    """Whether a file holds nothing but blank lines and ``#`` comments (an empty YAML
    document); False for one that cannot be read or is over BLANK_BYTES."""
    try:
        if os.path.getsize(path) > BLANK_BYTES:
            return False
        with open(path, "rb") as stream:
            data = stream.read(BLANK_BYTES + 1)
    except OSError:
        return False
    return all(not line.strip() or line.strip().startswith(b"#") for line in data.splitlines())


def _shown_name(path: str) -> str:
    """A path for a line of stderr: as it is, or quoted with its escapes (``repr``) where
    it is not printable text or holds ', ' (a list's separator)."""
    return path if path.isprintable() and ", " not in path else repr(path)


def collect(paths: tuple[str, ...] | list[str], options: ScanOptions = ScanOptions()
            ) -> Collected:
    """The sources of ``paths`` (see the module docstring).  What git tracks is asked
    afresh for each call (``tracked.forget``)."""
    from furncheck.tracked import forget

    forget()
    collected = Collected()
    seen: set[str] = set()
    rules: dict[str, IgnoreRules] = {}  # per folder: its gitignores read once for all
    for given in paths:
        if given == STDIN:
            files = [STDIN]
            if options.force_exclude and options.stdin_name \
                    and _excluded(options.stdin_name, options, rules):
                collected.force_excluded += 1
                files = []
        elif not given:                 # '' (an unset variable in a CI script)
            collected.sources.append(error_report("", "an empty path names no file"))
            continue
        elif os.path.isdir(given):
            files = _scan_folder(given, options, collected)
        elif options.force_exclude and _excluded(given, options, rules):
            collected.force_excluded += 1
            files = []
        elif options.skip_non_designs and not _is_design(given):
            collected.skipped_files.setdefault(_identity(given), given)
            files = []
        else:
            files = [given]
        for file in files:
            key = file if file == STDIN else _identity(file)
            if key not in seen:
                seen.add(key)
                collected.sources.append(file)
    return collected


def _identity(path: str) -> str:
    """What tells two paths of one file apart from two files: its real path."""
    return os.path.normcase(os.path.realpath(path))


def _excluded(path: str, options: ScanOptions, rules: dict[str, IgnoreRules]) -> bool:
    """Whether a scan would have left out the named file ``path`` (``force_exclude``:
    ``ignores.left_out_by_a_scan``; ``rules``: its rules of the folders met so far)."""
    from furncheck.ignores import left_out_by_a_scan

    return left_out_by_a_scan(path, options.excludes, rules)


def _scan_folder(folder: str, options: ScanOptions, collected: Collected) -> list[str]:
    """The design files under ``folder``, sorted; its unreadable folders and 'no design
    files' become error reports in ``collected``."""
    found = find_design_files(folder, options.excludes, options.unscanned)
    collected.sources.extend(
        error_report(path, f"{path}: cannot read this directory: {why}")
        for path, why in found.unreadable)
    for path in found.skipped:
        collected.skipped_files.setdefault(_identity(path), path)
    if not found.files and not found.unreadable:
        left_out = "" if not found.ignored else \
            f" ({found.ignored} left out by .gitignore or exclude patterns)"
        collected.sources.append(error_report(
            folder, f"{folder}: no design files (.yaml, .yml or .json with a top-level "
                    f"'furncheck' key) in this directory{left_out}"))
    return found.files


@dataclass
class FolderScan:
    """What ``find_design_files`` found: design files (sorted by path), [(unreadable
    folder, reason)], and the YAML/JSON files that were no designs."""

    files: list[str] = field(default_factory=list)
    unreadable: list[tuple[str, str]] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)
    ignored: int = 0        # YAML/JSON files and folders an ignore or exclude pattern left out


def find_design_files(folder: str, excludes: tuple[PatternFile, ...] = (),
                      unscanned: tuple[str, ...] = ()) -> FolderScan:
    """The design files below ``folder`` (paths are ``folder`` joined with the relative
    path, normalized), by the rules of the module docstring; the folders ``unscanned``
    (absolute) are not entered."""
    from furncheck.ignores import Kept, rules_above

    scan = FolderScan()
    visited: set[tuple[int, int]] = set()
    try:
        own = os.stat(folder)
        own = (own.st_dev, own.st_ino)
    except OSError:
        own = None
    for path in unscanned:          # as if met before: never entered (unless scanned itself)
        try:
            identity = os.stat(path)
        except OSError:
            continue
        if (identity.st_dev, identity.st_ino) != own:
            visited.add((identity.st_dev, identity.st_ino))
    candidates: list[str] = []
    linked_files: set[str] = set()      # candidates that are symlinks
    top = os.path.normpath(folder)
    direct = [(top, rules_above(os.path.abspath(top), excludes))]
    linked: list[tuple[str, IgnoreRules]] = []    # folders reached through a symlink
    while direct or linked:
        via_link = not direct
        current, rules = (linked if via_link else direct).pop()
        try:
            identity = os.stat(current)
            if (identity.st_dev, identity.st_ino) in visited:
                continue             # a symlink loop, or a folder linked twice
            visited.add((identity.st_dev, identity.st_ino))
            with os.scandir(current) as entries:
                listing = sorted(entries, key=lambda entry: entry.name)
        except OSError as error:
            scan.unreadable.append((current, error.strerror or str(error)))
            continue
        if current != top and any(entry.name == CACHEDIR_TAG for entry in listing) \
                and is_cache_tag(os.path.join(current, CACHEDIR_TAG)):
            continue                    # a cache's folder (a result cache not in use)
        rules = rules.entering(os.path.abspath(current),       # (a .git link to nothing
                               any(entry.name == GIT_DIR and _exists(entry)  # is none)
                                   for entry in listing))
        subfolders: list[tuple[str, IgnoreRules]] = []
        links: list[tuple[str, IgnoreRules]] = []
        for entry in listing:
            if entry.name.startswith("."):
                continue
            path = os.path.normpath(os.path.join(current, entry.name))
            is_dir = _is_folder(entry)
            state = rules.state(os.path.abspath(path), is_dir)
            if state is Kept.NO:
                if is_dir or os.path.splitext(entry.name)[1].lower() in DESIGN_SUFFIXES:
                    scan.ignored += 1
                continue
            if is_dir:
                inside = rules.under_ignored() if state is Kept.TRACKED else rules
                (links if via_link or entry.is_symlink() else subfolders).append((path, inside))
            elif os.path.splitext(entry.name)[1].lower() in DESIGN_SUFFIXES:
                candidates.append(path)
                if entry.is_symlink():
                    linked_files.add(path)
        direct.extend(reversed(subfolders))   # depth first, in name order
        linked.extend(reversed(links))
    for path in candidates:
        if _is_design(path):
            scan.files.append(path)
        else:
            scan.skipped.append(path)
    scan.files.sort(key=lambda path: PurePath(path).parts)
    if linked_files:                # a file linked to one the scan found itself: by that
        real = {_identity(path) for path in scan.files if path not in linked_files}
        scan.files = [path for path in scan.files       # one's own path (the link named
                      if path not in linked_files or _identity(path) not in real]  # it)
    scan.unreadable.sort()
    return scan


def _is_folder(entry: os.DirEntry) -> bool:
    """A folder, or a symlink to one (followed); False for a broken link."""
    try:
        return entry.is_dir(follow_symlinks=True)
    except OSError:
        return False


def _exists(entry: os.DirEntry) -> bool:
    """Whether a folder entry is a file or a folder, following a symlink (a broken link
    is neither, as ``os.path.exists`` says)."""
    try:
        return entry.is_dir() or entry.is_file()
    except OSError:
        return False


def _is_design(path: str) -> bool:
    """Whether the file at ``path`` is a design: a YAML/JSON file with a top-level
    ``furncheck`` key.  A file that cannot be read counts as one: its report says why it
    cannot be read.  Other extensions are no designs."""
    fmt = DESIGN_SUFFIXES.get(Path(path).suffix.lower())
    if fmt is None:
        return False
    try:
        info = os.stat(path)
        if not stat.S_ISREG(info.st_mode):
            return True
        with open(path, "rb") as stream:
            if info.st_size > tol.MAX_FILE_BYTES:   # too large to check: its report
                from furncheck.detect import declares_design_at_large  # says so

                return declares_design_at_large(stream, fmt)
            data = stream.read(tol.MAX_FILE_BYTES + 1)
    except OSError:
        return True
    from furncheck.detect import declares_design  # json and its patterns: scans only
    return declares_design(data, fmt)


def error_report(path: str, message: str) -> DesignReport:
    """The report of a source that could not be checked."""
    return DesignReport(design=path, name=Path(path).stem or path, valid=None, error=message)
