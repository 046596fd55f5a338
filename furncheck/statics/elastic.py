"""Elastic planks (contract section 3a): the statics model of ``model: elastic``.

Each plank is a Timoshenko beam along its longer in-plane axis e1, with e2 the other
in-plane axis (the section's width b) and e3 its face normal (the thickness t), cut into
elements at nodes on that axis wherever a joint, a ground contact or a load acts (at the
projection of its point), at the plank's ends and centre, and at least every
1 / BEAM_SEGMENTS of its length.  What acts off the axis is tied to its node by a rigid
offset (``point_maps``, ``joint_deviation_blocks``): a leg under a table top's corner
twists the top.  A nail joint is a spring between its two planks' nodes, from its nail
row (``joint_springs``); ground contacts are stiff unilateral springs with friction
anchors (ELASTIC_CONTACT_STIFFNESS).  The model is a ``StaticsModel`` like the rigid
one: the same mixed system, with the beams' stiffness K_b in its plank block, and the
same contact loop.  After the solve, ``plank_results`` gives each plank's sag (from the
straight line through its outermost supports, or from the tangent at the one end that
holds it) and its largest bending plus axial stress.

Elements (local axes e1, e2, e3; displacements u and rotations theta per node, theta_3 =
du_2/ds, theta_2 = -du_3/ds): axial E A / L, torsion G J / L (J of a rectangle, Roark),
and in each bending plane the Timoshenko element with Phi = 12 E I / (k G A L^2), k = 5/6
(Przemieniecki): its nodal values are exact for end loads and, with the consistent
nodal loads used here, for a uniform load along it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase, Plank
from furncheck.geometry import Geometry, Joint
from furncheck.statics.model import (
    _SIX,
    StaticsModel,
    add_point_load,
    grounded_parts,
    joint_deviation_blocks,
    point_maps,
)

SHEAR_FACTOR = 5.0 / 6.0
"""Timoshenko's shear correction of a rectangular section."""


# --- elements, pure functions of geometry and material ---------------------------------------

def section_properties(width, thickness) -> dict:
    """Section of a plank as a beam (floats or arrays): area A, I_2 = b t^3 / 12 (bending
    out of its plane, about e2: the sag of a shelf), I_3 = t b^3 / 12 (in its plane, about
    e3) and the torsion constant of a rectangle, J = a c^3 (1/3 - 0.21 (c/a) (1 - c^4 /
    (12 a^4))), a >= c its sides (Roark, Formulas for Stress and Strain, table 10.7)."""
    a, c = np.maximum(width, thickness), np.minimum(width, thickness)
    return {"A": width * thickness,
            "I2": width * thickness ** 3 / 12.0,
            "I3": thickness * width ** 3 / 12.0,
            "J": a * c ** 3 * (1.0 / 3.0 - 0.21 * (c / a) * (1.0 - c ** 4 / (12.0 * a ** 4)))}


def beam_stiffness_local(length, width, thickness, elastic_modulus: float,
                         shear_modulus: float) -> np.ndarray:
    """(12, 12) stiffness of a Timoshenko beam element in its local axes, DOFs per node
    (u1, u2, u3, theta1, theta2, theta3), node 1 then node 2 (N/m, N, N m); (n, 12, 12)
    for arrays of n lengths, widths and thicknesses."""
    L, b, t = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (length, width, thickness))
    section = section_properties(b, t)
    E, G = elastic_modulus, shear_modulus
    shear_area = SHEAR_FACTOR * section["A"]
    K = np.zeros((len(L), 12, 12))

    def put(i: int, j: int, value: np.ndarray) -> None:
        K[:, i, j] = value
        K[:, j, i] = value

    axial, torsion = E * section["A"] / L, G * section["J"] / L
    for i, j, value in ((0, 0, axial), (6, 6, axial), (0, 6, -axial),
                        (3, 3, torsion), (9, 9, torsion), (3, 9, -torsion)):
        put(i, j, value)
    # (deflection, rotation, sign of the coupling): plane 1-2 (u2, theta3), plane 1-3 (u3,
    # theta2), where theta3 = du2/ds but theta2 = -du3/ds
    for w, r, inertia, sign in ((1, 5, section["I3"], 1.0), (2, 4, section["I2"], -1.0)):
        phi = 12.0 * E * inertia / (shear_modulus * shear_area * L * L)
        c = E * inertia / (L ** 3 * (1.0 + phi))
        for i, j, value in ((w, w, 12.0), (w + 6, w + 6, 12.0), (w, w + 6, -12.0),
                            (w, r, sign * 6.0 * L), (w, r + 6, sign * 6.0 * L),
                            (w + 6, r, -sign * 6.0 * L), (w + 6, r + 6, -sign * 6.0 * L),
                            (r, r, (4.0 + phi) * L * L), (r + 6, r + 6, (4.0 + phi) * L * L),
                            (r, r + 6, (2.0 - phi) * L * L)):
            put(i, j, value * c)
    return K[0] if np.ndim(length) == 0 else K


def uniform_load_local(length, load: np.ndarray) -> np.ndarray:
    """(12,) consistent nodal loads of a uniform load ``load`` (3,) N/m along a beam element,
    in its local axes: q L / 2 at each node and end moments q L^2 / 12 (signs of theta_3 =
    du2/ds, theta_2 = -du3/ds); (n, 12) for n lengths and loads (n, 3)."""
    L = np.atleast_1d(np.asarray(length, dtype=float))
    q = np.asarray(load, dtype=float).reshape(-1, 3)
    f = np.zeros((len(L), 12))
    f[:, 0] = f[:, 6] = q[:, 0] * L / 2.0
    f[:, 1] = f[:, 7] = q[:, 1] * L / 2.0
    f[:, 5], f[:, 11] = q[:, 1] * L * L / 12.0, -q[:, 1] * L * L / 12.0
    f[:, 2] = f[:, 8] = q[:, 2] * L / 2.0
    f[:, 4], f[:, 10] = -q[:, 2] * L * L / 12.0, q[:, 2] * L * L / 12.0
    return f[0] if np.ndim(length) == 0 else f


def nail_row_spread(length: float, nails: int) -> float:
    """m^2: S = sum y_i^2 of a joint's nails (contract section 3); a one-nail joint uses
    S = L^2 / 12 of its contact region (contract section 3a: never zero)."""
    if nails <= 1:
        return length * length / 12.0
    return length * length * (nails * nails - 1.0) / (12.0 * nails)


def joint_springs(joint: Joint, nail_slip: float, nail_withdrawal: float) -> np.ndarray:
    """(6, 6) world-frame stiffness W of a nail joint (wrench = W deviation), from its n
    nails in the joint frame (x, y the joint line, n the nail axis; contract 3a): along n
    n k_w, across it n k_s; rotation about y n k_w (t/2)^2, about x k_w S, about n k_s S."""
    n = float(joint.nails)
    spread = nail_row_spread(joint.length, joint.nails)
    half = 0.5 * joint.edge_thickness
    frame = np.asarray(joint.frame, dtype=float)
    translation = np.diag([n * nail_slip, n * nail_slip, n * nail_withdrawal])
    rotation = np.diag([nail_withdrawal * spread, n * nail_withdrawal * half * half,
                        nail_slip * spread])
    W = np.zeros((6, 6))
    W[:3, :3] = frame @ translation @ frame.T
    W[3:, 3:] = frame @ rotation @ frame.T
    return W


def along_width(plank: Plank) -> bool:
    """Whether the plank's beam runs along its local y (its width is the longer side; on a
    tie it runs along local x)."""
    return plank.width > plank.length


def beam_frame(plank: Plank, crosswise: bool | None = None) -> np.ndarray:
    """(3, 3) columns e1 (the beam axis: the plank's longer in-plane axis, or local y when
    ``crosswise``), e2 (the other in-plane axis), e3 (the face normal), world frame."""
    axes = plank.rotation_matrix
    if not (along_width(plank) if crosswise is None else crosswise):
        return axes.copy()
    return np.column_stack([axes[:, 1], -axes[:, 0], axes[:, 2]])


def beam_length_width(plank: Plank, crosswise: bool | None = None) -> tuple[float, float]:
    """(beam length, section width) of the plank (m), as ``beam_frame``."""
    if not (along_width(plank) if crosswise is None else crosswise):
        return plank.length, plank.width
    return plank.width, plank.length


# --- the model ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class Beams:
    """The beam elements of an elastic model.

    plank, nodes : (nE,) local plank and (nE, 2) local nodes of each element
    length   : (nE,) m
    frames   : (nE, 3, 3) columns e1, e2, e3 (world)
    local_stiffness : (nE, 12, 12) in the element's axes
    width, thickness : (nE,) m, the section
    node_s   : (nN,) m, each node's position along its plank's axis from the centre
    plank_half : (nP,) m, half the beam length of each plank
    origins  : per node, its local plank and the keys of what it serves (``_plank_nodes``)
    crosswise : per plank, whether its beam runs along its local y (``along_width``)
    """

    plank: np.ndarray
    nodes: np.ndarray
    length: np.ndarray
    frames: np.ndarray
    local_stiffness: np.ndarray
    width: np.ndarray
    thickness: np.ndarray
    node_s: np.ndarray
    plank_half: np.ndarray
    origins: tuple = ()
    crosswise: tuple = ()

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
    nodes = [(float(np.mean(positions)), tuple(keys)) for _, keys, positions in groups]
    placed = np.array([s for s, _ in nodes])
    for i in range(1, tol.BEAM_SEGMENTS):
        s = -half + i * step
        if np.abs(placed - s).min() > 0.25 * step:
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


def build_elastic_model(design: Design, geometry: Geometry,
                        template: StaticsModel | None = None) -> StaticsModel:
    """The elastic ``StaticsModel`` of the grounded components (see the module docstring).

    ``template``: a model of the same design before a small edit (the same joints,
    contacts and loads): its nodes are kept, each at the new place of what it serves, so
    that the two models' unknowns correspond (the force sensitivity differences them)."""
    material = design.material
    planks_used, joints, contacts, components = grounded_parts(design, geometry)
    local = {plank: k for k, plank in enumerate(planks_used)}
    plank_list = [design.planks[i] for i in planks_used]
    crosswise = _crosswise(design, geometry, plank_list, joints, contacts) \
        if template is None else template.beams.crosswise
    frames = [beam_frame(p, c) for p, c in zip(plank_list, crosswise)]
    halves = np.array([0.5 * beam_length_width(p, c)[0]
                       for p, c in zip(plank_list, crosswise)])

    def along(k: int, point) -> float:
        return float((np.asarray(point, dtype=float) - plank_list[k].center_array)
                     @ frames[k][:, 0])

    position: dict[tuple, float] = {}      # attachment key -> s along its plank
    owner_of: dict[tuple, int] = {}
    for row, j in enumerate(joints):
        joint = geometry.joints[j]
        for side, plank_id in enumerate(joint.planks):
            k = local[design.plank_index[plank_id]]
            position[("joint", row, side)], owner_of[("joint", row, side)] = \
                along(k, joint.point), k
    for row, c in enumerate(contacts):
        k = local[design.plank_index[geometry.contacts[c].plank]]
        position[("contact", row)], owner_of[("contact", row)] = \
            along(k, geometry.contacts[c].point), k
    for ci, case in enumerate(design.load_cases):
        for li, load in enumerate(case.loads):
            k = local.get(design.plank_index[load.plank])
            if k is not None and load.point is not None and not load.spread:
                position[("load", ci, li)], owner_of[("load", ci, li)] = along(k, load.point), k

    if template is None:
        attachments: list[list] = [[] for _ in plank_list]
        for key, s in position.items():
            attachments[owner_of[key]].append((s, key))
        origins = [origin for k in range(len(plank_list))
                   for origin in _plank_nodes(k, float(halves[k]), attachments[k])]
    else:
        origins = list(template.beams.origins)

    def place(key: tuple) -> float:
        if key[0] == "end":
            return key[2] * float(halves[key[1]])
        if key[0] == "centre":
            return 0.0
        if key[0] == "grid":
            return (2.0 * key[2] - 1.0) * float(halves[key[1]])
        return min(max(position[key], -halves[owner_of[key]]), halves[owner_of[key]])

    node_plank = np.array([origin[0] for origin in origins], dtype=int)
    node_s = np.array([float(np.mean([place(key) for key in origin[1:]]))
                       for origin in origins])
    node_of = {key: node for node, origin in enumerate(origins) for key in origin[1:]}
    node_points = np.array([plank_list[k].center_array + s * frames[k][:, 0]
                            for k, s in zip(node_plank, node_s)]).reshape(-1, 3)
    beams = _beams(plank_list, frames, node_plank, node_s, halves, material, tuple(origins),
                   crosswise)

    joint_nodes = np.array([[node_of[("joint", row, side)] for side in (0, 1)]
                            for row in range(len(joints))], dtype=int).reshape(-1, 2)
    points = np.array([geometry.joints[j].point for j in joints], dtype=float).reshape(-1, 3)
    joint_blocks = joint_deviation_blocks(points, node_points[joint_nodes])
    stiffness = np.array([joint_springs(geometry.joints[j], material.nail_slip,
                                        material.nail_withdrawal) for j in joints],
                         dtype=float).reshape(-1, 6, 6)

    owner = np.array([owner_of[("contact", row)] for row in range(len(contacts))], dtype=int)
    contact_points = np.array([geometry.contacts[c].point for c in contacts],
                              dtype=float).reshape(-1, 3)
    contact_node = np.array([node_of[("contact", row)] for row in range(len(contacts))],
                            dtype=int)
    load_nodes = {(case.name, li): node_of.get(("load", ci, li), node_of[("centre", k)])
                  for ci, case in enumerate(design.load_cases)
                  for li, load in enumerate(case.loads)
                  if (k := local.get(design.plank_index[load.plank])) is not None}
    component_of = {p: c for c, comp in enumerate(components) for p in comp}
    return StaticsModel(
        design=design, geometry=geometry, planks=tuple(planks_used), joints=tuple(joints),
        contacts=tuple(contacts), node_plank=node_plank, node_points=node_points,
        joint_nodes=joint_nodes, joint_blocks=joint_blocks, joint_stiffness=stiffness,
        contact_maps=point_maps(contact_points - node_points[contact_node].reshape(-1, 3)),
        contact_node=contact_node, contact_plank=owner, contact_points=contact_points,
        contact_component=np.array([component_of[p] for p in owner], dtype=int),
        components=components, friction=material.friction,
        contact_stiffness=tol.ELASTIC_CONTACT_STIFFNESS, kind="elastic",
        beam_stiffness=_assemble(beams, len(node_plank)), beams=beams,
        nodal_weight=_nodal_loads(beams, _weights_per_length(design, plank_list, beams),
                                  len(node_plank)),
        load_nodes=load_nodes)


def _beams(planks: list[Plank], frames: list[np.ndarray], node_plank: np.ndarray,
           node_s: np.ndarray, halves: np.ndarray, material, origins: tuple,
           crosswise: tuple[bool, ...]) -> Beams:
    """The elements between consecutive nodes of each plank."""
    same = node_plank[1:] == node_plank[:-1]
    first = np.flatnonzero(same)
    nodes = np.column_stack([first, first + 1])
    plank = node_plank[first]
    length = node_s[first + 1] - node_s[first]
    widths = np.array([beam_length_width(planks[k], crosswise[k])[1] for k in plank],
                      dtype=float)
    thickness = np.array([planks[k].thickness for k in plank], dtype=float)
    local = beam_stiffness_local(length, widths, thickness, material.elastic_modulus,
                                 material.shear_modulus).reshape(-1, 12, 12)
    return Beams(plank=plank, nodes=nodes, length=length,
                 frames=np.array([frames[k] for k in plank]).reshape(-1, 3, 3),
                 local_stiffness=local, width=widths, thickness=thickness, node_s=node_s,
                 plank_half=halves, origins=origins, crosswise=crosswise)


def _element_dofs(beams: Beams) -> np.ndarray:
    """(nE, 12) the global DOF numbers of each element's two nodes."""
    return (6 * beams.nodes[:, :, None] + _SIX[None, None, :]).reshape(-1, 12)


def _assemble(beams: Beams, n_nodes: int) -> sp.csr_matrix:
    """K_b = sum T^T K_local T over the elements, (6 nN, 6 nN) sparse."""
    T = beams.transform()
    world = np.transpose(T, (0, 2, 1)) @ beams.local_stiffness @ T
    dofs = _element_dofs(beams)
    rows = np.broadcast_to(dofs[:, :, None], world.shape).ravel()
    cols = np.broadcast_to(dofs[:, None, :], world.shape).ravel()
    n = 6 * n_nodes
    return sp.csr_matrix((world.ravel(), (rows, cols)), shape=(n, n))


def _weights_per_length(design: Design, planks: list[Plank], beams: Beams) -> np.ndarray:
    """(nE, 3) N/m: each element's share of its plank's weight, spread along the plank."""
    loads = np.zeros((len(beams.plank), 3))
    for e, k in enumerate(beams.plank):
        plank = planks[k]
        loads[e, 2] = -design.plank_mass(plank) * tol.GRAVITY \
            / beam_length_width(plank, beams.crosswise[k])[0]
    return loads


def _element_loads_local(beams: Beams, loads: np.ndarray) -> np.ndarray:
    """(nE, 12) consistent nodal loads of uniform world loads (nE, 3) N/m, local axes."""
    local_loads = np.einsum("eab,ea->eb", beams.frames, loads)          # R^T q
    return uniform_load_local(beams.length, local_loads).reshape(-1, 12)


def _nodal_loads(beams: Beams, loads: np.ndarray, n_nodes: int) -> np.ndarray:
    """(6 nN,) the consistent nodal loads of uniform loads (nE, 3) N/m along the elements."""
    f_local = _element_loads_local(beams, loads)
    world = np.einsum("eba,eb->ea", beams.transform(), f_local)         # T^T f
    f = np.zeros(6 * n_nodes)
    np.add.at(f, _element_dofs(beams).ravel(), world.ravel())
    return f


def case_line_loads(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(nE, 3) N/m: self-weight and the case's spread loads along each element."""
    beams, design = model.beams, model.design
    plank_list = [design.planks[i] for i in model.planks]
    loads = _weights_per_length(design, plank_list, beams)
    local = model.local_planks
    for load in case.loads:
        if load.spread and load.plank in local:
            k = local[load.plank]
            span = beam_length_width(plank_list[k], beams.crosswise[k])[0]
            loads[beams.plank == k] += np.asarray(load.force, dtype=float) / span
    return loads


def elastic_forces(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(6 nN,) self-weight and spread loads as consistent nodal loads along the beams, and
    every other load at the node of its point (its plank's centre when it has none), with
    its moment about that node."""
    beams = model.beams
    f = model.self_weight.copy()
    local = model.local_planks
    spread = [load for load in case.loads if load.spread and load.plank in local]
    if spread:
        plank_list = [model.design.planks[i] for i in model.planks]
        loads = np.zeros((len(beams.plank), 3))
        for load in spread:
            k = local[load.plank]
            loads[beams.plank == k] += (np.asarray(load.force, dtype=float)
                                        / beam_length_width(plank_list[k],
                                                            beams.crosswise[k])[0])
        f += _nodal_loads(beams, loads, model.n_nodes)
    for index, load in enumerate(case.loads):
        if load.spread or load.plank not in local:
            continue
        plank = model.design.planks[model.planks[local[load.plank]]]
        node = model.load_nodes.get((case.name, index))
        if node is None:        # a case built after the model: the nearest node
            node = _node_of(model, local[load.plank],
                            plank.center if load.point is None else load.point)
        add_point_load(f, node, model.node_points[node],
                       load if load.point is not None else _at(load, plank.center))
    return f


def _at(load, point):
    """The load acting at ``point`` (a load without point acts at its plank's centre)."""
    from dataclasses import replace

    return replace(load, point=tuple(float(v) for v in point))


def _node_of(model: StaticsModel, k: int, point) -> int:
    """The node of local plank k nearest the projection of ``point`` on its axis."""
    members = np.flatnonzero(model.node_plank == k)
    plank = model.design.planks[model.planks[k]]
    axis = beam_frame(plank, model.beams.crosswise[k])[:, 0]
    s = float((np.asarray(point, dtype=float) - plank.center_array) @ axis)
    return int(members[np.argmin(np.abs(model.beams.node_s[members] - s))])


# --- results: sag and stress ----------------------------------------------------------------------

@dataclass(frozen=True)
class PlankStatics:
    """Per local plank of an elastic model, for one load case (SI).

    sag    : (nP,) m, the largest deflection of its own bending (contract section 3a)
    span   : (nP,) m, between its outermost supports (twice the overhang of a cantilever);
             0 when it has no support to measure from
    stress : (nP,) Pa, the largest |M_2| / (b t^2 / 6) + |M_3| / (t b^2 / 6) + |N| / (b t)
    """

    sag: np.ndarray
    span: np.ndarray
    stress: np.ndarray


def plank_results(model: StaticsModel, case: LoadCase, q: np.ndarray,
                  holding: np.ndarray | None = None) -> PlankStatics:
    """Sag, span and stress of every plank for node displacements ``q`` (6 nN,) of the
    case; ``holding`` (nK,) bool: the contacts that carry (all when None)."""
    beams = model.beams
    n_planks = len(model.planks)
    T = beams.transform()
    u = q.reshape(-1, 6)[beams.nodes].reshape(-1, 12)
    local = np.einsum("eab,eb->ea", T, u)
    line_loads = case_line_loads(model, case)
    forces = np.einsum("eab,eb->ea", beams.local_stiffness, local) \
        - _element_loads_local(beams, line_loads)
    bending = beams.width * beams.thickness ** 2 / 6.0
    in_plane = beams.thickness * beams.width ** 2 / 6.0
    area = beams.width * beams.thickness
    ends = [np.abs(forces[:, 4 + 6 * end]) / bending + np.abs(forces[:, 5 + 6 * end]) / in_plane
            + np.abs(forces[:, 6 * end]) / area for end in (0, 1)]
    element_stress = np.maximum(*ends)
    stress = np.zeros(n_planks)
    np.maximum.at(stress, beams.plank, element_stress)

    supports: list[list[int]] = [[] for _ in range(n_planks)]
    carried_by = _carrying_neighbours(model)
    for nodes in model.joint_nodes:
        a, b = (int(model.node_plank[node]) for node in nodes)
        for node, plank, other in ((nodes[0], a, b), (nodes[1], b, a)):
            if other in carried_by[plank]:
                supports[plank].append(int(node))
    carrying = np.ones(len(model.contacts), dtype=bool) if holding is None else holding
    for node, carries in zip(model.contact_node, carrying):
        if carries:
            supports[model.node_plank[node]].append(int(node))
    sag, span = np.zeros(n_planks), np.zeros(n_planks)
    displacement = q.reshape(-1, 6)
    for k in range(n_planks):
        if supports[k] and k not in _lying_on_floor(model):
            sag[k], span[k] = _sag(model, k, sorted(set(supports[k])), displacement,
                                   line_loads)
    return PlankStatics(sag, span, stress)


def _carrying_neighbours(model: StaticsModel) -> list[set[int]]:
    """Per local plank P, the planks jointed to it that carry it: those that still reach a
    plank on the ground when P is taken away (a shelf's sides carry it, and it braces
    them; a lip nailed under a shelf's tip, or a shelf hanging on a post, reaches the
    ground only through the plank it hangs on and carries nothing).  Kept per model."""
    cached = model.plank_cache.get("carrying")
    if cached is not None:
        return cached
    n = len(model.planks)
    neighbours: list[set[int]] = [set() for _ in range(n)]
    for nodes in model.joint_nodes:
        a, b = (int(model.node_plank[node]) for node in nodes)
        neighbours[a].add(b)
        neighbours[b].add(a)
    grounded = {int(k) for k in model.contact_plank}
    carrying: list[set[int]] = []
    for removed in range(n):
        reached = {k for k in grounded if k != removed}
        frontier = list(reached)
        while frontier:
            k = frontier.pop()
            for other in neighbours[k] - reached - {removed}:
                reached.add(other)
                frontier.append(other)
        carrying.append(neighbours[removed] & reached)
    model.plank_cache["carrying"] = carrying
    return carrying


def _lying_on_floor(model: StaticsModel) -> set[int]:
    """Local planks lying on the floor on a broad face (all four corners of that face are
    ground contacts): the floor holds them along their whole face, not at the corners the
    contacts stand for, so they are given no sag."""
    cached = model.plank_cache.get("lying")
    if cached is not None:
        return cached
    corners: dict[int, set[int]] = {}
    for row, c in enumerate(model.contacts):
        corners.setdefault(int(model.contact_plank[row]), set()).add(
            model.geometry.contacts[c].corner)
    lying = {k for k, found in corners.items()
             if {0, 1, 2, 3} <= found or {4, 5, 6, 7} <= found}
    model.plank_cache["lying"] = lying
    return lying


def _profile(model: StaticsModel, k: int, displacement: np.ndarray,
             line_loads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(s, w): positions along local plank k's axis (m; its nodes and SAG_SAMPLES points
    inside each element) and the transverse deflection there ((m, 2) m, along e2 and e3):
    between nodes the cubic of the nodal deflections and slopes plus the deflection of
    the element's own uniform load, q L^4 xi^2 (1 - xi)^2 / 24 EI + q L^2 xi (1 - xi) /
    2 k G A (exact for a slender element), so that a largest sag between nodes is read."""
    beams = model.beams
    frame = beam_frame(model.design.planks[model.planks[k]], beams.crosswise[k])
    elements = np.flatnonzero(beams.plank == k)
    material = model.design.material
    xi = np.linspace(0.0, 1.0, tol.SAG_SAMPLES + 2)[:-1]                # node 1 and inside
    h1, h2 = 1 - 3 * xi ** 2 + 2 * xi ** 3, xi - 2 * xi ** 2 + xi ** 3
    h3, h4 = 3 * xi ** 2 - 2 * xi ** 3, -xi ** 2 + xi ** 3
    positions, deflections = [], []
    for e in elements:
        a, b = beams.nodes[e]
        L = beams.length[e]
        w_a, w_b = displacement[a, :3] @ frame[:, 1:], displacement[b, :3] @ frame[:, 1:]
        slope_a, slope_b = (np.array([displacement[n, 3:] @ frame[:, 2],      # du2/ds
                                      -(displacement[n, 3:] @ frame[:, 1])])  # du3/ds
                            for n in (a, b))
        section = section_properties(beams.width[e], beams.thickness[e])
        q = line_loads[e] @ frame[:, 1:]                                  # along e2, e3
        inertia = np.array([section["I3"], section["I2"]])
        bubble = (q[None, :] * L ** 4 * (xi ** 2 * (1 - xi) ** 2)[:, None]
                  / (24.0 * material.elastic_modulus * inertia[None, :])
                  + q[None, :] * L * L * (xi * (1 - xi))[:, None]
                  / (2.0 * SHEAR_FACTOR * material.shear_modulus * section["A"]))
        w = (h1[:, None] * w_a + L * h2[:, None] * slope_a + h3[:, None] * w_b
             + L * h4[:, None] * slope_b + bubble)
        positions.append(beams.node_s[a] + xi * L)
        deflections.append(w)
    last = beams.nodes[elements[-1], 1]
    positions.append(np.array([beams.node_s[last]]))
    deflections.append((displacement[last, :3] @ frame[:, 1:])[None, :])
    return np.concatenate(positions), np.vstack(deflections)


def _sag(model: StaticsModel, k: int, supports: list[int], displacement: np.ndarray,
         line_loads: np.ndarray) -> tuple[float, float]:
    """(sag, span) of local plank k (contract 3a) from its deflected axis (``_profile``):
    between its outermost supports, the largest deviation from the straight line through
    them (span: their distance); beyond them, each overhang's largest deviation from the
    tangent at its support (span: twice the overhang); the one nearest its limit (the
    largest sag / span) is the plank's.  Held at one point, only the overhangs count."""
    beams = model.beams
    s, transverse = _profile(model, k, displacement, line_loads)
    frame = beam_frame(model.design.planks[model.planks[k]], beams.crosswise[k])
    positions = beams.node_s[supports]
    low, high = supports[int(np.argmin(positions))], supports[int(np.argmax(positions))]
    sa, sb = beams.node_s[low], beams.node_s[high]
    reach = 1e-9 + 1e-9 * beams.plank_half[k]
    measures = []                                   # (sag, span)
    if sb - sa > tol.NODE_MERGE:
        wa, wb = displacement[low, :3] @ frame[:, 1:], displacement[high, :3] @ frame[:, 1:]
        inside = (s >= sa - reach) & (s <= sb + reach)
        line = wa[None, :] + ((s[inside] - sa) / (sb - sa))[:, None] * (wb - wa)[None, :]
        measures.append((float(np.linalg.norm(transverse[inside] - line, axis=1).max()),
                         float(sb - sa)))
    for root, outside, overhang in ((low, s < sa - reach, sa + beams.plank_half[k]),
                                    (high, s > sb + reach, beams.plank_half[k] - sb)):
        if not outside.any():
            continue
        w0 = displacement[root, :3] @ frame[:, 1:]
        slope = np.array([displacement[root, 3:] @ frame[:, 2],           # du2/ds
                          -(displacement[root, 3:] @ frame[:, 1])])       # du3/ds
        tangent = w0[None, :] + (s[outside] - beams.node_s[root])[:, None] * slope[None, :]
        measures.append((float(np.linalg.norm(transverse[outside] - tangent, axis=1).max()),
                         2.0 * float(overhang)))
    if not measures:
        return 0.0, 0.0
    return max(measures, key=lambda m: m[0] / m[1] if m[1] > 0 else 0.0)
