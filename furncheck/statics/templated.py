"""Elastic models of small edits built on a template (the force sensitivity's stepped
designs): the model of a design whose joints, contacts and loads are the template's, its
nodes kept, each at the new place of what it serves, so that the two models' unknowns
correspond.  What depends only on which joints, contacts and loads there are is taken
from the template (``Attachments``, the node layout, ``TOPOLOGY_CACHE``); every number
that depends on where things are is computed as ``elastic.build_elastic_model`` computes
it, for the elements of several models at once (``build_elastic_models``).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.geometry import Geometry
from furncheck.statics.beams import (
    beam_frame,
    beam_length_width,
    beam_stiffness_local,
    nail_row_parts,
    part_points,
)
from furncheck.statics.elements import (
    Beams,
    element_dofs,
    element_inputs,
    element_nodes,
    element_world_loads,
    read_only,
    weights_per_length,
)
from furncheck.statics.model import StaticsModel
from furncheck.statics.offsets import (
    anchored_contacts,
    contact_frames,
    in_contact_frames,
    joint_deviation_blocks,
    point_maps,
    rest_maps,
)
from furncheck.statics.stations import station_places

TOPOLOGY_CACHE = ("carrying", "lying", "supports")
"""The entries of ``StaticsModel.plank_cache`` (filled by ``bending``) that depend on which
planks are jointed and which contacts stand, not on where: a model built on a template
(the same joints and contacts) shares them, as it shares its node layout
("node_layout", ``elastic._NodeLayout``)."""


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class Attachments:
    """What a model built on a template (``built_on``) takes over of how the template's
    attachments were listed: each row's local plank (joints' two sides, contacts, resting
    corners' other planks, loads at a point), the contact rows of the resting corners and
    the (case, load) numbers of the loads, in that order."""

    owners: np.ndarray
    rest_rows: tuple[int, ...]
    loads: tuple[tuple[int, int], ...]


def built_on(design: Design, geometry: Geometry, template: StaticsModel) -> StaticsModel:
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
        from furncheck.statics.elastic import build_elastic_model  # it builds on this module

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


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
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
    joint_points: np.ndarray       # the joints' springs' points (``beams.part_points``)
    part_arms: np.ndarray
    contact_points: np.ndarray     # the corners', then the support stations'
    materials: list
    station_shares: np.ndarray | None


def _placed_on(design: Design, geometry: Geometry, template: StaticsModel) -> _Placed:
    """The nodes of a model of ``design`` built on ``template``, each at the new place of
    what it serves (the node layout's ``positions``)."""
    joints, contacts = template.joints, template.contacts
    attachments: Attachments = template.plank_cache["attachments"]
    plank_list = [design.planks[i] for i in template.planks]
    crosswise = template.beams.crosswise
    frames = [beam_frame(p, c) for p, c in zip(plank_list, crosswise)]
    halves = np.array([0.5 * beam_length_width(p, c)[0]
                       for p, c in zip(plank_list, crosswise)])
    joint_points, arms = part_points([geometry.joints[j] for j in joints],
                                     template.plank_cache["joint_part_counts"])
    contact_points = [geometry.contacts[c].point for c in contacts[:template.n_corners]]
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
    corners = np.array(contact_points, dtype=float).reshape(-1, 3)
    station_points, shares = station_places(template.plank_cache["support_stations"],
                                            corners, node_s, node_plank, centres, axes)
    return _Placed(design, geometry, plank_list, frames, halves, node_s, node_points,
                   joint_points, arms, np.vstack([corners, station_points]),
                   [design.material_of(p) for p in plank_list],
                   shares if template.station_shares is not None else None)


def _finished_on(placed: list[_Placed], template: StaticsModel) -> list[StaticsModel]:
    """The models of designs placed on ``template`` (``_placed_on``), their element,
    joint and contact arithmetic done for all of them at once (the same numbers as one
    model at a time: see ``build_elastic_models``)."""
    count = len(placed)
    node_plank = template.plank_cache["node_layout"].node_plank
    first, nodes, plank = element_nodes(node_plank)
    inputs = [element_inputs(p.plank_list, p.frames, plank, p.node_s, first, p.materials,
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
    weights = [read_only(weights_per_length(p.design, p.plank_list, b))
               for p, b in zip(placed, beams)]
    world = np.split(element_world_loads(np.concatenate([b.frames for b in beams]),
                                          length, np.concatenate(weights)), count)
    dofs = element_dofs(beams[0]).ravel()
    joint_nodes, contact_node = template.joint_nodes, template.contact_node
    joint_blocks = np.split(joint_deviation_blocks(
        np.concatenate([p.joint_points for p in placed]),
        np.concatenate([p.node_points[joint_nodes] for p in placed])), count)
    offsets = np.split(point_maps(np.concatenate(
        [p.contact_points - p.node_points[contact_node].reshape(-1, 3) for p in placed])),
        count)
    materials = {(p.design.material.nail_slip, p.design.material.nail_withdrawal)
                 for p in placed}
    part_counts = template.plank_cache["joint_part_counts"]
    if len(materials) == 1:
        ((slip, withdrawal),) = materials
        springs = np.split(nail_row_parts(
            [p.geometry.joints[j] for p in placed for j in template.joints],
            np.tile(part_counts, count), slip, withdrawal)[0], count)
    else:
        springs = [nail_row_parts([p.geometry.joints[j] for j in template.joints],
                                  part_counts, p.design.material.nail_slip,
                                  p.design.material.nail_withdrawal)[0] for p in placed]
    compliance = np.split(np.linalg.inv(np.concatenate(springs)), count) \
        if template.n_springs else [np.zeros((0, 6, 6))] * count
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
            beams=beams[k], nodal_weight=nodal_weight, load_nodes=template.load_nodes,
            joint_parts=template.joint_parts,
            part_arms=None if template.joint_parts is None else p.part_arms,
            station_corners=template.station_corners, station_shares=p.station_shares)
        model.__dict__["joint_compliance"] = compliance[k]     # its cached property's value
        for key in ("node_layout", "attachments", "joint_part_counts", "support_stations",
                    *TOPOLOGY_CACHE):
            if key in template.plank_cache:
                model.plank_cache[key] = template.plank_cache[key]
        model.plank_cache["weights_per_length"] = weights[k]
        models.append(model)
    return models
