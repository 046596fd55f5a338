"""Static equilibrium of rigid planks: the paper's mixed formulation (section 5.1).

Unknowns are a small rigid displacement per plank, q_i = (u_i, theta_i) (m, rad, about the
plank centre), and the wrench of every nail joint, h_j = (h^t, h^r) (N, N m, world frame,
what the joint's first plank exerts on its second, moment about the joint point).  With
G the linearized joint deviation map (d = G q) and E = diag(eps^t, eps^r) the joint
compliances, stationarity of the potential energy (paper eq. 3) is the sparse system

    [ K_c  G^T ] [q]   [f]
    [ G    -E  ] [h] = [0]

where f holds self-weight and loads (force, moment about each centre) and K_c the ground
contact springs.  Contacts are unilateral penalty springs with friction anchors (section 5.2):
a contact is *stick* (three springs to its anchor), *slip* (normal spring; friction mu N along
a fixed direction, i.e. the anchor relocated to the cone's edge) or *lifted* (no force).  An
active-set loop switches contacts until every force is admissible.  When that loop cannot
finish, small linear programs decide whether any admissible equilibrium exists at all, so
the verdicts 'lift-off' and 'sliding' mean exactly what contract section 3 says.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase
from furncheck.geometry import Geometry

STICK, LIFT = 0, 2
_MECHANISM_DETAIL = ("the planks rest on too few ground points to be held even if bolted "
                     "down (all their ground contacts lie on one line)")
_SIX = np.arange(6)


@dataclass(frozen=True)
class StaticsModel:
    """The load-independent part of a design's statics.

    planks   : design plank indices taking part (those of grounded components)
    joints   : geometry joint indices taking part
    contacts : geometry contact indices taking part
    G        : (6 nJ, 6 nP) sparse joint deviation map
    contact_maps : (nK, 3, 6) displacement of each contact point from its plank's q
    contact_plank : (nK,) local plank number of each contact
    contact_component : (nK,) component number of each contact
    components : local plank numbers of each grounded component
    """

    design: Design
    geometry: Geometry
    planks: tuple[int, ...]
    joints: tuple[int, ...]
    contacts: tuple[int, ...]
    G: sp.csr_matrix
    compliance: np.ndarray
    contact_maps: np.ndarray
    contact_plank: np.ndarray
    contact_points: np.ndarray
    contact_component: np.ndarray
    components: tuple[tuple[int, ...], ...]
    friction: float

    @property
    def n_dof(self) -> int:
        return 6 * len(self.planks)

    @cached_property
    def condensation(self) -> _Condensation | None:
        """The contact-free part of the system, condensed onto the grounded planks."""
        return _condense(self)


@dataclass(frozen=True)
class CaseStatics:
    """Solution of one load case.

    stability : 'stable', 'lift-off', 'sliding', or 'mechanism' (no force state could be
                computed: the planks are free to move even when held at every contact)
    joint_wrenches : (nJ, 6) force N and moment N m per model joint, or None (mechanism)
    contact_forces : (nK, 3) N, the ground's force on each model contact, or None
    culprits  : plank ids whose contacts lift or slide (for messages)
    detail    : a sentence with the numbers behind an unstable verdict
    """

    stability: str
    joint_wrenches: np.ndarray | None
    contact_forces: np.ndarray | None
    culprits: tuple[str, ...] = ()
    detail: str = ""
    state: np.ndarray | None = None     # the solution [q; h] of a stable case
    holding: np.ndarray | None = None   # (nK,) bool: contacts on the ground (not lifted)


def build_model(design: Design, geometry: Geometry) -> StaticsModel:
    """Assemble G, the compliances and the contact maps for the grounded components."""
    grounded_planks = sorted(i for comp, g in zip(geometry.components, geometry.grounded)
                             if g for i in comp)
    local = {plank: k for k, plank in enumerate(grounded_planks)}
    joints = [j for j, joint in enumerate(geometry.joints)
              if design.plank_index[joint.planks[0]] in local]
    plank_of = {design.planks[i].id: i for i in grounded_planks}
    contacts = [k for k, c in enumerate(geometry.contacts) if c.plank in plank_of]

    G = _joint_map(design, geometry, joints, local)
    compliance = np.concatenate([
        np.r_[np.full(3, tol.JOINT_COMPLIANCE_T),
              np.full(3, tol.joint_compliance_r(geometry.joints[j].edge_thickness))]
        for j in joints]) if joints else np.zeros(0)

    maps, owner, points = [], [], []
    for k in contacts:
        contact = geometry.contacts[k]
        plank_index = design.plank_index[contact.plank]
        maps.append(_point_map(contact.point - design.planks[plank_index].center_array))
        owner.append(local[plank_index])
        points.append(contact.point)
    components = tuple(tuple(local[i] for i in comp)
                       for comp, g in zip(geometry.components, geometry.grounded) if g)
    component_of = {p: c for c, comp in enumerate(components) for p in comp}
    return StaticsModel(
        design=design, geometry=geometry, planks=tuple(grounded_planks), joints=tuple(joints),
        contacts=tuple(contacts), G=G, compliance=compliance,
        contact_maps=np.array(maps).reshape(-1, 3, 6),
        contact_plank=np.array(owner, dtype=int),
        contact_points=np.array(points).reshape(-1, 3),
        contact_component=np.array([component_of[p] for p in owner], dtype=int),
        components=components, friction=design.material.friction)


def _joint_map(design: Design, geometry: Geometry, joints: list[int],
               local: dict[int, int]) -> sp.csr_matrix:
    """(6 nJ, 6 nP) linearized joint deviations d = G q (paper eq. 1, small rotations):

        d^t = (u_a + theta_a x r_a) - (u_b + theta_b x r_b),   d^r = theta_a - theta_b

    with a, b the joint's first and second plank and r = joint point - plank centre.
    """
    n_joints = len(joints)
    if n_joints == 0:
        return sp.csr_matrix((0, 6 * len(local)))
    points = np.array([geometry.joints[j].point for j in joints])
    rows, cols, vals = [], [], []
    for side, position in ((1.0, 0), (-1.0, 1)):
        planks = np.array([design.plank_index[geometry.joints[j].planks[position]]
                           for j in joints])
        centres = np.array([design.planks[i].center_array for i in planks])
        blocks = np.zeros((n_joints, 6, 6))
        blocks[:, :3, :3] = np.eye(3)
        blocks[:, :3, 3:] = -_skew_many(points - centres)
        blocks[:, 3:, 3:] = np.eye(3)
        base_col = 6 * np.array([local[i] for i in planks])
        rows.append(np.broadcast_to(6 * np.arange(n_joints)[:, None, None] + _SIX[None, :, None],
                                    blocks.shape).ravel())
        cols.append(np.broadcast_to(base_col[:, None, None] + _SIX[None, None, :],
                                    blocks.shape).ravel())
        vals.append(side * blocks.ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(6 * n_joints, 6 * len(local)))


def external_forces(model: StaticsModel, case: LoadCase) -> np.ndarray:
    """(6 nP,) self-weight and the case's loads: force (N) and moment about the centre (N m)."""
    design = model.design
    f = np.zeros(model.n_dof)
    local = {design.planks[i].id: k for k, i in enumerate(model.planks)}
    for k, i in enumerate(model.planks):
        plank = design.planks[i]
        f[6 * k + 2] -= design.plank_mass(plank) * tol.GRAVITY
    for load in case.loads:
        if load.plank not in local:
            continue
        k = local[load.plank]
        plank = design.planks[model.planks[k]]
        force = np.asarray(load.force, dtype=float)
        f[6 * k:6 * k + 3] += force
        if load.point is not None:
            f[6 * k + 3:6 * k + 6] += np.cross(np.asarray(load.point) - plank.center_array, force)
    return f


def solve_case(model: StaticsModel, f: np.ndarray) -> CaseStatics:
    """Equilibrium of one load case with unilateral, frictional ground contacts."""
    if not model.planks:
        return CaseStatics("stable", np.zeros((0, 6)), np.zeros((0, 3)))
    solver = _ActiveSet(model, f, _force_scale(model, f))
    all_stick = np.full(len(model.contacts), STICK)
    normal = solver.normal_phase(all_stick, one_at_a_time=False) \
        or solver.normal_phase(all_stick, one_at_a_time=True)
    if normal is None:
        if not _unilateral_feasible(model, f):
            return solver.unstable("lift-off")
        # An equilibrium exists but the active set did not find it: take one from the
        # feasibility program itself.
        forces = _cone_solution(model, f)
        return solver.prescribed(forces) if forces is not None else solver.unstable("sliding")
    status, solution = normal
    if solver.within_cones(solution):
        return solver.stable(solution, status)
    frictional = solver.friction_phase(status, solution)
    if frictional is not None:
        return solver.stable(frictional[1], frictional[0])
    forces = _cone_solution(model, f)
    if forces is None:
        return solver.sliding(solution)
    return solver.prescribed(forces)


@dataclass
class _Solution:
    q: np.ndarray
    h: np.ndarray
    contact_forces: np.ndarray
    contact_displacements: np.ndarray
    ground: np.ndarray              # x_g, the grounded planks' displacements


class _ActiveSet:
    """Contact state iterations for one load case (statuses STICK, LIFT)."""

    def __init__(self, model: StaticsModel, f: np.ndarray, scale: float):
        self.model = model
        self.f = f
        self.condensed = model.condensation
        if self.condensed is not None:
            self.inner_part, self.ground_rhs = self.condensed.load(f)
        self.force_tol = tol.FORCE_REL_TOL * scale
        self.disp_tol = self.force_tol / tol.CONTACT_STIFFNESS
        self.mu = model.friction

    # -- phases --------------------------------------------------------------------------------
    def normal_phase(self, status: np.ndarray, one_at_a_time: bool):
        """Lift contacts that pull, re-seat those that sink, friction unlimited.

        Lifting every pulling contact at once is fast; lifting only the one that pulls
        hardest is the slower, surer fallback.
        """
        status = status.copy()
        seen = set()
        for _ in range(tol.CONTACT_ITERATIONS):
            key = status.tobytes()
            if key in seen:
                return None
            seen.add(key)
            solution = self.solve(status)
            if solution is None:
                return None
            if not self._update_normals(solution, status, one_at_a_time):
                return status, solution
        return None

    def friction_phase(self, status: np.ndarray, start: _Solution):
        """Let contacts outside their friction cone slip (paper 5.2, friction anchors).

        A slipping contact's anchor is relocated so that its spring pulls with exactly
        mu N, against the contact's motion: the tangential spring is elastic-perfectly-
        plastic.  With the normal forces N of the last iterate as the caps, the equilibrium
        minimizes a convex energy of the grounded planks' displacements (see
        ``_FrictionEnergy``), solved by Newton's method with a line search; then the caps
        are updated from the new normal forces until they agree.  None if there is no
        minimum (the load exceeds what friction can hold) or the caps do not settle.
        """
        status = status.copy()
        ground = start.ground
        caps = self.mu * np.maximum(start.contact_forces[:, 2], 0.0)
        for _ in range(tol.FRICTION_CAP_ITERATIONS):
            energy = _FrictionEnergy(self, status != LIFT, caps)
            ground = energy.minimize(ground)
            if ground is None:
                return None
            solution = energy.solution(ground)
            if self._update_normals(solution, status):
                caps = self.mu * np.maximum(solution.contact_forces[:, 2], 0.0)
                continue
            new_caps = self.mu * np.maximum(solution.contact_forces[:, 2], 0.0)
            if np.abs(new_caps - caps).max(initial=0.0) <= self.force_tol:
                return status, solution
            caps = new_caps
        return None

    # -- results -------------------------------------------------------------------------------
    def stable(self, solution: _Solution, status: np.ndarray) -> CaseStatics:
        return CaseStatics("stable", _wrenches(solution.h), solution.contact_forces,
                           state=np.concatenate([solution.q, solution.h]),
                           holding=status != LIFT)

    def sliding(self, solution: _Solution) -> CaseStatics:
        """Report a case that slides, with the forces it would need if friction were endless."""
        model = self.model
        forces = solution.contact_forces
        tangential = np.hypot(forces[:, 0], forces[:, 1])
        over = tangential > self.mu * forces[:, 2] + self.force_tol
        sideways = float(np.hypot(*forces[:, :2].sum(axis=0)))
        capacity = self.mu * float(forces[:, 2].sum())
        centre = (forces[:, 2] @ model.contact_points) / max(float(forces[:, 2].sum()), 1e-300)
        arms = model.contact_points - centre
        twist = abs(float((arms[:, 0] * forces[:, 1] - arms[:, 1] * forces[:, 0]).sum()))
        radius = float(np.sqrt(forces[:, 2] @ (arms ** 2).sum(axis=1)
                               / max(float(forces[:, 2].sum()), 1e-300)))
        significant = twist > 0.05 * sideways * radius + self.force_tol
        twist_text = f" and a {twist:.3g} N m twist" if significant else ""
        detail = (f"no equilibrium within the friction cones (mu = {self.mu:g}): the ground "
                  f"must resist {sideways:.4g} N sideways{twist_text}, friction gives at most "
                  f"{capacity:.4g} N")
        return CaseStatics("sliding", _wrenches(solution.h), forces, self._plank_ids(over),
                           detail)

    def unstable(self, stability: str) -> CaseStatics:
        """Report a case without admissible equilibrium: forces as if bolted to the ground."""
        bolted = self.solve(np.full(len(self.model.contacts), STICK))
        if bolted is None:
            return CaseStatics("mechanism", None, None, (), _MECHANISM_DETAIL)
        pulling = bolted.contact_forces[:, 2] < -self.force_tol
        if stability == "lift-off":
            detail = ("no equilibrium with the ground only pushing: the load's line of action "
                      "falls outside the support polygon, the design topples "
                      f"(held down, the ground would have to pull "
                      f"{-bolted.contact_forces[pulling, 2].sum():.4g} N)")
        else:
            detail = ("the contact iteration found no admissible contact state; forces shown "
                      "as if the design were bolted to the ground")
        return CaseStatics(stability, _wrenches(bolted.h), bolted.contact_forces,
                           self._plank_ids(pulling), detail)

    def prescribed(self, contact_forces: np.ndarray) -> CaseStatics:
        """Joint wrenches for contact forces fixed by a feasibility program.

        The contact forces enter as loads; feeble springs (CONTACT_STIFFNESS x 1e-9) only
        remove the rigid motions and carry no force since the loads balance.
        """
        model = self.model
        f = self.f.copy()
        for row, force in enumerate(contact_forces):
            k = model.contact_plank[row]
            f[6 * k:6 * k + 6] += model.contact_maps[row].T @ force
        feeble = _ActiveSet(model, f, 1.0)
        solution = feeble.solve(np.full(len(model.contacts), STICK), stiffness_scale=1e-9)
        if solution is None:
            return CaseStatics("mechanism", None, None, (), _MECHANISM_DETAIL)
        return CaseStatics("stable", _wrenches(solution.h), contact_forces.copy())

    def within_cones(self, solution: _Solution) -> bool:
        forces = solution.contact_forces
        tangential = np.hypot(forces[:, 0], forces[:, 1])
        return bool(np.all(tangential <= self.mu * forces[:, 2] + self.force_tol))

    # -- the linear solve ----------------------------------------------------------------------
    def solve(self, status: np.ndarray, stiffness_scale: float = 1.0) -> _Solution | None:
        """Solve the mixed system for the given contact states; None if it is a mechanism.

        Only the grounded planks' six displacements each are solved for here (a small dense
        system, see ``_Condensation``); the rest follows by one matrix-vector product.
        """
        model, condensed = self.model, self.condensed
        springs = self._spring_matrices(status) * stiffness_scale
        if condensed is None or not self._restrained(springs):
            return None
        maps = model.contact_maps
        stiffness = _condensed_stiffness(model, springs)
        try:
            ground = np.linalg.solve(stiffness, self.ground_rhs)
        except np.linalg.LinAlgError:
            return None
        if not _accurate(stiffness, ground, self.ground_rhs):
            return None
        plank_q = ground.reshape(-1, 6)[condensed.contact_block]           # (nK, 6)
        displacement = (maps @ plank_q[:, :, None])[:, :, 0]
        forces = -(springs @ displacement[:, :, None])[:, :, 0]
        return self.assemble(ground, forces, displacement)

    def assemble(self, ground: np.ndarray, forces: np.ndarray,
                 displacement: np.ndarray) -> _Solution:
        """The full solution from the grounded planks' displacements x_g."""
        x = self.condensed.expand(self.inner_part, ground)
        return _Solution(x[:self.model.n_dof], x[self.model.n_dof:], forces, displacement,
                         ground)

    def _spring_matrices(self, status: np.ndarray) -> np.ndarray:
        return _anchor_springs(status == STICK)

    def _restrained(self, springs: np.ndarray) -> bool:
        """Every grounded component is held in all six rigid directions by its contacts."""
        model = self.model
        for c in range(len(model.components)):
            members = model.contact_component == c
            if not members.any():
                return False
            points = model.contact_points[members]
            reference = points.mean(axis=0)
            arm = points - reference
            length = max(float(np.abs(arm).max()), 1e-6)
            rigid = np.zeros((len(points), 3, 6))
            rigid[:, :, :3] = np.eye(3)
            rigid[:, :, 3:] = -_skew_many(arm) / length
            stiffness = (np.transpose(rigid, (0, 2, 1)) @ springs[members] @ rigid).sum(axis=0)
            singular = np.linalg.svd(stiffness, compute_uv=False)
            if singular[-1] <= tol.MECHANISM_RCOND * max(singular[0], 1e-300):
                return False
        return True

    # -- state updates -------------------------------------------------------------------------
    def _update_normals(self, solution: _Solution, status: np.ndarray,
                        one_at_a_time: bool = False) -> bool:
        normal = solution.contact_forces[:, 2]
        pulling = (status != LIFT) & (normal < -self.force_tol)
        if one_at_a_time and pulling.any():
            hardest = int(np.argmin(np.where(pulling, normal, np.inf)))
            pulling = np.zeros_like(pulling)
            pulling[hardest] = True
        sinking = (status == LIFT) & (solution.contact_displacements[:, 2] < -self.disp_tol)
        status[pulling] = LIFT
        status[sinking] = STICK
        return bool(pulling.any() or sinking.any())

    def _plank_ids(self, mask: np.ndarray) -> tuple[str, ...]:
        design, model = self.model.design, self.model
        ids = {design.planks[model.planks[model.contact_plank[k]]].id
               for k in np.nonzero(mask)[0]}
        return tuple(p.id for p in design.planks if p.id in ids)


_ROUNDOFF = 1e-13
"""Relative round-off of a matrix-vector product of the condensed system (a few hundred
terms of double precision)."""


def _anchor_springs(holding: np.ndarray) -> np.ndarray:
    """(nK, 3, 3): contact force = -S w for contact point displacement w: springs to the
    anchor in all three directions where the contact holds, none where it lifted."""
    springs = np.zeros((len(holding), 3, 3))
    springs[holding] = np.eye(3) * tol.CONTACT_STIFFNESS
    return springs


def _condensed_stiffness(model: StaticsModel, springs: np.ndarray) -> np.ndarray:
    """S0 + K_c: the condensed system's matrix with the contact springs (n_g, n_g)."""
    condensed = model.condensation
    maps = model.contact_maps
    blocks = np.transpose(maps, (0, 2, 1)) @ (springs @ maps)       # (nK, 6, 6)
    per_plank = np.zeros((len(condensed.plank_offsets), 6, 6))
    np.add.at(per_plank, condensed.contact_block, blocks)
    stiffness = condensed.schur.copy()
    for block, offset in zip(per_plank, condensed.plank_offsets):
        stiffness[offset:offset + 6, offset:offset + 6] += block
    return stiffness


def system_matrix(model: StaticsModel, holding: np.ndarray) -> sp.csr_matrix:
    """The full mixed matrix [[K_c, G^T], [G, -E]] with anchor springs at the holding
    contacts (sparse, (6 nP + 6 nJ) square): the A of the paper's eq. 6."""
    n = model.n_dof
    maps = model.contact_maps
    blocks = np.transpose(maps, (0, 2, 1)) @ (_anchor_springs(holding) @ maps)
    base = 6 * model.contact_plank[:, None, None]
    rows = np.broadcast_to(base + _SIX[None, :, None], blocks.shape).ravel()
    cols = np.broadcast_to(base + _SIX[None, None, :], blocks.shape).ravel()
    K_c = sp.csr_matrix((blocks.ravel(), (rows, cols)), shape=(n, n))
    return sp.bmat([[K_c, model.G.T], [model.G, -sp.diags(model.compliance)]], format="csr")


def solve_system(model: StaticsModel, holding: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """A^-1 rhs for ``system_matrix(model, holding)`` and rhs (n,) or (n, k), reusing the
    design's condensation (one sparse LU per design): the solve behind eq. 6."""
    condensed = model.condensation
    rhs = np.asarray(rhs, dtype=float)
    single = rhs.ndim == 1
    R = rhs[:, None] if single else rhs
    inner = condensed.lu.solve(R[condensed.inner]) if len(condensed.inner) else \
        np.zeros((0, R.shape[1]))
    ground_rhs = R[condensed.ground] - condensed.coupling.T @ inner
    ground = np.linalg.solve(_condensed_stiffness(model, _anchor_springs(holding)), ground_rhs)
    out = np.zeros_like(R)
    out[condensed.ground] = ground
    out[condensed.inner] = inner - condensed.reduced @ ground
    return out[:, 0] if single else out


class _FrictionEnergy:
    """The condensed potential energy with elastic-perfectly-plastic friction springs.

    For the grounded planks' displacements x (x_g of ``_Condensation``), with w_k = M_k x
    the displacement of contact k, k the spring stiffness and c_k = mu N_k its friction cap:

        Phi(x) = 1/2 x.S0.x - b.x + sum_active [ 1/2 k w_z^2 + psi(|w_t|) ]
        psi(r) = 1/2 k r^2           if k r <= c      (sticking to its anchor)
               = c r - c^2 / (2 k)   otherwise         (slipping: force c against w_t)

    Phi is convex and once differentiable; its minimizer is the equilibrium, and it has
    none when the loads exceed what friction can hold (the design slides).
    """

    def __init__(self, solver: _ActiveSet, active: np.ndarray, caps: np.ndarray):
        self.solver = solver
        condensed = solver.condensed
        self.model = solver.model
        self.maps = solver.model.contact_maps[active]           # (na, 3, 6)
        self.block = condensed.contact_block[active]            # plank block of each
        self.blocks = len(condensed.plank_offsets)
        self.caps = caps[active]
        self.active = active
        self.schur = condensed.schur
        self.rhs = solver.ground_rhs
        self.k = tol.CONTACT_STIFFNESS

    def _displacements(self, x: np.ndarray) -> np.ndarray:
        """(na, 3): w_k = M_k x, each contact from its plank's six displacements."""
        return (self.maps @ x.reshape(-1, 6)[self.block][:, :, None])[:, :, 0]

    def _forces(self, x: np.ndarray):
        """Contact displacements w (na, 3), |w_t|, sticking mask and forces (na, 3) at x."""
        k, caps = self.k, self.caps
        w = self._displacements(x)
        r = np.hypot(w[:, 0], w[:, 1])
        sticking = k * r <= caps
        safe_r = np.where(r > 0.0, r, 1.0)
        unit = w[:, :2] / safe_r[:, None]
        force_t = np.where(sticking[:, None], -k * w[:, :2], -caps[:, None] * unit)
        return w, safe_r, sticking, np.column_stack([force_t, -k * w[:, 2]])

    def _gradient(self, x: np.ndarray) -> np.ndarray:
        """dPhi/dx: the out-of-balance generalized force on the grounded planks."""
        force = self._forces(x)[3]
        generalized = (np.transpose(self.maps, (0, 2, 1)) @ force[:, :, None])[:, :, 0]
        per_block = np.zeros((self.blocks, 6))
        np.add.at(per_block, self.block, generalized)
        return self.schur @ x - self.rhs - per_block.ravel()

    def _hessian(self, x: np.ndarray) -> np.ndarray:
        """d2Phi/dx2: S0 plus each contact's tangent stiffness (a slipping spring keeps
        only the stiffness across its slip direction, caps / |w_t|)."""
        k, caps = self.k, self.caps
        w, safe_r, sticking, _ = self._forces(x)
        unit = w[:, :2] / safe_r[:, None]
        tangent = np.where(sticking[:, None, None], k * np.eye(2),
                           (caps / safe_r)[:, None, None]
                           * (np.eye(2) - unit[:, :, None] * unit[:, None, :]))
        springs = np.zeros((len(self.active), 3, 3))
        springs[self.active, :2, :2] = tangent
        springs[self.active, 2, 2] = k
        return _condensed_stiffness(self.model, springs)

    def minimize(self, x: np.ndarray) -> np.ndarray | None:
        """Newton's method from x with an exact line search on the directional derivative
        (the energy itself is a sum of large terms that cancel, too noisy to compare near
        the minimum; its gradient is not).  None if Phi has no minimum (it falls without
        bound along a sliding motion) or Newton does not converge."""
        for _ in range(tol.FRICTION_NEWTON_ITERATIONS):
            gradient = self._gradient(x)
            if np.abs(gradient).max(initial=0.0) <= self._gradient_floor(x):
                return x
            hessian = self._hessian(x)
            shift = tol.SOLVE_RESIDUAL * max(float(np.abs(np.diag(hessian)).max()), 1.0)
            try:
                step = np.linalg.solve(hessian + shift * np.eye(len(x)), -gradient)
            except np.linalg.LinAlgError:
                return None
            x = x + self._line_search(x, step) * step
            if np.abs(x).max() > tol.SLIDING_DISPLACEMENT:
                return None
        return None

    def _line_search(self, x: np.ndarray, step: np.ndarray) -> float:
        """t in (0, 1] minimizing Phi(x + t step): Phi is convex, so its slope along the
        step rises with t; take the full step if the slope is still <= 0 there, else
        bisect for the zero of the slope."""
        if float(self._gradient(x + step) @ step) <= 0.0:
            return 1.0
        low, high = 0.0, 1.0
        for _ in range(tol.LINE_SEARCH_BISECTIONS):
            middle = 0.5 * (low + high)
            if float(self._gradient(x + middle * step) @ step) <= 0.0:
                low = middle
            else:
                high = middle
        return max(low, 0.5 * high)

    def _gradient_floor(self, x: np.ndarray) -> float:
        """N: the force tolerance, or the round-off floor of S0 x if that is larger."""
        roundoff = _ROUNDOFF * float(np.abs(self.schur).max(initial=0.0)
                                     * np.abs(x).sum() + np.abs(self.rhs).max(initial=0.0))
        return max(self.solver.force_tol, roundoff)

    def solution(self, x: np.ndarray) -> _Solution:
        force = self._forces(x)[3]
        forces = np.zeros((len(self.active), 3))
        forces[self.active] = force
        displacement = np.zeros((len(self.active), 3))
        displacement[self.active] = self._displacements(x)
        return self.solver.assemble(x, forces, displacement)


# --- existence of an admissible equilibrium (linear programs) ---------------------------------

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


# --- small helpers ----------------------------------------------------------------------------

@dataclass(frozen=True)
class _Condensation:
    """Static condensation of the mixed system onto the grounded planks.

    Order the unknowns as g (the six displacements of each plank with ground contacts) and
    i (all other plank displacements and every joint wrench).  Contact springs touch only
    the g-g block, so with A the contact-free matrix

        S0 = A_gg - A_gi A_ii^-1 A_ig,   X = A_ii^-1 A_ig,   y = A_ii^-1 b_i

    are computed once per design (A_ii by one sparse LU) and per load case, and each
    contact-state iteration only solves (S0 + K_c) x_g = b_g - A_gi y, a dense system of
    6 x (grounded planks); then x_i = y - X x_g.
    """

    ground: np.ndarray           # indices of g in the full unknown vector
    inner: np.ndarray            # indices of i
    lu: object                   # SuperLU of A_ii
    coupling: sp.csc_matrix      # A_ig (n_i, n_g)
    reduced: np.ndarray          # X = A_ii^-1 A_ig
    schur: np.ndarray            # S0
    contact_block: np.ndarray    # per contact, number of its plank's 6-block in x_g
    plank_offsets: np.ndarray    # offset of each grounded plank's block in x_g
    size: int

    def load(self, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(y, b_g - A_gi y) for the plank loads f (the joint rows have no load)."""
        b = np.zeros(self.size)
        b[:len(f)] = f
        inner = self.lu.solve(b[self.inner]) if len(self.inner) else np.zeros(0)
        return inner, b[self.ground] - self.coupling.T @ inner

    def expand(self, inner_part: np.ndarray, ground: np.ndarray) -> np.ndarray:
        """The full unknown vector [q; h] from x_g."""
        x = np.zeros(self.size)
        x[self.ground] = ground
        x[self.inner] = inner_part - self.reduced @ ground
        return x


def _condense(model: StaticsModel) -> _Condensation | None:
    """Build the condensation; None if the contact-free part is singular (a plank that
    is neither grounded nor jointed to a grounded plank cannot be held)."""
    n, m = model.n_dof, model.G.shape[0]
    G = model.G.tocoo()
    diagonal = n + np.arange(m)
    A = sp.csc_matrix((np.concatenate([G.data, G.data, -model.compliance]),
                       (np.concatenate([G.col, n + G.row, diagonal]),
                        np.concatenate([n + G.row, G.col, diagonal]))), shape=(n + m, n + m))
    grounded, contact_block = np.unique(model.contact_plank, return_inverse=True)
    ground = (6 * grounded[:, None] + _SIX[None, :]).ravel()
    inner = np.setdiff1d(np.arange(n + m), ground)
    ni = len(inner)
    order = np.concatenate([inner, ground])
    permuted = A[order][:, order].tocsc()
    A_ii = permuted[:ni, :ni].tocsc()
    coupling = permuted[:ni, ni:].tocsc()
    lu, reduced = None, np.zeros((ni, len(ground)))
    if ni:
        lu = _factor(A_ii, np.asarray(coupling.sum(axis=1)).ravel())
        if lu is None:
            return None
        reduced = lu.solve(coupling.toarray()) if len(ground) else reduced
    schur = permuted[ni:, ni:].toarray() - np.asarray(coupling.T @ reduced)
    return _Condensation(ground, inner, lu, coupling, reduced, schur,
                         contact_block.astype(int), 6 * np.arange(len(grounded)), n + m)


def _factor(A: sp.csc_matrix, probe: np.ndarray):
    """SuperLU of the symmetric matrix A, or None if it is singular.  The factors are
    checked on the right-hand side ``probe``.

    A symmetric fill-reducing ordering with diagonal pivots keeps the factors about ten
    times sparser than the default; if it solves the probe columns poorly (a tiny pivot),
    partial pivoting (SuperLU's default) is used instead.
    """
    rhs = probe if np.any(probe) else np.ones(A.shape[0])
    for options in (_SYMMETRIC_LU, {}):
        try:
            lu = spla.splu(A, **options)
        except RuntimeError:
            continue
        if _accurate(A, lu.solve(rhs), rhs):
            return lu
    return None


def _accurate(A, x: np.ndarray, b: np.ndarray) -> bool:
    """Whether x solves A x = b to a normwise backward error below SOLVE_RESIDUAL:
    max|A x - b| <= tol (max row sum of |A| x max|x| + max|b|)."""
    if not np.all(np.isfinite(x)):
        return False
    norm = float(abs(A).sum(axis=1).max()) if A.shape[0] else 0.0
    scale = norm * float(np.abs(x).max(initial=0.0)) + float(np.abs(b).max(initial=0.0))
    return float(np.abs(A @ x - b).max(initial=0.0)) <= tol.SOLVE_RESIDUAL * max(scale, 1e-300)


_SYMMETRIC_LU = {"permc_spec": "MMD_AT_PLUS_A", "diag_pivot_thresh": 0.0,
                 "options": {"SymmetricMode": True}}


def _force_scale(model: StaticsModel, f: np.ndarray) -> float:
    """N: sum of the applied force magnitudes (the scale of the force tolerances)."""
    return max(float(np.linalg.norm(f.reshape(-1, 6)[:, :3], axis=1).sum()), 1e-12)


def _wrenches(h: np.ndarray) -> np.ndarray:
    return h.reshape(-1, 6).copy()


def _skew(v: np.ndarray) -> np.ndarray:
    """[v]x, so that _skew(v) @ w = v x w."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _skew_many(v: np.ndarray) -> np.ndarray:
    out = np.zeros((len(v), 3, 3))
    out[:, 0, 1], out[:, 0, 2] = -v[:, 2], v[:, 1]
    out[:, 1, 0], out[:, 1, 2] = v[:, 2], -v[:, 0]
    out[:, 2, 0], out[:, 2, 1] = -v[:, 1], v[:, 0]
    return out


def _point_map(r: np.ndarray) -> np.ndarray:
    """(3, 6): displacement of a point at offset r from the centre, [I, -[r]x] @ (u, theta)."""
    return np.hstack([np.eye(3), -_skew(r)])
