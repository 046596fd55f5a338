"""Which paths a directory scan leaves out: ``.gitignore`` files and ``--exclude`` patterns.

Both are gitignore patterns (matched by ``pathspec``, git's own wildmatch rules): a pattern
without a slash matches a name at any depth (``node_modules``, ``*.draft.yaml``), one with
a slash is anchored at its base folder (``/build``, ``drafts/old``), a trailing slash
matches folders only, ``**`` any number of folders, ``!`` re-includes.

- A ``.gitignore`` file's patterns are relative to its folder.  The deepest file that has
  a matching pattern decides, and within a file the last matching pattern, as in git.
  ``.git/info/exclude`` counts as a ``.gitignore`` at the repository's top.
- Exclude patterns (``--exclude``, ``exclude`` in ``[tool.furncheck]``) are relative to
  their own base folder (the current folder, the pyproject.toml's folder); a path that
  one of them matches is left out whatever the ``.gitignore`` files say.

A folder that is left out is not entered, so nothing below it can be re-included (git
behaves the same).  A folder named on the command line is searched even if a pattern
leaves it out; the other patterns apply inside it.  Paths are compared as absolute paths,
not resolved through symlinks (git does not follow symlinks either).
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass

from furncheck.config import GIT_DIR

GITIGNORE = ".gitignore"


@dataclass(frozen=True)
class Rule:
    """One gitignore pattern: ``pattern`` (pathspec's, compiled from the line, a
    folder-only line without its trailing slash), ``ignores`` (False for a ``!`` line),
    ``folders_only`` (the line ended in '/')."""

    pattern: object
    ignores: bool
    folders_only: bool

    def matches(self, relative: str, is_dir: bool) -> bool:
        """Whether the pattern names the path ``relative`` ('/'-separated, below the base
        folder) itself, as git matches it while it walks the tree: not through a folder
        above it (pathspec's patterns also match everything inside a folder they name,
        which git reaches only by leaving that folder out, and which must not re-include
        what a ``!folder/`` line's folder holds)."""
        if self.folders_only and not is_dir:
            return False
        found = self.pattern.regex.search(relative)
        return found is not None and found.groupdict().get(_FOLDER_GROUP) is None


_FOLDER_GROUP = "ps_d"
"""The group of a pathspec pattern's regex that matches a folder above the path."""


@dataclass(frozen=True)
class PatternFile:
    """Gitignore patterns that apply below ``base`` (an absolute folder).

    source : where the patterns come from, for messages (a file, or '--exclude')
    """

    base: str
    rules: tuple[Rule, ...]
    source: str

    def verdict(self, path: str, is_dir: bool) -> bool | None:
        """True: ``path`` (absolute) is ignored, False: re-included by a ``!`` pattern,
        None: no pattern matches it (or it is not below ``base``); the last pattern that
        matches decides."""
        relative = os.path.relpath(path, self.base)
        if relative == os.curdir or relative.split(os.sep)[0] == os.pardir:
            return None
        relative = relative.replace(os.sep, "/")
        return next((rule.ignores for rule in reversed(self.rules)
                     if rule.matches(relative, is_dir)), None)

    def opened_at(self, folder: str) -> PatternFile:
        """These patterns for a scan of ``folder`` (absolute), named on the command line:
        without the patterns that leave out ``folder`` itself or a folder between ``base``
        and it (they would leave out everything in it: a named folder is searched, as a
        named file is checked)."""
        relative = os.path.relpath(folder, self.base)
        if relative == os.curdir or relative.split(os.sep)[0] == os.pardir:
            return self
        parts = relative.split(os.sep)
        prefixes = ["/".join(parts[:count]) for count in range(1, len(parts) + 1)]
        kept = tuple(rule for rule in self.rules
                     if not (rule.ignores and any(rule.matches(prefix, True)
                                                  for prefix in prefixes)))
        return self if len(kept) == len(self.rules) else PatternFile(self.base, kept,
                                                                     self.source)


def patterns(lines: list[str] | tuple[str, ...], base: str, source: str) -> PatternFile:
    """Gitignore ``lines`` anchored at folder ``base``; a line that is not a valid pattern
    (an unclosed or reversed bracket, a lone '!' or '\\') matches nothing, as in git."""
    import pathspec

    rules = []
    for line in lines:
        text = _TRAILING_SPACES.sub("", line)
        folders_only = text.endswith("/")
        try:
            spec = pathspec.GitIgnoreSpec.from_lines([text[:-1] if folders_only else text])
        except (ValueError, re.error):  # pathspec's GitIgnorePatternError is a ValueError
            continue
        rules.extend(Rule(pattern, bool(pattern.include), folders_only)
                     for pattern in spec.patterns if pattern.include is not None)
    return PatternFile(os.path.abspath(base), tuple(rules), source)


_TRAILING_SPACES = re.compile(r"(?<!\\) +$")
"""A line's trailing spaces, which git drops unless the first is escaped ('\\ ')."""


def read_pattern_file(path: str, base: str) -> PatternFile | None:
    """The patterns of the gitignore file at ``path`` (anchored at ``base``), or None when
    there is no readable file there (a byte-order mark at its start is dropped, as git
    drops it)."""
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as stream:
            lines = stream.read().splitlines()
    except OSError:
        return None
    return patterns(lines, base, path)


@dataclass(frozen=True)
class IgnoreRules:
    """The gitignore files in force in one folder (outermost first) and the excludes."""

    gitignores: tuple[PatternFile, ...] = ()
    excludes: tuple[PatternFile, ...] = ()

    def ignored(self, path: str, is_dir: bool) -> bool:
        """Whether the absolute ``path`` is left out."""
        if any(rule.verdict(path, is_dir) for rule in self.excludes):
            return True
        for rule in reversed(self.gitignores):
            verdict = rule.verdict(path, is_dir)
            if verdict is not None:
                return verdict
        return False

    def entering(self, folder: str) -> IgnoreRules:
        """The rules inside ``folder`` (absolute): these plus its own ``.gitignore``."""
        own = read_pattern_file(os.path.join(folder, GITIGNORE), folder)
        if own is None:
            return self
        return IgnoreRules(self.gitignores + (own,), self.excludes)


def repository_root(folder: str) -> str | None:
    """The nearest folder at or above ``folder`` (absolute) holding ``.git`` (a folder, or
    the file of a worktree or submodule), or None outside a repository."""
    current = folder
    while True:
        if os.path.exists(os.path.join(current, GIT_DIR)):
            return current
        parent = os.path.dirname(current)
        if parent == current:
            return None
        current = parent


def rules_above(folder: str, excludes: tuple[PatternFile, ...] = ()) -> IgnoreRules:
    """The rules in force when a scan starts at ``folder`` (absolute): the gitignore files
    of the folders above it up to the top of its repository (and ``.git/info/exclude``),
    not yet ``folder``'s own (none outside a repository), and ``excludes``; all without
    the patterns that would leave out ``folder`` itself (``PatternFile.opened_at``)."""
    root = repository_root(folder)
    gitignores: list[PatternFile] = []
    if root is not None:
        info = read_pattern_file(os.path.join(root, GIT_DIR, "info", "exclude"), root)
        if info is not None:
            gitignores.append(info)
        relative = os.path.relpath(folder, root)
        parts = [] if relative == os.curdir else relative.split(os.sep)
        current = root
        for part in parts:
            own = read_pattern_file(os.path.join(current, GITIGNORE), current)
            if own is not None:
                gitignores.append(own)
            current = os.path.join(current, part)
    return IgnoreRules(tuple(rule.opened_at(folder) for rule in gitignores),
                       tuple(rule.opened_at(folder) for rule in excludes))
