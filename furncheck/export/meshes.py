"""Plank meshes: every plank a closed, coloured box, as GLB (viewers, web pages) and
OBJ + MTL (CAD and modelling tools).

    glb_bytes(design, report, marks) -> bytes        write_meshes(...) -> [glb, obj, mtl]
    obj_text(design, report, marks, mtl_name) -> str mtl_text(design, report, marks) -> str

Both are written here, with numpy, json and struct alone (no trimesh: the files are
small and fully specified, and writing them takes a millisecond):

* GLB (glTF 2.0, binary) is in metres and Y-up, as glTF prescribes: the vertices are the
  planks' corners in metres with the design's z up, and the root node ``design root``
  turns them by -90 degrees about x (glTF y = design z, glTF z = -design y).  One node
  per plank, named by its id, with its own mesh (same name) and material (same name),
  whose ``baseColorFactor`` is the views' colour of the plank's utilization
  (``colours.utilization_rgb``) converted from sRGB to linear, as glTF wants, so a viewer
  shows the views' colour.  Each plank node's ``extras`` hold ``utilization`` (null when
  not solved) and, for a plank a suggestion changed or added, ``mark``: 'changed' or
  'added'; such a plank's mesh has a second primitive, lines along its box's edges (drawn
  1 mm outside it) in the mark's colour (material ``changed`` or ``added``).  The scene's
  ``extras`` name the design and its file unit.
* OBJ is in the design file's unit and keeps its z up (the header says so); ``mtllib``
  names the MTL written beside it.  One object (``o``) per plank, named by its id, using
  the material of the same name (``Kd``: the views' colour); a changed or added plank is
  preceded by a comment saying so and has its box's 12 edges as line elements (``l``).

A box has the 8 corners of ``Plank.corners`` as vertices (same order) and 12 triangles,
counter-clockwise seen from outside, so normals point outward and every box is watertight
with positive volume.  No normals are written: viewers shade each face flat (glTF asks
them to), which is what a plank looks like.  The same input always gives the same bytes.
"""

from __future__ import annotations

import json
import struct
from pathlib import Path

import numpy as np

from furncheck.design.model import Design
from furncheck.export.colours import MARK_RGB, utilization_rgb
from furncheck.export.findings import plank_utilization
from furncheck.files import utf8, write_atomically
from furncheck.result import DesignReport

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

BOX_EDGES = np.array([[0, 1], [2, 3], [4, 5], [6, 7],      # along local x
                      [0, 2], [1, 3], [4, 6], [5, 7],      # along local y
                      [0, 4], [1, 5], [2, 6], [3, 7]])     # along local z
"""(12, 2) int: the edges of a box over the same corner order."""

SCENE_ROOT = "design root"
"""Name of the GLB's root node (a space is not allowed in plank ids, so no plank node
can share it)."""

Z_UP_TO_Y_UP = (-0.7071067811865476, 0.0, 0.0, 0.7071067811865476)
"""Root node rotation, quaternion (x, y, z, w): -90 degrees about x, design z -> glTF y."""

OUTLINE_GAP = 0.001
"""m: how far outside its box a marked plank's outline runs (lines on the faces would
flicker against them)."""

GLTF_FLOAT, GLTF_UINT16 = 5126, 5123
GLTF_ARRAY_BUFFER, GLTF_ELEMENT_ARRAY_BUFFER = 34962, 34963
GLTF_LINES, GLTF_TRIANGLES = 1, 4
ROUGHNESS = 0.85
"""Materials are matt (MDF), not metallic."""


def plank_colours(design: Design, report: DesignReport | None) -> dict[str, tuple]:
    """Per plank id, its sRGB colour (the views'): by utilization, grey without a report."""
    used = plank_utilization(report, design.planks) if report is not None else \
        {plank.id: None for plank in design.planks}
    return {plank_id: utilization_rgb(value) for plank_id, value in used.items()}


def srgb_to_linear(values) -> list[float]:
    """sRGB components (0..1) to linear ones (IEC 61966-2-1), glTF's colour space."""
    values = np.asarray(values, dtype=float)
    linear = np.where(values <= 0.04045, values / 12.92, ((values + 0.055) / 1.055) ** 2.4)
    return [round(float(value), 6) for value in linear]


def glb_bytes(design: Design, report: DesignReport | None = None,
              marks: dict[str, str] | None = None) -> bytes:
    """The design as a binary glTF 2.0 file (metres, Y-up; see the module docstring).
    ``report``: its validation (colours by utilization; grey without); ``marks``: plank id
    -> 'changed' or 'added' (``findings.changed_planks``)."""
    marks = marks or {}
    colours = plank_colours(design, report)
    used = plank_utilization(report, design.planks) if report is not None else {}
    mark_names = sorted({marks[plank.id] for plank in design.planks if plank.id in marks})
    materials = [_material(plank.id, colours[plank.id]) for plank in design.planks]
    materials += [_material(name, MARK_RGB[name]) for name in mark_names]
    chunks: list[bytes] = []
    views: list[dict] = []
    accessors: list[dict] = []

    def add(data: np.ndarray, target: int, accessor: dict) -> int:
        raw = data.tobytes()
        views.append({"buffer": 0, "byteOffset": sum(map(len, chunks)),
                      "byteLength": len(raw), "target": target})
        chunks.append(raw + b"\0" * (-len(raw) % 4))
        accessors.append({"bufferView": len(views) - 1, **accessor})
        return len(accessors) - 1

    def positions(corners: np.ndarray) -> int:
        data = corners.astype("<f4")
        return add(data, GLTF_ARRAY_BUFFER,
                   {"componentType": GLTF_FLOAT, "count": len(data), "type": "VEC3",
                    "min": [float(v) for v in data.min(axis=0)],
                    "max": [float(v) for v in data.max(axis=0)]})

    def indices(index: np.ndarray) -> int:
        data = index.astype("<u2").reshape(-1)
        return add(data, GLTF_ELEMENT_ARRAY_BUFFER,
                   {"componentType": GLTF_UINT16, "count": len(data), "type": "SCALAR"})

    nodes: list[dict] = [{"name": SCENE_ROOT, "rotation": list(Z_UP_TO_Y_UP),
                          "children": list(range(1, len(design.planks) + 1))}]
    meshes: list[dict] = []
    for k, plank in enumerate(design.planks):
        primitives = [{"attributes": {"POSITION": positions(plank.corners)},
                       "indices": indices(BOX_FACES), "material": k,
                       "mode": GLTF_TRIANGLES}]
        extras: dict = {"utilization": used.get(plank.id)}
        if plank.id in marks:
            extras["mark"] = marks[plank.id]
            primitives.append({
                "attributes": {"POSITION": positions(_outline_corners(plank))},
                "indices": indices(BOX_EDGES),
                "material": len(design.planks) + mark_names.index(marks[plank.id]),
                "mode": GLTF_LINES})
        meshes.append({"name": plank.id, "primitives": primitives})
        nodes.append({"name": plank.id, "mesh": k, "extras": extras})
    document = {
        "asset": {"version": "2.0", "generator": "furncheck"},
        "scene": 0,
        "scenes": [{"name": design.name, "nodes": [0],
                    "extras": {"design": design.name, "units": design.units}}],
        "nodes": nodes, "meshes": meshes, "materials": materials,
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": sum(map(len, chunks))}],
    }
    return _glb(json.dumps(document, separators=(",", ":"), allow_nan=False).encode(),
                b"".join(chunks))


def obj_text(design: Design, report: DesignReport | None = None,
             marks: dict[str, str] | None = None, mtl_name: str | None = None) -> str:
    """The design as OBJ text in its file unit, z up, one object per plank using the
    material of its id (``mtl_text``; ``mtl_name``: the MTL file named by ``mtllib``)."""
    marks = marks or {}
    lines = [f"# furncheck plank mesh, lengths in {design.units}, z up",
             f"# design {design.name}"]
    if mtl_name:
        lines.append(f"mtllib {mtl_name}")
    for k, plank in enumerate(design.planks):
        base = 8 * k + 1
        if plank.id in marks:
            lines.append(f"# {plank.id}: {marks[plank.id]}")
        lines.append(f"o {plank.id}")
        lines.append(f"usemtl {plank.id}")
        lines.extend("v " + " ".join(_number(v) for v in corner)
                     for corner in (plank.corners / design.unit_scale).tolist())
        lines.extend(f"f {a + base} {b + base} {c + base}" for a, b, c in BOX_FACES.tolist())
        if plank.id in marks:
            lines.extend(f"l {a + base} {b + base}" for a, b in BOX_EDGES.tolist())
    return "\n".join(lines) + "\n"


def mtl_text(design: Design, report: DesignReport | None = None,
             marks: dict[str, str] | None = None) -> str:
    """One material per plank, named by its id: diffuse colour ``Kd`` = the views'
    colour of its utilization (a comment says which, and its mark)."""
    marks = marks or {}
    used = plank_utilization(report, design.planks) if report is not None else {}
    colours = plank_colours(design, report)
    lines = [f"# furncheck plank materials of {design.name}: colour = utilization"]
    for plank in design.planks:
        value = used.get(plank.id)
        note = "not solved" if value is None else f"utilization {value:.3f}"
        if plank.id in marks:
            note += f", {marks[plank.id]}"
        red, green, blue = colours[plank.id]
        lines += [f"newmtl {plank.id}", f"# {note}",
                  f"Kd {red:.4f} {green:.4f} {blue:.4f}", "Ka 0 0 0", "Ks 0 0 0", "d 1",
                  "illum 1", ""]
    return "\n".join(lines)


def write_meshes(design: Design, stem: Path, report: DesignReport | None = None,
                 marks: dict[str, str] | None = None) -> list[str]:
    """Write ``stem.glb`` (metres, Y-up), ``stem.obj`` (file unit) and ``stem.mtl``; the
    folder must exist.  Returns their paths in that order."""
    stem = Path(stem)
    paths = [stem.parent / f"{stem.name}{suffix}" for suffix in (".glb", ".obj", ".mtl")]
    write_atomically(str(paths[0]), glb_bytes(design, report, marks))
    write_atomically(str(paths[1]),
                     utf8(obj_text(design, report, marks, paths[2].name)))
    write_atomically(str(paths[2]), utf8(mtl_text(design, report, marks)))
    return [str(path) for path in paths]


def _material(name: str, rgb) -> dict:
    return {"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": [*srgb_to_linear(rgb), 1.0], "metallicFactor": 0.0,
        "roughnessFactor": ROUGHNESS}}


def _outline_corners(plank) -> np.ndarray:
    """(8, 3) m: the plank's box grown by OUTLINE_GAP on every side."""
    signs = (plank.corners - plank.center_array) @ plank.rotation_matrix
    signs = np.sign(signs)
    grown = plank.half_extents + OUTLINE_GAP
    return plank.center_array + (signs * grown) @ plank.rotation_matrix.T


def _glb(document: bytes, binary: bytes) -> bytes:
    """GLB container: header, JSON chunk (padded with spaces), BIN chunk (padded with
    zeros), every chunk 4-byte aligned."""
    document += b" " * (-len(document) % 4)
    binary += b"\0" * (-len(binary) % 4)
    length = 12 + 8 + len(document) + 8 + len(binary)
    return b"".join([struct.pack("<4sII", b"glTF", 2, length),
                     struct.pack("<I4s", len(document), b"JSON"), document,
                     struct.pack("<I4s", len(binary), b"BIN\0"), binary])


def _number(value: float) -> str:
    """A coordinate with up to 9 decimals, no trailing zeros, no '-0'."""
    text = f"{value:.9f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text
