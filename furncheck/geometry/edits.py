"""Whether edits of a design keep its joints and contacts, many at a time.

``interpenetrations`` (planks cutting into each other), ``EditedTables`` (the geometry and
the cuts of many edits of one design in one vectorized pass) and ``EditMargins`` /
``edit_margins_many`` (continuous margins of those criteria, to predict where an edit
stops keeping them).
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.geometry.analysis import (
    _boxes_meet,
    _completed,
    _detected_joints,
    _joint_from_touch,
    _pairs_to_detect,
    _unchanged_joints,
    _unchanged_planks,
    analyze,
    interpenetrations,
    nail_count,
)
from furncheck.geometry.faces import (
    _bears,
    _best_touches,
    _box_depths,
    _clipped_to_rectangles,
    _design_tables,
    _dot,
    _Faces,
    _height_slopes,
    _least,
    _most,
    _overlapping,
    _region_gaps,
    _separating_axes,
    _stacked_tables,
)
from furncheck.geometry.model import (
    _COS_MAX_TILT,
    _GEOMETRY_EPS,
    Contact,
    Geometry,
    anchor_contacts,
    corner_contacts,
)
from furncheck.geometry.near import missed_ground, near_band


class EditedTables:
    """The face tables and boxes of many edits of one design at once: the design's own
    rows, then the rows of the planks that each edit changes (its ``index`` maps the
    edit's plank numbers to rows).  Edits that do not keep the design's planks, material
    and tolerance (``_unchanged_planks``) have no rows (``same`` None)."""

    def __init__(self, design: Design, geometry: Geometry, edits: list[Design]):
        self.design, self.geometry, self.edits = design, geometry, edits
        self.same = [_unchanged_planks(edited, (design, geometry)) for edited in edits]
        changes = [([] if same is None else
                    [i for i, plank in enumerate(edited.planks) if plank.id not in same],
                    edited.planks) for edited, same in zip(edits, self.same)]
        self.changed = [changed for changed, _ in changes]
        self.planks, self.faces, (self.lo, self.hi), self.index = _stacked_tables(
            design.planks, _design_tables(design.planks), changes)
        self.kept = [False] * len(edits)

    def geometries(self) -> list[Geometry]:
        """``analyze(edited, (design, geometry))`` of every edit, the joints of all edits'
        changed planks detected together.  ``kept[k]`` tells whether edit k was found to
        keep every joint (the same faces) and ground contact (the same corners) of the
        design (``_KeptStructure``): its geometry is the design's with those joints and
        contacts measured again, and it has no problem as an edit."""
        design, geometry = self.design, self.geometry
        slack = design.tolerance + _GEOMETRY_EPS
        found: list = [None] * len(self.edits)
        structure = _KeptStructure(design, geometry)
        detect = []
        for k, (edited, same, index) in enumerate(zip(self.edits, self.same, self.index)):
            if same is None or edited.joints is not None:
                found[k] = analyze(edited, (design, geometry))
                continue
            detect.append((k, _fresh_pairs(self.changed[k], self.lo[index], self.hi[index],
                                           slack)))
        rows = [self.index[k][fresh] for k, fresh in detect]
        best = _best_touches(self.planks, np.concatenate(rows) if rows else
                             np.zeros((0, 2), dtype=int), slack, False, self.faces)
        missing = self._near_misses([k for k, _ in detect], structure)
        for k, fresh in detect:
            edited, index, same = self.edits[k], self.index[k], self.same[k]
            fresh = fresh.tolist()
            mine = {(i, j): best[key] for i, j in fresh
                    if (key := (int(index[i]), int(index[j]))) in best}
            kept = structure.of(edited, fresh, mine, same)
            if kept is not None and k in missing:
                kept = None                     # it keeps the joints but misses one narrowly
            if kept is not None:
                found[k], self.kept[k] = kept, True
                continue
            known = _unchanged_joints(edited, (design, geometry), same)
            pairs, detected = _pairs_to_detect(edited, self.lo[index], self.hi[index], known)
            joints = _detected_joints(edited, pairs, detected, known, mine)
            found[k] = _completed(edited, joints, [], geometry, same)
        return found

    def _near_misses(self, which: list[int], structure: _KeptStructure) -> set[int]:
        """Of the edits numbered ``which``, those whose changed planks miss a joint or a
        ground contact narrowly (``geometry.near``) if they keep the design's structure
        otherwise: their end faces measured against every face within the near-miss band,
        all edits at once.  (Such an edit is analyzed in full, which reports them.)"""
        slack, band = near_band(self.design)
        if not structure.usable or not which:
            return set()
        band = max(band, slack)     # (no band: slivers within the tolerance all the same)
        fresh = {k: _fresh_pairs(self.changed[k], self.lo[self.index[k]],
                                 self.hi[self.index[k]], band) for k in which}
        rows = [self.index[k][fresh[k]] for k in which]
        best = _best_touches(self.planks, np.concatenate(rows), band, False, self.faces,
                             bearing=0.0)
        missing = set()
        for k in which:
            index = self.index[k]
            for i, j in fresh[k].tolist():
                touch = best.get((int(index[i]), int(index[j])))
                if touch is not None and (abs(touch.gap) > slack or not _bears(touch)) and \
                        (i, j) not in structure.joint_of:
                    missing.add(k)
                    break
            else:
                if missed_ground(self.edits[k], self.geometry.contacts,
                                 self.geometry.components, self.geometry.grounded,
                                 only=self.changed[k]):
                    missing.add(k)
        return missing

    def cuts(self, which: list[int]) -> list[list[tuple[str, str, float]]]:
        """``interpenetrations`` of the edits numbered ``which``, their depths at once
        (an edit without rows on its own)."""
        found = {k: interpenetrations(self.edits[k]) for k in which if self.same[k] is None}
        tabled = [k for k in which if k not in found]
        slack = self.design.tolerance + _GEOMETRY_EPS
        pairs = [_overlapping(self.lo[self.index[k]], self.hi[self.index[k]], slack)
                 for k in tabled]
        rows = [self.index[k][mine] for k, mine in zip(tabled, pairs)]
        depth = _box_depths(self.faces.rotations, self.faces.halves, self.faces.centers,
                            np.concatenate(rows)) if rows else np.zeros(0)
        start = 0
        for k, mine in zip(tabled, pairs):
            planks = self.edits[k].planks
            found[k] = [(planks[i].id, planks[j].id, float(d)) for (i, j), d in
                        zip(mine, depth[start:start + len(mine)]) if d > slack]
            start += len(mine)
        return [found[k] for k in which]


def _fresh_pairs(changed: list[int], lo: np.ndarray, hi: np.ndarray,
                 slack: float) -> np.ndarray:
    """The plank pairs (i < j, in order) with a plank of ``changed`` whose boxes (``lo``,
    ``hi``) meet within the slack: the pairs ``analysis._pairs_to_detect`` marks fresh,
    found from the changed planks' rows alone."""
    if not changed:
        return np.zeros((0, 2), dtype=int)
    rows = np.array(changed)
    meet = _boxes_meet(lo[rows], hi[rows], lo, hi, slack)
    meet[np.arange(len(rows)), rows] = False
    mine, other = np.nonzero(meet)
    n = len(lo)
    codes = np.unique(np.minimum(rows[mine], other) * n + np.maximum(rows[mine], other))
    return np.column_stack([codes // n, codes % n])


class _KeptStructure:
    """The joints and ground contacts of a design without geometric violations, for
    recognizing the edits that keep all of them (the range search's, mostly): an edit
    whose changed planks' fresh pairs touch exactly as the design's joints of those
    planks did (the same faces) and whose changed planks touch the ground at the same
    corners (none sunk) has the design's geometry with those joints and contacts measured
    again, in the same order; its components, grounding and (no) violations are the
    design's.  What ``analyze`` would find, without the bookkeeping."""

    def __init__(self, design: Design, geometry: Geometry):
        self.original = geometry
        self.usable = not geometry.violations and design.joints is None
        self.slack = design.tolerance + _GEOMETRY_EPS
        self.spacing = design.material.nail_spacing
        index = design.plank_index
        self.joint_of = {tuple(sorted((index[j.face], index[j.edge]))): n
                         for n, j in enumerate(geometry.joints)}
        self.contacts: dict[str, list[Contact]] = {}
        for contact in geometry.contacts:
            if contact.anchor is None:
                self.contacts.setdefault(contact.plank, []).append(contact)

    def of(self, edited: Design, fresh: list, touches: dict,
           same: frozenset[str]) -> Geometry | None:
        """The geometry of ``edited`` (whose planks ``same`` are the design's, and whose
        plank pairs ``fresh`` (i < j) with a changed plank have the best ``touches``) if it
        keeps every joint and contact of the design; None if it may not."""
        if not self.usable:
            return None
        joints = list(self.original.joints)
        replaced = 0
        for i, j in fresh:
            touch, n = touches.get((i, j)), self.joint_of.get((i, j))
            if touch is None or touch.gap < -self.slack:
                if n is not None:
                    return None                 # the joint parts
                continue
            if n is None:
                return None                     # a new joint
            old = joints[n]
            if (touch.face.id, touch.edge.id, touch.edge_face, touch.face_side) != \
                    (old.face, old.edge, old.edge_face, old.face_side):
                return None                     # the planks meet otherwise
            joints[n] = _joint_from_touch(touch, (touch.face.id, touch.edge.id),
                                          nail_count(touch.length, self.spacing), "")
            replaced += 1
        if replaced != sum(j.face not in same or j.edge not in same for j in joints):
            return None                         # a joint of a changed plank was not found
        contacts = []
        for plank in edited.planks:
            before = self.contacts.get(plank.id, [])
            if plank.id in same:
                contacts.extend(before)
                continue
            touching, sunk = corner_contacts(edited, plank, self.slack)
            if sunk or [(c.wall, c.corner) for c in touching] != \
                    [(c.wall, c.corner) for c in before]:
                return None                     # sunk, or other corners on a support
            contacts.extend(touching)
        contacts.extend(anchor_contacts(edited))
        return Geometry(tuple(joints), tuple(contacts), self.original.components,
                        self.original.grounded, ())


# --- margins of an edit -----------------------------------------------------------------------

class EditMargins:
    """Continuous margins (m, or cosines) of the criteria that decide whether an edit of a
    design keeps its joints and ground contacts (``edit_check.check_edit``), for edits that
    change the planks ``changed`` (indices) only.  Calling it on an edited design gives

    required  : (R,) must stay > 0: for every joint of a changed plank its gap within
                +-slack, its tilt, its edge plank outside the face, and the overlap of the
                end face with the face (2-D separating axes); per changed plank its size
                and its ground contact (grounded planks keep one, others stay clear, and
                nothing sinks deeper than the slack).
    forbidden : (F, A) groups that must not all become > 0: every other narrow face on a
                broad face among pairs with a changed plank (a new joint; only when joints
                are detected), and per such pair the separating-axis overlaps beyond the
                slack (one plank cutting into the other, ``interpenetrations``).

    The rows are fixed at construction, so the margins of two steps of one DOF compare
    entry by entry.  Under a translation or a size change every margin is linear in the
    step (a joint's gap piecewise linear: the least point of the part of its end face over
    the face moves where that part's clipping changes): a search can predict where the
    first criterion flips and confirm it with ``check_edit`` instead of bisecting blindly.
    The criteria mirror ``analyze`` closely, not exactly (the clipped area of a touching
    region is approximated by its separating axes): a prediction is only ever a guess to
    be confirmed.
    """

    def __init__(self, design: Design, geometry: Geometry, changed: tuple[int, ...],
                 turn: float = 180.0, turning: tuple[int, ...] | None = None):
        """``turn``: the most (degrees) that the edits turn any plank; a narrow face tilted
        further than that beyond the largest joint tilt from a broad face can never come to
        rest on it, and is left out (translations and size changes turn nothing).
        ``turning``: the changed planks that the edits turn (None: all of them); between
        two planks that do not turn the tilt stays as it is.  Every pair with a changed
        plank is watched, however far apart: a plank that a search could push through
        another must not be found valid on the far side of it."""
        n = len(design.planks)
        self.changed = tuple(sorted(set(changed)))
        self.slack = design.tolerance + _GEOMETRY_EPS
        self.pairs = np.array(sorted({(min(c, k), max(c, k)) for c in self.changed
                                      for k in range(n) if k != c}), dtype=int).reshape(-1, 2)
        ordered = np.vstack([self.pairs, self.pairs[:, ::-1]])          # (edge, face) both ways
        self.edge = np.repeat(ordered[:, 0], 8)
        self.face = np.repeat(ordered[:, 1], 8)
        self.f = np.tile(np.repeat(np.arange(4), 2), len(ordered))
        self.g = np.tile(np.arange(2), 4 * len(ordered))
        joints = [((design.plank_index[j.edge] * 4 + 2 * j.edge_face[0]
                    + (j.edge_face[1] < 0)) * n + design.plank_index[j.face]) * 2
                  + int(j.face_side < 0) for j in geometry.joints]
        self.is_joint = np.isin(((self.edge * 4 + self.f) * n + self.face) * 2 + self.g,
                                joints)             # (edge, f, face, g) as one number
        turns = np.zeros(n, dtype=bool)
        turns[list(self.changed if turning is None else turning)] = True
        # per row, the largest tilt (degrees) between its faces that can still become a
        # joint: the largest joint tilt, plus the turn where one of the planks turns
        reach = np.where(turns[self.edge] | turns[self.face],
                         min(tol.JOINT_MAX_TILT_DEG + turn, 180.0), tol.JOINT_MAX_TILT_DEG)
        self.planks = design.planks
        self.unchanged_tables = _design_tables(design.planks)
        if reach.min(initial=180.0) < 180.0:
            faces = self.unchanged_tables[0]
            tilt = -(faces.narrow_normal[self.edge, self.f]
                     * faces.broad_normal[self.face, self.g]).sum(axis=1)
            keep = self.is_joint | (tilt >= np.cos(np.radians(reach)) - _GEOMETRY_EPS)
            self.edge, self.face, self.f, self.g, self.is_joint = (
                self.edge[keep], self.face[keep], self.f[keep], self.g[keep], self.is_joint[keep])
        self.detected = design.joints is None
        grounded = {c.plank for c in geometry.contacts if c.on is None and c.anchor is None}
        sunk = {v.where for v in geometry.violations if v.kind == "penetration"}
        self.grounded = [design.planks[i].id in grounded for i in self.changed]
        self.sunk = [design.planks[i].id in sunk for i in self.changed]

    def __call__(self, design: Design) -> tuple[np.ndarray, np.ndarray]:
        return edit_margins_many([(self, design)])[0]


def edit_margins_many(requests: list[tuple[EditMargins, Design]]
                      ) -> list[tuple[np.ndarray, np.ndarray]]:
    """``margins(edited)`` for each (margins, edited) of ``requests``, all margins made for
    one design: every row of all of them in one vectorized pass.  The tables are the
    design's (``unchanged_tables``) with the changed planks of every edit appended; each
    request's rows index its own changed planks there."""
    if not requests:
        return []
    first = requests[0][0]
    if any(margins.planks is not first.planks for margins, _ in requests):
        raise ValueError("edit_margins_many: margins made for different designs")
    _, faces, boxes, index = _stacked_tables(
        first.planks, first.unchanged_tables,
        [(list(margins.changed), edited.planks) for margins, edited in requests])
    rows = {name: [slots[getattr(margins, name)] for (margins, _), slots in zip(requests, index)]
            for name in ("edge", "face", "pairs")}
    slack = first.slack
    combos = _combo_margins(faces, faces.rotations, faces.halves, boxes,
                            np.concatenate(rows["edge"]), np.concatenate(rows["face"]),
                            np.concatenate([margins.f for margins, _ in requests]),
                            np.concatenate([margins.g for margins, _ in requests]), slack)
    cuts = _cut_margins(faces.rotations, faces.halves, faces.centers, boxes,
                        np.concatenate(rows["pairs"]), slack)
    out = []
    combo_start = cut_start = 0
    for margins, edited in requests:
        mine = combos[combo_start:combo_start + len(margins.edge)]
        cutting = cuts[cut_start:cut_start + len(margins.pairs)]
        combo_start += len(margins.edge)
        cut_start += len(margins.pairs)
        per_plank = []
        for index, grounded, sunk in zip(margins.changed, margins.grounded, margins.sunk):
            plank = edited.planks[index]
            lowest = float(plank.corners[:, 2].min())
            per_plank += [plank.length, plank.width]
            if not grounded:
                per_plank.append(lowest - slack)
                continue
            per_plank.append(slack - lowest)
            if not sunk:
                per_plank.append(lowest + slack)
        required = np.concatenate([mine[margins.is_joint].ravel(), per_plank])
        if margins.detected:        # the new touches' groups, padded with margins of 1.0
            others = mine[~margins.is_joint]
            forbidden = np.ones((len(cutting) + len(others), cutting.shape[1]))
            forbidden[:len(cutting)] = cutting
            forbidden[len(cutting):, :others.shape[1]] = others
        else:
            forbidden = cutting.copy()
        out.append((required, forbidden))
    return out


def _combo_margins(faces: _Faces, rot: np.ndarray, half: np.ndarray,
                   boxes: tuple[np.ndarray, np.ndarray], edge: np.ndarray, face: np.ndarray,
                   f: np.ndarray, g: np.ndarray, slack: float) -> np.ndarray:
    """(C, 18) margins of narrow face f of plank edge resting on broad face g of plank face
    (``rot`` (n, 3, 3), ``half`` (n, 3), ``boxes``: all planks' rotations, half extents
    and bounding boxes): gap + slack, slack - gap (the gap of the part of the end face
    over the face, ``_touching_gaps``: piecewise linear in a translation, where the
    clipping changes), tilt (alignment - cos of the largest
    tilt), height of the edge plank's centre above the face, the overlap of the end face's
    projection with the face along the face's two axes and the projection's two edge
    normals (both ends each, less a round-off slack: faces that only share an edge do not
    overlap), and the overlap of the two bounding boxes within the slack (``analyze`` looks
    only at pairs whose boxes meet: a tilted end can touch a face while its box clears)."""
    normal = faces.broad_normal[face, g]                                   # (C, 3)
    offset = faces.broad_offset[face, g]
    corners = faces.narrow_corners[edge, f]                                # (C, 4, 3)
    # component by component (``_dot``, ``_least``, ``_most``): numpy's reductions and
    # matmuls over axes of two to four entries cost many times the arithmetic
    heights = _dot(corners, normal[:, None, :]) - offset[:, None]          # (C, 4)
    alignment = -_dot(faces.narrow_normal[edge, f], normal)
    outside = _dot(faces.centers[edge], normal) - offset
    half_f = half[face]
    face_center = faces.centers[face] + half_f[:, 2:3] * normal
    relative = corners - face_center[:, None, :]
    rot_f = rot[face]
    qx = _dot(relative, rot_f[:, None, :, 0])                              # (C, 4) in the
    qy = _dot(relative, rot_f[:, None, :, 1])                              # face's x-y
    gap = _touching_gaps(qx, qy, _dot(relative, normal[:, None, :]), half_f, _least(heights))
    overlap = np.empty((len(edge), 8))
    overlap[:, 0] = half_f[:, 0] - _least(qx)
    overlap[:, 1] = half_f[:, 1] - _least(qy)
    overlap[:, 4] = _most(qx) + half_f[:, 0]
    overlap[:, 5] = _most(qy) + half_f[:, 1]
    unusable = []
    for k in range(2):             # the projection's edge normals, (-side_y, side_x)
        nx, ny = qy[:, k] - qy[:, k + 1], qx[:, k + 1] - qx[:, k]
        length = np.sqrt(nx * nx + ny * ny)
        unusable.append(length <= _GEOMETRY_EPS * _GEOMETRY_EPS)
        scale = np.where(length > 0.0, length, 1.0)
        nx, ny = nx / scale, ny / scale
        projected = qx * nx[:, None] + qy * ny[:, None]
        radius = np.abs(nx) * half_f[:, 0] + np.abs(ny) * half_f[:, 1]
        overlap[:, 2 + k] = radius - _least(projected)
        overlap[:, 6 + k] = _most(projected) + radius
    overlap -= _GEOMETRY_EPS
    # across the joint line (the normal of the projection's side along it, corners 0-1),
    # a joint needs a band of MIN_BEARING_SHARE of the edge plank's thickness, not a hair
    needed = tol.MIN_BEARING_SHARE * 2.0 * half[edge, 2]
    overlap[:, 2] -= needed
    overlap[:, 6] -= needed
    for k, mask in enumerate(unusable):
        overlap[mask, 2 + k] = overlap[mask, 6 + k] = 1.0
    lo, hi = boxes
    return np.column_stack([gap + slack, slack - gap, alignment - _COS_MAX_TILT, outside,
                            overlap, hi[face] + slack - lo[edge], hi[edge] + slack - lo[face]])


def _touching_gaps(qx: np.ndarray, qy: np.ndarray, heights: np.ndarray, half: np.ndarray,
                   corner_gap: np.ndarray) -> np.ndarray:
    """(C,) m: the gap of each end face (corners ``qx``, ``qy`` (C, 4) in the face's x-y,
    ``heights`` above it) where it lies over the face, as ``analyze`` measures it
    (``faces._region_gaps``: the least height over the clipped region); ``corner_gap``,
    its corners' least, where no part of it lies over the face (the overlap margins
    watch that)."""
    hx, hy = half[:, :1], half[:, 1:2]
    across = ~(np.all((np.abs(qx) <= hx) & (np.abs(qy) <= hy), axis=1)     # partly over
               | np.all(qx > hx, axis=1) | np.all(qx < -hx, axis=1)        # the face: the
               | np.all(qy > hy, axis=1) | np.all(qy < -hy, axis=1))       # others keep
    rows = np.flatnonzero(across)                                          # their corners'
    gaps = corner_gap.copy()
    if len(rows):
        x, y, h = qx[rows], qy[rows], half[rows]
        local = np.stack([x, y], axis=2)
        xs, ys, count = _clipped_to_rectangles(x, y, h[:, 0], h[:, 1])
        clipped = _region_gaps(xs, ys, count, _height_slopes(local, heights[rows]), local, h,
                               corner_gap[rows])
        gaps[rows] = np.where(count >= 3, clipped, corner_gap[rows])
    return gaps


def _cut_margins(rot: np.ndarray, half: np.ndarray, centre: np.ndarray,
                 boxes: tuple[np.ndarray, np.ndarray], pairs: np.ndarray,
                 slack: float) -> np.ndarray:
    """(P, 36) margins whose all being > 0 means the pair's boxes overlap deeper than the
    slack (``interpenetrations``): per separating axis both ends of the overlap of their
    projections beyond the slack (1.0 for degenerate axes), then the bounding boxes'."""
    if len(pairs) == 0:
        return np.zeros((0, 36))
    a, b = pairs[:, 0], pairs[:, 1]
    usable, radius, distance = _separating_axes(rot, half, centre, pairs)
    sat = np.concatenate([radius - slack - distance, radius - slack + distance], axis=1)
    sat = np.where(np.tile(usable, 2), sat, 1.0)
    lo, hi = boxes
    return np.concatenate([sat, hi[b] - slack - lo[a], hi[a] - slack - lo[b]], axis=1)
