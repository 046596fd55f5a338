"""The condensed system with the contact springs (contract 3a: stiff unilateral ground
contacts), for a contact state: the springs ``anchor_springs``, the condensed matrix
``condensed_stiffness`` and, per contact state, its matrix factored once
(``anchored_system``, a ``_Factored``: Cholesky by LAPACK directly, LU when that fails);
``system_matrix`` and ``solve_system`` give the full mixed matrix and its solve to the
sensitivity analysis, ``solve_with_springs`` a solve with given springs.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.condense import _accurate, _contact_free_matrix
from furncheck.statics.lapack import cholesky, cholesky_solve
from furncheck.statics.model import _SIX, StaticsModel, block_sums, spring_rows

if TYPE_CHECKING:
    import scipy.sparse as sp


def anchor_springs(holding: np.ndarray, stiffness: float | np.ndarray) -> np.ndarray:
    """(nK, 3, 3): contact force = -S w for contact point displacement w: springs of
    ``stiffness`` (N/m; per contact, ``StaticsModel.contact_springs``) to the anchor in
    all three directions where the contact holds, none where it lifted."""
    springs = np.zeros((len(holding), 3, 3))
    springs[holding] = np.eye(3) * spring_rows(stiffness, holding, 2)
    return springs


def condensed_stiffness(model: StaticsModel, springs: np.ndarray) -> np.ndarray:
    """S0 + K_c: the condensed system's matrix with the contact springs (n_g, n_g)."""
    maps = model.contact_maps
    blocks = np.transpose(maps, (0, 2, 1)) @ (springs @ maps)       # (nK, 6, 6)
    return _with_rest_blocks(model, _with_contact_blocks(model, blocks), springs)


def _anchored_stiffness(model: StaticsModel, holding: np.ndarray,
                        scale: float = 1.0) -> np.ndarray:
    """``condensed_stiffness`` for the anchor springs of ``holding`` (x ``scale``): each
    holding contact adds scale k M^T M, M^T M kept once per model."""
    blocks = model.contact_gram * (scale * model.contact_springs
                                   * holding.astype(float))[:, None, None]
    stiffness = _with_contact_blocks(model, blocks)
    if model.rest_node is None:
        return stiffness
    return _with_rest_blocks(model, stiffness,
                             anchor_springs(holding, model.contact_springs) * scale)


def _rest_coupling(model: StaticsModel, springs: np.ndarray) -> list[tuple]:
    """For the resting corners, the blocks their springs S (nK, 3, 3) add besides
    M_a^T S M_a at their own node's: (block of the node they rest on, that node's own
    M_b^T S M_b), and the cross blocks -M_a^T S M_b, -M_b^T S M_a, as (rows' node, columns'
    node, (nR, 6, 6) blocks) triples."""
    rows = model.rest_rows
    a, b = model.contact_node[rows], model.rest_node[rows]
    m_a, m_b, s = model.contact_maps[rows], model.rest_maps[rows], springs[rows]
    t_a, t_b = np.transpose(m_a, (0, 2, 1)), np.transpose(m_b, (0, 2, 1))
    return [(b, b, t_b @ s @ m_b), (a, b, -(t_a @ s @ m_b)), (b, a, -(t_b @ s @ m_a))]


def _with_rest_blocks(model: StaticsModel, stiffness: np.ndarray,
                      springs: np.ndarray) -> np.ndarray:
    """The condensed matrix with the resting corners' other blocks (``_rest_coupling``)
    added (it is unchanged without rests)."""
    if model.rest_node is None:
        return stiffness
    for row_nodes, col_nodes, blocks in _rest_coupling(model, springs):
        r, c = 6 * model.ground_block[row_nodes], 6 * model.ground_block[col_nodes]
        for k in range(len(blocks)):
            stiffness[r[k]:r[k] + 6, c[k]:c[k] + 6] += blocks[k]
    return stiffness


def _with_contact_blocks(model: StaticsModel, blocks: np.ndarray) -> np.ndarray:
    """S0 with each contact's (6, 6) block added to its plank's diagonal block."""
    condensed = model.condensation
    per_plank = block_sums(condensed.contact_block, blocks.reshape(-1, 36),
                           len(condensed.plank_offsets))
    stiffness = condensed.schur.copy()
    rows, cols = _diagonal_blocks(len(condensed.plank_offsets))
    stiffness[rows, cols] += per_plank.ravel()
    return stiffness


@functools.lru_cache(maxsize=64)
def _diagonal_blocks(count: int) -> tuple[np.ndarray, np.ndarray]:
    """Row and column indices of the entries of ``count`` consecutive (6, 6) diagonal
    blocks, block by block, row-major (kept per count: every contact solve uses them;
    read only)."""
    base = 6 * np.arange(count)[:, None, None]
    rows = np.broadcast_to(base + _SIX[None, :, None], (count, 6, 6)).ravel()
    cols = np.broadcast_to(base + _SIX[None, None, :], (count, 6, 6)).ravel()
    rows.flags.writeable = cols.flags.writeable = False
    return rows, cols


def system_matrix(model: StaticsModel, holding: np.ndarray) -> sp.csr_matrix:
    """The full mixed matrix [[K_b + K_c, G^T], [G, -E]] with anchor springs at the
    holding contacts (sparse, (6 nN + 6 nJ) square): the A of the paper's eq. 6."""
    import scipy.sparse as sp

    n, m = model.n_dof, 6 * model.n_springs
    maps = model.contact_maps
    blocks = np.transpose(maps, (0, 2, 1)) @ (anchor_springs(holding, model.contact_springs)
                                              @ maps)
    base = 6 * model.contact_node[:, None, None]
    rows = np.broadcast_to(base + _SIX[None, :, None], blocks.shape).ravel()
    cols = np.broadcast_to(base + _SIX[None, None, :], blocks.shape).ravel()
    parts = [(blocks.ravel(), rows, cols)]
    if model.rest_node is not None:
        springs = anchor_springs(holding, model.contact_springs)
        for row_nodes, col_nodes, extra in _rest_coupling(model, springs):
            r = np.broadcast_to(6 * row_nodes[:, None, None] + _SIX[None, :, None], extra.shape)
            c = np.broadcast_to(6 * col_nodes[:, None, None] + _SIX[None, None, :], extra.shape)
            parts.append((extra.ravel(), r.ravel(), c.ravel()))
    values, rows, cols = (np.concatenate(part) for part in zip(*parts))
    K_c = sp.coo_matrix((values, (rows, cols)), shape=(n + m, n + m))
    return (_contact_free_matrix(model) + K_c).tocsr()


def solve_system(model: StaticsModel, holding: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """A^-1 rhs for ``system_matrix(model, holding)`` and rhs (n,) or (n, k), reusing the
    design's condensation (one sparse LU per design) and the factor of the condensed
    matrix of this contact state (``anchored_system``): the solve behind eq. 6."""
    condensed = model.condensation
    inner, ground_rhs = condensed.split(np.asarray(rhs, dtype=float))
    ground = anchored_system(model, holding).solve(ground_rhs)
    if ground is None:
        raise np.linalg.LinAlgError("singular condensed system")
    return condensed.expand(inner, ground)


def solve_with_springs(model: StaticsModel, springs: np.ndarray,
                       rhs: np.ndarray) -> np.ndarray:
    """A^-1 rhs for the mixed matrix with contact blocks M^T S M of ``springs`` S (nK, 3,
    3), which need not be symmetric (a slipping contact's tangent, ``contact_law``), and
    rhs (n,) or (n, k): through the design's condensation, the condensed matrix solved by
    LU and checked as ``solve`` is (LinAlgError when it is singular)."""
    condensed = model.condensation
    inner, ground_rhs = condensed.split(np.asarray(rhs, dtype=float))
    matrix = condensed_stiffness(model, springs)
    ground = _Factored(matrix, None).solve(ground_rhs)
    if ground is None or not _accurate(matrix, ground, ground_rhs):
        raise np.linalg.LinAlgError("singular condensed system")
    return condensed.expand(inner, ground)


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class _Factored:
    """A symmetric matrix factored once for all the right-hand sides that meet it: by
    Cholesky (positive definite: S0 + K_c of a contact state whose holding contacts
    restrain every component, a Newton step's Hessian), else by LU."""

    matrix: np.ndarray
    factor: np.ndarray | None       # upper Cholesky factor, None: solved by LU

    def solve(self, rhs: np.ndarray) -> np.ndarray | None:
        """x with matrix @ x = rhs, None if the matrix is singular."""
        if self.factor is not None:
            return cholesky_solve(self.factor, rhs)
        try:
            return np.linalg.solve(self.matrix, rhs)
        except np.linalg.LinAlgError:
            return None


def anchored_system(model: StaticsModel, holding: np.ndarray,
                    scale: float = 1.0) -> _Factored:
    """S0 + K_c of the anchor springs at ``holding`` (x ``scale``), ``_Factored``, kept per
    model and contact state: the load cases of a design mostly start from the same state."""
    key = (holding.tobytes(), scale)
    systems = model.anchored_systems
    if key in systems:
        systems[key] = systems.pop(key)         # the most recently used last
        return systems[key]
    matrix = _anchored_stiffness(model, holding, scale)
    systems[key] = _Factored(matrix, cholesky(matrix))
    _trim(systems, 2 * matrix.nbytes)
    return systems[key]


def _trim(systems: dict, each: int) -> None:
    """Forget the least recently used factored systems beyond ANCHORED_CACHE_BYTES (each
    takes ``each`` bytes, matrix and factor; the newest is always kept): a big design's
    contact iterations meet many states of a matrix of tens of MB.  A forgotten state met
    again is factored again, to the same numbers."""
    while len(systems) > 1 and len(systems) * each > tol.ANCHORED_CACHE_BYTES:
        del systems[next(iter(systems))]
