"""The friction phase's energy: contacts that slip, as elastic-perfectly-plastic springs.

``_FrictionEnergy`` is the condensed potential energy of the grounded nodes' displacements
with each active contact's anchor spring capped at its friction force mu N (``caps``);
its minimizer is the equilibrium for those caps (``contacts._ActiveSet.friction_phase``
updates the caps from the normal forces it gives).  Newton steps solve through the
all-sticking system by Woodbury's identity (``_ContactSpace``), and the line search along
a step is exact in closed form (``_StepSlope``: each contact's displacement is affine in
the step length, its stick/slip breakpoints the roots of a quadratic).  ``_anderson``
mixes cap iterates where Newton's method on the caps does not shrink their mismatch.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.anchored import _Factored, anchored_system, condensed_stiffness
from furncheck.statics.lapack import cholesky, routines
from furncheck.statics.model import StaticsModel, spring_rows

if TYPE_CHECKING:
    from furncheck.statics.contacts import _ActiveSet


_EYE2 = np.eye(2)
_TWO = np.arange(2)

_ROUNDOFF = 1e-13
"""Relative round-off of a matrix-vector product of the condensed system (a few hundred
terms of double precision)."""


class _ContactSpace:
    """What the friction energy of one set of active contacts needs besides the caps, kept
    per active set (the caps change from one iteration to the next, the set seldom):

    map : (3 na, n) the contact displacements w = map @ x (x the grounded planks'
        displacements, w per active contact x, y, z), dense
    tangential : (2 na, n) its rows of w_x and w_y, T
    system : A = S0 + k sum_active M^T M, the condensed matrix with every active contact
        sticking, ``_Factored`` (``anchored_system``, kept per model)
    reach : (n, 2 na) A^-1 T^T, or None (not built yet, or A singular)
    compliance : (2 na, 2 na) T A^-1 T^T: the contacts' tangential displacements under
        unit tangential forces at the contacts, all sticking
    normal_compliance : (na, 2 na) their normal displacements under the same forces

    ``reach`` and the compliances cost about two factorings of the Hessian, so they are
    built only for an active set that needs more than DIRECT_NEWTON_SOLVES solves.
    """

    def __init__(self, model: StaticsModel, active: np.ndarray):
        key = active.tobytes()
        shared = model.contact_spaces.get(key)
        if shared is None:          # the maps and A's pieces serve every load case
            shared = model.contact_spaces[key] = _SharedSpace(model, active)
        self.map, self.tangential = shared.map, shared.tangential
        self.model, self.active = model, active
        self.reach: np.ndarray | None = None
        self.solves = 0
        self._shared = shared

    def through_sticking(self) -> bool:
        """Whether a Hessian solve (counted here, per load case) goes through A by
        Woodbury's identity: once more than DIRECT_NEWTON_SOLVES were asked of this active
        set, if A is regular."""
        self.solves += 1
        if self.solves == tol.DIRECT_NEWTON_SOLVES + 1:
            shared = self._shared.through_sticking(self.model)
            self.system, self.reach = shared.system, shared.reach
            if self.reach is not None:
                self.compliance = shared.compliance
                self.normal_compliance = shared.normal_compliance
        return self.reach is not None


class _SharedSpace:
    """What ``_ContactSpace`` holds of an active set that does not depend on the load case
    (kept per model: ``StaticsModel.contact_spaces``): the maps, and A's factor, reach
    and compliances once a case asks for them (``through_sticking``)."""

    def __init__(self, model: StaticsModel, active: np.ndarray):
        condensed = model.condensation
        maps = model.contact_maps[active]                           # (na, 3, 6)
        count, blocks = len(maps), len(condensed.plank_offsets)
        dense = np.zeros((count, 3, blocks, 6))
        dense[np.arange(count), :, condensed.contact_block[active], :] = maps
        if model.rest_node is not None:         # a resting corner moves against its support
            resting = np.flatnonzero(model.rest_node[active] >= 0)
            if resting.size:
                rows = np.flatnonzero(active)[resting]
                dense[resting, :, model.ground_block[model.rest_node[rows]], :] -= \
                    model.rest_maps[rows]
        self.map = dense.reshape(3 * count, 6 * blocks)
        self.tangential = np.ascontiguousarray(dense[:, :2].reshape(2 * count, 6 * blocks))
        self.active = active        # not the model: it keeps this (no reference cycle)
        self.system = None

    def through_sticking(self, model: StaticsModel) -> _SharedSpace:
        """Itself, with A factored (``anchored_system`` of ``model``, the one that keeps
        it), reach = A^-1 T^T (None if A is singular) and the compliances, made on the
        first call."""
        if self.system is None:
            self.system = anchored_system(model, self.active)
            self.reach = self.system.solve(self.tangential.T)
            if self.reach is not None:
                self.compliance = self.tangential @ self.reach
                self.normal_compliance = self.map[2::3] @ self.reach
        return self


class _FrictionEnergy:
    """The condensed potential energy with elastic-perfectly-plastic friction springs.

    For the grounded planks' displacements x (x_g of ``_Condensed``), with w_k = M_k x
    the displacement of contact k, k the spring stiffness and c_k = mu N_k its friction cap:

        Phi(x) = 1/2 x.S0.x - b.x + sum_active [ 1/2 k w_z^2 + psi(|w_t|) ]
        psi(r) = 1/2 k r^2           if k r <= c      (sticking to its anchor)
               = c r - c^2 / (2 k)   otherwise         (slipping: force c against w_t)

    Phi is convex and once differentiable; its minimizer is the equilibrium, and it has
    none when the loads exceed what friction can hold (the design slides).

    Its Hessian is H = A - sum_slipping T_k^T D_k T_k: the all-sticking matrix A of
    ``_ContactSpace`` (factored once per active set) less, at each slipping contact, the
    tangential stiffness it lost, D_k = k I - (c / r) (I - u u^T) (u its slip direction,
    T_k its two rows of T).  Newton's steps solve with H through A by Woodbury's identity
    (a dense system of twice the slipping contacts' size) instead of factoring H afresh,
    once the active set has had DIRECT_NEWTON_SOLVES solves.
    """

    def __init__(self, solver: _ActiveSet, active: np.ndarray, caps: np.ndarray):
        self.solver = solver
        self.model = solver.model
        self.space = solver.contact_space(active)
        self.caps = caps[active]
        self.active = active
        self.schur = solver.condensed.schur
        self.rhs = solver.ground_rhs
        self.k = spring_rows(solver.model.contact_springs, active)   # N/m, scalar or (na,)
        self._schur_size = float(np.abs(self.schur).max(initial=0.0))
        self._rhs_size = float(np.abs(self.rhs).max(initial=0.0))
        self._forces_at: np.ndarray | None = None     # the x of the kept _forces
        self._slips_at: np.ndarray | None = None      # the x of the kept _slips

    def _forces(self, x: np.ndarray):
        """Contact displacements w (na, 3), |w_t| (1 where 0), sticking mask and forces
        (na, 3) at x (kept for the last x: the gradient, the Newton step and the line
        search all start from them)."""
        if x is self._forces_at:
            return self._forces_kept
        k, caps = self.k, self.caps
        w = (self.space.map @ x).reshape(-1, 3)
        r = np.hypot(w[:, 0], w[:, 1])
        sticking = k * r <= caps
        safe_r = np.where(r > 0.0, r, 1.0)
        forces = w * -np.where(sticking, k, caps / safe_r)[:, None]  # force_t = -scale w_t
        forces[:, 2] = w[:, 2] * -k
        self._forces_at, self._forces_kept = x, (w, safe_r, sticking, forces)
        return self._forces_kept

    def _gradient(self, x: np.ndarray) -> np.ndarray:
        """dPhi/dx: the out-of-balance generalized force on the grounded planks."""
        force = self._forces(x)[3]
        return self.schur @ x - self.rhs - self.space.map.T @ force.ravel()

    def _slips(self, x: np.ndarray):
        """The slipping contacts at x (indices among the active ones), their rows in T
        (2 each), their slip directions u (p, 2) and D_k (p, 2, 2), the stiffness each
        lost by slipping: k I - (c / r) (I - u u^T) - SLIP_STIFFNESS k u u^T (the last a
        feeble spring along the slip, so that a design free to slide is not singular)."""
        if x is self._slips_at:
            return self._slips_kept
        w, safe_r, sticking, _ = self._forces(x)
        slipping = np.flatnonzero(~sticking)
        unit = w[slipping, :2] / safe_r[slipping, None]
        along = unit[:, :, None] * unit[:, None, :]
        across = slip_tangent(self.caps[slipping], safe_r[slipping], unit)
        lost = spring_rows(self.k, slipping, 2) * (_EYE2 - tol.SLIP_STIFFNESS * along) - across
        rows = (2 * slipping[:, None] + _TWO).ravel()
        self._slips_at, self._slips_kept = x, (slipping, rows, unit, lost)
        return self._slips_kept

    def _hessian_solve(self, x: np.ndarray, rhs: np.ndarray) -> np.ndarray | None:
        """H^-1 rhs (rhs (n,) or (n, m)) by Woodbury's identity: with a = A^-1 rhs,
        H^-1 rhs = a + Y_P (I - D G_PP)^-1 D T_P a, Y_P = A^-1 T_P^T (``reach``) and
        G_PP = T_P A^-1 T_P^T (``compliance``) of the slipping contacts P; by H itself
        for an active set's first DIRECT_NEWTON_SOLVES solves, or where A or the Woodbury
        system is singular.  None if H is singular."""
        space = self.space
        if not space.through_sticking():
            return self._factored_hessian(x).solve(rhs)
        base = space.system.solve(rhs)
        slipping, rows, _, lost = self._slips(x)
        if base is None or not slipping.size:
            return base
        weights = self._woodbury(rows, lost, space.tangential[rows] @ base)
        if weights is None:
            return self._factored_hessian(x).solve(rhs)
        return base + space.reach[:, rows] @ weights

    def _woodbury(self, rows: np.ndarray, lost: np.ndarray,
                  moved: np.ndarray) -> np.ndarray | None:
        """(I - D G_PP)^-1 D v for v = ``moved`` (2p,) or (2p, m), the slipping contacts'
        tangential displacements T_P a; None if singular."""
        count, tail = len(lost), moved.shape[1:]
        pulled = np.einsum("kij,kj...->ki...", lost, moved.reshape((count, 2) + tail))
        compliance = self.space.compliance[rows[:, None], rows].reshape(count, 2, 2 * count)
        capacitance = np.eye(2 * count) - np.einsum(
            "kij,kjm->kim", lost, compliance).reshape(2 * count, 2 * count)
        weights, info = routines().gesv(capacitance, pulled.reshape((2 * count,) + tail))[2:]
        return weights if info == 0 else None

    def _factored_hessian(self, x: np.ndarray) -> _Factored:
        """The Hessian at x, assembled and shifted by its round-off (SOLVE_RESIDUAL of its
        diagonal) so that a slipping contact's zero stiffness along its slip leaves it
        factorable, and factored."""
        k, caps = self.k, self.caps
        w, safe_r, sticking, _ = self._forces(x)
        unit = w[:, :2] / safe_r[:, None]
        tangent = np.where(sticking[:, None, None], spring_rows(k, None, 2) * _EYE2,
                           slip_tangent(caps, safe_r, unit))
        springs = np.zeros((len(self.active), 3, 3))
        springs[self.active, :2, :2] = tangent
        springs[self.active, 2, 2] = k
        hessian = condensed_stiffness(self.model, springs)
        shift = tol.SOLVE_RESIDUAL * max(float(np.abs(np.diag(hessian)).max()), 1.0)
        hessian[np.diag_indices(len(x))] += shift
        return _Factored(hessian, cholesky(hessian))

    def minimize(self, x: np.ndarray) -> np.ndarray | None:
        """Newton's method from x with a line search on the directional derivative (the
        energy itself is a sum of large terms that cancel, too noisy to compare near the
        minimum; its gradient is not), until the out-of-balance force is within the
        force tolerance.  None if Phi has no minimum (it falls without bound along a
        sliding motion: the displacements pass SLIDING_DISPLACEMENT) or Newton does not
        converge."""
        gradient = self._gradient(x)
        best = np.inf                       # the least out-of-balance force met so far
        for _ in range(tol.FRICTION_NEWTON_ITERATIONS):
            size = float(np.abs(gradient).max(initial=0.0))
            if size <= self._gradient_floor(x):
                return x
            best = min(best, size)
            step = self._hessian_solve(x, -gradient)
            if step is None:
                return None
            x, gradient = self._line_search(x, step, gradient, best)
            if not np.abs(x).max() <= tol.SLIDING_DISPLACEMENT:
                return None
            if gradient is None:
                gradient = self._gradient(x)
        return None

    def _line_search(self, x: np.ndarray, step: np.ndarray, gradient: np.ndarray,
                     best: float) -> tuple[np.ndarray, np.ndarray | None]:
        """The next point along the Newton step from x, and the gradient there if it was
        computed on the way (None: not yet).

        Phi is convex, so its slope along the step rises with t from g.step < 0.  The full
        step (t = 1) is taken where the slope there is within LINE_SEARCH_SLOPE of the
        start's (Newton's step near the minimum); where it is still < 0 but has risen to
        LINE_SEARCH_EXTEND of the start's or less; and, whatever the slope, where it brings
        the largest out-of-balance force below FULL_STEP_GRADIENT of ``best``, the least
        met so far (a step that lets many contacts change between sticking and slipping
        at once).  Otherwise the slope's zero is sought (``_StepSlope``: each contact's
        displacement is affine in t, so the slope is a sum of closed forms, O(contacts)
        per t): below t = 1 between the breakpoints where contacts pass between sticking
        and slipping, beyond t = 1 (the energy is much flatter than the Hessian said, as
        along a sliding motion) by doubling t, up to where the displacements pass
        SLIDING_DISPLACEMENT (Phi has no minimum there: the design slides)."""
        w, _, _, force = self._forces(x)
        slope0 = float(gradient @ step)
        full = x + step
        full_gradient = self._gradient(full)
        full_slope = float(full_gradient @ step)
        if not slope0 < 0.0:                # no descent left but round-off
            return full, full_gradient
        if abs(full_slope) <= tol.LINE_SEARCH_SLOPE * -slope0:
            return full, full_gradient
        if full_slope < 0.0 and (full_slope > tol.LINE_SEARCH_EXTEND * slope0
                                 or not np.abs(full).max() <= tol.SLIDING_DISPLACEMENT):
            return full, full_gradient
        if np.abs(full_gradient).max() <= tol.FULL_STEP_GRADIENT * best:
            return full, full_gradient
        moved = (self.space.map @ step).reshape(-1, 3)
        slope = _StepSlope(w, force, moved, self.k, self.caps, slope0,
                           float(step @ (self.schur @ step)))
        t = slope.zero(full_slope,
                       (tol.SLIDING_DISPLACEMENT + np.abs(x).max()) / np.abs(step).max())
        return x + t * step, None

    def _gradient_floor(self, x: np.ndarray) -> float:
        """N: the force tolerance, or the round-off floor of S0 x if that is larger."""
        return balance_floor(self.solver.force_tol, self._schur_size, self._rhs_size, x)

    def cap_newton(self, x: np.ndarray, caps: np.ndarray, residual: np.ndarray):
        """Newton's step for the caps' fixed point c = G(c) (G: the caps mu N that the
        minimizer x of Phi with caps c gives; ``residual`` = G(c) - c, both (nK,)).

        A slipping contact's force changes with its cap by -u (u its slip direction), so
        the minimizer moves by dx = -H^-1 T_k^T u dc (H the Hessian at x) and the normal
        forces N = -k w_z with it: that is G' (columns only for the slipping contacts; a
        sticking contact's cap changes nothing).  Solves (I - G') dc = G(c) - c on the
        slipping contacts' caps and returns the caps c + dc (>= 0) with the minimizer
        x + dx predicted for them (the next ``minimize`` starts there); None if I - G' or
        H is singular."""
        force = self._forces(x)[3]
        slipping, rows, unit, lost = self._slips(x)
        if not slipping.size:               # G' = 0: the plain update is Newton's
            return caps + residual, x
        space, count = self.space, len(slipping)
        spread = np.zeros((count, 2, count))                  # B = T_P^T spread
        spread[np.arange(count), :, np.arange(count)] = unit
        spread = spread.reshape(2 * count, count)
        weights = None if not space.through_sticking() else self._woodbury(
            rows, lost, space.compliance[rows[:, None], rows] @ spread)
        if weights is None:                 # by H itself
            moves = self._factored_hessian(x).solve(space.tangential[rows].T @ spread)
            if moves is None:
                return None
            normal_moves = space.map[2::3] @ moves
        else:                               # H^-1 B = Y_P (spread + weights)
            combined = spread + weights
            normal_moves = space.normal_compliance[:, rows] @ combined
        pressing = force[:, 2] > 0.0
        jacobian = (self.solver.mu * spring_rows(self.k, None, 1)) * normal_moves \
            * pressing[:, None]                                                   # (na, p)
        change, info = routines().gesv(np.eye(count) - jacobian[slipping],
                             residual[self.active][slipping])[2:]
        if info != 0:
            return None
        new_caps = caps + residual
        new_caps[self.active] += jacobian @ change
        shift = moves @ change if weights is None else space.reach[:, rows] @ (combined @ change)
        return np.maximum(new_caps, 0.0), x - shift

    def contact_state(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The contact forces and displacements (nK, 3) at x: zero force where lifted,
        and the lifted contacts' own displacements (a lifted corner that the slipping
        has pushed below the floor must be seated again)."""
        _, _, _, force = self._forces(x)
        forces = np.zeros((len(self.active), 3))
        forces[self.active] = force
        return forces, self.solver.contact_displacements(x)


class _StepSlope:
    """The slope of Phi along x + t d (t >= 0) in closed form, from each contact's path
    w(t) = w + t dw:

        Phi'(t) = Phi'(0) + t (d.S0.d + k sum dw_z^2) + sum_k [s_k(t) - s_k(0)]
        s_k(t) = k p                 sticking (|w_t(t)| <= c_k / k)
               = c_k p / |w_t(t)|    slipping,     p = w_t(t).dw_t

    (s_k(0) = -F_t.dw_t from the forces F at x): O(contacts) per t, no matrix product."""

    def __init__(self, w: np.ndarray, force: np.ndarray, dw: np.ndarray, k: float,
                 caps: np.ndarray, slope0: float, stretch: float):
        self.wx, self.wy, self.dx, self.dy = w[:, 0], w[:, 1], dw[:, 0], dw[:, 1]
        self.k, self.caps, self.start = k, caps, slope0
        self.radius2 = (caps / k) ** 2                              # of the sticking disc
        self.base = slope0 + float((force[:, :2] * dw[:, :2]).sum())
        self.curvature = stretch + (k * float(dw[:, 2] @ dw[:, 2]) if not isinstance(k, np.ndarray)
                                    else float((k * dw[:, 2]) @ dw[:, 2]))
        self.alpha = self.dx * self.dx + self.dy * self.dy          # |dw_t|^2
        self.beta = self.wx * self.dx + self.wy * self.dy           # w_t.dw_t

    def zero(self, full_slope: float, reach: float) -> float:
        """The t > 0 where the slope vanishes, given the slope at t = 1 (``full_slope``).

        Below t = 1 (``full_slope`` > 0): the zero lies between the last breakpoint where
        the slope is < 0 (or 0) and the next (or 1); found there within LINE_SEARCH_SLOPE
        of the start's slope (``_root``).  Beyond (``full_slope`` < 0): the slope is
        sampled at t = 2, 4, 8, ... and the step is the secant's zero between the last
        sample < 0 and the first >= 0, or the farthest sample if the slope stays < 0 up to
        ``reach`` (the displacements pass SLIDING_DISPLACEMENT there)."""
        if full_slope < 0.0:
            doublings = min(tol.LINE_SEARCH_ITERATIONS,
                            math.ceil(math.log2(max(reach, 2.0))))
            farther = 2.0 ** np.arange(1, doublings + 1)
            values = self._at(farther)
            rising = np.flatnonzero(values >= 0.0)
            if not rising.size:
                return float(farther[-1])
            j = int(rising[0])
            low, low_slope = (farther[j - 1], values[j - 1]) if j else (1.0, full_slope)
            high, high_slope = farther[j], values[j]
            return _secant(low, high, low_slope, high_slope)
        breaks = self._breakpoints()
        breaks = breaks[breaks < 1.0]
        low, low_slope, high, high_slope = 0.0, self.start, 1.0, full_slope
        if breaks.size:
            values = self._at(breaks)
            rising = np.flatnonzero(values >= 0.0)
            if rising.size:
                j = int(rising[0])
                high, high_slope = breaks[j], values[j]
                if j:
                    low, low_slope = breaks[j - 1], values[j - 1]
            else:
                low, low_slope = breaks[-1], values[-1]
        return self._root(low, high, low_slope, high_slope)

    def _breakpoints(self) -> np.ndarray:
        """Sorted t > 0 where a contact passes between sticking and slipping: the roots of
        |w_t + t dw_t|^2 = (c / k)^2."""
        alpha, beta = self.alpha, self.beta
        excess = self.wx * self.wx + self.wy * self.wy - self.radius2
        discriminant = beta * beta - alpha * excess
        real = (alpha > 0.0) & (discriminant > 0.0)
        q = -(beta[real] + np.copysign(np.sqrt(discriminant[real]), beta[real]))
        roots = np.concatenate([q / alpha[real], excess[real] / q])
        return np.sort(roots[roots > 0.0])

    def _at(self, t: np.ndarray) -> np.ndarray:
        """The slope at each t (m,)."""
        px = self.wx[:, None] + self.dx[:, None] * t                # (na, m)
        py = self.wy[:, None] + self.dy[:, None] * t
        along = px * self.dx[:, None] + py * self.dy[:, None]
        radius2 = px * px + py * py
        sticking = radius2 <= self.radius2[:, None]
        slipping = self.caps[:, None] * along / np.sqrt(np.where(sticking, 1.0, radius2))
        terms = np.where(sticking, spring_rows(self.k, None, 1) * along, slipping)
        return self.base + self.curvature * t + terms.sum(axis=0)

    def _root(self, low: float, high: float, low_slope: float, high_slope: float) -> float:
        """The zero of the slope in [low, high] (< 0 at low, >= 0 at high, no contact
        changing state in between): exact where every contact sticks (the slope is
        linear), else by Newton's method on the smooth slope, from the full step (t = 1)
        if it lies in the bracket, kept in the bracket (the secant through its ends where
        a Newton step would leave it), until the slope is within LINE_SEARCH_SLOPE of its
        start or the bracket within LINE_SEARCH_BRACKET of its size."""
        middle = 0.5 * (low + high)
        px, py = self.wx + middle * self.dx, self.wy + middle * self.dy
        sticking = px * px + py * py <= self.radius2
        k = self.k
        if not isinstance(k, np.ndarray):
            constant = self.base + k * float(self.beta[sticking].sum())
            linear = self.curvature + k * float(self.alpha[sticking].sum())
        else:                               # the anchors' ties have their own springs
            constant = self.base + float(k[sticking] @ self.beta[sticking])
            linear = self.curvature + float(k[sticking] @ self.alpha[sticking])
        slipping = ~sticking & (self.caps > 0.0)
        if not slipping.any() and linear > 0.0:
            return min(max(-constant / linear, low), high)
        wx, wy, dx, dy = (v[slipping] for v in (self.wx, self.wy, self.dx, self.dy))
        caps, cross = self.caps[slipping], (wx * dy - wy * dx) ** 2    # |w_t x dw_t|^2
        target = tol.LINE_SEARCH_SLOPE * abs(self.start)
        t = 1.0 if low < 1.0 <= high else _secant(low, high, low_slope, high_slope)
        for _ in range(tol.LINE_SEARCH_ITERATIONS):
            px, py = wx + t * dx, wy + t * dy
            radius = np.hypot(px, py)
            value = constant + linear * t + float(caps @ ((px * dx + py * dy) / radius))
            if abs(value) <= target:
                return t
            if value < 0.0:
                low, low_slope = t, value
            else:
                high, high_slope = t, value
            if high - low <= tol.LINE_SEARCH_BRACKET * high:
                return t
            derivative = linear + float(caps @ (cross / radius ** 3))
            guess = t - value / derivative if derivative > 0.0 else high
            t = guess if low < guess < high else _secant(low, high, low_slope, high_slope)
        return t


def balance_floor(force_tol: float, schur_size: float, rhs_size: float,
                  x: np.ndarray) -> float:
    """N: the out-of-balance force below which the condensed equilibrium S0 x = b + M^T f
    counts as met at x: the force tolerance, or the round-off of S0 x if that is larger
    (``schur_size``, ``rhs_size``: the largest entries of S0 and b)."""
    return max(force_tol, _ROUNDOFF * (schur_size * float(np.abs(x).sum()) + rhs_size))


def slip_tangent(caps: np.ndarray, stretch: np.ndarray, unit: np.ndarray) -> np.ndarray:
    """(p, 2, 2): a slipping contact's tangential stiffness, (c / r) (I - u u^T): the force
    c = mu N keeps its size and turns with the slip direction u (p, 2) as the tangential
    displacement (of size r, ``stretch``) turns; nothing along u."""
    return (caps / stretch)[:, None, None] * (_EYE2 - unit[:, :, None] * unit[:, None, :])


def _secant(low: float, high: float, low_slope: float, high_slope: float) -> float:
    """Where the line through (low, low_slope) and (high, high_slope) crosses zero."""
    return low - low_slope * (high - low) / (high_slope - low_slope)


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
