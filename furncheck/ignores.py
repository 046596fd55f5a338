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
behaves the same).  A pattern names a path itself, as git matches paths while it walks
the tree: ``!build/`` re-includes the folder, not the files in it that another pattern
ignores.  A folder named on the command line is searched even if the patterns leave it
out (one that names it or everything in it, ``build/``, ``build/**``, ``*``, unless a
later ``!`` line re-includes it); inside it every pattern applies, such a one with the
named folder read as a name it does not match (``OpenedRule``: ``build/**`` then leaves
out nothing there, ``*`` and ``out*`` still what they name on their own).  A nested
repository or a submodule has its own rules, as in git (``IgnoreRules.entering``).  A
line that is not
a valid pattern (a lone ``!`` or ``\\``, a reversed range ``[z-a]``, which git reads as
its first character) matches nothing.  Paths are compared as absolute paths,
not resolved through symlinks (git does not follow symlinks either).
"""

from __future__ import annotations

import enum
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

    def covers(self, folder: str) -> bool:
        """Whether the pattern names the folder ``folder`` (relative, as in ``matches``)
        or everything in it (``build/**``, ``*``)."""
        return self.matches(folder, True) or (
            not self.folders_only and self.pattern.regex.search(folder + "/") is not None)


_FOLDER_GROUP = "ps_d"
"""The group of a pathspec pattern's regex that matches a folder above the path."""

_NAMED = "\x00"
"""What a folder named on the command line reads as in the paths below it, for a pattern
that leaves that folder out (``OpenedRule``): a name no pattern means."""


@dataclass(frozen=True)
class OpenedRule(Rule):
    """A pattern that leaves out a folder named on the command line (or a folder above
    it), for the scan of that folder: the named ``folders`` (relative, deepest first)
    are searched, but inside them the pattern still names what it names on its own
    (``out*`` leaves out ``out/output-tmp`` of a named ``out``; ``build/**`` nothing of a
    named ``build``: it named the folder's contents through the folder's own name)."""

    folders: tuple[str, ...] = ()

    def _inside(self, relative: str) -> str | None:
        """``relative`` with the last name of the named folder it lies in read as _NAMED
        (the folders above it keep theirs: ``logs/**/tmp`` still names ``tmp`` folders
        deeper in a named ``logs/tmp``); None for a named folder itself."""
        for folder in self.folders:
            if relative == folder:
                return None
            if relative.startswith(folder + "/"):
                parent = folder.rpartition("/")[0]
                return (f"{parent}/" if parent else "") + _NAMED + relative[len(folder):]
        return relative

    def matches(self, relative: str, is_dir: bool) -> bool:
        inside = self._inside(relative)
        return inside is not None and super().matches(inside, is_dir)

    def covers(self, folder: str) -> bool:
        inside = self._inside(folder)
        return inside is not None and super().covers(inside)


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
        relative = self._relative(path)
        if relative is None:
            return None
        return next((rule.ignores for rule in reversed(self.rules)
                     if rule.matches(relative, is_dir)), None)

    def leaves_out(self, folder: str) -> bool | None:
        """Whether these patterns leave out the folder ``folder`` (absolute) as a whole,
        for a scan named there: the last pattern that names it or everything in it
        (``Rule.covers``) decides; None when none does (or it is not below ``base``)."""
        relative = self._relative(folder)
        if relative is None:
            return None
        return next((rule.ignores for rule in reversed(self.rules) if rule.covers(relative)),
                    None)

    def opened_at(self, folders: list[str]) -> PatternFile:
        """These patterns for a scan of a folder named on the command line, ``folders``
        (absolute) being it and the folders above it that are left out (``leaves_out``
        of the rules together): an ignoring pattern that names one of them or everything
        in it no longer leaves them out (a named folder is searched, as a named file is
        checked), but still leaves out what it names below them on its own
        (``OpenedRule``); the others as they are."""
        relatives = sorted((r for r in map(self._relative, folders) if r is not None),
                           key=len, reverse=True)
        opened = tuple(OpenedRule(rule.pattern, rule.ignores, rule.folders_only,
                                  tuple(relatives))
                       if rule.ignores and any(rule.covers(r) for r in relatives) else rule
                       for rule in self.rules)
        return self if opened == self.rules else PatternFile(self.base, opened, self.source)

    def _relative(self, path: str) -> str | None:
        """``path`` (absolute) relative to ``base``, '/'-separated; None for ``base``
        itself or a path outside it."""
        relative = os.path.relpath(path, self.base)
        if relative == os.curdir or relative.split(os.sep)[0] == os.pardir:
            return None
        return relative.replace(os.sep, "/")


class PatternError(ValueError):
    """An exclude pattern (``--exclude``, ``exclude`` of [tool.furncheck]) that is not a
    valid gitignore pattern: said in one line, where a ``.gitignore`` line like it would
    match nothing, as in git."""


def patterns(lines: list[str] | tuple[str, ...], base: str, source: str,
             excludes: bool = False) -> PatternFile:
    """Gitignore ``lines`` anchored at folder ``base``; a line that is not a valid pattern
    (a lone '!' or '\\', a reversed range) matches nothing (module docstring).

    ``excludes``: the lines are exclude patterns typed by a user (``--exclude``, the
    config's ``exclude``), not a ``.gitignore`` file's: a path typed from the base folder
    with a leading './' is that path anchored there ('./x.yaml' is '/x.yaml', x.yaml in
    the base folder alone; './designs/drafts' is '/designs/drafts': git would read
    either literally and match nothing), and a line that is not a valid pattern (a lone
    '!' or '/', a reversed range, an unclosed '[') raises ``PatternError`` instead of
    matching nothing unseen; a blank line or a '#' comment is passed over, as in a
    ``.gitignore``."""
    import pathspec

    rules = []
    for line in lines:
        text = _without_trailing_spaces(line)
        if excludes and (not text.strip() or text.startswith("#")):
            continue
        if excludes and text.startswith("./"):
            text = "/" + text[2:].lstrip("/")
        folders_only = text.endswith("/")
        try:
            spec = pathspec.GitIgnoreSpec.from_lines([text[:-1] if folders_only else text])
        except (ValueError, re.error):  # pathspec's GitIgnorePatternError is a ValueError
            if excludes:
                raise PatternError(f"{source}: {line!r} is not a valid gitignore pattern"
                                   ) from None
            continue
        if excludes and not any(pattern.include is not None for pattern in spec.patterns):
            raise PatternError(f"{source}: {line!r} is not a valid gitignore pattern (it "
                               "matches nothing)")
        rules.extend(Rule(pattern, bool(pattern.include), folders_only)
                     for pattern in spec.patterns if pattern.include is not None)
    return PatternFile(os.path.abspath(base), tuple(rules), source)


def exclude_patterns(lines: list[str] | tuple[str, ...], base: str, source: str,
                     typed: bool = False) -> tuple[PatternFile, ...]:
    """The exclude patterns ``lines`` anchored at folder ``base`` (``patterns`` with
    ``excludes``), each line that is typed as a path to somewhere else anchored there
    instead, so that none silently matches nothing: one beginning with ``../`` (after a
    ``./``: a pattern typed from a subfolder of the scanned tree) at that folder above
    ``base``, an absolute path of this system (``--exclude $PWD/drafts``, compared
    through symlinks; not one that names a path below ``base`` read as anchored there,
    as ``/build`` does) at its own folder.  ``typed``: the lines come from the command
    line, where a leading '#' is part of the name (``--exclude '#draft.yaml'``), not a
    comment as in a config's list.  A line that is no valid pattern raises
    ``PatternError`` naming it as written."""
    groups: dict[str, list[str]] = {}
    for line in lines:
        anchor, text = _anchored(line, os.path.abspath(base), typed)
        try:                            # (each line on its own, to name it as written)
            patterns([text], anchor, source, excludes=True)
        except PatternError:
            if text == line:
                raise
            raise PatternError(f"{source}: {line!r} is not a valid gitignore pattern (it "
                               f"names {anchor} itself, or nothing)") from None
        groups.setdefault(anchor, []).append(text)
    return tuple(patterns(group, anchor, source, excludes=True)
                 for anchor, group in groups.items())


def _anchored(line: str, base: str, typed: bool) -> tuple[str, str]:
    """(folder, pattern): where an exclude ``line`` is anchored and the pattern there
    (``exclude_patterns``)."""
    if typed and line.startswith("#"):
        return base, "\\" + line
    text = line
    while text.startswith("./"):
        text = text[2:].lstrip("/")
    if text.startswith("../") or text == "..":
        anchor = base
        while text.startswith("../") or text == "..":
            anchor, text = os.path.dirname(anchor), text[3:].lstrip("/")
        return anchor, "/" + text
    if os.path.isabs(line) and not os.path.lexists(base + line) \
            and os.path.lexists(line.rstrip("/") or "/"):
        absolute = os.path.realpath(line)
        real_base = os.path.realpath(base)
        folder_only = "/" if line.endswith("/") else ""
        if absolute.startswith(real_base.rstrip(os.sep) + os.sep):
            relative = os.path.relpath(absolute, real_base).replace(os.sep, "/")
            return base, "/" + relative + folder_only
        return os.path.dirname(absolute), "/" + os.path.basename(absolute) + folder_only
    return base, line


def _without_trailing_spaces(line: str) -> str:
    """``line`` without its trailing spaces, as git drops them: all of them, but for the
    first one where it is escaped by an odd number of backslashes before it ('a\\ ')."""
    stripped = line.rstrip(" ")
    if stripped != line and (len(stripped) - len(stripped.rstrip("\\"))) % 2 == 1:
        stripped += " "
    return stripped


def read_pattern_file(path: str, base: str) -> PatternFile | None:
    """The patterns of the gitignore file at ``path`` (anchored at ``base``), or None when
    there is no readable file there (a byte-order mark at its start is dropped, as git
    drops it)."""
    try:
        with open(path, encoding="utf-8-sig", errors="surrogateescape") as stream:
            lines = stream.read().splitlines()
    except OSError:
        return None
    return patterns(lines, base, path)


class Kept(enum.Enum):
    """``IgnoreRules.state`` of a path: a scan keeps it (YES), leaves it out (NO), or a
    ``.gitignore`` ignores it but git tracks it all the same (TRACKED: a tracked file, or
    a folder holding one, entered for those files alone)."""

    YES = "kept"
    NO = "left out"
    TRACKED = "tracked"


@dataclass(frozen=True)
class IgnoreRules:
    """The gitignore files in force in one folder (outermost first) and the excludes;
    ``root``: the top of the repository the folder lies in (None outside one);
    ``below_ignored``: the folder lies in one a ``.gitignore`` ignores, entered for the
    files git tracks in it (``TRACKED``), where the others stay ignored."""

    gitignores: tuple[PatternFile, ...] = ()
    excludes: tuple[PatternFile, ...] = ()
    root: str | None = None
    below_ignored: bool = False

    def state(self, path: str, is_dir: bool) -> Kept:
        """Whether a scan keeps the absolute ``path``: an exclude pattern leaves it out;
        else the deepest gitignore file with a pattern that matches it decides (the
        folder's ``below_ignored`` standing for one that ignores everything), but a file
        that git tracks, and a folder that holds one, are not ignored, as in git
        (``tracked.tracked_ignored``)."""
        if any(rule.verdict(path, is_dir) for rule in self.excludes):
            return Kept.NO
        verdict = self.below_ignored or next(
            (found for found in (rule.verdict(path, is_dir)
                                 for rule in reversed(self.gitignores))
             if found is not None), False)
        if not verdict:
            return Kept.YES
        return Kept.TRACKED if self._tracked(path, is_dir) else Kept.NO

    def _tracked(self, path: str, is_dir: bool) -> bool:
        if self.root is None:
            return False
        from furncheck.tracked import tracked_ignored  # asks git: only where it matters

        files, folders = tracked_ignored(self.root)
        return path in (folders if is_dir else files)

    def under_ignored(self) -> IgnoreRules:
        """These rules for a folder that a ``.gitignore`` ignores and git tracks files in
        (``Kept.TRACKED``): only those files are kept below it."""
        return IgnoreRules(self.gitignores, self.excludes, self.root, True)

    def leaves_out(self, folder: str) -> bool:
        """Whether the folder ``folder`` (absolute) is left out as a whole (an exclude,
        else the deepest gitignore file that decides, as ``ignored``; ``PatternFile.
        leaves_out``)."""
        if any(rule.leaves_out(folder) for rule in self.excludes):
            return True
        return next((verdict for verdict in (rule.leaves_out(folder)
                                             for rule in reversed(self.gitignores))
                     if verdict is not None), False)

    def entering(self, folder: str, top: bool | None = None) -> IgnoreRules:
        """The rules inside ``folder`` (absolute): these plus its own ``.gitignore``; at
        the top of a repository (a nested one, a submodule) the gitignore files above it
        are another repository's and stop applying, as in git (its ``.git/info/exclude``
        applies instead; the excludes stay).  ``top``: whether ``folder`` holds ``.git``,
        where the caller's listing of it says (else looked up)."""
        gitignores, root, below = self.gitignores, self.root, self.below_ignored
        if top is None:
            top = os.path.exists(os.path.join(folder, GIT_DIR))
        if top:
            info = read_pattern_file(_info_exclude(folder), folder)
            gitignores = () if info is None else (info,)
            root, below = folder, False
        own = read_pattern_file(os.path.join(folder, GITIGNORE), folder)
        if own is not None:
            gitignores += (own,)
        if gitignores is self.gitignores and root == self.root:
            return self
        return IgnoreRules(gitignores, self.excludes, root, below)


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


def _info_exclude(root: str) -> str:
    """The ``info/exclude`` file of the repository whose top is ``root``: in its ``.git``
    folder, or where a ``.git`` file points (``gitdir: ...``: a submodule's folder in its
    parent's ``.git/modules``, a worktree's, whose ``commondir`` names the folder holding
    it)."""
    git = os.path.join(root, GIT_DIR)
    if os.path.isfile(git):
        try:
            with open(git, encoding="utf-8", errors="surrogateescape") as stream:
                pointer = stream.readline().strip()
        except OSError:
            pointer = ""
        if pointer.startswith("gitdir:"):
            git = os.path.join(root, pointer[len("gitdir:"):].strip())
            try:
                with open(os.path.join(git, "commondir"), encoding="utf-8",
                          errors="surrogateescape") as stream:
                    git = os.path.join(git, stream.readline().strip())
            except OSError:
                pass
    return os.path.join(git, "info", "exclude")


def rules_above(folder: str, excludes: tuple[PatternFile, ...] = ()) -> IgnoreRules:
    """The rules in force when a scan starts at ``folder`` (absolute): the gitignore files
    of the folders above it up to the top of its repository (and ``.git/info/exclude``),
    not yet ``folder``'s own (none outside a repository), and ``excludes``; where they
    leave out ``folder`` or a folder above it, the patterns that do opened there
    (``PatternFile.opened_at``: they no longer leave those folders out, and apply below
    them as to any folder)."""
    root = repository_root(folder)
    gitignores = _gitignores_above(folder, root)
    rules = IgnoreRules(tuple(gitignores), excludes, root)
    ancestors = [folder]
    while os.path.dirname(ancestors[-1]) != ancestors[-1]:
        ancestors.append(os.path.dirname(ancestors[-1]))
    left_out = [path for path in ancestors if rules.leaves_out(path)]
    if not left_out:
        return rules
    return IgnoreRules(tuple(rule.opened_at(left_out) for rule in gitignores),
                       tuple(rule.opened_at(left_out) for rule in excludes), root)


def _gitignores_above(folder: str, root: str | None) -> list[PatternFile]:
    """The gitignore files of the folders above ``folder`` (absolute) up to ``root``, the
    top of its repository (``repository_root``), outermost first, and
    ``.git/info/exclude``; none outside a repository (``root`` None)."""
    gitignores: list[PatternFile] = []
    if root is None:
        return gitignores
    info = read_pattern_file(_info_exclude(root), root)
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
    return gitignores


def left_out_by_a_scan(path: str, excludes: tuple[PatternFile, ...] = (),
                       read: dict[str, IgnoreRules] | None = None) -> bool:
    """Whether a scan of the repository (or of the current folder, outside one) would
    leave out the file ``path``: a hidden name on its way there, an exclude pattern that
    matches it or a folder it lies in, or a ``.gitignore`` that ignores it or a folder
    it lies in, unless git tracks it (``IgnoreRules.state``) (``--force-exclude``: a
    hook handed the changed files checks what CI's scan checks).  ``read``: the rules
    inside each folder met so far (with the same ``excludes``), kept there for the next
    file: a hook hands over hundreds of files of one folder, whose gitignore files are
    then read once."""
    absolute = os.path.abspath(path)
    folder = os.path.dirname(absolute)
    root = repository_root(folder)
    top = root or os.path.abspath(os.curdir)
    relative = os.path.relpath(absolute, top)
    if not relative.startswith(os.pardir) and any(
            part.startswith(".") for part in relative.split(os.sep)):
        return True
    if read is None:
        read = {}
    if folder not in read:
        read[folder] = IgnoreRules(tuple(_gitignores_above(folder, root)), excludes,
                                   root).entering(folder)
    rules = read[folder]
    current, is_dir, tracked_in_ignored = absolute, False, False
    while True:
        state = rules.state(current, is_dir)
        if state is Kept.NO or (is_dir and _cache_folder(current)):
            return True
        if state is Kept.TRACKED and is_dir:    # an ignored folder git tracks files in:
            tracked_in_ignored = True           # only those are kept
        parent = os.path.dirname(current)
        if parent == current:
            break
        current, is_dir = parent, True
    return tracked_in_ignored and rules.under_ignored().state(absolute, False) \
        is not Kept.TRACKED


def _cache_folder(folder: str) -> bool:
    """Whether ``folder`` holds a CACHEDIR.TAG (``files.CACHEDIR_TAG``): a scan does not
    enter it."""
    from furncheck.files import CACHEDIR_TAG, is_cache_tag

    return is_cache_tag(os.path.join(folder, CACHEDIR_TAG))
