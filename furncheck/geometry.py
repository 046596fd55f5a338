"""Joints, ground contacts and connectivity of a design (contract section 2).

A nail joint joins an *edge plank* (one of its four narrow faces rests on the other plank)
to a *face plank* (its broad face receives the nails).  Everything here is SI (metres) and
works for arbitrary plank rotations: faces are handled as oriented rectangles, the touching
region is the edge face's projection clipped to the face plank's face.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Plank
from furncheck.result import Violation

_COS_MAX_TILT = float(np.cos(np.radians(tol.JOINT_MAX_TILT_DEG)))
_GEOMETRY_EPS = 1e-9
"""m: numeric slack added to the design's tolerance (which may be zero)."""


@dataclass(frozen=True)
class Joint:
    """A nail joint.

    planks : (first, second) plank ids as listed (auto-detected: (face, edge))
    face, edge : the face plank and the edge plank
    point  : (3,) m, centroid of the touching region
    length : m, extent of the touching region along the joint line
    nails  : nail count
    frame  : (3, 3) world columns x (edge plank's thickness normal), y (joint line),
             n (face plank's normal pointing into the edge plank)
    edge_thickness : m, thickness t of the edge plank (the nail lever, contract section 3)
    edge_face : which narrow face of the edge plank rests on the face plank, as
             (local axis 0 = x / 1 = y, sign +1 / -1)
    face_side : which broad face of the face plank receives it (+1 = local +z, -1 = -z)
    key    : key path of the listed joint ('joints[2]'), '' when auto-detected
    """

    planks: tuple[str, str]
    face: str
    edge: str
    point: np.ndarray
    length: float
    nails: int
    frame: np.ndarray
    edge_thickness: float
    edge_face: tuple[int, int] = (0, 1)
    face_side: int = 1
    key: str = ""

    @property
    def name(self) -> str:
        return f"{self.planks[0]}/{self.planks[1]}"


@dataclass(frozen=True)
class Contact:
    """A plank corner touching the ground; ``point`` (3,) m lies on z = 0.

    corner : index of the corner in ``Plank.corners`` (identifies the contact across edits)
    """

    plank: str
    point: np.ndarray
    corner: int = 0


@dataclass(frozen=True)
class Geometry:
    """What the statics needs, plus the geometric violations.

    components : plank indices of each jointed group, in order of their first plank
    grounded   : per component, whether any of its planks touches the ground
    """

    joints: tuple[Joint, ...]
    contacts: tuple[Contact, ...]
    components: tuple[tuple[int, ...], ...]
    grounded: tuple[bool, ...]
    violations: tuple[Violation, ...]


@dataclass(frozen=True)
class _Touch:
    """A narrow face of ``edge`` found on a broad face of ``face`` (before nail counting)."""

    face: Plank
    edge: Plank
    point: np.ndarray
    length: float
    frame: np.ndarray
    gap: float          # m, signed distance of the edge face's nearest corner (< 0: inside)
    alignment: float    # -(edge face normal . face normal), 1 when flush
    area: float         # m^2 of the touching region
    edge_face: tuple[int, int] = (0, 1)
    face_side: int = 1


def analyze(design: Design, previous: tuple[Design, Geometry] | None = None) -> Geometry:
    """Detect or check joints, find ground contacts and connected components.

    ``previous``: an earlier version of the same design (same planks, in the same order)
    and its analysis; joints between planks that did not change are taken from it instead
    of being detected again (the result is the same, only faster: for design edits).
    """
    violations: list[Violation] = []
    same = _unchanged_planks(design, previous)
    if design.joints is None:
        joints = _detect_joints(design, _unchanged_joints(design, previous, same))
    else:
        joints = _listed_joints(design, violations)
    return _completed(design, joints, violations, None if same is None else previous[1], same)


def _completed(design: Design, joints: list[Joint], violations: list[Violation],
               earlier: Geometry | None, same: frozenset[str] | None) -> Geometry:
    """The geometry of a design with these joints: its ground contacts, components and
    connectivity violations added (``earlier``: the analysis of a version in which the
    planks ``same`` are the same, see ``analyze``)."""
    contacts = _ground_contacts(design, violations, earlier, same)
    if earlier is not None and [j.planks for j in joints] == [j.planks for j in earlier.joints]:
        components = earlier.components          # they follow from the joined pairs alone
    else:
        components = _components(design, joints)
    plank_has_contact = {c.plank for c in contacts}
    grounded = tuple(any(design.planks[i].id in plank_has_contact for i in comp)
                     for comp in components)
    _connectivity_violations(design, joints, components, grounded, violations)
    return Geometry(tuple(joints), tuple(contacts), components, grounded, tuple(violations))


def follow(geometry: Geometry, design: Design) -> Geometry:
    """The same joints (same faces) and ground contacts (same corners) on an edited design,
    their points, frames and lengths recomputed: the structure a small design change keeps,
    for derivatives.  Joints whose faces no longer overlap keep their old values."""
    joints, contacts = follow_many(geometry, [(design, range(len(geometry.joints)),
                                               range(len(geometry.contacts)))])[0]
    return replace(geometry, joints=joints, contacts=contacts)


def follow_many(geometry: Geometry, edits: list) -> list[tuple[tuple[Joint, ...],
                                                               tuple[Contact, ...]]]:
    """``follow`` of chosen joints and contacts on many edited versions of one design at
    once (for the sensitivity of every DOF): ``edits`` is a list of (edited design, joint
    indices, contact indices into ``geometry``); returns per edit the followed joints and
    contacts in that order.  All touching regions are measured in one vectorized pass; a
    plank shared by several edits (the same object) is tabled once."""
    planks: list[Plank] = []
    slot: dict[int, int] = {}

    def tabled(plank: Plank) -> int:
        if id(plank) not in slot:
            slot[id(plank)] = len(planks)
            planks.append(plank)
        return slot[id(plank)]

    rows, owners, contacts_out = [], [], []
    for k, (design, joint_ids, contact_ids) in enumerate(edits):
        index = design.plank_index
        for j in joint_ids:
            joint = geometry.joints[j]
            rows.append((tabled(design.planks[index[joint.edge]]),
                         tabled(design.planks[index[joint.face]]),
                         2 * joint.edge_face[0] + (0 if joint.edge_face[1] > 0 else 1),
                         0 if joint.face_side > 0 else 1))
            owners.append((k, joint))
        followed = []
        for c in contact_ids:
            contact = geometry.contacts[c]
            x, y, _ = design.planks[index[contact.plank]].corners[contact.corner]
            followed.append(replace(contact, point=np.array([x, y, 0.0])))
        contacts_out.append(tuple(followed))
    joints_out: list[list[Joint]] = [[] for _ in edits]
    if rows:
        edge, face, f, g = (np.array(column, dtype=int) for column in zip(*rows))
        faces = _face_tables(tuple(planks))
        gap = (np.einsum("cka,ca->ck", faces.narrow_corners[edge, f],
                         faces.broad_normal[face, g])
               - faces.broad_offset[face, g][:, None]).min(axis=1)
        touches = _touch_regions(planks, faces, edge, face, f, g, gap, np.ones(len(edge)))
        for (k, joint), touch in zip(owners, touches):
            joints_out[k].append(joint if touch is None else replace(
                joint, point=touch.point, length=touch.length, frame=touch.frame,
                edge_thickness=touch.edge.thickness))
    return [(tuple(joints), contacts) for joints, contacts in zip(joints_out, contacts_out)]


# --- joints -----------------------------------------------------------------------------------

def nail_count(length: float, spacing: float) -> int:
    """max(1, floor(L / spacing)), with a little slack against round-off (300/20 -> 15)."""
    return max(1, int(np.floor(length / spacing * (1.0 + tol.NAIL_COUNT_EPS))))


def _detect_joints(design: Design, known: dict | None = None) -> list[Joint]:
    """Joints detected from the geometry; ``known``: see ``_unchanged_joints``."""
    pairs, fresh = _pairs_to_detect(design, *_bounding_boxes(design.planks), known)
    best = _best_touches(design.planks, pairs[fresh], design.tolerance + _GEOMETRY_EPS,
                         keep_deep=False)
    return _detected_joints(design, pairs, fresh, known, best)


def _pairs_to_detect(design: Design, lo: np.ndarray, hi: np.ndarray,
                     known: dict | None) -> tuple[np.ndarray, np.ndarray]:
    """The plank pairs (i < j) whose boxes (``lo``, ``hi``) meet within the slack, and
    whether each must be detected (not both planks among the ``known`` unchanged ones)."""
    slack = design.tolerance + _GEOMETRY_EPS
    overlap = np.all((lo[:, None, :] <= hi[None, :, :] + slack)
                     & (lo[None, :, :] <= hi[:, None, :] + slack), axis=2)
    pairs = np.argwhere(np.triu(overlap, k=1))
    if known is None:
        return pairs, np.ones(len(pairs), dtype=bool)
    changed = np.array([plank.id not in known["planks"] for plank in design.planks])
    fresh = changed[pairs[:, 0]] | changed[pairs[:, 1]] if len(pairs) else \
        np.zeros(0, dtype=bool)
    return pairs, fresh


def _detected_joints(design: Design, pairs: np.ndarray, fresh: np.ndarray,
                     known: dict | None, best: dict) -> list[Joint]:
    """The joints of ``pairs`` in order: a known one where the pair is not ``fresh``, else
    from its best touch (``best``, keyed by the pair) if that lies within the slack."""
    slack = design.tolerance + _GEOMETRY_EPS
    joints = []
    for (i, j), detect in zip(pairs.tolist(), fresh.tolist()):
        if not detect:
            if (i, j) in known:
                joints.append(known[(i, j)])
            continue
        touch = best.get((i, j))
        if touch is not None and touch.gap >= -slack:
            nails = nail_count(touch.length, design.material.nail_spacing)
            joints.append(_joint_from_touch(touch, (touch.face.id, touch.edge.id), nails, ""))
    return joints


def _unchanged_planks(design: Design,
                      previous: tuple[Design, Geometry] | None) -> frozenset[str] | None:
    """The ids of the planks that an earlier version of the design has unchanged, or None
    if that version cannot stand in for them (other planks or order, material, tolerance,
    units or joint list)."""
    if previous is None:
        return None
    before = previous[0]
    if [p.id for p in before.planks] != [p.id for p in design.planks] or \
            before.material != design.material or before.tolerance != design.tolerance or \
            before.units != design.units or before.joints != design.joints or \
            before.lines != design.lines:
        return None
    return frozenset(new.id for old, new in zip(before.planks, design.planks) if old == new)


def _unchanged_joints(design: Design, previous: tuple[Design, Geometry] | None,
                      same: frozenset[str] | None) -> dict | None:
    """From an earlier version of the design with the planks ``same`` unchanged: {(i, j):
    joint} for detected joints between two unchanged planks, plus 'planks': ``same``."""
    if same is None or design.joints is not None:
        return None
    known: dict = {"planks": same}
    for joint in previous[1].joints:
        if joint.face in same and joint.edge in same:
            i, j = sorted((design.plank_index[joint.face], design.plank_index[joint.edge]))
            known[(i, j)] = joint
    return known


def _listed_joints(design: Design, violations: list[Violation]) -> list[Joint]:
    slack = design.tolerance + _GEOMETRY_EPS
    specs = design.joints or ()
    pairs = np.array([[design.plank_index[a], design.plank_index[b]] for a, b in
                      (spec.planks for spec in specs)], dtype=int).reshape(-1, 2)
    best = _best_touches(design.planks, pairs, slack, keep_deep=True)
    joints = []
    for index, (spec, (i, j)) in enumerate(zip(specs, pairs)):
        key = f"joints[{index}]"
        touch = best.get((int(i), int(j)))
        name = f"{spec.planks[0]}/{spec.planks[1]}"
        line = design.line_of(key)
        if touch is None:
            violations.append(Violation("disconnected", name, None,
                                        _apart_message(design, int(i), int(j)), line))
            continue
        if touch.gap < -slack:
            violations.append(Violation(
                "disconnected", name, None,
                f"planks interpenetrate by {_fmt_len(-touch.gap, design)}, more than the "
                f"tolerance {_fmt_len(design.tolerance, design)}", line))
            continue
        nails = spec.nails or nail_count(touch.length, design.material.nail_spacing)
        joints.append(_joint_from_touch(touch, spec.planks, nails, key))
    return joints


def _joint_from_touch(touch: _Touch, planks: tuple[str, str], nails: int, key: str) -> Joint:
    return Joint(planks=tuple(planks), face=touch.face.id, edge=touch.edge.id,
                 point=touch.point, length=touch.length, nails=nails, frame=touch.frame,
                 edge_thickness=touch.edge.thickness, edge_face=touch.edge_face,
                 face_side=touch.face_side, key=key)


@dataclass(frozen=True)
class _Faces:
    """Face tables of all planks (n planks).

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
                  faces: _Faces | None = None) -> dict:
    """For each plank pair (i, j) (indices into ``planks``, whose face tables ``faces`` are
    when given), the best narrow-face-on-broad-face contact either way round: contacts
    within the slack beat deeper ones, then the flushest, then the largest.  ``keep_deep``
    keeps faces sunk deeper than the slack (to report interpenetration)."""
    if len(pairs) == 0:
        return {}
    faces = _face_tables(planks) if faces is None else faces
    ordered = np.vstack([pairs, pairs[:, ::-1]])                 # (edge, face) both ways
    edge, face = ordered[:, 0], ordered[:, 1]
    alignment = -np.einsum("pfa,pga->pfg", faces.narrow_normal[edge], faces.broad_normal[face])
    heights = (np.einsum("pfca,pga->pfgc", faces.narrow_corners[edge], faces.broad_normal[face])
               - faces.broad_offset[face][:, None, :, None])
    gap = heights.min(axis=3)                                     # (P, 4, 2)
    outside = (np.einsum("pa,pga->pg", faces.centers[edge], faces.broad_normal[face])
               - faces.broad_offset[face]) >= 0.0
    candidates = (alignment >= _COS_MAX_TILT) & (gap <= slack) & outside[:, None, :]
    if not keep_deep:
        candidates &= gap >= -slack
    best: dict[tuple[int, int], _Touch] = {}
    n_pairs = len(pairs)
    chosen = np.argwhere(candidates)
    p, f, g = chosen[:, 0], chosen[:, 1], chosen[:, 2]
    touches = _touch_regions(planks, faces, edge[p], face[p], f, g, gap[p, f, g],
                             alignment[p, f, g])
    for p_k, touch in zip(chosen[:, 0].tolist(), touches):
        if touch is None:
            continue
        key = tuple(int(v) for v in pairs[p_k % n_pairs])
        rank = (touch.gap >= -slack, round(touch.alignment, 9), touch.area)
        current = best.get(key)
        if current is None or rank > (current.gap >= -slack, round(current.alignment, 9),
                                      current.area):
            best[key] = touch
    return best


def _touch_regions(planks, faces: _Faces, edge: np.ndarray, face: np.ndarray,
                   f: np.ndarray, g: np.ndarray, gap: np.ndarray,
                   alignment: np.ndarray) -> list[_Touch | None]:
    """For candidate contacts c (edge plank edge[c]'s narrow face f[c] on face plank
    face[c]'s broad face g[c], indices into ``planks`` and ``faces``): clip the narrow
    face's projection to the broad face (in the face plank's local x-y) and measure the
    touching region; None where it is empty."""
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
    regions = []
    for quad, (hx, hy), (ax, ay), least in zip(local.tolist(), half_f[:, :2].tolist(),
                                               along_2d.tolist(),
                                               (tol.MIN_JOINT_AREA_FRACTION * face_area)):
        polygon = _clip_to_rectangle(quad, hx, hy)
        if len(polygon) < 3:
            regions.append(None)
            continue
        area, cx, cy = _polygon_area_centroid(polygon)
        extent = [x * ax + y * ay for x, y in polygon]
        regions.append((area, cx, cy, max(extent) - min(extent)) if area > least else None)
    thickness_normal = rot_e[:, :, 2]
    x_axis = thickness_normal - np.einsum("ca,ca->c", thickness_normal, normal)[:, None] * normal
    x_axis /= np.linalg.norm(x_axis, axis=1, keepdims=True)
    frames = np.stack([x_axis, np.cross(normal, x_axis), normal], axis=2)  # columns x, y, n
    centroids = np.array([(0.0, 0.0) if region is None else region[1:3] for region in regions])
    points = face_center + rot_f[:, :, 0] * centroids[:, :1] + rot_f[:, :, 1] * centroids[:, 1:]
    touches: list[_Touch | None] = []
    for c, (region, face_c, edge_c, f_c, g_c, gap_c, alignment_c) in enumerate(zip(
            regions, face.tolist(), edge.tolist(), f.tolist(), g.tolist(), gap.tolist(),
            alignment.tolist())):
        touches.append(None if region is None else _Touch(
            planks[face_c], planks[edge_c], points[c], region[3], frames[c], gap_c,
            alignment_c, region[0], edge_face=(f_c // 2, 1 - 2 * (f_c % 2)),
            face_side=1 - 2 * g_c))
    return touches


def _clip_to_rectangle(polygon: list, half_x: float, half_y: float) -> list:
    """Sutherland-Hodgman clip of a convex polygon [(x, y), ...] to |x| <= half_x,
    |y| <= half_y (plain floats: the polygons are tiny, numpy would only add overhead)."""
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


def _bounding_boxes(planks: tuple[Plank, ...]) -> tuple[np.ndarray, np.ndarray]:
    """World axis-aligned boxes (n, 3) lower and upper corners."""
    corners = np.stack([p.corners for p in planks])
    return corners.min(axis=1), corners.max(axis=1)


def end_gap(design: Design, i: int, j: int) -> float | None:
    """How far (m) the end face of one of planks i, j is from the broad face of the other
    that it faces (its gap, or its depth when it cuts in), None when neither plank's end
    faces the other: what keeps a listed joint from closing."""
    touch = _nearest_touch(design, i, j)
    return None if touch is None else abs(float(touch.gap))


def _nearest_touch(design: Design, i: int, j: int) -> _Touch | None:
    return _best_touches(design.planks, np.array([[i, j]]), slack=np.inf,
                         keep_deep=False).get((i, j))


def _apart_message(design: Design, i: int, j: int) -> str:
    """Why two listed planks form no joint, with the gap between the end face and the face
    it should rest on when one faces the other."""
    touch = _nearest_touch(design, i, j)
    if touch is not None and touch.gap > 0:
        return (f"planks do not touch: the end of {touch.edge.id} is "
                f"{_fmt_len(touch.gap, design)} from the face of {touch.face.id} "
                f"(tolerance {_fmt_len(design.tolerance, design)})")
    a, b = design.planks[i], design.planks[j]
    diff = a.corners[:, None, :] - b.corners[None, :, :]
    gap = float(np.sqrt((diff ** 2).sum(axis=2)).min())
    return (f"planks do not touch: no end face of one lies on a face of the other "
            f"(closest corners {_fmt_len(gap, design)} apart)")


def interpenetrations(design: Design) -> list[tuple[str, str, float]]:
    """Plank pairs whose boxes overlap deeper than the tolerance: (id, id, depth m).

    Separating-axis test of two oriented boxes over their 15 candidate axes; the depth is
    the smallest overlap of their projections.  Planks meeting at a joint only touch, so
    their depth is ~0.  (Not a violation of the contract's kinds: furncheck uses it to
    refuse design edits that would push one plank through another.)
    """
    slack = design.tolerance + _GEOMETRY_EPS
    pairs = _overlapping(*_bounding_boxes(design.planks), slack)
    if len(pairs) == 0:
        return []
    depth = _box_depths(np.stack([p.rotation_matrix for p in design.planks]),
                        np.stack([p.half_extents for p in design.planks]),
                        np.stack([p.center_array for p in design.planks]), pairs)
    return [(design.planks[i].id, design.planks[j].id, float(d))
            for (i, j), d in zip(pairs, depth) if d > slack]


def _overlapping(lo: np.ndarray, hi: np.ndarray, slack: float) -> np.ndarray:
    """Pairs (i < j) of boxes that overlap by more than the slack along every axis."""
    overlap = np.all((lo[:, None, :] < hi[None, :, :] - slack)
                     & (lo[None, :, :] < hi[:, None, :] - slack), axis=2)
    return np.argwhere(np.triu(overlap, k=1))


def _box_depths(rot: np.ndarray, half: np.ndarray, centre: np.ndarray,
                pairs: np.ndarray) -> np.ndarray:
    """Per pair (a, b) of planks (rotations, half extents, centres): how deep their boxes
    overlap, the smallest overlap of their projections on the 15 separating axes."""
    a, b = pairs[:, 0], pairs[:, 1]
    ra, rb = np.transpose(rot[a], (0, 2, 1)), np.transpose(rot[b], (0, 2, 1))  # rows = axes
    crosses = np.cross(ra[:, :, None, :], rb[:, None, :, :]).reshape(-1, 9, 3)
    axes = np.concatenate([ra, rb, crosses], axis=1)                            # (P, 15, 3)
    norms = np.linalg.norm(axes, axis=2)
    usable = norms > 1e-9
    axes = axes / np.where(usable, norms, 1.0)[:, :, None]
    radius_a = (np.abs(np.einsum("pka,pia->pki", axes, ra)) * half[a][:, None, :]).sum(axis=2)
    radius_b = (np.abs(np.einsum("pka,pia->pki", axes, rb)) * half[b][:, None, :]).sum(axis=2)
    distance = np.abs(np.einsum("pka,pa->pk", axes, centre[b] - centre[a]))
    return np.where(usable, radius_a + radius_b - distance, np.inf).min(axis=1)


class EditedTables:
    """The face tables and boxes of many edits of one design at once: the design's own
    rows, then the rows of the planks that each edit changes (its ``index`` maps the
    edit's plank numbers to rows).  Edits that do not keep the design's planks, material
    and tolerance (``_unchanged_planks``) have no rows (``same`` None)."""

    def __init__(self, design: Design, geometry: Geometry, edits: list[Design]):
        self.design, self.geometry, self.edits = design, geometry, edits
        count = len(design.planks)
        self.same, self.index, changed = [], [], []
        for edited in edits:
            same = _unchanged_planks(edited, (design, geometry))
            self.same.append(same)
            index = np.arange(count)
            if same is not None:
                moved = [i for i, plank in enumerate(edited.planks) if plank.id not in same]
                index[moved] = count + len(changed) + np.arange(len(moved))
                changed.extend(edited.planks[i] for i in moved)
            self.index.append(index)
        self.planks = design.planks + tuple(changed)
        self.faces = _face_tables(self.planks)
        self.lo, self.hi = _bounding_boxes(self.planks)

    def geometries(self) -> list[Geometry]:
        """``analyze(edited, (design, geometry))`` of every edit, the joints of all edits'
        changed planks detected together."""
        design, geometry = self.design, self.geometry
        slack = design.tolerance + _GEOMETRY_EPS
        found: list = [None] * len(self.edits)
        detect = []
        for k, (edited, same, index) in enumerate(zip(self.edits, self.same, self.index)):
            if same is None or edited.joints is not None:
                found[k] = analyze(edited, (design, geometry))
                continue
            known = _unchanged_joints(edited, (design, geometry), same)
            pairs, fresh = _pairs_to_detect(edited, self.lo[index], self.hi[index], known)
            detect.append((k, known, pairs, fresh))
        rows = [self.index[k][pairs[fresh]] for k, _, pairs, fresh in detect]
        best = _best_touches(self.planks, np.concatenate(rows) if rows else
                             np.zeros((0, 2), dtype=int), slack, False, self.faces)
        for k, known, pairs, fresh in detect:
            edited, index = self.edits[k], self.index[k]
            mine = {(i, j): best[key] for i, j in pairs[fresh].tolist()
                    if (key := (int(index[i]), int(index[j]))) in best}
            joints = _detected_joints(edited, pairs, fresh, known, mine)
            found[k] = _completed(edited, joints, [], geometry, self.same[k])
        return found

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


# --- ground, components -----------------------------------------------------------------------

def _ground_contacts(design: Design, violations: list[Violation],
                     earlier: Geometry | None = None,
                     same: frozenset[str] | None = None) -> list[Contact]:
    """Corners with z <= tolerance touch the ground; those below -tolerance penetrate it.
    The contacts and penetrations of the planks ``same`` are taken from ``earlier``."""
    slack = design.tolerance + _GEOMETRY_EPS
    contacts: list[Contact] = []
    reused: dict[str, list] = {}
    if earlier is not None:
        for contact in earlier.contacts:
            reused.setdefault(contact.plank, []).append(contact)
        for violation in earlier.violations:
            if violation.kind == "penetration":
                reused.setdefault(violation.where, []).append(violation)
    for index, plank in enumerate(design.planks):
        if same is not None and plank.id in same:
            for item in reused.get(plank.id, ()):
                (contacts if isinstance(item, Contact) else violations).append(item)
            continue
        z = plank.corners[:, 2]
        for corner in np.nonzero(z <= slack)[0]:
            x, y, _ = plank.corners[corner]
            contacts.append(Contact(plank.id, np.array([x, y, 0.0]), int(corner)))
        if z.min() < -slack:
            deepest = plank.corners[int(np.argmin(z))]
            violations.append(Violation(
                "penetration", plank.id, None,
                f"corner at {_fmt_point(deepest, design)} is {_fmt_len(-deepest[2], design)} "
                f"below the ground (tolerance {_fmt_len(design.tolerance, design)})",
                design.line_of(f"planks[{index}].center")))
    return contacts


def _components(design: Design, joints: list[Joint]) -> tuple[tuple[int, ...], ...]:
    """Connected groups of planks through joints (union-find), each sorted."""
    parent = list(range(len(design.planks)))

    def root(k: int) -> int:
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for joint in joints:
        a, b = (design.plank_index[pid] for pid in joint.planks)
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    groups: dict[int, list[int]] = {}
    for k in range(len(design.planks)):
        groups.setdefault(root(k), []).append(k)
    return tuple(tuple(g) for g in sorted(groups.values()))


def _connectivity_violations(design: Design, joints: list[Joint],
                             components: tuple[tuple[int, ...], ...],
                             grounded: tuple[bool, ...], violations: list[Violation]) -> None:
    if len(design.planks) > 1:
        joined = {pid for joint in joints for pid in joint.planks}
        listed = {pid for spec in design.joints or () for pid in spec.planks}
        for index, plank in enumerate(design.planks):
            if plank.id not in joined and plank.id not in listed:
                violations.append(Violation(
                    "disconnected", plank.id, None,
                    "plank is joined to no other plank (no end face rests on a neighbour's "
                    "face, and no neighbour's end face rests on it)",
                    design.line_of(f"planks[{index}]")))
    for component, is_grounded in zip(components, grounded):
        if not is_grounded:
            ids = [design.planks[i].id for i in component]
            lowest = min(float(design.planks[i].corners[:, 2].min()) for i in component)
            violations.append(Violation(
                "floating", ",".join(ids), None,
                f"{_plural(len(ids), 'plank')} {'touch' if len(ids) > 1 else 'touches'} the "
                f"ground nowhere (lowest corner "
                f"{_fmt_len(lowest, design)} above it)",
                design.line_of(f"planks[{component[0]}]")))


# --- formatting helpers for messages ----------------------------------------------------------

def _fmt_len(value_m: float, design: Design) -> str:
    return f"{value_m / design.unit_scale:.4g} {design.units}"


def _fmt_point(point_m: np.ndarray, design: Design) -> str:
    coords = ", ".join(f"{v / design.unit_scale:.4g}" for v in point_m)
    return f"({coords}) {design.units}"


def _plural(n: int, word: str) -> str:
    return f"{n} {word}s" if n != 1 else f"1 {word}"


# --- margins of an edit -----------------------------------------------------------------------

class EditMargins:
    """Continuous margins (m, or cosines) of the criteria that decide whether an edit of a
    design keeps its joints and ground contacts (``dofs.check_edit``), for edits that
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
    step: a search can predict where the first criterion flips and confirm it with
    ``check_edit`` instead of bisecting blindly.  The criteria mirror ``analyze`` closely,
    not exactly (the clipped area of a touching region is approximated by its separating
    axes): a prediction is only ever a guess to be confirmed.
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
        self.unchanged_tables = self._all_tables(design.planks)
        if reach.min(initial=180.0) < 180.0:
            faces = self.unchanged_tables[0]
            tilt = -(faces.narrow_normal[self.edge, self.f]
                     * faces.broad_normal[self.face, self.g]).sum(axis=1)
            keep = self.is_joint | (tilt >= np.cos(np.radians(reach)) - _GEOMETRY_EPS)
            self.edge, self.face, self.f, self.g, self.is_joint = (
                self.edge[keep], self.face[keep], self.f[keep], self.g[keep], self.is_joint[keep])
        self.detected = design.joints is None
        grounded = {c.plank for c in geometry.contacts}
        sunk = {v.where for v in geometry.violations if v.kind == "penetration"}
        self.grounded = [design.planks[i].id in grounded for i in self.changed]
        self.sunk = [design.planks[i].id in sunk for i in self.changed]

    @staticmethod
    def _all_tables(planks) -> tuple[_Faces, tuple[np.ndarray, np.ndarray]]:
        """Face tables and bounding boxes of ``planks``."""
        return _face_tables(planks), _bounding_boxes(planks)

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
    faces, (lo, hi) = first.unchanged_tables
    count = len(lo)
    changed: list[Plank] = []
    rows = {"edge": [], "face": [], "pairs": []}
    for margins, edited in requests:
        index = np.arange(count)
        index[list(margins.changed)] = count + len(changed) + np.arange(len(margins.changed))
        changed.extend(edited.planks[i] for i in margins.changed)
        for name, table in rows.items():
            table.append(index[getattr(margins, name)])
    new_faces, (new_lo, new_hi) = EditMargins._all_tables(tuple(changed))
    faces = _Faces(*(np.concatenate([getattr(faces, name), getattr(new_faces, name)])
                     for name in _Faces.__dataclass_fields__))
    boxes = (np.concatenate([lo, new_lo]), np.concatenate([hi, new_hi]))
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
        required = [mine[margins.is_joint].ravel()]
        for index, grounded, sunk in zip(margins.changed, margins.grounded, margins.sunk):
            plank = edited.planks[index]
            lowest = float(plank.corners[:, 2].min())
            required.append([plank.length, plank.width])
            if not grounded:
                required.append([lowest - slack])
                continue
            required.append([slack - lowest])
            if not sunk:
                required.append([lowest + slack])
        groups = [cutting]
        if margins.detected:
            others = mine[~margins.is_joint]
            groups.append(np.pad(others, ((0, 0), (0, cutting.shape[1] - others.shape[1])),
                                 constant_values=1.0))
        out.append((np.concatenate([np.asarray(r, dtype=float) for r in required]),
                    np.vstack(groups)))
    return out


def _combo_margins(faces: _Faces, rot: np.ndarray, half: np.ndarray,
                   boxes: tuple[np.ndarray, np.ndarray], edge: np.ndarray, face: np.ndarray,
                   f: np.ndarray, g: np.ndarray, slack: float) -> np.ndarray:
    """(C, 18) margins of narrow face f of plank edge resting on broad face g of plank face
    (``rot`` (n, 3, 3), ``half`` (n, 3), ``boxes``: all planks' rotations, half extents
    and bounding boxes): gap + slack, slack - gap, tilt (alignment - cos of the largest
    tilt), height of the edge plank's centre above the face, the overlap of the end face's
    projection with the face along the face's two axes and the projection's two edge
    normals (both ends each, less a round-off slack: faces that only share an edge do not
    overlap), and the overlap of the two bounding boxes within the slack (``analyze`` looks
    only at pairs whose boxes meet: a tilted end can touch a face while its box clears)."""
    normal = faces.broad_normal[face, g]                                   # (C, 3)
    offset = faces.broad_offset[face, g]
    corners = faces.narrow_corners[edge, f]                                # (C, 4, 3)
    gap = ((corners * normal[:, None, :]).sum(axis=2) - offset[:, None]).min(axis=1)
    alignment = -(faces.narrow_normal[edge, f] * normal).sum(axis=1)
    outside = (faces.centers[edge] * normal).sum(axis=1) - offset
    half_f = half[face]
    face_center = faces.centers[face] + half_f[:, 2:3] * normal
    quad = (corners - face_center[:, None, :]) @ rot[face][:, :, :2]       # (C, 4, 2)
    sides = np.stack([quad[:, 1] - quad[:, 0], quad[:, 2] - quad[:, 1]], axis=1)  # (C, 2, 2)
    normals = np.stack([-sides[:, :, 1], sides[:, :, 0]], axis=2)
    length = np.linalg.norm(normals, axis=2, keepdims=True)
    usable = length[:, :, 0] > _GEOMETRY_EPS * _GEOMETRY_EPS
    normals = normals / np.where(length > 0.0, length, 1.0)
    axes = np.concatenate([np.broadcast_to(np.eye(2), (len(edge), 2, 2)), normals], axis=1)
    projected = quad @ np.transpose(axes, (0, 2, 1))                       # (C, 4, 4 axes)
    radius = (np.abs(axes) * half_f[:, None, :2]).sum(axis=2)             # (C, 4 axes)
    overlap = np.concatenate([radius - projected.min(axis=1),
                              projected.max(axis=1) + radius], axis=1) - _GEOMETRY_EPS
    overlap[:, [2, 3, 6, 7]] = np.where(np.tile(usable, 2), overlap[:, [2, 3, 6, 7]], 1.0)
    lo, hi = boxes
    return np.column_stack([gap + slack, slack - gap, alignment - _COS_MAX_TILT, outside,
                            overlap, hi[face] + slack - lo[edge], hi[edge] + slack - lo[face]])


def _cut_margins(rot: np.ndarray, half: np.ndarray, centre: np.ndarray,
                 boxes: tuple[np.ndarray, np.ndarray], pairs: np.ndarray,
                 slack: float) -> np.ndarray:
    """(P, 36) margins whose all being > 0 means the pair's boxes overlap deeper than the
    slack (``interpenetrations``): per separating axis both ends of the overlap of their
    projections beyond the slack (1.0 for degenerate axes), then the bounding boxes'."""
    if len(pairs) == 0:
        return np.zeros((0, 36))
    a, b = pairs[:, 0], pairs[:, 1]
    ra, rb = np.transpose(rot[a], (0, 2, 1)), np.transpose(rot[b], (0, 2, 1))
    crosses = np.cross(ra[:, :, None, :], rb[:, None, :, :]).reshape(-1, 9, 3)
    axes = np.concatenate([ra, rb, crosses], axis=1)                            # (P, 15, 3)
    norms = np.linalg.norm(axes, axis=2)
    usable = norms > 1e-9
    axes = axes / np.where(usable, norms, 1.0)[:, :, None]
    radius = ((np.abs(axes @ rot[a]) * half[a][:, None, :]).sum(axis=2)
              + (np.abs(axes @ rot[b]) * half[b][:, None, :]).sum(axis=2))
    distance = (axes @ (centre[b] - centre[a])[:, :, None])[:, :, 0]
    sat = np.concatenate([radius - slack - distance, radius - slack + distance], axis=1)
    sat = np.where(np.tile(usable, 2), sat, 1.0)
    lo, hi = boxes
    return np.concatenate([sat, hi[b] - slack - lo[a], hi[a] - slack - lo[b]], axis=1)
