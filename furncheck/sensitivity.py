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
statics is solved for them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck.design.model import Design, LoadCase
from furncheck.dofs import Blocked, Dof, OutOfReach, Structure, apply_dof, design_size, structure
from furncheck.geometry import Geometry, analyze, follow
from furncheck.statics import (
    anchor_springs,
    build_model,
    external_forces,
    solve_case,
    solve_system,
    system_matrix,
)

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
    """

    case: str
    dofs: tuple[Dof, ...]
    joint_wrenches: np.ndarray
    contact_forces: np.ndarray
    blocked: dict[str, str]


class Linearization:
    """A solved load case of a design, ready for eq. 6 with any DOFs."""

    def __init__(self, design: Design, case: LoadCase, geometry: Geometry | None = None,
                 frame: Structure | None = None, shared: dict | None = None):
        self.shared = {} if shared is None else shared   # edited models, across load cases
        self.design = design
        self.case = case
        self.geometry = geometry or analyze(design)
        self.frame = frame or structure(design, self.geometry)
        self.model = build_model(design, self.geometry)
        self.statics = solve_case(self.model, external_forces(self.model, case))
        if self.statics.stability != "stable" or self.statics.state is None:
            raise ValueError(f"case {case.name!r} has no solved equilibrium to differentiate "
                             f"({self.statics.stability}; nothing grounded, or the contact "
                             "forces came from the feasibility program)")
        self.holding = self.statics.holding
        self.state = self.statics.state
        self.size = design_size(design)

    def step(self, dof: Dof) -> float:
        """The difference step for ``dof`` in its own unit."""
        return ASSEMBLY_STEP if dof.is_rotation else ASSEMBLY_STEP * self.size

    def assembly(self, dof: Dof, amount: float) -> tuple:
        """(A, b, contact maps) of the design with ``dof`` stepped by ``amount``, contact
        states and structure held.  The edited design and its model are kept in ``shared``
        (pass one dict to the linearizations of all load cases of a design)."""
        key = (dof, amount)
        if key not in self.shared:
            edited = apply_dof(self.design, self.frame, dof, amount)
            self.shared[key] = (edited, build_model(edited, follow(self.geometry, edited)))
        edited, model = self.shared[key]
        case = next(c for c in edited.load_cases if c.name == self.case.name)
        b = np.concatenate([external_forces(model, case), np.zeros(model.G.shape[0])])
        return system_matrix(model, self.holding), b, model.contact_maps

    def derivatives(self, dofs: list[Dof]) -> Sensitivity:
        """Eq. 6 for every DOF that can move."""
        moving, columns, map_rates, blocked = [], [], [], {}
        for dof in dofs:
            h = self.step(dof)
            try:
                a_plus, b_plus, maps_plus = self.assembly(dof, h)
                a_minus, b_minus, maps_minus = self.assembly(dof, -h)
            except Blocked as why:
                blocked[dof.name] = why.reason
                continue
            except OutOfReach as why:      # cannot happen for the tiny difference step
                blocked[dof.name] = str(why)
                continue
            columns.append((b_plus - b_minus) / (2 * h) - ((a_plus - a_minus) @ self.state)
                           / (2 * h))
            map_rates.append((maps_plus - maps_minus) / (2 * h))
            moving.append(dof)
        model = self.model
        n_joints, n_contacts = model.G.shape[0] // 6, len(model.contacts)
        if not moving:
            return Sensitivity(self.case.name, (), np.zeros((0, n_joints, 6)),
                               np.zeros((0, n_contacts, 3)), blocked)
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
                           blocked)


def sensitivity(design: Design, dofs: list[Dof], case_name: str | None = None) -> Sensitivity:
    """Derivatives of the joint wrenches and contact forces of one load case (the first if
    none is named) with respect to ``dofs``; see the module docstring."""
    case = design.load_cases[0] if case_name is None else \
        next(c for c in design.load_cases if c.name == case_name)
    return Linearization(design, case).derivatives(dofs)
