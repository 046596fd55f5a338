"""Independent geometry checks for the bundled catalog (``designs/``).

A second, deliberately simple implementation of contract section 2, used while building the
catalog and by ``test_catalog.py``: it reads a design file as plain YAML/JSON and, with numpy
only (no furncheck import), lists

* every *touch*: a narrow face of plank A lying on a broad face of plank B (faces opposed
  within 60 degrees, nearest corner within the tolerance of B's face plane and not deeper,
  the projection overlapping B's face with positive area) -- the joints the checker should
  detect;
* every pair of planks whose boxes interpenetrate deeper than the tolerance (separating-axis
  test on the boxes shrunk by the tolerance) -- which a furniture design must never have;
* each plank's lowest corner and its ground-contact corners (|z| <= tolerance).

Run it on files while editing them::

    python tests/catalog_tools.py designs/stool.yaml [more files...]

Lengths are in the design file's unit throughout (mm for the whole catalog).
"""

from __future__ import annotations

import json
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml

DEFAULT_THICKNESS_MM = 12.0
DEFAULT_TOLERANCE_MM = 0.5
COS_MAX_TILT = float(np.cos(np.radians(60.0)))
MIN_AREA = 1e-6          # (file unit)^2: a touching region smaller than this is no joint


def rotation_matrix(rotation_deg) -> np.ndarray:
    """R = Rz @ Ry @ Rx; columns are the plank's local x, y, z axes in world coordinates."""
    rx, ry, rz = np.radians(np.asarray(rotation_deg, dtype=float))
    r_x = np.array([[1, 0, 0], [0, np.cos(rx), -np.sin(rx)], [0, np.sin(rx), np.cos(rx)]])
    r_y = np.array([[np.cos(ry), 0, np.sin(ry)], [0, 1, 0], [-np.sin(ry), 0, np.cos(ry)]])
    r_z = np.array([[np.cos(rz), -np.sin(rz), 0], [np.sin(rz), np.cos(rz), 0], [0, 0, 1]])
    return r_z @ r_y @ r_x


@dataclass(frozen=True)
class Box:
    """A plank as a box: centre (3,), rotation (3, 3) columns = local axes, half (3,)."""

    id: str
    center: np.ndarray
    rotation: np.ndarray
    half: np.ndarray

    @property
    def corners(self) -> np.ndarray:
        """(8, 3) world corners."""
        signs = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)], float)
        return self.center + (signs * self.half) @ self.rotation.T

    def face(self, axis: int, sign: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Face with outward normal sign * local axis: (normal (3,), centre (3,),
        corners (4, 3))."""
        normal = sign * self.rotation[:, axis]
        centre = self.center + normal * self.half[axis]
        u_axis, v_axis = [a for a in range(3) if a != axis]
        u = self.rotation[:, u_axis] * self.half[u_axis]
        v = self.rotation[:, v_axis] * self.half[v_axis]
        corners = np.array([centre + u + v, centre - u + v, centre - u - v, centre + u - v])
        return normal, centre, corners


@dataclass(frozen=True)
class Touch:
    """Narrow face ``edge_face`` of plank ``edge`` on a broad face of plank ``face``."""

    edge: str
    face: str
    edge_face: str       # '+x', '-x', '+y' or '-y' of the edge plank
    gap: float           # distance of the nearest corner from the face plane (< 0: inside)
    tilt_deg: float      # angle between the two faces
    area: float          # touching region, (file unit)^2
    length: float        # its extent along the edge face's long direction

    @property
    def nails(self) -> int:
        return max(1, int(np.floor(self.length / 20.0 * (1 + 1e-6))))


def load(path: str | Path) -> dict:
    """The design file as a plain dict."""
    text = Path(path).read_text()
    return json.loads(text) if str(path).endswith(".json") else yaml.safe_load(text)


def boxes(design: dict) -> list[Box]:
    """Every plank of a design dict as a Box (file length unit)."""
    thickness = float((design.get("material") or {}).get("thickness", DEFAULT_THICKNESS_MM))
    out = []
    for plank in design["planks"]:
        own = plank.get("material") or {}
        t = float(plank.get("thickness", own.get("thickness", thickness)))
        half = 0.5 * np.array([plank["size"][0], plank["size"][1], t], dtype=float)
        out.append(Box(plank["id"], np.asarray(plank["center"], float),
                       rotation_matrix(plank.get("rotation", [0, 0, 0])), half))
    return out


def tolerance(design: dict) -> float:
    return float(design.get("tolerance", DEFAULT_TOLERANCE_MM))


def _clip(polygon: list, hx: float, hy: float) -> list:
    """Sutherland-Hodgman clip of a convex polygon to |x| <= hx, |y| <= hy."""
    for axis, sign, limit in ((0, 1, hx), (0, -1, hx), (1, 1, hy), (1, -1, hy)):
        kept = []
        for k, cur in enumerate(polygon):
            prev = polygon[k - 1]
            cur_in, prev_in = sign * cur[axis] <= limit, sign * prev[axis] <= limit
            if cur_in != prev_in:
                t = (sign * limit - prev[axis]) / (cur[axis] - prev[axis])
                kept.append(prev + t * (cur - prev))
            if cur_in:
                kept.append(cur)
        polygon = kept
        if not polygon:
            return []
    return polygon


def _area(polygon: list) -> float:
    if len(polygon) < 3:
        return 0.0
    p = np.array(polygon)
    return 0.5 * abs(float(np.dot(p[:, 0], np.roll(p[:, 1], -1))
                           - np.dot(p[:, 1], np.roll(p[:, 0], -1))))


def touch(edge: Box, face: Box, tol: float) -> Touch | None:
    """The best narrow face of ``edge`` resting on a broad face of ``face``, or None."""
    best = None
    for axis, sign, label in ((0, 1, "+x"), (0, -1, "-x"), (1, 1, "+y"), (1, -1, "-y")):
        normal, _, corners = edge.face(axis, sign)
        long_axis = 1 - axis
        for fsign in (1, -1):
            fnormal, fcentre, _ = face.face(2, fsign)
            cos = -float(normal @ fnormal)
            if cos < COS_MAX_TILT:
                continue
            if float((edge.center - fcentre) @ fnormal) < 0:      # edge plank behind the face
                continue
            heights = (corners - fcentre) @ fnormal
            gap = float(heights.min())
            if gap > tol or gap < -tol:
                continue
            local = [np.array([(c - fcentre) @ face.rotation[:, 0],
                               (c - fcentre) @ face.rotation[:, 1]]) for c in corners]
            region = _clip(local, face.half[0], face.half[1])
            area = _area(region)
            if area <= MIN_AREA:
                continue
            along = edge.rotation[:, long_axis]
            along2 = np.array([along @ face.rotation[:, 0], along @ face.rotation[:, 1]])
            along2 /= np.linalg.norm(along2)
            extent = [float(p @ along2) for p in region]
            candidate = Touch(edge.id, face.id, label, gap,
                              float(np.degrees(np.arccos(min(1.0, cos)))), area,
                              max(extent) - min(extent))
            if best is None or (candidate.tilt_deg, -candidate.area) < (best.tilt_deg,
                                                                         -best.area):
                best = candidate
    return best


def touches(design: dict) -> list[Touch]:
    """Every plank pair's touch (either way round; both if both exist)."""
    planks, tol = boxes(design), tolerance(design)
    out = []
    for i, a in enumerate(planks):
        for b in planks[i + 1:]:
            for edge, face in ((a, b), (b, a)):
                found = touch(edge, face, tol)
                if found is not None:
                    out.append(found)
    return out


def interpenetration(a: Box, b: Box) -> float:
    """Depth (file unit) by which two boxes overlap along their least-overlap separating
    axis; <= 0 when they are apart or merely touch."""
    axes = [a.rotation[:, k] for k in range(3)] + [b.rotation[:, k] for k in range(3)]
    for i in range(3):
        for j in range(3):
            cross = np.cross(a.rotation[:, i], b.rotation[:, j])
            if np.linalg.norm(cross) > 1e-6:
                axes.append(cross / np.linalg.norm(cross))
    depth = np.inf
    ca, cb = a.corners, b.corners
    for axis in axes:
        pa, pb = ca @ axis, cb @ axis
        overlap = min(pa.max(), pb.max()) - max(pa.min(), pb.min())
        depth = min(depth, overlap)
    return float(depth)


def overlaps(design: dict) -> list[tuple[str, str, float]]:
    """Plank pairs interpenetrating deeper than the tolerance: (a, b, depth)."""
    planks, tol = boxes(design), tolerance(design)
    out = []
    for i, a in enumerate(planks):
        for b in planks[i + 1:]:
            depth = interpenetration(a, b)
            if depth > tol:
                out.append((a.id, b.id, depth))
    return out


def ground(design: dict) -> dict[str, tuple[float, int]]:
    """Per plank: (lowest corner z, number of corners with |z| <= tolerance)."""
    tol = tolerance(design)
    out = {}
    for box in boxes(design):
        z = box.corners[:, 2]
        out[box.id] = (float(z.min()), int(np.sum(np.abs(z) <= tol)))
    return out


def components(design: dict) -> list[set[str]]:
    """Groups of planks connected through touches."""
    ids = [p["id"] for p in design["planks"]]
    parent = {i: i for i in ids}

    def root(k):
        while parent[k] != k:
            k = parent[k]
        return k

    for t in touches(design):
        parent[root(t.edge)] = root(t.face)
    groups: dict[str, set[str]] = {}
    for i in ids:
        groups.setdefault(root(i), set()).add(i)
    return list(groups.values())


def mass_kg(design: dict) -> float:
    """Total self-weight mass, kg (mm designs; a plank's own density where it has one)."""
    density = float((design.get("material") or {}).get("density", 750.0))
    return sum(float((plank.get("material") or {}).get("density", density))
               * float(np.prod(2 * b.half)) * 1e-9
               for plank, b in zip(design["planks"], boxes(design)))


def centre_of_mass(design: dict) -> np.ndarray:
    """Self-weight centre of mass (file unit; a plank's own density where it has one)."""
    density = float((design.get("material") or {}).get("density", 750.0))
    masses = np.array([float((plank.get("material") or {}).get("density", density))
                       * np.prod(2 * b.half) for plank, b in zip(design["planks"], boxes(design))])
    centres = np.array([b.center for b in boxes(design)])
    return masses @ centres / masses.sum()


def describe(path: str | Path) -> str:
    """A readable summary of one file's geometry."""
    design = load(path)
    lines = [f"== {path}: {len(design['planks'])} planks, self-weight {mass_kg(design):.2f} kg, "
             f"centre of mass {np.round(centre_of_mass(design), 1).tolist()}"]
    found = touches(design)
    lines.append(f"touches ({len(found)}):")
    for t in found:
        lines.append(f"  {t.edge}{t.edge_face} on {t.face}: gap {t.gap:+.4f}, tilt "
                     f"{t.tilt_deg:.1f} deg, length {t.length:.1f} ({t.nails} nails)")
    bad = overlaps(design)
    lines.append("overlaps: " + (", ".join(f"{a}/{b} {d:.2f}" for a, b, d in bad) or "none"))
    lines.append("ground: " + ", ".join(f"{k} z>={z:.2f} ({n})" for k, (z, n) in
                                        ground(design).items() if z < 1.0))
    groups = components(design)
    if len(groups) > 1:
        lines.append("components: " + " | ".join(",".join(sorted(g)) for g in groups))
    return "\n".join(lines)


if __name__ == "__main__":
    for name in sys.argv[1:]:
        print(describe(name))
