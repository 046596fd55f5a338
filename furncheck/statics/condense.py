"""Static condensation of the mixed system onto the grounded planks.

``_condense`` gives, once per design, ``_PlankCondensation`` (up to DENSE_PLANKS_MAX
plank displacements: the joints eliminated, a dense Cholesky factor of the planks' joint
stiffness; a larger elastic model the same with one sparse LU, ``_condense_beams``) or
``_Condensation`` (a larger rigid model: one sparse LU of the contact-free mixed system,
checked by ``_factor`` / ``_accurate``).  The contact springs on top of it, a contact
state's factored matrix and the full mixed system are ``statics.anchored``'s.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.elements import beam_entries_placed, element_entries
from furncheck.statics.lapack import cholesky, cholesky_solve
from furncheck.statics.model import _SIX, StaticsModel

if TYPE_CHECKING:
    import scipy.sparse as sp


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class _Condensed:
    """What the contact iterations use of a condensation onto the grounded planks g
    (i: the other unknowns): S0, the coupling and X = (i-i block)^-1 (i-g block); each
    kind adds its factor and ``split`` / ``expand``."""

    ground: np.ndarray           # indices of g
    inner: np.ndarray            # indices of i
    coupling: object             # the i-g block (sparse or dense)
    reduced: np.ndarray | None   # X; None for a large system (``_implicit``): X x_g is
                                 # then solved for when needed, never stored
    schur: np.ndarray            # S0
    contact_block: np.ndarray    # per contact, number of its plank's 6-block in x_g
    plank_offsets: np.ndarray    # offset of each grounded plank's block in x_g
    size: int                    # unknowns of the whole mixed system

    def load(self, f: np.ndarray):
        """``split`` of the plank loads f (the joint rows have no load)."""
        b = np.zeros(self.size)
        b[:len(f)] = f
        return self.split(b)


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class _Condensation(_Condensed):
    """Static condensation of the mixed system onto the grounded planks.

    Order the unknowns as g (the six displacements of each plank with ground contacts) and
    i (all other plank displacements and every joint wrench).  Contact springs touch only
    the g-g block, so with A the contact-free matrix

        S0 = A_gg - A_gi A_ii^-1 A_ig,   X = A_ii^-1 A_ig,   y = A_ii^-1 b_i

    are computed once per design (A_ii by one sparse LU) and per load case, and each
    contact-state iteration only solves (S0 + K_c) x_g = b_g - A_gi y, a dense system of
    6 x (grounded planks); then x_i = y - X x_g.
    """

    lu: object = None            # SuperLU of A_ii (the coupling is A_ig, sparse)

    def split(self, rhs: np.ndarray):
        """(y, b_g - A_gi y) for a right-hand side of the whole system, (size,) or
        (size, k): y is what ``expand`` needs besides x_g."""
        inner = self.lu.solve(np.asfortranarray(rhs[self.inner])) if len(self.inner) else \
            np.zeros((0,) + rhs.shape[1:])
        return inner, rhs[self.ground] - self.coupling.T @ inner

    def expand(self, inner_part: np.ndarray, ground: np.ndarray) -> np.ndarray:
        """The full unknown vector [q; h] (or k of them, columns) from x_g."""
        x = np.zeros((self.size,) + ground.shape[1:])
        x[self.ground] = ground
        x[self.inner] = inner_part - _times_reduced(self, ground)
        return x


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class _PlankCondensation(_Condensed):
    """The same condensation for a design of few planks, through the planks alone.

    The joint rows of the mixed system give h = W (G q - r_h), W = E^-1 (diagonal), so the
    planks' displacements solve K q = r_q + G^T W r_h with the joint stiffness
    K = G^T W G (dense, 6 nP square; positive definite on the planks that are not
    grounded, every one of which is jointed, directly or not, to a grounded one).
    Condensed onto the grounded planks g, with i the others (a dense Cholesky factor):

        S0 = K_gg - K_gi K_ii^-1 K_ig,   X = K_ii^-1 K_ig,   y = K_ii^-1 f_i

    and as in ``_Condensation`` each contact-state iteration solves (S0 + K_c) x_g =
    f_g - K_gi y, then q_i = y - X x_g and h = W (G q - r_h).
    """

    factor: np.ndarray | None = None    # Cholesky factor of K_ii (the coupling is K_ig, dense)
    model: StaticsModel | None = None    # its joint blocks apply G, G^T and W (a weak
                                         # proxy: the model keeps its condensation, and a
                                         # cycle would keep a big model's memory until the
                                         # garbage collector's next full pass)
    lu: object = None                    # instead of ``factor``: SuperLU of a sparse K_ii

    def split(self, rhs: np.ndarray):
        """(the part of the solution x_g does not change, f_g - K_gi y) for a right-hand
        side [r_q; r_h] of the whole mixed system, (size,) or (size, k)."""
        n = self.model.n_dof
        r_h = rhs[n:]
        f = rhs[:n]
        if np.any(r_h):
            f = f + self.model.reactions(self.model.joint_wrench(r_h))
        inner = self._inner_solve(f[self.inner]) if len(self.inner) else \
            np.zeros((0,) + rhs.shape[1:])
        return (inner, r_h), f[self.ground] - self.coupling.T @ inner

    def _inner_solve(self, rhs: np.ndarray) -> np.ndarray:
        """K_ii^-1 rhs, by the dense Cholesky factor or the sparse LU."""
        if self.lu is not None:     # columns in SuperLU's own (Fortran) order: no copy
            return self.lu.solve(np.asfortranarray(rhs))
        return cholesky_solve(self.factor, rhs)

    def expand(self, inner_part, ground: np.ndarray) -> np.ndarray:
        """[q; h] from x_g.  The wrenches are taken as W (G [0; y] - r_h) + W G [x_g; -X x_g]
        rather than from q = [x_g; y - X x_g]: q is mostly the whole design's motion on its
        soft contact springs, and y, the joints' deformation, 1e-5 of it, would lose five
        digits in the sum."""
        inner, r_h = inner_part
        n, shape = self.model.n_dof, ground.shape[1:]
        parts = np.zeros((n, 2) + shape)          # [0; y] and [x_g; -X x_g] side by side
        parts[self.inner, 0] = inner
        parts[self.ground, 1] = ground
        parts[self.inner, 1] = -_times_reduced(self, ground)
        deviations = self.model.deviations(parts.reshape((n, -1))).reshape((-1, 2) + shape)
        h = self.model.joint_wrench((deviations[:, 0] - r_h) + deviations[:, 1])
        q = parts[:, 0] + parts[:, 1]
        return np.concatenate([q, h])


def _condense_planks(model: StaticsModel, ground: np.ndarray,
                     contact_block: np.ndarray, plank_offsets: np.ndarray):
    """``_PlankCondensation`` of the model; None if K_ii is singular.  K is summed from
    the joints' blocks, B_s^T W B_t into the block of nodes (s, t), plus the beams'
    stiffness (elastic model)."""
    n, m = model.n_dof, 6 * model.n_springs
    blocks, nodes = model.joint_blocks, model.joint_nodes
    weighted = model.joint_stiffness[:, None] @ blocks                  # (nJ, 2, 6, 6)
    pairs = np.swapaxes(blocks, 2, 3)[:, :, None] @ weighted[:, None]   # (nJ, 2, 2, 6, 6)
    n_nodes = model.n_nodes
    # K is assembled with the nodes reordered, the others first and the grounded ones
    # last, so that its parts are slices rather than gathered rows and columns; each
    # entry sums its joints' terms in the joints' order, then its elements' (the joints'
    # sum alone is as before; where elements meet a joint the last bits may differ from
    # adding the elements' own sum to it)
    inner = _others(n, ground)
    grounded = ground[::6] // 6
    order = np.concatenate([inner[::6] // 6, grounded])
    position = np.empty(n_nodes, dtype=int)
    position[order] = np.arange(n_nodes)
    first = 6 * position[nodes]                                         # (nJ, 2)
    rows = first[:, :, None, None, None] + _SIX[None, None, None, :, None]
    cols = first[:, None, :, None, None] + _SIX[None, None, None, None, :]
    index, values = (rows * n + cols).ravel(), pairs.ravel()
    if model.beams is not None:
        beam_index, beam_values = beam_entries_placed(model.beams, position)
        index, values = np.concatenate([index, beam_index]), np.concatenate([values, beam_values])
    K = np.bincount(index, weights=values, minlength=n * n) \
        .astype(float, copy=False).reshape(n, n)     # (no terms at all: integer zeros)
    ni = len(inner)
    coupling = K[:ni, ni:]
    reduced = np.zeros((ni, len(ground)))
    factor = None
    if ni:
        K_ii = K[:ni, :ni]
        factor = cholesky(K_ii)
        if factor is None:
            return None
        probe = coupling.sum(axis=1) if len(ground) else np.ones(len(inner))
        if not np.any(probe):
            probe = np.ones(len(inner))
        solved = cholesky_solve(factor, np.column_stack([coupling, probe]))
        if not _accurate(K_ii, solved[:, -1], probe):
            return None
        reduced = solved[:, :-1]
    schur = K[ni:, ni:] - coupling.T @ reduced
    return _PlankCondensation(ground, inner, coupling, reduced, schur, contact_block,
                              plank_offsets, n + m, factor=factor, model=weakref.proxy(model))


def _condense_beams(model: StaticsModel, ground: np.ndarray,
                    contact_block: np.ndarray, plank_offsets: np.ndarray):
    """``_PlankCondensation`` of an elastic model too large for dense matrices: the joints
    eliminated as in ``_condense_planks``, K = K_b + G^T W G sparse (symmetric positive
    definite on the nodes that are not grounded), K_ii factored by one sparse LU (half the
    unknowns of the mixed system, and no indefinite joint rows to pivot on); None if K_ii
    is singular.  K's parts are assembled straight from the joints' and elements' entries
    (``_stiffness_entries``): K_ii sparse, K_ig and K_gg dense; where X = K_ii^-1 K_ig
    would be too big to store (``_implicit``), K comes from the sparse products instead
    (``_condense_implicit``: the entry lists of thousands of planks take more memory and
    time than they save)."""
    import scipy.sparse as sp

    n, m = model.n_dof, 6 * model.n_springs
    inner = _others(n, ground)
    ni, ng = len(inner), len(ground)
    if _implicit(ni, ng):
        return _condense_implicit(model, ground, inner, contact_block, plank_offsets)
    rows, cols, values = _stiffness_entries(model, inner, ground)
    in_rows, in_cols = rows < ni, cols < ni
    both = in_rows & in_cols
    inner_block = sp.coo_matrix((values[both], (rows[both], cols[both])),
                                shape=(ni, ni)).tocsc()
    across = in_rows & ~in_cols
    coupling = _dense_sum(rows[across], cols[across] - ni, values[across], ni, ng)
    grounded = ~in_rows & ~in_cols
    ground_block = _dense_sum(rows[grounded] - ni, cols[grounded] - ni, values[grounded],
                              ng, ng)
    reduced = np.zeros((ni, ng))
    lu = None
    if ni:
        lu, reduced = _factor_solving(inner_block, coupling)
        if lu is None:
            return None
    schur = ground_block - coupling.T @ reduced
    return _PlankCondensation(ground, inner, coupling, reduced, schur, contact_block,
                              plank_offsets, n + m, model=weakref.proxy(model), lu=lu)


def _condense_implicit(model: StaticsModel, ground: np.ndarray, inner: np.ndarray,
                       contact_block: np.ndarray, plank_offsets: np.ndarray):
    """``_condense_beams`` of a model whose X = K_ii^-1 K_ig is never stored: K = K_b +
    G^T W G by sparse products, S0 as the trailing block of one more factorization
    (``_trailing_schur``) or a few columns at a time (``_blocked_schur``)."""
    n, m = model.n_dof, 6 * model.n_springs
    G = model.G
    K = (model.beam_stiffness + (G.T @ _block_diagonal(model.joint_stiffness) @ G)).tocsc()
    inner_rows = K[inner]
    coupling_sparse = inner_rows[:, ground]
    inner_block = inner_rows[:, inner].tocsc()
    lu = _factor(inner_block,
                 np.asarray(coupling_sparse.sum(axis=1)).ravel()) if len(inner) else None
    if lu is None and len(inner):
        return None
    coupling = coupling_sparse.tocsr()
    ground_block = K[ground][:, ground].toarray()
    schur = _trailing_schur(inner_block, coupling, ground_block, lu)
    if schur is None:
        schur = _blocked_schur(ground_block, coupling, lu)
    return _PlankCondensation(ground, inner, coupling, None, schur, contact_block,
                              plank_offsets, n + m, model=weakref.proxy(model), lu=lu)


def _stiffness_entries(model: StaticsModel, inner: np.ndarray, ground: np.ndarray):
    """(rows, columns, values) of K = K_b + G^T W G, the unknowns numbered ``inner``
    first and ``ground`` after them: each joint's four (6, 6) blocks B_s^T W B_t between
    its nodes s, t, then each beam element's (12, 12) entries; an entry may be listed
    several times (to be summed)."""
    order = np.empty(model.n_dof, dtype=np.int64)
    order[inner] = np.arange(len(inner))
    order[ground] = len(inner) + np.arange(len(ground))
    blocks, nodes = model.joint_blocks, model.joint_nodes
    weighted = model.joint_stiffness[:, None] @ blocks                  # (nJ, 2, 6, 6)
    pairs = np.swapaxes(blocks, 2, 3)[:, :, None] @ weighted[:, None]   # (nJ, 2, 2, 6, 6)
    dofs = 6 * nodes[:, :, None] + _SIX                                 # (nJ, 2, 6)
    shape = pairs.shape
    joint_rows = np.broadcast_to(dofs[:, :, None, :, None], shape).ravel()
    joint_cols = np.broadcast_to(dofs[:, None, :, None, :], shape).ravel()
    parts = [(joint_rows, joint_cols, pairs.ravel())]
    if model.beams is not None:
        world, rows, cols = element_entries(model.beams)
        parts.append((rows.ravel(), cols.ravel(), world.ravel()))
    rows, cols, values = (np.concatenate(part) for part in zip(*parts))
    return order[rows], order[cols], values


def _dense_sum(rows: np.ndarray, cols: np.ndarray, values: np.ndarray, height: int,
               width: int) -> np.ndarray:
    """(height, width): the ``values`` summed at their (row, column), in order."""
    return np.bincount(rows * width + cols, weights=values, minlength=height * width) \
        .reshape(height, width)


def _block_diagonal(blocks: np.ndarray):
    """(6 nJ, 6 nJ) CSR matrix of the (nJ, 6, 6) blocks on its diagonal, every entry of
    a block stored (zeros too): the matrix ``scipy.sparse.block_diag(list(blocks),
    format="csr")`` gives, entry for entry and in the same order, made without a sparse
    matrix per block."""
    import scipy.sparse as sp

    size = 6 * len(blocks)
    columns = (6 * (np.arange(size, dtype=np.int32)[:, None] // 6) + _SIX[None, :]) \
        .astype(np.int32).ravel()
    pointers = np.arange(0, 6 * size + 1, 6, dtype=np.int32)
    return sp.csr_matrix((blocks.reshape(-1).copy(), columns, pointers), shape=(size, size))


def _implicit(n_inner: int, n_ground: int) -> bool:
    """Whether X = A_ii^-1 A_ig of a condensation would take more than CONDENSED_DENSE_BYTES
    as a dense matrix: then it is never stored (``_blocked_schur``, ``_times_reduced``)."""
    return 8 * n_inner * n_ground > tol.CONDENSED_DENSE_BYTES


def _blocked_schur(ground_block: np.ndarray, coupling, lu) -> np.ndarray:
    """S0 = A_gg - A_ig^T A_ii^-1 A_ig from the sparse coupling A_ig, a few columns of X at
    a time (at most CONDENSED_DENSE_BYTES of them)."""
    schur = ground_block
    n_inner, n_ground = coupling.shape
    if not n_inner or not n_ground:
        return schur
    width = max(1, tol.CONDENSED_DENSE_BYTES // (8 * n_inner))
    columns = coupling.tocsc()
    transposed = coupling.T.tocsr()
    for start in range(0, n_ground, width):
        block = slice(start, min(start + width, n_ground))
        reduced = lu.solve(columns[:, block].toarray(order="F"))
        schur[:, block] -= transposed @ reduced
    return schur


def _trailing_schur(inner_block: sp.csc_matrix, coupling, ground_block: np.ndarray,
                    lu) -> np.ndarray | None:
    """S0 = A_gg - A_ig^T A_ii^-1 A_ig of a symmetric positive definite A_ii (the elastic
    planks' stiffness) as the trailing block of one more factorization, instead of one
    solve per grounded unknown (a 2,001-plank wall: 0.15 s against 1.7 s).

    [[A_ii, A_ig], [A_gi, A_gg + s I]], its inner columns in the elimination order of
    ``lu`` (A_ii's own factor, so the fill is the same) and the grounded ones last, is
    factored without pivoting; elimination leaves S0 + s I = L_gg U_gg in the trailing
    block.  The shift s, the largest diagonal entry of A_gg, makes that block positive
    definite although S0 has the design's free motions (the contact springs hold them),
    at a round-off of ~1e-16 s, as small as S0's own.  None (then ``_blocked_schur``)
    when the grounded unknowns are more than TRAILING_SCHUR_MAX (the dense trailing
    factors would cost more memory than the solves), when the factorization did not keep
    them last (several separate parts of a design), or when its S0 fails a probe."""
    n_inner, n_ground = coupling.shape
    if not n_inner or not n_ground or n_ground > tol.TRAILING_SCHUR_MAX or lu is None:
        return None
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    order = np.argsort(lu.perm_c)
    rows = coupling[order]
    shift = float(np.abs(np.diag(ground_block)).max(initial=0.0)) or 1.0
    matrix = sp.bmat([[inner_block[order][:, order], rows],
                      [rows.T, sp.csc_matrix(ground_block + shift * np.eye(n_ground))]],
                     format="csc")
    try:
        factor = spla.splu(matrix, **_TRAILING_LU)
    except RuntimeError:
        return None
    tail = np.arange(n_inner, n_inner + n_ground)
    if not (np.array_equal(factor.perm_c[tail], tail)
            and np.array_equal(factor.perm_r[tail], tail)):
        return None
    lower = factor.L.tocsr()[n_inner:].tocsc()[:, n_inner:].toarray()
    upper = factor.U.tocsr()[n_inner:].tocsc()[:, n_inner:].toarray()
    schur = lower @ upper
    schur[np.diag_indices(n_ground)] -= shift
    probe = np.ones(n_ground)
    exact = ground_block @ probe - coupling.T @ lu.solve(coupling @ probe)
    scale = float(np.abs(ground_block).sum(axis=1).max())
    if not np.abs(schur @ probe - exact).max() <= tol.SOLVE_RESIDUAL * scale:
        return None
    return schur


_TRAILING_LU = {"permc_spec": "NATURAL", "diag_pivot_thresh": 0.0,
                "options": {"SymmetricMode": True}}


def _times_reduced(condensed: _Condensed, ground: np.ndarray) -> np.ndarray:
    """X x_g (x_g (n_g,) or (n_g, k)): by the stored X, or for an implicit condensation by
    one more solve, A_ii^-1 (A_ig x_g)."""
    if condensed.reduced is not None:
        return condensed.reduced @ ground
    if not len(condensed.inner):
        return np.zeros((0,) + ground.shape[1:])
    return condensed.lu.solve(np.asfortranarray(condensed.coupling @ ground))


def ground_unknowns(model: StaticsModel) -> int:
    """Unknowns of the condensed system (rows of S0, the dense matrix that every contact
    state factors): six per node that a ground contact sits on or a resting corner rests
    on, the g of ``_condense``."""
    nodes = model.contact_node
    if model.rest_node is not None:
        nodes = np.concatenate([nodes, model.rest_node[model.rest_rows]])
    return 6 * len(_distinct(nodes))


def _distinct(values: np.ndarray) -> np.ndarray:
    """``np.unique(values)`` (sorted, each once) without numpy 2's test for a masked
    array, which imports numpy.ma: 12 ms of a small design's cold start."""
    ordered = np.sort(values)
    if len(ordered) < 2:
        return ordered
    return ordered[np.concatenate(([True], ordered[1:] != ordered[:-1]))]


def _condense(model: StaticsModel) -> _Condensed | None:
    """Build the condensation; None if the contact-free part is singular (a plank that
    is neither grounded nor jointed to a grounded plank cannot be held).  Designs of up
    to DENSE_PLANKS_MAX plank displacements go through the planks with dense matrices
    (``_PlankCondensation``), larger elastic ones through the planks with a sparse LU
    (``_condense_beams``), larger rigid ones through the sparse mixed system by SuperLU."""
    n, m = model.n_dof, 6 * model.n_springs
    grounded, contact_block = np.unique(model.contact_node, return_inverse=True)
    if model.rest_node is not None:     # the nodes that resting corners rest on, too
        grounded = _distinct(np.concatenate([model.contact_node,
                                             model.rest_node[model.rest_rows]]))
        contact_block = np.searchsorted(grounded, model.contact_node)
    ground = (6 * grounded[:, None] + _SIX[None, :]).ravel()
    contact_block, plank_offsets = contact_block.astype(int), 6 * np.arange(len(grounded))
    if n <= tol.DENSE_PLANKS_MAX:
        return _condense_planks(model, ground, contact_block, plank_offsets)
    if model.beam_stiffness is not None:
        return _condense_beams(model, ground, contact_block, plank_offsets)
    inner = _others(n + m, ground)
    ni = len(inner)
    order = np.concatenate([inner, ground])
    A = _contact_free_matrix(model).tocsc()
    permuted = A[order][:, order].tocsc()
    coupling = permuted[:ni, ni:].tocsc()
    lu, reduced = None, np.zeros((ni, len(ground)))
    if ni:
        lu = _factor(permuted[:ni, :ni].tocsc(), np.asarray(coupling.sum(axis=1)).ravel())
        if lu is None:
            return None
        if _implicit(ni, len(ground)):
            schur = _blocked_schur(permuted[ni:, ni:].toarray(), coupling.tocsr(), lu)
            return _Condensation(ground, inner, coupling.tocsr(), None, schur, contact_block,
                                 plank_offsets, n + m, lu=lu)
        if len(ground):
            reduced = lu.solve(coupling.toarray(order="F"))
    schur = permuted[ni:, ni:].toarray() - np.asarray(coupling.T @ reduced)
    return _Condensation(ground, inner, coupling, reduced, schur, contact_block,
                         plank_offsets, n + m, lu=lu)


def _contact_free_matrix(model: StaticsModel) -> sp.coo_matrix:
    """[[K_b, G^T], [G, -E]]: the mixed system without contact springs (K_b the beams'
    stiffness, zero for rigid planks; E the joints' compliance blocks)."""
    import scipy.sparse as sp

    n, m = model.n_dof, 6 * model.n_springs
    G = model.G.tocoo()
    block = np.arange(m).reshape(-1, 6)
    rows_e = np.broadcast_to(block[:, :, None], (len(block), 6, 6)).ravel()
    cols_e = np.broadcast_to(block[:, None, :], (len(block), 6, 6)).ravel()
    parts_rows = [G.col, n + G.row, n + rows_e]
    parts_cols = [n + G.row, G.col, n + cols_e]
    parts_values = [G.data, G.data, -model.joint_compliance.ravel()]
    if model.beam_stiffness is not None:
        beams = model.beam_stiffness.tocoo()
        parts_rows.append(beams.row)
        parts_cols.append(beams.col)
        parts_values.append(beams.data)
    return sp.coo_matrix((np.concatenate(parts_values),
                          (np.concatenate(parts_rows), np.concatenate(parts_cols))),
                         shape=(n + m, n + m))


def _others(n: int, chosen: np.ndarray) -> np.ndarray:
    """0 ... n - 1 without ``chosen``, in order."""
    keep = np.ones(n, dtype=bool)
    keep[chosen] = False
    return np.flatnonzero(keep)


def _factor(A: sp.csc_matrix, probe: np.ndarray):
    """SuperLU of the symmetric matrix A, or None if it is singular.  The factors are
    checked on the right-hand side ``probe``.

    A symmetric fill-reducing ordering with diagonal pivots keeps the factors about ten
    times sparser than the default; if it solves the probe columns poorly (a tiny pivot),
    partial pivoting (SuperLU's default) is used instead.
    """
    import scipy.sparse.linalg as spla

    rhs = probe if np.any(probe) else np.ones(A.shape[0])
    for options in (_SYMMETRIC_LU, {}):
        try:
            lu = spla.splu(A, **options)
        except RuntimeError:
            continue
        if _accurate(A, lu.solve(rhs), rhs):
            return lu
    return None


def _factor_solving(A: sp.csc_matrix, columns: np.ndarray):
    """(SuperLU of the symmetric matrix A, A^-1 ``columns``), or (None, None) if A is
    singular: ``_factor`` with its probe, the sum of the columns, solved along with them
    (one solve for both)."""
    import scipy.sparse.linalg as spla

    probe = columns.sum(axis=1) if columns.shape[1] else np.zeros(A.shape[0])
    if not np.any(probe):
        probe = np.ones(A.shape[0])
    rhs = np.empty((A.shape[0], columns.shape[1] + 1), order="F")  # SuperLU's own order:
    rhs[:, :-1] = columns                                           # no copy per solve
    rhs[:, -1] = probe
    for options in (_SYMMETRIC_LU, {}):
        try:
            lu = spla.splu(A, **options)
        except RuntimeError:
            continue
        solved = lu.solve(rhs)
        if _accurate(A, solved[:, -1], probe):
            return lu, solved[:, :-1]
    return None, None


def _accurate(A, x: np.ndarray, b: np.ndarray, load_scale: float = 0.0) -> bool:
    """Whether x solves A x = b to a normwise backward error below SOLVE_RESIDUAL:
    max|A x - b| <= tol (max row sum of |A| x max|x| + max(max|b|, load_scale)).
    ``load_scale``: the size of the loads behind b when b is only their round-off."""
    if not np.all(np.isfinite(x)):
        return False
    norm = float(abs(A).sum(axis=1).max()) if A.shape[0] else 0.0
    scale = norm * float(np.abs(x).max(initial=0.0)) \
        + max(float(np.abs(b).max(initial=0.0)), load_scale)
    return float(np.abs(A @ x - b).max(initial=0.0)) <= tol.SOLVE_RESIDUAL * max(scale, 1e-300)


_SYMMETRIC_LU = {"permc_spec": "MMD_AT_PLUS_A", "diag_pivot_thresh": 0.0,
                 "options": {"SymmetricMode": True}}
