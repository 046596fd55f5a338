"""Face tables of planks and the touching region of a narrow face on a broad face.

Faces are handled as oriented rectangles; the touching region is the edge face's
projection clipped to the face plank's face (in its local x-y), measured by its area,
centroid, extent along the joint line and gap (its least height over the face).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Plank
from furncheck.geometry.boxes import overlapping_pairs
from furncheck.geometry.model import _COS_MAX_TILT


class _Touch(NamedTuple):
    """A narrow face of ``edge`` found on a broad face of ``face`` (before nail counting;
    a named tuple: thousands are made per batch of edits, a frozen dataclass costs more)."""

    face: Plank
    edge: Plank
    point: np.ndarray
    length: float
    frame: np.ndarray
    gap: float          # m, least height of the touching region over the face (< 0: inside)
    alignment: float    # -(edge face normal . face normal), 1 when flush
    area: float         # m^2 of the touching region
    edge_face: tuple[int, int] = (0, 1)
    face_side: int = 1


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class _Faces:
    """Face tables of the planks given (n planks: a design's, or those some pairs name).

    narrow_normal (n, 4, 3), narrow_corners (n, 4, 4, 3), narrow_long (n, 4, 3) unit joint
    line of each narrow face; broad_normal (n, 2, 3), broad_offset (n, 2) = n . face centre.
    Narrow faces in the order +x, -x, +y, -y of the plank's local axes; broad faces +z, -z.
    centers (n, 3), rotations (n, 3, 3) and halves (n, 3): the planks' own.
    """

    narrow_normal: np.ndarray
    narrow_corners: np.ndarray
    narrow_long: np.ndarray
    broad_normal: np.ndarray
    broad_offset: np.ndarray
    centers: np.ndarray
    rotations: np.ndarray
    halves: np.ndarray


def _face_tables(planks: tuple[Plank, ...]) -> _Faces:
    rot = np.stack([p.rotation_matrix for p in planks])          # (n, 3, 3) columns = axes
    half = np.stack([p.half_extents for p in planks])            # (n, 3)
    centers = np.stack([p.center_array for p in planks])         # (n, 3)
    axes, signs, longs = [0, 0, 1, 1], np.array([1.0, -1.0, 1.0, -1.0]), [1, 1, 0, 0]
    normal = np.transpose(rot[:, :, axes], (0, 2, 1)) * signs[None, :, None]
    face_center = centers[:, None, :] + normal * half[:, axes][:, :, None]
    long_unit = np.transpose(rot[:, :, longs], (0, 2, 1))
    u = long_unit * half[:, longs][:, :, None]                   # (n, 4, 3)
    w = (rot[:, :, 2] * half[:, 2:3])[:, None, :]                # (n, 1, 3)
    corners = face_center[:, :, None, :] + np.stack([u + w, -u + w, -u - w, u - w], axis=2)
    broad_normal = rot[:, :, 2][:, None, :] * np.array([1.0, -1.0])[None, :, None]
    broad_center = centers[:, None, :] + broad_normal * half[:, 2][:, None, None]
    broad_offset = np.einsum("nga,nga->ng", broad_normal, broad_center)
    return _Faces(normal, corners, long_unit, broad_normal, broad_offset, centers, rot, half)


def _best_touches(planks: tuple[Plank, ...], pairs: np.ndarray, slack: float, keep_deep: bool,
                  faces: _Faces | None = None, one_way: bool = False,
                  bearing: float | None = None) -> dict:
    """For each plank pair (i, j) (indices into ``planks``, whose face tables ``faces`` are
    when given; else made for the pairs' planks alone), the best narrow-face-on-broad-face
    contact either way round (``one_way``: only i's narrow faces on j's broad faces), by
    ``_rank``: contacts within the slack first, then the least sunk, then the flushest,
    then the largest.  ``keep_deep`` keeps faces sunk deeper than the slack (to report
    interpenetration).  ``bearing``: a region narrower across the joint line than this
    share of the edge plank's thickness is no contact (None:
    ``tolerances.MIN_BEARING_SHARE``; 0 keeps every one).  A contact's gap is that of
    the part of the narrow face over the broad face (``_region_gaps``), not of its nearest
    corner anywhere: a long edge turned away from a narrow face touches its plane beyond
    it, and counted as touching, but only where the planks' bounding boxes met (in some
    turns of the design; ``tests/test_geometry.py``)."""
    if len(pairs) == 0:
        return {}
    keyed = pairs
    if faces is None:           # the tables of the pairs' planks alone (``_pairs_planks``)
        planks, pairs = _pairs_planks(planks, pairs)
        faces = _face_tables(planks)
    ordered = pairs if one_way else np.vstack([pairs, pairs[:, ::-1]])   # (edge, face)
    edge, face = ordered[:, 0], ordered[:, 1]
    broad = faces.broad_normal[face]                              # (P, 2, 3)
    offset = faces.broad_offset[face]
    alignment = -_dot(faces.narrow_normal[edge][:, :, None, :], broad[:, None, :, :])
    heights = _dot(faces.narrow_corners[edge][:, :, None, :, :], broad[:, None, :, None, :]) \
        - offset[:, None, :, None]                                # (P, 4, 2, 4 corners)
    gap = _least(heights)                                         # (P, 4, 2)
    outside = _dot(faces.centers[edge][:, None, :], broad) - offset >= 0.0
    candidates = (alignment >= _COS_MAX_TILT) & (gap <= slack) & outside[:, None, :]
    if not keep_deep:           # sunk deeper whole: no part of it lies within the slack
        candidates &= _most(heights) >= -slack
    best: dict[tuple[int, int], _Touch] = {}
    n_pairs = len(pairs)
    chosen = np.argwhere(candidates)
    p, f, g = chosen[:, 0], chosen[:, 1], chosen[:, 2]
    touches = _touch_regions(planks, faces, edge[p], face[p], f, g, gap[p, f, g],
                             alignment[p, f, g],
                             tol.MIN_BEARING_SHARE if bearing is None else bearing)
    keys = [(i, j) for i, j in keyed.tolist()]
    for p_k, touch in zip(chosen[:, 0].tolist(), touches):
        if touch is None or touch.gap > slack or (not keep_deep and touch.gap < -slack):
            continue                        # the region's own gap (``_region_gaps``)
        key = keys[p_k % n_pairs]
        current = best.get(key)
        if current is None or _rank(touch, slack) > _rank(current, slack):
            best[key] = touch
    return best


def _pairs_planks(planks: tuple[Plank, ...], pairs: np.ndarray) -> tuple[tuple, np.ndarray]:
    """The planks that ``pairs`` name, in index order, and the pairs as indices into them:
    a design's face tables built for a few pairs among thousands of planks cost a pass
    over all of them each time (a message per plank joined to nothing, each measuring
    its few neighbours, made a stack of 80,000 loose boards quadratic)."""
    named = np.sort(pairs.ravel())
    used = named[np.concatenate([[True], named[1:] != named[:-1]])]
    if len(used) == len(planks):
        return planks, pairs
    return tuple(planks[i] for i in used.tolist()), np.searchsorted(used, pairs)


def _rank(touch: _Touch, slack: float) -> tuple:
    """How good a contact is, best highest (``_best_touches``): within the slack first,
    then, of contacts sunk deeper, the shallowest (a shelf turned half a degree sinks one
    end corner 1.1 mm into its side, while the side's end face lies 450 mm "inside" the
    shelf's lower face, whose plane runs through the side's centre: the depth, not the
    flusher faces, tells the contact), then the flushest, then the largest."""
    return (touch.gap >= -slack, min(touch.gap + slack, 0.0), round(touch.alignment, 9),
            touch.area)


def _touch_regions(planks, faces: _Faces, edge: np.ndarray, face: np.ndarray,
                   f: np.ndarray, g: np.ndarray, gap: np.ndarray,
                   alignment: np.ndarray, bearing: float = 0.0) -> list[_Touch | None]:
    """For candidate contacts c (edge plank edge[c]'s narrow face f[c] on face plank
    face[c]'s broad face g[c], indices into ``planks`` and ``faces``; ``gap``: the least
    height of the narrow face's corners over the broad face's plane): clip the narrow
    face's projection to the broad face (in the face plank's local x-y) and measure the
    touching region, its gap the least height over the region (``_region_gaps``); None
    where it is empty, or narrower across the joint line (area / length) than ``bearing``
    times the edge plank's thickness."""
    if len(edge) == 0:
        return []
    rot_f, half_f = faces.rotations[face], faces.halves[face]            # (C, 3, 3), (C, 3)
    rot_e, half_e = faces.rotations[edge], faces.halves[edge]
    normal = faces.broad_normal[face, g]                                  # (C, 3)
    face_center = faces.centers[face] + half_f[:, 2:3] * normal
    corners = faces.narrow_corners[edge, f]                               # (C, 4, 3)
    local = np.einsum("cka,cab->ckb", corners - face_center[:, None, :], rot_f[:, :, :2])
    joint_dir = faces.narrow_long[edge, f]
    along = joint_dir - np.einsum("ca,ca->c", joint_dir, normal)[:, None] * normal
    along_2d = np.einsum("ca,cab->cb", along, rot_f[:, :, :2])
    along_2d /= np.linalg.norm(along_2d, axis=1, keepdims=True)
    face_area = 4.0 * half_e[:, 2] * half_e[:, :2].max(axis=1)
    least = tol.MIN_JOINT_AREA_FRACTION * face_area
    slope = _height_slopes(local, _dot(corners - face_center[:, None, :], normal[:, None, :]))
    if len(edge) >= CLIP_AT_ONCE:
        xs, ys, count = _clipped_to_rectangles(local[:, :, 0], local[:, :, 1], half_f[:, 0],
                                               half_f[:, 1])
        area, cx, cy, extent = _polygon_measures(xs, ys, count, along_2d)
        found = (count >= 3) & (area > least)
        gaps = _region_gaps(xs, ys, count, slope, local, half_f, gap)
        regions = [(a, x, y, e, h) if ok else None for a, x, y, e, h, ok in
                   zip(area.tolist(), cx.tolist(), cy.tolist(), extent.tolist(),
                       gaps.tolist(), found.tolist())]
    else:
        regions = [_clipped_region(quad, hx, hy, ax, ay, least_c, slope_c, gap_c)
                   for quad, (hx, hy), (ax, ay), least_c, slope_c, gap_c in zip(
                       local.tolist(), half_f[:, :2].tolist(), along_2d.tolist(),
                       least.tolist(), slope.tolist(), gap.tolist())]
    thickness_normal = rot_e[:, :, 2]
    x_axis = thickness_normal - np.einsum("ca,ca->c", thickness_normal, normal)[:, None] * normal
    x_axis /= np.linalg.norm(x_axis, axis=1, keepdims=True)
    frames = np.stack([x_axis, np.cross(normal, x_axis), normal], axis=2)  # columns x, y, n
    centroids = np.array([(0.0, 0.0) if region is None else region[1:3] for region in regions])
    points = face_center + rot_f[:, :, 0] * centroids[:, :1] + rot_f[:, :, 1] * centroids[:, 1:]
    touches: list[_Touch | None] = []
    for c, (region, face_c, edge_c, f_c, g_c, alignment_c) in enumerate(zip(
            regions, face.tolist(), edge.tolist(), f.tolist(), g.tolist(),
            alignment.tolist())):
        touch = None if region is None else _Touch(
            planks[face_c], planks[edge_c], points[c], region[3], frames[c], region[4],
            alignment_c, region[0], edge_face=(f_c // 2, 1 - 2 * (f_c % 2)),
            face_side=1 - 2 * g_c)
        touches.append(None if touch is None or (bearing > 0.0 and not _bears(touch, bearing))
                       else touch)          # a sliver: no room for nails
    return touches


def _height_slopes(local: np.ndarray, heights: np.ndarray) -> np.ndarray:
    """(C, 3): the height over the broad face's plane of a point of each narrow face,
    h0 + a x + b y of its projection (x, y) (the face plank's local x-y): affine, since
    the narrow face is flat and, tilted by less than JOINT_MAX_TILT_DEG, projects one to
    one.  From its corners' projections ``local`` (C, 4, >= 2) and ``heights`` (C, 4): the
    slopes (a, b) along its two sides (corner 0 to 1, 1 to 2), h0 through corner 1; a face
    seen edge-on (no such filter before ``follow_many``'s re-measuring) is taken as flat
    at its corners' least height."""
    u = local[:, 0, :2] - local[:, 1, :2]
    w = local[:, 1, :2] - local[:, 2, :2]
    rise_u, rise_w = heights[:, 0] - heights[:, 1], heights[:, 1] - heights[:, 2]
    det = u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]
    safe = np.where(det != 0.0, det, 1.0)
    a = np.where(det != 0.0, (rise_u * w[:, 1] - rise_w * u[:, 1]) / safe, 0.0)
    b = np.where(det != 0.0, (u[:, 0] * rise_w - w[:, 0] * rise_u) / safe, 0.0)
    h0 = np.where(det != 0.0, heights[:, 1] - a * local[:, 1, 0] - b * local[:, 1, 1],
                  heights.min(axis=1))         # edge-on (never past the tilt filter): flat
    return np.column_stack([h0, a, b])


def _region_gaps(xs: np.ndarray, ys: np.ndarray, count: np.ndarray, slope: np.ndarray,
                 local: np.ndarray, half: np.ndarray, gap: np.ndarray) -> np.ndarray:
    """(C,) m: the least height over the broad face of each clipped touching region
    (vertices ``xs``, ``ys`` (C, 8), ``count`` used; heights by ``slope``,
    ``_height_slopes``); ``gap``, its corners' least, where the narrow face lies on the
    broad face whole (nothing was clipped): the same number as ``_clipped_region``'s."""
    heights = slope[:, :1] + slope[:, 1:2] * xs + slope[:, 2:3] * ys
    heights = np.where(np.arange(xs.shape[1])[None, :] < count[:, None], heights, np.inf)
    inside = np.all((np.abs(local[:, :, 0]) <= half[:, :1])
                    & (np.abs(local[:, :, 1]) <= half[:, 1:2]), axis=1)
    return np.where(inside, gap, heights.min(axis=1))


def _bearing(touch: _Touch) -> float:
    """m: how wide a touching region is across its joint line (its area over its length)."""
    return touch.area / max(touch.length, tol.BEARING_EPS)


def _bears(touch: _Touch, share: float | None = None) -> bool:
    """Whether a touching region is wide enough across its joint line for nails
    (``_bearing``): at least ``share`` (None: ``tolerances.MIN_BEARING_SHARE``) of the
    edge plank's thickness, to ``tolerances.BEARING_EPS``."""
    share = tol.MIN_BEARING_SHARE if share is None else share
    return touch.area >= (share * touch.edge.thickness - tol.BEARING_EPS) * touch.length


CLIP_AT_ONCE = 128
"""From this many candidate faces on, their touching regions are clipped as arrays
(``_clipped_to_rectangles``); fewer are clipped one by one in plain floats, which is faster
for them (the two give the same numbers to the last bit)."""


def _clipped_region(quad: list, half_x: float, half_y: float, along_x: float,
                    along_y: float, least: float, slope: list, gap: float) -> tuple | None:
    """(area, centroid x, y, extent along (along_x, along_y), least height) of the quad
    [(x, y), ...] clipped to |x| <= half_x, |y| <= half_y, or None if less than ``least``
    is left.  Its least height: ``gap`` (its corners') where nothing was clipped, else the
    least of h0 + a x + b y (``slope``) over the clipped polygon's vertices."""
    polygon = _clip_to_rectangle(quad, half_x, half_y)
    if len(polygon) < 3:
        return None
    area, cx, cy = _polygon_area_centroid(polygon)
    extent = [x * along_x + y * along_y for x, y in polygon]
    if polygon is not quad:
        h0, a, b = slope
        gap = min(h0 + a * x + b * y for x, y in polygon)
    return (area, cx, cy, max(extent) - min(extent), gap) if area > least else None


def _clip_to_rectangle(polygon: list, half_x: float, half_y: float) -> list:
    """Sutherland-Hodgman clip of a convex polygon [(x, y), ...] to |x| <= half_x,
    |y| <= half_y (plain floats: the polygons are tiny, numpy would only add overhead)."""
    if all(-half_x <= x <= half_x and -half_y <= y <= half_y for x, y in polygon):
        return polygon          # inside already (most end faces lie within their face)
    points = polygon
    for axis, sign, limit in ((0, 1.0, half_x), (0, -1.0, half_x), (1, 1.0, half_y),
                              (1, -1.0, half_y)):
        kept = []
        previous = points[-1]
        prev_in = sign * previous[axis] <= limit
        for current in points:
            cur_in = sign * current[axis] <= limit
            if cur_in != prev_in:
                t = (sign * limit - previous[axis]) / (current[axis] - previous[axis])
                kept.append((previous[0] + t * (current[0] - previous[0]),
                             previous[1] + t * (current[1] - previous[1])))
            if cur_in:
                kept.append(current)
            previous, prev_in = current, cur_in
        points = kept
        if not points:
            break
    return points


def _polygon_area_centroid(polygon: list) -> tuple[float, float, float]:
    """Area (m^2) and centroid x, y of a simple polygon [(x, y), ...] (shoelace formula)."""
    twice_area = cx = cy = 0.0
    x0, y0 = polygon[-1]
    for x1, y1 in polygon:
        cross = x0 * y1 - x1 * y0
        twice_area += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
        x0, y0 = x1, y1
    if abs(twice_area) < 1e-30:
        xs, ys = zip(*polygon)
        return 0.0, sum(xs) / len(xs), sum(ys) / len(ys)
    return abs(0.5 * twice_area), cx / (3.0 * twice_area), cy / (3.0 * twice_area)


def _clipped_to_rectangles(xs: np.ndarray, ys: np.ndarray, half_x: np.ndarray,
                           half_y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Sutherland-Hodgman clip of C convex quadrilaterals (vertices ``xs``, ``ys``, (C, 4))
    to the rectangles |x| <= half_x, |y| <= half_y (C,), all at once: the clipped
    polygons' vertices (C, 8) in order, and how many each has (C,; fewer than 3 when
    nothing is left).  Each half-plane adds at most one vertex to a convex polygon;
    vertices past a polygon's count are unused.  A half-plane is applied only to the
    polygons with a vertex outside it (it leaves the others as they are)."""
    count = np.full(len(xs), xs.shape[1])
    xs = np.pad(xs, ((0, 0), (0, 8 - xs.shape[1])))
    ys = np.pad(ys, ((0, 0), (0, 8 - ys.shape[1])))
    slots = np.arange(8)
    for axis, sign, limit in ((0, 1.0, half_x), (0, -1.0, half_x), (1, 1.0, half_y),
                              (1, -1.0, half_y)):
        along = xs if axis == 0 else ys
        outside = (sign * along > limit[:, None]) & (slots < count[:, None])
        clipped = np.flatnonzero(outside.any(axis=1))
        if len(clipped):
            xs[clipped], ys[clipped], count[clipped] = _clipped_by(
                xs[clipped], ys[clipped], count[clipped], axis, sign, limit[clipped])
    return xs, ys, count


def _clipped_by(xs: np.ndarray, ys: np.ndarray, count: np.ndarray, axis: int, sign: float,
                limit: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One Sutherland-Hodgman step of ``_clipped_to_rectangles``: the polygons clipped to
    sign * (x or y, by ``axis``) <= limit, vertex by vertex as the scalar algorithm goes
    (the same arithmetic, so the same numbers)."""
    rows = np.arange(len(xs))
    along = xs if axis == 0 else ys
    previous = np.maximum(count - 1, 0)
    px, py, pa = xs[rows, previous], ys[rows, previous], along[rows, previous]
    prev_in = sign * pa <= limit
    kept_x, kept_y = np.zeros_like(xs), np.zeros_like(ys)
    kept = np.zeros(len(xs), dtype=int)
    with np.errstate(divide="ignore", invalid="ignore"):
        for j in range(int(count.max(initial=0))):
            active = j < count
            cx, cy, ca = xs[:, j], ys[:, j], along[:, j]
            cur_in = sign * ca <= limit
            crossing = active & (cur_in != prev_in)
            t = (sign * limit - pa) / (ca - pa)
            where = rows[crossing]
            kept_x[where, kept[crossing]] = (px + t * (cx - px))[crossing]
            kept_y[where, kept[crossing]] = (py + t * (cy - py))[crossing]
            kept += crossing
            inside = active & cur_in
            where = rows[inside]
            kept_x[where, kept[inside]] = cx[inside]
            kept_y[where, kept[inside]] = cy[inside]
            kept += inside
            px, py, pa, prev_in = cx, cy, ca, cur_in
    return kept_x, kept_y, kept


def _polygon_measures(xs: np.ndarray, ys: np.ndarray, count: np.ndarray,
                      along: np.ndarray) -> tuple[np.ndarray, ...]:
    """Area (m^2), centroid x, y (shoelace formula, summed vertex by vertex) and extent
    along the unit direction ``along`` (C, 2) of C simple polygons (``xs``, ``ys``: (C, 8)
    vertices, the first ``count`` used); area 0 for a degenerate one."""
    rows = np.arange(len(xs))
    last = np.maximum(count - 1, 0)
    x0, y0 = xs[rows, last], ys[rows, last]
    twice = np.zeros(len(xs))
    sum_x, sum_y = np.zeros(len(xs)), np.zeros(len(xs))
    low, high = np.full(len(xs), np.inf), np.full(len(xs), -np.inf)
    for j in range(int(count.max(initial=0))):
        active = j < count
        x1, y1 = xs[:, j], ys[:, j]
        cross = np.where(active, x0 * y1 - x1 * y0, 0.0)
        twice = twice + cross
        sum_x = sum_x + (x0 + x1) * cross
        sum_y = sum_y + (y0 + y1) * cross
        projected = x1 * along[:, 0] + y1 * along[:, 1]
        low = np.where(active, np.minimum(low, projected), low)
        high = np.where(active, np.maximum(high, projected), high)
        x0, y0 = np.where(active, x1, x0), np.where(active, y1, y0)
    degenerate = np.abs(twice) < 1e-30
    safe = np.where(degenerate, 1.0, twice)
    return (np.where(degenerate, 0.0, np.abs(0.5 * twice)), sum_x / (3.0 * safe),
            sum_y / (3.0 * safe), high - low)


def _bounding_boxes(planks: tuple[Plank, ...]) -> tuple[np.ndarray, np.ndarray]:
    """World axis-aligned boxes (n, 3) lower and upper corners."""
    corners = np.stack([p.corners for p in planks])
    return corners.min(axis=1), corners.max(axis=1)


def _tables(planks: tuple[Plank, ...]) -> tuple[_Faces, tuple[np.ndarray, np.ndarray]]:
    """Face tables and bounding boxes of ``planks``."""
    return _face_tables(planks), _bounding_boxes(planks)


def _design_tables(planks: tuple[Plank, ...]) -> tuple[_Faces, tuple[np.ndarray, np.ndarray]]:
    """``_tables`` of a design's own planks, kept for the design's many edits (read only:
    the batches of edits stack them, ``_stacked_tables``, the margins index them)."""
    try:
        return _kept_tables(planks)
    except TypeError:           # a plank built with unhashable values: tabled afresh
        return _tables(planks)


@functools.lru_cache(maxsize=8)
def _kept_tables(planks: tuple[Plank, ...]) -> tuple[_Faces, tuple[np.ndarray, np.ndarray]]:
    faces, boxes = _tables(planks)
    for array in (*(getattr(faces, name) for name in _Faces.__dataclass_fields__), *boxes):
        array.flags.writeable = False
    return faces, boxes


def _stacked_tables(planks: tuple[Plank, ...],
                    tables: tuple[_Faces, tuple[np.ndarray, np.ndarray]],
                    changes: list[tuple[list[int], tuple[Plank, ...]]]) -> tuple:
    """The tables of many edits of one design in one: the design's ``planks`` (their
    ``tables``, from ``_tables``), then per edit of ``changes`` (the plank numbers it
    changes, its planks) its changed planks.  Returns the stacked planks, face tables and
    boxes, and per edit the row of each of its planks."""
    count = len(planks)
    appended: list[Plank] = []
    index = []
    for changed, edited in changes:
        rows = np.arange(count)
        rows[changed] = count + len(appended) + np.arange(len(changed))
        appended.extend(edited[i] for i in changed)
        index.append(rows)
    faces, (lo, hi) = tables
    if appended:
        new_faces, (new_lo, new_hi) = _tables(tuple(appended))
        faces = _Faces(*(np.concatenate([getattr(faces, name), getattr(new_faces, name)])
                         for name in _Faces.__dataclass_fields__))
        lo, hi = np.concatenate([lo, new_lo]), np.concatenate([hi, new_hi])
    return planks + tuple(appended), faces, (lo, hi), index


def _overlapping(lo: np.ndarray, hi: np.ndarray, slack: float) -> np.ndarray:
    """Pairs (i < j) of boxes that overlap by more than the slack along every axis."""
    return overlapping_pairs(lo, hi, slack)


def _box_depths(rot: np.ndarray, half: np.ndarray, centre: np.ndarray,
                pairs: np.ndarray) -> np.ndarray:
    """Per pair (a, b) of planks (rotations, half extents, centres): how deep their boxes
    overlap, the smallest overlap of their projections on the 15 separating axes."""
    usable, radius, distance = _separating_axes(rot, half, centre, pairs)
    return np.where(usable, radius - np.abs(distance), np.inf).min(axis=1)


def _separating_axes(rot: np.ndarray, half: np.ndarray, centre: np.ndarray,
                     pairs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The 15 candidate separating axes of each pair (a, b) of oriented boxes (rotations,
    half extents, centres): the three axes of each box and the nine cross products of
    one's with the other's.  Per pair and axis (P, 15): whether the axis is usable (not
    a cross product of parallel axes), the sum of the two boxes' projected half extents
    along it, and the distance of b's centre from a's along it (signed)."""
    a, b = pairs[:, 0], pairs[:, 1]
    ra, rb = np.transpose(rot[a], (0, 2, 1)), np.transpose(rot[b], (0, 2, 1))  # rows = axes
    u, v = ra[:, :, None, :], rb[:, None, :, :]
    crosses = np.stack([u[..., 1] * v[..., 2] - u[..., 2] * v[..., 1],
                        u[..., 2] * v[..., 0] - u[..., 0] * v[..., 2],
                        u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]], axis=-1)
    axes = np.concatenate([ra, rb, crosses.reshape(-1, 9, 3)], axis=1)          # (P, 15, 3)
    norms = np.sqrt(_dot(axes, axes))
    usable = norms > 1e-9
    axes = axes / np.where(usable, norms, 1.0)[:, :, None]
    radius = 0.0
    for box, rows in ((a, ra), (b, rb)):
        extents = half[box]
        for i in range(3):
            radius = radius + np.abs(_dot(axes, rows[:, None, i])) * extents[:, None, i]
    distance = _dot(axes, (centre[b] - centre[a])[:, None, :])
    return usable, radius, distance


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Dot products along the last axis (3 entries), broadcast: component by component,
    since numpy's reductions and matmuls over axes of a few entries cost many times the
    arithmetic."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def _least(values: np.ndarray) -> np.ndarray:
    """Smallest of the 4 entries along the last axis (like ``_dot``, without a reduction)."""
    return np.minimum(np.minimum(values[..., 0], values[..., 1]),
                      np.minimum(values[..., 2], values[..., 3]))


def _most(values: np.ndarray) -> np.ndarray:
    """Largest of the 4 entries along the last axis."""
    return np.maximum(np.maximum(values[..., 0], values[..., 1]),
                      np.maximum(values[..., 2], values[..., 3]))
