"""Whether pictures can be drawn, and whether an output folder can be used: the checks
the commands make before any work (``suggest --out``, ``validate --views``)."""

from __future__ import annotations

import hashlib
import importlib.util
import os
import re

from furncheck.export.errors import ExportUnavailable

_UNSAFE = re.compile(r"[^\w.+-]+")
"""Runs of characters that a file name made from a design's name does not keep: all but
letters, digits, '_', '.', '+' and '-' (a path separator, a space, a colon)."""
_RESERVED = re.compile(r"(con|prn|aux|nul|com[1-9]|lpt[1-9])(\..*)?", re.IGNORECASE)
"""Names Windows keeps for devices, with or without an extension."""
STEM_BYTES = 120
"""Longest stem (UTF-8 bytes): with '-suggestion-NN-forces.png' and the like added it stays
well inside the 255 bytes a file name may have."""


def pictures_missing() -> ExportUnavailable | None:
    """Why pictures cannot be drawn here (matplotlib cannot be imported: not installed,
    or installed but broken, at its top or in the modules drawing uses), or None.  (What
    drawing needs is imported here, by a run that is about to draw.)"""
    if importlib.util.find_spec("matplotlib") is None:
        return ExportUnavailable("matplotlib")
    from furncheck.export.views import view_figure_modules

    try:
        view_figure_modules()
    except ExportUnavailable as missing:
        return missing
    except Exception:       # a broken install fails in many ways: a missing shared
        return ExportUnavailable("matplotlib")      # library (OSError), a bad build...
    return None


def prepare_out_dir(out_dir: str) -> str | None:
    """Create ``out_dir`` (with its parents) if needed; why it cannot be used, or None."""
    if os.path.exists(out_dir) and not os.path.isdir(out_dir):
        return "it is not a directory"
    from furncheck.files import why_failed, why_unwritable

    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as error:
        return why_failed(error)        # in the words os.access's finding reads
    if not os.access(out_dir, os.W_OK):
        return why_unwritable(out_dir)
    return None


def file_stem(name: str) -> str:
    """A design's ``name`` as the stem of the files written for it into an output folder:
    each run of other characters than letters, digits, '_', '.', '+' and '-' (a '/', a
    space) made one '_', leading dots dropped (no hidden file, no '..'), 'design' for
    what is left empty, 'design-' before a name Windows keeps for a device ('CON',
    'nul.txt'), and a stem longer than STEM_BYTES cut there and told apart by 8 hex
    digits of the name's SHA-1.  So every file stays inside the folder whatever the name
    says ('../../x' writes '_.._x-view.png' there, '/tmp/x' '_tmp_x-view.png')."""
    stem = _UNSAFE.sub("_", name).lstrip(".") or "design"
    if _RESERVED.fullmatch(stem):
        stem = f"design-{stem}"
    if len(stem.encode()) > STEM_BYTES:
        digest = hashlib.sha1(name.encode()).hexdigest()[:8]
        stem = stem.encode()[:STEM_BYTES - 9].decode(errors="ignore") + "-" + digest
    return stem
