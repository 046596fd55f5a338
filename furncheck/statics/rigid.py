"""The rigid model (``model: rigid``, paper section 5.1): one node per plank at its centre,
nail joints as stiff 6-DOF penalty springs, ground contacts as penalty springs with
friction anchors.
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.geometry import Geometry
from furncheck.statics.model import _SIX, StaticsModel, grounded_parts
from furncheck.statics.offsets import (
    anchored_contacts,
    contact_frames,
    in_contact_frames,
    joint_deviation_blocks,
    point_maps,
    rest_maps,
)


def build_rigid_model(design: Design, geometry: Geometry) -> StaticsModel:
    """Assemble G, the compliances and the contact maps of rigid planks, one node each at
    its centre."""
    grounded_planks, joints, contacts, components = grounded_parts(design, geometry)
    local = {plank: k for k, plank in enumerate(grounded_planks)}
    centres = np.array([design.planks[i].center_array for i in grounded_planks],
                       dtype=float).reshape(-1, 3)
    joint_nodes = np.array([[local[design.plank_index[p]] for p in geometry.joints[j].planks]
                            for j in joints], dtype=int).reshape(-1, 2)
    points = np.array([geometry.joints[j].point for j in joints], dtype=float).reshape(-1, 3)
    joint_blocks = joint_deviation_blocks(points, centres[joint_nodes])
    thickness = np.array([geometry.joints[j].edge_thickness for j in joints], dtype=float)
    stiffness = np.zeros((len(joints), 6, 6))
    stiffness[:, _SIX[:3], _SIX[:3]] = 1.0 / tol.JOINT_COMPLIANCE_T
    stiffness[:, _SIX[3:], _SIX[3:]] = 1.0 / tol.joint_compliance_r(thickness)[:, None]

    owner = np.array([local[design.plank_index[geometry.contacts[k].plank]] for k in contacts],
                     dtype=int)
    contact_points = np.array([geometry.contacts[k].point for k in contacts],
                              dtype=float).reshape(-1, 3)
    component_of = {p: c for c, comp in enumerate(components) for p in comp}
    frames = contact_frames(design, geometry, contacts)
    resting = [geometry.contacts[k].on for k in contacts]
    rest_node = None if all(on is None for on in resting) else np.array(
        [-1 if on is None else local[design.plank_index[on]] for on in resting], dtype=int)
    return StaticsModel(
        design=design, geometry=geometry, planks=tuple(grounded_planks), joints=tuple(joints),
        contacts=tuple(contacts), node_plank=np.arange(len(grounded_planks)),
        node_points=centres, joint_nodes=joint_nodes, joint_blocks=joint_blocks,
        joint_stiffness=stiffness,
        contact_maps=in_contact_frames(point_maps(contact_points - centres[owner].reshape(-1, 3)),
                                       frames),
        contact_node=owner, contact_plank=owner, contact_points=contact_points,
        contact_component=np.array([component_of[p] for p in owner], dtype=int),
        components=components, friction=design.material.friction, contact_frames=frames,
        contact_anchored=anchored_contacts(geometry, contacts), rest_node=rest_node,
        rest_maps=rest_maps(rest_node, contact_points, centres, frames))
