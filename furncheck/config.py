"""Options from ``[tool.furncheck]`` in the nearest ``pyproject.toml`` (contract section 4).

The search starts in the folder of the PATHs given (their common folder; the current one
for standard input) and goes up to the top of the repository (the folder holding ``.git``)
or of the file system; the first ``pyproject.toml`` with a ``[tool.furncheck]`` table is
used (one without that table says nothing about furncheck and is passed over).  The command
line wins over every key; ``exclude`` patterns add to ``--exclude`` ones.

    [tool.furncheck]
    exclude = ["drafts", "vendor/**"]   # gitignore patterns, anchored at this file's folder
    format = "github"                   # validate's --format
    jobs = 2                            # --jobs (validate, range)
    model = "rigid"                     # --model (validate, suggest, range)
    cache = false                       # --no-cache
    cache-dir = ".furncheck-cache"      # --cache-dir, relative to this file's folder
    skip-non-designs = true             # --skip-non-designs
    force-exclude = true                # --force-exclude

An unknown key or a value of the wrong type is an error (``ConfigError``, one line naming
the file and the key), as in design files: a typo must not be silently ignored.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass

from furncheck import tolerances as tol
from furncheck.errors import FurncheckError
from furncheck.plain import closest
from furncheck.report import REPORTERS

PYPROJECT = "pyproject.toml"
GIT_DIR = ".git"
"""The folder that marks the top of a git repository (where the search stops)."""
_MAY_HOLD_TABLE = re.compile(
    r"""tool.*furncheck|^[ \t]*(\[+[ \t]*["']?tool["']?[ \t]*\]|["']?tool["']?[ \t]*=)""",
    re.MULTILINE)
"""Where a pyproject.toml could define ``tool.furncheck``: a line that names both (a
``[tool.furncheck]`` header, a dotted key, or only a comment), a bare ``[tool]`` header
or a ``tool = {...}`` inline table.  A file with none of them is passed over unparsed (a
broken file too: it says nothing about furncheck); one with any is parsed in full."""


class ConfigError(FurncheckError):
    """A ``[tool.furncheck]`` table that cannot be used; ``str()`` is the line to show."""


@dataclass(frozen=True)
class Config:
    """The options of one ``[tool.furncheck]`` table; None (or ()) where it sets none.

    path : the pyproject.toml it comes from (None: no table found)
    folder : that file's folder (absolute): the base of ``exclude`` and ``cache_dir``
    """

    path: str | None = None
    folder: str | None = None
    exclude: tuple[str, ...] = ()
    format: str | None = None
    jobs: int | None = None
    model: str | None = None
    cache: bool | None = None
    cache_dir: str | None = None
    skip_non_designs: bool | None = None
    force_exclude: bool | None = None


def load_config(paths: tuple[str, ...] | list[str] = ()) -> Config:
    """The ``[tool.furncheck]`` options for a run on ``paths`` (see the module docstring);
    ``Config()`` when no such table is found.  Raises ConfigError."""
    folder = start_folder(paths)
    while True:
        candidate = os.path.join(folder, PYPROJECT)
        if os.path.isfile(candidate):
            table = _furncheck_table(candidate)
            if table is not None:
                return _config(candidate, table)
        parent = os.path.dirname(folder)
        if os.path.exists(os.path.join(folder, GIT_DIR)) or parent == folder:
            return Config()
        folder = parent


def start_folder(paths: tuple[str, ...] | list[str]) -> str:
    """Where the search for pyproject.toml starts: the common folder of ``paths`` (a file
    stands for its folder; ``-`` for the current one), absolute."""
    folders = []
    for path in paths:
        absolute = os.path.abspath(os.curdir if path == "-" else path)
        folders.append(absolute if os.path.isdir(absolute) else os.path.dirname(absolute))
    try:
        return os.path.commonpath(folders) if folders else os.path.abspath(os.curdir)
    except ValueError:          # paths on different drives (Windows)
        return os.path.abspath(os.curdir)


def _furncheck_table(path: str) -> dict | None:
    """The ``[tool.furncheck]`` table of a pyproject.toml, None where it has none."""
    try:
        with open(path, "rb") as stream:
            text = stream.read().decode("utf-8")
        if not _MAY_HOLD_TABLE.search(text):
            return None
        import tomllib  # here: most runs find no pyproject.toml with the table to read

        document = tomllib.loads(text)
    except OSError as error:
        raise ConfigError(f"{path}: cannot read: {error.strerror or error}") from None
    except (ValueError, UnicodeDecodeError) as error:   # tomllib.TOMLDecodeError too
        raise ConfigError(f"{path}: not valid TOML: {error}") from None
    tool = document.get("tool")
    table = tool.get("furncheck") if isinstance(tool, dict) else None
    if table is not None and not isinstance(table, dict):
        raise ConfigError(f"{path}: tool.furncheck: expected a table, got "
                          f"{type(table).__name__}")
    return table


_KEYS = ("cache", "cache-dir", "exclude", "force-exclude", "format", "jobs", "model",
         "skip-non-designs")


def _config(path: str, table: dict) -> Config:
    for key in table:
        if key not in _KEYS:
            close = closest(key, _KEYS)
            meant = f"did you mean {close!r}? " if close else ""
            raise ConfigError(f"{path}: [tool.furncheck]: unknown key {key!r} ({meant}known: "
                              f"{', '.join(_KEYS)})")

    def fail(key: str, expected: str) -> ConfigError:
        return ConfigError(f"{path}: [tool.furncheck] {key}: expected {expected}, got "
                           f"{table[key]!r}")

    def choice(key: str, choices: tuple[str, ...]) -> str | None:
        value = table.get(key)
        if value is not None and value not in choices:
            raise fail(key, "one of " + ", ".join(choices))
        return value

    def flag(key: str) -> bool | None:
        value = table.get(key)
        if value is not None and not isinstance(value, bool):
            raise fail(key, "true or false")
        return value

    exclude = table.get("exclude", [])
    if isinstance(exclude, str):
        exclude = [exclude]
    if not isinstance(exclude, list) or not all(isinstance(item, str) for item in exclude):
        raise fail("exclude", "a list of gitignore patterns")
    jobs = table.get("jobs")
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise fail("jobs", "a whole number of at least 1")
    cache_dir = table.get("cache-dir")
    if cache_dir is not None and (not isinstance(cache_dir, str) or not cache_dir
                                  or "\0" in cache_dir):
        raise fail("cache-dir", "a folder")
    folder = os.path.dirname(os.path.abspath(path))
    return Config(
        path=path, folder=folder, exclude=tuple(exclude), format=choice("format", tuple(REPORTERS)),
        jobs=jobs, model=choice("model", tol.MODELS), cache=flag("cache"),
        cache_dir=None if cache_dir is None else os.path.join(folder,
                                                              os.path.expanduser(cache_dir)),
        skip_non_designs=flag("skip-non-designs"), force_exclude=flag("force-exclude"))
