"""Force sensitivity: how joint wrenches and contact forces change with each design DOF
(paper section 5.2, eq. 6).

At a solved load case the statics is the linear system A(g) x(g) = b(g) (``statics``), with
the contacts' states held (the paper's assumption: contacts neither lift nor slide under an
infinitesimal change).  Differentiating,

    dx/dg = A^-1 (db/dg - dA/dg x),

so every DOF costs one more right-hand side for the factorization the solve already has
(``statics.solve_system``).  dA/dg and db/dg come from central differences of the
*assembly* (joint points and frames, contact points, load points, self-weight) of the
design with the DOF stepped by +-h through the geometric constraints of ``dofs`` -- no
statics is solved for them.  Only the terms a step changes are evaluated (the joints and
contacts of the planks it moves, their weights and loads: ``Linearization._local``), so
a DOF costs about as much as its few moved planks, not a new assembly of the design.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from furncheck.design.model import Design, LoadCase
from furncheck.dofs import Blocked, Dof, OutOfReach, Structure, apply_dof, design_size, structure
from furncheck.geometry import Contact, Geometry, Joint, analyze, follow_many
from furncheck.statics import (
    anchor_springs,
    build_model,
    external_forces,
    solve_case,
    solve_system,
)
from furncheck.statics.model import _point_map
from furncheck.tolerances import GRAVITY

ASSEMBLY_STEP = 1e-4
"""Step of the central difference of the assembly, as a fraction of the design's size
(lengths) or in degrees (rotations).  Where the assembly is smooth this is exact to ~1e-8.
Where it has a kink -- a flush end face that a rotation tilts rests on one edge or the other
depending on the sign of the turn -- the derivative is the mean of the two one-sided
slopes; ranges do not rely on it beyond a first guess (every end is confirmed by the full
check)."""


@dataclass(frozen=True)
class Sensitivity:
    """Derivatives of one load case's forces with respect to DOFs.

    dofs            : the DOFs, in order (blocked ones are left out, see ``blocked``)
    joint_wrenches  : (n_dofs, nJ, 6): d(force N, moment N m) per DOF unit (file length
                      unit or degree), joints in the order of ``CaseResult.joints``
    contact_forces  : (n_dofs, nK, 3): d(ground force, N) per DOF unit
    blocked         : DOF name -> reason it cannot move
    joint_lengths   : (n_dofs, nJ): d(joint length, m) per DOF unit (the nail count
                      follows the length in steps; this is its smooth trend)
    """

    case: str
    dofs: tuple[Dof, ...]
    joint_wrenches: np.ndarray
    contact_forces: np.ndarray
    blocked: dict[str, str]
    joint_lengths: np.ndarray


class Linearization:
    """A solved load case of a design, ready for eq. 6 with any DOFs."""

    def __init__(self, design: Design, case: LoadCase, geometry: Geometry | None = None,
                 frame: Structure | None = None, shared: dict | None = None,
                 bolted: bool = False):
        """``bolted``: a case without a solved equilibrium (it lifts off or slides, or its
        forces came from the feasibility program) is linearized as if every contact were
        held -- the state whose pulling contacts say how far it is from standing."""
        self.shared = {} if shared is None else shared   # edited models, across load cases
        self.design = design
        self.case = case
        self.geometry = geometry or analyze(design)
        self.frame = frame or structure(design, self.geometry)
        self.model = build_model(design, self.geometry)
        f = external_forces(self.model, case)
        self.statics = solve_case(self.model, f)
        self.bolted = self.statics.stability != "stable" or self.statics.state is None
        if not self.bolted:
            self.holding = self.statics.holding
            self.state = self.statics.state
        elif bolted and self.statics.stability != "mechanism" and self.model.planks:
            self.holding = np.ones(len(self.model.contacts), dtype=bool)
            self.state = solve_system(self.model, self.holding,
                                      np.concatenate([f, np.zeros(self.model.G.shape[0])]))
        else:
            raise ValueError(f"case {case.name!r} has no solved equilibrium to differentiate "
                             f"({self.statics.stability}; nothing grounded, or the contact "
                             "forces came from the feasibility program)")
        self.size = design_size(design)

    @property
    def joint_wrenches(self) -> np.ndarray:
        """(nJ, 6) the joint wrenches of the linearized state."""
        return self.state[self.model.n_dof:].reshape(-1, 6)

    @property
    def contact_forces(self) -> np.ndarray:
        """(nK, 3) the ground's forces of the linearized state (springs at the holding
        contacts, as in ``solve_case``)."""
        model = self.model
        q = self.state[:model.n_dof].reshape(-1, 6)[model.contact_plank]
        displacement = (model.contact_maps @ q[:, :, None])[:, :, 0]
        return -(anchor_springs(self.holding) @ displacement[:, :, None])[:, :, 0]

    def step(self, dof: Dof) -> float:
        """The difference step for ``dof`` in its own unit."""
        return ASSEMBLY_STEP if dof.is_rotation else ASSEMBLY_STEP * self.size

    def stepped(self, dof: Dof) -> _Stepped:
        """The design with ``dof`` stepped by +-h and the joints and contacts the step
        moves, followed on both (raises Blocked or OutOfReach)."""
        self._step([dof])
        outcome = self.shared[dof]
        if isinstance(outcome, Exception):
            raise outcome
        return outcome

    def _step(self, dofs: list[Dof]) -> None:
        """Step every DOF not stepped yet and follow all their joints in one pass; the
        results (or the Blocked / OutOfReach of a DOF) are kept in ``shared`` (pass one
        dict to the linearizations of all load cases of a design)."""
        pending, edits = [], []
        geometry = self.geometry
        for dof in dofs:
            if dof in self.shared:
                continue
            h = self.step(dof)
            try:
                plus = apply_dof(self.design, self.frame, dof, h)
                minus = apply_dof(self.design, self.frame, dof, -h)
            except (Blocked, OutOfReach) as why:
                self.shared[dof] = why
                continue
            changed = tuple(i for i, (p, a, b) in enumerate(zip(self.design.planks, plus.planks,
                                                                   minus.planks))
                            if a != p or b != p)
            ids = {self.design.planks[i].id for i in changed}
            joints = tuple(j for j, joint in enumerate(geometry.joints)
                           if joint.edge in ids or joint.face in ids)
            contacts = tuple(k for k, contact in enumerate(geometry.contacts)
                             if contact.plank in ids)
            pending.append((dof, h, changed, joints, contacts, plus, minus))
            edits += [(plus, joints, contacts), (minus, joints, contacts)]
        followed = follow_many(geometry, edits)
        for k, (dof, h, changed, joints, contacts, plus, minus) in enumerate(pending):
            self.shared[dof] = _Stepped(h, changed, joints, contacts,
                                        (plus, *followed[2 * k]), (minus, *followed[2 * k + 1]))

    def derivatives(self, dofs: list[Dof]) -> Sensitivity:
        """Eq. 6 for every DOF that can move."""
        moving, columns, map_rates, length_rates, blocked = [], [], [], [], {}
        self._step(dofs)
        for dof in dofs:
            stepped = self.shared[dof]
            if isinstance(stepped, Blocked):
                blocked[dof.name] = stepped.reason
                continue
            if isinstance(stepped, OutOfReach):     # not for the tiny difference step
                blocked[dof.name] = str(stepped)
                continue
            plus, minus = self._local(stepped, *stepped.plus), \
                self._local(stepped, *stepped.minus)
            scale = 1.0 / (2.0 * stepped.h)
            columns.append((plus[0] - minus[0]) * scale)
            map_rates.append((plus[1] - minus[1]) * scale)
            length_rates.append((plus[2] - minus[2]) * scale)
            moving.append(dof)
        model = self.model
        n_joints, n_contacts = model.G.shape[0] // 6, len(model.contacts)
        if not moving:
            return Sensitivity(self.case.name, (), np.zeros((0, n_joints, 6)),
                               np.zeros((0, n_contacts, 3)), blocked, np.zeros((0, n_joints)))
        rates = solve_system(model, self.holding, np.column_stack(columns))   # (n, n_dofs)
        n = model.n_dof
        joint_rates = rates[n:].T.reshape(len(moving), n_joints, 6)
        q = self.state[:n].reshape(-1, 6)[model.contact_plank]               # (nK, 6)
        springs = anchor_springs(self.holding)
        contact_rates = []
        for column, map_rate in enumerate(map_rates):
            dq = rates[:n, column].reshape(-1, 6)[model.contact_plank]
            dw = ((map_rate @ q[:, :, None]) + (model.contact_maps @ dq[:, :, None]))[:, :, 0]
            contact_rates.append(-(springs @ dw[:, :, None])[:, :, 0])
        return Sensitivity(self.case.name, tuple(moving), joint_rates, np.array(contact_rates),
                           blocked, np.array(length_rates))

    def _local(self, stepped: _Stepped, design: Design, joints: tuple[Joint, ...],
               contacts: tuple[Contact, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The parts of b - A x that a step changes, evaluated on the stepped ``design``
        (x the linearized state; every other entry is the same on both sides of the
        difference and left zero), its contact maps and its joint lengths.

        With r = joint point - plank centre, a joint enters A x through its deviation
        rows (theta_a x r_a - theta_b x r_b) and its planks' moment rows (+-r x h^t); a
        contact through M^T S M q (M = [I, -[r]x], r = contact point - centre); a plank
        through its weight and its loads' moments about its centre.
        """
        model = self.model
        n = model.n_dof
        q = self.state[:n].reshape(-1, 6)
        wrench = self.state[n:].reshape(-1, 6)
        residual = np.zeros(len(self.state))
        maps = np.zeros_like(model.contact_maps)
        lengths = np.zeros(len(model.joints))
        index = design.plank_index
        for j, joint in zip(stepped.joints, joints):
            row = self._joint_row.get(j)
            if row is None:
                continue
            a, b = (self._local_plank[index[plank]] for plank in joint.planks)
            r_a = joint.point - design.planks[model.planks[a]].center_array
            r_b = joint.point - design.planks[model.planks[b]].center_array
            residual[n + 6 * row:n + 6 * row + 3] -= (_cross(q[a, 3:], r_a)
                                                      - _cross(q[b, 3:], r_b))
            residual[6 * a + 3:6 * a + 6] -= _cross(r_a, wrench[row, :3])
            residual[6 * b + 3:6 * b + 6] += _cross(r_b, wrench[row, :3])
            lengths[row] = joint.length
        springs = anchor_springs(self.holding)
        for k, contact in zip(stepped.contacts, contacts):
            row = self._contact_row.get(k)
            if row is None:
                continue
            a = model.contact_plank[row]
            maps[row] = _point_map(contact.point - design.planks[model.planks[a]].center_array)
            residual[6 * a:6 * a + 6] -= maps[row].T @ (springs[row] @ (maps[row] @ q[a]))
        case = next(c for c in design.load_cases if c.name == self.case.name)
        for i in stepped.changed:
            a = self._local_plank.get(i)
            if a is None:
                continue
            plank = design.planks[i]
            residual[6 * a + 2] -= design.plank_mass(plank) * GRAVITY
            for load in case.loads:
                if load.plank == plank.id and load.point is not None:
                    residual[6 * a + 3:6 * a + 6] += _cross(
                        np.asarray(load.point) - plank.center_array, load.force)
        return residual, maps, lengths

    @cached_property
    def _local_plank(self) -> dict[int, int]:
        return {plank: k for k, plank in enumerate(self.model.planks)}

    @cached_property
    def _joint_row(self) -> dict[int, int]:
        return {j: row for row, j in enumerate(self.model.joints)}

    @cached_property
    def _contact_row(self) -> dict[int, int]:
        return {k: row for row, k in enumerate(self.model.contacts)}


def _cross(u, v) -> np.ndarray:
    """u x v of two 3-vectors (np.cross costs ~50 times more on single vectors)."""
    return np.array([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                     u[0] * v[1] - u[1] * v[0]])


@dataclass(frozen=True)
class _Stepped:
    """A DOF stepped by +-h: the planks it changes (design indices), the geometry joints
    and contacts on them, and (design, those joints followed, those contacts followed)
    per side."""

    h: float
    changed: tuple[int, ...]
    joints: tuple[int, ...]
    contacts: tuple[int, ...]
    plus: tuple[Design, tuple[Joint, ...], tuple[Contact, ...]]
    minus: tuple[Design, tuple[Joint, ...], tuple[Contact, ...]]


def sensitivity(design: Design, dofs: list[Dof], case_name: str | None = None) -> Sensitivity:
    """Derivatives of the joint wrenches and contact forces of one load case (the first if
    none is named) with respect to ``dofs``; see the module docstring."""
    case = design.load_cases[0] if case_name is None else \
        next(c for c in design.load_cases if c.name == case_name)
    return Linearization(design, case).derivatives(dofs)
