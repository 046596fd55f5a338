"""How the ground pushes on each contact of a solved case, for the force sensitivity.

``ContactLaw`` gives the contact forces as a function of the contacts' displacements, with
each contact's state held as the solve left it (lifted, sticking, or slipping with mu N
against its slip), and its tangent for eq. 6: the paper's assumption that contacts neither
lift nor change between sticking and slipping under an infinitesimal change.
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.friction import slip_tangent
from furncheck.statics.model import StaticsModel, spring_rows


class ContactLaw:
    """The ground's force on each contact as a function of its point's displacement w (m),
    for a solved case: zero where the contact lifted; -k w where it sticks; where it
    slipped (the friction phase's elastic-perfectly-plastic anchor spring), the normal
    part -k w_z and the friction force mu N against the tangential displacement,
    f_t = -mu N w_t / |w_t|, N = -k w_z.

    holding, slipping : (nK,) bool; k N/m (``StaticsModel.contact_springs``: a scalar,
    or per contact), mu the friction coefficient.
    """

    def __init__(self, holding: np.ndarray, slipping: np.ndarray, k: float, mu: float):
        self.holding = np.asarray(holding, dtype=bool)
        self.slipping = np.asarray(slipping, dtype=bool) & self.holding
        self.k = k
        self.mu = mu

    @classmethod
    def of_solution(cls, model: StaticsModel, holding: np.ndarray, displacements: np.ndarray,
                    forces: np.ndarray) -> ContactLaw:
        """The law of a solved case: a holding contact slipped where its force is not
        -k w (its tangential force is below k |w_t|: capped at mu N)."""
        k = model.contact_springs
        stretch = np.hypot(displacements[:, 0], displacements[:, 1])
        pull = np.hypot(forces[:, 0], forces[:, 1])
        slipping = np.asarray(holding, dtype=bool) \
            & (k * stretch - pull > tol.SLIP_DETECTION * k * stretch)
        return cls(holding, slipping, k, model.friction)

    def forces(self, w: np.ndarray, rows: np.ndarray | None = None) -> np.ndarray:
        """(n, 3) N: the force on contacts ``rows`` (all when None) displaced by w (n, 3)."""
        holding, slipping = (self.holding, self.slipping) if rows is None else \
            (self.holding[rows], self.slipping[rows])
        k = spring_rows(self.k, rows)
        force = -spring_rows(k, None, 1) * w * holding[:, None]
        if slipping.any():
            wt = w[slipping, :2]
            normal = -spring_rows(k, slipping) * w[slipping, 2]
            r = np.hypot(wt[:, 0], wt[:, 1])
            force[slipping, :2] = -(self.mu * normal / np.where(r > 0.0, r, 1.0))[:, None] * wt
        return force

    def tangent(self, w: np.ndarray) -> np.ndarray:
        """(nK, 3, 3) S at the displacements w (nK, 3): df = -S dw.
        Sticking: k I; slipping, with t = w_t / |w_t| and cap = mu N: S_tt = cap / |w_t|
        (I - t t^T) + SLIP_STIFFNESS k t t^T (it gives along its slip, resists across it;
        the feeble spring along the slip, as in the friction phase's Newton steps, keeps
        the system regular where a whole component slides at the edge of sliding),
        S_tz = -mu k t (pressing harder raises the friction), S_zz = k; lifted: 0.  Not
        symmetric where it slips."""
        springs = np.zeros((len(self.holding), 3, 3))
        springs[self.holding] = np.eye(3) * spring_rows(self.k, self.holding, 2)
        if self.slipping.any():
            wt = w[self.slipping, :2]
            r = np.hypot(wt[:, 0], wt[:, 1])
            t = wt / r[:, None]
            k = spring_rows(self.k, self.slipping)
            cap = self.mu * -k * w[self.slipping, 2]
            block = np.zeros((len(r), 3, 3))
            block[:, :2, :2] = slip_tangent(cap, r, t, np.broadcast_to(k, r.shape))
            block[:, :2, 2] = -self.mu * spring_rows(k, None, 1) * t
            block[:, 2, 2] = k
            springs[self.slipping] = block
        return springs
