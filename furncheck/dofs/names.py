"""The design DOFs by name (``<plank>.<kind>``), their values, and the two ways a change
can be refused: ``Blocked`` (the DOF cannot move at all) and ``OutOfReach`` (this step
cannot be made)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck.design.model import Design
from furncheck.errors import DofError

DOF_KINDS = ("x", "y", "z", "rx", "ry", "rz", "length", "width")
AXIS = {"x": 0, "y": 1, "z": 2, "rx": 0, "ry": 1, "rz": 2}
"""The world axis of each translation and rotation kind."""


@dataclass(frozen=True)
class Dof:
    """One design DOF: a plank id and one of DOF_KINDS."""

    plank: str
    kind: str

    @property
    def name(self) -> str:
        return f"{self.plank}.{self.kind}"

    @property
    def is_rotation(self) -> bool:
        return self.kind in ("rx", "ry", "rz")

    def unit(self, design: Design) -> str:
        return "deg" if self.is_rotation else design.units


class Blocked(Exception):
    """The DOF cannot change at all without breaking a joint or a ground contact."""

    def __init__(self, reason: str):
        self.reason = reason
        super().__init__(reason)


class OutOfReach(Exception):
    """This particular step cannot be made (the DOF itself can move by smaller steps)."""


def parse_dof(design: Design, name: str) -> Dof:
    """``'shelf.length'`` -> Dof; plank ids may contain dots, the kind is the last part."""
    plank, dot, kind = name.rpartition(".")
    if not dot or not plank:
        raise DofError(name, f"a DOF is <plank>.<{'|'.join(DOF_KINDS)}>")
    if kind not in DOF_KINDS:
        raise DofError(name, f"unknown DOF kind {kind!r}; expected one of "
                             f"{', '.join(DOF_KINDS)}")
    if plank not in design.plank_index:
        raise DofError(name, f"no plank {plank!r} in {design.name} (planks: "
                             f"{', '.join(p.id for p in design.planks)})")
    return Dof(plank, kind)


def design_size(design: Design) -> float:
    """The largest bounding-box edge of the design, in its file unit: the scale of the
    translation and length DOFs (the paper makes them dimensionless by it)."""
    corners = np.vstack([p.corners for p in design.planks])
    return float((corners.max(axis=0) - corners.min(axis=0)).max()) / design.unit_scale


def all_dofs(design: Design) -> list[Dof]:
    """Every DOF of the design, plank by plank in file order."""
    return [Dof(p.id, kind) for p in design.planks for kind in DOF_KINDS]


def dof_value(design: Design, dof: Dof) -> float:
    """The DOF's current absolute value: file length unit or degrees."""
    plank = design.plank(dof.plank)
    if dof.kind in ("x", "y", "z"):
        return plank.center[AXIS[dof.kind]] / design.unit_scale
    if dof.is_rotation:
        return float(plank.rotation[AXIS[dof.kind]])
    size = plank.length if dof.kind == "length" else plank.width
    return size / design.unit_scale

