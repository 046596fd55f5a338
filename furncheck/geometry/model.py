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


@dataclass(frozen=True)
class Contact:
    """A plank corner touching the ground; ``point`` (3,) m lies on z = 0.

    corner : index of the corner in ``Plank.corners`` (identifies the contact across edits)
    """

    plank: str
    point: np.ndarray
    corner: int = 0


@dataclass(frozen=True)
class NearMiss:
    """A joint or ground contact that the planks miss by more than the tolerance but at
    most ``NEAR_MISS_FACTOR`` times it (``furncheck.geometry.near``).

    planks   : (face, edge) plank ids of a missed joint, named as the joint would be;
               (plank,) of a missed ground contact
    distance : m, the gap between the end face and the face (or the floor), > 0; for a
               joint < 0 when the end face cuts into the face (an overlap)
    """

    planks: tuple[str, ...]
    distance: float

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

    @property
    def stands(self) -> bool:
        """Whether the design stands as it is drawn: every group of planks reaches the
        ground and no joint or ground contact is missed narrowly.  Only then are its
        statics solved (``check.check_design``): the forces of a design whose leg is 4 mm
        short describe a piece nobody meant to build."""
        return all(self.grounded) and not self.near_misses
