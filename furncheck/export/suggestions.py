"""The files of ``furncheck suggest --out DIR``: per suggestion, its design file (the very
text that was validated), its meshes and its force-space plot.

    DIR/suggestion-01.yaml   DIR/suggestion-01.glb   DIR/suggestion-01.obj
    DIR/suggestion-01-forces.png
"""

from __future__ import annotations

import importlib.util
import os
from dataclasses import dataclass
from pathlib import Path

from furncheck.export.errors import ExportUnavailable
from furncheck.export.meshes import write_meshes
from furncheck.export.plots import plot_force_space
from furncheck.suggest import SuggestionReport

__all__ = ["ExportUnavailable", "Written", "prepare_out_dir", "write_files"]


@dataclass(frozen=True)
class Written:
    """Files written for one suggestion (paths as strings, under the DIR given)."""

    design_file: str | None = None
    meshes: tuple[str, ...] = ()
    plots: tuple[str, ...] = ()


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


def write_files(result: SuggestionReport, out_dir: str,
                meshes: bool = True) -> dict[int, Written]:
    """Write every suggestion's files; rank -> what was written.  Raises
    ExportUnavailable (before writing anything) when meshes are wanted and the export
    extra is missing."""
    if meshes and result.suggestions:
        for module in ("trimesh", "matplotlib"):
            if importlib.util.find_spec(module) is None:
                raise ExportUnavailable(module)
    written = {}
    for suggestion in result.suggestions:
        stem = Path(out_dir) / f"suggestion-{suggestion.rank:02d}"
        design_file = f"{stem}.yaml"
        Path(design_file).write_text(suggestion.text, encoding="utf-8")
        mesh_files: tuple[str, ...] = ()
        plots: tuple[str, ...] = ()
        if meshes:
            mesh_files = tuple(write_meshes(suggestion.design, stem))
            plots = (plot_force_space(result.report, suggestion.report,
                                      Path(f"{stem}-forces.png")),)
        written[suggestion.rank] = Written(design_file, mesh_files, plots)
    return written
