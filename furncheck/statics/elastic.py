"""Elastic planks (contract section 3a): the statics model of ``model: elastic``.

Each plank is a Timoshenko beam (``beams``) along its longer in-plane axis, cut into
elements at nodes on that axis wherever a joint, a ground contact or a load acts (at the
projection of its point), at the plank's ends and centre, and at least every
1 / BEAM_SEGMENTS of its length.  What acts off the axis is tied to its node by a rigid
offset (``point_maps``, ``joint_deviation_blocks``): a leg under a table top's corner
twists the top.  A nail joint is a spring between its two planks' nodes, from its nail
row (``beams.joint_springs``); ground contacts are stiff unilateral springs with friction
anchors (ELASTIC_CONTACT_STIFFNESS).  The model is a ``StaticsModel`` like the rigid
one: the same mixed system, with the beams' stiffness K_b in its plank block, and the
same contact loop.  Self-weight and spread loads act along the beams as consistent nodal
loads (``elastic_forces``).  After the solve, ``bending.plank_results`` gives each
plank's sag and stress.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase, Material, Plank
from furncheck.geometry import Geometry
from furncheck.statics.beams import (
    along_width,
    beam_frame,
    beam_length_width,
    beam_stiffness_local,
    nail_row_springs,
    uniform_load_local,
)
from furncheck.statics.model import (
    _SIX,
    StaticsModel,
    add_point_loads,
    anchored_contacts,
    block_sums,
    contact_frames,
    grounded_parts,
    in_contact_frames,
    joint_deviation_blocks,
    point_maps,
    rest_maps,
)

if TYPE_CHECKING:
    import scipy.sparse as sp


@dataclass(frozen=True)
class Beams:
    """The beam elements of an elastic model.

    plank, nodes : (nE,) local plank and (nE, 2) local nodes of each element
    length   : (nE,) m
    frames   : (nE, 3, 3) columns e1, e2, e3 (world)
    local_stiffness : (nE, 12, 12) in the element's axes
    width, thickness : (nE,) m, the section
    elastic_modulus, shear_modulus : (nE,) Pa, E and G of each element's plank
    node_s   : (nN,) m, each node's position along its plank's axis from the centre
    plank_half : (nP,) m, half the beam length of each plank
    origins  : per node, its local plank and the keys of what it serves (``_plank_nodes``)
    crosswise : per plank, whether its beam runs along its local y (``along_width``)
    plank_frames : (nP, 3, 3) each plank's beam axes (``beam_frame``)
    """

    plank: np.ndarray
    nodes: np.ndarray
    length: np.ndarray
    frames: np.ndarray
    local_stiffness: np.ndarray
    width: np.ndarray
    thickness: np.ndarray
    elastic_modulus: np.ndarray
    shear_modulus: np.ndarray
    node_s: np.ndarray
    plank_half: np.ndarray
    origins: tuple = ()
    crosswise: tuple = ()
    plank_frames: np.ndarray | None = None

    def transform(self) -> np.ndarray:
        """(nE, 12, 12) T: local = T world, blockdiag(R^T x 4)."""
        T = np.zeros((len(self.plank), 12, 12))
        for block in range(4):
            T[:, 3 * block:3 * block + 3, 3 * block:3 * block + 3] = \
                np.transpose(self.frames, (0, 2, 1))
        return T


def _plank_nodes(k: int, half: float, attachments: list[tuple[float, tuple]]) -> list[tuple]:
    """The nodes of local plank k, a beam of half length ``half``, in order along it, each
    as its origin: k and the attachment keys it serves (``attachments``: (s, key),
    s the attachment's position along the axis; those within NODE_MERGE of each other, or
    a tenth of a grid step on a short plank, share a node at their mean), with the ends
    ('end', k, -1 / 1) and the centre ('centre', k), or ('grid', k, fraction) for the grid
    of BEAM_SEGMENTS where no node is within a quarter of its step (fraction 0 .. 1 from
    the -e1 end).  Consecutive nodes are at least the merge distance apart."""
    step = 2.0 * half / tol.BEAM_SEGMENTS
    merge = min(tol.NODE_MERGE, 0.1 * step)
    marks = [(-half, ("end", k, -1)), (0.0, ("centre", k)), (half, ("end", k, 1))]
    required = sorted(((min(max(s, -half), half), key) for s, key in [*attachments, *marks]),
                      key=lambda item: item[0])
    groups: list[list] = []
    for s, key in required:
        if groups and s - groups[-1][0] <= merge:
            groups[-1][1].append(key)
            groups[-1][2].append(s)
        else:
            groups.append([s, [key], [s]])
    nodes = [(sum(positions) / len(positions), tuple(keys)) for _, keys, positions in groups]
    placed = [s for s, _ in nodes]
    for i in range(1, tol.BEAM_SEGMENTS):
        s = -half + i * step
        if min(abs(p - s) for p in placed) > 0.25 * step:
            nodes.append((s, (("grid", k, i / tol.BEAM_SEGMENTS),)))
    return [(k, *origin) for _, origin in sorted(nodes, key=lambda item: item[0])]


def _crosswise(design: Design, geometry: Geometry, planks: list[Plank], joints: list[int],
               contacts: list[int]) -> tuple[bool, ...]:
    """Per plank, whether its beam runs along its local y: its longer side (contract 3a);
    a square plank (sides within the design's tolerance) along the side over which what
    holds it (its joints' and contacts' points) is spread the most, so that describing it
    turned by 90 degrees changes nothing."""
    points: dict[str, list] = {p.id: [] for p in planks}
    for j in joints:
        joint = geometry.joints[j]
        for plank_id in joint.planks:
            points[plank_id].append(joint.point)
    for c in contacts:
        points[geometry.contacts[c].plank].append(geometry.contacts[c].point)
    out = []
    for plank in planks:
        if abs(plank.length - plank.width) > design.tolerance or not points[plank.id]:
            out.append(along_width(plank))
            continue
        local = plank.to_local(np.array(points[plank.id]))
        spread = local.max(axis=0) - local.min(axis=0)
        out.append(bool(spread[1] > spread[0] + tol.NODE_MERGE))
    return tuple(out)


TOPOLOGY_CACHE = ("carrying", "lying", "supports")
"""The entries of ``StaticsModel.plank_cache`` (filled by ``bending``) that depend on which
planks are jointed and which contacts stand, not on where: a model built on a template
(the same joints and contacts) shares them, as it shares its ``_NodeLayout``
("node_layout")."""


@dataclass(frozen=True)
class _NodeLayout:
    """Which attachments each node serves, as arrays (from the nodes' origins: a local
    plank and the keys it serves, ``_plank_nodes``), so that the nodes of a model built on
    a template are placed without going through the keys again.

    node_plank : (nN,) local plank of each node
    key_node, key_plank : (m,) node and local plank of each key of every origin, in order
    key_row    : (m,) the attachment row of a key (its place in the build's attachment
                 list: joints' two sides, contacts, loads), -1 for an end, centre or grid
    key_scale  : (m,) where an end, centre or grid key sits, in half lengths from the centre
    counts     : (nN,) keys per node
    row_node   : (nA,) the node of each attachment row
    centre_node : (nP,) the node at each plank's centre
    """

    node_plank: np.ndarray
    key_node: np.ndarray
    key_plank: np.ndarray
    key_row: np.ndarray
    key_scale: np.ndarray
    counts: np.ndarray
    row_node: np.ndarray
    centre_node: np.ndarray

    @classmethod
    def of(cls, origins: tuple, keys: list[tuple], owners: list[int]) -> _NodeLayout:
        row_of = {key: row for row, key in enumerate(keys)}
        key_node, key_plank, key_row, key_scale = [], [], [], []
        centre_node = {}
        for node, (plank, *served) in enumerate(origins):
            for key in served:
                row = row_of.get(key, -1)
                key_node.append(node)
                key_plank.append(owners[row] if row >= 0 else plank)
                key_row.append(row)
                key_scale.append(float(key[2]) if key[0] == "end" else
                                 2.0 * key[2] - 1.0 if key[0] == "grid" else 0.0)
                if key[0] == "centre":
                    centre_node[plank] = node
        key_node = np.array(key_node, dtype=int)
        key_row = np.array(key_row, dtype=int)
        row_node = np.zeros(len(keys), dtype=int)
        attached = key_row >= 0
        row_node[key_row[attached]] = key_node[attached]
        return cls(node_plank=np.array([origin[0] for origin in origins], dtype=int),
                   key_node=key_node, key_plank=np.array(key_plank, dtype=int),
                   key_row=key_row, key_scale=np.array(key_scale, dtype=float),
                   counts=np.bincount(key_node, minlength=len(origins)),
                   row_node=row_node,
                   centre_node=np.array([centre_node[k] for k in range(len(centre_node))],
                                        dtype=int))

    def positions(self, along: np.ndarray, halves: np.ndarray) -> np.ndarray:
        """(nN,) m: each node's place along its plank's axis, the mean of what it serves:
        an attachment at its place ``along`` (nA,) kept on the plank (within +-half its
        length, ``halves`` (nP,)), an end, the centre or a grid point where it is."""
        half = halves[self.key_plank]
        attached = self.key_row >= 0
        values = self.key_scale * half
        values[attached] = np.minimum(np.maximum(along[self.key_row[attached]],
                                                 -half[attached]), half[attached])
        return np.bincount(self.key_node, weights=values, minlength=len(self.counts)) \
            / self.counts


def build_elastic_model(design: Design, geometry: Geometry,
                        template: StaticsModel | None = None) -> StaticsModel:
    """The elastic ``StaticsModel`` of the grounded components (see the module docstring).

    ``template``: a model of the same design before a small edit (the same joints,
    contacts and loads): its nodes are kept, each at the new place of what it serves, so
    that the two models' unknowns correspond (the force sensitivity differences them)."""
    if template is not None and "attachments" in template.plank_cache:
        return _built_on(design, geometry, template)
    material = design.material
    planks_used, joints, contacts, components = grounded_parts(design, geometry)
    local = {plank: k for k, plank in enumerate(planks_used)}
    plank_list = [design.planks[i] for i in planks_used]
    crosswise = _crosswise(design, geometry, plank_list, joints, contacts) \
        if template is None else template.beams.crosswise
    frames = [beam_frame(p, c) for p, c in zip(plank_list, crosswise)]
    halves = np.array([0.5 * beam_length_width(p, c)[0]
                       for p, c in zip(plank_list, crosswise)])

    keys: list[tuple] = []              # what is attached where: its key,
    owners: list[int] = []              # its local plank
    points: list = []                   # and its point
    for row, j in enumerate(joints):
        joint = geometry.joints[j]
        for side, plank_id in enumerate(joint.planks):
            keys.append(("joint", row, side))
            owners.append(local[design.plank_index[plank_id]])
            points.append(joint.point)
    for row, c in enumerate(contacts):
        keys.append(("contact", row))
        owners.append(local[design.plank_index[geometry.contacts[c].plank]])
        points.append(geometry.contacts[c].point)
    for row, c in enumerate(contacts):              # a resting corner's other plank
        if geometry.contacts[c].on is not None:
            keys.append(("rest", row))
            owners.append(local[design.plank_index[geometry.contacts[c].on]])
            points.append(geometry.contacts[c].point)
    for ci, case in enumerate(design.load_cases):
        for li, load in enumerate(case.loads):
            k = local.get(design.plank_index[load.plank])
            if k is not None and load.point is not None and not load.spread:
                keys.append(("load", ci, li))
                owners.append(k)
                points.append(load.point)
    centres = np.array([p.center_array for p in plank_list], dtype=float).reshape(-1, 3)
    axes = np.array([frame[:, 0] for frame in frames], dtype=float).reshape(-1, 3)
    owner_array = np.array(owners, dtype=int)
    along = ((np.array(points, dtype=float).reshape(-1, 3) - centres[owner_array])
             * axes[owner_array]).sum(axis=1)

    if template is None:
        attachments: list[list] = [[] for _ in plank_list]
        for key, s, owner in zip(keys, along.tolist(), owners):
            attachments[owner].append((s, key))
        origins = tuple(origin for k in range(len(plank_list))
                        for origin in _plank_nodes(k, float(halves[k]), attachments[k]))
        layout = _NodeLayout.of(origins, keys, owners)
    else:
        origins = template.beams.origins
        layout = template.plank_cache["node_layout"]

    node_plank = layout.node_plank
    node_s = layout.positions(along, halves)
    node_points = (centres[node_plank] + node_s[:, None] * axes[node_plank]).reshape(-1, 3)
    beams = _beams(plank_list, frames, node_plank, node_s, halves,
                   [design.material_of(p) for p in plank_list], origins, crosswise)

    weights = _read_only(_weights_per_length(design, plank_list, beams))
    n_sides = 2 * len(joints)
    joint_nodes = layout.row_node[:n_sides].reshape(-1, 2)
    points = np.array([geometry.joints[j].point for j in joints], dtype=float).reshape(-1, 3)
    joint_blocks = joint_deviation_blocks(points, node_points[joint_nodes])
    stiffness = nail_row_springs([geometry.joints[j] for j in joints], material.nail_slip,
                                 material.nail_withdrawal)

    owner = owner_array[n_sides:n_sides + len(contacts)]
    contact_points = np.array([geometry.contacts[c].point for c in contacts],
                              dtype=float).reshape(-1, 3)
    contact_node = layout.row_node[n_sides:n_sides + len(contacts)]
    load_rows = {key[1:]: row for row, key in enumerate(keys) if key[0] == "load"}
    load_nodes = {(case.name, li): int(layout.row_node[load_rows[ci, li]])
                  if (ci, li) in load_rows else int(layout.centre_node[k])
                  for ci, case in enumerate(design.load_cases)
                  for li, load in enumerate(case.loads)
                  if (k := local.get(design.plank_index[load.plank])) is not None}
    component_of = {p: c for c, comp in enumerate(components) for p in comp}
    frames = contact_frames(design, geometry, contacts)
    rest_node = None
    if any(key[0] == "rest" for key in keys):
        rest_node = np.full(len(contacts), -1)
        for index, key in enumerate(keys):
            if key[0] == "rest":
                rest_node[key[1]] = layout.row_node[index]
    model = StaticsModel(
        design=design, geometry=geometry, planks=tuple(planks_used), joints=tuple(joints),
        contacts=tuple(contacts), node_plank=node_plank, node_points=node_points,
        joint_nodes=joint_nodes, joint_blocks=joint_blocks, joint_stiffness=stiffness,
        contact_maps=in_contact_frames(
            point_maps(contact_points - node_points[contact_node].reshape(-1, 3)), frames),
        contact_frames=frames, contact_anchored=anchored_contacts(geometry, contacts),
        rest_node=rest_node,
        rest_maps=rest_maps(rest_node, contact_points, node_points, frames),
        contact_node=contact_node, contact_plank=owner, contact_points=contact_points,
        contact_component=np.array([component_of[p] for p in owner], dtype=int),
        components=components, friction=material.friction,
        contact_stiffness=tol.ELASTIC_CONTACT_STIFFNESS,
        anchor_stiffness=tol.ANCHOR_STIFFNESS,
        beams=beams,
        nodal_weight=_nodal_loads(beams, weights, len(node_plank)),
        load_nodes=load_nodes)
    model.plank_cache["node_layout"] = layout
    model.plank_cache["weights_per_length"] = weights
    model.plank_cache["attachments"] = _Attachments(
        owner_array, tuple(key[1] for key in keys if key[0] == "rest"),
        tuple(key[1:] for key in keys if key[0] == "load"))
    if template is not None:        # the same joints and contacts: the same topology
        assert template.joints == model.joints and template.contacts == model.contacts
        for key in TOPOLOGY_CACHE:
            if key in template.plank_cache:
                model.plank_cache[key] = template.plank_cache[key]
    return model


@dataclass(frozen=True)
class _Attachments:
    """What a model built on a template (``_built_on``) takes over of how the template's
    attachments were listed: each row's local plank (joints' two sides, contacts, resting
    corners' other planks, loads at a point), the contact rows of the resting corners and
    the (case, load) numbers of the loads, in that order."""

    owners: np.ndarray
    rest_rows: tuple[int, ...]
    loads: tuple[tuple[int, int], ...]


def _built_on(design: Design, geometry: Geometry, template: StaticsModel) -> StaticsModel:
    """``build_elastic_model(design, geometry, template)``: the same model, with what
    depends only on which joints, contacts and loads there are (the grounded parts, the
    attachments' owners and nodes, the loads' nodes, the contacts' components and resting
    corners) taken from the template instead of listed again; every number that depends
    on where things are is computed as there."""
    return _finished_on([_placed_on(design, geometry, template)], template)[0]


def build_elastic_models(designs: list[Design], geometries: list[Geometry],
                         template: StaticsModel) -> Iterator[StaticsModel]:
    """``build_elastic_model(design, geometry, template)`` of each design and its geometry
    (small edits of the template's design, the force sensitivity's stepped designs): the
    same models, their element-by-element arithmetic (the elements' stiffness and nodal
    weights, the nail rows' springs and compliances, the joints' and contacts' offsets)
    done for up to BATCH_ELEMENTS elements of several models at once.  Each of those
    numbers depends on its own element, joint or contact alone, so batching changes none
    of them, only how many array operations make them.  A generator: only one batch of
    models is kept at a time."""
    for batch in build_elastic_model_batches(designs, geometries, template):
        yield from batch


def build_elastic_model_batches(designs: list[Design], geometries: list[Geometry],
                                template: StaticsModel) -> Iterator[list[StaticsModel]]:
    """``build_elastic_models`` a batch (a list of models, in order) at a time."""
    if "attachments" not in template.plank_cache:
        for design, geometry in zip(designs, geometries):
            yield [build_elastic_model(design, geometry, template=template)]
        return
    per_batch = max(1, BATCH_ELEMENTS // max(len(template.beams.length), 1))
    for start in range(0, len(designs), per_batch):
        placed = [_placed_on(d, g, template)
                  for d, g in zip(designs[start:start + per_batch],
                                  geometries[start:start + per_batch])]
        yield _finished_on(placed, template)


BATCH_ELEMENTS = 16384
"""Most beam elements (of all models together) that ``build_elastic_models`` builds in
one pass (their stiffness matrices take 1,152 bytes each)."""


@dataclass(frozen=True)
class _Placed:
    """A design's nodes placed on a template's (``_placed_on``): what ``_finished_on``
    needs of it besides the template."""

    design: Design
    geometry: Geometry
    plank_list: list
    frames: list
    halves: np.ndarray
    node_s: np.ndarray
    node_points: np.ndarray
    joint_points: np.ndarray
    contact_points: np.ndarray
    materials: list


def _placed_on(design: Design, geometry: Geometry, template: StaticsModel) -> _Placed:
    """The nodes of a model of ``design`` built on ``template``, each at the new place of
    what it serves (``_NodeLayout.positions``)."""
    joints, contacts = template.joints, template.contacts
    attachments: _Attachments = template.plank_cache["attachments"]
    plank_list = [design.planks[i] for i in template.planks]
    crosswise = template.beams.crosswise
    frames = [beam_frame(p, c) for p, c in zip(plank_list, crosswise)]
    halves = np.array([0.5 * beam_length_width(p, c)[0]
                       for p, c in zip(plank_list, crosswise)])
    joint_points = [geometry.joints[j].point for j in joints]
    contact_points = [geometry.contacts[c].point for c in contacts]
    points = [point for point in joint_points for _ in (0, 1)] + contact_points \
        + [contact_points[row] for row in attachments.rest_rows] \
        + [design.load_cases[ci].loads[li].point for ci, li in attachments.loads]
    centres = np.array([p.center_array for p in plank_list], dtype=float).reshape(-1, 3)
    axes = np.array([frame[:, 0] for frame in frames], dtype=float).reshape(-1, 3)
    owner_array = attachments.owners
    along = ((np.array(points, dtype=float).reshape(-1, 3) - centres[owner_array])
             * axes[owner_array]).sum(axis=1)
    layout = template.plank_cache["node_layout"]
    node_plank = layout.node_plank
    node_s = layout.positions(along, halves)
    node_points = (centres[node_plank] + node_s[:, None] * axes[node_plank]).reshape(-1, 3)
    return _Placed(design, geometry, plank_list, frames, halves, node_s, node_points,
                   np.array(joint_points, dtype=float).reshape(-1, 3),
                   np.array(contact_points, dtype=float).reshape(-1, 3),
                   [design.material_of(p) for p in plank_list])


def _finished_on(placed: list[_Placed], template: StaticsModel) -> list[StaticsModel]:
    """The models of designs placed on ``template`` (``_placed_on``), their element,
    joint and contact arithmetic done for all of them at once (the same numbers as one
    model at a time: see ``build_elastic_models``)."""
    count = len(placed)
    node_plank = template.plank_cache["node_layout"].node_plank
    first, nodes, plank = _element_nodes(node_plank)
    inputs = [_element_inputs(p.plank_list, p.frames, plank, p.node_s, first, p.materials,
                              template.beams.crosswise) for p in placed]
    length, widths, thickness, moduli = (np.concatenate([item[k] for item in inputs])
                                         for k in range(4))
    local = np.split(beam_stiffness_local(length, widths, thickness, moduli[:, 0],
                                          moduli[:, 1]).reshape(-1, 12, 12), count)
    beams = [Beams(plank=plank, nodes=nodes, length=item[0], frames=item[4][plank],
                   local_stiffness=stiffness, width=item[1], thickness=item[2],
                   elastic_modulus=item[3][:, 0], shear_modulus=item[3][:, 1],
                   node_s=p.node_s, plank_half=p.halves, origins=template.beams.origins,
                   crosswise=template.beams.crosswise, plank_frames=item[4])
             for p, item, stiffness in zip(placed, inputs, local)]
    weights = [_read_only(_weights_per_length(p.design, p.plank_list, b))
               for p, b in zip(placed, beams)]
    world = np.split(_element_world_loads(np.concatenate([b.frames for b in beams]),
                                          length, np.concatenate(weights)), count)
    dofs = _element_dofs(beams[0]).ravel()
    joint_nodes, contact_node = template.joint_nodes, template.contact_node
    joint_blocks = np.split(joint_deviation_blocks(
        np.concatenate([p.joint_points for p in placed]),
        np.concatenate([p.node_points[joint_nodes] for p in placed])), count)
    offsets = np.split(point_maps(np.concatenate(
        [p.contact_points - p.node_points[contact_node].reshape(-1, 3) for p in placed])),
        count)
    materials = {(p.design.material.nail_slip, p.design.material.nail_withdrawal)
                 for p in placed}
    if len(materials) == 1:
        ((slip, withdrawal),) = materials
        springs = np.split(nail_row_springs(
            [p.geometry.joints[j] for p in placed for j in template.joints], slip,
            withdrawal), count)
    else:
        springs = [nail_row_springs([p.geometry.joints[j] for j in template.joints],
                                    p.design.material.nail_slip,
                                    p.design.material.nail_withdrawal) for p in placed]
    compliance = np.split(np.linalg.inv(np.concatenate(springs)), count) \
        if len(template.joints) else [np.zeros((0, 6, 6))] * count
    contacts = list(template.contacts)
    models = []
    for k, p in enumerate(placed):
        design, geometry = p.design, p.geometry
        frames = contact_frames(design, geometry, contacts)
        nodal_weight = np.zeros(6 * len(node_plank))
        np.add.at(nodal_weight, dofs, world[k].ravel())
        model = StaticsModel(
            design=design, geometry=geometry, planks=template.planks,
            joints=template.joints, contacts=template.contacts, node_plank=node_plank,
            node_points=p.node_points, joint_nodes=joint_nodes, joint_blocks=joint_blocks[k],
            joint_stiffness=springs[k],
            contact_maps=in_contact_frames(offsets[k], frames),
            contact_frames=frames, contact_anchored=anchored_contacts(geometry, contacts),
            rest_node=template.rest_node,
            rest_maps=rest_maps(template.rest_node, p.contact_points, p.node_points, frames),
            contact_node=contact_node, contact_plank=template.contact_plank,
            contact_points=p.contact_points, contact_component=template.contact_component,
            components=template.components, friction=design.material.friction,
            contact_stiffness=tol.ELASTIC_CONTACT_STIFFNESS,
            anchor_stiffness=tol.ANCHOR_STIFFNESS,
            beams=beams[k], nodal_weight=nodal_weight, load_nodes=template.load_nodes)
        model.__dict__["joint_compliance"] = compliance[k]     # its cached property's value
        for key in ("node_layout", "attachments", *TOPOLOGY_CACHE):
            if key in template.plank_cache:
                model.plank_cache[key] = template.plank_cache[key]
        model.plank_cache["weights_per_length"] = weights[k]
        models.append(model)
    return models


def _read_only(array: np.ndarray) -> np.ndarray:
    """The array, marked read-only (kept in ``StaticsModel.plank_cache`` and shared)."""
    array.flags.writeable = False
    return array


def _element_nodes(node_plank: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(first node of each element, its (nE, 2) nodes, its local plank): an element
    between each two consecutive nodes of a plank."""
    first = np.flatnonzero(node_plank[1:] == node_plank[:-1])
    return first, np.column_stack([first, first + 1]), node_plank[first]


def _element_inputs(planks: list[Plank], frames: list[np.ndarray], plank: np.ndarray,
                    node_s: np.ndarray, first: np.ndarray, materials: list[Material],
                    crosswise: tuple[bool, ...]) -> tuple[np.ndarray, ...]:
    """Each element's length, width, thickness and moduli (nE, 2), and the planks' beam
    axes (nP, 3, 3)."""
    length = node_s[first + 1] - node_s[first]
    plank_widths = np.array([beam_length_width(p, c)[1] for p, c in zip(planks, crosswise)],
                            dtype=float)
    plank_thickness = np.array([p.thickness for p in planks], dtype=float)
    plank_frames = np.array(frames, dtype=float).reshape(-1, 3, 3)
    moduli = np.array([(m.elastic_modulus, m.shear_modulus) for m in materials],
                      dtype=float).reshape(-1, 2)[plank]
    return length, plank_widths[plank], plank_thickness[plank], moduli, plank_frames


def _beams(planks: list[Plank], frames: list[np.ndarray], node_plank: np.ndarray,
           node_s: np.ndarray, halves: np.ndarray, materials: list[Material], origins: tuple,
           crosswise: tuple[bool, ...]) -> Beams:
    """The elements between consecutive nodes of each plank (``materials``: each plank's,
    ``Design.material_of``)."""
    first, nodes, plank = _element_nodes(node_plank)
    length, widths, thickness, moduli, plank_frames = _element_inputs(
        planks, frames, plank, node_s, first, materials, crosswise)
    local = beam_stiffness_local(length, widths, thickness, moduli[:, 0],
                                 moduli[:, 1]).reshape(-1, 12, 12)
    return Beams(plank=plank, nodes=nodes, length=length, frames=plank_frames[plank],
                 local_stiffness=local, width=widths, thickness=thickness,
                 elastic_modulus=moduli[:, 0], shear_modulus=moduli[:, 1], node_s=node_s,
                 plank_half=halves, origins=origins, crosswise=crosswise,
                 plank_frames=plank_frames)


def _element_dofs(beams: Beams) -> np.ndarray:
    """(nE, 12) the global DOF numbers of each element's two nodes."""
    return (6 * beams.nodes[:, :, None] + _SIX[None, None, :]).reshape(-1, 12)


def assemble_beams(beams: Beams, n_nodes: int) -> sp.csr_matrix:
    """K_b = sum T^T K_local T over the elements, (6 nN, 6 nN) sparse."""
    import scipy.sparse as sp

    world, rows, cols = _element_entries(beams)
    n = 6 * n_nodes
    return sp.csr_matrix((world.ravel(), (rows.ravel(), cols.ravel())), shape=(n, n))


def assemble_beams_dense(beams: Beams, position: np.ndarray) -> np.ndarray:
    """K_b as ``assemble_beams`` gives it, dense, with node k's rows and columns at block
    ``position[k]`` (a permutation of the nodes), for designs small enough for dense
    matrices.  An entry sums the terms of at most two elements (the two that meet at a
    node, on its diagonal block), and a sum of two terms does not depend on their order,
    so the matrix is the sparse one's to the last bit."""
    world, rows, cols = _element_entries(beams)
    n_dof = 6 * len(position)
    block = 6 * np.asarray(position)
    rows = (block[rows // 6] + rows % 6).ravel()
    cols = (block[cols // 6] + cols % 6).ravel()
    return block_sums(rows * n_dof + cols, world.reshape(-1, 1), n_dof * n_dof) \
        .reshape(n_dof, n_dof)


def _element_entries(beams: Beams) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(T^T K_local T (nE, 12, 12), the global row and the column of each of its
    entries, each (nE, 12, 12))."""
    T = beams.transform()
    world = np.transpose(T, (0, 2, 1)) @ beams.local_stiffness @ T
    dofs = _element_dofs(beams)
    rows = np.broadcast_to(dofs[:, :, None], world.shape)
    cols = np.broadcast_to(dofs[:, None, :], world.shape)
    return world, rows, cols


def element_end_forces(beams: Beams, q: np.ndarray) -> np.ndarray:
    """(nE, 12) each element's end forces K_local T u in its own axes for node
    displacements q (6 nN,): T u is each end's displacement and rotation in the element's
    axes, R^T u."""
    u = q.reshape(-1, 6)[beams.nodes].reshape(-1, 4, 3)               # u_a, theta_a, u_b, ...
    return np.einsum("eab,eb->ea", beams.local_stiffness, (u @ beams.frames).reshape(-1, 12))


def element_forces(beams: Beams, q: np.ndarray, n_nodes: int) -> np.ndarray:
    """(6 nN,) K_b q without assembling K_b: each element's end forces
    (``element_end_forces``) turned back to the world (T^T) and summed at its nodes."""
    local = element_end_forces(beams, q)
    world = local.reshape(-1, 4, 3) @ np.transpose(beams.frames, (0, 2, 1))
    return block_sums(beams.nodes.ravel(), world.reshape(-1, 6), n_nodes).ravel()


def _weights_per_length(design: Design, planks: list[Plank], beams: Beams) -> np.ndarray:
    """(nE, 3) N/m: each element's share of its plank's weight, spread along the plank."""
    per_plank = np.array([-design.plank_mass(plank) * tol.GRAVITY
                          / beam_length_width(plank, crosswise)[0]
                          for plank, crosswise in zip(planks, beams.crosswise)], dtype=float)
    loads = np.zeros((len(beams.plank), 3))
    loads[:, 2] = per_plank[beams.plank]
    return loads


def _element_loads_local(beams: Beams, loads: np.ndarray) -> np.ndarray:
    """(nE, 12) consistent nodal loads of uniform world loads (nE, 3) N/m, local axes."""
    local_loads = np.einsum("eab,ea->eb", beams.frames, loads)          # R^T q
    return uniform_load_local(beams.length, local_loads).reshape(-1, 12)


def _element_world_loads(frames: np.ndarray, length: np.ndarray,
                         loads: np.ndarray) -> np.ndarray:
    """(nE, 12) T^T f: the consistent nodal loads of uniform loads (nE, 3) N/m along
    elements of axes ``frames`` (nE, 3, 3) and lengths (nE,), world axes (the arithmetic
    of ``_nodal_loads``, element by element)."""
    local_loads = np.einsum("eab,ea->eb", frames, loads)                 # R^T q
    f_local = uniform_load_local(length, local_loads).reshape(-1, 12)
    T = np.zeros((len(length), 12, 12))
    for block in range(4):
        T[:, 3 * block:3 * block + 3, 3 * block:3 * block + 3] = np.transpose(frames, (0, 2, 1))
    return np.einsum("eba,eb->ea", T, f_local)


def _nodal_loads(beams: Beams, loads: np.ndarray, n_nodes: int) -> np.ndarray:
    """(6 nN,) the consistent nodal loads of uniform loads (nE, 3) N/m along the elements."""
    f_local = _element_loads_local(beams, loads)
    world = np.einsum("eba,eb->ea", beams.transform(), f_local)         # T^T f
    f = np.zeros(6 * n_nodes)
    np.add.at(f, _element_dofs(beams).ravel(), world.ravel())
    return f


def case_line_loads(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(nE, 3) N/m: self-weight and the case's spread loads along each element."""
    weights = model.plank_cache.get("weights_per_length")
    if weights is None:
        plank_list = [model.design.planks[i] for i in model.planks]
        weights = _weights_per_length(model.design, plank_list, model.beams)
    return weights + _spread_line_loads(model, case)


def _spread_line_loads(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(nE, 3) N/m: the case's spread loads, each along its plank's whole beam (kept per
    model and case, read-only: the forces and the planks' results both read them)."""
    kept = model.plank_cache.get(("spread", id(case)))
    if kept is not None and kept[0] is case:
        return kept[1]
    loads = _read_only(_spread_line_loads_of(model, case))
    model.plank_cache[("spread", id(case))] = (case, loads)
    return loads


def _spread_line_loads_of(model: StaticsModel, case: LoadCase) -> np.ndarray:
    beams, local = model.beams, model.local_planks
    loads = np.zeros((len(beams.plank), 3))
    for load in case.loads:
        if load.spread and load.plank in local:
            k = local[load.plank]
            plank = model.design.planks[model.planks[k]]
            span = beam_length_width(plank, beams.crosswise[k])[0]
            loads[beams.plank == k] += np.asarray(load.force, dtype=float) / span
    return loads


def elastic_forces(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(6 nN,) self-weight and spread loads as consistent nodal loads along the beams, and
    every other load at the node of its point (its plank's centre when it has none), with
    its moment about that node."""
    f = model.self_weight.copy()
    local = model.local_planks
    if any(load.spread and load.plank in local for load in case.loads):
        f += _nodal_loads(model.beams, _spread_line_loads(model, case), model.n_nodes)
    nodes, forces, points = [], [], []
    for index, load in enumerate(case.loads):
        if load.spread or load.plank not in local:
            continue
        plank = model.design.planks[model.planks[local[load.plank]]]
        point = plank.center if load.point is None else load.point
        node = model.load_nodes.get((case.name, index))
        if node is None:        # a case built after the model: the nearest node
            node = _node_of(model, local[load.plank], point)
        nodes.append(node)
        forces.append(load.force)
        points.append(point)
    if nodes:
        nodes = np.array(nodes, dtype=int)
        add_point_loads(f, nodes, model.node_points[nodes],
                        np.array(forces, dtype=float), np.array(points, dtype=float))
    return f


def _node_of(model: StaticsModel, k: int, point) -> int:
    """The node of local plank k nearest the projection of ``point`` on its axis."""
    members = np.flatnonzero(model.node_plank == k)
    plank = model.design.planks[model.planks[k]]
    axis = beam_frame(plank, model.beams.crosswise[k])[:, 0]
    s = float((np.asarray(point, dtype=float) - plank.center_array) @ axis)
    return int(members[np.argmin(np.abs(model.beams.node_s[members] - s))])
