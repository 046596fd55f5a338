"""Which planks of an elastic model are checked as plates (``statics.plates``), and what
holds each: its joint lines as support segments, with each nail row's grip against
turning, and the rails that bend with it as stiffeners.

``held_planks`` yields the planks not standing on the floor that joint lines, held
straight by their other planks (``elastic._holds_straight``: a panel, not a rail), hold
along at least PLATE_HELD_SHARE of one of their sides, on one line or one side of their
middle, and somewhere off that line too, and that their weight or loads push across
their face (``_loaded_across``); each with its segments and stiffeners
(``_support_segments``: a line is a support where its other plank carries it where it
is, ``_carried``, and a stiffener where that plank spans between panels and bends with
the plate, ``_bending_across``); and the planks that one joint alone holds
(``elastic.hung_planks``), hung on its line along their beam (``_hangs_along``), as
cantilever plates, whether or not the other plank holds the line straight: the row
gripping it is their only hold against turning (``plate_mesh._hinge``).
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Plank


def held_planks(model, only: set[int] | None = None):
    """(local index, plank, support segments, stiffeners) of each plank of the model that
    does not stand on the floor, that its weight or a load pushes across its face, and
    that joint lines held straight by their other planks hold along one of its sides
    over at least PLATE_HELD_SHARE of it (on one line, or on one side of its middle: the
    union of their spans), besides somewhere off that line (the plate is then held, not
    hinged on one line): each segment ((x0, y0), (x1, y1), grip), plank-local, and the
    rails nailed along it (``_support_segments``); and those that one joint alone holds,
    hung on its line (``_hangs_along``), no stiffeners.  ``only``: of these local planks
    alone."""
    from furncheck.statics.elastic import _joint_lines, model_hung_planks

    design, geometry = model.design, model.geometry
    grounded = {contact.plank for contact in geometry.contacts if contact.on_floor}
    held = carried = hung = None
    joints_of: dict[str, list] = {}
    for k, index in enumerate(model.planks):
        plank = design.planks[index]
        if plank.id in grounded or (only is not None and k not in only):
            continue
        if held is None:
            held = model.plank_cache.get("joint_lines")
            if held is None:        # (a stepped model's: only those of the planks asked)
                ids = None if only is None else \
                    {design.planks[model.planks[i]].id for i in only}
                held = _joint_lines(design, geometry, [
                    j for j in model.joints
                    if ids is None or not ids.isdisjoint(geometry.joints[j].planks)])
            for j in model.joints:                  # in ``_joint_lines``' order
                for plank_id in geometry.joints[j].planks:
                    joints_of.setdefault(plank_id, []).append(geometry.joints[j])
            carried = _carried(geometry, joints_of)     # (its floor feet found once)
        lines = held.get(plank.id)
        if not lines:
            continue
        if hung is None:
            hung = model_hung_planks(model)
        if plank.id in hung:
            hanging = _hanging(model, plank, hung[plank.id], lines, joints_of[plank.id],
                               bool(model.beams.crosswise[k]))
            if hanging is not None:
                yield (k, plank, *hanging)
                continue
        if len(lines) == 1:
            continue
        joints = joints_of[plank.id]
        if not _loaded_across(design, plank):
            continue
        segments, stiffeners = _support_segments(design, plank, lines, joints, carried)
        if _holds_beam(plank, segments, 0) or _holds_beam(plank, segments, 1):
            yield k, plank, segments, stiffeners


def _loaded_across(design: Design, plank: Plank) -> bool:
    """Whether its weight or a load of some case pushes the plank across its face (a
    plank standing on edge, loaded in its plane only, bends as its beam does)."""
    normal = plank.axes[2]
    if abs(normal[2]) > tol.PLATE_SLANT:
        return True
    return any(force_across(load.force, normal) != 0.0
               for case in design.load_cases for load in case.loads if load.plank == plank.id)


def force_across(force, normal) -> float:
    """N: a force's component along a plank's face ``normal``; 0 where it is PLATE_SLANT of
    the force or less (a push along a turned plank's face, or a weight on a plank standing
    on edge, its normal off the horizontal by round-off: along the face, in any turn of
    the design)."""
    across = float(np.dot(force, normal))
    return 0.0 if abs(across) <= tol.PLATE_SLANT * float(np.linalg.norm(force)) else across


def _holds_beam(plank: Plank, segments, axis: int) -> bool:
    """Whether ``segments`` along the plank's local ``axis`` (0: x) cover at least
    PLATE_HELD_SHARE of its side along it on one line, or on one side of its middle
    line, and some segment lies off that line (see ``held_planks``)."""
    from furncheck.statics.elastic import _union_length

    size = (plank.length, plank.width)[axis]
    need = tol.PLATE_HELD_SHARE * size - tol.NODE_MERGE - tol.NODE_MERGE_ROUNDOFF
    along = [seg for seg in segments if _segment_axis(seg) == axis]
    for side in (-1.0, 0.0, 1.0):
        mine = [seg for seg in along if _side(seg[0][1 - axis]) == side]
        if _union_length([(seg[0][axis], seg[1][axis]) for seg in mine]) < need:
            continue
        lines = {round(seg[0][1 - axis] / tol.NODE_MERGE) for seg in mine}
        if len(lines) > 1 or any(_segment_axis(seg) != axis or
                                 round(seg[0][1 - axis] / tol.NODE_MERGE) not in lines
                                 for seg in segments):
            return True
    return False


def _hanging(model, plank: Plank, hung: tuple, lines, joints, crosswise: bool):
    """(support segments, stiffeners) of a plank that one joint alone holds, but for its
    leaves (``hung``: that joint's row in ``model.joints`` and its leaves' rows; ``lines``
    and ``joints``: its joint lines and joints, in that order), where it hangs on that
    joint as a plate (``hung_plate_segments``): its leaves' rows are stiffeners (a lip
    bends with the plate along its line, ``_bending_across``), and their weights loads on
    the plate, each at its row's middle (``plates.attach``).  None where it does not."""
    from furncheck.statics.plates import attach

    design, geometry = model.design, model.geometry
    holding = geometry.joints[model.joints[hung[0]]]
    segments = hung_plate_segments(design, plank, holding, crosswise)
    if segments is None:
        return None
    leaves = [(line, joint) for line, joint in zip(lines, joints, strict=True)
              if joint is not holding]
    stiffeners = _support_segments(design, plank, [line for line, _ in leaves],
                                   [joint for _, joint in leaves],
                                   lambda partner, joint: False)[1] if leaves else []
    weights = []
    for _, joint in leaves:
        leaf = design.plank(next(p for p in joint.planks if p != plank.id))
        weights.append((tuple(joint.point.tolist()),
                        (0.0, 0.0, -design.plank_mass(leaf) * tol.GRAVITY)))
    attach(design, plank.id, tuple(weights))
    return segments, stiffeners


def hung_plate_segments(design: Design, plank: Plank, joint, crosswise: bool) -> list | None:
    """The support segment of a plank that ``joint`` alone holds (``elastic.hung_planks``)
    where it is checked as a plate hung on that joint's line: its weight or a load
    pushes across its face (``_loaded_across``) and it hangs along its beam
    (``_hangs_along``; ``crosswise``: its beam runs along its local y); else None.  The
    one test of both the plate check (``held_planks``) and the row's cut into parts
    (``elastic.joint_part_counts``): a row is cut only where a plate reads the bending
    across the plank that the parts' rigid arms hold straight."""
    if not _loaded_across(design, plank):
        return None
    line = (tuple(joint.point.tolist()), tuple((joint.length * joint.frame[:, 1]).tolist()),
            None)
    segments, _ = _support_segments(design, plank, [line], [joint])
    return segments if _hangs_along(plank, segments, crosswise) else None


def _hangs_along(plank: Plank, segments, crosswise: bool) -> bool:
    """Whether a plank that one joint alone holds (``elastic.hung_planks``) hangs on it
    along its beam (its longer side, or its local y where ``crosswise``: the model's), as
    a plate: its one line (``segments``, the joint's) runs along the beam over at least
    PLATE_HELD_SHARE of its length, and the plank is wider than JOINT_PART_NARROW
    thicknesses across it, where the beam, its section held straight, shows none of its
    bending across it (a shelf nailed by its back edge onto a
    rail read 5.08 mm, two 450 mm overhangs from the joint's middle, before its row was
    cut into parts; the plate hung on the row sags 0.4 mm)."""
    if len(segments) != 1:
        return False
    axis = 1 if crosswise else 0
    (start, end, _), = segments
    need = tol.PLATE_HELD_SHARE * (plank.length, plank.width)[axis] - tol.NODE_MERGE
    return _segment_axis(segments[0]) == axis and end[axis] - start[axis] >= need \
        and (plank.width, plank.length)[axis] > tol.JOINT_PART_NARROW * plank.thickness


def _side(offset: float) -> float:
    """-1, 0 or 1: which side of the beam's axis a line at ``offset`` (m) lies on (0:
    within NODE_MERGE of it)."""
    return 0.0 if abs(offset) <= tol.NODE_MERGE else float(np.sign(offset))


def _segment_axis(segment) -> int:
    """0 where a segment ((x0, y0), (x1, y1), grip) runs along the plank's x, else 1."""
    (x0, y0), (x1, y1), _ = segment
    return 0 if abs(y1 - y0) <= abs(x1 - x0) else 1


def _carried(geometry, joints_of: dict[str, list]):
    """A test whether a plank (id) holds a joint's line up where it is: it stands on the
    floor along at least SPAN_ACROSS_STANDING of the line (its floor corners that far
    apart along it), or another of its joints runs along the line over as much of it (a
    divider standing on a cabinet's bottom, a back panel nailed to a shelf below): not a
    rail that spans between two panels, which carries what the line puts on it by
    bending."""
    from furncheck.statics.elastic import floor_feet, stands_along

    feet = floor_feet(geometry)

    def carried(partner: str, joint) -> bool:
        line = joint.frame[:, 1]
        if stands_along(feet.get(partner, ()), line, joint.length):
            return True
        need = tol.SPAN_ACROSS_STANDING * joint.length - tol.NODE_MERGE
        return any(other is not joint and other.length >= need
                   and abs(float(other.frame[:, 1] @ line)) >= 1.0 - tol.PLATE_SLANT
                   for other in joints_of.get(partner, ()))
    return carried


def _support_segments(design: Design, plank: Plank, lines, joints,
                      carried=None) -> tuple[list, list]:
    """The plank's joint lines (``lines``, of ``joints`` in order) as local segments along
    its x or y axis (clipped to the plank; a line at a slant to both is left out): those
    held straight by their other planks and held up by them where they are (``carried``,
    ``_carried``; all lines, straight or not, where it is None: a plank's only joint,
    ``held_planks``), each with its nail row's grip against turning
    about it per metre (contract 3a: n nail_withdrawal (t/2)^2 over its length, N m /
    rad per m; the other plank taken as not turning), and the others, the rails and
    aprons that bend with the plank (a rail stiff in its own plane that spans between
    panels too: it carries what the plate puts on it by bending), each with the bending
    stiffness it adds across the plank's face, E I (N m^2, ``_bending_across``):
    (supports, stiffeners), each ((x0, y0), (x1, y1), value)."""
    frame = plank.rotation_matrix
    sizes = (plank.length, plank.width)
    half = (sizes[0] / 2.0, sizes[1] / 2.0)
    withdrawal = design.material_of(plank).nail_withdrawal
    supports, stiffeners = [], []
    for (point, line, straight), joint in zip(lines, joints, strict=True):
        along = np.asarray(line) @ frame[:, :2]
        length = float(np.hypot(*along))
        if length <= 0.0:
            continue
        axis = int(abs(along[1]) > abs(along[0]))
        if abs(along[1 - axis]) > tol.PLATE_SLANT * length:
            continue
        centre = plank.to_local(np.asarray(point)[None, :])[0, :2]
        low, high = centre.tolist(), centre.tolist()
        low[axis] -= length / 2.0
        high[axis] += length / 2.0
        low = tuple(min(max(v, -h), h) for v, h in zip(low, half))     # on the plank
        high = tuple(min(max(v, -h), h) for v, h in zip(high, half))
        if high[axis] - low[axis] <= tol.NODE_MERGE:
            continue
        ends = (low, high)
        partner_id = next(p for p in joint.planks if p != plank.id)
        if carried is None or (straight(sizes[axis], sizes[1 - axis])
                               and carried(partner_id, joint)):
            grip = joint.nails * withdrawal * (0.5 * joint.edge_thickness) ** 2
            supports.append((*ends, grip / length))
        else:
            stiffeners.append((*ends, _bending_across(design, plank, design.plank(partner_id),
                                                      joint, length)))
    return supports, stiffeners


def _bending_across(design: Design, plank: Plank, partner: Plank, joint,
                    length: float) -> float:
    """N m^2: the bending stiffness a rail or batten (``partner``, nailed along ``joint``'s
    line, ``length`` of it on the plank) adds to the plank's plate along that line, out
    of the plate's plane: its own E I, I = t_p h^3 / 12 (a_h . n)^2 + h t_p^3 / 12 (n_p .
    n)^2 (t_p its thickness, h its depth across the line in its own plane, a_h that
    axis, n_p its normal, n the plate's), and the composite action of the two nailed
    together by Eurocode 5's method for mechanically jointed beams (EN 1995-1-1 Annex B,
    as the beams have it): gamma E_f A_f E_r A_r / (gamma E_f A_f + E_r A_r) d^2, d
    between the rail's centroid and the plate's mid-plane, the plate's flange A_f = t b_ef
    with b_ef the rail's width on the plate (its thickness on edge, its depth lying flat)
    plus at most 0.2 of the line's length l and 30 plate thicknesses, half on each side
    the plate reaches (EN 1995-1-1 9.1.2, table 9.1: particleboard or fibreboard with
    random fibre orientation; taken as both sides' sum, the smaller reading), and gamma
    = 1 / (1 + pi^2 E_f A_f s / (K l^2)) for the nails' spacing s and slip modulus K
    (``nail_slip``) over l."""
    from furncheck.statics.elastic import depth_across

    normal = plank.rotation_matrix[:, 2]
    line = joint.frame[:, 1]
    axes = partner.rotation_matrix
    depth, axis = depth_across(partner, line)
    in_plane = axes[:, axis]
    t_p = partner.thickness
    second_moment = (t_p * depth ** 3 / 12.0 * float(in_plane @ normal) ** 2
                     + depth * t_p ** 3 / 12.0 * float(axes[:, 2] @ normal) ** 2)
    e_rail = design.material_of(partner).elastic_modulus
    material = design.material_of(plank)
    rail_area = e_rail * t_p * depth
    d = abs(float((partner.center_array - plank.center_array) @ normal))
    local = plank.to_local(partner.center_array[None, :])[0, :2]
    line_axis = int(abs(float(line @ plank.rotation_matrix[:, 1]))
                    > abs(float(line @ plank.rotation_matrix[:, 0])))
    reach = 0.5 * (plank.length, plank.width)[1 - line_axis]
    offset = local[1 - line_axis]
    across = np.cross(normal, line)                 # in the plate, across the line
    web = min(abs(float(in_plane @ across)) * depth + abs(float(axes[:, 2] @ across)) * t_p,
              2 * reach)
    side = 0.5 * min(0.2 * length, 30.0 * plank.thickness)
    width = (web + min(side, max(reach - offset - 0.5 * web, 0.0))
             + min(side, max(reach + offset - 0.5 * web, 0.0)))
    flange = material.elastic_modulus * plank.thickness * width
    spacing = length / max(joint.nails, 1)
    gamma = 1.0 / (1.0 + np.pi ** 2 * flange * spacing / (material.nail_slip * length ** 2))
    composite = gamma * flange * rail_area / (gamma * flange + rail_area) * d * d
    return e_rail * second_moment + composite
