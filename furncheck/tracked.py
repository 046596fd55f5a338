"""Which files git tracks though a ``.gitignore`` matches them (a thin edge: it runs git).

A ``.gitignore`` never ignores a tracked file, in git: a design committed before a
``*.json`` line was added, or forced in with ``git add -f``, is still checked by a scan
(``ignores.IgnoreRules.state``).  ``tracked_ignored`` asks ``git ls-files --cached
--ignored --exclude-standard`` once per repository and scan, the first time a
``.gitignore`` ignores something there; where git cannot tell (it is not installed, the
repository is not one it reads, or is owned by another user: git's own check stands),
the answer is empty and the ignore rules alone decide.

git runs with the repository's configuration, but never with a command of it: its file
system monitor (``core.fsmonitor``, which ``ls-files`` would run) is off, and the
environment's ``GIT_*`` variables (a commit hook's ``GIT_INDEX_FILE`` names the outer
repository's index, wrong for a nested one) are dropped.
"""

from __future__ import annotations

import os

TRACKED_IGNORED_SECONDS = 60.0
"""How long ``git ls-files`` may take to list a repository's tracked, ignored files."""

_TRACKED: dict[str, tuple[frozenset, frozenset]] = {}


def tracked_ignored(root: str) -> tuple[frozenset, frozenset]:
    """(files, folders), absolute paths under ``root``: the files that git tracks in the
    repository whose top is ``root`` though its ignore rules match them, and the folders
    above them up to ``root`` (module docstring); asked once per scan (``forget``)."""
    found = _TRACKED.get(root)
    if found is None:
        found = _TRACKED[root] = _ask_git(root)
    return found


def forget() -> None:
    """Forget what git said (``tracked_ignored``): the next scan asks again (a process
    that scans again after a commit must not go by the last answer)."""
    _TRACKED.clear()


def _ask_git(root: str) -> tuple[frozenset, frozenset]:
    """``tracked_ignored``'s answer from git itself; empty where git cannot give one."""
    import shutil
    import subprocess

    git = shutil.which("git")
    if git is None:
        return frozenset(), frozenset()
    environment = {name: value for name, value in os.environ.items()
                   if not name.startswith("GIT_")}
    try:
        listed = subprocess.run(
            [git, "-c", "core.fsmonitor=false", "-C", root, "ls-files", "-z", "--cached",
             "--ignored", "--exclude-standard"], capture_output=True,
            stdin=subprocess.DEVNULL, timeout=TRACKED_IGNORED_SECONDS, env=environment,
            check=False)
    except (OSError, subprocess.SubprocessError):
        return frozenset(), frozenset()
    if listed.returncode != 0:
        return frozenset(), frozenset()
    files, folders = set(), set()
    for name in listed.stdout.split(b"\0"):
        if not name:
            continue
        path = os.path.join(root, os.fsdecode(name).replace("/", os.sep))
        files.add(path)
        folder = os.path.dirname(path)
        while folder not in folders and len(folder) > len(root):
            folders.add(folder)
            folder = os.path.dirname(folder)
    return frozenset(files), frozenset(folders)
