"""Existence of an admissible equilibrium, decided by small linear programs.

``_unilateral_feasible`` (can every component be held with normal forces >= 0, friction
unlimited?) and ``_cone_solution`` (contact forces inside polygonal friction pyramids), both
on the per-component equilibrium rows of ``_component_problem``.  scipy.optimize is slow to
import, so ``linprog`` is imported inside the functions that use it.
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.model import StaticsModel, _skew


def _component_problem(model: StaticsModel, f: np.ndarray, component: int):
    """Equilibrium rows (6, 3 nk) for the component's contact forces and the applied wrench
    (6,), both about the mean contact point."""
    design = model.design
    members = np.nonzero(model.contact_component == component)[0]
    points = model.contact_points[members]
    reference = points.mean(axis=0)
    rows = np.zeros((6, 3 * len(members)))
    for col, point in enumerate(points):
        rows[:3, 3 * col:3 * col + 3] = np.eye(3)
        rows[3:, 3 * col:3 * col + 3] = _skew(point - reference)
    wrench = np.zeros(6)
    for k in model.components[component]:
        centre = design.planks[model.planks[k]].center_array
        force, moment = f[6 * k:6 * k + 3], f[6 * k + 3:6 * k + 6]
        wrench[:3] += force
        wrench[3:] += moment + np.cross(centre - reference, force)
    return members, rows, wrench


def _unilateral_feasible(model: StaticsModel, f: np.ndarray) -> bool:
    """Whether every component can be held with normal forces >= 0 (friction unlimited)."""
    from scipy.optimize import linprog

    for component in range(len(model.components)):
        members, rows, wrench = _component_problem(model, f, component)
        if len(members) == 0:
            return False
        bounds = [b for _ in members for b in ((None, None), (None, None), (0, None))]
        result = linprog(np.zeros(3 * len(members)), A_eq=rows, b_eq=-wrench, bounds=bounds,
                         method="highs")
        if result.status != 0:
            return False
    return True


def _cone_solution(model: StaticsModel, f: np.ndarray) -> np.ndarray | None:
    """Contact forces (nK, 3) holding every component inside polygonal friction pyramids
    inscribed in the Coulomb cones (exact to 1 - cos(pi / FRICTION_CONE_SIDES)), or None
    when there are none: the design slides."""
    from scipy.optimize import linprog

    sides = tol.FRICTION_CONE_SIDES
    angles = 2.0 * np.pi * np.arange(sides) / sides
    generators = np.column_stack([model.friction * np.cos(angles),
                                  model.friction * np.sin(angles), np.ones(sides)]).T
    forces = np.zeros((len(model.contacts), 3))
    for component in range(len(model.components)):
        members, rows, wrench = _component_problem(model, f, component)
        if len(members) == 0:
            return None
        A = np.hstack([rows[:, 3 * c:3 * c + 3] @ generators for c in range(len(members))])
        result = linprog(np.zeros(A.shape[1]), A_eq=A, b_eq=-wrench, bounds=(0, None),
                         method="highs")
        if result.status != 0:
            return None
        weights = result.x.reshape(len(members), sides)
        forces[members] = weights @ generators.T
    return forces
