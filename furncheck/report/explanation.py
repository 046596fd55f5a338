"""The explanation of ``furncheck suggest`` in words and as JSON: what each violation
would need and what the search tried (``furncheck.suggest.explain``).

    What it would take (hand statics, each violation on its own):
      sliding in case 'shove': the push of 110 N exceeds mu W = 0.5 x 124 N = 62 N; ...
    What was tried:
      continuous changes (paper 6.4): 25 of 32 DOFs free (7 cannot move on their own); ...
      support plank: not applicable: it does not repair sliding
"""

from __future__ import annotations

import math
from typing import Any

from furncheck.plain import distinguishing_digits, plain_list, plain_number
from furncheck.report.common import plural
from furncheck.report.numbers import format_number
from furncheck.suggest.candidates import MAX_STEP
from furncheck.suggest.explain import Explanation
from furncheck.suggest.needs import Need
from furncheck.suggest.tried import FOUND, NOT_APPLICABLE, LineSearch, Trial, Tried
from furncheck.tolerances import GRAVITY

DIGITS = 3
"""Significant digits of the numbers in the sentences (the JSON keeps the report's)."""

SHOWN = 8
"""Line searches and discrete trials listed in the text; the rest are counted."""


def _n(value: float, digits: int = DIGITS) -> str:
    """``digits`` significant digits, whole units at least (1250, not 1.25e+03); more than
    DIGITS (``_digits``: a value told from its limit) as ``plain_number`` writes them,
    where ``format_number`` writes 0 below the report's 6 decimals (a metre design's
    small sag)."""
    whole = len(str(int(abs(round(value)))))
    if digits > DIGITS:
        return plain_number(value, max(digits, whole))
    return format_number(value, max(digits, whole))


def _digits(value: float, limit: float) -> int:
    """Significant digits with which ``_n`` shows a value and the limit it is compared
    with differently (``plain.distinguishing_digits``): 1.208 against 1.205, not 1.21
    against 1.21."""
    whole = len(str(int(abs(round(max(abs(value), abs(limit)))))))
    return distinguishing_digits(value, limit, max(DIGITS, whole))


# -- what it would take ------------------------------------------------------------------
def need_text(need: Need, units: str) -> str:
    """One sentence: the violation, its numbers, and what would hold it."""
    head = f"{need.kind} {need.where}"
    if need.case is not None:
        head += f" in case '{need.case}'" + \
            (f" (the worst of {len(need.cases)})" if len(need.cases) > 1 else "")
    if not need.values:
        return f"{head}: no hand estimate ({need.why})"
    return f"{head}: {_SENTENCES[need.kind](need.values, units)}"


def _sliding(v: dict, units: str) -> str:
    if v["friction"] <= 0.0:        # no weight holds a push without friction
        on = _resting(v) if "part" in v else ""
        return (f"{on}the push of {_n(v['push'])} N meets no friction (mu = 0): no weight "
                f"holds it; friction mu >= {_n(v['friction_needed'])} would (or no push)")
    digits = _digits(v["push"], v["holds"])
    push, holds = _n(v["push"], digits), _n(v["holds"], digits)
    if "part" in v:                 # a loose part on its rests, the floor holding
        more = f"{_n(v['extra_mass'])} kg more weight on {v['part']}, or " \
            if "extra_mass" in v else ""
        return (f"{_resting(v)}the push of {push} N along its "
                f"rests exceeds mu N = {_n(v['friction'])} x {_n(v['weight'])} N = {holds} N "
                f"(N: what presses it onto them); {more}friction mu >= "
                f"{_n(v['friction_needed'])}, or fixing it to them, would hold it (or a push "
                f"of at most {holds} N)")
    return (f"the push of {push} N exceeds mu W = {_n(v['friction'])} x "
            f"{_n(v['weight'])} N = {holds} N; {_n(v['extra_mass'])} kg more weight "
            f"on it, or friction mu >= {_n(v['friction_needed'])}, would hold it (or a push "
            f"of at most {holds} N)")


def _lift_off(v: dict, units: str) -> str:
    if "part" in v:
        return _lift_off_part(v, units)
    x, y = v["point"]
    text = (f"the resultant of its weight and loads, {_n(v['weight'])} N, meets the floor at "
            f"({_n(x)}, {_n(y)}) {units}, {_n(v['outside'])} {units} outside the support "
            f"beyond {v['edge_plank']}; a base reaching {_n(v['wider'])} {units} further "
            f"that way (a foot or outrigger, or the supports set wider) would hold it")
    if "ballast_arm" in v:
        text += (f", or {_n(v['ballast'])} kg of ballast over {v['ballast_plank']} "
                 f"({_n(v['ballast_arm'])} {units} inside the tipping edge: W d / a = "
                 f"{_n(v['weight'])} N x {_n(v['outside'])} {units} / "
                 f"{_n(v['ballast_arm'])} {units} = {_n(v['ballast'] * GRAVITY)} N)")
    elif "ballast" in v:
        text += (f", or {_n(v['ballast'])} kg of ballast over {v['ballast_plank']} "
                 f"({_n(v['ballast'] * GRAVITY)} N: the resultant passes a corner of the "
                 "support, so both edges beside it must hold)")
    if "push_max" in v:
        text += (f", or a horizontal push or pull of at most {_n(v['push_max'])} N (now "
                 f"{_n(v['push'])} N)")
    if "also" in v:             # a loose part that still tips once the whole is held
        text += f"; and {_lift_off_part(v['also'], units)}"
    return text


def _resting(v: dict) -> str:
    """'top resting on end_l and end_r: ', the loose part a need is of (``needs``)."""
    return f"{v['part']} resting on {plain_list(v['on'].split(','))}: "


def _lift_off_part(v: dict, units: str) -> str:
    """A loose part that tips off its rests, or that its loads lift (``needs.
    _lift_off_part``)."""
    if "lifted" in v:
        return (f"{_resting(v)}its loads lift it off its rests "
                f"with {_n(v['lifted'])} N; fixing it down (nails or screws taking at least "
                f"that pull) would hold it")
    point = ", ".join(_n(c) for c in v["point"])
    text = (f"{_resting(v)}its weight and loads press it onto its "
            f"rests with {_n(v['weight'])} N along a line that meets their plane at "
            f"({point}) {units}, {_n(v['outside'])} {units} outside them beyond "
            f"{v['edge_plank']}; fixing it down (nails or screws taking at least "
            f"{_n(v['hold'])} N of pull at its rests on {v['hold_plank']}")
    if "hold_arm" in v:
        text += (f": W d / a = {_n(v['weight'])} N x {_n(v['outside'])} {units} / "
                 f"{_n(v['hold_arm'])} {units}")
    text += ")"
    if "ballast" in v:
        text += f", or {_n(v['ballast'])} kg of ballast on it over {v['hold_plank']},"
    return text + " would hold it"


def _non_durable(v: dict, units: str) -> str:
    if "rating_needed" in v:
        return (f"the anchor holds {_n(v['force'])} N against its {_n(v['capacity'])} N; "
                f"an anchor rated for at least {_n(v['rating_needed'])} N would hold it")
    pulls = v["pull"] / v["pull_capacity"] >= v["shear"] / v["shear_capacity"]
    force, capacity = ("pull", "pull_capacity") if pulls else ("shear", "shear_capacity")
    digits = _digits(v[force], v[capacity])
    ratio = _n(v["ratio"], _digits(v["ratio"], 1.0))
    text = (f"{force} {_n(v[force], digits)} N per nail against {_n(v[capacity], digits)} N "
            f"(x {ratio}); the force per nail goes with 1 / n for the same joint "
            f"forces, so {v['nails_needed']} nails instead of {v['nails']} would hold it")
    if "length_needed" in v:
        text += (f": a joint {_n(v['length_needed'])} {units} long at {_n(v['spacing'])} "
                 f"{units} spacing (now {_n(v['length'])} {units})")
    if "room" in v:             # its planks have no room for that along its line
        text += (f", more than the {_n(v['room'])} {units} that {v['room_plank']} gives "
                 f"along the joint: a {v['room_grow']} {v['room_plank']}, or a brace that "
                 f"takes the load off the joint")
    return text


def _bent(v: dict, units: str) -> str:
    t = "t" if v["dimension"] == "thickness" else "w"
    grown = _digits(v["size"], v["size_needed"])
    size, needed = f"{_n(v['size'], grown)} {units}", f"{_n(v['size_needed'], grown)} {units}"
    word = "thick" if v["dimension"] == "thickness" else "deep (on edge)"
    ratio = _n(v["ratio"], _digits(v["ratio"], 1.0))
    if "sag" in v:
        crept = v["sag"] * (1 + v["creep"])
        digits = _digits(crept, v["sag_allowed"])
        bends = f"bows {_n(crept, digits)} {units} sideways" if v.get("sideways") else \
            f"sags {_n(crept, digits)} {units}"
        now = f"{bends} with creep " \
              f"({_n(v['sag'], digits)} {units} x {_n(1 + v['creep'])}) against " \
              f"{_n(v['sag_allowed'], digits)} {units} allowed"
        law = f"sag goes with 1 / {t}^3 for the same load (I = b {t}^3 / 12)"
        formula = f"{size} x ({ratio})^(1/3)"
    else:
        digits = _digits(v["stress"], v["strength"])
        now = f"bending stress {_n(v['stress'], digits)} N/mm^2 against " \
              f"{_n(v['strength'], digits)} N/mm^2"
        law = f"stress goes with 1 / {t}^2 for the same load (S = b {t}^2 / 6)"
        formula = f"{size} x ({ratio})^(1/2)"
    if "sag" in v:
        return (f"{now}; {law}, so at least {t} = {formula} = {needed} {word} is needed (a "
                f"lower bound: its own weight grows with {t}, and nailed ends hold a stiffer "
                f"plank less firmly)")
    return (f"{now}; {law}, so about {t} = {formula} = {needed} {word} would hold it (its "
            f"own weight, which grows with {t}, not counted)")


def _geometric(kind: str):
    def sentence(v: dict, units: str) -> str:
        if "bearing" in v:
            digits = _digits(v["bearing"], v["bearing_needed"])
            return (f"the end bears on {_n(v['bearing'], digits)} {units} of its "
                    f"{_n(v['thickness'])} {units} thickness, where nails need "
                    f"{_n(v['bearing_needed'], digits)} {units}: the face plank reaching "
                    f"{_n(v['change_min'])} to {_n(v['change_max'])} {units} further over it "
                    f"(or the planks moved that much together) would join them")
        if "through" in v and v["copy"]:
            return (f"{v['second']} is {v['first']} drawn a second time, in the same place: "
                    f"removing {v['second']} (its loads, joints and fixings then "
                    f"{v['first']}'s) leaves the one board")
        if "through" in v:
            low, high = _n(v["change_min"]), _n(v["change_max"])
            return (f"drawn {_n(v['through'])} {units} through each other: moving one "
                    f"{low} to {high} {units} out of the other (the way they overlap "
                    f"least) would leave them touching, not joined")
        if v.get("carried"):
            return f"{_n(v['distance'])} {units} above the floor, it hangs on joints it " \
                   "misses: closing those carries it, nothing to lower"
        low, high = _n(v['change_min']), _n(v['change_max'])
        span = f"{low} to {high} {units}" if low != high else f"{_n(v['distance'])} {units}"
        tolerance = f"to within the {_n(v['tolerance'])} {units} tolerance"
        if kind == "disconnected" and v.get("overlap"):
            return f"the end cuts {_n(v['distance'])} {units} into the face; drawing it " \
                   f"back by {span} ({tolerance}) would join them"
        if kind == "disconnected":
            return f"the end is {_n(v['distance'])} {units} from the face; closing it by " \
                   f"{span} ({tolerance}) would join them"
        if kind == "penetration" and "wall" in v:
            return f"{_n(v['distance'])} {units} behind wall {v['wall']}; moving it out or " \
                   f"shortening it by {span} ({tolerance}) would bring it to the wall"
        if kind == "penetration":
            return f"{_n(v['distance'])} {units} into the floor; raising or shortening it by " \
                   f"{span} ({tolerance}) would stand it on the floor"
        return f"{_n(v['distance'])} {units} above the floor; lowering it by {span} " \
               f"({tolerance}) would stand it on the floor"
    return sentence


_SENTENCES = {
    "sliding": _sliding, "lift-off": _lift_off, "non-durable": _non_durable,
    "sagging": _bent, "overstressed": _bent, "disconnected": _geometric("disconnected"),
    "penetration": _geometric("penetration"), "floating": _geometric("floating"),
}


# -- what was tried ----------------------------------------------------------------------
def tried_lines(tried: Tried, found: int) -> list[str]:
    """The search in a few lines: the continuous search, its line searches and the
    discrete rules' trials -- each of them (the first SHOWN) when nothing was found, else
    counted."""
    lines = [_continuous(tried)]
    detailed = found == 0
    searches = tried.line_searches
    if searches:
        succeeded = sum(1 for s in searches if s.interval is not None)
        limit = " (the limit)" if len(searches) >= tried.search_limit else ""
        count = f"{len(searches)} line search{'es' if len(searches) != 1 else ''}"
        if tried.culled_searched:       # ContinuousSearch.directions' fallback
            count += (f" ({tried.culled_searched} of them "
                      f"{'a single change' if tried.culled_searched == 1 else 'single changes'}"
                      " culled as breaking another check first: none was kept)")
        lines.append(f"{count}{limit} with the full checks, "
                     f"{succeeded} with a valid interval"
                     + (f", {tried.dropped} of them dropped (the design file at its middle "
                        f"was not valid)" if tried.dropped else "")
                     + (f"; {tried.unsearched} more directions not searched "
                        f"({'enough found' if found >= tried.wanted else 'the limit'})"
                        if tried.unsearched else "") + (":" if detailed else ""))
        if detailed:
            lines.extend("  " + _line_search(s) for s in searches[:SHOWN])
            if len(searches) > SHOWN:
                lines.append(f"  and {len(searches) - SHOWN} more")
    trials = tried.discrete
    if not detailed:
        return lines + _rules(trials)
    lines.extend(_trial(t) for t in trials[:SHOWN])
    if len(trials) > SHOWN:
        rest = trials[SHOWN:]
        rules = sum(t.outcome == NOT_APPLICABLE for t in rest)
        parts = ([f"{plural(len(rest) - rules, 'candidate')} tried"] if rules < len(rest)
                 else []) + ([f"{rules} where a rule did not apply"] if rules else [])
        lines.append(f"and {plural(len(rest), 'more trial')}: {', '.join(parts)}")
    return lines


def _rules(trials: tuple[Trial, ...]) -> list[str]:
    """One line per discrete rule: why it does not apply, or how many of its candidates
    were tried and found."""
    rules: dict[str, list[Trial]] = {}
    for trial in trials:
        rules.setdefault(trial.rule, []).append(trial)
    lines = []
    for rule, tried in rules.items():
        built = [t for t in tried if t.outcome != NOT_APPLICABLE]
        if not built:
            lines.append(f"{rule}: not applicable: {tried[0].reason}")
            continue
        found = sum(1 for t in built if t.outcome == FOUND)
        lines.append(f"{rule}: {plural(len(built), 'candidate')} tried, {found} found")
    return lines


def _continuous(tried: Tried) -> str:
    blocked = f"{len(tried.blocked)} cannot move on their own" if tried.blocked else ""
    locked = f"{tried.locked} locked" if tried.locked else ""
    far = f"{tried.far} far from the violations, left out" if tried.far else ""
    aside = ", ".join(part for part in (blocked, locked, far) if part)
    head = (f"continuous changes (paper 6.4{', geometric repairs only' if tried.geometric else ''}"
            f"): {tried.free} of {tried.dofs} DOFs free" + (f" ({aside})" if aside else ""))
    if not tried.directions:
        return head + "; no check to restore has a rate along them"
    relevant = tried.directions[0].relevant
    formed = sum(d.evaluated for d in tried.directions)
    kept = sum(d.kept for d in tried.directions)
    culls = [(sum(d.facing_away for d in tried.directions), "face away from the valid region"),
             (sum(d.breaks_other for d in tried.directions), "break another check first"),
             (sum(d.too_far for d in tried.directions),
              f"reach it only beyond {_n(MAX_STEP)} x the design's size "
              f"({_n(math.degrees(MAX_STEP))} degrees for a turn)")]
    culled = ", ".join(f"{count} {why}" for count, why in culls if count)
    skipped = sum(d.possible - d.evaluated for d in tried.directions)
    return (f"{head}; the {relevant} that move the violated checks, combined 1 to "
            f"{tried.max_dofs} at a time: {plural(formed, 'direction')} formed"
            + (f" ({skipped} more contain a smaller one that works)" if skipped else "")
            + f", {kept if kept else 'none'} kept" + (f" (culled: {culled})" if culled else ""))


def _line_search(search: LineSearch) -> str:
    names = " + ".join(search.dofs)
    lead = search.changes[0] if search.changes else 0.0
    unit = _unit(search.units[0]) if search.units else ""

    def at(step: float) -> str:
        """The first DOF's change at ``step``, signed, in its unit."""
        return f"{_n(step * lead)} {unit}"

    first = f" of {search.dofs[0]}" if len(search.dofs) > 1 else ""
    if search.interval is not None:
        low, high = search.interval
        dropped = f" (not offered: {' + '.join(search.contains)}, valid too, changes less)" \
            if search.contains else ""
        return f"{names}: valid for {at(low)} to {at(high)}{first}{dropped}"
    if not search.probes:
        return f"{names}: not probed"
    reach = f"probed {plural(len(search.probes), 'step')} as far as {at(search.furthest)}" \
        f"{first}" + \
        (" (the furthest searched)" if search.furthest >= MAX_STEP * (1 - 1e-9) else "")
    best = search.best
    if best is None:
        what = "every step probed breaks a joint, cuts into a plank, or topples or slides"
    else:
        what = f"at best a joint or plank at {_n(100 * (1 - best[1]))} % of its limit " \
               f"(at {at(best[0])})"
    verdict = f"; at {at(search.looked_at)}: {search.verdict}" if search.verdict else ""
    return f"{names}: no valid step, {reach}: {what}{verdict}"


def _trial(trial: Trial) -> str:
    target = f" for {trial.target}" if trial.target else ""
    if trial.outcome == FOUND:
        return f"{trial.rule}{target}: found {trial.plank}".rstrip()
    return f"{trial.rule}{target}: {trial.outcome}: {trial.reason}"


def _unit(unit: str) -> str:
    return "degrees" if unit == "deg" else unit


# -- text and JSON -----------------------------------------------------------------------
def explanation_lines(explanation: Explanation, units: str, found: int,
                      indent: str) -> list[str]:
    """The explanation's text lines, after the suggestions (none found: every violation
    remains)."""
    lines = []
    if explanation.remaining:
        count = len(explanation.remaining)
        remain = "The violation remains" if count == 1 else f"All {count} violations remain"
        lines.append(f"{indent}{remain}.")
    lines.append(f"{indent}What it would take (hand statics, each violation on its own):")
    lines.extend(f"{indent}  {need_text(need, units)}" for need in explanation.needs)
    lines.append(f"{indent}What was tried:")
    lines.extend(f"{indent}  {line}" for line in tried_lines(explanation.tried, found))
    return lines


def explanation_dict(explanation: Explanation, units: str) -> dict[str, Any]:
    """The ``explanation`` object of ``suggest --format json``."""
    tried = explanation.tried
    return {
        "remaining": [{"kind": v.kind, "where": v.where, "case": v.case}
                      for v in explanation.remaining],
        "needs": [{"kind": need.kind, "where": need.where, "case": need.case,
                   "cases": list(need.cases), "text": need_text(need, units),
                   "values": dict(need.values)} for need in explanation.needs],
        "tried": {
            "dofs": tried.dofs, "free": tried.free, "locked": tried.locked,
            "blocked": len(tried.blocked), "max_dofs": tried.max_dofs,
            "max_suggestions": tried.wanted,
            "geometric": tried.geometric,
            "directions": [{"dofs": d.size, "relevant": d.relevant, "possible": d.possible,
                            "evaluated": d.evaluated, "kept": d.kept,
                            "facing_away": d.facing_away, "breaks_other": d.breaks_other,
                            "too_far": d.too_far} for d in tried.directions],
            "line_searches": [_search_dict(s) for s in tried.line_searches],
            "search_limit": tried.search_limit, "unsearched": tried.unsearched,
            "dropped": tried.dropped,
            "discrete": [{"rule": t.rule, "for": t.target, "outcome": t.outcome,
                          "reason": t.reason, "plank": t.plank} for t in tried.discrete],
        },
    }


def _search_dict(search: LineSearch) -> dict[str, Any]:
    best = search.best
    return {"dofs": list(search.dofs), "outcome": search.outcome,
            "range": list(search.interval) if search.interval is not None else None,
            "predicted": search.predicted, "probes": len(search.probes),
            "furthest": search.furthest,
            "best_margin": best[1] if best is not None else -math.inf,
            "verdict": search.verdict, "text": _line_search(search)}
