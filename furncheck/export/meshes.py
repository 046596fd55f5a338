"""Plank meshes: every plank as a closed box, written as GLB (viewers) and OBJ (CAD tools).

The OBJ is in the design file's length unit (mm or m), so it measures what the design file
says (the unit is named in its header comment).  The GLB is in metres, the unit glTF
prescribes, so viewers show a mm design at its real size; its scene ``extras`` record the
design and its file unit (``{"design": name, "units": "mm"}``).

A box has the 8 corners of ``Plank.corners`` as vertices (same order) and 12 triangles,
counter-clockwise seen from outside, so normals point outward and every box is watertight
with positive volume.  No normals are written: a viewer then shades each face flat (glTF
requires it), which is what a plank looks like.
"""

from __future__ import annotations

from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING

import numpy as np

from furncheck.design.model import Design, Plank
from furncheck.export.errors import ExportUnavailable

if TYPE_CHECKING:
    import trimesh

BOX_FACES = np.array([
    [0, 2, 1], [1, 2, 3],      # -z  (corner index bits: 1 = +x, 2 = +y, 4 = +z local)
    [4, 5, 6], [5, 7, 6],      # +z
    [0, 1, 5], [0, 5, 4],      # -y
    [2, 6, 7], [2, 7, 3],      # +y
    [0, 4, 6], [0, 6, 2],      # -x
    [1, 3, 7], [1, 7, 5],      # +x
])
"""(12, 3) int: the triangles of a box over the corner order of ``Plank.corners``,
counter-clockwise seen from outside (a rotation keeps that: its determinant is +1)."""

SCENE_ROOT = "design root"
"""Root frame of the scene graph.  trimesh's default, 'world', is a valid plank id and
would clash with that plank's node; a space is not allowed in plank ids."""


def plank_vertices(plank: Plank, unit_scale: float) -> np.ndarray:
    """(8, 3) float: the plank's corners in file units (``unit_scale``: metres per unit)."""
    return plank.corners / unit_scale


def design_mesh(design: Design) -> trimesh.Trimesh:
    """All planks as one mesh, file units, in file order.

    Plank i owns vertices 8 i .. 8 i + 7 and faces 12 i .. 12 i + 11; the plank ids are in
    ``metadata["planks"]``.  Touching planks keep their own vertices (no merging), so
    every box stays closed.
    """
    trimesh = _trimesh()
    vertices = np.reshape([plank_vertices(plank, design.unit_scale)
                           for plank in design.planks], (-1, 3))
    faces = (BOX_FACES + 8 * np.arange(len(design.planks))[:, None, None]).reshape(-1, 3)
    mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    mesh.metadata["planks"] = [plank.id for plank in design.planks]
    mesh.units = design.units
    return mesh


def design_scene(design: Design, metres: bool = False) -> trimesh.Scene:
    """One box geometry and one node per plank, both named by the plank id, in file order
    (viewers list the planks by name); file units, or metres."""
    trimesh = _trimesh()
    scene = trimesh.Scene(base_frame=SCENE_ROOT)
    scene.metadata.update({"design": design.name, "units": design.units})
    scale = 1.0 if metres else design.unit_scale
    for plank in design.planks:
        box = trimesh.Trimesh(vertices=plank_vertices(plank, scale),
                              faces=BOX_FACES, process=False)
        scene.add_geometry(box, geom_name=plank.id, node_name=plank.id)
    return scene


def write_meshes(design: Design, stem: Path) -> list[str]:
    """Write ``stem.glb`` (metres) and ``stem.obj`` (file unit); the folder must exist.
    Returns their paths in that order.  The same design always gives the same bytes."""
    scene = design_scene(design)  # raises ExportUnavailable first when trimesh is missing
    in_metres = design_scene(design, metres=True)
    from trimesh.exchange.gltf import export_glb
    from trimesh.exchange.obj import export_obj

    glb_path = stem.parent / f"{stem.name}.glb"
    obj_path = stem.parent / f"{stem.name}.obj"
    # Left to itself trimesh writes normals whenever it has them cached: say never.
    glb_path.write_bytes(export_glb(in_metres, include_normals=False))
    obj_text = export_obj(scene, include_normals=False, include_color=False,
                          include_texture=False,
                          header=f"furncheck plank mesh, lengths in {design.units}")
    obj_path.write_bytes(obj_text.encode("utf-8"))
    return [str(glb_path), str(obj_path)]


def _trimesh() -> ModuleType:
    """The trimesh module, or ExportUnavailable when the export extra is not installed."""
    try:
        import trimesh
    except ImportError as error:
        raise ExportUnavailable("trimesh") from error
    return trimesh
