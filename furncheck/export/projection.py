"""The fixed oblique view of every picture: planks as shaded, depth-sorted faces.

The camera looks at the design from the front right and above, along -VIEW (VIEW points
from the design toward the viewer: azimuth AZIMUTH_DEG from the front, -y, toward +x;
elevation ELEVATION_DEG above the floor), with parallel rays (an axonometric view, so
equal lengths look equal wherever they are).  A world point p is drawn at (p . RIGHT,
p . UP) and lies at depth p . VIEW (larger: nearer).

Planks are drawn far to near (the painter's algorithm), each with the box faces that
face the viewer (a box is convex: those never hide each other).  Which of two planks is
in front is decided by a plane separating them (``behind``): for boxes that do not cut
into each other one of their six face planes does, except where only an edge of each
touches the other; where none is found, the nearer centre is in front.  The order is a
topological sort of "is behind", farthest first among the planks free to go.  A face is
lit by its angle to LIGHT (Lambert, plus an ambient share), so the three visible sides of
a plank read as a solid.  Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from furncheck.design.model import Plank

AZIMUTH_DEG = 35.0
ELEVATION_DEG = 24.0
_AZ, _EL = math.radians(AZIMUTH_DEG), math.radians(ELEVATION_DEG)
VIEW = np.array([math.cos(_EL) * math.sin(_AZ), -math.cos(_EL) * math.cos(_AZ), math.sin(_EL)])
"""Unit vector from the design toward the viewer."""
RIGHT = np.array([math.cos(_AZ), math.sin(_AZ), 0.0])
"""Unit vector of the picture's x axis (horizontal)."""
UP = np.cross(VIEW, RIGHT)
"""Unit vector of the picture's y axis (world z leans toward it)."""
LIGHT = np.array([-0.35, -0.55, 0.76]) / np.linalg.norm([-0.35, -0.55, 0.76])
"""Unit vector toward the light: above, front left."""
AMBIENT = 0.55
"""Share of a face's colour it keeps in no light; the rest grows with cos(face, LIGHT)."""

BOX_QUADS = np.array([
    [0, 2, 3, 1], [4, 5, 7, 6],      # -z, +z   (corner order of ``Plank.corners``)
    [0, 1, 5, 4], [2, 6, 7, 3],      # -y, +y
    [0, 4, 6, 2], [1, 3, 7, 5],      # -x, +x
])
"""(6, 4) int: the faces of a box as quads over the corners."""
QUAD_AXIS = np.array([2, 2, 1, 1, 0, 0])
QUAD_SIGN = np.array([-1.0, 1.0, -1.0, 1.0, -1.0, 1.0])
"""Each face's outward normal: sign x the plank's local axis QUAD_AXIS."""


BOX_EDGES = tuple((a, b) for a in range(8) for b in range(a + 1, 8)
                  if bin(a ^ b).count("1") == 1)
"""The 12 edges of a box by its corners (``Plank.corners``' order: the corner's index
bits are its signs along the local x, y and z: an edge joins two that differ in one)."""


def project(points: np.ndarray) -> np.ndarray:
    """(..., 2): picture coordinates of world points (..., 3), in their unit."""
    points = np.asarray(points, dtype=float)
    return np.stack([points @ RIGHT, points @ UP], axis=-1)


def plank_faces(planks: list[Plank] | tuple[Plank, ...], unit_scale: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every box face of the planks: ((6 n, 4, 3) corners in file units, (6 n, 3) outward
    unit normals, (6 n,) plank index)."""
    if not planks:
        return np.zeros((0, 4, 3)), np.zeros((0, 3)), np.zeros(0, dtype=int)
    corners = np.stack([plank.corners for plank in planks]) / unit_scale   # (n, 8, 3)
    axes = np.stack([plank.rotation_matrix for plank in planks])          # columns: x, y, z
    faces = corners[:, BOX_QUADS]                                          # (n, 6, 4, 3)
    normals = np.transpose(axes, (0, 2, 1))[:, QUAD_AXIS] * QUAD_SIGN[None, :, None]
    index = np.repeat(np.arange(len(planks)), 6)
    return faces.reshape(-1, 4, 3), normals.reshape(-1, 3), index


def visible_order(planks, unit_scale: float, normals: np.ndarray,
                  slack: float = 0.0) -> np.ndarray:
    """Indices into ``plank_faces`` of the faces that face the viewer, planks far to near
    (``plank_order``), each plank's faces together."""
    facing = normals @ VIEW > 1e-9
    return np.concatenate([[6 * k + f for f in range(6) if facing[6 * k + f]]
                           for k in plank_order(planks, unit_scale, slack)]
                          or [np.zeros(0)]).astype(int)


def plank_order(planks, unit_scale: float, slack: float = 0.0) -> list[int]:
    """Plank indices in drawing order, far to near (module docstring); ``slack``: how far
    (file unit) planks may overlap and still count as separated (the design's
    tolerance)."""
    count = len(planks)
    corners = np.stack([plank.corners for plank in planks]) / unit_scale if count else \
        np.zeros((0, 8, 3))
    axes = [plank.rotation_matrix.T for plank in planks]
    depth = (corners.mean(axis=1) @ VIEW).tolist()
    outline = project(corners)                                  # (n, 8, 2)
    low, high = outline.min(axis=1), outline.max(axis=1)
    overlap = np.all((high[:, None] >= low[None]) & (high[None] >= low[:, None]), axis=2)
    behind: list[set[int]] = [set() for _ in range(count)]     # i: the planks behind i
    for i, j in zip(*np.nonzero(np.triu(overlap, 1))):
        i, j = int(i), int(j)
        order = _separated(corners[i], corners[j], np.vstack([axes[i], axes[j]]), slack)
        if order is None:
            order = 1 if depth[i] < depth[j] else -1 if depth[i] > depth[j] else 0
        if order > 0:
            behind[j].add(i)
        elif order < 0:
            behind[i].add(j)
    drawn: list[int] = []
    done = [False] * count
    while len(drawn) < count:
        free = [k for k in range(count) if not done[k] and all(done[b] for b in behind[k])]
        pool = free or [k for k in range(count) if not done[k]]      # a cycle: break it
        pick = min(pool, key=lambda k: (depth[k], k))
        done[pick] = True
        drawn.append(pick)
    return drawn


def _separated(one: np.ndarray, other: np.ndarray, axes: np.ndarray,
               slack: float) -> int | None:
    """+1 when box ``one`` is behind ``other`` (a plane normal to one of ``axes``
    separates them and ``other`` is on the viewer's side), -1 when in front, 0 when a
    separating plane runs along the line of sight (neither hides the other), None when
    no axis separates them."""
    a, b = axes @ one.T, axes @ other.T                           # (6, 8) each
    below = a.max(axis=1) <= b.min(axis=1) + slack
    above = b.max(axis=1) <= a.min(axis=1) + slack
    for k in np.flatnonzero(below | above):
        toward = float(axes[k] @ VIEW)
        if abs(toward) < 1e-9:
            return 0
        sign = 1 if below[k] else -1
        return sign if toward > 0 else -sign
    return None


def shaded(colours: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """(n, 3) colours lit by LIGHT for faces with (n, 3) unit normals."""
    light = AMBIENT + (1.0 - AMBIENT) * np.clip(normals @ LIGHT, 0.0, 1.0)
    return np.clip(colours * light[:, None], 0.0, 1.0)


def box_edges(plank, unit_scale: float) -> np.ndarray:
    """(12, 2, 2): the plank's box edges (``BOX_EDGES``) in the view, each from one corner
    to the other, file unit (``unit_scale`` m each)."""
    return project(plank.corners / unit_scale)[np.array(BOX_EDGES)]
