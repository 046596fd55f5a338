"""A plate plank's plate itself (``statics.plates`` says which planks, on what supports,
under what loads): Mindlin, bilinear elements with selectively reduced shear integration
(bending by 2 x 2 Gauss points, transverse shear by one), on a grid through every support
line's ends and load patch's edges, about PLATE_CELLS elements across its shorter side
(none shorter than PLATE_CELL_FLOOR of its thickness; ``grid_lines``,
``_element_matrices``); the supported nodes' w held at zero, each nail row's grip a
rotational spring along its line, each rail a Hermite beam along its line;
factored as a band (LAPACK's pbtrf, the nodes numbered across the shorter direction
first) and kept for the last PLATE_CACHE asked (``plate_grid``: planks alike, and a plank
an edit leaves as it was, share one); solved for many loads at once
(``plate_solutions``), its sag and span read between its supports (``sag_span``).
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np

from furncheck import tolerances as tol
from furncheck.statics.beams import SHEAR_FACTOR


class PlateGrid(NamedTuple):
    """A plank's plate, factored (``plate_grid``): the grid lines (x, y, m, plank-local,
    ascending), the supported nodes (indices, row-major, x fastest), each unknown's place
    in the banded matrix (``_ranks``), those held at zero (the supported nodes' w:
    identity rows in the matrix), the banded Cholesky factor (``_banded_factor``), per element
    the (3, 12) map from its unknowns to its centre's moments (M_x, M_y, M_xy, N m / m)
    and its unknowns (``_element_dofs``), the plate's thickness (m), the elements'
    centres (x, y) and areas (m^2), the nodes (X, Y, row-major) and which of them lie
    between the supports (within the supported nodes' bounding box, ``sag_span``); for a
    plate hung on one line, its ``_hinge`` (every node lies beyond it), else None."""

    xs: np.ndarray
    ys: np.ndarray
    supported: np.ndarray
    rank: np.ndarray
    fixed: np.ndarray
    factor: np.ndarray
    moments: np.ndarray
    dofs: np.ndarray
    thickness: float
    centres: tuple
    areas: np.ndarray
    nodes: tuple
    between: np.ndarray
    hinge: tuple | None = None


def grid_lines(low: float, high: float, lines, edges, cell: float) -> np.ndarray:
    """Ascending grid coordinates from ``low`` to ``high`` through every support or rail
    line's coordinate and end (``lines``: those within NODE_MERGE of one another taken
    as one, ``_merged``) and every load patch edge (``edges``) not within NODE_MERGE of
    those (a patch edge may move; a support may not lose its grid line), likewise
    merged, each interval cut into equal cells of at most ``cell``, the kept lines
    themselves exactly among them (``_on_segment`` finds a support's nodes by their
    distance to its line)."""
    fixed = _merged(np.sort(np.clip(np.asarray([*lines], dtype=float), low, high)),
                    low, high)
    soft = np.sort([value for value in np.clip(np.asarray(edges, dtype=float), low, high)
                    if np.abs(fixed - value).min() > tol.NODE_MERGE])
    kept = fixed
    if len(soft):
        kept = np.sort(np.concatenate([fixed, _merged(soft)]))
    if len(kept) > tol.PLATE_GRID_LINES:        # many point loads: their edges are left
        kept = fixed                            # out (each load is still shared by area)
    # (np.sort, not np.unique: numpy 2's unique imports numpy.ma, 12 ms of a cold start)
    low, size = kept[:-1], np.diff(kept)
    cuts = np.maximum(1, np.ceil(size / cell - tol.PLATE_CELL_SLACK).astype(int))
    step = np.arange(1, int(cuts.sum()) + 1) - np.repeat(np.cumsum(cuts) - cuts, cuts)
    grid = np.concatenate([kept[:1], np.repeat(low, cuts)
                           + np.repeat(size, cuts) * step / np.repeat(cuts, cuts)])
    grid[np.cumsum(cuts)] = kept[1:]        # each kept line as it is, not off by round-off
    return grid


def _merged(points: np.ndarray, low: float | None = None,
            high: float | None = None) -> np.ndarray:
    """Grid lines for the ascending ``points``, each within NODE_MERGE of one, no two
    within NODE_MERGE of each other (but where a run is cut into equal parts, see below),
    and the same for the points' mirror image, mirrored: a design and its mirror image
    get mirrored grids (keeping the first of two points a fraction of a millimetre
    apart, as before, gave a chair's seat a line at -200 mm and one at +199.7 mm, and its
    stress moved by 1e-5 of itself when mirrored).  Where ``low`` and ``high`` are given
    (the plate's edges), they are lines, each taking the points within NODE_MERGE of
    it, the distance measured as ``_on_segment`` measures it, |point - edge| (``point >
    low + NODE_MERGE`` rounds the other way at times: a support 1 mm inside a 1902 mm
    shelf's end, 1.0000000000000009 mm as measured, was folded into the edge and then
    found on no line, and the plate, held on two of its four supports, read a 3.65 mm
    sag for 0.82).  The other points fall into runs, each point within NODE_MERGE of the
    next; a run gets k = floor(length / (2 NODE_MERGE)) + 1 lines at the middles of k
    equal parts (one at its middle where it is shorter than twice NODE_MERGE), each point
    within NODE_MERGE of its part's middle."""
    merge = tol.NODE_MERGE
    lines = []
    if low is not None:
        points = points[(np.abs(points - low) > merge) & (np.abs(high - points) > merge)]
        lines.append(low)
    if len(points):
        breaks = np.flatnonzero(np.diff(points) > merge) + 1
        for run in np.split(points, breaks):
            start, length = float(run[0]), float(run[-1] - run[0])
            parts = math.floor(length / (2.0 * merge)) + 1
            lines.extend(start + length * (2 * np.arange(parts) + 1) / (2 * parts))
    if high is not None:
        lines.append(high)
    return np.asarray(lines, dtype=float)


_CORNERS = np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)], dtype=float)


def _reference_derivatives(xi: float, eta: float) -> tuple[np.ndarray, ...]:
    """(4,) each: the bilinear shape functions and their derivatives by xi and eta."""
    a, b = _CORNERS[:, 0], _CORNERS[:, 1]
    return ((1 + a * xi) * (1 + b * eta) / 4, a * (1 + b * eta) / 4, b * (1 + a * xi) / 4)


def _bending_matrix(rigidity: float, poisson: float) -> np.ndarray:
    """(3, 3) N m: the moments (M_x, M_y, M_xy) per unit curvature (kappa_x, kappa_y,
    2 kappa_xy) of an isotropic plate of ``rigidity`` D = E t^3 / 12 (1 - nu^2)."""
    return rigidity * np.array([[1, poisson, 0], [poisson, 1, 0], [0, 0, (1 - poisson) / 2]])


def _element_matrices(rigidity: float, poisson: float, shear: float) -> np.ndarray:
    """(6, 144): six (12, 12) matrices, flattened, whose sum weighted by (hy/hx, hx/hy,
    1, hy, hx, hx hy) is the stiffness of an hx x hy element (unknowns w, beta_x, beta_y
    per corner, corners counter-clockwise from (-, -)): bending by 2 x 2 Gauss points,
    transverse shear (``shear``: k G t, N/m) by one (``_unit_element_matrices``)."""
    bending, shearing = _unit_element_matrices(poisson)
    return (rigidity * bending + shear * shearing).reshape(6, 144)


@functools.lru_cache(maxsize=4)
def _unit_element_matrices(poisson: float) -> tuple[np.ndarray, np.ndarray]:
    """(bending, shear), (6, 12, 12) each: ``_element_matrices``' terms for D = 1 and
    k G t = 1.  With dx = (2 / hx) d/dxi and dy = (2 / hy) d/deta, the bending integrand
    B^T C B hx hy / 4 splits into hy/hx, hx/hy and 1 terms, the shear one's k G t hx hy
    B_s^T B_s into the hy/hx, hx/hy, hy, hx and hx hy ones.  Read-only: the cache
    shares them."""
    C = _bending_matrix(1.0, poisson)
    bending, shearing = np.zeros((6, 12, 12)), np.zeros((6, 12, 12))
    g = 1 / np.sqrt(3)
    for xi in (-g, g):
        for eta in (-g, g):
            _, dxi, deta = _reference_derivatives(xi, eta)
            gx, gy = np.zeros((3, 12)), np.zeros((3, 12))
            gx[0, 1::3], gx[2, 2::3] = dxi, dxi          # kappa_x, and d beta_y / dx
            gy[1, 2::3], gy[2, 1::3] = deta, deta        # kappa_y, and d beta_x / dy
            bending[0] += gx.T @ C @ gx
            bending[1] += gy.T @ C @ gy
            bending[2] += gx.T @ C @ gy + gy.T @ C @ gx
    n, dxi, deta = _reference_derivatives(0.0, 0.0)
    sx, sy, s0 = np.zeros((2, 12)), np.zeros((2, 12)), np.zeros((2, 12))
    sx[0, 0::3], sy[1, 0::3] = dxi, deta
    s0[0, 1::3], s0[1, 2::3] = n, n
    shearing[0] += 4 * sx.T @ sx
    shearing[1] += 4 * sy.T @ sy
    shearing[3] -= 2 * (sx.T @ s0 + s0.T @ sx)
    shearing[4] -= 2 * (sy.T @ s0 + s0.T @ sy)
    shearing[5] += s0.T @ s0
    for array in (bending, shearing):
        array.setflags(write=False)
    return bending, shearing


@functools.lru_cache(maxsize=tol.PLATE_CACHE)
def plate_grid(cells: int, floor: float, patch_cells: int, poisson: float, merge: float,
               lines: int, slack: float, length: float, width: float, thickness: float,
               elastic_modulus: float, shear_modulus: float, segments: tuple,
               patches: tuple, stiffeners: tuple = ()) -> PlateGrid | None:
    """``plate_for``'s ``PlateGrid`` of a ``length`` x ``width`` x ``thickness`` plate
    (m) of moduli E and G (Pa) on ``segments``, stiffened by ``stiffeners``, its grid
    through ``patches``; its first arguments are the tolerances it follows (PLATE_CELLS,
    PLATE_CELL_FLOOR, PLATE_PATCH_CELLS and PLATE_POISSON, as given; NODE_MERGE,
    PLATE_GRID_LINES and PLATE_CELL_SLACK, which ``grid_lines`` reads, for the key
    alone), so that a grid made under others is not taken for this one.  Its arrays are
    read-only: the cache shares them."""
    half_x, half_y = length / 2.0, width / 2.0
    lines = (*segments, *stiffeners)
    quarters = np.linspace(0.0, 1.0, patch_cells + 1)
    lines_x = [v for (a, b, _) in lines for v in (a[0], b[0])]
    lines_y = [v for (a, b, _) in lines for v in (a[1], b[1])]
    edges_x = [v for p in patches for v in p[0] + (p[1] - p[0]) * quarters]
    edges_y = [v for p in patches for v in p[2] + (p[3] - p[2]) * quarters]
    cell = max(min(length, width) / cells, floor * thickness)
    xs = grid_lines(-half_x, half_x, lines_x, edges_x, cell)
    ys = grid_lines(-half_y, half_y, lines_y, edges_y, cell)
    nx, ny = len(xs), len(ys)
    t = thickness
    rigidity = elastic_modulus * t ** 3 / (12 * (1 - poisson ** 2))
    terms = _element_matrices(rigidity, poisson,
                              SHEAR_FACTOR * shear_modulus * t)
    hx = np.tile(np.diff(xs), ny - 1)                # per element, row-major
    hy = np.repeat(np.diff(ys), nx - 1)
    weights = np.column_stack([hy / hx, hx / hy, np.ones_like(hx), hy, hx, hx * hy])
    upper = weights @ terms[:, _UPPER_FLAT]         # (nE, 78): each element's upper triangle
    X, Y = np.tile(xs, ny), np.repeat(ys, nx)       # the nodes, row-major
    supported = _supported_nodes(xs, ys, segments)
    held = np.column_stack([X[supported], Y[supported]])
    hinge = None
    if len(held) < 3 or np.linalg.svd(held - held.mean(axis=0), compute_uv=False)[-1] \
            <= tol.NODE_MERGE:                  # on one line: its grip alone holds it
        hinge = _hinge(xs, ys, supported, segments)
        if hinge is None:
            return None
    fixed = np.zeros(3 * nx * ny, dtype=bool)
    fixed[3 * supported] = True
    layout = _layout(nx, ny)
    rank, dofs = layout.rank, layout.dofs
    grip_dofs, grips = _grips(xs, ys, segments)
    rows, cols, values = _stiffener_entries(xs, ys, stiffeners)
    factor = _banded_factor(layout, upper.ravel(),
                            (np.concatenate([rank[grip_dofs], rank[rows]]),
                             np.concatenate([rank[grip_dofs], rank[cols]]),
                             np.concatenate([grips, values])), rank[fixed])
    _, dxi, deta = _reference_derivatives(0.0, 0.0)
    C = _bending_matrix(rigidity, poisson)
    kappa = np.zeros((len(hx), 3, 12))
    kappa[:, 0, 1::3] = 2 * dxi / hx[:, None]
    kappa[:, 1, 2::3] = 2 * deta / hy[:, None]
    kappa[:, 2, 1::3] = 2 * deta / hy[:, None]
    kappa[:, 2, 2::3] = 2 * dxi / hx[:, None]
    moments = C @ kappa                             # (nE, 3, 12)
    if factor is None:
        return None
    cx = np.tile(0.5 * (xs[1:] + xs[:-1]), ny - 1)
    cy = np.repeat(0.5 * (ys[1:] + ys[:-1]), nx - 1)
    sx, sy = X[supported], Y[supported]
    slack = tol.NODE_MERGE
    between = (X >= sx.min() - slack) & (X <= sx.max() + slack) \
        & (Y >= sy.min() - slack) & (Y <= sy.max() + slack)
    if hinge is not None:
        between = np.ones_like(between)
        hinge = (*hinge[:2], *_line_moments(hinge[2], hinge[3], xs, ys, weights, terms,
                                            layout.dofs, cx, cy))
    arrays = (xs, ys, supported, fixed, factor, moments, cx, cy, X, Y, between,
              *(hinge or ()))
    for array in arrays:
        array.setflags(write=False)
    return PlateGrid(xs, ys, supported, rank, fixed, factor, moments, dofs, thickness,
                     (cx, cy), hx * hy, (X, Y), between, hinge)


def _hinge(xs: np.ndarray, ys: np.ndarray, supported: np.ndarray, segments) -> tuple | None:
    """For a plate whose supported nodes lie on one grid line, which its segments' nail
    rows grip against turning about it (a shelf nailed by its back edge onto a rail, a
    board on a single rail: ``plate_supports``): (per node, the unknown of the turn
    about the line at its support node, the nearest supported node along the line, and
    its distance from the line, m, signed; the supported nodes, in order along the line,
    and their grid line's axis), from which ``plate_solutions`` reads its deflections
    from the tangent at the line (contract 3a: a plank held at one end only), and
    ``_line_moments`` the moments at the line, where a cantilever's largest are.  None
    where they hold it nowhere along the line or do not grip it, or the nodes do not all
    lie on one line along an axis (it is then free to move)."""
    if len(supported) < 2 or not segments:
        return None
    i, j = supported % len(xs), supported // len(xs)
    axis = 0 if np.all(j == j[0]) else 1 if np.all(i == i[0]) else None
    grips = np.zeros(len(supported))
    for segment in segments:
        nodes, _ = _on_segment(xs, ys, segment)
        grips[np.searchsorted(supported, nodes)] = np.maximum(
            grips[np.searchsorted(supported, nodes)], segment[2])
    if axis is None or not np.all(grips > 0.0):
        return None
    X, Y = np.tile(xs, len(ys)), np.repeat(ys, len(xs))
    along, across = (X, Y) if axis == 0 else (Y, X)
    line, place = (ys[j[0]], xs[i]) if axis == 0 else (xs[i[0]], ys[j])
    nearest = np.abs(along[:, None] - place[None, :]).argmin(axis=1)
    turn = 3 * supported + (2 if axis == 0 else 1)   # beta_y along x, beta_x along y
    return turn[nearest], across - line, supported, axis


def _line_moments(supported: np.ndarray, axis: int, xs: np.ndarray, ys: np.ndarray,
                  weights: np.ndarray, terms: np.ndarray, dofs: np.ndarray, cx: np.ndarray,
                  cy: np.ndarray) -> tuple:
    """For a plate hung on one line (``_hinge``): (rows, columns, values, lengths), the
    moments that the elements on each side of the line put on its nodes' turn about it,
    sum over an element's unknowns u of its stiffness row times u (its nodal moment: the
    consistent one of its bending and shear, K_e u_e), row 2 r + side for the r-th
    supported node, each over that node's share of the line (``lengths``, m: half the
    distance to its neighbours on the line), N m / m, from the elements along the line
    alone (past a line that ends inside the plate, the moment at its end grows without
    bound as the cells shrink, as a plate's does at a support's corner: the elements
    beyond are left out, and its end reads what the line holds there).  A cantilever's
    largest moment is at its line, where the elements' centres, half a cell off, read it
    low (a board on a centre rail, both sides loaded, turns its line not at all: the
    grip takes nothing of the two sides' moments); a linear element's nodal moment is
    M + Q h / 2 of its centre's, the moment at its end less q h^2 / 8 (a percent of a
    141 mm cantilever's on 30 mm cells)."""
    turn = 3 * supported + (2 if axis == 0 else 1)
    where = {int(dof): r for r, dof in enumerate(turn)}
    line = (ys if axis == 0 else xs)[(supported // len(xs))[0] if axis == 0
                                     else (supported % len(xs))[0]]
    across, lengthwise = (cy, cx) if axis == 0 else (cx, cy)
    place = (xs[supported % len(xs)] if axis == 0 else ys[supported // len(xs)])
    within = (lengthwise > place[0]) & (lengthwise < place[-1])
    rows, cols, values = [], [], []
    for e in np.flatnonzero(np.isin(dofs, turn).any(axis=1) & within):
        stiffness = (weights[e] @ terms).reshape(12, 12)
        side = int(across[e] > line)
        for i in np.flatnonzero(np.isin(dofs[e], turn)):
            rows.append(np.full(12, 2 * where[int(dofs[e, i])] + side))
            cols.append(dofs[e])
            values.append(stiffness[i])
    bounds = np.concatenate([[place[0]], 0.5 * (place[1:] + place[:-1]), [place[-1]]])
    return (np.concatenate(rows), np.concatenate(cols), np.concatenate(values),
            np.repeat(np.diff(bounds), 2))


class _Layout(NamedTuple):
    """An nx x ny grid's numbering (``_layout``): each unknown's place in the banded
    matrix (``_ranks``), each element's unknowns (``_element_dofs``), and for the
    elements' upper triangles (``_UPPER``, element by element) their flat places in the
    band storage (``bands.ravel()``, ``_banded_factor``), with the band's width (the
    bands above the diagonal) and its order."""

    rank: np.ndarray
    dofs: np.ndarray
    flat: np.ndarray
    width: int
    size: int


@functools.lru_cache(maxsize=tol.PLATE_CACHE)
def _layout(nx: int, ny: int) -> _Layout:
    """The ``_Layout`` of an nx x ny grid.  Read-only: the cache shares it among the plates
    of one grid's shape."""
    rank = _ranks(nx, ny)
    dofs = _element_dofs(nx, ny)
    first, second = rank[dofs][:, _UPPER[0]], rank[dofs][:, _UPPER[1]]
    low, high = np.minimum(first, second).ravel(), np.maximum(first, second).ravel()
    size, width = len(rank), int((high - low).max(initial=0))
    flat = (width + low - high) * size + high
    for array in (rank, dofs, flat):
        array.setflags(write=False)
    return _Layout(rank, dofs, flat, width, size)


def _ranks(nx: int, ny: int) -> np.ndarray:
    """(3 nx ny,) each unknown's place in the banded matrix: the nodes numbered with the
    grid's shorter direction fastest, so that the band is about three times that
    direction's node count wide."""
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))         # node j * nx + i
    node_rank = (j * nx + i) if nx <= ny else (i * ny + j)
    return (3 * node_rank.ravel()[:, None] + np.arange(3)).ravel()


_UPPER = np.triu_indices(12)           # an element matrix's upper triangle, diagonal in
_UPPER_FLAT = _UPPER[0] * 12 + _UPPER[1]


def _banded_factor(layout: _Layout, element_values: np.ndarray, entries: tuple,
                   fixed: np.ndarray) -> np.ndarray | None:
    """The banded Cholesky factor (LAPACK's upper band storage) of the plate's stiffness:
    the elements' upper triangles (``element_values``) at their places (``layout.flat``)
    and the ``entries`` (rows, columns, values, both triangles given: the grips on the
    diagonal, the stiffeners between the nodes of an element's edge, both inside the
    elements' band), with the unknowns held at zero (``fixed``: their places) as
    identity rows and columns (their right-hand sides are zero, and so are they); None
    where the supports leave the plate free to move (not positive definite)."""
    from furncheck.statics.lapack import banded_cholesky

    rows, cols, more = entries
    upper = rows <= cols
    n, width = layout.size, layout.width
    bands = np.bincount(layout.flat, weights=element_values,
                        minlength=(width + 1) * n).reshape(width + 1, n)
    rows, cols = rows[upper], cols[upper]
    if rows.size and int((cols - rows).max()) > width:
        raise ValueError("a grip or stiffener entry outside the elements' band")
    np.add.at(bands, (width + rows - cols, cols), more[upper])      # in order, as one sum
    bands[:, fixed] = 0.0                           # their columns, to the diagonal
    bands[width, fixed] = 1.0
    offsets = np.arange(1, width + 1)
    beyond = fixed[:, None] + offsets               # their rows, right of the diagonal
    inside = beyond < n
    bands[np.broadcast_to(width - offsets, beyond.shape)[inside], beyond[inside]] = 0.0
    return banded_cholesky(bands)


def _stiffener_entries(xs: np.ndarray, ys: np.ndarray, stiffeners) -> tuple:
    """(rows, columns, values): each stiffener's Euler-Bernoulli beam elements between
    the grid nodes along its line, on the nodes' w and their slope along it (beta_x for
    a line along x, beta_y along y), each h long: E I / h^3 [[12, 6 h, -12, 6 h], [6 h,
    4 h^2, -6 h, 2 h^2], [-12, -6 h, 12, -6 h], [6 h, 2 h^2, -6 h, 4 h^2]]."""
    rows, cols, values = [], [], []
    for stiffener in stiffeners:
        nodes, s, axis = _nodes_along(xs, ys, stiffener)
        h = np.diff(s)
        ends = h > 0.0
        a, b, h = nodes[:-1][ends], nodes[1:][ends], h[ends]
        if len(h) == 0:
            continue
        one = np.ones_like(h)
        k = stiffener[2] / h[:, None, None] ** 3 * np.stack([
            np.stack([12 * one, 6 * h, -12 * one, 6 * h], axis=1),
            np.stack([6 * h, 4 * h * h, -6 * h, 2 * h * h], axis=1),
            np.stack([-12 * one, -6 * h, 12 * one, -6 * h], axis=1),
            np.stack([6 * h, 2 * h * h, -6 * h, 4 * h * h], axis=1)], axis=1)
        dofs = np.column_stack([3 * a, 3 * a + 1 + axis, 3 * b, 3 * b + 1 + axis])
        rows.append(np.repeat(dofs, 4, axis=1).ravel())
        cols.append(np.tile(dofs, (1, 4)).ravel())
        values.append(k.ravel())
    if not rows:
        return np.zeros(0, dtype=int), np.zeros(0, dtype=int), np.zeros(0)
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(values)


def _element_dofs(nx: int, ny: int) -> np.ndarray:
    """(nE, 12) each element's unknowns, corners counter-clockwise from (-, -)."""
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1))
    i, j = i.ravel(), j.ravel()
    corners = np.column_stack([j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1,
                               (j + 1) * nx + i])
    return (3 * corners[:, :, None] + np.arange(3)).reshape(-1, 12)


def _on_segment(xs: np.ndarray, ys: np.ndarray, segment) -> tuple[np.ndarray, int]:
    """The grid nodes (indices, row-major, x fastest, ascending) on a segment ((x0, y0),
    (x1, y1), grip) along x or y, and its axis (0: x)."""
    (x0, y0), (x1, y1), _ = segment
    slack = tol.NODE_MERGE        # its grid line, kept within that of it (``grid_lines``)
    if abs(y1 - y0) <= abs(x1 - x0):                # along x, at y0 = y1
        i = np.flatnonzero((xs >= x0 - slack) & (xs <= x1 + slack))
        j = np.flatnonzero(np.abs(ys - y0) <= slack)
        axis = 0
    else:
        i = np.flatnonzero(np.abs(xs - x0) <= slack)
        j = np.flatnonzero((ys >= y0 - slack) & (ys <= y1 + slack))
        axis = 1
    return (j[:, None] * len(xs) + i[None, :]).ravel(), axis


def _nodes_along(xs: np.ndarray, ys: np.ndarray, segment) -> tuple[np.ndarray, np.ndarray, int]:
    """The grid nodes on a segment (``_on_segment``), in order along it, their
    coordinates along it, and its axis (0: x)."""
    nodes, axis = _on_segment(xs, ys, segment)
    s = xs[nodes % len(xs)] if axis == 0 else ys[nodes // len(xs)]
    order = np.argsort(s)
    return nodes[order], s[order], axis


def _supported_nodes(xs: np.ndarray, ys: np.ndarray, segments) -> np.ndarray:
    """Indices of the grid nodes on the support segments (row-major, x fastest)."""
    on = np.zeros(len(xs) * len(ys), dtype=bool)
    for segment in segments:
        on[_on_segment(xs, ys, segment)[0]] = True
    return np.flatnonzero(on)


def _grips(xs: np.ndarray, ys: np.ndarray, segments) -> tuple[np.ndarray, np.ndarray]:
    """The unknowns (indices) and stiffnesses (N m / rad) of the nail rows' grip: each
    segment's grip per metre times each of its nodes' share of its length, on the node's
    turn about the segment (beta_y for a line along x, beta_x for one along y)."""
    dofs, values = [], []
    for segment in segments:
        nodes, s, axis = _nodes_along(xs, ys, segment)
        if len(nodes) == 0:
            continue
        low, high = segment[0][axis], segment[1][axis]
        bounds = np.concatenate([[low], 0.5 * (s[1:] + s[:-1]), [high]])
        dofs.append(3 * nodes + (2 if axis == 0 else 1))
        values.append(segment[2] * np.diff(bounds))
    if not dofs:
        return np.zeros(0, dtype=int), np.zeros(0)
    return np.concatenate(dofs), np.concatenate(values)


def plate_solutions(grid: PlateGrid, loads: list) -> list[tuple[np.ndarray, float]]:
    """Per (uniform, points) of ``loads``, solved at once: the plate's node deflections
    (m, along the plank's face normal; row-major, x fastest) under a ``uniform`` pressure
    (Pa) and forces spread over patches (``points``: ((x0, x1, y0, y1), N) each, shared
    by the elements by their overlap with the square: its edges are grid lines, or within
    a millimetre of one), and its largest bending stress (Pa), 6 |M| / t^2 of the largest
    principal moment at an element's centre.  A plate hung on one line (``_hinge``): its
    deflections from the tangent at the line, and the moments at the line
    (``_line_moments``: a cantilever's largest, half a cell from the nearest centre)
    among the moments.  Each load's, bit for bit, as if solved
    alone (LAPACK's pbtrs solves each column on its own; the moments are summed term by
    term, where a matrix product's blocking depends on how many columns it has)."""
    from furncheck.statics.lapack import banded_solve

    xs, ys = grid.xs, grid.ys
    pressure = np.zeros((len(grid.areas), len(loads)))
    for column, (uniform, points) in enumerate(loads):
        pressure[:, column] = uniform
        for (x0, x1, y0, y1), force in points:     # each element's share of the square
            over_x = np.clip(np.minimum(xs[1:], x1) - np.maximum(xs[:-1], x0), 0.0, None)
            over_y = np.clip(np.minimum(ys[1:], y1) - np.maximum(ys[:-1], y0), 0.0, None)
            overlap = np.outer(over_y, over_x).ravel()
            pressure[:, column] += force / ((x1 - x0) * (y1 - y0)) * overlap / grid.areas
    nx, ny = len(xs), len(ys)
    share = (pressure * (grid.areas / 4.0)[:, None]).reshape(ny - 1, nx - 1, len(loads))
    on_nodes = np.zeros((ny, nx, len(loads)))     # each element's share to its corners' w
    on_nodes[:-1, :-1] += share                     # counter-clockwise from (-, -)
    on_nodes[:-1, 1:] += share
    on_nodes[1:, 1:] += share
    on_nodes[1:, :-1] += share
    f = np.zeros((3 * nx * ny, len(loads)))
    f[0::3] = on_nodes.reshape(nx * ny, len(loads))
    free = ~grid.fixed
    ranked = np.zeros((len(grid.rank), len(loads)))
    ranked[grid.rank[free]] = f[free]
    u = np.zeros_like(f)
    u[free] = banded_solve(grid.factor, ranked)[grid.rank[free]]
    on_elements = u[grid.dofs]                      # (nE, 12, k)
    m = np.zeros((len(grid.areas), 3, len(loads)))  # (nE, 3, k), term by term: each
    for term in range(12):                          # load's bit for bit as if alone
        m += grid.moments[:, :, term, None] * on_elements[:, None, term, :]
    principal = np.abs(0.5 * (m[:, 0] + m[:, 1])) + np.hypot(0.5 * (m[:, 0] - m[:, 1]),
                                                             m[:, 2])
    largest = principal.max(axis=0, initial=0.0)
    w = u[0::3]
    if grid.hinge is not None:          # from the tangent at its line; its moments there
        tangent, distance, rows, cols, values, lengths = grid.hinge
        w = w - u[tangent] * distance[:, None]
        for column in range(len(loads)):
            at_line = np.bincount(rows, weights=values * u[cols, column],
                                  minlength=len(lengths)) / lengths
            largest[column] = max(largest[column], float(np.abs(at_line).max()))
    stress = 6.0 * largest / grid.thickness ** 2
    return [(w[:, column], float(stress[column])) for column in range(len(loads))]


def sag_span(grid: PlateGrid, w: np.ndarray) -> tuple[float, float]:
    """(m, m): the largest deflection between the supports (at the nodes within the
    supported nodes' bounding box: an overhang beyond them is its beam's, measured from
    the tangent at its support, contract 3a; at every node of a plate hung on one line,
    whose ``w`` is measured from the tangent there, ``plate_solutions``), and its span
    (``_span_at``: for a plate hung on one line, twice the distance to its nearest node
    of the line, straight across it where the line reaches, else to the line's end)."""
    between = np.where(grid.between, np.abs(w), -1.0)
    k = int(np.argmax(between))
    return float(max(between[k], 0.0)), _span_at(grid, k)


def _span_at(grid: PlateGrid, k: int) -> float:
    """m: the span at node ``k``, as contract 3a has a beam's (between its outermost
    supports), along the plank's axes through it: the shorter of the distances between
    the outermost supported nodes met on either side along x and along y (a shelf
    between its sides: the distance between them; a top held all round: its shorter
    side's); where no axis meets one on both sides, twice the distance to the nearest
    one met (an edge held on one side, as a cantilever); where none is met, twice the
    distance to the nearest supported node."""
    X, Y = grid.nodes
    sx, sy = X[grid.supported], Y[grid.supported]
    x, y = X[k], Y[k]
    spans, reaches = [], []
    for along, across, at, level in ((sx, sy, x, y), (sy, sx, y, x)):
        line = along[np.abs(across - level) <= tol.NODE_MERGE_ROUNDOFF]
        below, above = line[line < at], line[line > at]
        if len(below) and len(above):
            spans.append(float(above.max() - below.min()))
        reaches += [at - float(below.max())] if len(below) else []
        reaches += [float(above.min()) - at] if len(above) else []
    if spans:
        return min(spans)
    if reaches:
        return 2.0 * min(reaches)
    return float(2.0 * np.hypot(sx - x, sy - y).min())
