"""How a thicker plank grows (``grown``), for the thicker-board rule (``thicker``).

A plank grows away from the faces that hold it: a face on which another plank's end is
nailed or rests, or that lies on the floor or a wall stays where it is (a shelf on
brackets grows upward, a post with a shelf nailed to its front grows backward); with
neither face held a level plank (a shelf between two sides) grows downward, its top face
and what stands on it where they were (a shelf flush with the sides' tops stays flush),
any other toward the planks its ends are nailed to (a table's leg grows inward), else
equally both ways; with both held it grows toward a face whose planks rest on it alone
(a chair's back on its seat, which moves with it), else into the planks standing square
on one face, cut that much shorter (a cabinet's bottom into its kick board, ripped
narrower; the lower face first), else it cannot grow.  Load and anchor points on a
face that moves move with it, and those on a cut plank's cut end with that end.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Plank
from furncheck.geometry import Geometry
from furncheck.suggest.discrete.common import PARALLEL_COS, amount, level, names


def grown(design: Design, geometry: Geometry, thicknesses: dict[str, float],
          stretchable: frozenset[str] = frozenset()) -> Design | None:
    """The design with the planks of ``thicknesses`` (id -> m) that thick, each grown away
    from its held faces (module docstring); a plank held on both faces grows toward the
    side where only planks nailed to it alone rest (a chair's back on its seat), which
    move with that face, else into the planks standing square on one face, cut that much
    shorter (``_cut_side``); load and anchor points on a moved face or a cut end move with
    it.  A plank of ``stretchable`` (one the same fix adds) on whose face a grown plank's
    edge is nailed is lengthened with it, so that it still covers that edge (a back panel
    over a seat made thicker).  None when a plank cannot grow."""
    held = _held_sides(design, geometry)
    resting = _resting(geometry)
    jointed = geometry.jointed()
    planks = {p.id: p for p in design.planks}
    moves: dict[str, list] = {}                    # plank id -> how its points move
    for plank_id, thickness in thicknesses.items():
        plank = planks[plank_id]
        grow = thickness - plank.thickness
        if grow <= 0.0:
            continue
        axis = plank.rotation_matrix[:, 2]
        sides = held.get(plank_id, set())
        if len(sides) == 2:
            side = next((s for s in (1, -1) if all(
                len(set(jointed.get(leaf, ()))) == 1
                for leaf in resting.get((plank_id, s), ()))), None)
            if side is not None:
                for leaf in resting.get((plank_id, side), ()):
                    shift = axis * side * grow
                    planks[leaf] = replace(planks[leaf], center=tuple(
                        float(v) for v in planks[leaf].center_array + shift))
                    moves.setdefault(leaf, []).append(_translation(shift))
            else:       # the planks standing on one face cut shorter by the growth
                side = _cut_side(plank, resting, planks, grow)
                if side is None:
                    return None
                for leaf in resting[(plank_id, side)]:
                    planks[leaf], move = _cut(planks[leaf], axis * side, grow, design)
                    moves.setdefault(leaf, []).append(move)
        elif sides:
            side = -next(iter(sides))
        else:
            side = _free_side(design, geometry, plank, grow, planks)
            if side is None:
                return None
        centre = plank.center_array + axis * side * 0.5 * grow
        planks[plank_id] = replace(plank, thickness=float(thickness),
                                   center=tuple(float(v) for v in centre))
        moves.setdefault(plank_id, []).append(_face_shift(plank, axis, side, grow, design))
        for joint in geometry.joints:
            if joint.edge == plank_id and joint.face in stretchable:
                planks[joint.face] = _covering(planks[joint.face], planks[plank_id],
                                               axis * side)
    if not moves:
        return None

    def moved(plank_id: str, point):
        for move in moves.get(plank_id, ()):
            point = move(point)
        return point
    cases = tuple(replace(case, loads=tuple(
        replace(load, point=moved(load.plank, load.point)) if load.point is not None
        else load for load in case.loads)) for case in design.load_cases)
    anchors = tuple(replace(a, point=moved(a.plank, a.point)) for a in design.anchors)
    return replace(design, planks=tuple(planks[p.id] for p in design.planks),
                   load_cases=cases, anchors=anchors)


CUT_LEFT = 2.0
"""A plank standing on a face that grows is cut shorter only where at least this many
times the cut would be left of it along the cut (``_cut_side``)."""


def _cut_side(plank: Plank, resting: dict, planks: dict[str, Plank],
              grow: float) -> int | None:
    """The face (+1 local +z, -1 -z) of a plank held on both faces toward which it can grow
    by cutting the planks that stand on that face shorter (``_cut``: a cabinet's bottom,
    the dividers standing on it and a kick board under it, grows down into the kick
    board, ripped that much narrower): each of them standing square on it, within
    PARALLEL_COS (an in-plane axis along its normal), and at least CUT_LEFT times the
    cut long that way.  The lower face of a level plank first (its top and what stands
    on it stay), else the face with fewer planks to cut; None where neither face will
    do."""
    axis = plank.rotation_matrix[:, 2]
    order = (-1, 1) if axis[2] > 0.0 else (1, -1)
    if not level(plank):
        order = tuple(sorted((1, -1), key=lambda s: len(resting.get((plank.id, s), ()))))
    for side in order:
        leaves = resting.get((plank.id, side), ())
        if leaves and all(_fits(planks[leaf], axis * side, grow) for leaf in leaves):
            return side
    return None


def _fits(leaf: Plank, way: np.ndarray, grow: float) -> bool:
    """Whether ``leaf`` stands square along ``way`` and is long enough to be cut by
    ``grow`` (``_cut_side``)."""
    axis, _, cosine = _toward(leaf, way)
    return cosine >= PARALLEL_COS and _sizes(leaf)[axis] >= CUT_LEFT * grow / cosine


def _toward(plank: Plank, way: np.ndarray) -> tuple[int, np.ndarray, float]:
    """The plank's in-plane axis nearest ``way`` (a unit vector): its index (0: length,
    1: width), its direction turned toward ``way``, and the cosine between the two."""
    axes = plank.rotation_matrix
    axis = int(np.argmax(np.abs(axes[:, :2].T @ way)))
    cosine = float(axes[:, axis] @ way)
    return axis, axes[:, axis] * (1.0 if cosine > 0.0 else -1.0), abs(cosine)


def _sizes(plank: Plank) -> list[float]:
    return [plank.length, plank.width]


def _cut(leaf: Plank, way: np.ndarray, grow: float, design: Design):
    """(``leaf`` cut, how a point on it moves): standing on a face that moves ``grow``
    along ``way`` (a unit vector, from the face into the leaf), it is cut shorter at that
    end by what keeps its other end where it was, grow / cos along its own axis
    (``_cut_side``); a point on that end (within the design's tolerance of it) or in the
    strip cut off comes onto the new end (a load on a kick board's top edge stays on its
    edge), any other stays where it is."""
    axis, along, cosine = _toward(leaf, way)
    cut = grow / cosine
    sizes = _sizes(leaf)
    new_end = cut - 0.5 * sizes[axis]                       # along ``along``
    slack = design.tolerance + tol.ON_PLANK_EPS
    centre = leaf.center_array

    def move(point):
        short = new_end - float((np.asarray(point) - centre) @ along)
        if short <= 0.0 or short > cut + slack:
            return point
        return tuple(float(v) for v in np.asarray(point) + along * short)

    sizes[axis] -= cut
    return replace(leaf, length=sizes[0], width=sizes[1], center=tuple(
        float(v) for v in centre + along * 0.5 * cut)), move


def cut_phrase(design: Design, edited: Design) -> str:
    """'; rip kick 3 mm narrower (80 -> 77 mm) to make room': the planks of ``design``
    that ``edited`` (``design`` with planks thickened, ``grown``) has shorter or
    narrower, cut to make room for them (``_cut``), in shop words ('' where none is)."""
    scale, unit = design.unit_scale, design.units
    parts = []
    for plank in design.planks:
        if plank.id not in edited.plank_index:
            continue
        after = edited.plank(plank.id)
        for (verb, shorter), old, new in zip((("cut", "shorter"), ("rip", "narrower")),
                                             _sizes(plank), _sizes(after)):
            if new < old * (1.0 - tol.STOCK_MATCH):
                parts.append(f"{verb} {plank.id} {amount((old - new) / scale)} {unit} "
                             f"{shorter} ({amount(old / scale)} -> {amount(new / scale)} "
                             f"{unit})")
    return f"; {names(parts)} to make room" if parts else ""


def _covering(face: Plank, edge: Plank, way: np.ndarray) -> Plank:
    """``face`` lengthened along its in-plane axis nearest ``way`` (the way ``edge`` grew,
    a unit vector), its far end moved, until it reaches ``edge``'s grown face there."""
    axis, along, _ = _toward(face, way)
    sizes = _sizes(face)
    reach = float(edge.center_array @ way) + 0.5 * edge.thickness
    end = float(face.center_array @ way) + 0.5 * sizes[axis] * float(along @ way)
    short = (reach - end) / max(float(along @ way), 1e-12)
    if short <= 0.0:
        return face
    sizes[axis] += short
    return replace(face, length=sizes[0], width=sizes[1], center=tuple(
        float(v) for v in face.center_array + along * 0.5 * short))


def _resting(geometry: Geometry) -> dict[tuple[str, int], list[str]]:
    """(face plank, its side) -> the edge planks nailed on that broad face."""
    found: dict[tuple[str, int], list[str]] = {}
    for joint in geometry.joints:
        found.setdefault((joint.face, int(joint.face_side)), []).append(joint.edge)
    return found


def _free_side(design: Design, geometry: Geometry, plank: Plank, grow: float,
               planks: dict[str, Plank]) -> int | None:
    """How a plank held on neither face grows: 0 both ways, else toward +1 or -1 local
    z; the first whose new corners stay out of the floor and of the faces its ends rest
    on (a splayed leg, its ends cut square to it, cannot grow either way without
    cutting in), trying a level plank's downward side first (its top face stays: module
    docstring) and another's side toward the planks its ends are nailed to first (a
    table's leg grows inward, its outer face still flush with the top's edge: both ways
    it stuck out past the edge by half the growth); None if none does.  ``planks``: the
    planks as grown so far."""
    planes = [(np.array([0.0, 0.0, 1.0]), 0.0)]
    for joint in geometry.joints:
        if joint.edge == plank.id:
            face = planks[joint.face]
            outward = face.rotation_matrix[:, 2] * joint.face_side
            planes.append((outward, float(outward @ face.center_array) + face.half_extents[2]))
    slack = design.tolerance + tol.ON_PLANK_EPS
    axis = plank.rotation_matrix[:, 2]
    order = (0, 1, -1)
    inward = sum(float((planks[joint.face].center_array - plank.center_array) @ axis)
                 for joint in geometry.joints if joint.edge == plank.id)
    if level(plank):
        down = -1 if axis[2] > 0.0 else 1
        order = (down, 0, -down)
    elif abs(inward) > slack:
        side = 1 if inward > 0.0 else -1
        order = (side, 0, -side)
    for side in order:
        moved = replace(plank, thickness=plank.thickness + grow, center=tuple(
            float(v) for v in plank.center_array + axis * side * 0.5 * grow))
        corners = moved.corners
        old = plank.corners
        if all((corners @ n - offset).min() >= min(float((old @ n - offset).min()), 0.0) - slack
               for n, offset in planes):
            return side
    return None


def _translation(shift: np.ndarray):
    return lambda point: tuple(float(v) for v in np.asarray(point) + shift)


def _face_shift(plank: Plank, axis: np.ndarray, side: int, grow: float, design: Design):
    """How a point on ``plank`` moves when it grows by ``grow`` toward ``side`` (0: both
    ways): with its face when it lies on a face that moves, else not at all."""
    half = plank.half_extents[2]
    slack = design.tolerance + tol.ON_PLANK_EPS

    def move(point):
        height = float((np.asarray(point) - plank.center_array) @ axis)
        for face in (1, -1):
            if abs(height - face * half) <= slack and side in (0, face):
                step = grow if side else 0.5 * grow
                return tuple(float(v) for v in np.asarray(point) + axis * face * step)
        return point
    return move


def _held_sides(design: Design, geometry: Geometry) -> dict[str, set[int]]:
    """plank id -> its broad faces (+1 local +z, -1 -z) that hold: a joint's face side,
    a resting plank's, and the face a plank lying on the floor or a wall lies on."""
    held: dict[str, set[int]] = {}
    for joint in geometry.joints:
        held.setdefault(joint.face, set()).add(int(joint.face_side))
    for contact in geometry.contacts:
        if contact.on is not None and contact.frame is not None:
            face = design.plank(contact.on)
            side = 1 if float(np.asarray(contact.frame[2]) @ face.rotation_matrix[:, 2]) > 0 \
                else -1
            held.setdefault(contact.on, set()).add(side)
        elif contact.anchor is None and 0 <= contact.corner < 8:
            plank = design.plank(contact.plank)
            support = np.array([0.0, 0.0, 1.0]) if contact.wall is None else \
                np.asarray(design.walls[contact.wall].normal)
            if abs(float(plank.rotation_matrix[:, 2] @ support)) >= 0.95:
                held.setdefault(plank.id, set()).add(-1 if contact.corner < 4 else 1)
    return held
