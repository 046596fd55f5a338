"""The friction phase's energy: Tresca problems, every contact unilateral and its friction
capped at a fixed force.

``_FrictionEnergy`` is the condensed potential energy of the grounded nodes' displacements
with every contact's normal spring pushing only (a corner that lifts carries no normal
force) and its anchor spring elastic-perfectly-plastic, capped at its friction cap
(``caps``); its minimizer is the equilibrium for those caps, every corner pressing or
lifted as its own displacement says (``contacts._ActiveSet.friction_phase`` updates the
caps to mu N of the normal forces it gives, until they agree: within one minimization a
corner that lifts keeps the friction of its cap, which the next update takes away).
Newton's steps factor the small condensed Hessian afresh, and the line search along a
step is exact in closed form (``_StepSlope``: each contact's displacement is affine in the
step length, its breakpoints the roots of a quadratic or a line).  ``_anderson`` mixes
cap iterates where Newton's method on the caps does not shrink their mismatch.

Earlier versions lifted and re-seated corners between minimizations, each with the
normal springs of its contacts' statuses; a corner that lifts once friction is capped and
sinks once another slips sent those statuses round (a tenth of the elastic cabinet's
``range`` cases, settled only by Newton's method on the whole contact law or the linear
programs, at ten times the cost).  Inside the energy, pressing and lifting are part of
the minimization and cannot go round.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.anchored import _Factored, condensed_stiffness
from furncheck.statics.lapack import cholesky, routines

if TYPE_CHECKING:
    from furncheck.statics.contacts import _ActiveSet


_EYE2 = np.eye(2)


class _FrictionEnergy:
    """The condensed potential energy of one Tresca problem: every contact unilateral, its
    friction capped at a fixed force.

    For the grounded planks' displacements x (x_g of ``_Condensed``), with w_k = M_k x
    the displacement of contact k, k its spring stiffness and c_k its friction cap:

        Phi(x) = 1/2 x.S0.x - b.x + sum_k [ 1/2 k min(w_z, 0)^2 + psi(|w_t|) ]
        psi(r) = 1/2 k r^2           if k r <= c      (sticking to its anchor)
               = c r - c^2 / (2 k)   otherwise         (slipping: force c against w_t)

    (an anchor's tie pulls as well as it pushes: 1/2 k w_z^2, and never slips).  Phi is
    convex and once differentiable; its minimizer is the equilibrium of the caps c, each
    corner pressing or lifted as its own displacement says, and it has none when the
    loads exceed what the caps can hold (the design slides).  ``contacts._ActiveSet.
    friction_phase`` updates the caps to mu N of the normal forces the minimizer gives
    until they agree (Coulomb's law).

    Its Hessian is S0 + sum_k M_k^T D_k M_k with D_k of the contact's state: k along the
    normal where it presses (0 where it lifts); k I across the floor where it sticks, and
    where it slips the stiffness it keeps, (c / r) (I - u u^T) (u its slip direction), and
    a feeble SLIP_STIFFNESS k along u (so that a design free to slide is not singular);
    factored afresh at each Newton step (the condensed system is small: Woodbury updates
    of one factored matrix per pattern of pressing contacts, or per minimization, tried,
    met 6 to 20 contacts per step whose springs had changed on the catalog's cabinet, and
    took longer).
    """

    def __init__(self, solver: _ActiveSet, caps: np.ndarray):
        model = solver.model
        self.solver = solver
        self.model = model
        self.map = solver.contact_map()
        self.schur = solver.condensed.schur
        self.rhs = solver.ground_rhs
        count = len(model.contacts)
        self.k = model.contact_springs_each
        self.tie = np.zeros(count, dtype=bool) if model.contact_anchored is None \
            else np.asarray(model.contact_anchored, dtype=bool)
        self.caps = caps
        self._floor_sizes = solver.balance_sizes
        self._state_at: np.ndarray | None = None     # the x of the kept _state
        self._last_hessian: _Factored | None = None  # of the last Newton step's start

    def _state(self, x: np.ndarray):
        """Contact displacements w (nK, 3), |w_t| (1 where 0), pressing and sticking masks
        and forces (nK, 3) at x (kept for the last x: the gradient, the Newton step and the
        line search all start from them).  A contact without friction (cap 0: it lifted
        in the caps' iterate) is not sticking."""
        if x is self._state_at:
            return self._state_kept
        k, caps = self.k, self.caps
        w = (self.map @ x).reshape(-1, 3)
        r = np.hypot(w[:, 0], w[:, 1])
        sticking = (k * r <= caps) & (caps > 0.0)
        pressing = (w[:, 2] < 0.0) | self.tie
        safe_r = np.where(r > 0.0, r, 1.0)
        forces = w * -np.where(sticking, k, caps / safe_r)[:, None]  # force_t = -scale w_t
        forces[:, 2] = np.where(pressing, w[:, 2] * -k, 0.0)
        self._state_at, self._state_kept = x, (w, safe_r, pressing, sticking, forces)
        return self._state_kept

    def _gradient(self, x: np.ndarray) -> np.ndarray:
        """dPhi/dx: the out-of-balance generalized force on the grounded planks."""
        force = self._state(x)[4]
        return self.schur @ x - self.rhs - self.map.T @ force.ravel()

    def _springs(self, x: np.ndarray) -> np.ndarray:
        """(nK, 3, 3) each contact's stiffness D_k at x (class docstring): k along the
        normal where it presses; k I across where it sticks, where it slips (c / r)
        (I - u u^T) + SLIP_STIFFNESS k u u^T, and nothing where it has no friction cap."""
        k, caps = self.k, self.caps
        w, safe_r, pressing, sticking, _ = self._state(x)
        springs = np.zeros((len(k), 3, 3))
        springs[:, 0, 0] = springs[:, 1, 1] = np.where(sticking, k, 0.0)
        springs[:, 2, 2] = np.where(pressing, k, 0.0)
        slipping = np.flatnonzero(~sticking & (caps > 0.0))
        if slipping.size:
            unit = w[slipping, :2] / safe_r[slipping, None]
            springs[slipping, :2, :2] = slip_tangent(caps[slipping], safe_r[slipping], unit,
                                                     k[slipping])
        return springs

    def _factored_hessian(self, x: np.ndarray) -> _Factored:
        """The Hessian at x, assembled and shifted by its round-off (SOLVE_RESIDUAL of its
        diagonal) so that a slipping contact's zero stiffness along its slip leaves it
        factorable, and factored (by LU where Cholesky fails)."""
        hessian = condensed_stiffness(self.model, self._springs(x))
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
        last = np.inf                       # the one before the last step
        for _ in range(tol.FRICTION_NEWTON_ITERATIONS):
            size = float(np.abs(gradient).max(initial=0.0))
            floors = balance_floors(self.solver.force_tol, self._floor_sizes, x)
            if balanced(size, last, floors):
                return x
            best, last = min(best, size), size
            self._last_hessian = self._factored_hessian(x)
            step = self._last_hessian.solve(-gradient)
            if step is None or not np.all(np.isfinite(step)):
                return x if size <= floors[1] else None
            start = x
            x, gradient = self._line_search(x, step, gradient, best)
            if past_sliding(x):
                return start if size <= floors[1] else None
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
        LINE_SEARCH_EXTEND of the start's or less; and, where the slope there is still <= 0
        (Phi fell all along the step), where it brings the largest out-of-balance force
        below FULL_STEP_GRADIENT of ``best``, the least met so far (a step that lets many
        contacts change state at once; beyond the minimum along the step it could go uphill,
        see FULL_STEP_GRADIENT).  Otherwise the slope's zero is sought (``_StepSlope``: each
        contact's displacement is affine in t, so the slope is a sum of closed forms,
        O(contacts) per t): below t = 1 between the breakpoints where contacts lift, press,
        stick or slip, beyond t = 1 (the energy is much flatter than the Hessian said, as
        along a sliding motion) by doubling t, up to where the displacements pass
        SLIDING_DISPLACEMENT (Phi has no minimum there: the design slides)."""
        w, _, _, _, force = self._state(x)
        slope0 = float(gradient @ step)
        full = x + step
        full_gradient = self._gradient(full)
        full_slope = float(full_gradient @ step)
        if not slope0 < 0.0:                # no descent left but round-off
            return full, full_gradient
        if abs(full_slope) <= tol.LINE_SEARCH_SLOPE * -slope0:
            return full, full_gradient
        if full_slope < 0.0 and (full_slope > tol.LINE_SEARCH_EXTEND * slope0
                                 or past_sliding(full)):
            return full, full_gradient
        if full_slope <= 0.0 \
                and np.abs(full_gradient).max() <= tol.FULL_STEP_GRADIENT * best:
            return full, full_gradient
        moved = (self.map @ step).reshape(-1, 3)
        slope = _StepSlope(w, force, moved, self.k, self.caps, self.tie, slope0,
                           float(step @ (self.schur @ step)))
        t = slope.zero(full_slope,
                       (tol.SLIDING_DISPLACEMENT + np.abs(x).max()) / np.abs(step).max())
        return x + t * step, None

    def cap_newton(self, x: np.ndarray, caps: np.ndarray, residual: np.ndarray):
        """Newton's step for the caps' fixed point c = G(c) (G: the caps mu N that the
        minimizer x of Phi with caps c gives; ``residual`` = G(c) - c, both (nK,)).

        A slipping contact's force changes with its cap by -u (u its slip direction; a
        contact whose cap is 0 and that has moved is on that branch too), so
        the minimizer moves by dx = -H^-1 T_k^T u dc (H the Hessian at x, T_k the
        contact's two tangential rows of M) and the normal forces N = -k w_z of the
        pressing contacts with it: that is G' (columns only for the slipping contacts; a
        sticking contact's cap changes nothing).  Solves (I - G') dc = G(c) - c on the
        slipping contacts' caps and returns the caps c + dc (>= 0) with the minimizer
        x + dx predicted for them (the next ``minimize`` starts there); None if I - G' or
        H is singular.  H is the one factored at the start of ``minimize``'s last Newton
        step, where there was one (that step met the force tolerance: its contacts'
        states are x's, their slip directions nearly; an approximate G' costs the caps'
        iteration nothing on the catalog and saves a factoring per update)."""
        w, safe_r, pressing, sticking, force = self._state(x)
        slipping = np.flatnonzero(~sticking & (np.hypot(w[:, 0], w[:, 1]) > 0.0))
        if not slipping.size:               # G' = 0: the plain update is Newton's
            return caps + residual, x
        unit = w[slipping, :2] / safe_r[slipping, None]
        tangential = self.map.reshape(-1, 3, self.map.shape[1])[slipping, :2]  # (p, 2, n)
        pushed = np.einsum("pi,pin->np", unit, tangential)                    # T_P^T U
        moves = (self._last_hessian or self._factored_hessian(x)).solve(pushed)
        if moves is None or not np.all(np.isfinite(moves)):
            return None
        normal_moves = self.map[2::3] @ moves                                  # (nK, p)
        pressed = pressing & (force[:, 2] > 0.0)
        jacobian = (self.solver.mu * self.k * pressed)[:, None] * normal_moves
        change, info = routines().gesv(np.eye(len(slipping)) - jacobian[slipping],
                                       residual[slipping])[2:]
        if info != 0:
            return None
        new_caps = caps + residual + jacobian @ change
        return np.maximum(new_caps, 0.0), x - moves @ change

    def contact_state(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The contact forces and displacements (nK, 3) at x (no normal force where a
        corner lifted; its friction is its cap's, zero once the caps agree)."""
        return self._state(x)[4].copy(), self.solver.contact_displacements(x)


class _StepSlope:
    """The slope of Phi along x + t d (t >= 0) in closed form, from each contact's path
    w(t) = w + t dw:

        Phi'(t) = Phi'(0) + t d.S0.d + sum_k [s_k(t) - s_k(0)]
        s_k(t) = k w_t(t).dw_t + k min(w_z(t), 0) dw_z       sticking (|w_t(t)| <= c_k / k)
               = c_k w_t(t).dw_t / |w_t(t)| + ...             slipping

    (an anchor's tie: k w_z(t) dw_z, pressing or not; s_k(0) = -F.dw from the forces F
    at x): O(contacts) per t, no matrix product.  Its breakpoints are where a contact
    passes between sticking and slipping or between pressing and lifting."""

    def __init__(self, w: np.ndarray, force: np.ndarray, dw: np.ndarray, k: np.ndarray,
                 caps: np.ndarray, tie: np.ndarray, slope0: float, stretch: float):
        self.wx, self.wy, self.dx, self.dy = w[:, 0], w[:, 1], dw[:, 0], dw[:, 1]
        self.k, self.caps, self.start = k, caps, slope0
        self.radius2 = (caps / k) ** 2                              # of the sticking disc
        free = ~tie                                                 # unilateral normals
        self.wz, self.dz, self.kz = w[free, 2], dw[free, 2], k[free]
        self.base = slope0 + float((force[:, :2] * dw[:, :2]).sum()) \
            + float(force[free, 2] @ dw[free, 2])
        self.curvature = stretch + float((k[tie] * dw[tie, 2]) @ dw[tie, 2])
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
        """Sorted t > 0 where a contact passes between sticking and slipping (the roots of
        |w_t + t dw_t|^2 = (c / k)^2) or between pressing and lifting (w_z + t dw_z = 0)."""
        alpha, beta = self.alpha, self.beta
        excess = self.wx * self.wx + self.wy * self.wy - self.radius2
        discriminant = beta * beta - alpha * excess
        real = (alpha > 0.0) & (discriminant > 0.0)
        q = -(beta[real] + np.copysign(np.sqrt(discriminant[real]), beta[real]))
        moving = self.dz != 0.0
        roots = np.concatenate([q / alpha[real], excess[real] / q,
                                -self.wz[moving] / self.dz[moving]])
        return np.sort(roots[roots > 0.0])

    def _at(self, t: np.ndarray) -> np.ndarray:
        """The slope at each t (m,)."""
        px = self.wx[:, None] + self.dx[:, None] * t                # (nK, m)
        py = self.wy[:, None] + self.dy[:, None] * t
        along = px * self.dx[:, None] + py * self.dy[:, None]
        radius2 = px * px + py * py
        sticking = radius2 <= self.radius2[:, None]
        slipping = self.caps[:, None] * along / np.sqrt(np.where(sticking, 1.0, radius2))
        terms = np.where(sticking, self.k[:, None] * along, slipping)
        normal = (self.kz * self.dz)[:, None] * np.minimum(
            self.wz[:, None] + self.dz[:, None] * t, 0.0)
        return self.base + self.curvature * t + terms.sum(axis=0) + normal.sum(axis=0)

    def _root(self, low: float, high: float, low_slope: float, high_slope: float) -> float:
        """The zero of the slope in [low, high] (< 0 at low, >= 0 at high, no contact
        changing state in between): exact where no contact slips (the slope is linear),
        else by Newton's method on the smooth slope, from the full step (t = 1)
        if it lies in the bracket, kept in the bracket (the secant through its ends where
        a Newton step would leave it), until the slope is within LINE_SEARCH_SLOPE of its
        start or the bracket within LINE_SEARCH_BRACKET of its size."""
        middle = 0.5 * (low + high)
        px, py = self.wx + middle * self.dx, self.wy + middle * self.dy
        sticking = px * px + py * py <= self.radius2
        pressing = self.wz + middle * self.dz < 0.0
        k, kz = self.k, self.kz[pressing] * self.dz[pressing]
        constant = self.base + float(k[sticking] @ self.beta[sticking]) \
            + float(kz @ self.wz[pressing])
        linear = self.curvature + float(k[sticking] @ self.alpha[sticking]) \
            + float(kz @ self.dz[pressing])
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


def displacement_size(ground: np.ndarray) -> float:
    """m (or rad): the largest move of a grounded node in the condensed displacements x_g
    (six per node): the length of its translation or of its rotation vector, whichever is
    larger, what SLIDING_DISPLACEMENT is measured against.  Lengths, not the largest
    component: a rigid motion of the design turns the vectors and leaves their lengths (a
    table bolted down on one leg moved its leg 10.3 m as written and 8.3 m, the largest
    component, turned by 37 degrees: a mechanism in one turn, not in the other)."""
    nodes = ground.reshape(-1, 6)
    squares = np.concatenate([np.einsum("ij,ij->i", nodes[:, :3], nodes[:, :3]),
                              np.einsum("ij,ij->i", nodes[:, 3:], nodes[:, 3:])])
    return math.sqrt(float(squares.max(initial=0.0)))       # not a number where one is not


def past_sliding(ground: np.ndarray) -> bool:
    """Whether ``displacement_size(ground)`` passes SLIDING_DISPLACEMENT (or is not a
    number).  Each length lies between the largest component and sqrt(3) times it, so
    that component decides where it can, at a fraction of the cost (every Newton step
    asks)."""
    largest = float(np.abs(ground).max(initial=0.0))
    if not largest <= tol.SLIDING_DISPLACEMENT:          # past it, or not a number
        return True
    if math.sqrt(3.0) * largest <= tol.SLIDING_DISPLACEMENT:
        return False
    return not displacement_size(ground) <= tol.SLIDING_DISPLACEMENT


def balance_sizes(schur: np.ndarray, rhs: np.ndarray,
                  contacts: np.ndarray) -> tuple[np.ndarray, float, float, np.ndarray]:
    """What ``balance_floors`` measures round-off by, kept per condensed system: |S0|, the
    largest entry of S0, that of b, and the contacts' |M|^T K |M| (``contacts``, made by
    ``contact_magnitudes``)."""
    magnitudes = np.abs(schur)
    return (magnitudes, float(magnitudes.max(initial=0.0)), float(np.abs(rhs).max(initial=0.0)),
            contacts)


def contact_magnitudes(mapping: np.ndarray, springs: np.ndarray) -> np.ndarray:
    """(n, n): |M|^T K |M| for the contact map M (3 nK, n) and every contact's spring k in
    all three directions (``springs`` (nK,)): row i of it times |x| estimates how much
    the contact forces' part of the out-of-balance force at x, M^T f(M x), moves in row i
    when each w = M x is off by its round-off, relative to |M| |x| (one unit of the last
    place per w: CONTACT_ROUNDOFF).  Every spring counts, as if it held (a corner that
    lifts carries no force; one that slips carries its cap, which moves with w by at most
    the spring's stiffness, mu k along the normal in ``newton``'s law)."""
    magnitudes = np.abs(mapping)
    return magnitudes.T @ (np.repeat(springs, 3)[:, None] * magnitudes)


def balance_floors(force_tol: float, sizes: tuple[np.ndarray, float, float, np.ndarray],
                   x: np.ndarray) -> tuple[float, float]:
    """N: (tight, loose), the out-of-balance forces below which the condensed equilibrium
    S0 x = b + M^T f counts as met at x (``balanced``), each at least the force tolerance.
    The tight floor is the round-off of S0 x row by row (BALANCE_ROW_ROUNDOFF of
    max_i sum_j |S0_ij x_j|, plus that of b); the loose one bounds it for every row at
    once, however their terms cancel (BALANCE_ROUNDOFF of max|S0| sum|x|, plus that of b).
    The loose floor alone, about a thousand times the tight one for the stiff joints of
    the rigid model, let Newton's method stop up to 1e-4 N short where it still converged:
    the forces of a design turned about the vertical moved by 2e-5 of themselves
    (``tests/test_invariants.py``).

    The loose floor adds the round-off of the contact forces M^T f(M x): CONTACT_ROUNDOFF
    of max_i (|M|^T K |M| |x|)_i (``contact_magnitudes``: an estimate, every spring
    counted).  A contact spring of the elastic model (1e10 N/m) turns each metre of
    |M| |x| into about 2e-6 N of round-off in the force it computes from w: a
    near-mechanism whose grounded plank turned by 3.3 rad under the friction phase's
    first caps (a table's top edited down through its legs' ends) stalled at 5e-7 to
    6e-7 N against floors of 4e-7 N (the force tolerance), ran out of Newton steps and was
    left to the programs, in some turns of the design only (a leg/apron joint's force
    181.6 N against 182.2 N; in its 'lean' case, which stalled alike, 82.7 N against
    85.6 N).  In the tight floor the estimate stopped converging minimizations early: a
    racking table edited into a near-mechanism (0.8 m) settled its caps one update sooner
    as written than turned, its forces 5e-6 of themselves apart."""
    magnitudes, schur_size, rhs_size, contacts = sizes
    size = np.abs(x)
    contact = tol.CONTACT_ROUNDOFF * float((contacts @ size).max(initial=0.0))
    loose = max(force_tol, tol.BALANCE_ROUNDOFF * (schur_size * float(size.sum()) + rhs_size)
                + contact)
    row = float((magnitudes @ size).max(initial=0.0))
    tight = max(force_tol, min(loose, tol.BALANCE_ROW_ROUNDOFF * (row + rhs_size)))
    return tight, loose


def balanced(size: float, last: float, floors: tuple[float, float]) -> bool:
    """Whether an out-of-balance force ``size`` (N; ``last``: the one before the last
    Newton step) meets the equilibrium: below the tight floor of ``balance_floors``, or
    below the loose one where the last step stalled (it did not bring the force under
    BALANCE_STALLED of the one before: round-off, or a damped step; either way no worse
    than the loose floor, which the earlier rule took alone).  A step that fails from
    below the loose floor (a singular system, displacements past SLIDING_DISPLACEMENT)
    leaves its start as the equilibrium, as that rule did."""
    tight, loose = floors
    return size <= tight or (size <= loose and size > tol.BALANCE_STALLED * last)


def slip_tangent(caps: np.ndarray, stretch: np.ndarray, unit: np.ndarray,
                 springs: np.ndarray) -> np.ndarray:
    """(p, 2, 2): a slipping contact's tangential stiffness, (c / r) (I - u u^T) +
    SLIP_STIFFNESS k u u^T: the force c = mu N keeps its size and turns with the slip
    direction u (p, 2) as the tangential displacement (of size r, ``stretch``) turns;
    along u only a feeble spring (k: ``springs``, (p,)), so that a design free to slide
    at the edge of sliding is not singular."""
    along = unit[:, :, None] * unit[:, None, :]
    return (caps / stretch)[:, None, None] * (_EYE2 - along) \
        + (tol.SLIP_STIFFNESS * springs)[:, None, None] * along


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
