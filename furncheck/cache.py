"""The result cache of ``furncheck validate`` (contract section 4).

What is cached: each design's check result (the ``DesignReport``), not a rendered report,
so one entry serves every ``--format``; reporters render a cached result to the same bytes
as a fresh one.  Only results of designs that were read and checked are stored; an input
error (a missing file, a syntax error) costs nothing to find again and is never cached.

The key of an entry (SHA-256) covers everything a result depends on:

- the file's content (its bytes) and its path as given (a report names it, and a design
  without ``name`` is named after its file);
- every option that changes results: ``--model`` (the design's own ``model`` is part of its
  content);
- the code that computes it: furncheck's version, a digest of the source of the installed
  ``furncheck`` package (a development install changes without a new version), the Python
  version, the installed numpy, scipy and PyYAML (a digest of each distribution's
  ``RECORD``, the hashes of its files: the same for every install of one build, so that
  CI jobs installing afresh share entries; found without importing them),
  and the BLAS thread variables (another thread count may round a last digit differently).

Entries are files ``<dir>/v1/<2 hex digits>/<62 hex digits>`` holding a marker, the key,
a CRC-32 of the rest and the result encoded as lists, strings and numbers
(``furncheck.result_codec``) in Python's ``marshal`` format, which reads back four times
faster than JSON.  Unlike a pickle, an entry is data only: reading one never runs code.
(marshal is not hardened against data crafted to crash it: restore a cache directory
only from where you would take code.)  Entries are written atomically
(``furncheck.files.write_atomically``), so runs in parallel over one cache directory leave
only complete entries.  An entry that cannot be read, is cut short, fails its CRC, holds
another key or a malformed result is ignored: the design is checked and its entry written
again.  The cache never fails a run: when its directory
cannot be written, results are not stored and one warning says so (none where no
result was lost: a warm cache restored read-only).  Deleting the directory
at any time is safe.

The default directory is the user cache directory: ``$FURNCHECK_CACHE_DIR`` when set, else
``$XDG_CACHE_HOME/furncheck`` or ``~/.cache/furncheck`` (Linux and other Unix),
``~/Library/Caches/furncheck`` (macOS), ``%LOCALAPPDATA%\\furncheck\\Cache`` (Windows).
"""

from __future__ import annotations

import base64
import hashlib
import importlib.util
import json
import marshal
import os
import re
import stat
import sys
import zlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from furncheck import __version__
from furncheck import tolerances as tol
from furncheck.files import (
    CACHEDIR_SIGNATURE,
    CACHEDIR_TAG,
    why_failed,
    why_unwritable,
    write_atomically,
)
from furncheck.result import DesignReport
from furncheck.result_codec import CodecError, decode_report, encode

LAYOUT = "v1"
"""Version of the entries' layout and encoding: the name of the folder they live in."""

ENV_DIRECTORY = "FURNCHECK_CACHE_DIR"
"""Environment variable naming the cache directory (over the platform's default)."""

_DEPENDENCIES = (("numpy", "numpy"), ("scipy", "scipy"), ("yaml", "PyYAML"))
"""The numerical dependencies whose build a result depends on: (module, distribution)."""
_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


CACHE_TAG = CACHEDIR_SIGNATURE + (b"\n# This file is a cache directory tag created by "
                                  b"furncheck (its results).\n# For information about cache "
                                  b"directory tags see https://bford.info/cachedir/\n")
"""The CACHEDIR.TAG furncheck writes in its entries' folder (``files.CACHEDIR_TAG``)."""

IGNORE_ALL = b"# made by furncheck: its result cache, nothing to commit\n*\n"
"""The ``.gitignore`` that a cache folder furncheck makes holds (``cache-dir =
".furncheck-cache"`` in a repository stays out of ``git status``); a folder that
existed before is left as it was."""


def default_directory() -> str:
    """The user cache directory of furncheck (see the module docstring)."""
    chosen = os.environ.get(ENV_DIRECTORY)
    if chosen:
        return expand_user(chosen)
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA") or expand_user(r"~\AppData\Local")
        return os.path.join(base, "furncheck", "Cache")
    if sys.platform == "darwin":
        return expand_user("~/Library/Caches/furncheck")
    base = os.environ.get("XDG_CACHE_HOME")
    if not base or not os.path.isabs(base):
        base = expand_user("~/.cache")
    if not os.path.isabs(base):         # no home known at all: not a folder named '~'
        import tempfile

        uid = os.getuid() if hasattr(os, "getuid") else 0
        return os.path.join(tempfile.gettempdir(), f"furncheck-cache-{uid}")
    return os.path.join(base, "furncheck")


def expand_user(path: str) -> str:
    """``os.path.expanduser``, but a HOME set to nothing (some CI containers run so) counts
    as unset: the user database's home, as Python takes it when HOME is unset (the empty
    one made '~/.cache' the root's '/.cache').  Where neither knows a home (a container's
    user with no passwd entry), a '~' path stays as it is (``default_directory`` then
    uses the temporary folder: never a folder named '~' in the current one)."""
    if not (path == "~" or path.startswith(("~/", "~" + os.sep))) \
            or os.environ.get("HOME", None) != "":
        return os.path.expanduser(path)
    home = _user_database_home()
    return path if home is None else home + path[1:]


def _user_database_home() -> str | None:
    """The current user's home from the user database, None where there is none."""
    try:
        import pwd

        return pwd.getpwuid(os.getuid()).pw_dir or None
    except (ImportError, KeyError, AttributeError, OSError):
        return None


def code_fingerprint() -> str:
    """A digest of the code that computes results: furncheck's version and source, the
    Python version, the installed numerical dependencies, the BLAS thread settings."""
    digest = hashlib.sha256()
    for part in (__version__, sys.version, *_dependency_files(),
                 *(f"{name}={os.environ.get(name, '')}" for name in _THREAD_VARIABLES)):
        digest.update(part.encode() + b"\0")
    _digest_sources(digest)
    return digest.hexdigest()


def source_fingerprint() -> str:
    """A digest of furncheck's version and source alone (``furncheck.cluster`` compares a
    cluster's workers with this process by it)."""
    digest = hashlib.sha256(__version__.encode() + b"\0")
    _digest_sources(digest)
    return digest.hexdigest()


def _digest_sources(digest) -> None:
    package = Path(__file__).resolve().parent
    for source in sorted(package.rglob("*.py")):
        digest.update(source.relative_to(package).as_posix().encode() + b"\0")
        digest.update(source.read_bytes() + b"\0")


def _dependency_files() -> list[str]:
    """Per dependency, found without importing it: a digest of its installed
    distribution's ``RECORD`` (each of its files with the hash the wheel gave it, the same
    for every install of one build, wherever and whenever it was installed: CI jobs that
    install the same versions afresh share their entries), or where it has none (a source
    tree on the path) where its package is, with the size and modification time of its
    ``__init__.py``.  (The modification time alone, kept before, is the install's: pip
    stamps each file with it, so a fresh install missed every entry.)"""
    versions = []
    for name, distribution in _DEPENDENCIES:
        try:
            spec = importlib.util.find_spec(name)
            origin = spec.origin if spec is not None else None
            record = _record(Path(origin).parent, distribution) if origin else None
            info = os.stat(origin) if origin and record is None else None
        except (ImportError, ValueError, OSError):
            info = origin = record = None
        if record is not None:
            versions.append(f"{name}=record:{hashlib.sha256(record).hexdigest()}")
        else:
            versions.append(f"{name}={origin}:{info.st_size}:{info.st_mtime_ns}" if info
                            else f"{name}=?")
    return versions


def _record(package: Path, distribution: str) -> bytes | None:
    """The files of the distribution ``distribution`` installed beside ``package`` as its
    ``RECORD`` lists them with their hashes (its ``<name>-<version>.dist-info`` folder,
    the name compared as pip normalizes it): the lines that carry a hash, but for those
    of the dist-info folder itself (``INSTALLER``, ``REQUESTED`` and the like say how it
    was installed, not what) and of files it put outside the folder it is in
    (``../../../bin/f2py``: a script's first line names the environment's Python).  Of
    several such folders (a stale one left by an upgrade), the one whose hash of the
    package's ``__init__.py`` is the file's on disk; None where there is none."""
    wanted = _normalized(distribution)
    listed = f"{package.name}/__init__.py,".encode()
    try:
        init = (package / "__init__.py").read_bytes()
    except OSError:
        return None
    actual = b"sha256=" + base64.urlsafe_b64encode(hashlib.sha256(init).digest()).rstrip(b"=")
    for entry in sorted(os.listdir(package.parent)):
        stem, dot, kind = entry.rpartition(".")
        if kind != "dist-info" or _normalized(stem.rpartition("-")[0]) != wanted:
            continue
        try:
            record = (package.parent / entry / "RECORD").read_bytes()
        except OSError:
            continue
        lines = record.splitlines()
        if not any(line.startswith(listed + actual + b",") for line in lines):
            continue
        return b"\n".join(line for line in lines
                          if not line.startswith((b"../", entry.encode() + b"/"))
                          and line.split(b",")[1:2] not in ([], [b""]))
    return None


def _normalized(name: str) -> str:
    """A distribution's name as pip compares names (PEP 503): lower case, runs of '-',
    '_' and '.' as one '-'."""
    return re.sub(r"[-_.]+", "-", name).lower()


@dataclass
class ResultCache:
    """Design results stored under ``directory`` for runs with the same code and
    result-changing options (``options``, e.g. ``{"model": "rigid"}``; None values
    count too).  ``unwritable`` holds the reason when storing failed (then no more tries).
    """

    directory: str
    options: dict[str, str | None] = field(default_factory=dict)
    unwritable: str | None = None
    lost: int = 0       # results not stored because of ``unwritable`` (pieces do not count)
    _prefix: bytes = field(init=False, repr=False)

    def __post_init__(self) -> None:
        context = {"code": code_fingerprint(), "options": self.options}
        self._prefix = json.dumps(context, sort_keys=True).encode() + b"\0"

    def key(self, path: str, content: bytes) -> str:
        """The entry's key (64 hex digits) of the file ``path`` (as given) holding
        ``content``."""
        digest = hashlib.sha256(self._prefix)
        digest.update(path.encode("utf-8", "surrogateescape") + b"\0")
        digest.update(content)
        return digest.hexdigest()

    def key_of(self, path: str) -> str | None:
        """The key of the file ``path`` as it is now, or None for an input that is not
        cached (not a regular file that can be read: ``read_source``)."""
        content = read_source(path)
        return None if content is None else self.key(path, content)

    def entry_path(self, key: str) -> str:
        return os.path.join(self.directory, LAYOUT, key[:2], key[2:])

    def piece_path(self, key: str, fmt: str) -> str:
        """Where the report piece of ``key`` in format ``fmt`` is stored."""
        return f"{self.entry_path(key)}.{fmt}"

    def get(self, key: str, path: str) -> DesignReport | None:
        """The stored result of ``key`` (its report naming ``path``), or None: not stored,
        or the entry is damaged (it is then overwritten by the next ``put``)."""
        data = _read_entry(self.entry_path(key), _MARKER + bytes.fromhex(key))
        if data is None:
            return None
        try:
            report = decode_report(data)
        except (CodecError, TypeError, ValueError):
            return None
        if report.design != path or report.error is not None:
            return None
        return report

    def get_piece(self, key: str, fmt: str) -> tuple[bool | None, bool, Any] | None:
        """The stored ``(valid, error, piece)`` of ``key``'s report in format ``fmt`` (an
        ``Entry``'s fields), or None: not stored, or damaged."""
        data = _read_entry(self.piece_path(key, fmt),
                           _MARKER + bytes.fromhex(key) + fmt.encode() + b"\0")
        if type(data) is not tuple or len(data) != 3:
            return None
        return data

    def probe(self) -> None:
        """Find out now whether entries can be written (``unwritable`` says why not), so
        that worker processes, whose own findings are lost, need not try."""
        folder = os.path.join(self.directory, LAYOUT)
        made = not os.path.lexists(self.directory)
        try:
            os.makedirs(folder, exist_ok=True)
            if not os.access(folder, os.W_OK | os.X_OK):
                self.unwritable = f"{self.directory}: {why_unwritable(folder)}"
                return
            if made:            # a folder of its own: git leaves it out (as pytest's)
                write_atomically(os.path.join(self.directory, ".gitignore"), IGNORE_ALL)
        except OSError as error:
            self.unwritable = f"{self.directory}: {why_failed(error)}"
            return
        if os.path.islink(folder):     # (restored from an archive): no entry can be
            self.unwritable = (f"{self.directory}: {LAYOUT} is a symbolic link (nothing "
                               f"is written through one)")     # stored, and the run says so
            return
        tag = os.path.join(folder, CACHEDIR_TAG)    # scans pass the folder over, whatever
        if not os.path.lexists(tag):                # cache is in use (and backups do)
            try:
                write_atomically(tag, CACHE_TAG, follow_links=False)
            except OSError:
                pass                    # (the entries' own writes will say what is wrong)

    def store(self, path: str, key: str | None, report: DesignReport) -> bool:
        """``put`` the report of the file ``path`` under ``key`` (its ``key_of`` before it
        was checked) if the file still holds what it held then: a file edited during its
        check is not stored under its old content's key.  Whether it was stored.  (It may
        run in a worker process: entries are written atomically.)"""
        if key is None or report.error is not None or self.key_of(path) != key:
            return False
        return self.put(key, report)

    def put(self, key: str, report: DesignReport) -> bool:
        """Store ``report`` (a checked design, not an input error) under ``key``; whether
        it was stored."""
        if report.error is not None:
            return False
        if self.unwritable is not None:
            self.lost += 1
            return False
        return self._write(self.entry_path(key), _MARKER + bytes.fromhex(key), encode(report))

    def put_piece(self, key: str, fmt: str, fields: tuple[bool | None, bool, Any]) -> bool:
        """Store ``(valid, error, piece)`` of ``key``'s report in format ``fmt`` (only for
        a key whose report is stored: the piece is made from it)."""
        if self.unwritable is not None:         # (no result lost: a piece is made from
            return False                        # the stored result again)
        return self._write(self.piece_path(key, fmt),
                           _MARKER + bytes.fromhex(key) + fmt.encode() + b"\0", fields)

    def _write(self, target: str, header: bytes, data: Any) -> bool:
        """Write an entry: never through a symlink (a cache restored from an archive may
        hold one, at an entry or at its folder): such an entry is not stored."""
        try:
            payload = marshal.dumps(data)
            folder = os.path.dirname(target)
            layout = os.path.join(os.path.realpath(self.directory), LAYOUT)
            if os.path.realpath(os.path.dirname(folder)) != layout:
                return False                    # the layout's folder is a link: make
            os.makedirs(folder, exist_ok=True)  # nothing through it
            if os.path.realpath(folder) != os.path.join(layout, os.path.basename(folder)):
                return False                    # a folder of the layout is a link
            write_atomically(target, header + _crc(payload) + payload, follow_links=False)
        except (OSError, ValueError) as error:   # ValueError: marshal of an odd value
            self.unwritable = f"{self.directory}: {why_failed(error)}"
            self.lost += 1
            return False
        return True


def _read_entry(path: str, header: bytes) -> Any:
    """The data of the entry at ``path``, or None when it is missing, does not start with
    ``header``, fails its CRC or does not unmarshal."""
    try:                                    # an entry that is a link is not read
        with open(os.open(path, os.O_RDONLY | _NO_FOLLOW), "rb") as stream:
            entry = stream.read()
    except OSError:
        return None
    payload = entry[len(header) + 4:]
    if not entry.startswith(header) or entry[len(header):len(header) + 4] != _crc(payload):
        return None
    try:
        return marshal.loads(payload)
    except (ValueError, EOFError, TypeError, RecursionError):
        return None


_MARKER = b"furncheck-result\0"
_NO_FOLLOW = getattr(os, "O_NOFOLLOW", 0)


def _crc(payload: bytes) -> bytes:
    return zlib.crc32(payload).to_bytes(4, "big")


def read_source(path: str) -> bytes | None:
    """The bytes of the file ``path`` to key it by, or None when it is no regular file of
    at most ``MAX_FILE_BYTES`` that can be read (the check reports it; such inputs are
    never cached)."""
    try:
        info = os.stat(path)
        if not stat.S_ISREG(info.st_mode) or info.st_size > tol.MAX_FILE_BYTES:
            return None
        with open(path, "rb") as stream:
            return stream.read()
    except OSError:
        return None
