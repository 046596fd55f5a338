"""What each violation would need, by hand statics: the numbers behind "no suggestion".

Each violation is taken on its own, in the load case where it is worst, with the loads
and planks as they are:

* sliding: friction holds while the sideways load H on a grounded group of planks stays
  within mu W, W the downward load it stands with (its planks' weight and the loads on
  them).  Needed: W >= H / mu (``extra_mass`` = (H / mu - W) / g more on it) or
  mu >= H / W (``friction_needed``); with mu = 0 no weight does (no ``extra_mass``).
* lift-off: the resultant of the group's weight and loads meets the floor at p; the
  support polygon is the convex hull of its ground contacts.  p lies ``outside`` = d
  beyond its nearest edge, so the overturning moment about that edge is V d (V the
  downward resultant).  Needed: a base reaching d further that way (``wider``), or
  ballast at the support point where the least of it holds (``geometry.support.
  hold_down_ratios``): V d / a at the point farthest from the edge, at arm a, where p
  lies beyond one edge, more beyond a corner (``ballast``);
  with sideways loads, the largest fraction of them that keeps p inside (``push_max``).
* a loose part (``geometry.loose``: a top lying on its frame by resting joints, with what
  rests on it) that tips off its rests or slides on them while the whole stands, or
  whatever stands by a wall: the same statics in the plane of its rests
  (``geometry.support.tipping_on_plane``): the pull a fixing there must take (``hold``,
  V d / a beyond one edge, ``hold_arm``), or its loads' lift (``lifted``), ballast where
  its rests are level; for sliding, its push along them against mu N, N what presses it
  onto them (``part``, ``on``: its planks and those under it).
* non-durable joint: the pull and shear per nail are the joint's forces shared by its n
  nails (``nail_groups.nail_pull_shear``: every term goes with 1 / n for the same wrench),
  so n' = ceil(n x max(pull / capacity, shear / capacity)) nails hold it; unless the file
  lists the count, that is a joint n' x spacing long.
* an anchor over its capacity: a rating of at least its force x the safety factor.
* sagging / overstressed plank (elastic model): for the same load and span the sag goes
  with 1 / (E I), I = b t^3 / 12, and the stress with 1 / S, S = b t^2 / 6 -- t the
  dimension the plank bends across: its thickness, or its width for a plank on edge
  under vertical loads.  Needed: t' = t (sag (1 + creep) / allowed)^(1/3), or
  t' = t (stress / strength)^(1/2).  Its own weight, which grows with t, is left out;
  and where nails hold its ends, a stiffer plank is held less firmly (the joints' springs
  stay as they are), so its sag falls more slowly than 1 / t^3: the sag's t' is a lower
  bound (the particleboard shelf of the catalog, 45.8 mm by the formula, still sags 2.5 x
  its allowance at that thickness; the cantilever, whose support is a determinate joint,
  1.05 x: its own weight).
* geometric: the gap, depth or height to close, to within the tolerance; an overlap
  (an end cutting into a face) as a negative gap.  A group that floats only because it
  misses joints to a standing group (``near.carried_groups``) has nothing to lower:
  ``carried``, closing those joints carries it.

The values are SI-free for the reports: lengths in the design's unit, forces N, masses
kg, stress N/mm^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Plank
from furncheck.geometry import Geometry, end_bearing, end_gap, interpenetrations
from furncheck.geometry.loose import LoosePart, loose_parts
from furncheck.geometry.model import nails_listed
from furncheck.geometry.near import carried_groups
from furncheck.geometry.support import (
    DUPLICATE,
    convex_hull,
    floor_point,
    hold_down_ratios,
    nearest_edge,
    outside,
    plank_loads,
    tipping_on_plane,
)
from furncheck.plain import plain_number
from furncheck.result import CaseResult, DesignReport, Violation
from furncheck.tolerances import GRAVITY, MIN_BEARING_SHARE
from furncheck.validity import bows_sideways

LEVEL_COS = 0.95
"""A plank's length axis counts as horizontal, and a face normal as horizontal, when
their vertical component is below 1 - this (about 18 degrees)."""


@dataclass(frozen=True)
class Need:
    """What one violation would need (see the module docstring for ``values``' keys).

    kind, where, case : the violation's (``case`` the worst of its cases, None for
                geometry)
    cases  : every case the violation occurs in
    values : the numbers, by name; empty when there is no hand estimate (``why`` says
             why)
    """

    kind: str
    where: str
    case: str | None
    cases: tuple[str, ...] = ()
    values: dict = field(default_factory=dict)
    why: str = ""


def violation_needs(design: Design, geometry: Geometry, report: DesignReport) -> tuple[Need, ...]:
    """One ``Need`` per violated (kind, place), in the order of the report."""
    groups: dict[tuple[str, str], list[Violation]] = {}
    for violation in report.violations:
        groups.setdefault((violation.kind, violation.where), []).append(violation)
    cases = {case.name: case for case in report.cases}
    needs = []
    for (kind, where), violations in groups.items():
        names = tuple(v.case for v in violations if v.case is not None)
        estimate = _ESTIMATES.get(kind)
        if estimate is None:
            needs.append(Need(kind, where, None, names, {}, "no hand estimate"))
            continue
        found = [estimate(design, geometry, where, cases.get(v.case), v.case)
                 if kind != "sagging" else
                 _bent(design, geometry, where, cases.get(v.case), v.case, sagging=True,
                       across=bows_sideways(v))
                 for v in violations]
        worst = max(found, key=_severity)
        needs.append(Need(kind, where, worst.case, names, worst.values, worst.why))
    return tuple(needs)


def _severity(need: Need) -> float:
    """How far a need is from holding, to pick the worst of a violation's cases: its
    ``ratio``; a frictionless slide (no ratio: mu = 0) by the friction it needs."""
    values = need.values
    return values.get("ratio", values.get("friction_needed", 0.0))


# -- stability ---------------------------------------------------------------------------
def _sliding(design: Design, geometry: Geometry, where: str, case: CaseResult | None,
             case_name: str | None) -> Need:
    part = _sliding_part(design, geometry, where, case_name)
    if part is not None:
        return part
    if _on_walls(design, geometry, where):
        return Need("sliding", where, case_name, why="it leans on walls or is anchored")
    weight, push = weight_and_push(design, geometry, where, case_name)
    mu = design.material.friction
    if weight <= 0.0:
        return Need("sliding", where, case_name, why="its loads lift it")
    if mu <= 0.0:           # no weight holds a push without friction
        return Need("sliding", where, case_name, values={
            "push": push, "weight": weight, "friction": mu, "holds": 0.0,
            "friction_needed": push / weight})
    if push <= mu * weight:         # within mu W as a whole: its feet share it unevenly
        return Need("sliding", where, case_name,
                    why=f"its push of {plain_number(push)} N is within what friction gives "
                        f"it as a whole ({plain_number(mu * weight)} N): it slides by a "
                        "twist or an uneven share between its feet, which hand statics of "
                        "the whole does not tell")
    needed = push / mu
    return Need("sliding", where, case_name, values={
        "push": push, "weight": weight, "friction": mu, "holds": mu * weight,
        "extra_mass": (needed - weight) / GRAVITY, "friction_needed": push / weight,
        "ratio": push / (mu * weight)})


def floor_friction(design: Design, geometry: Geometry, where: str,
                   case_name: str | None) -> tuple[float, float] | None:
    """``weight_and_push`` of ``where``'s group where the floor's friction alone holds it:
    None where it has a part resting on others (a top on its frame, held by the friction
    on its rests) or leans on a wall or is anchored."""
    if _parts_of(design, geometry, where) or _on_walls(design, geometry, where):
        return None
    return weight_and_push(design, geometry, where, case_name)


def weight_and_push(design: Design, geometry: Geometry, where: str,
                    case_name: str | None) -> tuple[float, float]:
    """(N, N): the weight W that the grounded group of planks named by ``where`` presses
    on the floor with in the case, and the sideways push H on it (the horizontal
    resultant of its weight and loads): friction holds it as a whole while H <= mu W."""
    forces, _ = _group_loads(design, geometry, where, case_name)
    total = forces.sum(axis=0)
    return float(-total[2]), float(np.hypot(total[0], total[1]))


def _sliding_part(design: Design, geometry: Geometry, where: str,
                  case_name: str | None) -> Need | None:
    """The sliding need of the loose part of ``where``'s group (``geometry.loose``: a top
    on its frame) that friction on its rests holds least, where one needs more than it
    has: the push along its rests' faces against mu N, N what presses it onto them
    (``part``: its planks, ``on``: the planks it rests on; ``extra_mass`` only where its
    rests are level to within PUSH_ANGLE, so that a mass on it presses them by its weight
    and pushes it nowhere); None where no loose part slides (the whole then does)."""
    mu = design.material.friction
    worst = None
    for part in _parts_of(design, geometry, where):
        total = _part_loads(design, case_name, part.planks)[0].sum(axis=0)
        pressing = float(-(total @ part.push))
        along = float(np.linalg.norm(total + pressing * part.push))
        if pressing > 0.0 and along > mu * pressing \
                and (worst is None or along / pressing > worst[0]):
            worst = (along / pressing, part, along, pressing)
    if worst is None:
        return None
    _, part, along, pressing = worst
    values = {"push": along, "weight": pressing, "friction": mu, "holds": mu * pressing,
              "friction_needed": along / pressing,
              "part": part.names(design), "on": part.under_names(design)}
    if mu <= 0.0:               # no weight holds a push without friction
        return Need("sliding", where, case_name, values=values)
    values["ratio"] = along / (mu * pressing)
    if part.push[2] >= math.cos(math.radians(tol.PUSH_ANGLE)):
        values["extra_mass"] = (along / mu - pressing) / (GRAVITY * float(part.push[2]))
    return Need("sliding", where, case_name, values=values)


def _parts_of(design: Design, geometry: Geometry, where: str) -> list[LoosePart]:
    """The loose parts (``geometry.loose``) among the planks of ``where``'s group."""
    group = _group(design, geometry, where)
    return [part for part in loose_parts(design, geometry) if part.planks <= group]


def _lift_off(design: Design, geometry: Geometry, where: str, case: CaseResult | None,
              case_name: str | None) -> Need:
    part = _lift_off_part(design, geometry, where, case_name)
    if _on_walls(design, geometry, where):
        return part or Need("lift-off", where, case_name,
                            why="it leans on walls or is anchored")
    forces, points = _group_loads(design, geometry, where, case_name)
    group = _group(design, geometry, where)
    feet = [c for c in geometry.contacts
            if c.on_floor and design.plank_index[c.plank] in group]
    weight = float(-forces[:, 2].sum())
    if weight <= 0.0 or not feet:
        return Need("lift-off", where, case_name,
                    why="its loads lift it" if feet else "it has no ground contact")
    hull, owners = _hull([c.point[:2] for c in feet], [c.plank for c in feet])
    crossing = _floor_crossing(forces, points)
    distance, nearest = outside(hull, crossing)
    if distance <= 0.0:                 # the whole stands: what tips is a part on its rests
        return part or Need("lift-off", where, case_name,
                            why="the loads' resultant meets the floor inside the support: it "
                                "tips where planks rest on others in a way hand statics does "
                                "not tell")
    scale = design.unit_scale
    away = (crossing - nearest) / distance
    arms = (nearest - hull) @ away
    values = {"weight": weight, "point": tuple(float(v) / scale for v in crossing),
              "outside": distance / scale,
              "edge_plank": _edge_planks(hull, owners, nearest),
              "wider": distance / scale, "ratio": 1.0 + distance / max(float(arms.max()), 1e-12)}
    ratios = hold_down_ratios(hull, crossing)
    if ratios is not None and np.isfinite(ratios.min()):
        least, planks, arm, beyond = _least_hold(ratios, hull, owners, crossing, nearest,
                                                 distance, design)
        values.update({"ballast": weight * least / GRAVITY, "ballast_plank": planks})
        if beyond:                                              # W d / a
            values["ballast_arm"] = arm / scale
    sideways = forces.copy()
    sideways[:, :2] = 0.0
    push = float(np.hypot(*forces[:, :2].sum(axis=0)))
    if push > 0.0:
        still = _floor_crossing(sideways, points)
        fraction = _inside_fraction(hull, still, crossing)
        if fraction is not None:
            values.update({"push": push, "push_max": fraction * push})
    if part is not None:        # held down as a whole, a loose part still tips
        values["also"] = part.values
    return Need("lift-off", where, case_name, values=values)


def _lift_off_part(design: Design, geometry: Geometry, where: str,
                   case_name: str | None) -> Need | None:
    """The lift-off need of the loose part of ``where``'s group (``geometry.loose``) that
    tips furthest off its rests, or whose loads lift it: by ``tipping_on_plane``, where
    its loads' resultant meets the plane of its rests (``point``, 3 coordinates), how far
    outside the polygon of its resting corners (``outside``) and beyond which planks
    under it (``edge_plank``), and the least pull at one resting corner that would hold it
    down (``hold`` N, at a corner on ``hold_plank``, 'end_l or end_r' where they tie;
    ``hold_arm`` where it lies beyond one edge: V d / a), as ballast on it there where its
    rests are level to within PUSH_ANGLE (``ballast`` kg); a part its loads lift needs
    their upward part held (``lifted`` N).  None where no part tips."""
    scale, worst = design.unit_scale, None
    for part in _parts_of(design, geometry, where):
        forces, points = _part_loads(design, case_name, part.planks)
        total = forces.sum(axis=0)
        if float(total @ part.push) > 0.0:          # lifted bodily: the worst there is
            return Need("lift-off", where, case_name, values={
                "part": part.names(design), "on": part.under_names(design),
                "lifted": float(total @ part.push), "ratio": math.inf})
        tipping = tipping_on_plane(total, np.cross(points, forces).sum(axis=0),
                                   part.points, part.push)
        held = None if tipping is None else tipping.least_pull()
        if held is not None and (worst is None or tipping.outside > worst[1].outside):
            worst = (part, tipping, held)
    if worst is None:
        return None
    part, tipping, _ = worst
    hull, owners = part.points[tipping.hull], [part.under[k] for k in tipping.hull]
    least, planks, arm, beyond = _least_hold(tipping.ratios, hull, owners, tipping.crossing,
                                             tipping.nearest_point, tipping.outside, design)
    pull = tipping.load * least
    values = {"part": part.names(design), "on": part.under_names(design),
              "weight": tipping.load,
              "point": tuple(float(v) / scale for v in tipping.crossing),
              "outside": tipping.outside / scale,
              "edge_plank": _edge_planks(hull, owners, tipping.nearest_point),
              "hold": pull, "hold_plank": planks,
              "ratio": 1.0 + tipping.outside / arm if arm > 0.0 else math.inf}
    if beyond:
        values["hold_arm"] = arm / scale      # beyond one edge: V d / a
    if part.push[2] >= math.cos(math.radians(tol.PUSH_ANGLE)):
        values["ballast"] = pull / (GRAVITY * float(part.push[2]))
    return Need("lift-off", where, case_name, values=values)


def _least_hold(ratios: np.ndarray, hull: np.ndarray, owners: list[str], crossing: np.ndarray,
                nearest: np.ndarray, distance: float, design: Design
                ) -> tuple[float, str, float, bool]:
    """(least, planks, arm, beyond) of a support polygon ``hull`` (the plank of each point
    in ``owners``) that the loads' line misses, meeting its plane at ``crossing``,
    ``distance`` from its nearest point ``nearest``, with ``ratios`` the least pull at
    each point over the load (``hold_down_ratios``): the least of them, the planks where
    it is least ('end_l or end_r', to HOLD_TIE), how far inside the edge nearest the
    crossing the first of them lies (a), and whether it lies beyond that one edge
    (least = d / a, the W d / a of the floor's and a loose part's hand estimates)."""
    far = int(np.argmin(ratios))
    least = float(ratios[far])
    tied = ratios <= least * (1.0 + tol.HOLD_TIE) + tol.HOLD_TIE
    planks = " or ".join(sorted({owner for owner, tie in zip(owners, tied) if tie},
                                key=design.plank_index.__getitem__))
    arm = float((nearest - hull[far]) @ ((crossing - nearest) / distance))
    beyond = arm > 0.0 and math.isclose(least, distance / arm, rel_tol=1e-9)
    return least, planks, arm, beyond


def _part_loads(design: Design, case_name: str | None,
                planks: frozenset[int]) -> tuple[np.ndarray, np.ndarray]:
    """``geometry.support.plank_loads`` of ``planks`` in the case named ``case_name``."""
    case = next((c for c in design.load_cases if c.name == case_name), None)
    return plank_loads(design, case, planks)


def _on_walls(design: Design, geometry: Geometry, where: str) -> bool:
    """Whether the group of ``where`` touches a wall or is anchored to one (the hand
    estimates take the floor alone: a design that merely has walls nearby, 10 mm off, is
    estimated as it stands)."""
    if not design.walls and not design.anchors:
        return False
    group = _group(design, geometry, where)
    return any(design.plank_index[c.plank] in group for c in geometry.contacts
               if c.wall is not None or c.anchor is not None) \
        or any(design.plank_index[a.plank] in group for a in design.anchors)


def _group(design: Design, geometry: Geometry, where: str) -> set[int]:
    """Plank indices of the group standing with the first plank of ``where``: jointed
    together or resting on each other."""
    parent = list(range(len(design.planks)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    index = design.plank_index
    links = [joint.planks for joint in geometry.joints]
    links += [(c.plank, c.on) for c in geometry.contacts if c.on is not None]
    for a, b in links:
        parent[root(index[a])] = root(index[b])
    first = root(index[where.split(",")[0].split("/")[0]])
    return {i for i in range(len(design.planks)) if root(i) == first}


def _group_loads(design: Design, geometry: Geometry, where: str,
                 case_name: str | None) -> tuple[np.ndarray, np.ndarray]:
    """(forces (k, 3) N, points (k, 3) m): the weight of each plank of the group at its
    centre and every load of the case on its planks (``_part_loads``)."""
    return _part_loads(design, case_name, frozenset(_group(design, geometry, where)))


def _floor_crossing(forces: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(2,) m: where the loads' resultant line meets the floor (z = 0): the point p with
    p x F = M, F the resultant and M the loads' moment about the origin (F_z < 0)."""
    return floor_point(forces.sum(axis=0), np.cross(points, forces).sum(axis=0))


def _hull(points: list, owners: list[str]) -> tuple[np.ndarray, list[str]]:
    """The support polygon of the contact points (``geometry.support.convex_hull``) and
    the plank of each of its points."""
    chosen = convex_hull(points)
    return np.array([points[k] for k in chosen], dtype=float), [owners[k] for k in chosen]


def _edge_planks(hull: np.ndarray, owners: list[str], point: np.ndarray) -> str:
    """The planks of the support polygon's edge (or corner) nearest ``point`` (on the
    polygon ``hull``, each vertex's plank in ``owners``): 'leg_r' at a corner or along
    one plank's edge, 'side_l and side_r' along an edge from one plank to another (a
    step's front edge, which both sides' feet make)."""
    distances = np.linalg.norm(hull - point, axis=1)
    vertex = int(np.argmin(distances))
    if distances[vertex] <= DUPLICATE or len(hull) < 2:
        return owners[vertex]
    k = nearest_edge(hull, point)[0]
    first, second = owners[k], owners[(k + 1) % len(hull)]
    return first if first == second else " and ".join(sorted((first, second)))


def _inside_fraction(hull: np.ndarray, start: np.ndarray, end: np.ndarray) -> float | None:
    """The largest f in [0, 1] with start + f (end - start) inside the convex polygon, or
    None when ``start`` itself lies outside (the loads topple it without the push)."""
    if len(hull) < 3 or outside(hull, start)[0] > 0.0:
        return None
    fraction = 1.0
    delta = end - start
    for a, b in zip(hull, np.roll(hull, -1, axis=0)):
        normal = np.array([b[1] - a[1], a[0] - b[0]])        # outward (counter-clockwise)
        rate = float(normal @ delta)
        if rate > 0.0:
            fraction = min(fraction, float(normal @ (a - start)) / rate)
    return max(fraction, 0.0)


# -- durability --------------------------------------------------------------------------
def _non_durable(design: Design, geometry: Geometry, where: str, case: CaseResult | None,
                 case_name: str | None) -> Need:
    if where.startswith("anchors["):
        return _anchor(design, where, case, case_name)
    joint = next((j for j in geometry.joints if j.name == where), None)
    result = next((j for j in case.joints if "/".join(j.planks) == where), None) \
        if case is not None else None
    if joint is None or result is None:
        return Need("non-durable", where, case_name, why="no joint result")
    ratio = max(result.pull / result.pull_capacity, result.shear / result.shear_capacity)
    nails = int(math.ceil(result.nails * ratio - 1e-9))
    values = {"pull": result.pull, "pull_capacity": result.pull_capacity,
              "shear": result.shear, "shear_capacity": result.shear_capacity,
              "nails": result.nails, "nails_needed": nails, "ratio": ratio}
    if not nails_listed(design, joint):
        spacing = design.material.nail_spacing
        values.update({"spacing": spacing / design.unit_scale,
                       "length": joint.length / design.unit_scale,
                       "length_needed": nails * spacing / design.unit_scale})
        room, plank, axis = min(_room(design.plank(p), joint.frame[:, 1])
                                for p in (joint.edge, joint.face))
        if nails * spacing > room * (1.0 + tol.ROOM_SLACK):
            values.update({"room": room / design.unit_scale, "room_plank": plank,
                           "room_grow": ("longer", "wider", "thicker")[axis]})
    return Need("non-durable", where, case_name, values=values)


def _room(plank: Plank, line: np.ndarray) -> tuple[float, str, int]:
    """(m, id, axis): how long a line along ``line`` (unit, world) through the plank's
    middle runs inside it (the chord of its box: 2 min_i h_i / |c_i|, c the line in the
    plank's axes), the plank's id and the local axis (0 length, 1 width, 2 thickness)
    whose faces end that chord: what a joint along the line has room for on it."""
    direction = np.abs(plank.rotation_matrix.T @ line)
    reach = [float(h) / float(c) if c > 1e-12 else math.inf
             for h, c in zip(plank.half_extents, direction)]
    axis = int(np.argmin(reach))
    return 2.0 * reach[axis], plank.id, axis


def _anchor(design: Design, where: str, case: CaseResult | None,
            case_name: str | None) -> Need:
    index = int(where[len("anchors["):-1])
    result = next((a for a in case.anchors if a.index == index), None) \
        if case is not None else None
    if result is None:
        return Need("non-durable", where, case_name, why="no anchor result")
    return Need("non-durable", where, case_name, values={
        "force": result.size, "capacity": result.capacity,
        "rating_needed": result.size * design.safety_factor,
        "ratio": result.size / result.capacity})


# -- bending (elastic model) -------------------------------------------------------------
def _bent(design: Design, geometry: Geometry, where: str, case: CaseResult | None,
          case_name: str | None, sagging: bool, across: bool = False) -> Need:
    kind = "sagging" if sagging else "overstressed"
    result = next((p for p in case.planks or () if p.id == where), None) \
        if case is not None else None
    if result is None:
        return Need(kind, where, case_name, why="no plank result")
    plank = design.plank(where)
    dimension, size = _bending_depth(plank, across)
    if sagging:
        creep = design.material_of(plank).creep
        ratio = result.sag * (1.0 + creep) / result.sag_allowed
        values = {"sag": result.sag, "creep": creep, "sag_allowed": result.sag_allowed,
                  "ratio": ratio, "exponent": 3}
        if across:                  # it bows sideways: the words say so
            values["sideways"] = True
    else:
        ratio = result.stress / result.strength
        values = {"stress": result.stress, "strength": result.strength, "ratio": ratio,
                  "exponent": 2}
    scale = design.unit_scale
    values.update({"dimension": dimension, "size": size / scale,
                   "size_needed": size * ratio ** (1.0 / values["exponent"]) / scale})
    return Need(kind, where, case_name, values=values)


def _bending_depth(plank: Plank, across: bool = False) -> tuple[str, float]:
    """('thickness', t) for a plank that bends across its thickness; ('width', w) for a
    plank on edge with its length level (a rail or apron under vertical loads), which
    bends across its width, unless it bows ``across`` (sideways: a coffee table's end
    panel splayed by its top, a rail pushed sideways), across its thickness."""
    rotation = plank.rotation_matrix
    length_axis = rotation[:, 0] if plank.length >= plank.width else rotation[:, 1]
    level = abs(float(length_axis[2])) < 1.0 - LEVEL_COS
    on_edge = abs(float(rotation[2, 2])) < 1.0 - LEVEL_COS
    if level and on_edge and not across:
        return "width", min(plank.length, plank.width)
    return "thickness", plank.thickness


# -- geometry ----------------------------------------------------------------------------
def _geometric(design: Design, geometry: Geometry, where: str, case: CaseResult | None,
               case_name: str | None, kind: str) -> Need:
    tolerance = design.tolerance
    scale = design.unit_scale
    if kind == "disconnected":
        if "/" not in where:
            return Need(kind, where, None, why="joined to nothing")
        a, b = (design.plank_index[p] for p in where.split("/", 1))
        sliver = end_bearing(design, a, b)
        if sliver is not None:                  # on the face, over too narrow a band
            band, thickness = sliver
            needed = MIN_BEARING_SHARE * thickness
            return Need(kind, where, None, values={
                "bearing": band / scale, "thickness": thickness / scale,
                "bearing_needed": needed / scale, "change_min": (needed - band) / scale,
                "change_max": (thickness - band) / scale})
        gap = end_gap(design, a, b, signed=True)
        if gap is None:
            return _drawn_through(design, where, a, b)
        distance = abs(gap)
    elif kind == "penetration":
        distance, wall = _deepest(design, design.plank(where))
    else:
        distance = min(float(design.plank(p).corners[:, 2].min()) for p in where.split(","))
        if where in carried_groups(design, geometry):
            return Need(kind, where, None, values={
                "distance": distance / scale, "tolerance": tolerance / scale,
                "carried": True})
    values = {"distance": distance / scale, "tolerance": tolerance / scale,
              "change_min": max(distance - tolerance, 0.0) / scale,
              "change_max": (distance + tolerance) / scale}
    if kind == "disconnected" and gap < 0.0:
        values["overlap"] = True
    if kind == "penetration" and wall is not None:
        values["wall"] = wall
    return Need(kind, where, None, values=values)


def _drawn_through(design: Design, where: str, a: int, b: int) -> Need:
    """The estimate for two planks drawn through each other (``geometry.drawn_through``):
    how deep (the least overlap of their boxes), and whether one is the other drawn
    twice (the same sizes, every corner within the tolerance of one of the other's)."""
    first, second = design.planks[a], design.planks[b]
    depth = next((d for i, j, d in interpenetrations(design)
                  if {i, j} == {first.id, second.id}), None)
    if depth is None:
        return Need("disconnected", where, None, why="neither plank's end faces the other")
    slack = design.tolerance + 1e-9
    gaps = np.linalg.norm(first.corners[:, None, :] - second.corners[None, :, :], axis=2)
    copy = bool(gaps.min(axis=1).max() <= slack and gaps.min(axis=0).max() <= slack)
    scale = design.unit_scale
    return Need("disconnected", where, None, values={
        "through": depth / scale, "copy": copy, "first": first.id, "second": second.id,
        "change_min": max(depth - design.tolerance, 0.0) / scale,
        "change_max": depth / scale})


def _deepest(design: Design, plank: Plank) -> tuple[float, int | None]:
    """(m, wall): how deep the plank's deepest corner lies below the floor or behind a wall
    (its index; None for the floor), whichever is deeper."""
    depth, where = -float(plank.corners[:, 2].min()), None
    for index, wall in enumerate(design.walls):
        behind = -float(((plank.corners - np.asarray(wall.point)) @ np.asarray(wall.normal))
                        .min())
        if behind > depth:
            depth, where = behind, index
    return depth, where


_ESTIMATES = {
    "sliding": _sliding,
    "lift-off": _lift_off,
    "non-durable": _non_durable,
    "sagging": lambda *args: _bent(*args, sagging=True),
    "overstressed": lambda *args: _bent(*args, sagging=False),
    "disconnected": lambda *args: _geometric(*args, kind="disconnected"),
    "penetration": lambda *args: _geometric(*args, kind="penetration"),
    "floating": lambda *args: _geometric(*args, kind="floating"),
}
"""Violation kind -> its estimate (design, geometry, where, case result, case name)."""
