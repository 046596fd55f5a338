"""Joints, ground contacts and connectivity of a design (contract section 2).

``analyze`` detects the joints (or checks the listed ones), finds the ground contacts and
the connected components and reports the geometric violations; given an earlier version of
the design it detects only the joints of the planks that changed.  ``follow_many`` measures
a structure's joints again on edited designs (for derivatives).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Plank, tabulate_planks
from furncheck.geometry.boxes import meeting_pairs
from furncheck.geometry.faces import (
    _bears,
    _best_touches,
    _bounding_boxes,
    _box_depths,
    _face_tables,
    _overlapping,
    _Touch,
    _touch_regions,
)
from furncheck.geometry.fit import (
    _apart_message,
    _cut_in_phrase,
    _fmt_len,
    _fmt_point,
    _nearest_touch,
    _plural,
    box_neighbours,
    cut_in_pairs,
    cut_ins,
)
from furncheck.geometry.model import (
    _GEOMETRY_EPS,
    Contact,
    Geometry,
    Joint,
    anchor_contacts,
    anchor_tie,
    corner_contacts,
    support_point,
)
from furncheck.geometry.near import (
    near_miss_violation,
    near_misses,
    sliver,
    sliver_message,
)
from furncheck.result import Violation


def analyze(design: Design, previous: tuple[Design, Geometry] | None = None) -> Geometry:
    """Detect or check joints, find ground contacts and connected components.

    ``previous``: an earlier version of the same design (same planks, in the same order)
    and its analysis; joints between planks that did not change are taken from it instead
    of being detected again (the result is the same, only faster: for design edits).
    """
    violations: list[Violation] = []
    tabulate_planks(design.planks)
    same = _unchanged_planks(design, previous)
    rests: list[Contact] = []
    if design.joints is None:
        joints = _detect_joints(design, _unchanged_joints(design, previous, same))
    else:
        joints, rests = _listed_joints(design, violations)
    return _completed(design, joints, violations, None if same is None else previous[1], same,
                      rests)


def _completed(design: Design, joints: list[Joint], violations: list[Violation],
               earlier: Geometry | None, same: frozenset[str] | None,
               rests: list[Contact] | None = None) -> Geometry:
    """The geometry of a design with these joints (and resting joints' contacts
    ``rests``): its ground and wall contacts, anchors, resting contacts, components, near
    misses (``geometry.near``) and connectivity violations added (``earlier``: the
    analysis of a version in which the planks ``same`` are the same, see ``analyze``).
    A group of planks resting on a grounded one (or carrying one) is grounded too."""
    contacts = _ground_contacts(design, violations, earlier, same) + anchor_contacts(design) \
        + list(rests or ())
    if earlier is not None and [j.planks for j in joints] == [j.planks for j in earlier.joints]:
        components = earlier.components          # they follow from the joined pairs alone
    else:
        components = _components(design, joints)
    plank_has_contact = {c.plank for c in contacts if c.on is None}
    grounded = [any(design.planks[i].id in plank_has_contact for i in comp)
                for comp in components]
    if rests:                                    # grounded through what they rest on
        component_of = {design.planks[i].id: c for c, comp in enumerate(components)
                        for i in comp}
        links = {(component_of[c.plank], component_of[c.on]) for c in rests}
        changed = True
        while changed:
            changed = False
            for a, b in links:
                if grounded[a] != grounded[b]:
                    grounded[a] = grounded[b] = True
                    changed = True
    grounded = tuple(grounded)
    missed = near_misses(design, joints, [c for c in contacts if c.on is None], components,
                         grounded)
    _connectivity_violations(design, joints, components, grounded, violations,
                             {pid for miss in missed if len(miss.planks) == 2
                              for pid in miss.planks})
    violations.extend(near_miss_violation(design, miss) for miss in missed)
    return Geometry(tuple(joints), tuple(contacts), components, grounded, tuple(violations),
                    tuple(missed))


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
            if contact.anchor is not None:      # it rides on its plank (``dofs.apply_dof``)
                point = anchor_tie(design, contact.anchor)
            elif contact.on is not None:        # a resting joint's corner, measured again
                followed.append(_rest_followed(design, contact))
                continue
            else:
                point = support_point(design, contact.wall,
                                      design.planks[index[contact.plank]].corners[contact.corner])
            followed.append(replace(contact, point=point))
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


def meeting_count(design: Design) -> int:
    """How many plank pairs of ``design`` the joint detection compares face by face
    (``_meeting``), for ``check.refuse_overlapping``."""
    return len(_meeting(design, *_bounding_boxes(design.planks)))


def _meeting(design: Design, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """The plank pairs (i < j) whose boxes (``lo``, ``hi``) meet within the design's
    tolerance: those the joint detection compares."""
    return meeting_pairs(lo, hi, design.tolerance + _GEOMETRY_EPS)


def _pairs_to_detect(design: Design, lo: np.ndarray, hi: np.ndarray,
                     known: dict | None) -> tuple[np.ndarray, np.ndarray]:
    """The plank pairs (i < j) whose boxes (``lo``, ``hi``) meet within the tolerance
    (``_meeting``), and whether each must be detected (not both planks among the
    ``known`` unchanged ones)."""
    pairs = _meeting(design, lo, hi)
    if known is None:
        return pairs, np.ones(len(pairs), dtype=bool)
    changed = np.array([plank.id not in known["planks"] for plank in design.planks])
    fresh = changed[pairs[:, 0]] | changed[pairs[:, 1]] if len(pairs) else \
        np.zeros(0, dtype=bool)
    return pairs, fresh


def _boxes_meet(lo_a: np.ndarray, hi_a: np.ndarray, lo_b: np.ndarray, hi_b: np.ndarray,
                slack: float) -> np.ndarray:
    """(A, B): whether box a (lower, upper corners) and box b meet within the slack along
    every axis."""
    return np.all((lo_a[:, None, :] <= hi_b[None, :, :] + slack)
                  & (lo_b[None, :, :] <= hi_a[:, None, :] + slack), axis=2)


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


def _listed_joints(design: Design,
                   violations: list[Violation]) -> tuple[list[Joint], list[Contact]]:
    """The listed joints, measured, and the contacts of the resting ones (``_rest``);
    a listed joint whose planks do not touch, or cut into each other, is disconnected."""
    slack = design.tolerance + _GEOMETRY_EPS
    specs = design.joints or ()
    pairs = np.array([[design.plank_index[a], design.plank_index[b]] for a, b in
                      (spec.planks for spec in specs)], dtype=int).reshape(-1, 2)
    best = _best_touches(design.planks, pairs, slack, keep_deep=True, bearing=0.0)
    joints, rests = [], []
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
        if spec.rests:
            rests.extend(rest_contacts(touch, index))
            continue
        if not _bears(touch):       # a band too narrow for nails (resting joints need none)
            violations.append(Violation("disconnected", name, None,
                                        sliver_message(design, sliver(touch)), line))
            continue
        nails = spec.nails or nail_count(touch.length, design.material.nail_spacing)
        joints.append(_joint_from_touch(touch, spec.planks, nails, key))
    return joints, rests


def _rest_followed(design: Design, contact: Contact) -> Contact:
    """A resting joint's corner on an edited design: its touching region measured again
    (the old corner where the planks no longer touch)."""
    index = design.plank_index
    i, j = index[contact.plank], index[contact.on]
    touch = _best_touches(design.planks, np.array([[min(i, j), max(i, j)]]), slack=np.inf,
                          keep_deep=True, bearing=0.0).get((min(i, j), max(i, j)))
    if touch is None or touch.edge.id != contact.plank:
        return contact
    return rest_contacts(touch, contact.rest)[contact.corner]


def rest_contacts(touch: _Touch, index: int) -> list[Contact]:
    """The contacts of resting joint ``index`` (``Contact.on``): the four corners of the
    region where the edge plank's end face lies on the face plank, point +- L/2 along the
    joint line and +- w/2 across it (w = area / L), in the frame (x, y, n) of the touch."""
    x, y, n = touch.frame[:, 0], touch.frame[:, 1], touch.frame[:, 2]
    half_length = 0.5 * touch.length
    half_width = 0.5 * touch.area / max(touch.length, 1e-12)
    frame = np.array([x, y, n])
    return [Contact(touch.edge.id, touch.point + sx * half_width * x + sy * half_length * y,
                    k, None, None, touch.face.id, index, frame)
            for k, (sx, sy) in enumerate(((-1, -1), (1, -1), (-1, 1), (1, 1)))]


def _joint_from_touch(touch: _Touch, planks: tuple[str, str], nails: int, key: str) -> Joint:
    return Joint(planks=tuple(planks), face=touch.face.id, edge=touch.edge.id,
                 point=touch.point, length=touch.length, nails=nails, frame=touch.frame,
                 edge_thickness=touch.edge.thickness, edge_face=touch.edge_face,
                 face_side=touch.face_side, key=key)


# --- ground, components -----------------------------------------------------------------------

def _ground_contacts(design: Design, violations: list[Violation],
                     earlier: Geometry | None = None,
                     same: frozenset[str] | None = None) -> list[Contact]:
    """Corners within tolerance of the ground (z) or of a wall touch it; those below the
    ground or behind a wall by more than tolerance penetrate it (``corner_contacts``).
    The contacts and penetrations of the planks ``same`` are taken from ``earlier``."""
    slack = design.tolerance + _GEOMETRY_EPS
    contacts: list[Contact] = []
    reused: dict[str, list] = {}
    if earlier is not None:
        for contact in earlier.contacts:
            if contact.anchor is None and contact.on is None:
                reused.setdefault(contact.plank, []).append(contact)
        for violation in earlier.violations:
            if violation.kind == "penetration":
                reused.setdefault(violation.where, []).append(violation)
    for index, plank in enumerate(design.planks):
        if same is not None and plank.id in same:
            for item in reused.get(plank.id, ()):
                (contacts if isinstance(item, Contact) else violations).append(item)
            continue
        touching, sunk = corner_contacts(design, plank, slack)
        contacts.extend(touching)
        for wall, corner, depth in sunk:
            where = "below the ground" if wall is None else f"behind wall {wall}"
            violations.append(Violation(
                "penetration", plank.id, None,
                f"corner at {_fmt_point(plank.corners[corner], design)} is "
                f"{_fmt_len(depth, design)} {where} (tolerance "
                f"{_fmt_len(design.tolerance, design)})",
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


def interpenetrations(design: Design) -> list[tuple[str, str, float]]:
    """Plank pairs whose boxes overlap deeper than the tolerance: (id, id, depth m).

    Separating-axis test of two oriented boxes over their 15 candidate axes; the depth is
    the smallest overlap of their projections.  Planks meeting at a joint only touch, so
    their depth is ~0.  A design's own are ``disconnected`` (``drawn_through``); an edit
    that has any is refused (``edit_check``).
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


def drawn_through(design: Design, geometry: Geometry) -> list[Violation]:
    """Two planks drawn through each other, deeper than the tolerance (``interpenetrations``:
    a board pasted twice in one place, a shelf drawn into its side), form no joint: such a
    pair is ``disconnected`` (as the contract has a listed joint whose planks
    interpenetrate), each plank once, with the first plank in the file that it is drawn
    through (a board pasted k times: k - 1 lines, not k (k - 1) / 2); unless one of the
    ``geometry``'s violations names the pair already (a missed joint's overlap), or one of
    them is joined to nothing and its end cuts into the other (``cut_in_pairs``: its
    message says so).  Asked of a design being checked (``check.check_design``,
    ``check.is_valid``), not part of ``analyze``: an edit that cuts into a plank is refused
    as such (``edit_check``), and the geometry of an edit that keeps the design's joints is
    the design's."""
    index = design.plank_index
    found = []
    for a, b, depth in _drawn_through_pairs(design, geometry):
        touch = _nearest_touch(design, index[a], index[b])
        if touch is not None and touch.gap < 0.0:   # an end sunk into the other's face
            told = (f"an end of {touch.edge.id} runs {_fmt_len(-touch.gap, design)} past "
                    f"the face of {touch.face.id} it meets (tolerance "
                    f"{_fmt_len(design.tolerance, design)}): no joint forms; draw it back "
                    "onto that face (a board cut too long), or move it out")
        else:
            told = (f"{a} and {b} are drawn through each other, {_fmt_len(depth, design)} "
                    f"deep (tolerance {_fmt_len(design.tolerance, design)}): no joint "
                    "forms; move one out of the other, or remove one if it is drawn twice")
        found.append(Violation("disconnected", f"{a}/{b}", None, told,
                               design.line_of(f"planks[{index[b]}]")))
    return found


def _drawn_through_pairs(design: Design, geometry: Geometry) -> list[tuple[str, str, float]]:
    """``drawn_through``'s pairs (a, b, depth m), a before b in the file, in the order of
    b: each plank with the first plank in the file it is drawn through, those the
    geometry's violations tell already left out."""
    through = interpenetrations(design)
    if not through:
        return []
    named = {v.where for v in geometry.violations if v.kind == "disconnected"}
    cut = cut_in_pairs(design, geometry, {p for a, b, _ in through for p in (a, b)})
    index = design.plank_index
    first: dict[str, tuple[str, float]] = {}
    for a, b, depth in through:
        if index[a] > index[b]:
            a, b = b, a
        if f"{a}/{b}" in named or f"{b}/{a}" in named or (a, b) in cut or (b, a) in cut:
            continue
        if b not in first or index[a] < index[first[b][0]]:
            first[b] = (a, depth)
    return [(first[b][0], b, first[b][1]) for b in sorted(first, key=index.__getitem__)]


def drawn_through_closing(design: Design, geometry: Geometry) -> set[tuple[str, str]]:
    """(face, edge) plank ids of the joints that the pairs drawn through each other
    (``drawn_through``) would form where an end of one cuts into the other's face: a leg
    drawn 20 mm too long, up through the seat it stands under (joined to a rung, so not
    to nothing).  The joints a repair that draws the end back may add, as it may close a
    near miss (``cut_in_pairs`` for a plank joined to nothing)."""
    closing = set()
    for a, b, _ in _drawn_through_pairs(design, geometry):
        a, b = design.plank_index[a], design.plank_index[b]
        for edge, face in ((a, b), (b, a)):
            if cut_ins(design, edge, np.array([face])):
                closing.add((design.planks[face].id, design.planks[edge].id))
    return closing


def _connectivity_violations(design: Design, joints: list[Joint],
                             components: tuple[tuple[int, ...], ...],
                             grounded: tuple[bool, ...], violations: list[Violation],
                             nearly_joined: set[str]) -> None:
    """A plank joined to nothing (unless a missed joint, ``nearly_joined``, says why) is
    ``disconnected``; a group touching the ground nowhere is ``floating``."""
    if len(design.planks) > 1:
        joined = {pid for joint in joints for pid in joint.planks}
        listed = {pid for spec in design.joints or () for pid in spec.planks}
        neighbours = None       # whose boxes meet each plank's, once, where one needs them
        for index, plank in enumerate(design.planks):
            if plank.id not in joined and plank.id not in listed and \
                    plank.id not in nearly_joined:
                if neighbours is None:
                    neighbours = box_neighbours(design)
                violations.append(Violation(
                    "disconnected", plank.id, None,
                    "plank is joined to no other plank (no end face rests on a neighbour's "
                    "face, and no neighbour's end face rests on it)"
                    + _cut_in_phrase(design, index, neighbours[index]),
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
