"""Whether pictures can be drawn, and whether an output folder can be used: the checks
the commands make before any work (``suggest --out``, ``validate --views``)."""

from __future__ import annotations

import importlib.util
import os

from furncheck.export.errors import ExportUnavailable


def pictures_missing() -> ExportUnavailable | None:
    """Why pictures cannot be drawn here (matplotlib is not installed), or None."""
    if importlib.util.find_spec("matplotlib") is None:
        return ExportUnavailable("matplotlib")
    return None


def prepare_out_dir(out_dir: str) -> str | None:
    """Create ``out_dir`` (with its parents) if needed; why it cannot be used, or None."""
    if os.path.exists(out_dir) and not os.path.isdir(out_dir):
        return "it is not a directory"
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as error:
        return error.strerror or str(error)
    if not os.access(out_dir, os.W_OK):
        return "permission denied"
    return None
