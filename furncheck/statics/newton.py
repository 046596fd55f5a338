"""The whole contact law at once: a semismooth Newton method, for the cases that the active
set and the friction phase cannot settle: ``contacts.solve_case`` asks it from the
friction phase's last minimizer where that phase's caps did not settle, and
``contacts._ActiveSet.from_programs`` from every contact sticking once the friction
program has found that an equilibrium exists, before taking the program's own forces.

With x the grounded planks' displacements (the condensed unknowns), w = M x every
contact's displacement and f(w) the contact law of contract section 3a (a corner pressed
into the floor, w_z < 0, pushes back -k w_z; its tangential spring pulls -k w_t up to
mu N and with exactly mu N against w_t beyond; a corner above the floor carries nothing;
an anchor's tie pulls -k w whatever it does), the equilibrium is the root of

    R(x) = S0 x - b - M^T f(M x)

(S0 and b those of the condensation).  f is piecewise smooth, so Newton's method takes its
generalized Jacobian J = S0 + M^T D M, D = -df/dw per contact (``law``; not symmetric
where a contact slips: pressing harder raises its friction), and damps each step by
halving it until the residual's norm falls (Armijo); where no halving makes it fall (a
kink of f lies right at x, and the Jacobian there is the wrong side's), the smallest
step is taken all the same: it crosses the kink, and the next step uses the Jacobian
beyond it.  Unlike the active set, no contact status is carried from one iteration to
the next: the residual decides.  The root, where found, is the same equilibrium the
friction phase reaches where it settles (``tests/test_contact_cycles.py``); with
friction, where several equilibria could exist, it is one of them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.anchored import condensed_stiffness
from furncheck.statics.contact_law import ContactLaw
from furncheck.statics.friction import balance_floors, balanced, past_sliding
from furncheck.statics.lapack import routines

if TYPE_CHECKING:
    from furncheck.statics.contacts import _ActiveSet

ARMIJO = 1e-4
"""A damped step is taken when the squared residual falls by at least this fraction of
what the linearization promised (2 t |R|^2 for step length t)."""


def law(w: np.ndarray, k: np.ndarray, mu: float, anchored: np.ndarray | None):
    """The contact law at displacements w (nK, 3) (module docstring), with springs k (nK,)
    N/m: (forces (nK, 3), D (nK, 3, 3) with df = -D dw, pressed (nK,) bool): each
    contact's state read from w (pressed where w_z < 0 or an anchor's tie; slipping where
    k |w_t| passes mu N), then ``ContactLaw``'s forces and tangent for those states (a
    slipping contact's D keeps a feeble SLIP_STIFFNESS spring along its slip, so that a
    design free to slide at the edge of sliding is not singular)."""
    pressed = w[:, 2] < 0.0
    cap = mu * np.where(pressed, -k * w[:, 2], 0.0)
    if anchored is not None:
        pressed = pressed | anchored
        cap = np.where(anchored, np.inf, cap)
    slipping = pressed & (k * np.hypot(w[:, 0], w[:, 1]) > cap)
    contact = ContactLaw(pressed, slipping, k, mu)
    return contact.forces(w), contact.tangent(w), pressed


def newton_equilibrium(solver: _ActiveSet, start: np.ndarray):
    """The root of R (module docstring) from the grounded planks' displacements ``start``:
    (x, contact forces (nK, 3), pressed (nK,) bool), or None when Newton's method does
    not reach the force tolerance within CONTACT_NEWTON_ITERATIONS steps (no equilibrium,
    as when the design slides, or none that it finds), when a Jacobian is singular, or
    when the displacements pass SLIDING_DISPLACEMENT."""
    model = solver.model
    mapping = solver.contact_map()
    schur, rhs = solver.condensed.schur, solver.ground_rhs
    springs = model.contact_springs_each
    sizes = solver.balance_sizes

    def residual(x: np.ndarray):
        forces, tangent, pressed = law((mapping @ x).reshape(-1, 3), springs,
                                       model.friction, model.contact_anchored)
        return schur @ x - rhs - mapping.T @ forces.ravel(), forces, tangent, pressed

    x, last = start, np.inf
    r, forces, tangent, pressed = residual(x)
    for _ in range(tol.CONTACT_NEWTON_ITERATIONS):
        size = float(np.abs(r).max(initial=0.0))
        floors = balance_floors(solver.force_tol, sizes, x)
        if balanced(size, last, floors):
            return x, forces, pressed
        last = size
        step, info = routines().gesv(condensed_stiffness(model, tangent), -r)[2:]
        if info != 0 or not np.all(np.isfinite(step)):
            return (x, forces, pressed) if size <= floors[1] else None
        norm, t = float(r @ r), 2.0
        for _ in range(tol.LINE_SEARCH_ITERATIONS):     # no decrease at all: the smallest
            t *= 0.5                                    # step is taken (module docstring)
            trial = residual(x + t * step)
            if float(trial[0] @ trial[0]) <= (1.0 - 2.0 * ARMIJO * t) * norm:
                break
        previous = x, forces, pressed
        x = x + t * step
        r, forces, tangent, pressed = trial
        if past_sliding(x):
            return previous if size <= floors[1] else None
    if balanced(float(np.abs(r).max(initial=0.0)), last,
                balance_floors(solver.force_tol, sizes, x)):
        return x, forces, pressed           # reached on the last step
    return None
