"""A suggestion's cut list in the text report and the JSON (``suggest.cutlist``):

         changes 2 planks:
           leg_r: x 300 -> 560.3 mm
           stretcher: length 588 -> 848.6 mm, x 0 -> 130.3 mm

Lengths in the file's unit and angles in degrees to a tenth of the unit (a saw cuts no
finer), with more digits where a value would otherwise read unchanged; the JSON keeps the
report's six significant digits.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from furncheck.design.model import Design
from furncheck.report.common import plural
from furncheck.report.numbers import format_number
from furncheck.suggest.cutlist import (
    ANGLE_FIELDS,
    AnchorMove,
    LoadMove,
    LoadSpread,
    NailChange,
    PlankEdit,
    RatingChange,
)

AXIS_SLACK = 1.0
"""Degrees: a turn's axis this close to a world axis is named by it (``_turn``)."""

SAME_TURN = 1e-6
"""Degrees: angles that change by less than this as a turn are the same turn written
otherwise (near ry = 90 the file's angles trade places; 360 added to one)."""

MATERIAL_UNITS = {"density": "kg/m^3", "elastic_modulus": "N/mm^2",
                  "shear_modulus": "N/mm^2", "bending_strength": "N/mm^2", "creep": "",
                  "sag_limit": ""}
"""Units of a plank's own material values in a design file (lengths: the file's unit)."""


def cut_list_lines(edits: tuple[PlankEdit, ...], design: Design) -> list[str]:
    """'changes N planks:' and one line per plank (unindented; the caller indents)."""
    if not edits:
        return []
    lines = [f"changes {plural(len(edits), 'plank')}:"]
    for edit in edits:
        lines.append(f"  {edit.plank}: {_edit_text(edit, design)}")
    return lines


def nail_lines(changes: tuple[NailChange, ...]) -> list[str]:
    """'changes N joints:' and one line per joint (unindented): 'back/shelf: nails 4 -> 6'."""
    if not changes:
        return []
    return [f"changes {plural(len(changes), 'joint')}:",
            *(f"  {change.joint}: resting -> nailed, {plural(change.after, 'nail')}"
              if change.resting else f"  {change.joint}: nails {change.before} -> "
              f"{change.after}" for change in changes)]


def nails_json(changes: tuple[NailChange, ...]) -> list[dict[str, Any]]:
    """The JSON ``nails`` list: {"joint", "before", "after"} per changed joint, and
    ``"resting": true`` for a resting joint nailed (before: 0)."""
    return [{"joint": change.joint, "before": change.before, "after": change.after,
             **({"resting": True} if change.resting else {})} for change in changes]


def rating_lines(changes: tuple[RatingChange, ...]) -> list[str]:
    """'changes N wall fixings:' and one line per fixing (unindented): 'anchors[0]: rated
    120 -> 150 N'."""
    if not changes:
        return []
    return [f"changes {plural(len(changes), 'wall fixing')}:",
            *(f"  anchors[{change.anchor}]: rated {cut_number(change.before)} -> "
              f"{cut_number(change.after)} N" for change in changes)]


def added_anchor_lines(original: Design, edited: Design) -> list[str]:
    """'adds N wall fixings:' and one line per fixing a suggestion adds (the wall-anchor
    rule's; unindented), as its file lists them: 'anchors[0] on rail_l (wall 0): at
    (-300, 0, 1545.5) mm, rated 196 N'."""
    added = edited.anchors[len(original.anchors):]
    if not added:
        return []
    lines = [f"adds {plural(len(added), 'wall fixing')}:"]
    for index, anchor in enumerate(added, start=len(original.anchors)):
        point = ", ".join(cut_number(v / original.unit_scale) for v in anchor.point)
        lines.append(f"  anchors[{index}] on {anchor.plank} (wall {anchor.wall}): at "
                     f"({point}) {original.units}, rated {cut_number(anchor.capacity)} N")
    return lines


def ratings_json(changes: tuple[RatingChange, ...]) -> list[dict[str, Any]]:
    """The JSON ``ratings`` list: {"anchor", "before", "after"} (N) per changed fixing."""
    return [{"anchor": change.anchor, "before": change.before, "after": change.after}
            for change in changes]


def load_move_lines(moves: tuple[LoadMove, ...], design: Design) -> list[str]:
    """'moves N loads with their planks:' and one line per load (unindented): '80 kg on
    seat (case 'default'): at (560, 0, 450) -> (303.3, 0, 450) mm'."""
    return _moved_lines("load", moves, design,
                        lambda move: f"{move.load} on {move.plank} (case '{move.case}')")


def anchor_move_lines(moves: tuple[AnchorMove, ...], design: Design) -> list[str]:
    """'moves N wall fixings with their planks:' and one line per fixing (unindented):
    'anchors[0] on back (wall 0): at (-350, 0, 1620) -> (-350, 0, 1792.5) mm'."""
    return _moved_lines("wall fixing", moves, design,
                        lambda move: f"anchors[{move.anchor}] on {move.plank} "
                                     f"(wall {move.wall})")


def _moved_lines(what: str, moves: tuple, design: Design, label) -> list[str]:
    """'moves N <what>s with their planks:' and one line per move, ``label(move)``: at
    (before) -> (after) in the file's unit."""
    if not moves:
        return []
    planks = "its plank" if len(moves) == 1 else "their planks"
    lines = [f"moves {plural(len(moves), what)} with {planks}:"]
    for move in moves:
        for extra in range(MOVE_EXTRA_DIGITS + 1):     # digits enough to show the move
            start = ", ".join(cut_number(v, extra) for v in move.before)
            end = ", ".join(cut_number(v, extra) for v in move.after)
            if start != end:
                break
        lines.append(f"  {label(move)}: at ({start}) -> ({end}) {design.units}")
    return lines


MOVE_EXTRA_DIGITS = 4
"""Digits a moved load's or fixing's point may be written with beyond a tenth of the unit,
so that its line shows the move ('(0, 395, 745) -> (0, 395, 745)' read as none)."""


def load_spread_lines(spreads: tuple[LoadSpread, ...], design: Design) -> list[str]:
    """'spreads N loads over their resized planks:' and one line per load (unindented):
    "20 kg spread on top (case 'default'): over 1749 x 600 mm, was 1200 x 600 mm"."""
    if not spreads:
        return []
    planks = "its resized plank" if len(spreads) == 1 else "their resized planks"
    lines = [f"spreads {plural(len(spreads), 'load')} over {planks}:"]
    for spread in spreads:
        lines.append(f"  {spread.load} spread on {spread.plank} (case '{spread.case}'): over "
                     f"{cut_number(spread.after[0])} x {cut_number(spread.after[1])} "
                     f"{design.units}, was {cut_number(spread.before[0])} x "
                     f"{cut_number(spread.before[1])} {design.units}")
    return lines


def load_spreads_json(spreads: tuple[LoadSpread, ...]) -> list[dict[str, Any]]:
    """``[{"case", "plank", "load", "from": [length, width], "to": [length, width]}]``."""
    return [{"case": spread.case, "plank": spread.plank, "load": spread.load,
             "from": list(spread.before), "to": list(spread.after)} for spread in spreads]


def load_moves_json(moves: tuple[LoadMove, ...]) -> list[dict[str, Any]]:
    """``[{"case", "plank", "load", "from": [x, y, z], "to": [x, y, z]}]``."""
    return [{"case": move.case, "plank": move.plank, "load": move.load,
             "from": list(move.before), "to": list(move.after)} for move in moves]


def anchor_moves_json(moves: tuple[AnchorMove, ...]) -> list[dict[str, Any]]:
    """``[{"anchor", "plank", "wall", "from": [x, y, z], "to": [x, y, z]}]``."""
    return [{"anchor": move.anchor, "plank": move.plank, "wall": move.wall,
             "from": list(move.before), "to": list(move.after)} for move in moves]


def edits_json(edits: tuple[PlankEdit, ...]) -> list[dict[str, Any]]:
    """``[{"plank", "edit": "change"|"add"|"remove", "fields": {field: [from, to]}}]``,
    null for the side where the plank does not exist."""
    return [{"plank": edit.plank, "edit": edit.action,
             "fields": {f.field: [f.before, f.after] for f in edit.fields}}
            for edit in edits]


def _edit_text(edit: PlankEdit, design: Design) -> str:
    values = {f.field: (f.before, f.after) for f in edit.fields}
    if edit.action == "add":
        new = {name: after for name, (_, after) in values.items()}
        unit = design.units
        text = (f"new plank {cut_number(new['length'])} x {cut_number(new['width'])} x "
                f"{cut_number(new['thickness'])} {unit}, centred at ({cut_number(new['x'])}, "
                f"{cut_number(new['y'])}, {cut_number(new['z'])}) {unit}")
        if any(new[name] for name in ANGLE_FIELDS):
            text += (f", turned ({cut_number(new['rx'])}, {cut_number(new['ry'])}, "
                     f"{cut_number(new['rz'])}) degrees")
        return text
    if edit.action == "remove":
        return "taken away"
    text = ", ".join(f"{_label(f.field)} {from_to(f.before, f.after)}"
                     f"{_unit_of(f.field, design)}" for f in edit.fields)
    if sum(name in values for name in ANGLE_FIELDS) > 1:     # several angles, one turn
        text += f" ({_turn(edit, design)})"
    return text


def _turn(edit: PlankEdit, design: Design) -> str:
    """The change of a plank's angles as the one turn it is, 'a turn of 1.5 degrees about
    x' (about a world axis where the turn's axis lies within AXIS_SLACK of one, else
    about the axis (x, y, z)): the file's three angles can change by much more than the
    plank turns (a leg stood upright by ry = -90 and tilted 1.5 degrees reads rx 0 -> 90,
    ry -90 -> -88.5, rz 0 -> -90)."""
    from furncheck.design.model import rotation_matrix

    old = design.plank(edit.plank).rotation
    new = [f.after if f is not None else value
           for f, value in zip((edit.field(name) for name in ANGLE_FIELDS), old)]
    turn = rotation_matrix(new) @ rotation_matrix(old).T
    angle = math.degrees(math.acos(min(max((float(np.trace(turn)) - 1.0) / 2.0, -1.0), 1.0)))
    if angle < SAME_TURN:
        return "the same turn, its angles written otherwise"
    axis = np.array([turn[2, 1] - turn[1, 2], turn[0, 2] - turn[2, 0], turn[1, 0] - turn[0, 1]])
    if np.linalg.norm(axis) < 1e-6:     # a half turn: the axis is R + I's largest column
        half = turn + np.eye(3)
        axis = half[:, int(np.argmax(np.linalg.norm(half, axis=0)))]
    axis /= np.linalg.norm(axis)
    named = int(np.argmax(np.abs(axis)))
    if abs(axis[named]) >= math.cos(math.radians(AXIS_SLACK)):
        sign = "" if axis[named] > 0.0 or angle > 179.999 else "-"
        return f"a turn of {cut_number(angle)} degrees about {sign}{'xyz'[named]}"
    shown = ", ".join(f"{round(float(v), 2) + 0.0:g}" for v in axis)
    return f"a turn of {cut_number(angle)} degrees about ({shown})"


def from_to(before: float, after: float) -> str:
    """'588 -> 848.1'; with more digits where the two would read the same (a change
    finer than a tenth of the unit is still a change)."""
    for extra in range(0, 9):
        old, new = cut_number(before, extra), cut_number(after, extra)
        if old != new:
            break
    return f"{old} -> {new}"


def _label(field: str) -> str:
    return field.removeprefix("material.")


def _unit_of(field: str, design: Design) -> str:
    if field in ANGLE_FIELDS:
        return " degrees"
    if field.startswith("material."):
        unit = MATERIAL_UNITS.get(field.removeprefix("material."), design.units)
        return f" {unit}" if unit else ""
    return f" {design.units}"


def cut_number(value: float | None, extra: int = 0) -> str:
    """To a tenth of the unit or finer (at least four significant digits), ``extra``
    digits more; '-' for no value."""
    if value is None:
        return "-"
    whole = len(str(int(abs(round(value)))))
    return format_number(value, max(4, whole + 1) + extra)
