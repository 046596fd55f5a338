"""Force sensitivity: how joint wrenches and contact forces change with each design DOF
(paper section 5.2, eq. 6).

At a solved load case the statics is the linear system A(g) x(g) = b(g) (``statics``), with
the contacts' states held (the paper's assumption: contacts neither lift nor slide under an
infinitesimal change).  Differentiating,

    dx/dg = A^-1 (db/dg - dA/dg x),

with the contacts' law of the solved case (``statics.contact_law.ContactLaw``: a sticking
contact a spring, a slipping one mu N against its slip, which stays slipping),
so every DOF costs one more right-hand side for the factorization the solve already has
(``statics.solve_system``).  dA/dg and db/dg come from central differences of the
*assembly* (joint points and frames, contact points, load points, self-weight) of the
design with the DOF stepped by +-h through the geometric constraints of ``dofs`` -- no
statics is solved for them.  Only the terms a step changes are evaluated (the joints and
contacts of the planks it moves, their weights and loads: ``Linearization._local``), so
a DOF costs about as much as its few moved planks, not a new assembly of the design.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase
from furncheck.dofs import Blocked, Dof, OutOfReach, Structure, apply_dof, design_size, structure
from furncheck.geometry import Contact, Geometry, Joint, analyze, follow_many
from furncheck.statics import (
    CaseStatics,
    StaticsModel,
    build_model,
    external_forces,
    solve_load_case,
    solve_system,
)
from furncheck.statics.anchored import solve_with_springs
from furncheck.statics.contact_law import ContactLaw
from furncheck.statics.derivatives import AssemblySide, assembly_differences, assembly_steps


@dataclass(frozen=True)
class Sensitivity:
    """Derivatives of one load case's forces with respect to DOFs.

    dofs            : the DOFs, in order (blocked ones are left out, see ``blocked``)
    joint_wrenches  : (n_dofs, nJ, 6): d(force N, moment N m) per DOF unit (file length
                      unit or degree), joints in the order of ``CaseResult.joints``
    contact_forces  : (n_dofs, nC, 3): d(ground force, N) per DOF unit, at the geometry's
                      contacts (``StaticsModel.corner_forces``), as ``CaseResult.contacts``
    blocked         : DOF name -> reason it cannot move
    joint_lengths   : (n_dofs, nJ): d(joint length, m) per DOF unit (the nail count
                      follows the length in steps; this is its smooth trend)
    plank_sags, plank_spans, plank_stresses : (n_dofs, nP): d(sag m, span m, stress Pa)
                      per DOF unit of each plank (elastic model; (n_dofs, 0) in the rigid)
    """

    case: str
    dofs: tuple[Dof, ...]
    joint_wrenches: np.ndarray
    contact_forces: np.ndarray
    blocked: dict[str, str]
    joint_lengths: np.ndarray
    plank_sags: np.ndarray | None = None
    plank_spans: np.ndarray | None = None
    plank_stresses: np.ndarray | None = None


class Linearization:
    """A solved load case of a design, ready for eq. 6 with any DOFs."""

    def __init__(self, design: Design, case: LoadCase, geometry: Geometry | None = None,
                 frame: Structure | None = None, shared: dict | None = None,
                 bolted: bool = False, one_sided: bool = False,
                 model: StaticsModel | None = None, statics: CaseStatics | None = None):
        """``bolted``: a case without a solved equilibrium (it lifts off or slides, or its
        forces came from the feasibility program) is linearized as if every contact were
        held -- the state whose pulling contacts say how far it is from standing.
        ``one_sided``: forward differences of the assembly (+h and the design itself),
        half the work and accurate to ~h (1e-4 relative): enough to choose directions.
        ``model``: the design's statics model, if the caller has it (shared by the load
        cases: its factorizations are made once); ``statics``: the case solved on that
        model (``solve_load_case``), if the caller has it."""
        self.one_sided = one_sided
        self.shared = {} if shared is None else shared   # edited models, across load cases
        self.design = design
        self.case = case
        self.geometry = geometry or analyze(design)
        self.frame = frame or structure(design, self.geometry)
        self.model = model or build_model(design, self.geometry)
        f = external_forces(self.model, case)
        self.statics = statics if statics is not None and model is not None \
            else solve_load_case(self.model, case)
        self.bolted = self.statics.stability != "stable" or self.statics.state is None
        if not self.bolted:
            self.holding = self.statics.holding
            self.state = self.statics.state
            self.law = ContactLaw.of_solution(self.model, self.holding,
                                              self._contact_displacements(),
                                              self.statics.contact_forces)
        elif bolted and self.statics.joint_wrenches is not None and self.model.planks:
            self.holding = np.ones(len(self.model.contacts), dtype=bool)
            self.state = solve_system(self.model, self.holding,
                                      np.concatenate([f, np.zeros(6 * self.model.n_springs)]))
            self.law = ContactLaw(self.holding, np.zeros_like(self.holding),
                                  self.model.contact_springs, self.model.friction)
        else:
            raise ValueError(f"case {case.name!r} has no solved equilibrium to differentiate "
                             f"({self.statics.stability}; nothing grounded, or the contact "
                             "forces came from the feasibility program)")
        self.size = design_size(design)

    @property
    def joint_wrenches(self) -> np.ndarray:
        """(nJ, 6) the joint wrenches of the linearized state."""
        return self.model.joint_totals(self.state[self.model.n_dof:]).reshape(-1, 6)

    @property
    def contact_forces(self) -> np.ndarray:
        """(nC, 3) the ground's forces of the linearized state (its contact law, as in
        ``solve_case``: springs where contacts stick, mu N where they slipped) at the
        geometry's contacts (``StaticsModel.corner_forces``: the support stations'
        shared out to their corners)."""
        return self.model.corner_forces(self.law.forces(self._contact_displacements()))

    def _contact_displacements(self) -> np.ndarray:
        """(nK, 3) m: each contact point's displacement in the linearized state."""
        return self.model.contact_displacements(self.state)

    def step(self, dof: Dof) -> float:
        """The difference step for ``dof`` in its own unit."""
        fraction, degrees = assembly_steps(self.model)
        return degrees if dof.is_rotation else fraction * self.size

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
                minus = self.design if self.one_sided else \
                    apply_dof(self.design, self.frame, dof, -h)
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
                             if contact.plank in ids or contact.on in ids)
            pending.append((dof, h, changed, joints, contacts, plus, minus))
            edits.append((plus, joints, contacts))
            if not self.one_sided:
                edits.append((minus, joints, contacts))
        followed = iter(follow_many(geometry, edits))
        for dof, h, changed, joints, contacts, plus, minus in pending:
            plus_side = (plus, *next(followed))
            minus_side = (minus, tuple(geometry.joints[j] for j in joints),
                          tuple(geometry.contacts[k] for k in contacts)) if self.one_sided \
                else (minus, *next(followed))
            self.shared[dof] = _Stepped(h, changed, joints, contacts, plus_side, minus_side)

    def derivatives(self, dofs: list[Dof]) -> Sensitivity:
        """Eq. 6 for every DOF that can move."""
        moving, sides, blocked = [], [], {}
        self._step(dofs)
        for dof in dofs:
            stepped = self.shared[dof]
            if isinstance(stepped, Blocked):
                blocked[dof.name] = stepped.reason
                continue
            if isinstance(stepped, OutOfReach):     # not for the tiny difference step
                blocked[dof.name] = str(stepped)
                continue
            weight = 1.0 / ((1.0 if self.one_sided else 2.0) * stepped.h)
            minus_offset = 0.0 if self.one_sided else -stepped.h
            sides += [AssemblySide(len(moving), weight, stepped.h, stepped.changed,
                                   stepped.joints, stepped.contacts, *stepped.plus),
                      AssemblySide(len(moving), -weight, minus_offset, stepped.changed,
                                   stepped.joints, stepped.contacts, *stepped.minus)]
            moving.append(dof)
        model = self.model
        n_joints, n_contacts = len(model.joints), model.n_corners
        if not moving:
            return Sensitivity(self.case.name, (), np.zeros((0, n_joints, 6)),
                               np.zeros((0, n_contacts, 3)), blocked, np.zeros((0, n_joints)))
        springs = self.law.tangent(self._contact_displacements())
        width = max(1, tol.SENSITIVITY_BLOCK_BYTES // (8 * len(self.state)))
        planks = self._planks_read(sides)
        parts = []
        for start in range(0, len(moving), width):
            end = min(start + width, len(moving))
            block = [replace(side, column=side.column - start) for side in sides
                     if start <= side.column < end]
            parts.append(self._rates(block, end - start, springs, planks))
        joint_rates, contact_rates, length_rates, *bending = \
            (np.concatenate(arrays) for arrays in zip(*parts))
        return Sensitivity(self.case.name, tuple(moving), joint_rates, contact_rates,
                           blocked, length_rates, *bending)

    def _planks_read(self, sides: list[AssemblySide]) -> np.ndarray | None:
        """The local planks whose sag and stress rates are read: all (None) in a model of
        at most SENSITIVITY_ALL_PLANKS planks; in a larger one those the DOFs change and
        the planks jointed to them (sorted), the others' rates taken as 0 (a plank far
        from every change bends by a vanishing amount more; every suggestion and range
        end is checked in full)."""
        model = self.model
        if model.beams is None or len(model.planks) <= tol.SENSITIVITY_ALL_PLANKS:
            return None
        local = {i: k for k, i in enumerate(model.planks)}
        changed = {local[i] for side in sides for i in side.changed if i in local}
        pairs = model.node_plank[model.joint_nodes].reshape(-1, 2)
        touched = np.isin(pairs, list(changed)).any(axis=1)
        return np.union1d(np.array(sorted(changed), dtype=int),
                          pairs[touched].ravel()).astype(int)

    def _rates(self, sides: list[AssemblySide], n_dofs: int, springs: np.ndarray,
               planks: np.ndarray | None = None) -> tuple[np.ndarray, ...]:
        """Eq. 6 for ``n_dofs`` DOFs (the columns of ``sides``): their joint wrench rates
        (D, nJ, 6), contact force rates (D, nK, 3), joint length rates (D, nJ) and plank
        sag, span and stress rates (D, nP) each (of ``planks``, ``_planks_read``).
        ``derivatives`` hands the DOFs over a block at a time (at most
        SENSITIVITY_BLOCK_BYTES of right-hand sides), so that no dense all-DOF x
        all-unknown matrix is ever made."""
        model = self.model
        differences = assembly_differences(model, self.state, self.law, self.case.name,
                                           sides, n_dofs, planks)
        map_rates, length_rates = differences.maps, differences.lengths
        if self.law.slipping.any():         # a slipping contact's tangent is not symmetric
            rates = solve_with_springs(model, springs, differences.residual)
        else:
            rates = solve_system(model, self.holding, differences.residual)  # (n, n_dofs)
        n = model.n_dof
        joint_rates = model.joint_totals(rates[n:]).T.reshape(n_dofs, -1, 6)
        if differences.arms is not None:    # a part's arm moves with the edit too
            forces = self.state[n:].reshape(-1, 6)[:, :3]
            turned = np.cross(differences.arms, forces[None], axis=2)          # (D, nS, 3)
            np.add.at(joint_rates, (slice(None), model.joint_parts, slice(3, None)), turned)
        q = self.state[:n].reshape(-1, 6)[model.contact_node]               # (nK, 6)
        dq = rates[:n].T.reshape(n_dofs, -1, 6)[:, model.contact_node]      # (D, nK, 6)
        dw = (np.einsum("dkab,kb->dka", map_rates, q)
              + np.einsum("kab,dkb->dka", model.contact_maps, dq))
        if model.rest_node is not None:     # a resting corner moves against its support
            rows, nodes = model.rest_rows, model.rest_node[model.rest_rows]
            q_b = self.state[:n].reshape(-1, 6)[nodes]
            dq_b = rates[:n].T.reshape(n_dofs, -1, 6)[:, nodes]
            dw[:, rows] -= (np.einsum("dkab,kb->dka", differences.rest_maps[:, rows], q_b)
                            + np.einsum("kab,dkb->dka", model.rest_maps[rows], dq_b))
        contact_rates = model.corner_forces(-np.einsum("kab,dkb->dka", springs, dw))
        if differences.shares is not None:  # a station's share moves with the edit too
            station = self.law.forces(self._contact_displacements())[model.n_corners:]
            moved = differences.shares[:, :, None] * station[None]             # (D, nSt, 3)
            for side, sign in ((0, -1.0), (1, 1.0)):
                np.add.at(contact_rates, (slice(None), model.station_corners[:, side]),
                          sign * moved)
        bending = differences.plank_rates(rates[:n])
        return (joint_rates, contact_rates, length_rates, *bending)



@dataclass(frozen=True)
class _Stepped:
    """A DOF stepped by +-h (or +h and 0): the planks it changes (design indices), the
    geometry joints and contacts on them, and (design, those joints followed, those
    contacts followed) per side."""

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
