"""Elastic planks (contract section 3a): the statics model of ``model: elastic``.

Each plank is a Timoshenko beam (``beams``) along its longer in-plane axis, cut into
elements at nodes on that axis wherever a joint, a ground contact or a load acts (at the
projection of its point), at the plank's ends and centre, and at least every
1 / BEAM_SEGMENTS of its length.  What acts off the axis is tied to its node by a rigid
offset (``point_maps``, ``joint_deviation_blocks``): a leg under a table top's corner
twists the top.  A nail joint is a spring between its two planks' nodes, from its nail
row (``beams.joint_springs``); ground contacts are stiff unilateral springs with friction
anchors (ELASTIC_CONTACT_STIFFNESS).  The model is a ``StaticsModel`` like the rigid
one: the same mixed system, with the beams' stiffness K_b in its plank block, and the
same contact loop.  Self-weight and spread loads act along the beams as consistent nodal
loads (``elastic_forces``).  After the solve, ``bending.plank_results`` gives each
plank's sag and stress.

By job: this module places the nodes and builds a model; ``elements`` holds the beam
elements, their stiffness and their loads; ``templated`` builds the models of small edits
on a template's nodes (the force sensitivity's stepped designs).
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass
from functools import partial
from types import SimpleNamespace
from typing import Any, NamedTuple

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Plank
from furncheck.geometry import Geometry, follow_many
from furncheck.statics.beams import (
    along_width,
    beam_frame,
    beam_length_width,
    nail_row_parts,
    part_points,
)
from furncheck.statics.elements import beam_elements, nodal_loads, read_only, weights_per_length
from furncheck.statics.model import StaticsModel, grounded_parts
from furncheck.statics.offsets import (
    anchored_contacts,
    contact_frames,
    in_contact_frames,
    joint_deviation_blocks,
    point_maps,
    rest_maps,
)
from furncheck.statics.stations import (
    station_places,
    station_segments,
    support_edges,
    support_stations,
)
from furncheck.statics.templated import TOPOLOGY_CACHE, Attachments, built_on


def _plank_nodes(k: int, half: float, attachments: list[tuple[float, tuple]],
                 stations: int = 0) -> list[tuple]:
    """The nodes of local plank k, a beam of half length ``half``, in order along it, each
    as its origin: k and the attachment keys it serves (``attachments``: (s, key),
    s the attachment's position along the axis; those within NODE_MERGE of each other, or
    a tenth of a grid step on a short plank, share a node at their mean; the distance is
    compared with NODE_MERGE_ROUNDOFF to spare, so that attachments exactly a millimetre
    apart share one whatever the last bits of their positions), with the ends
    ('end', k, -1 / 1) and the centre ('centre', k), or ('grid', k, fraction) for the grid
    of BEAM_SEGMENTS where no node is within a quarter of its step (fraction 0 .. 1 from
    the -e1 end).  Consecutive nodes are apart (a node's mean lies within its group, and
    each group starts past the last one's attachments), though they may be nearer than
    the merge distance where a group's attachments spread over it.  ``stations``: for a
    plank the floor or a wall holds along its length, the parts of its grid of support
    stations (``stations.station_segments``), ('station', k, fraction) where no node is
    within a quarter of its step, placed before the grid of BEAM_SEGMENTS."""
    step = 2.0 * half / tol.BEAM_SEGMENTS
    merge = min(tol.NODE_MERGE, 0.1 * step) + tol.NODE_MERGE_ROUNDOFF
    marks = [(-half, ("end", k, -1)), (0.0, ("centre", k)), (half, ("end", k, 1))]
    required = sorted(((min(max(s, -half), half), key) for s, key in [*attachments, *marks]),
                      key=lambda item: item[0])
    groups: list[list] = []
    for s, key in required:
        if groups and s - groups[-1][0] <= merge:
            groups[-1][1].append(key)
            groups[-1][2].append(s)
        else:
            groups.append([s, [key], [s]])
    nodes = [(sum(positions) / len(positions), tuple(keys)) for _, keys, positions in groups]
    placed = [s for s, _ in nodes]
    for kind, parts in (("station", stations), ("grid", tol.BEAM_SEGMENTS)):
        spacing = 2.0 * half / max(parts, 1)
        for i in range(1, parts):
            s = -half + i * spacing
            if min(abs(p - s) for p in placed) > 0.25 * spacing:
                nodes.append((s, ((kind, k, i / parts),)))
                placed.append(s)
    return [(k, *origin) for _, origin in sorted(nodes, key=lambda item: item[0])]


def _crosswise(design: Design, geometry: Geometry, planks: list[Plank], joints: list[int],
               contacts: list[int], held: dict | None = None) -> tuple[bool, ...]:
    """Per plank, whether its beam runs along its local y: its longer side (contract 3a);
    a square plank (sides within the design's tolerance) along the side over which what
    holds it (its joints' and contacts' points) is spread the most, where that ties (by
    NODE_MERGE) across its joint lines (summed |line . axis| x length over its joints: a
    square shelf nailed by one edge spans away from that edge), and where that ties too
    along the side its loads lie farthest out on (every case's point loads: a square
    board on its corners loaded off its centre), so that describing it turned by 90
    degrees changes nothing; the local x where all of these tie.  A plank nailed along both
    its longer edges to panels spans across (``_spans_across``).  ``held``: the joints'
    ``_joint_lines``, where the caller has them."""
    if held is None:
        held = _joint_lines(design, geometry, joints)
    points = {p.id: [point for point, _, _ in held.get(p.id, ())] for p in planks}
    lines = {p.id: [line for _, line, _ in held.get(p.id, ())] for p in planks}
    for c in contacts:
        points[geometry.contacts[c].plank].append(geometry.contacts[c].point)
    grounded = {geometry.contacts[c].plank for c in contacts if geometry.contacts[c].on_floor}
    margin = tol.NODE_MERGE + tol.NODE_MERGE_ROUNDOFF
    out = []
    for plank in planks:
        if abs(plank.length - plank.width) > design.tolerance or not points[plank.id]:
            spans = plank.id not in grounded and _spans_across(plank, held.get(plank.id, []))
            out.append(along_width(plank) != spans)
            continue
        local = plank.to_local(np.array(points[plank.id]))
        spread = local.max(axis=0) - local.min(axis=0)
        if abs(spread[1] - spread[0]) > margin:
            out.append(bool(spread[1] > spread[0]))
            continue
        along = np.abs(np.array(lines[plank.id]).reshape(-1, 3) @ plank.rotation_matrix[:, :2])
        across_x, across_y = along.sum(axis=0)      # joint lines along x hold a span along y
        if abs(across_x - across_y) > margin:
            out.append(bool(across_x > across_y))
            continue
        loaded = [load.point for case in design.load_cases for load in case.loads
                  if load.plank == plank.id and load.point is not None and not load.spread]
        reach = np.abs(plank.to_local(np.array(loaded))[:, :2]).max(axis=0) if loaded \
            else np.zeros(2)
        out.append(bool(reach[1] > reach[0]) if abs(reach[1] - reach[0]) > margin
                   else along_width(plank))
    return tuple(out)


class BeamLayout(NamedTuple):
    """Where the elastic model lays each plank's one beam (``beam_layout``).

    crosswise  : per plank id, whether its beam runs along its local y (``_crosswise``);
                 an edit turns a plank's beam where this changes (in the plank's own
                 frame: an edit that turns the plank itself turns its beam with it)
    across     : the planks that span across by ``_spans_across``, their beam along their
                 shorter side
    candidates : the planks not standing on the floor with joint lines along one of their
                 sides on both sides of it, whoever holds them (``_held_along``): where
                 those lines come to cover their edges, held straight, they span across,
                 so an edit may turn their beam other than at the square
    held_along : the candidates whose beam runs along such lines, held straight and
                 covering SPAN_ACROSS_COVER of its length on both sides of it: such a
                 beam cannot bend along its length and reads almost none of the plank's
                 bending, which happens across it, as a plate's (a top nailed all round;
                 a seat whose legs' rows run along its beam, past square)
    """

    crosswise: dict[str, bool]
    across: frozenset[str]
    candidates: frozenset[str]
    held_along: frozenset[str]


def beam_layout(design: Design, geometry, planks: list[str] | None = None) -> BeamLayout:
    """The ``BeamLayout`` of the design's planks (or of ``planks``, by id, whose joints and
    whose neighbours' floor corners ``geometry`` holds: ``plank_geometry``), for whoever
    asks whether an edit turns a plank's beam (``ranges.notes.turn_reasons``,
    ``suggest.score``)."""
    joints = list(range(len(geometry.joints)))
    held = _joint_lines(design, geometry, joints)
    chosen = list(design.planks) if planks is None else [design.plank(p) for p in planks]
    mine = {plank.id for plank in chosen}
    flags = _crosswise(design, geometry, chosen, joints,
                       [c for c, contact in enumerate(geometry.contacts)
                        if contact.plank in mine], held)
    grounded = {contact.plank for contact in geometry.contacts if contact.on_floor}
    crosswise, across, candidates, held_along = {}, set(), set(), set()
    for plank, along_y in zip(chosen, flags):
        crosswise[plank.id] = along_y
        lines = held.get(plank.id)
        if plank.id in grounded or not lines:
            continue
        if any(_held_along(plank, lines, axis, straight_only=False) is not None
               for axis in (0, 1)):
            candidates.add(plank.id)
            if abs(plank.length - plank.width) > design.tolerance \
                    and along_y != along_width(plank):
                across.add(plank.id)
            axis = 1 if along_y else 0
            found = _held_along(plank, lines, axis)
            if found is not None and _covers(plank, axis, found[0]):
                held_along.add(plank.id)
    return BeamLayout(crosswise, frozenset(across), frozenset(candidates),
                      frozenset(held_along))


def plank_geometry(geometry: Geometry, edited: Design, planks) -> SimpleNamespace:
    """The joints of ``planks`` (ids) and the corners of the planks they are nailed to,
    followed from ``geometry`` onto ``edited`` (``geometry.follow_many``: the joints they
    have, measured again; one that the edit would open or close is not looked for), as
    a geometry for ``beam_layout`` of those planks: what an edit does to their beams,
    on a 2,000-plank wall as on a stool, without analysing the whole design."""
    wanted = set(planks)
    joints = [j for j, joint in enumerate(geometry.joints) if wanted.intersection(joint.planks)]
    near = wanted | {p for j in joints for p in geometry.joints[j].planks}
    corners = [c for c, contact in enumerate(geometry.contacts) if contact.plank in near]
    (followed, contacts), = follow_many(geometry, [(edited, joints, corners)])
    return SimpleNamespace(joints=tuple(followed), contacts=tuple(contacts))


def _joint_lines(design: Design, geometry,
                 joints: list[int]) -> dict[str, list[tuple[tuple, tuple, Any]]]:
    """Per plank id, its joints' (point, line: length x direction, both as floats, and
    whether the plank at the other end holds the line straight against the plank's
    bending across it, ``_holds_straight``, as a call made when asked, with the plank's
    section width and span across the line: most planks never ask)."""
    feet = floor_feet(geometry)
    held: dict[str, list] = {}
    for j in joints:
        joint = geometry.joints[j]
        direction = tuple(joint.frame[:, 1].tolist())
        length = joint.length
        line = (length * direction[0], length * direction[1], length * direction[2])
        point = tuple(joint.point.tolist())
        for plank_id, partner in zip(joint.planks, reversed(joint.planks)):
            straight = partial(_holds_straight, design, plank_id, partner,
                               feet.get(partner, ()), direction, length)
            held.setdefault(plank_id, []).append((point, line, straight))
    return held


def floor_feet(geometry) -> dict[str, list]:
    """Per plank id, the points where it stands on the floor (its floor contacts)."""
    feet: dict[str, list] = {}
    for contact in geometry.contacts:
        if contact.on_floor:
            feet.setdefault(contact.plank, []).append(contact.point)
    return feet


def hung_planks(joints: list, contacts: list,
                loaded: Collection[str] = ()) -> dict[str, tuple[int, tuple[int, ...]]]:
    """Per plank that one of ``joints`` alone holds, (that joint's index, the indices of
    its joints to its leaves): the planks nailed to it and to nothing else, carrying no
    load (of ``loaded``, the ids of the loaded planks), a lip or an upstand along its
    edge, which hang on it.  A plank so held stands neither on the floor nor rests on
    or under another plank among ``contacts``, nor is tied to a wall (a wall's contact may
    be its, not an anchor's tie, which holds it where it is): a shelf nailed by its back
    edge onto a rail or cleat, a flap, a board on a single rail.  Where it hangs on the
    joint's line as a plate (``plate_supports.hung_plate_segments``: loaded across its
    face, the row along its beam over a quarter of it, the plank wider than 8
    thicknesses), the plate check reads its bending across its width, its leaves' rows
    stiffeners of that plate and their weights loads on it, and the row is cut into
    parts, whatever the plank's width (``joint_part_counts``; where the other plank
    keeps the row whole, the plate's reading is the plank's, ``plates.whole_rows_hung``)."""
    mine: dict[str, list[int]] = {}
    for j, joint in enumerate(joints):
        for plank_id in joint.planks:
            mine.setdefault(plank_id, []).append(j)
    held = {plank_id for contact in contacts if contact.wall is None or contact.anchor is not None
            for plank_id in (contact.plank, contact.on) if plank_id is not None}

    def leaf(plank_id: str) -> bool:
        return len(mine[plank_id]) == 1 and plank_id not in held and plank_id not in loaded

    found = {}
    for plank_id, rows in mine.items():
        if plank_id in held:
            continue
        partners = [(j, next(p for p in joints[j].planks if p != plank_id)) for j in rows]
        holding = [j for j, partner in partners if not leaf(partner)]
        if len(holding) == 1:
            found[plank_id] = (holding[0], tuple(j for j in rows if j != holding[0]))
    return found


def model_hung_planks(model: StaticsModel) -> dict[str, tuple[int, tuple[int, ...]]]:
    """``hung_planks`` of an elastic model (its joints, its contacts, its design's loaded
    planks: indices into ``model.joints``), found once and kept in ``model.plank_cache``
    (``build_elastic_model`` keeps the ones it cut the rows by)."""
    cached = model.plank_cache.get("hung_planks")
    if cached is None:
        geometry = model.geometry
        cached = model.plank_cache["hung_planks"] = hung_planks(
            [geometry.joints[j] for j in model.joints],
            [geometry.contacts[c] for c in model.contacts], loaded_planks(model.design))
    return cached


def loaded_planks(design: Design) -> set[str]:
    """The ids of the planks that some load case loads."""
    return {load.plank for case in design.load_cases for load in case.loads}


def stands_along(feet, direction, length: float) -> bool:
    """Whether floor corners ``feet`` spread along ``direction`` (unit) over at least
    SPAN_ACROSS_STANDING of a line ``length`` long (a millimetre, NODE_MERGE, to spare):
    the plank standing on them holds that line up and straight."""
    if len(feet) < 2:
        return False
    dx, dy, dz = (float(c) for c in direction)
    reach = [dx * p[0] + dy * p[1] + dz * p[2] for p in feet]
    return max(reach) - min(reach) + tol.NODE_MERGE_ROUNDOFF \
        >= tol.SPAN_ACROSS_STANDING * length - tol.NODE_MERGE


def depth_across(plank: Plank, direction) -> tuple[float, int]:
    """(m, 0 or 1): the plank's depth across a line along ``direction`` (unit) in its
    own plane, and which of its local axes (0: x, 1: y) that depth runs along: a line
    more along its x has its width across it."""
    dx, dy, dz = (float(c) for c in direction)
    (ax, ay, az), (bx, by, bz), _ = plank.axes
    along_x = abs(dx * ax + dy * ay + dz * az) >= abs(dx * bx + dy * by + dz * bz)
    return (plank.width, 1) if along_x else (plank.length, 0)


def _holds_straight(design: Design, plank_id: str, partner_id: str, feet,
                    direction: tuple, length: float, width: float, span: float) -> bool:
    """Whether plank ``partner_id`` holds a joint line (``direction``, unit, and
    ``length``) straight along it while plank ``plank_id``, nailed along it, bends across,
    over ``span``, with a section ``width`` wide: it stands on the floor along the line
    (its floor corners ``feet`` spread along it over at least SPAN_ACROSS_STANDING of the
    line's length), or, bending in its own plane over the line's length, it gives no more
    than SPAN_ACROSS_STIFFNESS times what the plank gives across its span under the same
    load: L^3 / (E_p t_p h^3) against s^3 / (E w t^3) (h its depth across the line).  A
    nightstand's 550 mm side holds its 400 mm line about 2,600 times stiffer than the
    388 mm top bends across, a 190 mm one hung on a wall about 110 times, a 150 mm one
    on a base board about 50 times; a 100 mm apron under a 1200 mm bench seat 300 mm
    deep gives fourteen times more than the seat across: a rail, which bends with what
    is nailed along it."""
    if length <= 0.0 or span <= 0.0:
        return False
    if stands_along(feet, direction, length):
        return True
    partner, plank = design.plank(partner_id), design.plank(plank_id)
    depth = depth_across(partner, direction)[0]
    gives = length ** 3 / (design.material_of(partner).elastic_modulus * partner.thickness
                           * depth ** 3)
    allowed = tol.SPAN_ACROSS_STIFFNESS * span ** 3 / (
        design.material_of(plank).elastic_modulus * plank.thickness ** 3 * width)
    return gives <= allowed * (1.0 + tol.RATE_ROUNDOFF)     # equal to the last bits: holds


def _spans_across(plank: Plank, held: list[tuple[tuple, tuple, Any]]) -> bool:
    """Whether a plank that does not stand on the floor spans across its width, not along
    its length (contract 3a takes the longer in-plane axis; this is its one exception).
    It does where both its longer edges are nailed, along most of their length, to planks
    that hold the joint lines straight, and it is not nailed all round: on each side of
    its axis the joint lines along its longer side held straight (``held``: each joint's
    point, its line and whether the plank at its other end holds it straight,
    ``_joint_lines``, ``_holds_straight``) cover at least SPAN_ACROSS_COVER of that side
    (their union), and its joint lines across it held straight add up to less than
    SPAN_ACROSS_CROSSING times its shorter side (a back along one short edge too, not a
    rim all round).  Both shares are compared with a millimetre (NODE_MERGE) to spare,
    and that with NODE_MERGE_ROUNDOFF more, so that a design drawn with round numbers
    (sides covering exactly the share, or the share less the millimetre) does not sit on
    the edge of the rule, which a rigid motion's round-off could tip.

    A nightstand's top between its sides, a cabinet's shelf deeper than it is wide, a
    hanger held along its top and bottom edges: along its length such a beam is held all
    along by the panels and cannot bend, though the plank bends across, between them (a
    400 mm deep top over a 388 mm span then sags as a 380 mm deep one does, and the
    sides' nails share the load along their rows).  A seat on two long aprons, or a
    T-beam's flange, keeps its length: the rails bend with it along the span, and the
    composite beam is what carries the load.  So does a plank nailed by one long edge
    (a bracket under a shelf, a shelf on a back panel alone: which of its joints holds
    it and which loads it, the joints do not say), and one held along less of its edges
    (a top on narrow sides: the rest of it overhangs along its length)."""
    longer, shorter = (1, 0) if along_width(plank) else (0, 1)
    sizes = (plank.length, plank.width)
    found = _held_along(plank, held, longer)
    if found is None:
        return False
    covered, crossing = found
    rim = tol.SPAN_ACROSS_CROSSING * sizes[shorter] - tol.NODE_MERGE
    return _covers(plank, longer, covered) and crossing - tol.NODE_MERGE_ROUNDOFF < rim


def _covers(plank: Plank, axis: int, covered: tuple[float, float]) -> bool:
    """Whether joint lines covering ``covered`` (m, on each side) of the plank's side along
    its local ``axis`` cover SPAN_ACROSS_COVER of it on both sides, a millimetre
    (NODE_MERGE) to spare, and the last bits (NODE_MERGE_ROUNDOFF): ``_spans_across``'s
    cover, and ``BeamLayout.held_along``'s."""
    need = tol.SPAN_ACROSS_COVER * (plank.length, plank.width)[axis] - tol.NODE_MERGE
    return min(covered) + tol.NODE_MERGE_ROUNDOFF >= need


def _held_along(plank: Plank, held: list[tuple[tuple, tuple, Any]],
                axis: int, straight_only: bool = True
                ) -> tuple[tuple[float, float], float] | None:
    """((m, m), m): how much of the plank's length along its local ``axis`` (0: x, 1: y)
    its joint lines along that axis cover on each side of it (the union of their spans),
    and the length of its lines across it, each counting only where its other plank
    holds it straight (``_holds_straight``: a panel, not a rail), unless not
    ``straight_only`` (then every line along it counts, and none across); None where the
    lines along it lie on one side of it only (or on the axis: a line along the middle
    holds no side)."""
    other = 1 - axis
    axes = plank.axes[:2]                       # plain floats: every model build asks
    centre = plank.center
    sizes = (plank.length, plank.width)
    half = 0.5 * sizes[axis]
    spans: tuple[list, list] = ([], [])
    crossing = 0.0
    for point, line, straight in held:
        lx, ly, lz = line
        parts = [abs(lx * a[0] + ly * a[1] + lz * a[2]) for a in axes]
        if parts[axis] <= parts[other]:     # across: a rim where it holds, not a rail
            if straight_only and straight(sizes[other], sizes[axis]):
                crossing += parts[other]
            continue
        if straight_only and not straight(sizes[axis], sizes[other]):
            continue
        rx, ry, rz = (p - c for p, c in zip(point, centre))
        local = [rx * a[0] + ry * a[1] + rz * a[2] for a in axes]
        if abs(local[other]) <= tol.NODE_MERGE:
            continue
        spans[int(local[other] > 0.0)].append((max(local[axis] - 0.5 * parts[axis], -half),
                                               min(local[axis] + 0.5 * parts[axis], half)))
    if not (spans[0] and spans[1]):
        return None
    return (_union_length(spans[0]), _union_length(spans[1])), crossing


def _union_length(spans: list[tuple[float, float]]) -> float:
    """m: the length of the union of intervals (low, high)."""
    total, reach = 0.0, -np.inf
    for low, high in sorted(spans):
        if high > reach:
            total += high - max(low, reach)
            reach = high
    return total


def joint_part_counts(design: Design, joints: list, local: dict[int, int], frames: list,
                      sizes: np.ndarray, hung: dict | None = None) -> np.ndarray:
    """(nJ,) into how many parts each joint's nail row is cut (``beams.nail_row_parts``):
    the most of its two planks' ``L |y . e1| / part`` (its reach along that plank's beam,
    e1, over part = the least of JOINT_PART_LENGTH and JOINT_PART_SHARE of that beam's
    length), rounded to the nearest whole number, at most n / 2 of its n nails, at least
    1.  A joint across both beams (a shelf's end nailed through a side) stays whole.  So
    does one where a plank whose beam the row runs along (one that would cut it) would
    bend across its width under what the row holds it against, as a plate, which the
    rigid arms from its beam to the parts would hold straight: the row off the plank's
    middle (outside JOINT_PART_CORE of its half width), and the plank wider than
    JOINT_PART_NARROW thicknesses if it is the face plank (the row's force acts across
    its face) or lies level (JOINT_PART_LEVEL: its own load acts across its face: a
    shelf nailed by its back edge, a shelf deeper than it is wide held by its ends),
    JOINT_PART_EDGE_NARROW if it is an upright edge plank (the row's moment about its
    line acts across its face: a coffee table's end panel under the top; a rail on edge
    under a shelf is held along it), unless that plank is one of ``hung``
    (``hung_planks``: this row alone holds it, but for its leaves) and hangs on it as a
    plate, whose check
    reads its bending across its width (``plate_supports.hung_plate_segments``).
    ``sizes`` (nP, 2): each local plank's beam length and section width.  Reaches and
    widths are compared with PART_ROUNDING to spare, so that a joint exactly on a half
    part, or a plank exactly on a limit, is taken alike whatever the last bits of a
    turned design's numbers."""
    if not joints:
        return np.ones(0, dtype=int)
    owners = [design.planks[design.plank_index[plank_id]]
              for joint in joints for plank_id in joint.planks]
    sides = np.array([local[design.plank_index[plank.id]] for plank in owners],
                     dtype=int).reshape(-1, 2)                                 # (nJ, 2)
    axes = np.array(frames, dtype=float).reshape(-1, 3, 3)[sides]              # (nJ, 2, 3, 3)
    lines = np.array([joint.frame[:, 1] for joint in joints], dtype=float)     # (nJ, 3)
    lengths = np.array([joint.length for joint in joints], dtype=float)
    points = np.array([joint.point for joint in joints], dtype=float)
    centres = np.array([plank.center_array for plank in owners], dtype=float).reshape(-1, 2, 3)
    thickness = np.array([plank.thickness for plank in owners], dtype=float).reshape(-1, 2)
    length, width = sizes[sides, 0], sizes[sides, 1]                           # (nJ, 2)
    along = np.abs(np.einsum("ji,jsi->js", lines, axes[:, :, :, 0]))
    part = np.minimum(tol.JOINT_PART_LENGTH, tol.JOINT_PART_SHARE * length)
    cut = np.floor(lengths[:, None] * along / part + 0.5 + PART_ROUNDING).astype(int)
    offset = np.abs(np.einsum("jsi,jsi->js", points[:, None, :] - centres, axes[:, :, :, 1]))
    face = np.array([[plank_id == joint.face for plank_id in joint.planks]
                     for joint in joints], dtype=bool)
    level = np.abs(axes[:, :, 2, 2]) >= tol.JOINT_PART_LEVEL      # face normal's z
    narrow = np.where(face | level, tol.JOINT_PART_NARROW, tol.JOINT_PART_EDGE_NARROW)
    alone = np.zeros((len(joints), 2), dtype=bool)
    if hung:
        from furncheck.statics.plate_supports import hung_plate_segments

        for j, joint in enumerate(joints):
            for s, plank in enumerate(owners[2 * j:2 * j + 2]):
                if plank.id in hung and hung[plank.id][0] == j:
                    crosswise = abs(float(axes[j, s, :, 0] @ plank.rotation_matrix[:, 1])) > 0.5
                    alone[j, s] = hung_plate_segments(design, plank, joint,
                                                      crosswise) is not None
    plate = (width > narrow * thickness * (1.0 + PART_ROUNDING)) \
        & (offset > tol.JOINT_PART_CORE * 0.5 * width * (1.0 + PART_ROUNDING)) & ~alone
    nails = np.array([joint.nails for joint in joints], dtype=int)
    counts = np.maximum(np.minimum(cut.max(axis=1), nails // 2), 1)
    return np.where(((cut > 1) & plate).any(axis=1), 1, counts)


PART_ROUNDING = 1e-9
"""Parts of a joint's reach spared in rounding it to whole parts (``joint_part_counts``)."""


@dataclass(frozen=True, eq=False)    # holds arrays: no == by value
class _NodeLayout:
    """Which attachments each node serves, as arrays (from the nodes' origins: a local
    plank and the keys it serves, ``_plank_nodes``), so that the nodes of a model built on
    a template are placed without going through the keys again.

    node_plank : (nN,) local plank of each node
    key_node, key_plank : (m,) node and local plank of each key of every origin, in order
    key_row    : (m,) the attachment row of a key (its place in the build's attachment
                 list: joints' two sides, contacts, loads), -1 for an end, centre or grid
    key_scale  : (m,) where an end, centre or grid key sits, in half lengths from the centre
    counts     : (nN,) keys per node
    row_node   : (nA,) the node of each attachment row
    centre_node : (nP,) the node at each plank's centre
    """

    node_plank: np.ndarray
    key_node: np.ndarray
    key_plank: np.ndarray
    key_row: np.ndarray
    key_scale: np.ndarray
    counts: np.ndarray
    row_node: np.ndarray
    centre_node: np.ndarray

    @classmethod
    def of(cls, origins: tuple, keys: list[tuple], owners: list[int]) -> _NodeLayout:
        row_of = {key: row for row, key in enumerate(keys)}
        key_node, key_plank, key_row, key_scale = [], [], [], []
        centre_node = {}
        for node, (plank, *served) in enumerate(origins):
            for key in served:
                row = row_of.get(key, -1)
                key_node.append(node)
                key_plank.append(owners[row] if row >= 0 else plank)
                key_row.append(row)
                key_scale.append(float(key[2]) if key[0] == "end" else
                                 2.0 * key[2] - 1.0 if key[0] in ("grid", "station")
                                 else 0.0)
                if key[0] == "centre":
                    centre_node[plank] = node
        key_node = np.array(key_node, dtype=int)
        key_row = np.array(key_row, dtype=int)
        row_node = np.zeros(len(keys), dtype=int)
        attached = key_row >= 0
        row_node[key_row[attached]] = key_node[attached]
        return cls(node_plank=np.array([origin[0] for origin in origins], dtype=int),
                   key_node=key_node, key_plank=np.array(key_plank, dtype=int),
                   key_row=key_row, key_scale=np.array(key_scale, dtype=float),
                   counts=np.bincount(key_node, minlength=len(origins)),
                   row_node=row_node,
                   centre_node=np.array([centre_node[k] for k in range(len(centre_node))],
                                        dtype=int))

    def positions(self, along: np.ndarray, halves: np.ndarray) -> np.ndarray:
        """(nN,) m: each node's place along its plank's axis, the mean of what it serves:
        an attachment at its place ``along`` (nA,) kept on the plank (within +-half its
        length, ``halves`` (nP,)), an end, the centre or a grid point where it is."""
        half = halves[self.key_plank]
        attached = self.key_row >= 0
        values = self.key_scale * half
        values[attached] = np.minimum(np.maximum(along[self.key_row[attached]],
                                                 -half[attached]), half[attached])
        return np.bincount(self.key_node, weights=values, minlength=len(self.counts)) \
            / self.counts


def build_elastic_model(design: Design, geometry: Geometry,
                        template: StaticsModel | None = None) -> StaticsModel:
    """The elastic ``StaticsModel`` of the grounded components (see the module docstring).

    ``template``: a model of the same design before a small edit (the same joints,
    contacts and loads): its nodes are kept, each at the new place of what it serves, so
    that the two models' unknowns correspond (the force sensitivity differences them)."""
    if template is not None and "attachments" in template.plank_cache:
        return built_on(design, geometry, template)
    material = design.material
    planks_used, joints, contacts, components = grounded_parts(design, geometry)
    local = {plank: k for k, plank in enumerate(planks_used)}
    plank_list = [design.planks[i] for i in planks_used]
    joint_lines = _joint_lines(design, geometry, joints) if template is None else None
    crosswise = _crosswise(design, geometry, plank_list, joints, contacts, joint_lines) \
        if template is None else template.beams.crosswise
    frames = [beam_frame(p, c) for p, c in zip(plank_list, crosswise)]
    halves = np.array([0.5 * beam_length_width(p, c)[0]
                       for p, c in zip(plank_list, crosswise)])

    joint_list = [geometry.joints[j] for j in joints]
    hung = None if template is not None else hung_planks(
        joint_list, [geometry.contacts[c] for c in contacts], loaded_planks(design))
    part_counts = joint_part_counts(
        design, joint_list, local, frames,
        np.array([beam_length_width(p, c) for p, c in zip(plank_list, crosswise)],
                 dtype=float).reshape(-1, 2), hung) \
        if template is None else template.plank_cache["joint_part_counts"]
    spring_points, arms = part_points(joint_list, part_counts)
    spring_joint = np.repeat(np.arange(len(joints)), part_counts)
    keys: list[tuple] = []              # what is attached where: its key,
    owners: list[int] = []              # its local plank
    points: list = []                   # and its point
    for row, (j, point) in enumerate(zip(spring_joint.tolist(), spring_points)):
        for side, plank_id in enumerate(joint_list[j].planks):
            keys.append(("joint", row, side))
            owners.append(local[design.plank_index[plank_id]])
            points.append(point)
    for row, c in enumerate(contacts):
        keys.append(("contact", row))
        owners.append(local[design.plank_index[geometry.contacts[c].plank]])
        points.append(geometry.contacts[c].point)
    n_corners = len(contacts)
    for row, c in enumerate(contacts):              # a resting corner's other plank
        if geometry.contacts[c].on is not None:
            keys.append(("rest", row))
            owners.append(local[design.plank_index[geometry.contacts[c].on]])
            points.append(geometry.contacts[c].point)
    for ci, case in enumerate(design.load_cases):
        for li, load in enumerate(case.loads):
            k = local.get(design.plank_index[load.plank])
            if k is not None and load.point is not None and not load.spread:
                keys.append(("load", ci, li))
                owners.append(k)
                points.append(load.point)
    centres = np.array([p.center_array for p in plank_list], dtype=float).reshape(-1, 3)
    axes = np.array([frame[:, 0] for frame in frames], dtype=float).reshape(-1, 3)
    owner_array = np.array(owners, dtype=int)
    point_array = np.array(points, dtype=float).reshape(-1, 3)
    along = ((point_array - centres[owner_array]) * axes[owner_array]).sum(axis=1)
    n_sides = 2 * len(spring_joint)
    corner_points = point_array[n_sides:n_sides + n_corners]
    if template is None:
        edges, depths = support_edges(design, geometry, contacts,
                                      owner_array[n_sides:n_sides + n_corners],
                                      corner_points, plank_list, axes, halves)
        segments = station_segments(edges, halves, depths)
        attachments: list[list] = [[] for _ in plank_list]
        for key, s, owner in zip(keys, along.tolist(), owners):
            attachments[owner].append((s, key))
        origins = tuple(origin for k in range(len(plank_list))
                        for origin in _plank_nodes(k, float(halves[k]), attachments[k],
                                                   segments.get(k, 0)))
        layout = _NodeLayout.of(origins, keys, owners)
        stations = support_stations(edges, origins)
    else:
        origins = template.beams.origins
        layout = template.plank_cache["node_layout"]
        stations = template.plank_cache["support_stations"]

    node_plank = layout.node_plank
    node_s = layout.positions(along, halves)
    node_points = (centres[node_plank] + node_s[:, None] * axes[node_plank]).reshape(-1, 3)
    beams = beam_elements(plank_list, frames, node_plank, node_s, halves,
                   [design.material_of(p) for p in plank_list], origins, crosswise)

    weights = read_only(weights_per_length(design, plank_list, beams))
    joint_nodes = layout.row_node[:n_sides].reshape(-1, 2)
    joint_blocks = joint_deviation_blocks(spring_points, node_points[joint_nodes])
    stiffness = nail_row_parts(joint_list, part_counts, material.nail_slip,
                               material.nail_withdrawal)[0]
    parted = bool((np.asarray(part_counts) > 1).any())

    station_points, shares = station_places(stations, corner_points, node_s, node_plank,
                                            centres, axes)
    owner = np.concatenate([owner_array[n_sides:n_sides + n_corners],
                            node_plank[stations[:, 2]]])
    contact_points = np.vstack([corner_points, station_points])
    contact_node = np.concatenate([layout.row_node[n_sides:n_sides + n_corners],
                                   stations[:, 2]])
    held = [*contacts, *(contacts[a] for a in stations[:, 0].tolist())]
    load_rows = {key[1:]: row for row, key in enumerate(keys) if key[0] == "load"}
    load_nodes = {(case.name, li): int(layout.row_node[load_rows[ci, li]])
                  if (ci, li) in load_rows else int(layout.centre_node[k])
                  for ci, case in enumerate(design.load_cases)
                  for li, load in enumerate(case.loads)
                  if (k := local.get(design.plank_index[load.plank])) is not None}
    component_of = {p: c for c, comp in enumerate(components) for p in comp}
    frames = contact_frames(design, geometry, held)
    rest_node = None
    if any(key[0] == "rest" for key in keys):
        rest_node = np.full(len(held), -1)
        for index, key in enumerate(keys):
            if key[0] == "rest":
                rest_node[key[1]] = layout.row_node[index]
    model = StaticsModel(
        design=design, geometry=geometry, planks=tuple(planks_used), joints=tuple(joints),
        contacts=tuple(held), node_plank=node_plank, node_points=node_points,
        joint_nodes=joint_nodes, joint_blocks=joint_blocks, joint_stiffness=stiffness,
        contact_maps=in_contact_frames(
            point_maps(contact_points - node_points[contact_node].reshape(-1, 3)), frames),
        contact_frames=frames, contact_anchored=anchored_contacts(geometry, held),
        rest_node=rest_node,
        rest_maps=rest_maps(rest_node, contact_points, node_points, frames),
        contact_node=contact_node, contact_plank=owner, contact_points=contact_points,
        contact_component=np.array([component_of[p] for p in owner], dtype=int),
        components=components, friction=material.friction,
        contact_stiffness=tol.ELASTIC_CONTACT_STIFFNESS,
        anchor_stiffness=tol.ANCHOR_STIFFNESS,
        beams=beams,
        nodal_weight=nodal_loads(beams, weights, len(node_plank)),
        load_nodes=load_nodes,
        joint_parts=spring_joint if parted else None, part_arms=arms if parted else None,
        station_corners=stations[:, :2] if len(stations) else None,
        station_shares=shares if len(stations) else None)
    model.plank_cache["node_layout"] = layout
    model.plank_cache["support_stations"] = stations
    model.plank_cache["joint_part_counts"] = part_counts
    if hung is not None:            # the plate check asks again (``model_hung_planks``)
        model.plank_cache["hung_planks"] = hung
    model.plank_cache["weights_per_length"] = weights
    if joint_lines is not None:     # the plate check asks again (``plate_supports.held_planks``)
        model.plank_cache["joint_lines"] = joint_lines
    model.plank_cache["attachments"] = Attachments(
        owner_array, tuple(key[1] for key in keys if key[0] == "rest"),
        tuple(key[1:] for key in keys if key[0] == "load"))
    if template is not None:        # the same joints and contacts: the same topology
        assert template.joints == model.joints and template.contacts == model.contacts
        for key in TOPOLOGY_CACHE:
            if key in template.plank_cache:
                model.plank_cache[key] = template.plank_cache[key]
    return model


