"""Reports of ``furncheck suggest``: advice a maker can act on, or the JSON of contract
section 4.

    designs/shelf-cantilever-overloaded.yaml: INVALID, 1 violation
      non-durable: post/shelf in case 'default': pull 1005 N per nail exceeds 700 N
    3 suggestions:
      1. Shorten shelf by 180 mm (valid for 120-397 mm). Restores durability.
         changes 1 plank:
           shelf: length 400 -> 219.5 mm, x 350 -> 259.8 mm
         design: out/suggestion-01.yaml
      ...

A suggestion whose proportions a maker would not build (``suggest.score``) says why it is
ranked after the others ('implausible proportion: slat_12 hangs 64 % of its end past the
edge of cap, which it is nailed to').

The sentence of a continuous suggestion is ``shop_words``', its cut list ``cutlist``'s.
"""

from __future__ import annotations

import json
from typing import Any

from furncheck.design.model import Design
from furncheck.design.write import anchor_entry, plank_entry
from furncheck.export.suggestions import Written
from furncheck.files import neutral
from furncheck.plain import plain_number
from furncheck.report.common import plural
from furncheck.report.cutlist import (
    added_anchor_lines,
    anchor_move_lines,
    anchor_moves_json,
    cut_list_lines,
    edits_json,
    load_move_lines,
    load_moves_json,
    load_spread_lines,
    load_spreads_json,
    nail_lines,
    nails_json,
    rating_lines,
    ratings_json,
)
from furncheck.report.explanation import explanation_dict, explanation_lines
from furncheck.report.numbers import json_ready
from furncheck.report.shop_words import change_sentence, continuous_advice, follow_phrase
from furncheck.report.text import INDENT, design_lines
from furncheck.suggest import Suggestion, SuggestionReport
from furncheck.suggest.cutlist import friction_change, nail_changes, rating_changes


def advice(suggestion: Suggestion, original: Design) -> str:
    """'Move shelf 42 mm toward post and tilt it 3 degrees about y (valid for 18-61 mm).'
    or 'Add support-1 (582 x 300 mm) between shelf and base, centred at (250, 0, 303) mm,
    nailed to both.' (or 'under ledge, standing on the floor, ...')"""
    if suggestion.kind == "discrete" and not suggestion.dofs:
        return suggestion.advice
    follow = follow_phrase(suggestion.edits, {name.rpartition(".")[0] for name in
                                              suggestion.dofs}, original.units,
                           suggestion.advice)
    if suggestion.kind == "discrete":                       # a closure, finished
        closing = change_sentence(suggestion.dofs, suggestion.changes, suggestion.units,
                                  original, suggestion.design)
        return f"{closing}{follow}, and {suggestion.advice}"
    return continuous_advice(suggestion.dofs, suggestion.changes, suggestion.units,
                             suggestion.step, suggestion.range, suggestion.limited, original,
                             suggestion.design, follow)


def render_text(result: SuggestionReport, original: Design,
                written: dict[int, Written]) -> str:
    """The verdict, then one numbered piece of advice per suggestion and its files
    (``text.neutral``)."""
    return neutral(_text(result, original, written))


def _text(result: SuggestionReport, original: Design, written: dict[int, Written]) -> str:
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
        for line in (*cut_list_lines(suggestion.edits, original),
                     *nail_lines(nail_changes(original, suggestion.design)),
                     *added_anchor_lines(original, suggestion.design),
                     *rating_lines(rating_changes(original, suggestion.design)),
                     *_friction_lines(friction_change(original, suggestion.design)),
                     *load_move_lines(suggestion.loads_moved, original),
                     *load_spread_lines(suggestion.loads_spread, original),
                     *anchor_move_lines(suggestion.anchors_moved, original),
                     *_implausible_lines(suggestion)):
            lines.append(f"{INDENT}   {line}")
        files = written.get(suggestion.rank)
        if files is not None and files.design_file:
            lines.append(f"{INDENT}   design: {files.design_file}")
            for path in (*files.meshes, *files.plots):
                lines.append(f"{INDENT}   {path}")
    if explanation is not None and len(result.suggestions) < explanation.tried.wanted:
        lines.append(f"Fewer than {explanation.tried.wanted}, the most it lists "
                     "(--max-suggestions):")
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
            **_changes_and_files(suggestion, files),
        }
        added = suggestion.design.anchors[len(original.anchors):]
        if added:           # a wall anchor: the fixings, as a design file lists them
            entry["anchors"] = [anchor_entry(anchor, original) for anchor in added]
        nails = nail_changes(original, suggestion.design)
        if nails:           # more nails in a listed joint
            entry["nails"] = nails_json(nails)
        ratings = rating_changes(original, suggestion.design)
        if ratings:         # stronger wall fixings
            entry["ratings"] = ratings_json(ratings)
        friction = friction_change(original, suggestion.design)
        if friction is not None:    # non-slip pads
            entry["friction"] = list(friction)
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
        "limited": suggestion.limited,
        **_changes_and_files(suggestion, files),
    }


def _changes_and_files(suggestion: Suggestion, files: Written) -> dict[str, Any]:
    """The entries that close every suggestion's JSON, continuous or discrete, in the
    contract's order: what it changes (its cut list, the loads and fixings it carries
    along), its score and the files written for it."""
    return {
        "edits": edits_json(suggestion.edits),
        "loads_moved": load_moves_json(suggestion.loads_moved),
        "loads_spread": load_spreads_json(suggestion.loads_spread),
        "anchors_moved": anchor_moves_json(suggestion.anchors_moved),
        "score": _score_json(suggestion),
        "design_file": files.design_file,
        "meshes": list(files.meshes),
        "plots": list(files.plots),
    }


def _friction_lines(change: tuple[float, float] | None) -> list[str]:
    """'changes the friction on the floor: 0.15 -> 0.2' for non-slip pads."""
    if change is None:
        return []
    return [f"changes the friction on the floor: {plain_number(change[0], 6)} -> "
            f"{plain_number(change[1], 6)}"]


def _implausible_lines(suggestion: Suggestion) -> list[str]:
    """Why the shop's score ranks the suggestion after plausible ones
    (``suggest.score``: proportions a maker would not build), one line each."""
    score = suggestion.score
    if score is None:
        return []
    return [f"implausible proportion: {reason}" for reason in score.implausible]


def _score_json(suggestion: Suggestion) -> dict[str, Any] | None:
    """The shop's score it was ranked by (``suggest.score``)."""
    score = suggestion.score
    if score is None:
        return None
    return {"implausible": list(score.implausible), "broken_mirrors": score.broken,
            "cost": score.cost, "planks": score.touched}
