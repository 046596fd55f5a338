"""A solved elastic case's planks: their sag and bending stress (contract section 3a).

``plank_results`` reads, per plank, the largest deflection of its own bending (between
nodes too, ``_profile``) from the line through its outermost carrying supports or, beyond
them, from the tangent at the support (``_sag``), and the largest bending plus axial
stress at its nodes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import LoadCase
from furncheck.statics.beams import SHEAR_FACTOR, beam_frame, section_properties
from furncheck.statics.elastic import _element_loads_local, case_line_loads
from furncheck.statics.model import StaticsModel


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


def _transverse(displacement: np.ndarray, node: int,
                frame: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(w, w') at a node: its deflection across the beam axis (2,) m, along e2 and e3, and
    the axis's slope there (2,), du2/ds = theta . e3 and du3/ds = -theta . e2."""
    rotation = displacement[node, 3:]
    return (displacement[node, :3] @ frame[:, 1:],
            np.array([rotation @ frame[:, 2], -(rotation @ frame[:, 1])]))


def _profile(model: StaticsModel, k: int, displacement: np.ndarray, line_loads: np.ndarray,
             frame: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(s, w): positions along local plank k's axis (m; ``frame``: its beam axes), at its
    nodes and SAG_SAMPLES points inside each element, and the transverse deflection there
    ((m, 2) m, along e2 and e3): between nodes the cubic of the nodal deflections and
    slopes plus the deflection of the element's own uniform load, q L^4 xi^2 (1 - xi)^2 /
    24 EI + q L^2 xi (1 - xi) / 2 k G A (exact for a slender element), so that a largest
    sag between nodes is read."""
    beams = model.beams
    elements = np.flatnonzero(beams.plank == k)
    material = model.design.material
    xi = np.linspace(0.0, 1.0, tol.SAG_SAMPLES + 2)[:-1]                # node 1 and inside
    h1, h2 = 1 - 3 * xi ** 2 + 2 * xi ** 3, xi - 2 * xi ** 2 + xi ** 3
    h3, h4 = 3 * xi ** 2 - 2 * xi ** 3, -xi ** 2 + xi ** 3
    positions, deflections = [], []
    for e in elements:
        a, b = beams.nodes[e]
        L = beams.length[e]
        (w_a, slope_a), (w_b, slope_b) = (_transverse(displacement, n, frame) for n in (a, b))
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
    deflections.append(_transverse(displacement, last, frame)[0][None, :])
    return np.concatenate(positions), np.vstack(deflections)


def _sag(model: StaticsModel, k: int, supports: list[int], displacement: np.ndarray,
         line_loads: np.ndarray) -> tuple[float, float]:
    """(sag, span) of local plank k (contract 3a) from its deflected axis (``_profile``):
    between its outermost supports, the largest deviation from the straight line through
    them (span: their distance); beyond them, each overhang's largest deviation from the
    tangent at its support (span: twice the overhang); the one nearest its limit (the
    largest sag / span) is the plank's.  Held at one point, only the overhangs count."""
    beams = model.beams
    frame = beam_frame(model.design.planks[model.planks[k]], beams.crosswise[k])
    s, transverse = _profile(model, k, displacement, line_loads, frame)
    positions = beams.node_s[supports]
    low, high = supports[int(np.argmin(positions))], supports[int(np.argmax(positions))]
    sa, sb = beams.node_s[low], beams.node_s[high]
    reach = 1e-9 + 1e-9 * beams.plank_half[k]
    measures = []                                   # (sag, span)
    if sb - sa > tol.NODE_MERGE:
        wa, wb = (_transverse(displacement, n, frame)[0] for n in (low, high))
        inside = (s >= sa - reach) & (s <= sb + reach)
        line = wa[None, :] + ((s[inside] - sa) / (sb - sa))[:, None] * (wb - wa)[None, :]
        measures.append((float(np.linalg.norm(transverse[inside] - line, axis=1).max()),
                         float(sb - sa)))
    for root, outside, overhang in ((low, s < sa - reach, sa + beams.plank_half[k]),
                                    (high, s > sb + reach, beams.plank_half[k] - sb)):
        if not outside.any():
            continue
        w0, slope = _transverse(displacement, root, frame)
        tangent = w0[None, :] + (s[outside] - beams.node_s[root])[:, None] * slope[None, :]
        measures.append((float(np.linalg.norm(transverse[outside] - tangent, axis=1).max()),
                         2.0 * float(overhang)))
    if not measures:
        return 0.0, 0.0
    return max(measures, key=lambda m: m[0] / m[1] if m[1] > 0 else 0.0)
