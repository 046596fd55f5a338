"""Writing files so that a reader never sees half of one.

``write_atomically`` writes a temporary file beside the target and renames it over the
target (``os.replace``, atomic on POSIX and Windows within one file system): a run that
is interrupted, or that fails while writing, leaves the old file as it was, and two
processes writing the same path leave one complete file, the last writer's.  The report of
``-o FILE`` and every cache entry are written this way.
"""

from __future__ import annotations

import codecs
import contextlib
import errno
import os
from collections.abc import Iterator
from typing import BinaryIO

CACHEDIR_TAG = "CACHEDIR.TAG"
"""The file that marks a folder as a cache (the Cache Directory Tagging Specification,
bford.info/cachedir: backup tools and ``tar --exclude-caches`` pass such folders over):
furncheck writes one in its result cache's entries folder, and scans do not enter a
folder that holds one."""
CACHEDIR_SIGNATURE = b"Signature: 8a477f597d28d172789f06886806bc55"
"""How a CACHEDIR.TAG begins (the specification's signature)."""
TEMP_SUFFIX = ".tmp"
"""Suffix of the temporary files (``.NAME.XXXXXXXX.tmp`` beside the target)."""
TEMP_NAME_ROOM = 255 - len(".." + "XXXXXXXX" + TEMP_SUFFIX)
"""Bytes of the target's name that fit in a temporary file's name (255 bytes, the usual
limit of a file name); a longer one makes it ``.furncheck.XXXXXXXX.tmp``."""


def utf8(text: str) -> bytes:
    """``text`` in UTF-8; a file name that is not UTF-8 (its bytes held as surrogates, as
    Python reads such names) written with its odd characters escaped ('\\udcff'), as the
    JSON report writes them, so that every report, page and file written stays valid
    UTF-8 (a strict encoding failed on them: an internal error, and no page at all)."""
    return text.encode("utf-8", "backslashreplace")


def readable(text: str) -> str:
    """``text`` as the text of ``utf8``: what UTF-8 cannot hold (a file name's byte that
    is not UTF-8, held as a lone surrogate) written out as its escape, '\\udcff', the
    name every report shows (README, "-o FILE").  JSON would write the surrogate itself
    as "\\udcff", an escape that reads back as a lone surrogate, which JSON leaves
    undefined (RFC 8259 8.2: jq writes U+FFFD for it); XML and the runner's workflow
    commands cannot hold it either."""
    return text if text.isascii() else utf8(text).decode("utf-8")


def neutral(text: str) -> str:
    """A text report's lines with '##[' written '#\\x23[': a GitHub Actions runner reads
    '##[' anywhere in a line of the log as a workflow command (the old form,
    '##[error]...'), and a file's path, a design's name or a load case's name, which
    the lines quote, may hold one."""
    return text.replace("##[", "#\\x23[") if "##[" in text else text


def write_atomically(path: str, data: bytes, *, durable: bool = False,
                     follow_links: bool = True) -> None:
    """Replace the file at ``path`` by ``data`` in one step (see ``replacing``)."""
    with replacing(path, durable=durable, follow_links=follow_links) as stream:
        stream.write(data)


@contextlib.contextmanager
def replacing(path: str, *, durable: bool = False,
              follow_links: bool = True) -> Iterator[BinaryIO]:
    """A binary stream whose bytes replace the file at ``path`` in one step when the
    ``with`` block ends without an exception.

    The new file gets the old file's permission bits, or the usual ones for a new file
    (0o666 less the umask).  ``durable``: flush the data to the disk before the rename (a
    power cut then leaves the old or the new file, never an empty one).  An exception in
    the block (also KeyboardInterrupt) or an OSError leaves ``path`` untouched and no
    temporary file behind.  A symlink at ``path`` stays: the file it points to is
    replaced.  A special file (``/dev/stdout``, a pipe) cannot be replaced: it is written
    directly.  Without ``follow_links`` (the result cache, whose entries are never links
    nor special files: one planted there must not send a write elsewhere) whatever is at
    ``path`` is replaced.
    """
    if follow_links and os.path.exists(path) and not os.path.isfile(path):
        with open(path, "wb") as stream:    # (tested before resolving: /dev/stdout on a
            yield stream                    # pipe resolves to no file at all)
        return
    if follow_links:
        path = os.path.realpath(path)
    import tempfile  # here: only -o FILE and the cache write files

    folder, name = os.path.split(path)
    if len(os.fsencode(name)) > TEMP_NAME_ROOM:         # '.NAME.XXXXXXXX.tmp' too long
        name = "furncheck"
    try:
        handle, temporary = tempfile.mkstemp(dir=folder, prefix=f".{name}.",
                                             suffix=TEMP_SUFFIX)
    except FileNotFoundError as error:
        if not os.path.isdir(folder or "."):
            raise
        # the folder is there but makes no new files (/proc, /sys): its ENOENT is no reason
        raise OSError(error.errno, f"its folder {folder or '.'} takes no new files "
                                   f"({error.strerror})") from None
    try:
        with os.fdopen(handle, "wb") as stream:
            yield stream
            if durable:
                stream.flush()
                os.fsync(stream.fileno())
        os.chmod(temporary, _mode_for(path, follow_links))
        os.replace(temporary, path)
    except BaseException:   # also KeyboardInterrupt: never leave the temporary file
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def _mode_for(path: str, follow_links: bool = True) -> int:
    """Permission bits for the new file: the old file's, else (and without
    ``follow_links``: not those of what a link there points to) 0o666 less the umask."""
    if follow_links:
        try:
            return os.stat(path).st_mode & 0o7777
        except OSError:
            pass
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


READ_ONLY = "read-only file system"
"""How ``why_failed`` and ``why_unwritable`` say that a file system is mounted read-only."""
DENIED = "permission denied"
"""... and that the permissions forbid the write."""


def why_failed(error: Exception) -> str:
    """Why a write failed, in ``why_unwritable``'s words where it is the file system's or
    the permissions' ('read-only file system', 'permission denied': a CI job's cache
    restored read-only reads alike however it was found out), else the error's own."""
    code = getattr(error, "errno", None)
    if code == errno.EROFS:
        return READ_ONLY
    if code in (errno.EACCES, errno.EPERM):
        return DENIED
    return getattr(error, "strerror", None) or str(error)


def why_unwritable(path: str) -> str:
    """Why ``path`` (a file or folder that ``os.access`` finds not writable) cannot be
    written, in the words of the error writing would raise: 'read-only file system' where
    its file system is mounted so (a CI runner's read-only checkout), else 'permission
    denied'."""
    try:
        read_only = bool(os.statvfs(path).f_flag & os.ST_RDONLY)
    except (OSError, AttributeError):       # no statvfs (Windows), or gone
        read_only = False
    return READ_ONLY if read_only else DENIED


def is_cache_tag(path: str) -> bool:
    """Whether the file at ``path`` begins with CACHEDIR_SIGNATURE (a CACHEDIR.TAG); False
    where it cannot be read."""
    try:
        with open(path, "rb") as stream:
            return stream.read(len(CACHEDIR_SIGNATURE)) == CACHEDIR_SIGNATURE
    except OSError:
        return False


_WIDE_BOMS = ((codecs.BOM_UTF32_LE, "utf-32"), (codecs.BOM_UTF32_BE, "utf-32"),
              (codecs.BOM_UTF16_LE, "utf-16"), (codecs.BOM_UTF16_BE, "utf-16"))
"""Byte-order marks of UTF-32 and UTF-16 (UTF-32's first: its little-endian mark begins
with UTF-16's) and the codec that reads the text after them."""


def as_utf8(data: bytes) -> bytes:
    """``data``, a text file's bytes, in UTF-8: UTF-16 or UTF-32 text that begins with its
    byte-order mark (what an editor's 'Unicode' saves; YAML and JSON both allow it) recoded,
    anything else as it is.  Raises UnicodeDecodeError where such text does not decode."""
    for mark, codec in _WIDE_BOMS:
        if data.startswith(mark):
            return data.decode(codec).encode("utf-8")
    return data
