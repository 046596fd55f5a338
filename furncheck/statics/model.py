"""The load-independent statics model of a design, and the load vector of a case.

``StaticsModel`` (the joint deviation map G, joint compliances and contact maps of the
grounded components), ``CaseStatics`` (one case's result), ``build_model``,
``external_forces`` and the small rotation helpers they share.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase
from furncheck.geometry import Geometry

if TYPE_CHECKING:
    from furncheck.statics.condense import _Condensed

_SIX = np.arange(6)


@dataclass(frozen=True)
class StaticsModel:
    """The load-independent part of a design's statics.

    planks   : design plank indices taking part (those of grounded components)
    joints   : geometry joint indices taking part
    contacts : geometry contact indices taking part
    joint_planks, joint_blocks : (nJ, 2) local planks and (nJ, 2, 6, 6) signed blocks of
               the joint deviation map G (``G``: the same as a sparse (6 nJ, 6 nP) matrix)
    contact_maps : (nK, 3, 6) displacement of each contact point from its plank's q
    contact_plank : (nK,) local plank number of each contact
    contact_component : (nK,) component number of each contact
    components : local plank numbers of each grounded component
    """

    design: Design
    geometry: Geometry
    planks: tuple[int, ...]
    joints: tuple[int, ...]
    contacts: tuple[int, ...]
    joint_planks: np.ndarray
    joint_blocks: np.ndarray
    compliance: np.ndarray
    contact_maps: np.ndarray
    contact_plank: np.ndarray
    contact_points: np.ndarray
    contact_component: np.ndarray
    components: tuple[tuple[int, ...], ...]
    friction: float

    @property
    def n_dof(self) -> int:
        return 6 * len(self.planks)

    @cached_property
    def G(self) -> sp.csr_matrix:
        """(6 nJ, 6 nP) sparse joint deviation map, d = G q."""
        n_joints = len(self.joints)
        shape = (n_joints, 2, 6, 6)
        rows = np.broadcast_to(6 * np.arange(n_joints)[:, None, None, None]
                               + _SIX[None, None, :, None], shape).ravel()
        cols = np.broadcast_to(6 * self.joint_planks[:, :, None, None]
                               + _SIX[None, None, None, :], shape).ravel()
        return sp.csr_matrix((self.joint_blocks.ravel(), (rows, cols)),
                             shape=(6 * n_joints, self.n_dof))

    def deviations(self, q: np.ndarray) -> np.ndarray:
        """G q for plank displacements q, (6 nP,) or (6 nP, k), by blocks: per joint its
        (6, 12) rows of G times the 12 displacements of its two planks (one stacked
        matmul; two to five times faster than the same contraction by einsum)."""
        columns = q.reshape((len(self.planks), 6) + q.shape[1:])[self.joint_planks]
        columns = columns.reshape((len(self.joints), 12, math.prod(q.shape[1:])))  # (nJ, 12, k)
        return (self.joint_rows @ columns).reshape((-1,) + q.shape[1:])

    @cached_property
    def joint_rows(self) -> np.ndarray:
        """(nJ, 6, 12): each joint's rows of G, its first plank's columns then its second's."""
        return np.ascontiguousarray(np.transpose(self.joint_blocks, (0, 2, 1, 3))
                                    .reshape(-1, 6, 12))

    def reactions(self, h: np.ndarray) -> np.ndarray:
        """G^T h for joint values h, (6 nJ,) or (6 nJ, k), by blocks."""
        per_joint = np.einsum("jsab,ja...->jsb...", self.joint_blocks,
                              h.reshape((-1, 6) + h.shape[1:]))
        out = block_sums(self.joint_planks.ravel(), per_joint.reshape(2 * len(self.joints), -1),
                         len(self.planks))
        return out.reshape((-1,) + h.shape[1:])

    @cached_property
    def self_weight(self) -> np.ndarray:
        """(6 nP,) the planks' weights (N) as loads at their centres."""
        f = np.zeros(self.n_dof)
        f[2::6] = [-self.design.plank_mass(self.design.planks[i]) * tol.GRAVITY
                   for i in self.planks]
        return f

    @cached_property
    def node_points(self) -> np.ndarray:
        """(nP, 3) m: the point each six-displacement block q_k turns about (a rigid
        plank's centre)."""
        return np.array([self.design.planks[i].center_array for i in self.planks],
                        dtype=float).reshape(-1, 3)

    @cached_property
    def local_planks(self) -> dict[str, int]:
        """Plank id -> local plank number."""
        return {self.design.planks[i].id: k for k, i in enumerate(self.planks)}

    @cached_property
    def contact_gram(self) -> np.ndarray:
        """(nK, 6, 6) M^T M of each contact map: its anchor springs' stiffness per unit k."""
        maps = self.contact_maps
        return np.transpose(maps, (0, 2, 1)) @ maps

    @cached_property
    def rigid_grams(self) -> np.ndarray:
        """(nK, 6, 6) R^T R per contact, R its point's displacement under a rigid motion of
        its component (translation, and rotation x the spread of the component's contact
        points, about their mean): summed over a component's holding contacts, singular
        iff they cannot hold all six rigid motions (``contacts._ActiveSet._restrained``)."""
        grams = np.zeros((len(self.contacts), 6, 6))
        for c in range(len(self.components)):
            members = self.contact_component == c
            if not members.any():
                continue
            points = self.contact_points[members]
            arm = points - points.mean(axis=0)
            length = max(float(np.abs(arm).max()), 1e-6)
            rigid = np.zeros((len(points), 3, 6))
            rigid[:, :, :3] = np.eye(3)
            rigid[:, :, 3:] = -_skew_many(arm) / length
            grams[members] = np.transpose(rigid, (0, 2, 1)) @ rigid
        return grams

    @cached_property
    def restrained_states(self) -> dict:
        """Contact state -> whether its holding contacts restrain every component (filled
        by ``contacts._ActiveSet._restrained``)."""
        return {}

    @cached_property
    def anchored_systems(self) -> dict:
        """(contact state, spring scale) -> ``condense._Factored``, filled as the
        contact iterations meet them (``condense.anchored_system``)."""
        return {}

    @cached_property
    def condensation(self) -> _Condensed | None:
        """The contact-free part of the system, condensed onto the grounded planks."""
        from furncheck.statics.condense import _condense  # here: condense imports this module

        return _condense(self)


@dataclass(frozen=True)
class CaseStatics:
    """Solution of one load case.

    stability : 'stable', 'lift-off', 'sliding', or 'mechanism' (no force state could be
                computed: the planks are free to move even when held at every contact)
    joint_wrenches : (nJ, 6) force N and moment N m per model joint, or None (mechanism)
    contact_forces : (nK, 3) N, the ground's force on each model contact, or None
    culprits  : plank ids whose contacts lift or slide (for messages)
    detail    : a sentence with the numbers behind an unstable verdict
    """

    stability: str
    joint_wrenches: np.ndarray | None
    contact_forces: np.ndarray | None
    culprits: tuple[str, ...] = ()
    detail: str = ""
    state: np.ndarray | None = None     # the solution [q; h] of a stable case
    holding: np.ndarray | None = None   # (nK,) bool: contacts on the ground (not lifted)


def build_model(design: Design, geometry: Geometry) -> StaticsModel:
    """Assemble G, the compliances and the contact maps for the grounded components."""
    grounded_planks = sorted(i for comp, g in zip(geometry.components, geometry.grounded)
                             if g for i in comp)
    local = {plank: k for k, plank in enumerate(grounded_planks)}
    joints = [j for j, joint in enumerate(geometry.joints)
              if design.plank_index[joint.planks[0]] in local]
    plank_of = {design.planks[i].id: i for i in grounded_planks}
    contacts = [k for k, c in enumerate(geometry.contacts) if c.plank in plank_of]

    joint_planks, joint_blocks = _joint_blocks(design, geometry, joints, local)
    thickness = np.array([geometry.joints[j].edge_thickness for j in joints], dtype=float)
    compliance = np.empty((len(joints), 6))
    compliance[:, :3] = tol.JOINT_COMPLIANCE_T
    compliance[:, 3:] = tol.joint_compliance_r(thickness)[:, None]

    plank_of_contact = [design.plank_index[geometry.contacts[k].plank] for k in contacts]
    owner = [local[i] for i in plank_of_contact]
    points = np.array([geometry.contacts[k].point for k in contacts],
                      dtype=float).reshape(-1, 3)
    centres = np.array([design.planks[i].center_array for i in plank_of_contact],
                       dtype=float).reshape(-1, 3)
    components = tuple(tuple(local[i] for i in comp)
                       for comp, g in zip(geometry.components, geometry.grounded) if g)
    component_of = {p: c for c, comp in enumerate(components) for p in comp}
    return StaticsModel(
        design=design, geometry=geometry, planks=tuple(grounded_planks), joints=tuple(joints),
        contacts=tuple(contacts), joint_planks=joint_planks, joint_blocks=joint_blocks,
        compliance=compliance.ravel(),
        contact_maps=point_maps(points - centres),
        contact_plank=np.array(owner, dtype=int),
        contact_points=points,
        contact_component=np.array([component_of[p] for p in owner], dtype=int),
        components=components, friction=design.material.friction)


def _joint_blocks(design: Design, geometry: Geometry, joints: list[int],
                  local: dict[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """The joint deviation map G (paper eq. 1, small rotations) by blocks: the two planks
    (local numbers, (nJ, 2)) of each joint and its signed (6, 6) blocks ((nJ, 2, 6, 6)),

        d^t = (u_a + theta_a x r_a) - (u_b + theta_b x r_b),   d^r = theta_a - theta_b

    with a, b the joint's first and second plank and r = joint point - plank centre.
    """
    n_joints = len(joints)
    planks = np.zeros((n_joints, 2), dtype=int)
    blocks = np.zeros((n_joints, 2, 6, 6))
    if n_joints == 0:
        return planks, blocks
    points = np.array([geometry.joints[j].point for j in joints])
    for position, side in ((0, 1.0), (1, -1.0)):
        indices = [design.plank_index[geometry.joints[j].planks[position]] for j in joints]
        centres = np.array([design.planks[i].center_array for i in indices])
        planks[:, position] = [local[i] for i in indices]
        blocks[:, position, :3, :3] = side * np.eye(3)
        blocks[:, position, :3, 3:] = -side * _skew_many(points - centres)
        blocks[:, position, 3:, 3:] = side * np.eye(3)
    return planks, blocks


def external_forces(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(6 nP,) self-weight and the case's loads: force (N) and moment about the centre (N m)."""
    design = model.design
    f = model.self_weight.copy()
    local = model.local_planks
    for load in case.loads:
        if load.plank not in local:
            continue
        k = local[load.plank]
        plank = design.planks[model.planks[k]]
        fx, fy, fz = (float(v) for v in load.force)
        f[6 * k:6 * k + 3] += (fx, fy, fz)
        if load.point is not None:      # the moment r x F about the centre
            rx, ry, rz = (float(p) - float(c) for p, c in zip(load.point, plank.center))
            f[6 * k + 3:6 * k + 6] += (ry * fz - rz * fy, rz * fx - rx * fz, rx * fy - ry * fx)
    return f


# --- small helpers ----------------------------------------------------------------------------

def block_sums(index: np.ndarray, values: np.ndarray, count: int) -> np.ndarray:
    """(count, k): the rows of ``values`` (n, k) summed by ``index`` (n,), in order (what
    ``np.add.at`` gives; ``np.bincount`` is many times faster)."""
    k = values.shape[1]
    flat = (np.asarray(index)[:, None] * k + np.arange(k)).ravel()
    return np.bincount(flat, weights=values.ravel(), minlength=count * k).reshape(count, k)


def _skew(v: np.ndarray) -> np.ndarray:
    """[v]x, so that _skew(v) @ w = v x w."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _skew_many(v: np.ndarray) -> np.ndarray:
    out = np.zeros((len(v), 3, 3))
    out[:, 0, 1], out[:, 0, 2] = -v[:, 2], v[:, 1]
    out[:, 1, 0], out[:, 1, 2] = v[:, 2], -v[:, 0]
    out[:, 2, 0], out[:, 2, 1] = -v[:, 1], v[:, 0]
    return out


def point_maps(r: np.ndarray) -> np.ndarray:
    """(n, 3, 6): displacement of points at offsets r (n, 3) from their planks' centres,
    [I, -[r]x] @ (u, theta)."""
    maps = np.zeros((len(r), 3, 6))
    maps[:, :, :3] = np.eye(3)
    maps[:, :, 3:] = -_skew_many(r)
    return maps
