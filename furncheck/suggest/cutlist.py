"""The cut list of a suggestion: every plank it changes, adds or removes, from -> to.

``plank_edits(before, after)`` compares two designs plank by plank (matched by id) in the
values a design file writes: sizes and positions in the file's length unit, angles in
degrees, a plank's own material values in the file's units.  Every suggestion kind gets
its cut list from it (``ranking``): a continuous one's DOF changes *and* what the
geometric constraints made the neighbours do (a stretcher that lengthens with the leg it
joins), a discrete one's added planks.  The suggestion's design is parsed from the very
text of its file, so its cut list is the difference between the input file and the
written one.

    fields : length, width, thickness, x, y, z (the centre), rx, ry, rz (degrees), then
             material.<key> for the plank's own material values (``PLANK_MATERIAL_KEYS``)
"""

from __future__ import annotations

from dataclasses import dataclass

from furncheck.design.materials import PLANK_MATERIAL_KEYS, material_entry
from furncheck.design.model import Design, Plank
from furncheck.design.write import in_unit
from furncheck.plain import plain_load
from furncheck.tolerances import CUT_LIST_EPS

GEOMETRY_FIELDS = ("length", "width", "thickness", "x", "y", "z", "rx", "ry", "rz")
"""The fields of a plank's cut-list entry, in order, before its material values."""

SIZE_FIELDS = ("length", "width", "thickness")
POSITION_FIELDS = ("x", "y", "z")
ANGLE_FIELDS = ("rx", "ry", "rz")

@dataclass(frozen=True)
class FieldChange:
    """One field of one plank: its value before and after (None where the plank does not
    exist: an added plank has no ``before``, a removed one no ``after``); file length unit,
    degrees, or the material key's file unit."""

    field: str
    before: float | None
    after: float | None

    @property
    def change(self) -> float:
        """after - before (0 for an added or removed plank's field)."""
        if self.before is None or self.after is None:
            return 0.0
        return self.after - self.before


@dataclass(frozen=True)
class PlankEdit:
    """What a suggestion does to one plank: ``action`` 'change' (only the changed fields
    listed), 'add' or 'remove' (every field listed, the missing side None)."""

    plank: str
    action: str
    fields: tuple[FieldChange, ...]

    def field(self, name: str) -> FieldChange | None:
        return next((f for f in self.fields if f.field == name), None)


def plank_values(plank: Plank, design: Design) -> dict[str, float]:
    """The plank's cut-list fields (GEOMETRY_FIELDS, then material.<key>) as its design
    file writes them: lengths in ``design``'s unit to 12 significant digits, degrees."""
    scale = design.unit_scale
    values = {
        "length": in_unit(plank.length, scale),
        "width": in_unit(plank.width, scale),
        "thickness": in_unit(plank.thickness, scale),
        "x": in_unit(plank.center[0], scale),
        "y": in_unit(plank.center[1], scale),
        "z": in_unit(plank.center[2], scale),
        "rx": float(plank.rotation[0]),
        "ry": float(plank.rotation[1]),
        "rz": float(plank.rotation[2]),
    }
    own = material_entry(dict(plank.material), scale)
    for key in PLANK_MATERIAL_KEYS:
        if key in own:
            values[f"material.{key}"] = float(own[key])
    return values


def plank_edits(before: Design, after: Design) -> tuple[PlankEdit, ...]:
    """Every plank that ``after`` changes (in ``before``'s plank order), then every plank
    it adds (in its order), then every plank of ``before`` it lacks.  A field counts as
    changed when it moves by more than CUT_LIST_EPS (its unit); a material value that one
    side sets and the other does not is listed with None on the other side.  Both designs
    are read in ``before``'s length unit."""
    edits: list[PlankEdit] = []
    kept = {p.id for p in after.planks}
    for plank in before.planks:
        if plank.id not in kept:
            continue
        old = plank_values(plank, before)
        new = plank_values(after.plank(plank.id), before)
        changes = tuple(FieldChange(name, old.get(name), new.get(name))
                        for name in _ordered(old, new) if _differs(old.get(name), new.get(name)))
        if changes:
            edits.append(PlankEdit(plank.id, "change", changes))
    known = {p.id for p in before.planks}
    for plank in after.planks:
        if plank.id not in known:
            values = plank_values(plank, before)
            edits.append(PlankEdit(plank.id, "add", tuple(
                FieldChange(name, None, value) for name, value in values.items())))
    for plank in before.planks:
        if plank.id not in kept:
            values = plank_values(plank, before)
            edits.append(PlankEdit(plank.id, "remove", tuple(
                FieldChange(name, value, None) for name, value in values.items())))
    return tuple(edits)


@dataclass(frozen=True)
class NailChange:
    """A listed joint whose nail count a suggestion changes (``discrete.nails``), or a
    resting joint it nails (``discrete.nail_down``: ``resting``, from 0 nails to the
    count its length takes)."""

    joint: str
    before: int
    after: int
    resting: bool = False


def nail_changes(before: Design, after: Design) -> tuple[NailChange, ...]:
    """The listed joints of ``before`` whose explicit nail count ``after`` changes, and
    its resting joints that ``after`` nails (their nails as its geometry counts them),
    matched by their planks, in ``before``'s order ('a/b' as the file lists them)."""
    if before.joints is None or after.joints is None:
        return ()
    specs = {frozenset(spec.planks): spec for spec in after.joints}
    nailed = [spec for spec in before.joints if spec.rests
              and (other := specs.get(frozenset(spec.planks))) is not None and not other.rests]
    counted = {}
    if nailed:
        from furncheck.geometry import analyze

        counted = {frozenset(joint.planks): joint.nails for joint in analyze(after).joints}
    changes = []
    for spec in before.joints:
        other = specs.get(frozenset(spec.planks))
        if other is None:
            continue
        if spec in nailed:
            changes.append(NailChange("/".join(spec.planks), 0,
                                      counted.get(frozenset(spec.planks), 0), resting=True))
        elif spec.nails is not None and other.nails not in (None, spec.nails):
            changes.append(NailChange("/".join(spec.planks), spec.nails, other.nails))
    return tuple(changes)


@dataclass(frozen=True)
class RatingChange:
    """A wall fixing of the input whose rating a suggestion changes (``discrete.fixings``):
    its place in the file's ``anchors`` list and its capacity before and after (N)."""

    anchor: int
    before: float
    after: float


def rating_changes(before: Design, after: Design) -> tuple[RatingChange, ...]:
    """The anchors of ``before`` whose ``capacity`` ``after`` changes, in the file's order."""
    return tuple(RatingChange(index, old.capacity, new.capacity)
                 for index, (old, new) in enumerate(zip(before.anchors, after.anchors))
                 if old.capacity != new.capacity)


def friction_change(before: Design, after: Design) -> tuple[float, float] | None:
    """(before, after): the design's friction where ``after`` changes it (non-slip pads,
    ``discrete.pads``), else None."""
    old, new = before.material.friction, after.material.friction
    return None if old == new else (old, new)


@dataclass(frozen=True)
class LoadMove:
    """A load at a point that a suggestion carries along with its plank (a load keeps its
    place along a plank that is moved, turned or resized: the person at the seat's end
    sits at the end of the shortened seat): the first case it is in, its plank, what it
    is ('80 kg' or '100 N', as the case's load list says it) and its point before and
    after (file length unit)."""

    case: str
    plank: str
    load: str
    before: tuple[float, float, float]
    after: tuple[float, float, float]


def load_moves(before: Design, after: Design) -> tuple[LoadMove, ...]:
    """Every load at a point whose point ``after`` moves by more than CUT_LIST_EPS (the
    same load in several cases, through ``include``, once), in case and load order."""
    scale = before.unit_scale
    cases = {case.name: case for case in after.load_cases}
    moves: list[LoadMove] = []
    seen = set()
    for case in before.load_cases:
        other = cases.get(case.name)
        if other is None or len(other.loads) != len(case.loads):
            continue
        for old, new in zip(case.loads, other.loads):
            if old.point is None or new.point is None or old.plank != new.plank:
                continue
            moved = _point_move(old.point, new.point, scale)
            if moved is None:
                continue
            start, end = moved
            what = plain_load(old.mass, old.force)
            key = (old.plank, what, start, end)
            if key not in seen:
                seen.add(key)
                moves.append(LoadMove(case.name, old.plank, what, start, end))
    return tuple(moves)


@dataclass(frozen=True)
class AnchorMove:
    """A wall fixing of the input that a suggestion carries along with its plank (an
    anchor keeps its place on its plank when the plank is moved, turned or resized:
    README "Anchors"), so that the maker drills for it where the fix needs it: its place
    in the file's ``anchors`` list (from 0, as ``anchors[n]`` names it), its plank and
    wall, and its point before and after (file length unit)."""

    anchor: int
    plank: str
    wall: int
    before: tuple[float, float, float]
    after: tuple[float, float, float]


def anchor_moves(before: Design, after: Design) -> tuple[AnchorMove, ...]:
    """Every anchor of ``before`` whose point ``after`` moves by more than CUT_LIST_EPS,
    in the file's order (anchors that ``after`` adds are the wall-anchor rule's own,
    listed with its suggestion)."""
    scale = before.unit_scale
    moves = []
    for index, (old, new) in enumerate(zip(before.anchors, after.anchors)):
        moved = _point_move(old.point, new.point, scale)
        if moved is not None:
            moves.append(AnchorMove(index, old.plank, old.wall, *moved))
    return tuple(moves)


@dataclass(frozen=True)
class LoadSpread:
    """A load spread along its plank (``spread: true``: books on a shelf) on a plank that
    a suggestion lengthens or widens (or shortens, narrows): the same load then spreads
    over the plank as it is after, so that a longer top carries it thinner, which a
    maker should know before taking the fix (the dinner does not grow with the table).
    Its first case, its plank, what it is ('20 kg'), and the plank's length and width
    before and after (file length unit)."""

    case: str
    plank: str
    load: str
    before: tuple[float, float]
    after: tuple[float, float]


def load_spreads(before: Design, after: Design) -> tuple[LoadSpread, ...]:
    """Every spread load whose plank ``after`` resizes by more than CUT_LIST_EPS, in case
    and load order: each load of the file once (one that several cases include, by the
    case whose entry gives it and its place there; two equal loads on one plank twice)."""
    scale = before.unit_scale
    old_planks = {p.id: p for p in before.planks}
    new_planks = {p.id: p for p in after.planks}
    spreads: list[LoadSpread] = []
    seen = set()
    for case in before.load_cases:
        places: dict[str, int] = {}
        for index, load in enumerate(case.loads):
            origin = case.origin(index)
            place = places[origin] = places.get(origin, -1) + 1
            if not load.spread or load.plank not in new_planks or (origin, place) in seen:
                continue
            old, new = old_planks[load.plank], new_planks[load.plank]
            start = (in_unit(old.length, scale), in_unit(old.width, scale))
            end = (in_unit(new.length, scale), in_unit(new.width, scale))
            if any(_differs(a, b) for a, b in zip(start, end)):
                seen.add((origin, place))
                spreads.append(LoadSpread(case.name, load.plank,
                                          plain_load(load.mass, load.force), start, end))
    return tuple(spreads)


def planks_touched(edits: tuple[PlankEdit, ...]) -> int:
    """How many planks a maker has to cut, move or add (or take away)."""
    return len(edits)


def _ordered(old: dict[str, float], new: dict[str, float]) -> list[str]:
    names = list(GEOMETRY_FIELDS)
    names += [f"material.{key}" for key in PLANK_MATERIAL_KEYS
              if f"material.{key}" in old or f"material.{key}" in new]
    return names


def _point_move(old, new, scale: float) -> tuple[tuple, tuple] | None:
    """(before, after) of a point (m) in the file's unit, where it moves by more than
    CUT_LIST_EPS along some axis; None where it stays."""
    start = tuple(in_unit(v, scale) for v in old)
    end = tuple(in_unit(v, scale) for v in new)
    return (start, end) if any(_differs(a, b) for a, b in zip(start, end)) else None


def _differs(old: float | None, new: float | None) -> bool:
    if old is None or new is None:
        return old is not new
    return abs(new - old) > CUT_LIST_EPS
