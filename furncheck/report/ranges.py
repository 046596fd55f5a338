"""Reports of ``furncheck range``: a readable table, or the JSON of contract section 4."""

from __future__ import annotations

import json

from furncheck.files import neutral
from furncheck.ranges import DofRange
from furncheck.report.numbers import format_number, json_ready
from furncheck.report.text import shown


def render_json(design: str, ranges: list[DofRange]) -> str:
    """``{"design": ..., "ranges": [{"dof", "value", "valid", "unit"[, "reason"][,
    "limited"][, "rotations"]}]}``; ``limited`` ([low, high], only where one is true):
    that end is the search's limit, valid itself, nothing beyond it searched (contract
    section 4's ``valid`` is the interval within which the design stays valid: so far as
    searched); ``rotations``: for a turn the file's angle of its name does not follow
    alone, the file's rotation at the low and high ends (``DofRange.rotations``)."""
    entries = []
    for item in ranges:
        entry = {"dof": item.dof, "value": item.value,
                 "valid": list(item.valid) if item.valid is not None else None,
                 "unit": item.unit}
        if item.reason:
            entry["reason"] = item.reason
        if any(item.limited):
            entry["limited"] = list(item.limited)
        if item.rotations is not None:
            entry["rotations"] = [list(item.rotations[0]), list(item.rotations[1])]
        entries.append(entry)
    return json.dumps(json_ready({"design": design, "ranges": entries}), indent=2,
                      allow_nan=False) + "\n"


def render_text(design: str, ranges: list[DofRange]) -> str:
    """One row per DOF: name, current value, valid interval, unit, and why when a DOF
    cannot move (or the current value is invalid)."""
    rows = [("DOF", "value", "valid range", "unit", "")]
    for item in ranges:
        interval = "-" if item.valid is None else \
            f"{format_number(item.valid[0], 5)} .. {format_number(item.valid[1], 5)}"
        rows.append((item.dof, format_number(item.value, 5), interval, item.unit,
                     "; ".join(note for note in (item.reason, _limited(item),
                                                 _rotations(item)) if note)))
    widths = [max(len(row[i]) for row in rows) for i in range(4)]
    lines = [f"{shown(design)}:"]
    for dof, value, interval, unit, reason in rows:
        lines.append(f"  {dof:<{widths[0]}}  {value:>{widths[1]}}  {interval:<{widths[2]}}  "
                     f"{unit:<{widths[3]}}  {reason}".rstrip())
    return neutral("\n".join(lines) + "\n")


def _limited(item: DofRange) -> str:
    """Words for an interval that ends at the search's limit ('' when neither does)."""
    if not any(item.limited):
        return ""
    reach = f"{format_number(item.limit, 5)} {item.unit}"
    if all(item.limited):
        return f"valid as far as searched: {reach} either way"
    return f"valid as far as searched: {reach} {'down' if item.limited[0] else 'up'}"


def _rotations(item: DofRange) -> str:
    """The file's rotation at a turn's ends, where its own angle does not follow alone."""
    if item.rotations is None:
        return ""
    low, high = ("[" + ", ".join(format_number(v, 5) for v in angles) + "]"
                 for angles in item.rotations)
    return f"a turn about world {item.dof[-1]}: the file's rotation {low} .. {high}"
