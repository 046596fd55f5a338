"""Mirror symmetry of a design and symmetric edits of its mirror planks.

A *mirror plane* is a vertical plane through the centre of the design's bounding box,
normal to world x or y, about which at least one plank is the mirror image of another
(``MirrorPlane.partner``: every plank mirrored by the plane, to its image; a plank lying
across the plane is its own image).  Two planks are mirror images when every mirrored
corner of one lies within MIRROR_TOLERANCE_FACTOR x the design's tolerance of a corner
of the other (so their sizes, thicknesses and placements match).

A symmetric edit changes a mirror pair together, the image's DOF by the mirrored amount
(``mirrored_dof``): a move along the plane's normal the opposite way (the pair moves apart
or closer), along the plane the same way; a turn about the normal the same way, about
the other axes the opposite way (rotations are axial vectors); a size change the same,
of the image's matching side.  ``symmetric_units`` turns the free DOFs of a ``Margins``
into such units (a pair's two DOFs as one direction) for ``candidates``; whether a
suggestion's design keeps the symmetry is measured on the design itself
(``broken_pairs``), with everything the geometric constraints changed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from furncheck.design.model import Design, Plank
from furncheck.dofs import Dof
from furncheck.tolerances import MIRROR_TOLERANCE_FACTOR

MIRROR_AXES = (0, 1)
"""World axes a mirror plane may be normal to (x and y: gravity is not mirrored)."""

_SIZE_AXIS_COSINE = 0.99
"""A plank's mirrored length axis matches its image's length (or width) axis when their
cosine is at least this."""


@dataclass(frozen=True)
class MirrorPlane:
    """A plane normal to world ``axis`` (0 x, 1 y) at ``offset`` (m) along it, and the
    planks it mirrors: ``partner`` maps each to its image (itself when it lies across)."""

    axis: int
    offset: float
    partner: dict[str, str]

    @property
    def pairs(self) -> list[tuple[str, str]]:
        """The mirror pairs of two different planks, each once (design order kept by the
        caller's dict order)."""
        return [(a, b) for a, b in self.partner.items() if a < b]

    def covers(self, design: Design) -> bool:
        """Whether every plank of ``design`` has its image: the design is symmetric."""
        return len(self.partner) == len(design.planks)


def mirror_planes(design: Design) -> tuple[MirrorPlane, ...]:
    """The design's mirror planes with at least one mirror pair of two planks."""
    corners = np.vstack([p.corners for p in design.planks])
    middle = 0.5 * (corners.min(axis=0) + corners.max(axis=0))
    slack = MIRROR_TOLERANCE_FACTOR * design.tolerance
    planes = []
    for axis in MIRROR_AXES:
        partner = _partners(design.planks, axis, float(middle[axis]), slack)
        if any(a != b for a, b in partner.items()):
            planes.append(MirrorPlane(axis, float(middle[axis]), partner))
    return tuple(planes)


def broken_pairs(design: Design, planes: tuple[MirrorPlane, ...],
                 original: frozenset[str] = frozenset()) -> int:
    """How many of the planes' mirror relations (pairs, and planks that were their own
    image) ``design`` no longer has about the same planes, plus the planks it adds (those
    not in ``original``, the input's plank ids) that have no image about a plane among
    the added planks and are not their own: 0 for a symmetric edit (a support at one end
    of a symmetric bench breaks its symmetry as much as moving one of its legs)."""
    slack = MIRROR_TOLERANCE_FACTOR * design.tolerance
    broken = 0
    added = [plank for plank in design.planks if original and plank.id not in original]
    for plane in planes:
        for a, b in plane.partner.items():
            if a > b or a not in design.plank_index or b not in design.plank_index:
                continue
            if not _mirrored(design.plank(a), design.plank(b), plane.axis, plane.offset,
                             slack):
                broken += 1
        broken += sum(not any(_mirrored(plank, other, plane.axis, plane.offset, slack)
                              for other in added) for plank in added)
    return broken


def mirrored_dof(design: Design, plane: MirrorPlane, dof: Dof) -> tuple[Dof, float] | None:
    """The image's DOF that mirrors ``dof`` about ``plane`` and the sign of its change
    (+1 the same, -1 the opposite), or None when the plank has no image or its size
    axis matches no side of the image."""
    image = plane.partner.get(dof.plank)
    if image is None:
        return None
    if dof.kind in ("x", "y", "z"):
        return Dof(image, dof.kind), -1.0 if "xyz".index(dof.kind) == plane.axis else 1.0
    if dof.kind in ("rx", "ry", "rz"):
        return Dof(image, dof.kind), 1.0 if "xyz".index(dof.kind[1]) == plane.axis else -1.0
    side = 0 if dof.kind == "length" else 1
    mirrored = design.plank(dof.plank).rotation_matrix[:, side].copy()
    mirrored[plane.axis] *= -1.0
    axes = design.plank(image).rotation_matrix
    for other, kind in ((0, "length"), (1, "width")):
        if abs(float(mirrored @ axes[:, other])) >= _SIZE_AXIS_COSINE:
            return Dof(image, kind), 1.0
    return None


@dataclass(frozen=True)
class Unit:
    """A direction of one or two free DOFs (indices into ``Margins.dofs``) with unit
    coefficients: a mirror pair's symmetric change, or one DOF of a plank that is its own
    image."""

    dofs: tuple[int, ...]
    coefficients: tuple[float, ...]


def symmetric_units(design: Design, planes: tuple[MirrorPlane, ...],
                    dofs: list[Dof]) -> list[Unit]:
    """Per plane: every mirror pair's symmetric changes (each DOF of the first plank with
    its image's mirrored DOF, both free) and every DOF of a plank on the plane that its
    mirror keeps (a move along the plane, a turn about its normal, a size change);
    each unit once, in DOF order."""
    index = {dof: i for i, dof in enumerate(dofs)}
    units: dict[tuple[int, ...], Unit] = {}
    for plane in planes:
        for i, dof in enumerate(dofs):
            found = mirrored_dof(design, plane, dof)
            if found is None or found[0] not in index:
                continue
            image, sign = found
            j = index[image]
            if i == j:
                if sign > 0.0:
                    units.setdefault((i,), Unit((i,), (1.0,)))
                continue
            if i < j:
                root = 1.0 / math.sqrt(2.0)
                units.setdefault((i, j), Unit((i, j), (root, sign * root)))
    return [units[key] for key in sorted(units)]


def _partners(planks: tuple[Plank, ...], axis: int, offset: float,
              slack: float) -> dict[str, str]:
    """Plank id -> its image about the plane (only planks that have one).  A box's
    centre is the mean of its corners, so an image's centre is the mirrored centre:
    only planks whose centres match are compared corner by corner."""
    centers = np.array([p.center for p in planks])
    mirrored = centers.copy()
    mirrored[:, axis] = 2.0 * offset - mirrored[:, axis]
    partner: dict[str, str] = {}
    for i, j in _near_pairs(mirrored, centers, slack):
        a, b = planks[int(i)], planks[int(j)]
        if a.id not in partner and _mirrored(a, b, axis, offset, slack):
            partner[a.id] = b.id
    return partner


def _near_pairs(points: np.ndarray, others: np.ndarray, slack: float) -> np.ndarray:
    """(P, 2) pairs (i, j), row-major, with |points[i] - others[j]| <= slack: the pairs of
    the all-pairs comparison, found through a k-d tree of ``others`` (a little wider, as
    candidates) and then that same comparison on the candidates, so that a big design
    makes no n x n array."""
    from scipy.spatial import cKDTree

    found = cKDTree(others).query_ball_point(points, r=slack * (1.0 + 1e-6) + 1e-12)
    i = np.repeat(np.arange(len(points)), [len(js) for js in found])
    j = np.array([k for js in found for k in sorted(js)], dtype=int)
    keep = np.linalg.norm(points[i] - others[j], axis=1) <= slack
    return np.column_stack([i[keep], j[keep]]).astype(int).reshape(-1, 2)


def _mirrored(a: Plank, b: Plank, axis: int, offset: float, slack: float) -> bool:
    """Whether plank ``b`` is the mirror image of ``a`` about the plane normal to world
    ``axis`` at ``offset``: every mirrored corner of ``a`` within ``slack`` of one of
    ``b``'s (boxes of the same size and place then)."""
    if abs(a.thickness - b.thickness) > slack:
        return False
    image = a.corners.copy()
    image[:, axis] = 2.0 * offset - image[:, axis]
    distance = np.linalg.norm(image[:, None, :] - b.corners[None, :, :], axis=2)
    return bool(np.all(distance.min(axis=1) <= slack))
