"""An elastic design's deflected shape in one load case, for the views.

The elastic model (contract section 3a) solves a displacement q_k = (u_k, theta_k) (m,
rad, world frame) at every node on each plank's beam axis.  Between two nodes a, b of an
element of length L along the unit axis e, the axis point at xi = s / L in [0, 1] moves
by the element's own shape functions: along e linearly, across e by cubic Hermite
interpolation of the end displacements and the end slopes du/ds = theta x e,

    u(xi) = H1 u_a + H2 L (theta_a x e) + H3 u_b + H4 L (theta_b x e)   (across e),
    H1 = 1 - 3 xi^2 + 2 xi^3,  H2 = xi - 2 xi^2 + xi^3,  H3 = 3 xi^2 - 2 xi^3,
    H4 = xi^3 - xi^2,

which is the exact deflection of an Euler-Bernoulli element loaded at its ends (the
planks' shear deformation is small beside it).  The rigid model's displacements are
those of its penalty springs, not of the planks, so it has no deflected shape.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck.design.model import Design

SAMPLES_PER_ELEMENT = 9
"""Points drawn along each beam element (its ends and its middle included)."""


@dataclass(frozen=True)
class Deflection:
    """The deflected beam axes of a design's planks in one load case, file length unit.

    case    : the load case
    curves  : per plank (id, (k, 3) points along its beam axis, (k, 3) their
              displacements), in the design's plank order
    largest : the largest displacement of any axis point
    where   : the plank it is on
    """

    case: str
    curves: tuple[tuple[str, np.ndarray, np.ndarray], ...]
    largest: float
    where: str


def deflected_shape(design: Design, case_name: str) -> Deflection | None:
    """The design's deflection in the case ``case_name`` (solved here), or None when it
    has none to draw: rigid planks, a design that does not stand as drawn, a case without
    an equilibrium (no displacements), or an unknown case."""
    from furncheck.geometry import analyze
    from furncheck.statics.contacts import solve_case
    from furncheck.statics.model import build_model, external_forces

    case = next((case for case in design.load_cases if case.name == case_name), None)
    if not design.elastic or case is None:
        return None
    geometry = analyze(design)
    if not geometry.stands:
        return None
    model = build_model(design, geometry)
    if model.beams is None or not model.n_nodes:
        return None
    statics = solve_case(model, external_forces(model, case))
    if statics.displacements is None:
        return None
    return axis_curves(design, model, case_name, statics.displacements)


def axis_curves(design: Design, model, case_name: str, displacements: np.ndarray
                ) -> Deflection | None:
    """``Deflection`` of a solved elastic model (``StaticsModel`` with beams) for node
    displacements (6 nN,) m and rad."""
    beams = model.beams
    q = np.asarray(displacements, dtype=float).reshape(-1, 6)
    first, second = beams.nodes[:, 0], beams.nodes[:, 1]
    start, end = model.node_points[first], model.node_points[second]
    length = np.linalg.norm(end - start, axis=1)
    keep = length > 0.0
    axis = np.zeros_like(start)
    axis[keep] = (end - start)[keep] / length[keep, None]
    xi = np.linspace(0.0, 1.0, SAMPLES_PER_ELEMENT)
    h1, h2 = 1 - 3 * xi ** 2 + 2 * xi ** 3, xi - 2 * xi ** 2 + xi ** 3
    h3, h4 = 3 * xi ** 2 - 2 * xi ** 3, xi ** 3 - xi ** 2
    u_a, u_b = q[first, :3], q[second, :3]
    slope_a = np.cross(q[first, 3:], axis) * length[:, None]
    slope_b = np.cross(q[second, 3:], axis) * length[:, None]

    def across(v: np.ndarray) -> np.ndarray:
        return v - np.sum(v * axis, axis=1, keepdims=True) * axis

    along_a = u_a - across(u_a)
    along_b = u_b - across(u_b)
    # (nE, k, 3): linear along the axis, Hermite across it
    moved = (along_a[:, None] * (1 - xi)[:, None] + along_b[:, None] * xi[:, None]
             + across(u_a)[:, None] * h1[:, None] + across(slope_a)[:, None] * h2[:, None]
             + across(u_b)[:, None] * h3[:, None] + across(slope_b)[:, None] * h4[:, None])
    points = start[:, None] + (end - start)[:, None] * xi[None, :, None]
    scale = design.unit_scale
    curves = []
    largest, where = 0.0, ""
    for local, plank_index in enumerate(model.planks):
        elements = np.flatnonzero(beams.plank == local)
        if not len(elements):
            continue
        elements = elements[np.argsort(beams.node_s[first[elements]], kind="stable")]
        plank_points = points[elements].reshape(-1, 3) / scale
        plank_moves = moved[elements].reshape(-1, 3) / scale
        plank_id = design.planks[plank_index].id
        curves.append((plank_id, plank_points, plank_moves))
        size = float(np.linalg.norm(plank_moves, axis=1).max())
        if size > largest:
            largest, where = size, plank_id
    order = {plank.id: k for k, plank in enumerate(design.planks)}
    curves.sort(key=lambda curve: order[curve[0]])
    return Deflection(case_name, tuple(curves), largest, where)
