"""Existence of an admissible equilibrium, decided by small linear programs.

``unilateral_feasible`` (can every component be held with normal forces >= 0, friction
unlimited?) and ``cone_solution`` (contact forces inside polygonal friction pyramids), both
on the per-component equilibrium rows of ``_component_problem``; ``closest_admissible``
picks, among all the admissible contact forces, the one closest to a given (elastic)
solution, so that forces taken from a program are well defined.

A program's answer is one of three (``Feasibility``): an equilibrium exists, none exists
(HiGHS proved the program infeasible), or the solver gave up (iteration limit, numerical
trouble): that one is tried once more with the other HiGHS method and, if still open,
reported as such, never read as "no equilibrium".  The friction pyramids are inscribed in
the Coulomb cones (FRICTION_CONE_SIDES sides): a case they cannot hold may still be held
by the round cones, within 1 - cos(pi / sides) of the threshold, so 'sliding' is
conservative by at most that.  scipy.optimize is slow to import, so it is imported inside
the functions that use it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.model import StaticsModel
from furncheck.statics.offsets import skew

FEASIBLE, INFEASIBLE, UNDECIDED = "feasible", "infeasible", "undecided"


@dataclass(frozen=True)
class Feasibility:
    """A program's verdict: ``status`` FEASIBLE, INFEASIBLE or UNDECIDED (the solver
    stopped without proving either; ``message`` says why); ``forces`` (nK, 3) N, some
    admissible contact forces when FEASIBLE and asked for."""

    status: str
    forces: np.ndarray | None = None
    message: str = ""

    @property
    def exists(self) -> bool:
        return self.status == FEASIBLE


def _component_problem(model: StaticsModel, f: np.ndarray, component: int):
    """Equilibrium rows (6, 3 nk) for the component's contact forces (each in its contact's
    frame) and the applied wrench (6,), both about the mean contact point; the moment rows
    divided by the contacts' spread (m), so that all six rows are forces."""
    members = np.nonzero(model.contact_component == component)[0]
    points = model.contact_points[members]
    reference = points.mean(axis=0) if len(points) else np.zeros(3)
    spread = max(float(np.abs(points - reference).max(initial=0.0)), 1e-6)
    rows = np.zeros((6, 3 * len(members)))
    for col, point in enumerate(points):
        rows[:3, 3 * col:3 * col + 3] = np.eye(3)
        rows[3:, 3 * col:3 * col + 3] = skew(point - reference) / spread
    if model.contact_frames is not None:        # forces in the contacts' frames
        blocks = rows.reshape(6, len(members), 3).transpose(1, 0, 2)     # (nk, 6, 3)
        turned = blocks @ model.contact_frames[members].transpose(0, 2, 1)
        rows = turned.transpose(1, 0, 2).reshape(6, 3 * len(members))
    return members, rows, _wrench_about(model, f, component, reference, spread)


def _problems(model: StaticsModel, f: np.ndarray):
    """The equilibrium problems to solve, (contacts, rows, wrench) each: one per grounded
    component (``_component_problem``), or, where planks rest on others, one for all:
    each component's six rows about its own contacts, a resting corner's force in the rows
    of the component it belongs to and, against it, of the one it rests on."""
    if model.rest_node is None:
        for component in range(len(model.components)):
            yield _component_problem(model, f, component)
        return
    count = len(model.components)
    rows = np.zeros((6 * count, 3 * len(model.contacts)))
    wrench = np.zeros(6 * count)
    for c in range(count):
        members, own_rows, own_wrench = _component_problem(model, f, c)
        cols = (3 * members[:, None] + np.arange(3)[None, :]).ravel()
        rows[6 * c:6 * c + 6, cols] = own_rows
        wrench[6 * c:6 * c + 6] = own_wrench
        resting = np.flatnonzero(model.rest_component == c)
        if not resting.size:
            continue
        points = model.contact_points[members] if len(members) else \
            model.contact_points[resting]
        reference = points.mean(axis=0)
        spread = max(float(np.abs(points - reference).max(initial=0.0)), 1e-6)
        if not len(members):            # the wrench about the resting corners' mean
            wrench[6 * c:6 * c + 6] = _wrench_about(model, f, c, reference, spread)
        for k in resting:               # its force acts on this component reversed
            block = np.vstack([np.eye(3), skew(model.contact_points[k] - reference) / spread])
            rows[6 * c:6 * c + 6, 3 * k:3 * k + 3] -= block @ model.contact_frames[k].T
    yield np.arange(len(model.contacts)), rows, wrench


def _wrench_about(model: StaticsModel, f: np.ndarray, component: int,
                  reference: np.ndarray, spread: float) -> np.ndarray:
    """The component's applied wrench (6,) about ``reference``, moments / ``spread``."""
    wrench = np.zeros(6)
    for k in model.component_nodes[component]:
        centre = model.node_points[k]
        force, moment = f[6 * k:6 * k + 3], f[6 * k + 3:6 * k + 6]
        wrench[:3] += force
        wrench[3:] += (moment + np.cross(centre - reference, force)) / spread
    return wrench


def _linprog(c, **problem) -> tuple[str, object]:
    """HiGHS on the program; an unproven answer is tried again with the other method."""
    from scipy.optimize import linprog

    result = None
    for method in ("highs-ds", "highs-ipm"):
        result = linprog(c, method=method, **problem)
        if result.status == 0:
            return FEASIBLE, result
        if result.status == 2:
            return INFEASIBLE, result
    return UNDECIDED, result


def unilateral_feasible(model: StaticsModel, f: np.ndarray) -> Feasibility:
    """Whether every component can be held with normal forces >= 0 (friction unlimited)."""
    for members, rows, wrench in _problems(model, f):
        if len(members) == 0:
            return Feasibility(INFEASIBLE)
        bounds = [b for member in members
                  for b in ((None, None), (None, None), (None, None) if _tie(model, member)
                            else (0, None))]
        status, result = _linprog(np.zeros(3 * len(members)), A_eq=rows, b_eq=-wrench,
                                  bounds=bounds)
        if status != FEASIBLE:
            return Feasibility(status, message=result.message)
    return Feasibility(FEASIBLE)


def _tie(model: StaticsModel, member: int) -> bool:
    """Whether contact ``member`` is an anchor's tie (any force, no cone)."""
    return model.contact_anchored is not None and bool(model.contact_anchored[member])


_BOTH_WAYS = np.hstack([np.eye(3), -np.eye(3)])
"""(3, 6): an anchor's tie as non-negative weights of six edges: any force."""


def _member_generators(model: StaticsModel, member: int, heading: float) -> np.ndarray:
    """(3, m): edges whose non-negative combinations are the forces contact ``member`` may
    take: its friction pyramid, or any force for an anchor's tie."""
    return _BOTH_WAYS if _tie(model, member) else _generators(model.friction, heading)


def _generators(mu: float, heading: float = 0.0) -> np.ndarray:
    """(3, sides): the edges of the friction pyramid inscribed in the cone |f_t| <= mu f_n,
    the first along the tangential direction ``heading`` (rad, in the contact's frame).
    The pyramids are turned with the loads (``_headings``) so that a design turned about
    the vertical gets the same verdict and forces."""
    sides = tol.FRICTION_CONE_SIDES
    angles = heading + 2.0 * np.pi * np.arange(sides) / sides
    return np.column_stack([mu * np.cos(angles), mu * np.sin(angles), np.ones(sides)]).T


def _heading(horizontal: np.ndarray) -> float:
    """rad: the direction of a force's tangential components (x, y: the world's for the
    ground, t1, t2 of a contact's frame), 0 when it has none."""
    x, y = float(horizontal[0]), float(horizontal[1])
    return float(np.arctan2(y, x)) if np.hypot(x, y) > 0.0 else 0.0


def _headings(model: StaticsModel, members: np.ndarray, push: np.ndarray) -> list[float]:
    """rad, per contact of ``members``: the direction of the force ``push`` (world, (3,))
    in the contact's tangent plane, measured in its own frame (t1, t2: for the ground the
    world's x and y; for a wall, along it and up), so that the pyramids turn with the
    design, walls and all.  (The world's x, y angle taken as such in a wall's frame
    turned the wall's pyramids against it as the design turned about the vertical: near
    the edge of sliding, a wall shelf's nail joint force moved by 0.3 %.)  Where planks
    rest on others, the programs are one problem for all components, and ``push`` is the
    first component's (as before: a choice of orientation, the same for a turned
    design)."""
    return _per_contact(model, members, push, lambda local: _heading(local[:2]))


def _per_contact(model: StaticsModel, members: np.ndarray, push: np.ndarray,
                 measure) -> list:
    """``measure`` of the force ``push`` (world, (3,)) in each contact's frame, per contact
    of ``members`` (once for all where every contact's frame is the world's)."""
    if model.contact_frames is None:
        return [measure(push)] * len(members)
    return [measure(local) for local in model.contact_frames[members] @ push]


def cone_solution(model: StaticsModel, f: np.ndarray) -> Feasibility:
    """Whether contact forces inside the friction pyramids hold every component, and some
    such forces ((nK, 3) N) when they do."""
    forces = np.zeros((len(model.contacts), 3))
    for members, rows, wrench in _problems(model, f):
        if len(members) == 0:
            return Feasibility(INFEASIBLE)
        generators = [_member_generators(model, member, heading) for member, heading
                      in zip(members, _headings(model, members, -wrench[:3]))]
        A = np.hstack([rows[:, 3 * c:3 * c + 3] @ edges for c, edges in enumerate(generators)])
        status, result = _linprog(np.zeros(A.shape[1]), A_eq=A, b_eq=-wrench, bounds=(0, None))
        if status != FEASIBLE:
            return Feasibility(status, message=result.message)
        if model.contact_frames is None and model.contact_anchored is None \
                and model.rest_node is None:                            # one pyramid for all
            forces[members] = result.x.reshape(len(members), -1) @ generators[0].T
            continue
        offsets = np.cumsum([0] + [edges.shape[1] for edges in generators])
        for c, (member, edges) in enumerate(zip(members, generators)):
            forces[member] = edges @ result.x[offsets[c]:offsets[c + 1]]
    return Feasibility(FEASIBLE, forces)


def closest_admissible(model: StaticsModel, f: np.ndarray, target: np.ndarray) -> np.ndarray:
    """The contact forces (nK, 3) N inside the friction pyramids that hold every component
    and lie closest (least squares) to ``target`` (nK, 3), e.g. the forces of the elastic
    solution with unlimited friction: unlike a program's vertex, one set of forces for a
    given design and load, so the joint forces that follow are well defined too.

    Per component, with P the pyramid edges and A the equilibrium rows, the weights
    lambda >= 0 minimize |A P lambda + w|^2 rho^2 + |P lambda - target|^2 (non-negative
    least squares, scipy's ``nnls``): the equilibrium held to about 1 / rho^2 of the
    distance to the target; the least-norm change that makes it exact follows (it moves
    the forces by that much, far below the force tolerance).
    Call it only where ``cone_solution`` found forces.
    """
    from scipy.optimize import nnls

    forces = np.zeros((len(model.contacts), 3))
    weight = tol.EQUILIBRIUM_WEIGHT
    for members, rows, wrench in _problems(model, f):
        n = len(members)
        pushed = _pushed(model, members, -wrench[:3])
        blocks = [_admissible_edges(model, member, heading, target[member])
                  for member, heading in zip(members, pushed)]
        offsets = np.cumsum([0] + [block.shape[1] for block in blocks])
        edges = np.zeros((3 * n, offsets[-1]))
        for c, block in enumerate(blocks):
            edges[3 * c:3 * c + 3, offsets[c]:offsets[c + 1]] = block
        system = np.vstack([weight * (rows @ edges), edges])
        rhs = np.concatenate([-weight * wrench, target[members].ravel()])
        scale = max(float(np.abs(rhs).max(initial=0.0)), 1e-300)
        weights, _ = nnls(system, rhs / scale, maxiter=50 * system.shape[1])
        chosen = edges @ weights * scale
        # the least change that balances the component exactly (round-off of the weights'
        # equilibrium, about 1e-12 of the forces), so the joint solve sees balanced loads
        chosen -= np.linalg.lstsq(rows, rows @ chosen + wrench, rcond=None)[0]
        forces[members] = chosen.reshape(n, 3)
    return forces


def _pushed(model: StaticsModel, members: np.ndarray, push: np.ndarray) -> list[float | None]:
    """``_headings`` of the contacts of ``members``, None where the push has no tangential
    part in a contact's plane beyond round-off (``_direction``: under weight alone its
    direction is noise, and a pyramid turned by it would turn the forces with it)."""
    return _per_contact(model, members, push, _direction)


def _direction(force: np.ndarray) -> float | None:
    """rad: ``_heading`` of a force (3,) in a contact's frame, None where its tangential
    part is round-off (at most PUSH_ROUNDOFF of the force)."""
    sideways = float(np.hypot(force[0], force[1]))
    return _heading(force[:2]) if sideways > tol.PUSH_ROUNDOFF * float(np.linalg.norm(force)) \
        else None


def _admissible_edges(model: StaticsModel, member: int, heading: float | None,
                      target: np.ndarray) -> np.ndarray:
    """(3, m): the edges of the forces ``closest_admissible`` lets contact ``member`` take:
    its friction pyramid along its ``target`` force's tangential part (its frame; along the
    push where that part is round-off, PUSH_ROUNDOFF of the force), and that of
    ``cone_solution`` (along the push, ``heading``) where the push has a direction (both
    inscribed in the Coulomb cone, so are their non-negative combinations); any force for an
    anchor's tie.  The targets' pyramids alone missed forces that the program's hold: on
    ``l-shelf-pushed`` moved by 5 mm (held at 99 % of its friction, no corner to spare) no
    forces inside them balanced it, the least-squares weights missed balance by 8e-4 N,
    their exact balance left a cone by 2.5e-4 of its friction, and the program's own vertex
    forces were reported instead: different ones as the design was turned.  (The program's
    alone turn with the push, which under weight alone is round-off: the forces then turned
    with it.)"""
    if _tie(model, member):
        return _BOTH_WAYS
    own = _direction(target)
    if own is None:                         # a round-off sideways part: the push's, or 0
        own = 0.0 if heading is None else heading
    edges = _generators(model.friction, own)
    if heading is None or heading == own:
        return edges
    return np.hstack([edges, _generators(model.friction, heading)])
