"""Static condensation of the mixed system onto the grounded planks, and its solves.

``_Condensation`` / ``_condense`` (one sparse LU of the contact-free part per design, checked
by ``_factor`` / ``_accurate``), the contact springs ``_anchor_springs`` and the condensed
matrix ``_condensed_stiffness``; ``system_matrix`` and ``solve_system`` give the full mixed
matrix and its solve to the sensitivity analysis.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from furncheck import tolerances as tol
from furncheck.statics.model import _SIX, StaticsModel


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
    lu: object                   # SuperLU (or _DenseLU) of A_ii
    coupling: sp.csc_matrix      # A_ig (n_i, n_g); dense for a small system
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
    is neither grounded nor jointed to a grounded plank cannot be held).  Small systems
    (DENSE_SYSTEM_MAX) are factored densely, larger ones by SuperLU."""
    n, m = model.n_dof, model.G.shape[0]
    G = model.G.tocoo()
    diagonal = n + np.arange(m)
    rows = np.concatenate([G.col, n + G.row, diagonal])
    cols = np.concatenate([n + G.row, G.col, diagonal])
    values = np.concatenate([G.data, G.data, -model.compliance])
    grounded, contact_block = np.unique(model.contact_plank, return_inverse=True)
    ground = (6 * grounded[:, None] + _SIX[None, :]).ravel()
    inner = np.setdiff1d(np.arange(n + m), ground)
    ni = len(inner)
    order = np.concatenate([inner, ground])
    dense = n + m <= tol.DENSE_SYSTEM_MAX
    if dense:
        A = np.zeros((n + m, n + m))
        np.add.at(A, (rows, cols), values)
        permuted = A[np.ix_(order, order)]
        A_ii, coupling = permuted[:ni, :ni], permuted[:ni, ni:]
    else:
        A = sp.csc_matrix((values, (rows, cols)), shape=(n + m, n + m))
        permuted = A[order][:, order].tocsc()
        A_ii = permuted[:ni, :ni].tocsc()
        coupling = permuted[:ni, ni:].tocsc()
    lu, reduced = None, np.zeros((ni, len(ground)))
    if ni:
        probe = np.asarray(coupling.sum(axis=1)).ravel()
        lu = _factor_dense(A_ii, probe) if dense else _factor(A_ii, probe)
        if lu is None:
            return None
        if len(ground):
            reduced = lu.solve(coupling if dense else coupling.toarray())
    corner = permuted[ni:, ni:]
    schur = (corner if dense else corner.toarray()) - np.asarray(coupling.T @ reduced)
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


class _DenseLU:
    """LAPACK LU factors of a small dense matrix, solved like SuperLU's ``solve``."""

    def __init__(self, factors):
        self.factors = factors

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return sla.lu_solve(self.factors, rhs, check_finite=False)


def _factor_dense(A: np.ndarray, probe: np.ndarray) -> _DenseLU | None:
    """Dense LU (partial pivoting) of A, or None if it is singular: an exactly zero pivot,
    or a poor solve of the right-hand side ``probe``."""
    rhs = probe if np.any(probe) else np.ones(A.shape[0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", sla.LinAlgWarning)   # a zero pivot: checked below
        factors = sla.lu_factor(A, check_finite=False)
    if not np.all(np.diag(factors[0])):
        return None
    lu = _DenseLU(factors)
    return lu if _accurate(A, lu.solve(rhs), rhs) else None


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


def anchor_springs(holding: np.ndarray) -> np.ndarray:
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
    blocks = np.transpose(maps, (0, 2, 1)) @ (anchor_springs(holding) @ maps)
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
    ground = np.linalg.solve(_condensed_stiffness(model, anchor_springs(holding)), ground_rhs)
    out = np.zeros_like(R)
    out[condensed.ground] = ground
    out[condensed.inner] = inner - condensed.reduced @ ground
    return out[:, 0] if single else out
