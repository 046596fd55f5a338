"""Reports of ``furncheck suggest``: advice a maker can act on, or the JSON of contract
section 4.

    designs/shelf-cantilever-overloaded.yaml: INVALID, 1 violation
      non-durable: post/shelf in case 'default': pull 1005 N per nail exceeds 700 N
    3 suggestions:
      1. Shorten shelf by 180 mm (valid for 120-241 mm). Restores durability.
         design: out/suggestion-01.yaml
      ...
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from furncheck.design.model import Design
from furncheck.design.write import anchor_entry, plank_entry
from furncheck.export.suggestions import Written
from furncheck.report.common import plural
from furncheck.report.explanation import explanation_dict, explanation_lines
from furncheck.report.numbers import format_number, json_ready
from furncheck.report.text import INDENT, design_lines
from furncheck.suggest import Suggestion, SuggestionReport

ADVICE_DIGITS = 3
"""Significant digits of the amounts in the advice (the JSON keeps REPORT digits)."""

PARALLEL_COSINE = 0.95
"""Planks whose face normals' cosine exceeds this count as parallel."""

TOWARD_COSINE = 0.5
"""A plank is 'toward' which a move goes when the direction to its centre is within 60
degrees of the move."""


def advice(suggestion: Suggestion, original: Design) -> str:
    """'Move shelf 42 mm toward post and tilt it 3 degrees about y (valid for 18-61 mm).'
    or 'Add support-1 (582 x 300 mm) between shelf and base, centred at (250, 0, 303) mm,
    nailed to both.' (or 'under ledge, standing on the floor, ...')"""
    if suggestion.kind == "discrete":
        return suggestion.advice
    phrases = []
    for k, (name, change, unit) in enumerate(zip(suggestion.dofs, suggestion.changes,
                                                 suggestion.units)):
        plank, _, kind = name.rpartition(".")
        subject = plank if k == 0 or suggestion.dofs[k - 1].rpartition(".")[0] != plank \
            else "it"
        phrases.append(_phrase(original, plank, subject, kind, change, unit))
    sentence = " and ".join(phrases)
    low, high = suggestion.range
    step = suggestion.step
    lead = abs(suggestion.changes[0]) / step if step else 0.0
    unit = suggestion.units[0]
    valid_for = (f"valid for {_amount(low * lead)}-{_amount(high * lead)} {_unit(unit)}"
                 + (" of the first change" if len(suggestion.dofs) > 1 else ""))
    return f"{sentence[0].upper()}{sentence[1:]} ({valid_for})."


def _phrase(design: Design, plank: str, subject: str, kind: str, change: float,
            unit: str) -> str:
    amount = f"{_amount(abs(change))} {_unit(unit)}"
    if kind == "z":
        return f"{'raise' if change > 0 else 'lower'} {subject} by {amount}"
    if kind in ("x", "y"):
        sign = 1.0 if change > 0 else -1.0
        ahead = _toward(design, plank, "xy".index(kind), sign)
        behind = _toward(design, plank, "xy".index(kind), -sign)
        where = f"toward {ahead}" if ahead else f"away from {behind}" if behind else \
            f"along {'+' if change > 0 else '-'}{kind}"
        return f"move {subject} {amount} {where}"
    if kind == "length":
        return f"{'lengthen' if change > 0 else 'shorten'} {subject} by {amount}"
    if kind == "width":
        return f"{'widen' if change > 0 else 'narrow'} {subject} by {amount}"
    verb = "turn" if kind == "rz" else "tilt"
    sign = "+" if change > 0 else "-"
    return f"{verb} {subject} by {sign}{amount} about {kind[1]}"


def _toward(design: Design, plank_id: str, axis: int, sign: float) -> str | None:
    """The plank ahead of a move along ``axis``: among the others whose centre lies
    within 60 degrees of the move, a parallel one (the other leg of a pair) before the
    rest, then the nearest."""
    moved = design.plank(plank_id)
    normal = moved.rotation_matrix[:, 2]
    best, best_key = None, None
    for plank in design.planks:
        offset = plank.center_array - moved.center_array
        distance = float(np.linalg.norm(offset))
        if plank.id == plank_id or distance == 0 or sign * offset[axis] < TOWARD_COSINE * distance:
            continue
        parallel = abs(float(plank.rotation_matrix[:, 2] @ normal)) > PARALLEL_COSINE
        key = (not parallel, distance)
        if best_key is None or key < best_key:
            best, best_key = plank.id, key
    return best


def _amount(value: float) -> str:
    """ADVICE_DIGITS significant digits, but whole units at least (1250 mm, not 1.25e+03)."""
    whole = len(str(int(abs(round(value)))))
    return format_number(value, max(ADVICE_DIGITS, whole))


def _unit(unit: str) -> str:
    return "degrees" if unit == "deg" else unit


def render_text(result: SuggestionReport, original: Design,
                written: dict[int, Written]) -> str:
    """The verdict, then one numbered piece of advice per suggestion and its files."""
    lines = design_lines(result.report)
    if result.valid:
        lines.append("Nothing needs to change: the design is valid.")
        return "\n".join(lines) + "\n"
    explanation = result.explanation
    if not result.suggestions:
        lines.append("No suggestion: no change of the allowed DOFs was found that makes "
                     "the design valid.")
        if explanation is not None:
            lines.extend(explanation_lines(explanation, original.units, 0, INDENT))
        return "\n".join(lines) + "\n"
    lines.append(f"{plural(len(result.suggestions), 'suggestion')}:")
    for suggestion in result.suggestions:
        restores = " and ".join(suggestion.restores)
        lines.append(f"{INDENT}{suggestion.rank}. {advice(suggestion, original)} "
                     f"Restores {restores}.")
        files = written.get(suggestion.rank)
        if files is not None and files.design_file:
            lines.append(f"{INDENT}   design: {files.design_file}")
            for path in (*files.meshes, *files.plots):
                lines.append(f"{INDENT}   {path}")
    if explanation is not None and len(result.suggestions) < explanation.tried.wanted:
        lines.append(f"Fewer than the {explanation.tried.wanted} asked for:")
        lines.extend(explanation_lines(explanation, original.units, len(result.suggestions),
                                       INDENT))
    return "\n".join(lines) + "\n"


def render_json(result: SuggestionReport, original: Design,
                written: dict[int, Written]) -> str:
    """Contract section 4: design, valid, violations, suggestions (with ``advice`` and
    ``plots`` added; files null/empty without ``--out``), and for an invalid design the
    ``explanation`` (what remains, what it would take, what was tried)."""
    report = result.report
    document: dict[str, Any] = {
        "design": result.design,
        "valid": result.valid,
        "violations": [{"kind": v.kind, "where": v.where, "case": v.case,
                        "message": v.message} for v in report.violations],
        "suggestions": [_suggestion_dict(s, original, written.get(s.rank, Written()))
                        for s in result.suggestions],
    }
    if result.explanation is not None:
        document["explanation"] = explanation_dict(result.explanation, original.units)
    return json.dumps(json_ready(document), indent=2, allow_nan=False) + "\n"


def _suggestion_dict(suggestion: Suggestion, original: Design,
                     files: Written) -> dict[str, Any]:
    if suggestion.kind == "discrete":
        entry = {
            "rank": suggestion.rank,
            "kind": suggestion.kind,
            "rule": suggestion.rule,
            "restores": list(suggestion.restores),
            "adds": [plank_entry(plank, original) for plank in suggestion.adds],
            "between": list(suggestion.between),
            "advice": advice(suggestion, original),
            "design_file": files.design_file,
            "meshes": list(files.meshes),
            "plots": list(files.plots),
        }
        added = suggestion.design.anchors[len(original.anchors):]
        if added:           # a wall anchor: the fixings, as a design file lists them
            entry["anchors"] = [anchor_entry(anchor, original) for anchor in added]
        return entry
    return {
        "rank": suggestion.rank,
        "kind": suggestion.kind,
        "restores": list(suggestion.restores),
        "dofs": list(suggestion.dofs),
        "direction": list(suggestion.direction),
        "range": list(suggestion.range),
        "step": suggestion.step,
        "changes": dict(zip(suggestion.dofs, suggestion.changes)),
        "advice": advice(suggestion, original),
        "design_file": files.design_file,
        "meshes": list(files.meshes),
        "plots": list(files.plots),
    }
