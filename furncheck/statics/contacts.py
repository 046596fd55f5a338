"""Unilateral, frictional ground contacts: ``solve_case`` and its active set.

``_ActiveSet`` switches contacts between STICK and LIFT until every normal force is
admissible, then lets contacts outside their friction cone slip by minimizing the convex
energy ``_FrictionEnergy``; when that fails, the linear programs of ``feasibility`` decide
between 'lift-off', 'sliding' and an equilibrium taken from the program itself.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.condense import (
    _accurate,
    _cholesky,
    _condensed_stiffness,
    _Factored,
    anchored_system,
)
from furncheck.statics.feasibility import (
    INFEASIBLE,
    UNDECIDED,
    Feasibility,
    closest_admissible,
    cone_solution,
    unilateral_feasible,
)
from furncheck.statics.model import CaseStatics, StaticsModel, block_sums

STICK, LIFT = 0, 2
_LINE_DETAIL = ("all its ground contacts lie on one line: it can at best balance on that "
                "edge, and the least push about it tips the design over")
_LINE_SLIDING = ("no equilibrium within the friction cones, and its ground contacts lie on "
                 "one line: no forces to show")


def solve_case(model: StaticsModel, f: np.ndarray,
               start: np.ndarray | None = None) -> CaseStatics:
    """Equilibrium of one load case with unilateral, frictional ground contacts.

    ``start`` (bool per contact, optional): the contacts expected to hold, e.g. those
    that held in a design of which this one is a small edit.  The active set starts
    there instead of from every contact holding; the equilibrium it finds is the same
    (the contact problem's solution is unique), only sooner.

    When the active set or the friction phase cannot settle, the linear programs of
    ``feasibility`` decide: 'lift-off' only when no equilibrium exists with normal forces
    >= 0 even with unlimited friction, 'sliding' only when none exists inside the friction
    cones; otherwise the case is stable with the admissible contact forces closest to the
    elastic solution (``closest_admissible``) and the joint forces they imply.
    """
    if not model.planks:
        return CaseStatics("stable", np.zeros((0, 6)), np.zeros((0, 3)))
    solver = _ActiveSet(model, f, _force_scale(model, f))
    all_stick = np.full(len(model.contacts), STICK)
    normal = None
    if start is not None and len(start) == len(all_stick) and not start.all():
        normal = solver.normal_phase(np.where(start, STICK, LIFT), one_at_a_time=False)
    normal = normal or solver.normal_phase(all_stick, one_at_a_time=False) \
        or solver.normal_phase(all_stick, one_at_a_time=True)
    if normal is None:
        feasible = unilateral_feasible(model, f)
        if not feasible.exists:
            return solver.unstable("lift-off", feasible)
        bolted = solver.solve(all_stick)
        target = np.zeros((len(model.contacts), 3)) if bolted is None \
            else bolted.contact_forces
        return solver.from_programs(target, on_failure=None)
    status, solution = normal
    if solver.within_cones(solution):
        return solver.stable(solution, status)
    frictional = solver.friction_phase(status, solution)
    if frictional is not None:
        return solver.stable(frictional[1], frictional[0])
    return solver.from_programs(solution.contact_forces, on_failure=solution)


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
        self.scale = scale
        self.force_tol = tol.FORCE_REL_TOL * scale
        self.disp_tol = self.force_tol / model.contact_stiffness
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
        history: list[tuple[np.ndarray, np.ndarray]] = []     # (caps, the caps they gave)
        for _ in range(tol.FRICTION_CAP_ITERATIONS):
            energy = _FrictionEnergy(self, status != LIFT, caps)
            ground = energy.minimize(ground)
            if ground is None:
                return None
            solution = energy.solution(ground)
            if self._update_normals(solution, status):
                caps = self.mu * np.maximum(solution.contact_forces[:, 2], 0.0)
                history = []
                continue
            new_caps = self.mu * np.maximum(solution.contact_forces[:, 2], 0.0)
            if np.abs(new_caps - caps).max(initial=0.0) <= self.force_tol:
                return status, solution
            history = [*history[-tol.FRICTION_CAP_MEMORY:], (caps, new_caps)]
            caps = _anderson(history)
        return None

        return None

    # -- results -------------------------------------------------------------------------------
    def stable(self, solution: _Solution, status: np.ndarray) -> CaseStatics:
        return CaseStatics("stable", _wrenches(solution.h), solution.contact_forces,
                           state=np.concatenate([solution.q, solution.h]),
                           holding=status != LIFT, displacements=solution.q)

    def sliding(self, solution: _Solution) -> CaseStatics:
        """Report a case that slides, with the forces it would need if friction were endless."""
        model = self.model
        forces = solution.contact_forces
        over = self._outside_cones(forces)
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
                           detail, displacements=solution.q)

    def unstable(self, stability: str, program: Feasibility | None = None) -> CaseStatics:
        """Report a case without admissible equilibrium: forces as if bolted to the ground
        (none when even bolted down the contacts, all on one line, cannot hold it)."""
        bolted = self.solve(np.full(len(self.model.contacts), STICK))
        undecided = "" if program is None or program.status != UNDECIDED else (
            f"; the solver could not prove it either way ({program.message}), so the "
            "case is not passed")
        if bolted is None:
            detail = _LINE_DETAIL if stability == "lift-off" else _LINE_SLIDING
            return CaseStatics(stability, None, None, (), detail + undecided)
        pulling = bolted.contact_forces[:, 2] < -self.force_tol
        if stability == "lift-off":
            detail = ("no equilibrium with the ground only pushing: the load's line of action "
                      "falls outside the support polygon, the design topples "
                      f"(held down, the ground would have to pull "
                      f"{-bolted.contact_forces[pulling, 2].sum():.4g} N)")
        else:
            detail = (f"no equilibrium within the friction cones (mu = {self.mu:g}); forces "
                      "shown as if the design were bolted to the ground")
        return CaseStatics(stability, _wrenches(bolted.h), bolted.contact_forces,
                           self._plank_ids(pulling), detail + undecided,
                           displacements=bolted.q)

    def from_programs(self, target: np.ndarray, on_failure: _Solution | None) -> CaseStatics:
        """The verdict of the friction program when the iterations could not settle:
        stable with the admissible contact forces closest to ``target`` (the elastic
        forces), else 'sliding' (with the forces of ``on_failure`` if given)."""
        cone = cone_solution(self.model, self.f)
        if not cone.exists:
            if on_failure is not None and cone.status == INFEASIBLE:
                return self.sliding(on_failure)
            return self.unstable("sliding", cone)
        closest = closest_admissible(self.model, self.f, target)
        return self.prescribed(closest if self._admissible(closest) else cone.forces)

    def _admissible(self, forces: np.ndarray) -> bool:
        """Whether contact forces (nK, 3) press (N >= 0) and stay inside the friction
        cones, to the force tolerance (the exact balance of ``closest_admissible`` moves
        them by round-off; should it ever move them out, the program's own are used)."""
        return bool(np.all(forces[:, 2] >= -self.force_tol)
                    and not self._outside_cones(forces).any())

    def prescribed(self, contact_forces: np.ndarray) -> CaseStatics:
        """Joint wrenches for contact forces fixed by a feasibility program.

        The contact forces enter as loads; feeble springs (contact stiffness x 1e-9) only
        remove the rigid motions and carry no force since the loads balance (the solve is
        judged against the loads' scale: its own right-hand side is round-off).
        """
        model = self.model
        f = self.f.copy()
        for row, force in enumerate(contact_forces):
            k = model.contact_node[row]
            f[6 * k:6 * k + 6] += model.contact_maps[row].T @ force
        feeble = _ActiveSet(model, f, self.scale)
        solution = feeble.solve(np.full(len(model.contacts), STICK), stiffness_scale=1e-9,
                                load_scale=self.scale)
        if solution is None:
            return CaseStatics("lift-off", None, None, (), _LINE_DETAIL)
        return CaseStatics("stable", _wrenches(solution.h), contact_forces.copy(),
                           holding=contact_forces[:, 2] > self.force_tol,
                           displacements=solution.q)

    def within_cones(self, solution: _Solution) -> bool:
        return not self._outside_cones(solution.contact_forces).any()

    def _outside_cones(self, forces: np.ndarray) -> np.ndarray:
        """(nK,) bool: contact forces (nK, 3) whose sideways part exceeds mu N (beyond the
        force tolerance)."""
        return np.hypot(forces[:, 0], forces[:, 1]) > self.mu * forces[:, 2] + self.force_tol

    # -- the linear solve ----------------------------------------------------------------------
    def solve(self, status: np.ndarray, stiffness_scale: float = 1.0,
              load_scale: float = 0.0) -> _Solution | None:
        """Solve the mixed system for the given contact states; None if it is a mechanism.
        ``load_scale`` (N): the loads' size, for judging a solve whose right-hand side is
        far smaller (balanced loads).

        Only the grounded planks' six displacements each are solved for here (a small dense
        system, see ``_Condensed``, factored once per contact state: ``anchored_system``);
        the rest follows by one matrix-vector product.
        """
        model, condensed = self.model, self.condensed
        holding = status == STICK
        if condensed is None or not self._restrained(holding):
            return None
        system = anchored_system(model, holding, stiffness_scale)
        ground = system.solve(self.ground_rhs)
        if ground is None or not _accurate(system.matrix, ground, self.ground_rhs, load_scale):
            return None
        plank_q = ground.reshape(-1, 6)[condensed.contact_block]           # (nK, 6)
        displacement = (model.contact_maps @ plank_q[:, :, None])[:, :, 0]
        # the anchor springs: k (x the scale) in all three directions where a contact holds
        forces = -(model.contact_stiffness * stiffness_scale) * displacement \
            * holding[:, None]
        return self.assemble(ground, forces, displacement)

    def assemble(self, ground: np.ndarray, forces: np.ndarray,
                 displacement: np.ndarray) -> _Solution:
        """The full solution from the grounded planks' displacements x_g."""
        x = self.condensed.expand(self.inner_part, ground)
        return _Solution(x[:self.model.n_dof], x[self.model.n_dof:], forces, displacement,
                         ground)

    def _restrained(self, holding: np.ndarray) -> bool:
        """Every grounded component is held in all six rigid directions by its holding
        contacts (springs to their anchors in all three directions): kept per model and
        contact state."""
        model = self.model
        key = holding.tobytes()
        known = model.restrained_states
        if key not in known:
            known[key] = _rigidly_held(model, holding)
        return known[key]

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


class _FrictionEnergy:
    """The condensed potential energy with elastic-perfectly-plastic friction springs.

    For the grounded planks' displacements x (x_g of ``_Condensed``), with w_k = M_k x
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
        self.k = solver.model.contact_stiffness

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
        per_block = block_sums(self.block, generalized, self.blocks)
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
        gradient = None
        for _ in range(tol.FRICTION_NEWTON_ITERATIONS):
            if gradient is None:
                gradient = self._gradient(x)
            if np.abs(gradient).max(initial=0.0) <= self._gradient_floor(x):
                return x
            hessian = self._hessian(x)
            shift = tol.SOLVE_RESIDUAL * max(float(np.abs(np.diag(hessian)).max()), 1.0)
            hessian[np.diag_indices(len(x))] += shift
            step = _Factored(hessian, _cholesky(hessian)).solve(-gradient)
            if step is None:
                return None
            t, gradient = self._line_search(x, step, float(gradient @ step))
            x = x + t * step
            if np.abs(x).max() > tol.SLIDING_DISPLACEMENT:
                return None
        return None

    def _line_search(self, x: np.ndarray, step: np.ndarray,
                     slope0: float) -> tuple[float, np.ndarray | None]:
        """t in (0, 1] near the minimum of Phi(x + t step): Phi is convex, so its slope
        along the step rises with t from ``slope0`` < 0; take the full step if the slope is
        still <= 0 there, else find the slope's zero by regula falsi (Illinois), stopping
        once it is within LINE_SEARCH_SLOPE of |slope0| (Newton needs no more), after at
        most LINE_SEARCH_ITERATIONS tries.  With t, the gradient there (None when t is not
        where the last gradient was taken)."""
        gradient = self._gradient(x + step)
        high_slope = float(gradient @ step)
        if high_slope <= 0.0:
            return 1.0, gradient
        low, high, low_slope = 0.0, 1.0, min(slope0, -1e-300)
        best, best_gradient = 0.0, None
        side = 0
        for _ in range(tol.LINE_SEARCH_ITERATIONS):
            t = low - low_slope * (high - low) / (high_slope - low_slope)
            t = min(max(t, low + 0.01 * (high - low)), high - 0.01 * (high - low))
            gradient = self._gradient(x + t * step)
            slope = float(gradient @ step)
            if abs(slope) <= tol.LINE_SEARCH_SLOPE * abs(slope0):
                return t, gradient
            if slope < 0.0:
                low, low_slope, best, best_gradient = t, slope, t, gradient
                if side == -1:
                    high_slope *= 0.5
                side = -1
            else:
                high, high_slope = t, slope
                if side == 1:
                    low_slope *= 0.5
                side = 1
        if best > 0.0:
            return best, best_gradient
        return 0.5 * high, None

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


def _anderson(history: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """The next friction caps of the fixed point c = G(c) (G: the caps mu N that the
    equilibrium under caps c gives) by Anderson's mixing of the last iterates (c_i, G(c_i)):
    the weights a (sum 1) that minimize |sum a_i (G(c_i) - c_i)|, then sum a_i G(c_i), kept
    >= 0.  The plain update G(c) converges linearly (by factors of 0.1 to 0.4 on the
    catalog's cabinet); this takes a few iterations instead of fifteen."""
    if len(history) == 1:
        return history[0][1]
    residuals = np.array([g - c for c, g in history])                # (m, nK)
    images = np.array([g for _, g in history])
    differences = residuals[1:] - residuals[:1]                       # a_0 = 1 - sum a_i
    weights, *_ = np.linalg.lstsq(differences.T, -residuals[0], rcond=None)
    mixed = images[0] + weights @ (images[1:] - images[:1])
    return np.maximum(mixed, 0.0)


def _rigidly_held(model: StaticsModel, holding: np.ndarray) -> bool:
    """Whether the ``holding`` contacts hold every grounded component of the model in all
    six rigid directions."""
    grams = model.rigid_grams
    for c in range(len(model.components)):
        members = (model.contact_component == c) & holding
        if not members.any():
            return False
        stiffness = grams[members].sum(axis=0)
        singular = np.linalg.svd(stiffness, compute_uv=False)
        if singular[-1] <= tol.MECHANISM_RCOND * max(singular[0], 1e-300):
            return False
    return True


def _force_scale(model: StaticsModel, f: np.ndarray) -> float:
    """N: sum of the applied force magnitudes (the scale of the force tolerances)."""
    forces = f.reshape(-1, 6)[:, :3]
    return max(float(np.sqrt((forces * forces).sum(axis=1)).sum()), 1e-12)


def _wrenches(h: np.ndarray) -> np.ndarray:
    return h.reshape(-1, 6).copy()
