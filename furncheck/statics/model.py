"""The load-independent statics model of a design, and the load vector of a case.

``StaticsModel`` (the joint deviation map G, joint compliances and contact maps of the
grounded components), ``CaseStatics`` (one case's result), ``build_model``,
``external_forces`` and the small helpers they share.  How what acts on a plank is tied
to its node (offsets, contact frames, point loads) is in ``offsets``; the rigid model's
build in ``rigid``, the elastic one's in ``elastic``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase
from furncheck.geometry import Geometry
from furncheck.statics.offsets import add_point_load, skew_many

if TYPE_CHECKING:
    import scipy.sparse as sp

    from furncheck.statics.condense import _Condensed

_SIX = np.arange(6)


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class StaticsModel:
    """The load-independent part of a design's statics, in either model.

    The unknowns are six small displacements q_k = (u_k, theta_k) (m, rad) per *node*, the
    point ``node_points[k]`` of plank ``node_plank[k]`` it turns about, and a wrench per
    nail joint.  The rigid model has one node per plank, at its centre; the elastic model
    a row of nodes along each plank's beam axis, joined by beam elements (``beams``; their
    stiffness ``beam_stiffness``, ``statics.elastic``).

    planks   : design plank indices taking part (those of grounded components)
    joints   : geometry joint indices taking part
    contacts : geometry contact indices taking part
    node_plank, node_points : (nN,) local plank and (nN, 3) m, position of each node
    joint_nodes, joint_blocks : (nS, 2) local nodes and (nS, 2, 6, 6) signed blocks of
               the joint deviation map G (``G``: the same as a sparse (6 nS, 6 nN) matrix)
               of each joint *spring*: one per joint (nS = nJ), but in the elastic model
               a joint whose nail row runs along a plank's beam is cut into parts, each a
               spring at its own point (``joint_parts``)
    joint_stiffness : (nS, 6, 6) W, spring wrench = W (deviation), world frame: diagonal in
               the rigid model (its penalty constants), the nail row's springs in the
               elastic one (``beams.nail_row_parts``)
    joint_parts, part_arms : (nS,) the joint (row of ``joints``) of each spring and (nS, 3)
               m, its point less the joint's, or both None when every joint is one spring;
               the mixed system's wrench unknowns h are the springs', and
               ``joint_totals`` sums them into each joint's wrench about its point
    contact_maps : (nK, 3, 6) displacement of each contact point from its node's q, in
               the contact's frame (``contact_frames``): two tangential components, then
               the normal one (into the room for a wall, up for the ground)
    contact_frames : (nK, 3, 3) rows t1, t2, n of each contact's frame (world), or None
               when every contact is on the ground (the world frame: x, y, z)
    contact_anchored : (nK,) bool, the anchors' ties among the contacts (they hold both
               ways, never lift or slip), or None when the design has none
    rest_node, rest_maps : for a resting joint's corner (``Contact.on``), the node of the
               plank it rests on (-1 for other contacts) and that plank's map (nK, 3, 6)
               like ``contact_maps`` (zero for other contacts): the contact's displacement
               is contact_maps q[contact_node] - rest_maps q[rest_node], its force acts on
               the first plank and against it on the second; both None without rests
    contact_node, contact_plank : (nK,) local node and local plank of each contact
    contact_component : (nK,) component number of each contact
    station_corners, station_shares : (nSt, 2) contact rows and (nSt,) shares t of the
               elastic model's support stations (``statics.stations``: a plank the floor
               or a wall holds along its length), the last nSt of the nK contacts, each
               on the line between its edge's two corners (t = 0 at the first); None
               without them.  ``contacts`` lists a station under its first corner's
               geometry contact (its plank, support and frame); ``corner_forces`` shares
               the stations' forces out to the corners, which is what is reported
    contact_stiffness : N/m, the contacts' normal and anchor springs
    anchor_stiffness : N/m, the springs of the anchors' ties (``contact_springs``)
    components : local plank numbers of each grounded component (``component_nodes``:
               their nodes)
    beams    : the elements themselves (``elements.Beams``; None: rigid)
    """

    design: Design
    geometry: Geometry
    planks: tuple[int, ...]
    joints: tuple[int, ...]
    contacts: tuple[int, ...]
    node_plank: np.ndarray
    node_points: np.ndarray
    joint_nodes: np.ndarray
    joint_blocks: np.ndarray
    joint_stiffness: np.ndarray
    contact_maps: np.ndarray
    contact_node: np.ndarray
    contact_plank: np.ndarray
    contact_points: np.ndarray
    contact_component: np.ndarray
    components: tuple[tuple[int, ...], ...]
    friction: float
    contact_stiffness: float = tol.CONTACT_STIFFNESS
    anchor_stiffness: float = tol.CONTACT_STIFFNESS
    beams: object = None
    nodal_weight: np.ndarray | None = None
    load_nodes: dict | None = None     # (case name, load index) -> node (elastic model)
    contact_frames: np.ndarray | None = None
    contact_anchored: np.ndarray | None = None
    rest_node: np.ndarray | None = None
    rest_maps: np.ndarray | None = None
    joint_parts: np.ndarray | None = None
    part_arms: np.ndarray | None = None
    station_corners: np.ndarray | None = None
    station_shares: np.ndarray | None = None

    @property
    def n_dof(self) -> int:
        return 6 * len(self.node_plank)

    @property
    def n_springs(self) -> int:
        """Joint springs (``joint_nodes``): the wrench unknowns are six per spring."""
        return len(self.joint_nodes)

    def joint_totals(self, h: np.ndarray) -> np.ndarray:
        """Each joint's wrench (force N, moment N m about its point) from its springs'
        wrenches h, (6 nS,) or (6 nS, k) -> (6 nJ,) or (6 nJ, k): a part's force, and its
        moment plus its arm x its force, summed by joint (h itself where every joint is
        one spring)."""
        if self.joint_parts is None:
            return h
        per = h.reshape((self.n_springs, 6, -1))
        moved = per.copy()
        moved[:, 3:] += np.cross(self.part_arms[:, :, None], per[:, :3], axis=1)
        totals = block_sums(self.joint_parts, moved.reshape(self.n_springs, -1),
                            len(self.joints))
        return totals.reshape((6 * len(self.joints),) + h.shape[1:])

    @property
    def n_nodes(self) -> int:
        return len(self.node_plank)

    @cached_property
    def beam_stiffness(self) -> sp.csr_matrix | None:
        """(6 nN, 6 nN) sparse K_b, the beam elements' stiffness (None: rigid planks),
        assembled on first use (``beam_forces`` needs no assembly)."""
        if self.beams is None:
            return None
        from furncheck.statics.elements import assemble_beams

        return assemble_beams(self.beams, self.n_nodes)

    @cached_property
    def contact_springs(self) -> float | np.ndarray:
        """N/m: each contact's spring stiffness, in all three directions: the scalar
        ``contact_stiffness`` when no contact is an anchor's tie, else (nK,) with
        ``anchor_stiffness`` at the ties (``spring_rows`` picks rows of either)."""
        if self.contact_anchored is None:
            return self.contact_stiffness
        springs = np.full(len(self.contacts), self.contact_stiffness)
        springs[self.contact_anchored] = self.anchor_stiffness
        return springs

    @cached_property
    def contact_springs_each(self) -> np.ndarray:
        """(nK,) N/m: ``contact_springs`` as one (read-only) entry per contact, scalar or
        not (what the friction energy, ``newton``'s law and the round-off floors index)."""
        return np.broadcast_to(np.asarray(self.contact_springs, dtype=float),
                               (len(self.contacts),))

    def world_forces(self, forces: np.ndarray) -> np.ndarray:
        """(m, 3) N: contact forces given in the contacts' frames, in the world frame: of
        the first m contacts (all nK, or the corners' of ``corner_forces``)."""
        if self.contact_frames is None:
            return forces
        return np.einsum("kji,kj->ki", self.contact_frames[:len(forces)], forces)

    @property
    def n_corners(self) -> int:
        """The contacts that are the geometry's (its corners, anchors and resting
        corners): all but the support stations, which follow them."""
        stations = 0 if self.station_corners is None else len(self.station_corners)
        return len(self.contacts) - stations

    def corner_forces(self, forces: np.ndarray) -> np.ndarray:
        """(..., n_corners, 3) contact forces (or their rates) of the geometry's contacts
        from (..., nK, 3) of the model's, in the contacts' frames: each corner's own, plus
        (1 - t) of each support station on its edge at its first corner and t at its
        second (the lever rule: the same sum and moment; a station's frame is its
        corners').  The forces themselves where there are no stations."""
        if self.station_corners is None:
            return forces
        n = self.n_corners
        out = forces[..., :n, :].copy()
        station = forces[..., n:, :]
        shares = self.station_shares[:, None]
        for side, weight in ((0, 1.0 - shares), (1, shares)):
            rows = self.station_corners[:, side]
            np.add.at(np.moveaxis(out, -2, 0), rows, np.moveaxis(station * weight, -2, 0))
        return out

    def contact_displacements(self, q: np.ndarray) -> np.ndarray:
        """(nK, 3) m: each contact point's displacement for node displacements q (6 nN,),
        relative to the plank it rests on for a resting joint's corner."""
        node_q = q[:self.n_dof].reshape(-1, 6)[self.contact_node]
        w = (self.contact_maps @ node_q[:, :, None])[:, :, 0]
        if self.rest_node is not None:
            rows = self.rest_rows
            other = q[:self.n_dof].reshape(-1, 6)[self.rest_node[rows]]
            w[rows] -= (self.rest_maps[rows] @ other[:, :, None])[:, :, 0]
        return w

    @cached_property
    def ground_block(self) -> np.ndarray:
        """(nN,) each node's 6-block in the condensation's x_g (-1 for a node that is not
        in it): where a resting corner's other node sits, for the solves."""
        block = np.full(self.n_nodes, -1)
        nodes = self.condensation.ground[::6] // 6
        block[nodes] = np.arange(len(nodes))
        return block

    @cached_property
    def rest_component(self) -> np.ndarray:
        """(nK,) the grounded component of the plank each resting corner rests on (-1 for
        other contacts and without rests)."""
        component = np.full(len(self.contacts), -1)
        if self.rest_node is not None:
            of_plank = {p: c for c, members in enumerate(self.components) for p in members}
            rows = self.rest_rows
            component[rows] = [of_plank[int(self.node_plank[node])]
                               for node in self.rest_node[rows]]
        return component

    @cached_property
    def rest_face_above(self) -> np.ndarray:
        """(nK,) bool: resting corners whose face plank lies on top of the edge plank (its
        face looks down onto it: the face plank is the one carried, ``Contact.face_above``)."""
        return np.array([self.geometry.contacts[c].face_above for c in self.contacts],
                        dtype=bool)

    @cached_property
    def rest_rows(self) -> np.ndarray:
        """The contacts that are resting joints' corners (indices; none without rests)."""
        if self.rest_node is None:
            return np.zeros(0, dtype=int)
        return np.flatnonzero(self.rest_node >= 0)

    def contact_generalized(self, forces: np.ndarray) -> np.ndarray:
        """(6 nN,) the node loads of contact forces (nK, 3) in the contacts' frames: M^T f
        at each contact's node, and -M_b^T f at the node a resting corner rests on."""
        per_contact = (np.transpose(self.contact_maps, (0, 2, 1)) @ forces[:, :, None])[:, :, 0]
        out = block_sums(self.contact_node, per_contact, self.n_nodes)
        if self.rest_node is not None:
            rows = self.rest_rows
            other = (np.transpose(self.rest_maps[rows], (0, 2, 1))
                     @ forces[rows, :, None])[:, :, 0]
            out -= block_sums(self.rest_node[rows], other, self.n_nodes)
        return out.ravel()

    def beam_forces(self, q: np.ndarray) -> np.ndarray:
        """(6 nN,) K_b q element by element (zero for rigid planks)."""
        if self.beams is None:
            return np.zeros(self.n_dof)
        from furncheck.statics.elements import element_forces

        return element_forces(self.beams, q, self.n_nodes)

    @cached_property
    def component_nodes(self) -> tuple[tuple[int, ...], ...]:
        """Local node numbers of each grounded component."""
        return tuple(tuple(int(k) for k in np.flatnonzero(np.isin(self.node_plank, comp)))
                     for comp in self.components)

    @cached_property
    def G(self) -> sp.csr_matrix:
        """(6 nJ, 6 nN) sparse joint deviation map, d = G q (for the sparse paths of large
        designs: scipy.sparse is imported here)."""
        import scipy.sparse as sp

        n_springs = self.n_springs
        shape = (n_springs, 2, 6, 6)
        rows = np.broadcast_to(6 * np.arange(n_springs)[:, None, None, None]
                               + _SIX[None, None, :, None], shape).ravel()
        cols = np.broadcast_to(6 * self.joint_nodes[:, :, None, None]
                               + _SIX[None, None, None, :], shape).ravel()
        return sp.csr_matrix((self.joint_blocks.ravel(), (rows, cols)),
                             shape=(6 * n_springs, self.n_dof))

    @cached_property
    def joint_compliance(self) -> np.ndarray:
        """(nS, 6, 6) E = W^-1 per joint spring, the mixed system's -E blocks."""
        return np.linalg.inv(self.joint_stiffness) if self.n_springs \
            else np.zeros((0, 6, 6))

    def joint_wrench(self, deviations: np.ndarray) -> np.ndarray:
        """W d per joint spring for deviations (6 nS,) or (6 nS, k)."""
        if not self.n_springs:
            return np.zeros_like(deviations)
        per_joint = deviations.reshape((self.n_springs, 6, -1))
        return (self.joint_stiffness @ per_joint).reshape(deviations.shape)

    def deviations(self, q: np.ndarray) -> np.ndarray:
        """G q for node displacements q, (6 nN,) or (6 nN, k), by blocks: per joint its
        (6, 12) rows of G times the 12 displacements of its two nodes (one stacked
        matmul; two to five times faster than the same contraction by einsum)."""
        columns = q.reshape((self.n_nodes, 6) + q.shape[1:])[self.joint_nodes]
        columns = columns.reshape((self.n_springs, 12, math.prod(q.shape[1:])))  # (nS, 12, k)
        return (self.joint_rows @ columns).reshape((-1,) + q.shape[1:])

    @cached_property
    def joint_rows(self) -> np.ndarray:
        """(nJ, 6, 12): each joint's rows of G, its first node's columns then its second's."""
        return np.ascontiguousarray(np.transpose(self.joint_blocks, (0, 2, 1, 3))
                                    .reshape(-1, 6, 12))

    def reactions(self, h: np.ndarray) -> np.ndarray:
        """G^T h for joint spring values h, (6 nS,) or (6 nS, k), by blocks."""
        if not self.n_springs:
            return np.zeros((self.n_dof,) + h.shape[1:])
        per_joint = np.einsum("jsab,ja...->jsb...", self.joint_blocks,
                              h.reshape((-1, 6) + h.shape[1:]))
        out = block_sums(self.joint_nodes.ravel(), per_joint.reshape(2 * self.n_springs, -1),
                         self.n_nodes)
        return out.reshape((-1,) + h.shape[1:])

    @cached_property
    def self_weight(self) -> np.ndarray:
        """(6 nN,) the planks' weights (N) as loads: at their centres (rigid), spread along
        their beams (elastic)."""
        if self.nodal_weight is not None:
            return self.nodal_weight
        f = np.zeros(self.n_dof)
        f[2::6] = [-self.design.plank_mass(self.design.planks[i]) * tol.GRAVITY
                   for i in self.planks]
        return f

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
            rigid = rigid_motions(self.contact_points[members])
            grams[members] = np.transpose(rigid, (0, 2, 1)) @ rigid
        return grams

    @cached_property
    def plank_cache(self) -> dict:
        """Per-model facts about the planks that the elastic results reuse (filled by
        ``bending``: which joints carry which plank, which planks lie on the floor, the
        sections and beam axes)."""
        return {}

    @cached_property
    def restrained_states(self) -> dict:
        """Contact state -> whether its holding contacts restrain every component (filled
        by ``contacts._ActiveSet._restrained``)."""
        return {}

    @cached_property
    def contact_spaces(self) -> dict:
        """What the contact iterations of all load cases share: 'map', the contacts'
        displacements from the grounded planks' (``contacts._ActiveSet.contact_map``), and
        'magnitudes', what their round-off is measured by (``friction.contact_magnitudes``)."""
        return {}

    @cached_property
    def anchored_systems(self) -> dict:
        """(contact state, spring scale) -> ``anchored._Factored``, filled as the
        contact iterations meet them (``anchored.anchored_system``)."""
        return {}

    @cached_property
    def condensation(self) -> _Condensed | None:
        """The contact-free part of the system, condensed onto the grounded nodes."""
        from furncheck.statics.condense import _condense  # here: condense imports this module

        return _condense(self)


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class CaseStatics:
    """Solution of one load case.

    stability : 'stable', 'lift-off', 'sliding', or 'mechanism' (no force state could be
                computed: the planks are free to move even when held at every contact)
    joint_wrenches : (nJ, 6) force N and moment N m per model joint, or None (mechanism)
    part_wrenches : (nS, 6) the same per joint spring where the model cuts joints into
                parts (``StaticsModel.joint_parts``; their sum about each joint's point is
                its wrench), else None
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
    displacements: np.ndarray | None = None   # (6 nN,) q of the forces shown, if any
    ground: np.ndarray | None = None    # the grounded nodes' q (x_g) of a stable case found
                                        # by the contact iterations (not the programs')
    planks: object = None      # elastic.PlankStatics: sag, span, stress (elastic model)
    part_wrenches: np.ndarray | None = None   # (nS, 6) each spring's wrench about its
                                              # own point, where joints are cut into parts


def build_model(design: Design, geometry: Geometry) -> StaticsModel:
    """The statics model of the grounded components in the design's model (``design.model``:
    the one place where the model is chosen): rigid planks (paper section 5.1) or elastic
    beams (``statics.elastic``, contract section 3a)."""
    if design.elastic:
        from furncheck.statics.elastic import build_elastic_model

        return build_elastic_model(design, geometry)
    from furncheck.statics.rigid import build_rigid_model

    return build_rigid_model(design, geometry)


def grounded_parts(design: Design, geometry: Geometry):
    """(design plank indices, joints, contacts, components as local planks) of the
    grounded components, in order."""
    grounded_planks = sorted(i for comp, g in zip(geometry.components, geometry.grounded)
                             if g for i in comp)
    local = {plank: k for k, plank in enumerate(grounded_planks)}
    joints = [j for j, joint in enumerate(geometry.joints)
              if design.plank_index[joint.planks[0]] in local]
    plank_of = {design.planks[i].id: i for i in grounded_planks}
    contacts = [k for k, c in enumerate(geometry.contacts) if c.plank in plank_of]
    components = tuple(tuple(local[i] for i in comp)
                       for comp, g in zip(geometry.components, geometry.grounded) if g)
    return grounded_planks, joints, contacts, components


def rigid_motions(points: np.ndarray) -> np.ndarray:
    """(k, 3, 6) R per point: its displacement under a rigid motion of the body the points
    belong to (translation, and rotation x the points' spread about their mean:
    ``spread``)."""
    origin, length = spread(points)
    rigid = np.zeros((len(points), 3, 6))
    rigid[:, :, :3] = np.eye(3)
    rigid[:, :, 3:] = -skew_many(points - origin) / length
    return rigid


def spread(points: np.ndarray) -> tuple[np.ndarray, float]:
    """The points' mean and their spread about it (m, at least 1e-6): the centre and the
    length by which ``rigid_motions`` scales its rotations."""
    origin = points.mean(axis=0)
    return origin, max(float(np.abs(points - origin).max()), 1e-6)


def external_forces(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(6 nN,) self-weight and the case's loads: force (N) and moment (N m) about each
    node.  A load acts at the node of its point (its plank's centre when it has none);
    a spread load at its plank's centre in the rigid model, along its beam in the
    elastic one."""
    if model.beams is not None:
        from furncheck.statics.elements import elastic_forces

        return elastic_forces(model, case)
    design = model.design
    f = model.self_weight.copy()
    local = model.local_planks
    for load in case.loads:
        if load.plank not in local:
            continue
        k = local[load.plank]
        plank = design.planks[model.planks[k]]
        add_point_load(f, k, plank.center, load.force, load.point)
    return f


# --- small helpers ----------------------------------------------------------------------------

def block_sums(index: np.ndarray, values: np.ndarray, count: int) -> np.ndarray:
    """(count, k): the rows of ``values`` (n, k) summed by ``index`` (n,), in order (what
    ``np.add.at`` gives; ``np.bincount`` is many times faster)."""
    k = values.shape[1]
    flat = (np.asarray(index)[:, None] * k + np.arange(k)).ravel()
    return np.bincount(flat, weights=values.ravel(), minlength=count * k) \
        .astype(float, copy=False).reshape(count, k)


def spring_rows(springs: float | np.ndarray, rows=None, trailing: int = 0):
    """``StaticsModel.contact_springs`` (or rows ``rows`` of it: a mask or indices) shaped
    to broadcast over ``trailing`` more axes; a scalar stays a scalar (the same arithmetic
    as before anchors had their own springs)."""
    if not isinstance(springs, np.ndarray):
        return springs
    picked = springs if rows is None else springs[rows]
    return picked.reshape(picked.shape + (1,) * trailing)
