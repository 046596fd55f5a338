"""Durability and stability verdicts (contract section 3, paper sections 5.1 and 6.2).

Per nail, with t the edge plank's thickness and F, M the joint wrench in the joint frame
(n = nail axis, F_n > 0 pressing the planks together, y = the joint line):

    pull  = (2 |M_y| / t - F_n) / nails        (paper eq. 4)
    shear = sqrt(F_x^2 + F_y^2) / nails          (paper eq. 5)

A joint is durable iff pull <= nail_pull / safety_factor and shear <= nail_shear /
safety_factor.  Stability comes from the statics: 'lift-off' and 'sliding' cases.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase
from furncheck.geometry import Geometry, Joint
from furncheck.result import CaseResult, ContactResult, JointResult, Violation
from furncheck.statics import CaseStatics, StaticsModel


@dataclass(frozen=True)
class NailForces:
    """Per-nail forces of one joint, N."""

    pull: float
    shear: float
    pull_capacity: float
    shear_capacity: float

    @property
    def utilization(self) -> float:
        """max(pull / pull capacity, shear / shear capacity); > 1 means the joint fails."""
        return max(self.pull / self.pull_capacity, self.shear / self.shear_capacity)

    @property
    def durable(self) -> bool:
        return bool(within_capacity(self.pull, self.shear, self.pull_capacity,
                                    self.shear_capacity))


def within_capacity(pull, shear, pull_capacity: float, shear_capacity: float):
    """Whether per-nail pull and shear (N; floats or arrays) are within their capacities,
    up to the relative slack CAPACITY_REL_TOL: the durability verdict of a joint."""
    slack = 1.0 + tol.CAPACITY_REL_TOL
    return (pull <= pull_capacity * slack) & (shear <= shear_capacity * slack)


def nail_pull_shear(joints: list[Joint], wrenches: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per-nail pull and shear (N) of many joints; wrenches (nJ, 6) first plank on second
    (or (k, nJ, 6): k sets of them at once, e.g. one per load case).

    The wrench is turned into the face plank's action on the edge plank and expressed in
    the joint frame (x edge thickness normal, y joint line, n nail axis):
    pull = (2 |M_y| / t - F_n) / nails, shear = |(F_x, F_y)| / nails.
    """
    if not joints:
        return np.zeros(wrenches.shape[:-1]), np.zeros(wrenches.shape[:-1])
    frames = np.stack([j.frame for j in joints])                       # (nJ, 3, 3)
    sign = np.array([1.0 if j.planks[0] == j.face else -1.0 for j in joints])[:, None]
    force = np.einsum("jab,...ja->...jb", frames, sign * wrenches[..., :3])   # frame^T F
    moment_y = np.einsum("ja,...ja->...j", frames[:, :, 1], sign * wrenches[..., 3:])
    thickness = np.array([j.edge_thickness for j in joints])
    nails = np.array([j.nails for j in joints], dtype=float)
    pull = (2.0 * np.abs(moment_y) / thickness - force[..., 2]) / nails
    shear = np.hypot(force[..., 0], force[..., 1]) / nails
    return pull, shear


def evaluate_case(design: Design, geometry: Geometry, model: StaticsModel, case: LoadCase,
                  statics: CaseStatics) -> tuple[CaseResult, list[Violation]]:
    """Turn one case's statics into its CaseResult and violations.

    A case that topples ('lift-off') reports its joints as if the design were bolted down;
    those wrenches are shown but raise no 'non-durable' violation: the toppling comes first.
    """
    scale = design.unit_scale
    joints, violations = [], []
    pull_cap = design.material.nail_pull / design.safety_factor
    shear_cap = design.material.nail_shear / design.safety_factor
    if statics.joint_wrenches is not None:
        model_joints = [geometry.joints[j] for j in model.joints]
        pulls, shears = nail_pull_shear(model_joints, statics.joint_wrenches)
        for joint, wrench, pull, shear in zip(model_joints, statics.joint_wrenches.tolist(),
                                              pulls.tolist(), shears.tolist()):
            nails = NailForces(pull, shear, pull_cap, shear_cap)
            joints.append(JointResult(
                planks=joint.planks, point=_tuple(joint.point / scale), nails=joint.nails,
                force=tuple(wrench[:3]), moment=tuple(wrench[3:]), pull=pull, shear=shear,
                pull_capacity=pull_cap, shear_capacity=shear_cap,
                utilization=nails.utilization, durable=nails.durable))
            if not nails.durable and statics.stability in ("stable", "sliding"):
                violations.append(Violation("non-durable", joint.name, case.name,
                                            _durability_message(nails, design),
                                            _joint_line(design, joint)))
    contacts = []
    if statics.contact_forces is not None:
        points = (model.contact_points / scale).tolist()
        for row, (point, force) in enumerate(zip(points, statics.contact_forces.tolist())):
            plank = geometry.contacts[model.contacts[row]].plank
            contacts.append(ContactResult(plank, tuple(point), tuple(force)))
    stable = statics.stability == "stable"
    if not stable:
        kind = "sliding" if statics.stability == "sliding" else "lift-off"
        where = ",".join(statics.culprits) or ",".join(design.planks[i].id for i in model.planks)
        violations.append(Violation(kind, where, case.name, statics.detail,
                                    design.line_of(_case_key(design, case))))
    result = CaseResult(case.name, all(j.durable for j in joints), stable, tuple(joints),
                        tuple(contacts), statics.stability)
    return result, violations


def case_holds(design: Design, geometry: Geometry, model: StaticsModel,
               statics: CaseStatics) -> bool:
    """Whether a case has no violation: ``not evaluate_case(...)[1]`` without building its
    result (for searches that only need the verdict).  A case holds iff it is stable and
    every joint is durable (a sliding case is a violation whatever its joints do)."""
    return case_margin(design, geometry, model, statics)[1]


def case_margin(design: Design, geometry: Geometry, model: StaticsModel,
                statics: CaseStatics) -> tuple[float, bool]:
    """(smallest 1 - utilization of the case's joints (1.0 without joints; -inf when the
    case is not stable), whether the case holds), without building its result."""
    if statics.stability != "stable":
        return -np.inf, False
    if statics.joint_wrenches is None or not model.joints:
        return 1.0, True
    utilization, holds = joint_utilization(design, geometry, model, statics.joint_wrenches)
    return 1.0 - float(utilization.max()), bool(np.all(holds))


def joint_utilization(design: Design, geometry: Geometry, model: StaticsModel,
                      wrenches: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per model joint, for its wrenches in a solved case ((nJ, 6), or (k, nJ, 6) for k
    cases): max(pull / pull capacity, shear / shear capacity), and whether it is within
    capacity (``within_capacity``)."""
    pulls, shears = nail_pull_shear([geometry.joints[j] for j in model.joints], wrenches)
    pull_cap = design.material.nail_pull / design.safety_factor
    shear_cap = design.material.nail_shear / design.safety_factor
    return (np.maximum(pulls / pull_cap, shears / shear_cap),
            within_capacity(pulls, shears, pull_cap, shear_cap))


def _durability_message(nails: NailForces, design: Design) -> str:
    parts = []
    factor = ("" if design.safety_factor == 1.0
              else f" (capacity / safety factor {design.safety_factor:g})")
    if nails.pull > nails.pull_capacity:
        parts.append(f"pull {nails.pull:.4g} N per nail exceeds {nails.pull_capacity:.4g} N")
    if nails.shear > nails.shear_capacity:
        parts.append(f"shear {nails.shear:.4g} N per nail exceeds {nails.shear_capacity:.4g} N")
    return "; ".join(parts) + factor


def _joint_line(design: Design, joint: Joint) -> int | None:
    """Source line of a listed joint, or of the edge plank of a detected one."""
    if joint.key:
        return design.line_of(joint.key)
    return design.line_of(f"planks[{design.plank_index[joint.edge]}]")


def _case_key(design: Design, case: LoadCase) -> str:
    return "loads" if case.name == "default" and "loads" in design.lines \
        else f"load_cases.{case.name}"


def _tuple(values: np.ndarray) -> tuple[float, float, float]:
    return tuple(np.asarray(values, dtype=float).tolist())
