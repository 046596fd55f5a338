"""The geometry's values: joints, ground contacts and what the statics needs of them."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.result import Violation

_COS_MAX_TILT = float(np.cos(np.radians(tol.JOINT_MAX_TILT_DEG)))
_GEOMETRY_EPS = 1e-9
"""m: numeric slack added to the design's tolerance (which may be zero)."""


@dataclass(frozen=True)
class Joint:
    """A nail joint.

    planks : (first, second) plank ids as listed (auto-detected: (face, edge))
    face, edge : the face plank and the edge plank
    point  : (3,) m, centroid of the touching region
    length : m, extent of the touching region along the joint line
    nails  : nail count
    frame  : (3, 3) world columns x (edge plank's thickness normal), y (joint line),
             n (face plank's normal pointing into the edge plank)
    edge_thickness : m, thickness t of the edge plank (the nail lever, contract section 3)
    edge_face : which narrow face of the edge plank rests on the face plank, as
             (local axis 0 = x / 1 = y, sign +1 / -1)
    face_side : which broad face of the face plank receives it (+1 = local +z, -1 = -z)
    key    : key path of the listed joint ('joints[2]'), '' when auto-detected
    """

    planks: tuple[str, str]
    face: str
    edge: str
    point: np.ndarray
    length: float
    nails: int
    frame: np.ndarray
    edge_thickness: float
    edge_face: tuple[int, int] = (0, 1)
    face_side: int = 1
    key: str = ""

    @property
    def name(self) -> str:
        return f"{self.planks[0]}/{self.planks[1]}"

    @property
    def listed(self) -> int | None:
        """Its index in ``Design.joints`` ('joints[2]' -> 2), None when auto-detected."""
        return int(self.key.split("[", 1)[1].rstrip("]")) if self.key else None


def nails_listed(design, joint: Joint) -> bool:
    """Whether the joint's nail count is given in the file (not from its length)."""
    return joint.listed is not None and design.joints is not None \
        and design.joints[joint.listed].nails is not None


@dataclass(frozen=True)
class Contact:
    """A plank corner touching the ground or a wall; ``point`` (3,) m lies on its plane
    (z = 0 for the ground).

    corner : index of the corner in ``Plank.corners`` (identifies the contact across edits)
    wall   : index into ``Design.walls``, None for the ground
    anchor : index into ``Design.anchors`` for an anchor's tie (``point`` its point on the
             plank, ``corner`` -1, ``wall`` its wall; it holds both ways, without friction
             limit), else None
    on     : for a corner of a resting joint (``type: rests``, contract section 2), the
             plank it rests on (``plank`` is the joint's edge plank, ``on`` its face plank;
             ``corner`` 0-3 the corner of their touching region, ``rest`` the joint's
             index in ``Design.joints``, ``frame`` rows t1, t2 and the face plank's normal
             n pointing into the edge plank: the contact's frame), else None
    """

    plank: str
    point: np.ndarray
    corner: int = 0
    wall: int | None = None
    anchor: int | None = None
    on: str | None = None
    rest: int | None = None
    frame: np.ndarray | None = None

    @property
    def on_floor(self) -> bool:
        """Whether it is a plank's corner on the floor: not a wall's contact, an anchor's
        tie or a resting joint's corner."""
        return self.wall is None and self.anchor is None and self.on is None

    @property
    def face_above(self) -> bool:
        """For a resting joint's corner: whether the face plank (``on``) lies on top of
        the edge plank (``plank``), its face looking down onto it; False otherwise."""
        return self.frame is not None and self.on is not None and self.frame[2][2] < 0.0

    @property
    def resting(self) -> tuple[str, str]:
        """For a resting joint's corner: (the plank that lies on the other, the other): the
        face plank first where its face looks down onto the edge plank (``face_above``)."""
        return (self.on, self.plank) if self.face_above else (self.plank, self.on)


def anchor_contacts(design) -> list[Contact]:
    """The design's anchors as contacts (see ``Contact.anchor``), in order."""
    return [Contact(anchor.plank, anchor_tie(design, i), -1, anchor.wall, i)
            for i, anchor in enumerate(design.anchors)]


def anchor_tie(design, index: int) -> np.ndarray:
    """(3,) m: where anchor ``index`` holds its plank: its ``at`` brought along the plank's
    face normal onto the plank's mid-plane.  A screw through a board bears on its hole over
    the board's whole thickness, so the shear it takes acts at mid-thickness, and it pulls
    along its own axis, so where along that axis ``at`` is drawn does not matter; a point
    drawn on the face against the wall would instead turn the board's bending into shear
    along the wall (its back face stretches and shortens as it bends: two screws in a
    bending cleat then pulled against each other, by more as ``at`` lay further from the
    mid-plane, and on the front face the other way)."""
    anchor = design.anchors[index]
    plank = design.planks[design.plank_index[anchor.plank]]
    point = np.asarray(anchor.point, dtype=float)
    normal = plank.rotation_matrix[:, 2]
    return point - float((point - plank.center_array) @ normal) * normal


def support_point(design, wall: int | None, corner: np.ndarray) -> np.ndarray:
    """A corner (3,) m brought onto its support's plane: z = 0 for the ground, along the
    normal onto wall ``wall``."""
    if wall is None:
        return np.array([corner[0], corner[1], 0.0])
    plane = design.walls[wall]
    return corner - plane.distance(corner) * np.asarray(plane.normal)


def corner_contacts(design, plank, slack: float) -> tuple[list[Contact], list[tuple]]:
    """The corners of ``plank`` within ``slack`` (m) of the ground (z) and of each wall
    (distance in front of it), ground first, then the walls in order, as contacts; and
    per support the plank sinks into by more than ``slack``: (wall or None, corner index,
    depth m)."""
    corners = plank.corners
    contacts, sunk = [], []
    heights = [(None, corners[:, 2])] + [(w, wall.distance(corners))
                                         for w, wall in enumerate(design.walls)]
    for wall, height in heights:
        for corner in np.nonzero(height <= slack)[0]:
            contacts.append(Contact(plank.id, support_point(design, wall, corners[corner]),
                                    int(corner), wall))
        if height.min() < -slack:
            deepest = int(np.argmin(height))
            sunk.append((wall, deepest, float(-height[deepest])))
    return contacts, sunk


@dataclass(frozen=True)
class NearMiss:
    """A joint or ground contact that the planks miss by more than the tolerance but at
    most ``NEAR_MISS_FACTOR`` times it (``furncheck.geometry.near``).

    planks   : (face, edge) plank ids of a missed joint, named as the joint would be;
               (plank,) of a missed ground contact
    distance : m, the gap between the end face and the face (or the floor), > 0; for a
               joint < 0 when the end face cuts into the face (an overlap)
    bearing  : m, for a joint whose end face lies on the face (within the tolerance) but
               over a band too narrow for nails (``tolerances.MIN_BEARING_SHARE``): that
               band's width across the joint line; None otherwise
    """

    planks: tuple[str, ...]
    distance: float
    bearing: float | None = None

    @property
    def name(self) -> str:
        return "/".join(self.planks)


@dataclass(frozen=True)
class Geometry:
    """What the statics needs, plus the geometric violations.

    components : plank indices of each jointed group, in order of their first plank
    grounded   : per component, whether any of its planks touches the ground
    near_misses : the joints and ground contacts missed narrowly (each also a violation)
    """

    joints: tuple[Joint, ...]
    contacts: tuple[Contact, ...]
    components: tuple[tuple[int, ...], ...]
    grounded: tuple[bool, ...]
    violations: tuple[Violation, ...]
    near_misses: tuple[NearMiss, ...] = ()

    def jointed(self) -> dict[str, list[str]]:
        """Plank id -> the planks jointed to it, in joint order (planks without joints
        left out)."""
        found: dict[str, list[str]] = {}
        for joint in self.joints:
            a, b = joint.planks
            found.setdefault(a, []).append(b)
            found.setdefault(b, []).append(a)
        return found

    @property
    def stands(self) -> bool:
        """Whether the design stands as it is drawn: every group of planks reaches the
        ground and no joint or ground contact is missed narrowly.  Only then are its
        statics solved (``check.check_design``): the forces of a design whose leg is 4 mm
        short describe a piece nobody meant to build."""
        return all(self.grounded) and not self.near_misses
