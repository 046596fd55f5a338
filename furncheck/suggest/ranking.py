"""``suggest_design``: continuous and discrete suggestions, each written as a design file
and validated from that very text (contract section 4: every listed suggestion's file is
valid; one that is not is dropped, never listed), with its cut list (``cutlist``), ranked
by the shop's score (``score``).

Order: by ``ShopScore.key`` (plausible proportions, then the design's symmetry kept, then
the smallest relative change of the fewest planks), ties by the smaller step and the
order found (continuous before discrete); when both kinds are found and there are more
than K, at least DISCRETE_KEPT discrete suggestions are kept.
"""

from __future__ import annotations

import time
from dataclasses import replace

from furncheck.check import check_design
from furncheck.design.load import parse_design
from furncheck.design.model import Design
from furncheck.design.write import design_text
from furncheck.dofs import Dof, all_dofs
from furncheck.geometry import analyze
from furncheck.statics import build_model
from furncheck.statics.elastic import beam_layout
from furncheck.suggest.closures import finished_closures
from furncheck.suggest.continuous import LINE_SEARCHES_PER_SUGGESTION, ContinuousSearch
from furncheck.suggest.cutlist import anchor_moves, load_moves, load_spreads, plank_edits
from furncheck.suggest.discrete import Search, discrete_fixes
from furncheck.suggest.explain import explain
from furncheck.suggest.score import shop_score
from furncheck.suggest.suggestion import Suggestion, SuggestionReport
from furncheck.suggest.tried import Trial, Tried

DISCRETE_KEPT = 2
"""When there are more than K suggestions, at least this many discrete fixes (as many as
were found, up to K) are kept: a different kind of fix than the continuous ones."""


def suggest_design(design: Design, max_dofs: int = 3, max_suggestions: int = 8,
                   locked: tuple[Dof, ...] = ()) -> SuggestionReport:
    """Ranked suggestions for ``design`` (none when it is valid already)."""
    geometry = analyze(design)
    model = build_model(design, geometry) if geometry.stands else None
    solved: dict = {}       # the cases' statics, which the candidates linearize
    report = check_design(design, geometry, model, solved)
    if report.valid or max_suggestions <= 0:
        return SuggestionReport(design.source, design.name, report, ())
    start = time.perf_counter()
    search = ContinuousSearch(design, geometry, report, locked, model, solved)
    directions = search.directions(max_dofs)
    searching = time.perf_counter()
    continuous = search.run(directions, max_suggestions)
    discrete_start = time.perf_counter()
    trials: list[Trial] = []
    fixes = discrete_fixes(design, geometry, report, bool(continuous), locked, trials)
    closing = Search(design, geometry, report, locked, trials)
    closures = [] if continuous or not geometry.violations else finished_closures(
        search, directions, closing,
        {plank for fix in fixes if fix.rule == "reconnect" for plank in fix.between})
    end = time.perf_counter()
    suggestions: list[Suggestion] = []
    dropped = len(continuous) + len(fixes) + len(closures)
    for found in continuous:
        first = _first_written(search, found, len(suggestions) + 1)
        if first is None:
            continue
        written, step, changes = first
        suggestions.append(Suggestion(
            len(suggestions) + 1, "continuous", search.restores, *written,
            dofs=tuple(d.name for d in found.dofs),
            direction=tuple(float(v) for v in found.direction),
            range=(found.low, found.high), step=step, changes=changes,
            units=tuple(d.unit(design) for d in found.dofs), limited=found.limited))
    for fix in fixes:
        written = _written(fix.design, len(suggestions) + 1)
        if written is not None:
            suggestions.append(Suggestion(len(suggestions) + 1, "discrete", fix.restores,
                                          *written, adds=fix.adds, between=fix.between,
                                          rule=fix.rule, advice=fix.advice))
    for closure in closures:
        written = _written(closure.design, len(suggestions) + 1, search.editor.keeps)
        if written is not None:
            suggestions.append(Suggestion(
                len(suggestions) + 1, "discrete", closing.restores, *written,
                dofs=tuple(d.name for d in closure.dofs), changes=closure.changes,
                units=tuple(d.unit(design) for d in closure.dofs),
                between=tuple(dict.fromkeys(d.plank for d in closure.dofs)),
                rule="reconnect", advice=closure.advice))
    tried = Tried(len(all_dofs(design)), len(search.margins.dofs), len(locked),
                  dict(search.margins.blocked), max_dofs, max_suggestions,
                  bool(geometry.violations),
                  tuple(search.tally), tuple(search.line_searches),
                  LINE_SEARCHES_PER_SUGGESTION * max_suggestions, search.unsearched,
                  dropped - len(suggestions), tuple(trials), far=search.far,
                  culled_searched=search.culled_searched)
    ranked = _ranked(design, geometry, search.planes, suggestions, max_suggestions)
    return SuggestionReport(design.source, design.name, report, ranked,
                            search.searched, search.editor.checks,
                            {"candidates": searching - start,
                             "line search": discrete_start - searching,
                             "discrete": end - discrete_start},
                            explain(design, geometry, report, tried, len(ranked),
                                    search.editor))


def _ranked(design: Design, geometry, planes, suggestions: list[Suggestion],
            limit: int) -> tuple[Suggestion, ...]:
    """The suggestions with their cut lists and scores, best first (module docstring),
    at most ``limit``, renumbered (their files' names follow their new ranks)."""
    scored = []
    layout = beam_layout(design, geometry) if design.elastic and suggestions else None
    for suggestion in suggestions:
        edits = plank_edits(design, suggestion.design)
        score = shop_score(design, geometry, planes, suggestion.design, edits, layout)
        scored.append(replace(suggestion, edits=edits, score=score,
                              loads_moved=load_moves(design, suggestion.design),
                              loads_spread=load_spreads(design, suggestion.design),
                              anchors_moved=anchor_moves(design, suggestion.design)))
    scored.sort(key=lambda s: (s.score.key(), s.step if s.step is not None else 0.0,
                               s.rank))
    scored = _distinct_builds(scored)
    kept = scored[:limit]
    discrete = [s for s in scored if s.kind == "discrete"]
    wanted = min(DISCRETE_KEPT, len(discrete), limit)
    short = max(0, wanted - sum(s.kind == "discrete" for s in kept))   # never a negative slice
    missing = [s for s in discrete if all(s is not k for k in kept)][:short]
    for extra in missing:               # in place of the lowest-ranked continuous ones
        last = max(k for k, s in enumerate(kept) if s.kind != "discrete")
        kept[last] = extra
    kept.sort(key=lambda s: (s.score.key(), s.step if s.step is not None else 0.0, s.rank))
    return tuple(_renamed(suggestion, rank) for rank, suggestion in enumerate(kept, start=1))


def _distinct_builds(suggestions: list[Suggestion]) -> list[Suggestion]:
    """The suggestions without those that build what a better-ranked one builds: the
    same planks (sizes, places, turns and materials to the micrometre and the
    thousandth of a degree), listed joints, anchors and loads, whatever the added planks
    are called (two rules can reach one fix: a rail under the top between two legs is
    the apron there)."""
    seen, kept = set(), []
    for suggestion in suggestions:
        build = _build(suggestion.design)
        if build not in seen:
            seen.add(build)
            kept.append(suggestion)
    return kept


def _build(design: Design) -> tuple:
    """What a design builds, named by nothing: its planks' shapes, the listed joints
    between them, its anchors and its loads, each by the shape of its plank
    (``_distinct_builds``)."""
    def shape(plank) -> tuple:
        return (round(plank.length, 6), round(plank.width, 6), round(plank.thickness, 6),
                tuple(round(v, 6) for v in plank.center),
                tuple(round(v, 3) for v in plank.rotation), plank.material)

    def place(point) -> tuple | None:
        return None if point is None else tuple(round(v, 6) for v in point)

    shapes = {plank.id: shape(plank) for plank in design.planks}
    joints = None if design.joints is None else tuple(sorted(
        (tuple(sorted((shapes[a], shapes[b]))), joint.nails, joint.rests)
        for joint in design.joints for a, b in [joint.planks]))
    anchors = tuple(sorted((shapes[a.plank], place(a.point), a.wall, a.capacity, a.gap)
                           for a in design.anchors))
    loads = tuple((case.name, tuple((shapes[load.plank], place(load.force),
                                     place(load.point), load.spread)
                                    for load in case.loads))
                  for case in design.load_cases)
    return tuple(sorted(shapes.values())), joints, anchors, loads


def _renamed(suggestion: Suggestion, rank: int) -> Suggestion:
    """The suggestion as rank ``rank``: its design named ``<name>-suggestion-NN`` after it
    (the file's text written again with that name; nothing else in it changes)."""
    if suggestion.rank == rank:
        return suggestion
    base = suggestion.design.name.rsplit("-suggestion-", 1)[0]
    design = replace(suggestion.design, name=f"{base}-suggestion-{rank:02d}",
                     source=f"suggestion-{rank:02d}.yaml")
    return replace(suggestion, rank=rank, design=design, text=design_text(design, "yaml"),
                   report=replace(suggestion.report, design=design.source, name=design.name))


def _first_written(search: ContinuousSearch, found, rank: int):
    """(``_written``, step, changes) of the first of the found direction's designs
    (``ContinuousSearch.representatives``: shop-rounded changes first) that is valid from
    its text; None if none is."""
    for edited, step, changes in search.representatives(found):
        written = _written(edited, rank, search.editor.keeps)
        if written is not None:
            return written, step, changes
    return None


def _written(design: Design, rank: int, keeps=analyze):
    """(design, text, report) of the suggestion's design file, parsed back from its text
    and validated; None if it is not valid.  ``keeps``: the parsed design's geometry, or
    None when it must be refused (a continuous suggestion must keep the joints)."""
    text = design_text(replace(design, name=f"{design.name}-suggestion-{rank:02d}"), "yaml")
    written = parse_design(text, f"suggestion-{rank:02d}.yaml", "yaml")
    geometry = keeps(written)
    report = None if geometry is None else check_design(written, geometry)
    return (written, text, report) if report is not None and report.valid else None
