"""Why ``suggest`` found no suggestion (or fewer than asked for), from values: which
violations remain, what the search tried (``tried``), and what each violation would need
(``needs``, hand statics).

``explain`` is fed what the search leaves behind -- the report, the record of what was
tried -- and does no search of its own.  Only when nothing was found does it check the
designs of the discrete candidates that failed once more, to name the violation each one
leaves (the search itself stops at the first failing load case and keeps no report),
and the designs at the best probe of the first line searches that failed, to say what
fails there.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from furncheck.check import check_design
from furncheck.design.model import Design
from furncheck.dofs import Blocked, OutOfReach, parse_dof
from furncheck.edit_check import check_edit
from furncheck.geometry import Geometry
from furncheck.result import DesignReport, Violation
from furncheck.suggest.needs import Need, violation_needs
from furncheck.suggest.tried import FAILED, LineSearch, Trial, Tried

LOOKED_INTO = 6
"""At most this many failed line searches get a verdict (a full check each)."""


@dataclass(frozen=True)
class Explanation:
    """remaining : the violations no suggestion repairs (all of them when none was found,
                  none otherwise: every suggestion makes the design valid)
    needs      : per violated (kind, place), what it would need
    tried      : what the search tried
    """

    remaining: tuple[Violation, ...]
    needs: tuple[Need, ...]
    tried: Tried


def explain(design: Design, geometry: Geometry, report: DesignReport, tried: Tried,
            found: int, editor=None) -> Explanation:
    """The explanation of a search that found ``found`` suggestions for the invalid
    design (its ``report``); with none, each failed discrete candidate's reason names the
    violation it leaves, and with the search's ``editor`` (``edits.Editor``) the first
    LOOKED_INTO failed line searches get a verdict."""
    trials = _distinct(tried.discrete)
    searches = tried.line_searches
    if found == 0:
        trials = tuple(_detailed(trial) for trial in trials)
        if editor is not None:
            failed = [k for k, search in enumerate(searches)
                      if search.interval is None][:LOOKED_INTO]
            searches = tuple(replace(search, verdict=_verdict(editor, search))
                             if k in failed else search for k, search in enumerate(searches))
    return Explanation(report.violations if found == 0 else (),
                       violation_needs(design, geometry, report),
                       replace(tried, discrete=trials, line_searches=searches))


def _verdict(editor, search: LineSearch) -> str:
    """What fails at the search's most telling probe (``LineSearch.looked_at``): why the
    change cannot be made, what it does to the joints and contacts, or the first
    violation of the changed design."""
    step = search.looked_at
    if step is None:
        return ""
    design = editor.design
    dofs = tuple(parse_dof(design, name) for name in search.dofs)
    try:
        edited = editor.moved(dofs, tuple(step * change for change in search.changes))
    except (Blocked, OutOfReach) as why:
        return getattr(why, "reason", str(why)) or "the change cannot be made"
    after = None
    if search.best is None:        # no probe kept the joints: say which change breaks them
        problem, after = check_edit(editor.geometry, edited, design, stand=True)
        if problem is not None or after is None:
            return problem or "it is no design"
    remaining = check_design(edited, after).violations
    if not remaining:
        return "valid there, but not kept (the joints it would keep differ)"
    return _first(remaining, gradual=search.best is not None)


def _first(violations: tuple[Violation, ...], gradual: bool = True) -> str:
    """The first violation in words, '(and n more)'; with ``gradual`` False the first
    that is not a joint's or plank's utilization (what makes a margin -inf: toppling,
    sliding, geometry) when there is one."""
    first = violations[0]
    if not gradual:
        first = next((v for v in violations if v.kind not in _GRADUAL), first)
    case = f" in case '{first.case}'" if first.case is not None else ""
    more = f" (and {len(violations) - 1} more)" if len(violations) > 1 else ""
    return f"{first.kind}: {first.where}{case}: {first.message}{more}"


_GRADUAL = frozenset({"non-durable", "sagging", "overstressed"})
"""Violations measured by a utilization (``edits.utilization_margin``)."""


def _distinct(trials: tuple[Trial, ...]) -> tuple[Trial, ...]:
    """The trials without repeats of the same rule, target, outcome and reason (a rule
    that does not apply says so once)."""
    seen, kept = set(), []
    for trial in trials:
        key = (trial.rule, trial.target, trial.outcome, trial.reason)
        if key not in seen:
            seen.add(key)
            kept.append(trial)
    return tuple(kept)


def _detailed(trial: Trial) -> Trial:
    """A failed trial whose design was checked: its reason names the first violation
    that remains with the added plank (the worst of its kind's utilizations is not
    searched: the first one the report lists)."""
    if trial.outcome != FAILED or trial.candidate is None:
        return trial
    remaining = check_design(trial.candidate).violations
    if not remaining:
        return trial
    place = trial.reason.split(": ", 1)[0]
    return replace(trial, reason=f"{place}: with {trial.plank or 'it'}, {_first(remaining)}")
