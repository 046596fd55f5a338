"""Unilateral, frictional ground contacts: ``solve_case`` and its active set.

``_ActiveSet`` switches contacts between STICK and LIFT until every normal force is
admissible, then lets contacts outside their friction cone slip: Tresca problems, each
the minimum of a convex energy in which every corner presses or lifts as its
displacement says and slips at a fixed friction cap (``friction._FrictionEnergy``), the
caps updated to mu N until they agree; when that fails, the linear programs of
``feasibility`` decide between 'lift-off', 'sliding' and stable, and a stable case's
forces come from Newton's method on the whole contact law (``newton``), else from the
program itself.  What a case reports, once decided (stable, sliding, lift-off, the
programs' forces), ``outcomes._Outcomes`` builds: ``_ActiveSet`` inherits it.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.anchored import anchored_system
from furncheck.statics.condense import _accurate
from furncheck.statics.friction import (
    _anderson,
    _FrictionEnergy,
    balance_sizes,
    contact_magnitudes,
    past_sliding,
)
from furncheck.statics.model import (
    CaseStatics,
    StaticsModel,
    rigid_motions,
    spread,
    spring_rows,
)
from furncheck.statics.outcomes import LIFT, STICK, _Outcomes


def solve_case(model: StaticsModel, f: np.ndarray, start: np.ndarray | None = None,
               near: CaseStatics | None = None) -> CaseStatics:
    """Equilibrium of one load case with unilateral, frictional ground contacts.

    ``start`` (bool per contact, optional): the contacts expected to hold, e.g. those
    that held in the case before.  The active set starts there instead of from every
    contact holding, to the same equilibrium (where the frictional contact problem has
    one solution), only sooner.  ``near`` (optional): the same case solved on a design
    of which this one is a small edit (a range's or a line search's probe); its holding
    contacts are the start where ``start`` is not given, and where the friction phase
    runs it starts from that case's friction caps and displacements (``_near_start``),
    falling back to its own start where that does not settle.

    Where the normal phase's statuses cycle (a contact that pulls while its anchor holds
    it sideways sinks once lifted), the friction phase, with friction capped, takes over
    from the last iterate.  Where the friction phase's caps do not settle, the semismooth
    Newton method on the whole contact law (``newton``) is tried from its last
    minimizer.  When the active set, the friction phase and that cannot settle, the
    linear programs of ``feasibility`` decide: 'lift-off' only when no equilibrium exists
    with normal forces >= 0 even with unlimited friction, 'sliding' only when none exists
    inside the friction cones; otherwise the case is stable, with the equilibrium of the
    contact law that the semismooth Newton method (``newton``) reaches from every contact
    sticking, or where it reaches none, the admissible contact forces closest to the
    elastic solution (``closest_admissible``) and the joint forces they imply.
    """
    if not model.planks:
        return CaseStatics("stable", np.zeros((0, 6)), np.zeros((0, 3)))
    solver = _ActiveSet(model, f, _force_scale(model, f), near)
    if start is None and near is not None:
        start = near.holding
    all_stick = np.full(len(model.contacts), STICK)
    attempts = [(all_stick, False), (all_stick, True)]
    if start is not None and len(start) == len(all_stick) and not start.all():
        held = start if model.contact_anchored is None else start | model.contact_anchored
        attempts.insert(0, (np.where(held, STICK, LIFT), False))
    normal = None
    for initial, one_at_a_time in attempts:
        found = solver.normal_phase(initial, one_at_a_time)
        if found is None:
            continue
        status, solution, settled = found
        if settled:
            normal = status, solution
            break
        # the statuses cycle: contacts that pull while their anchors hold them sideways
        # and sink once lifted; with friction capped the friction phase may settle them
        frictional = solver.friction_phase(status, solution)
        if frictional is not None:
            settled_status, settled = frictional
            return solver.stable(settled, settled_status)
    if normal is None:
        from furncheck.statics.feasibility import unilateral_feasible

        feasible = unilateral_feasible(model, f)
        if not feasible.exists:
            return solver.unstable("lift-off", feasible)
        bolted = solver.solve(all_stick)
        target = np.zeros((len(model.contacts), 3)) if bolted is None \
            else bolted.contact_forces
        return solver.from_programs(target, on_failure=None, bolted=bolted)
    status, solution = normal
    if solver.within_cones(solution):
        return solver.stable(solution, status)
    frictional = solver.friction_phase(status, solution)
    if frictional is not None:
        settled_status, settled = frictional
        return solver.stable(settled, settled_status)
    if solver.cycled:       # the caps did not settle: not a sign of sliding
        settled = solver.by_newton(solver.last_ground)
        if settled is not None:
            return settled
    return solver.from_programs(solution.contact_forces, on_failure=solution,
                                bolted=solver.solve(all_stick))


class _Solution:
    """A contact state's equilibrium: contact forces and displacements (nK, 3), the
    grounded planks' displacements x_g (``ground``), and the whole solution [q; h] from
    them (``q``, ``h``: expanded through the condensation when first asked for; the
    iterations read only the contacts)."""

    def __init__(self, solver: _ActiveSet, contact_forces: np.ndarray,
                 contact_displacements: np.ndarray, ground: np.ndarray):
        self.contact_forces = contact_forces
        self.contact_displacements = contact_displacements
        self.ground = ground
        self._solver = solver

    @cached_property
    def _expanded(self) -> np.ndarray:
        solver = self._solver
        return solver.condensed.expand(solver.inner_part, self.ground)

    @property
    def q(self) -> np.ndarray:
        return self._expanded[:self._solver.model.n_dof]

    @property
    def h(self) -> np.ndarray:
        return self._expanded[self._solver.model.n_dof:]


class _ActiveSet(_Outcomes):
    """Contact state iterations for one load case (statuses STICK, LIFT)."""

    def __init__(self, model: StaticsModel, f: np.ndarray, scale: float,
                 near: CaseStatics | None = None):
        self.model = model
        self.near = near
        self.f = f
        self.condensed = model.condensation
        if self.condensed is not None:
            self.inner_part, self.ground_rhs = self.condensed.load(f)
        self.scale = scale
        self.force_tol = tol.FORCE_REL_TOL * scale
        self.disp_tol = self.force_tol / model.contact_stiffness
        self.mu = model.friction
        self.anchored = model.contact_anchored
        self.cycled, self.last_ground = False, None     # of the last friction phase

    # -- phases --------------------------------------------------------------------------------
    def normal_phase(self, status: np.ndarray, one_at_a_time: bool):
        """Lift contacts that pull, re-seat those that sink, friction unlimited:
        (statuses, solution, settled), settled False when the statuses came back to ones
        already tried (the last iterate is returned: with friction capped, the friction
        phase may still settle it); None when a solve fails or the iterations run out.

        Lifting every pulling contact at once is fast; lifting only the one that pulls
        hardest is the slower, surer fallback.  A lift that leaves a grounded part free
        to move (its holding corners on one line) seats the lifted corners that the
        loads would drive into the floor (``_seat_toppling``) and goes on; where they
        would drive none, the part topples or slides: None.
        """
        status = status.copy()
        seen = set()
        solved, solution = status, None
        for _ in range(tol.CONTACT_ITERATIONS):
            key = status.tobytes()
            if key in seen:
                return solved, solution, False
            seen.add(key)
            found = self.solve(status)
            if found is None:
                if self._restrained(status == STICK) or not self._seat_toppling(status):
                    return None
                continue
            solution = found
            solved = status.copy()
            if not self._update_normals(solution.contact_forces,
                                        solution.contact_displacements, status, one_at_a_time):
                return status, solution, True
        return None

    def friction_phase(self, status: np.ndarray, start: _Solution):
        """Let contacts outside their friction cone slip (paper 5.2, friction anchors).

        A slipping contact's anchor is relocated so that its spring pulls with exactly
        mu N, against the contact's motion: the tangential spring is elastic-perfectly-
        plastic.  With the normal forces N of the last iterate as the caps, the equilibrium
        minimizes a convex energy of the grounded planks' displacements in which every
        corner presses or lifts as its displacement says (see ``_FrictionEnergy``),
        solved by Newton's method with a line search along each step in closed form; the
        caps are then updated from the new normal forces until they agree (to the force
        tolerance): by Newton's method on the caps (``_FrictionEnergy.cap_newton``, which
        also predicts where the next minimum lies), or by Anderson's mixing of the last
        iterates where a Newton update did not shrink the disagreement; once
        FRICTION_CAP_STALLS updates in a row have not beaten the least disagreement so far,
        by relaxed plain updates c + FRICTION_CAP_RELAXATION (mu N - c) until one beats it,
        then by Newton's method again (a corner at the edge between sticking and slipping
        sent Newton's and Anderson's updates round).  The iterations start from ``start``,
        the normal phase's solution, with the caps of its forces (its contacts' statuses
        ``status`` are not needed: the minimization finds which corners press).  Only the
        solution returned is assembled in full.  None if there is no minimum (the load
        exceeds what friction can hold: ``cycled`` False) or the caps do not settle within
        FRICTION_CAP_ITERATIONS (``cycled`` True; ``last_ground``: the last minimizer, from
        which ``solve_case`` starts Newton's method on the whole law before the programs).

        Given a ``near`` case (``solve_case``), the iterations first start from its caps
        and displacements (``_near_start``); where they do not settle from there, they
        start again as above, so that a case that slides or goes round is decided as it
        would be without one (a probe of the elastic cabinet's range in a hundred finds no
        minimum from the near start and settles from its own), and the near start is not
        tried again in this case.
        """
        near = self._near_start()
        if near is not None:
            settled = self._settle(*near)
            if settled is not None:
                return settled
            self.near = None
        return self._settle(start.ground, self._caps(start.contact_forces))

    def _near_start(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(x_g, caps) where the ``near`` case settled, for this model: its grounded
        nodes' displacements and the caps mu N of its contact forces; None without a
        near case that settled (found stable from a contact state, the friction phase or
        Newton's method on the whole law), or where its grounded nodes or contacts are
        not as many as this one's (an edit that changed what stands on the floor).  The
        other nodes may differ (an elastic plank's nodes lie where joints and loads act:
        a probe that slides a shelf moves them), and contacts as many but others only
        make a poorer start (the iterations settle where they would from any).

        From there a probe settles in fewer Newton steps (the elastic cabinet's range:
        median 7 against 20 per phase, 1.7 times fewer in all) at the equilibrium it
        settles at from its own start, within what the iterations leave open: both stop
        once the caps agree with mu N to the force tolerance, and where many corners
        slip, or the friction forces are nearly indeterminate, the forces move more than
        the caps (the range probes of the catalog: at most 1.5e-6 of the loads' weight
        apart, chair-tilted in the rigid model; 3.7e-7 on the elastic cabinet).
        Starting each load case of one design from the case before, tried, took more
        steps than it saved."""
        near = self.near
        if near is None or near.ground is None \
                or len(near.contact_forces) != len(self.model.contacts) \
                or len(near.ground) != len(self.condensed.ground):
            return None
        return near.ground.copy(), self._caps(near.contact_forces)

    def _settle(self, ground: np.ndarray, caps: np.ndarray):
        """The friction phase's iterations from the grounded planks' displacements
        ``ground`` and the caps ``caps``: what ``friction_phase`` returns."""
        history: list[tuple[np.ndarray, np.ndarray]] = []     # (caps, the caps they gave)
        disagreement = least = np.inf
        stalls = 0                          # updates since the least disagreement so far
        self.cycled, self.last_ground = True, ground
        for _ in range(tol.FRICTION_CAP_ITERATIONS):
            energy = _FrictionEnergy(self, caps)
            ground = energy.minimize(ground)
            if ground is None:
                self.cycled = False
                return None
            self.last_ground = ground
            forces, displacements = energy.contact_state(ground)
            new_caps = self._caps(forces)
            residual = new_caps - caps
            size = np.abs(residual).max(initial=0.0)
            if size <= self.force_tol:
                status = np.where(self._pressing(forces), STICK, LIFT)
                return status, self.assemble(ground, forces, displacements)
            least, stalls = (size, 0) if size < least else (least, stalls + 1)
            history = [*history[-tol.FRICTION_CAP_MEMORY:], (caps, new_caps)]
            newton = energy.cap_newton(ground, caps, residual) \
                if size < disagreement and stalls < tol.FRICTION_CAP_STALLS else None
            disagreement = size
            if stalls >= tol.FRICTION_CAP_STALLS:     # going round: relaxed plain updates
                caps = caps + tol.FRICTION_CAP_RELAXATION * residual
            elif newton is None:
                caps = _anderson(history)
            else:
                caps, ground = newton
            if self.anchored is not None:
                caps[self.anchored] = tol.ANCHOR_CAP
        return None

    def by_newton(self, start: np.ndarray) -> CaseStatics | None:
        """The stable equilibrium that the semismooth Newton method on the whole contact
        law (``newton``) reaches from the grounded planks' displacements ``start``; None
        where it reaches none."""
        from furncheck.statics.newton import newton_equilibrium

        found = newton_equilibrium(self, start)
        if found is None:
            return None
        ground, forces, _ = found
        solution = self.assemble(ground, forces, self.contact_displacements(ground))
        return self.stable(solution, np.where(self._pressing(forces), STICK, LIFT))

    def _caps(self, forces: np.ndarray) -> np.ndarray:
        """(nK,) N: the friction caps mu N for contact forces (nK, 3); ANCHOR_CAP for the
        anchors' ties (they never slip)."""
        caps = self.mu * np.maximum(forces[:, 2], 0.0)
        if self.anchored is not None:
            caps[self.anchored] = tol.ANCHOR_CAP
        return caps

    # -- the linear solve ----------------------------------------------------------------------
    def solve(self, status: np.ndarray, stiffness_scale: float = 1.0,
              load_scale: float = 0.0) -> _Solution | None:
        """Solve the mixed system for the given contact states; None if it is a mechanism:
        singular, or regular only by round-off, its grounded planks then moving by more
        than SLIDING_DISPLACEMENT (``friction.past_sliding``; the backward-error check
        passes such a solve: the residual is judged against the matrix times the huge
        displacements).
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
        if stiffness_scale == 1.0 and past_sliding(ground):
            return None     # a mechanism in all but round-off: the springs cannot hold it
        displacement = self.contact_displacements(ground)
        # the anchor springs: k (x the scale) in all three directions where a contact holds
        forces = -(spring_rows(model.contact_springs, trailing=1) * stiffness_scale) \
            * displacement * holding[:, None]
        return self.assemble(ground, forces, displacement)

    def contact_displacements(self, ground: np.ndarray) -> np.ndarray:
        """(nK, 3) m: every contact's displacement (lifted ones too: whether they sink)
        for the grounded planks' displacements x_g (the contacts move with the grounded
        nodes)."""
        q = np.zeros(self.model.n_dof)
        q[self.condensed.ground] = ground
        return self.model.contact_displacements(q)

    def assemble(self, ground: np.ndarray, forces: np.ndarray,
                 displacement: np.ndarray) -> _Solution:
        """The solution from the grounded planks' displacements x_g."""
        return _Solution(self, forces, displacement, ground)

    @cached_property
    def balance_sizes(self) -> tuple[np.ndarray, float, float, np.ndarray]:
        """What the Newton iterations of this case (every friction minimization, and
        ``newton``) measure round-off by: ``friction.balance_sizes`` of its condensed
        system, made once (its contacts' ``friction.contact_magnitudes`` once per model)."""
        kept = self.model.contact_spaces
        if "magnitudes" not in kept:
            kept["magnitudes"] = contact_magnitudes(self.contact_map(),
                                                    self.model.contact_springs_each)
        return balance_sizes(self.condensed.schur, self.ground_rhs, kept["magnitudes"])

    def contact_map(self) -> np.ndarray:
        """(3 nK, n) the contact displacements w = map @ x of every contact (x the grounded
        planks' displacements, w per contact x, y, z; a resting corner's relative to
        the node it rests on), dense, kept per model (``StaticsModel.contact_spaces``)."""
        kept = self.model.contact_spaces
        if "map" not in kept:
            kept["map"] = _contact_map(self.model)
        return kept["map"]

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
    def _update_normals(self, forces: np.ndarray, displacements: np.ndarray,
                        status: np.ndarray, one_at_a_time: bool = False) -> bool:
        """Lift the holding contacts that pull (all, or only the hardest one), re-seat the
        lifted ones that sink, given the contact forces and displacements (nK, 3); whether
        any status changed."""
        normal = forces[:, 2]
        pulling = (status != LIFT) & (normal < -self.force_tol)
        if self.anchored is not None:
            pulling &= ~self.anchored          # an anchor's tie pulls as well as it pushes
        if one_at_a_time and pulling.any():
            hardest = int(np.argmin(np.where(pulling, normal, np.inf)))
            pulling = np.zeros_like(pulling)
            pulling[hardest] = True
        sinking = (status == LIFT) & (displacements[:, 2] < -self.disp_tol)
        status[pulling] = LIFT
        status[sinking] = STICK
        return bool(pulling.any() or sinking.any())

    def _seat_toppling(self, status: np.ndarray) -> bool:
        """Seat (STICK, in ``status``) the lifted contacts that the loads drive into the
        floor where the holding ones leave a grounded part free to move; whether any
        was.

        Lifting a corner that pulls can leave a part on corners along one line (a table
        whose centre of mass lies near the line of two of its feet, after its third and
        fourth feet lifted): no equilibrium of the holding corners alone, though the
        part comes down on another corner.  Its free motions are the rigid ones that
        keep the holding corners in place (``_free_motion``); along the one the loads do
        work on, the lifted corners that move down (into a wall, for a wall's contact:
        against its frame's normal) are those it comes down on.  False
        where they move none down: the part topples (the normal phase gives up, and the
        programs say so).  Where planks rest on others, nothing is seated (their parts'
        motions are coupled through the resting corners)."""
        model = self.model
        if model.rest_node is not None:
            return False
        lifted = status == LIFT
        loads = self.f.reshape(-1, 6)
        seated = False
        for c, nodes in enumerate(model.component_nodes):
            members = np.flatnonzero(model.contact_component == c)
            if not lifted[members].any():
                continue
            nodes = list(nodes)
            velocity = _free_motion(model.contact_points[members], ~lifted[members],
                                    model.node_points[nodes], loads[nodes])
            if velocity is None:
                continue
            inward = velocity[:, 2] if model.contact_frames is None else \
                np.einsum("kj,kj->k", model.contact_frames[members, 2], velocity)
            sinking = lifted[members] & (inward < -tol.SEAT_ROUNDOFF
                                         * float(np.abs(velocity).max()))
            status[members[sinking]] = STICK
            seated |= bool(sinking.any())
        return seated


def _free_motion(points: np.ndarray, holding: np.ndarray, node_points: np.ndarray,
                 loads: np.ndarray) -> np.ndarray | None:
    """(k, 3): the velocity of each contact point (``points``, of one grounded part) in
    the free rigid motion of the part that the loads drive, or None where its holding
    contacts (``holding``) leave it no free motion or the loads do no work on any.

    A rigid motion t = (v, w') (``model.rigid_motions``: translation v, rotation w' / L
    about the points' mean, L their spread) moves point p by R_p t; it is free where
    R_p t = 0 at every holding contact: the null space of their stacked R, whose rank
    counts the singular values above sqrt(MECHANISM_RCOND) of the largest (those of R^T R,
    which ``_rigidly_held`` judges, are their squares).  The loads (``loads``: force and
    moment per node, at ``node_points``) do work g.t on it, g = (F, M / L) with F their
    sum and M their moment about the points' mean; the motion they drive is the free one
    along g's projection onto the free motions (the only one where a single free motion
    is left, a turn about the line through two corners).  A projection that is round-off
    of g (the loads' line of action through that line) drives none."""
    origin, length = spread(points)
    rigid = rigid_motions(points)                                   # (k, 3, 6)
    constraints = rigid[holding].reshape(-1, 6)
    if len(constraints):
        _, values, rows = np.linalg.svd(constraints)
        cut = math.sqrt(tol.MECHANISM_RCOND) * max(float(values[0]), 1e-300)
        free = rows[int((values > cut).sum()):].T                  # (6, r)
    else:
        free = np.eye(6)
    if not free.size:
        return None
    force = loads[:, :3].sum(axis=0)
    moment = (np.cross(node_points - origin, loads[:, :3]) + loads[:, 3:]).sum(axis=0)
    work = np.concatenate([force, moment / length])
    along = free.T @ work
    if not np.linalg.norm(along) > tol.SEAT_ROUNDOFF * np.linalg.norm(work):
        return None
    return rigid @ (free @ along)


def _contact_map(model: StaticsModel) -> np.ndarray:
    """``_ActiveSet.contact_map`` of ``model``."""
    condensed = model.condensation
    maps = model.contact_maps                                       # (nK, 3, 6)
    count, blocks = len(maps), len(condensed.plank_offsets)
    dense = np.zeros((count, 3, blocks, 6))
    dense[np.arange(count), :, condensed.contact_block, :] = maps
    if model.rest_node is not None:         # a resting corner moves against its support
        rows = np.flatnonzero(model.rest_node >= 0)
        dense[rows, :, model.ground_block[model.rest_node[rows]], :] -= model.rest_maps[rows]
    return dense.reshape(3 * count, 6 * blocks)


def _rigidly_held(model: StaticsModel, holding: np.ndarray) -> bool:
    """Whether the ``holding`` contacts hold every grounded component of the model in all
    six rigid directions.  Where planks rest on others, a component is held by its own
    holding contacts and by those of the planks resting on it (each taken as held by what
    it rests on), its rigid motions measured about all of them."""
    resting = model.rest_node is not None
    for c in range(len(model.components)):
        members = (model.contact_component == c) & holding
        if resting:
            members |= (model.rest_component == c) & holding
        if not members.any():
            return False
        if resting:
            rigid = rigid_motions(model.contact_points[members])
            stiffness = (np.transpose(rigid, (0, 2, 1)) @ rigid).sum(axis=0)
        else:
            stiffness = model.rigid_grams[members].sum(axis=0)
        singular = np.linalg.svd(stiffness, compute_uv=False)
        if singular[-1] <= tol.MECHANISM_RCOND * max(singular[0], 1e-300):
            return False
    return True


def _force_scale(model: StaticsModel, f: np.ndarray) -> float:
    """N: sum of the applied force magnitudes (the scale of the force tolerances)."""
    forces = f.reshape(-1, 6)[:, :3]
    return max(float(np.sqrt((forces * forces).sum(axis=1)).sum()), 1e-12)
