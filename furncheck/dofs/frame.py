"""The constraint structure of a design (paper 6.1): per plank, the ends that must stay
where they are (on a face plank, the ground or a wall), the planks whose ends rest on its
faces, and what it lies flat on."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from furncheck.design.model import CORNER_SIGNS, Design, Vec3
from furncheck.geometry import Geometry

if TYPE_CHECKING:
    from furncheck.dofs.apply import TurnStart

@dataclass(frozen=True)
class End:
    """A plank end that must stay where it is: a narrow face (axis 0/1, sign +-1) resting
    on the face plank ``on`` (a plank id), or on the ground or a wall (``on`` = None;
    ``wall`` its index and ``plane`` a point of it, None for the ground)."""

    axis: int
    sign: int
    on: str | None
    normal: np.ndarray      # unit normal of the supporting face, pointing at this plank
    wall: int | None = None
    plane: Vec3 | None = None

    @property
    def support(self) -> str:
        """What holds the end, for messages: a plank id, 'the ground' or 'wall n'."""
        if self.on is not None:
            return self.on
        return "the ground" if self.wall is None else f"wall {self.wall}"

    @cached_property
    def normal_xyz(self) -> Vec3:
        """``normal`` as a tuple of floats (for the scalar arithmetic of ``apply_dof``)."""
        x, y, z = self.normal.tolist()
        return x, y, z


@dataclass(frozen=True)
class Structure:
    """Per plank: its held ends, the planks whose ends rest on its faces, its ground."""

    ends: dict[str, tuple[End, ...]]
    attached: dict[str, tuple[tuple[str, End], ...]]   # plank -> (edge plank, its end)
    lies_flat: dict[str, tuple[Vec3, ...]]   # plank -> normals of what it lies flat on
    joint_count: dict[str, int]

    @cached_property
    def free(self) -> frozenset[str]:
        """Planks held by one joint only and not standing or lying on the ground: they may
        simply move along with the plank they are jointed to."""
        return frozenset(plank for plank, count in self.joint_count.items()
                         if count == 1 and plank not in self.lies_flat
                         and not any(end.on is None for end in self.ends[plank]))

    @cached_property
    def turn_starts(self) -> dict[str, TurnStart]:
        """plank id -> the angle-independent part of its last turn (``apply._turn_start``): a
        cache, filled by ``apply_dof``."""
        return {}


def structure(design: Design, geometry: Geometry) -> Structure:
    """The held ends and attachments of every plank, from its joints (nailed or resting)
    and ground contacts."""
    ends: dict[str, list[End]] = {p.id: [] for p in design.planks}
    attached: dict[str, list[tuple[str, End]]] = {p.id: [] for p in design.planks}
    joint_count = {p.id: 0 for p in design.planks}
    for joint in geometry.joints:
        end = End(joint.edge_face[0], joint.edge_face[1], joint.face, joint.frame[:, 2].copy())
        ends[joint.edge].append(end)
        attached[joint.face].append((joint.edge, end))
        joint_count[joint.edge] += 1
        joint_count[joint.face] += 1
    for contact in geometry.contacts:     # a resting joint holds its end like a nailed one
        if contact.on is None or contact.corner != 0:
            continue
        normal = np.asarray(contact.frame[2], dtype=float)   # into the edge plank
        axes = design.plank(contact.plank).rotation_matrix
        along = [float(axes[:, a] @ normal) for a in (0, 1)]
        axis = int(np.argmax(np.abs(along)))
        end = End(axis, -1 if along[axis] > 0.0 else 1, contact.on, normal.copy())
        ends[contact.plank].append(end)
        attached[contact.on].append((contact.plank, end))
        joint_count[contact.plank] += 1
        joint_count[contact.on] += 1
    corners: dict[str, dict[int | None, set[int]]] = {}     # plank -> support -> corners
    for contact in geometry.contacts:
        if contact.anchor is None and contact.on is None:   # nor an anchor, nor a rest
            corners.setdefault(contact.plank, {}).setdefault(contact.wall, set()).add(
                contact.corner)
    flat: dict[str, list[Vec3]] = {}
    for plank in design.planks:
        for wall, touching in corners.get(plank.id, {}).items():
            normal = (0.0, 0.0, 1.0) if wall is None else design.walls[wall].normal
            plane = None if wall is None else design.walls[wall].point
            signs = CORNER_SIGNS[sorted(touching)]
            for axis in (0, 1):
                if np.all(signs[:, axis] == signs[0, axis]):
                    ends[plank.id].append(End(axis, int(signs[0, axis]), None,
                                              np.array(normal, dtype=float), wall, plane))
                    break
            else:
                flat.setdefault(plank.id, []).append(normal)
    return Structure({k: tuple(v) for k, v in ends.items()},
                     {k: tuple(v) for k, v in attached.items()},
                     {k: tuple(v) for k, v in flat.items()}, joint_count)

