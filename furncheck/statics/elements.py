"""The beam elements of an elastic model (contract section 3a): ``Beams`` (each element's
nodes, length, axes and stiffness in its own axes), their world stiffness K_b assembled
sparse or dense or applied without assembling, the end forces in each element, and the
consistent nodal loads of what acts along the beams (self-weight and spread loads,
``elastic_forces`` with every load of a case).  ``elastic.build_elastic_model`` places the
nodes; ``bending`` reads the elements' forces.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase, Material, Plank
from furncheck.statics.beams import (
    beam_frame,
    beam_length_width,
    beam_stiffness_local,
    uniform_load_local,
)
from furncheck.statics.model import _SIX, StaticsModel, block_sums
from furncheck.statics.offsets import add_point_loads

if TYPE_CHECKING:
    import scipy.sparse as sp


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
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
    origins  : per node, its local plank and the keys of what it serves (``elastic._plank_nodes``)
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


def read_only(array: np.ndarray) -> np.ndarray:
    """The array, marked read-only (kept in ``StaticsModel.plank_cache`` and shared)."""
    array.flags.writeable = False
    return array


def element_nodes(node_plank: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(first node of each element, its (nE, 2) nodes, its local plank): an element
    between each two consecutive nodes of a plank."""
    first = np.flatnonzero(node_plank[1:] == node_plank[:-1])
    return first, np.column_stack([first, first + 1]), node_plank[first]


def element_inputs(planks: list[Plank], frames: list[np.ndarray], plank: np.ndarray,
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


def beam_elements(planks: list[Plank], frames: list[np.ndarray], node_plank: np.ndarray,
           node_s: np.ndarray, halves: np.ndarray, materials: list[Material], origins: tuple,
           crosswise: tuple[bool, ...]) -> Beams:
    """The elements between consecutive nodes of each plank (``materials``: each plank's,
    ``Design.material_of``)."""
    first, nodes, plank = element_nodes(node_plank)
    length, widths, thickness, moduli, plank_frames = element_inputs(
        planks, frames, plank, node_s, first, materials, crosswise)
    local = beam_stiffness_local(length, widths, thickness, moduli[:, 0],
                                 moduli[:, 1]).reshape(-1, 12, 12)
    return Beams(plank=plank, nodes=nodes, length=length, frames=plank_frames[plank],
                 local_stiffness=local, width=widths, thickness=thickness,
                 elastic_modulus=moduli[:, 0], shear_modulus=moduli[:, 1], node_s=node_s,
                 plank_half=halves, origins=origins, crosswise=crosswise,
                 plank_frames=plank_frames)


def element_dofs(beams: Beams) -> np.ndarray:
    """(nE, 12) the global DOF numbers of each element's two nodes."""
    return (6 * beams.nodes[:, :, None] + _SIX[None, None, :]).reshape(-1, 12)


def assemble_beams(beams: Beams, n_nodes: int) -> sp.csr_matrix:
    """K_b = sum T^T K_local T over the elements, (6 nN, 6 nN) sparse."""
    import scipy.sparse as sp

    world, rows, cols = element_entries(beams)
    n = 6 * n_nodes
    return sp.csr_matrix((world.ravel(), (rows.ravel(), cols.ravel())), shape=(n, n))


def beam_entries_placed(beams: Beams, position: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """K_b's terms for a dense matrix with node k's rows and columns at block
    ``position[k]`` (a permutation of the nodes): each term's flat index in that (6 nN,
    6 nN) matrix and its value, element by element (``np.bincount`` of them is K_b; with
    other terms before them, each entry sums those first, then its elements' in order)."""
    world, rows, cols = element_entries(beams)
    n_dof = 6 * len(position)
    block = 6 * np.asarray(position)
    rows = block[rows // 6] + rows % 6
    cols = block[cols // 6] + cols % 6
    return (rows * n_dof + cols).ravel(), world.ravel()


def element_entries(beams: Beams) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(T^T K_local T (nE, 12, 12), the global row and the column of each of its
    entries, each (nE, 12, 12))."""
    T = beams.transform()
    world = np.transpose(T, (0, 2, 1)) @ beams.local_stiffness @ T
    dofs = element_dofs(beams)
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


def weights_per_length(design: Design, planks: list[Plank], beams: Beams) -> np.ndarray:
    """(nE, 3) N/m: each element's share of its plank's weight, spread along the plank."""
    per_plank = np.array([-design.plank_mass(plank) * tol.GRAVITY
                          / beam_length_width(plank, crosswise)[0]
                          for plank, crosswise in zip(planks, beams.crosswise)], dtype=float)
    loads = np.zeros((len(beams.plank), 3))
    loads[:, 2] = per_plank[beams.plank]
    return loads


def element_loads_local(beams: Beams, loads: np.ndarray) -> np.ndarray:
    """(nE, 12) consistent nodal loads of uniform world loads (nE, 3) N/m, local axes."""
    local_loads = np.einsum("eab,ea->eb", beams.frames, loads)          # R^T q
    return uniform_load_local(beams.length, local_loads).reshape(-1, 12)


def element_world_loads(frames: np.ndarray, length: np.ndarray,
                         loads: np.ndarray) -> np.ndarray:
    """(nE, 12) T^T f: the consistent nodal loads of uniform loads (nE, 3) N/m along
    elements of axes ``frames`` (nE, 3, 3) and lengths (nE,), world axes (the arithmetic
    of ``nodal_loads``, element by element)."""
    local_loads = np.einsum("eab,ea->eb", frames, loads)                 # R^T q
    f_local = uniform_load_local(length, local_loads).reshape(-1, 12)
    T = np.zeros((len(length), 12, 12))
    for block in range(4):
        T[:, 3 * block:3 * block + 3, 3 * block:3 * block + 3] = np.transpose(frames, (0, 2, 1))
    return np.einsum("eba,eb->ea", T, f_local)


def nodal_loads(beams: Beams, loads: np.ndarray, n_nodes: int) -> np.ndarray:
    """(6 nN,) the consistent nodal loads of uniform loads (nE, 3) N/m along the elements."""
    f_local = element_loads_local(beams, loads)
    world = np.einsum("eba,eb->ea", beams.transform(), f_local)         # T^T f
    f = np.zeros(6 * n_nodes)
    np.add.at(f, element_dofs(beams).ravel(), world.ravel())
    return f


def case_line_loads(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(nE, 3) N/m: self-weight and the case's spread loads along each element."""
    weights = model.plank_cache.get("weights_per_length")
    if weights is None:
        plank_list = [model.design.planks[i] for i in model.planks]
        weights = weights_per_length(model.design, plank_list, model.beams)
    return weights + _spread_line_loads(model, case)


def _spread_line_loads(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(nE, 3) N/m: the case's spread loads, each along its plank's whole beam (kept per
    model and case, read-only: the forces and the planks' results both read them)."""
    kept = model.plank_cache.get(("spread", id(case)))
    if kept is not None and kept[0] is case:
        return kept[1]
    loads = read_only(_spread_line_loads_of(model, case))
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
        f += nodal_loads(model.beams, _spread_line_loads(model, case), model.n_nodes)
    _add_point_loads(model, case, f)
    return f


def elastic_forces_many(models: list[StaticsModel], cases: list[LoadCase]) -> np.ndarray:
    """(S, 6 nN): ``elastic_forces`` of several models of one topology (built on one
    template: the same nodes and elements), each with its case: their spread loads' nodal
    loads made for all of them in one pass (element by element, summed at each model's
    nodes in the same order as ``nodal_loads``: the same numbers)."""
    first = models[0]
    count, size = len(models), 6 * first.n_nodes
    forces = np.array([m.self_weight for m in models], dtype=float).reshape(count, size)
    local = first.local_planks
    spread = [any(load.spread and load.plank in local for load in case.loads)
              for case in cases]
    if any(spread):
        chosen = [k for k, has in enumerate(spread) if has]
        beams = [models[k].beams for k in chosen]
        world = element_world_loads(
            np.concatenate([b.frames for b in beams]), np.concatenate([b.length for b in beams]),
            np.concatenate([_spread_line_loads(models[k], cases[k]) for k in chosen]))
        dofs = element_dofs(first.beams).ravel()
        nodal = np.zeros((len(chosen), size))
        np.add.at(nodal, (np.repeat(np.arange(len(chosen)), len(dofs)),
                          np.tile(dofs, len(chosen))), world.ravel())
        forces[chosen] += nodal
    for model, case, f in zip(models, cases, forces):
        _add_point_loads(model, case, f)
    return forces


def _add_point_loads(model: StaticsModel, case: LoadCase, f: np.ndarray) -> None:
    """Add every load of the case but the spread ones to ``f`` (6 nN,), at the node of its
    point (its plank's centre when it has none), with its moment about that node."""
    local = model.local_planks
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


def _node_of(model: StaticsModel, k: int, point) -> int:
    """The node of local plank k nearest the projection of ``point`` on its axis."""
    members = np.flatnonzero(model.node_plank == k)
    plank = model.design.planks[model.planks[k]]
    axis = beam_frame(plank, model.beams.crosswise[k])[:, 0]
    s = float((np.asarray(point, dtype=float) - plank.center_array) @ axis)
    return int(members[np.argmin(np.abs(model.beams.node_s[members] - s))])
