"""The pipeline: design file -> geometry -> statics -> verdicts -> DesignReport."""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np

from furncheck import tolerances as tol
from furncheck.design import Design
from furncheck.design.model import with_model
from furncheck.errors import DesignError, DesignTooBig
from furncheck.geometry import Geometry, analyze, drawn_through
from furncheck.nail_groups import joint_utilization, nail_rows
from furncheck.result import NOT_SOLVED, CaseResult, DesignReport
from furncheck.statics import (
    CaseStatics,
    StaticsModel,
    build_model,
    solve_load_case,
    solve_load_cases,
)
from furncheck.validity import (
    anchor_utilization,
    case_holds,
    case_loads,
    evaluate_case,
    worst_plank_utilization,
)


def check_design(design: Design, geometry: Geometry | None = None,
                 model: StaticsModel | None = None,
                 solved: dict[str, CaseStatics] | None = None) -> DesignReport:
    """Validate a loaded design in every load case (``geometry``, ``model``: its analysis
    and statics model, if the caller already has them; ``solved``: a dict that gets each
    case's ``CaseStatics`` by case name, for a caller that goes on with them).

    A design that does not stand as drawn (a group of planks reaching the ground nowhere,
    or a joint or ground contact missed narrowly: ``Geometry.stands``) gets its geometric
    violations only: its statics are not solved, and each case lists its loads but no
    joints, contacts or planks (an empty ``planks`` in the elastic model, whose cases
    have the key), and reads neither durable nor stable (nothing was shown to
    hold; no toppling of a stool whose leg is 4 mm short either)."""
    geometry = geometry or analyze(design)
    violations = list(geometry.violations) + drawn_through(design, geometry)
    if not geometry.stands:
        planks = () if design.elastic else None     # the key, empty
        cases = tuple(CaseResult(case.name, durable=False, stable=False, joints=(), contacts=(),
                                 stability=NOT_SOLVED, planks=planks,
                                 loads=case_loads(design, case))
                      for case in design.load_cases)
        return DesignReport(design=design.source, name=design.name, valid=False,
                            violations=tuple(violations), cases=cases, units=design.units)
    model = model or build_model(design, geometry)
    cases = []
    for case, statics in zip(design.load_cases, solve_load_cases(model, design.load_cases)):
        if solved is not None:
            solved[case.name] = statics
        result, case_violations = evaluate_case(design, geometry, model, case, statics)
        cases.append(result)
        violations.extend(case_violations)
    return DesignReport(design=design.source, name=design.name, valid=not violations,
                        violations=tuple(violations), cases=tuple(cases), units=design.units)


def refuse_too_big(design: Design, model: StaticsModel | None = None,
                   geometry: Geometry | None = None) -> None:
    """Raise DesignTooBig when the design's dense contact system would have more than
    MAX_GROUND_UNKNOWNS unknowns (``condense.ground_unknowns``; ``model``, ``geometry``:
    the design's, built here when not given), before anything is solved.  The commands
    ask it of the design they are given (``check_file``, ``range``, ``suggest``), not of
    the edits they check on the way."""
    from furncheck.statics.condense import ground_unknowns

    if model is None:
        geometry = geometry or analyze(design)
        if not geometry.stands:         # its statics are not solved
            return
        model = build_model(design, geometry)
    unknowns = ground_unknowns(model)
    if unknowns > tol.MAX_GROUND_UNKNOWNS:
        raise DesignTooBig.of_unknowns(design.source, unknowns, tol.MAX_GROUND_UNKNOWNS)


def is_valid(design: Design, geometry: Geometry | None = None,
             starts: tuple[CaseStatics | None, ...] | None = None,
             solved: dict[int, CaseStatics] | None = None) -> bool:
    """Whether the design is valid: ``check_design(...).valid``, stopping at the first
    load case with a violation (for searches that only need the verdict).  ``starts``:
    per load case, the case solved on a design this one is a small edit of
    (``case_statics``), where its contact iterations start (``solve_case``'s ``near``);
    ``solved``: a dict that gets each case solved by its index."""
    geometry = geometry or analyze(design)
    if geometry.violations or drawn_through(design, geometry):
        return False
    model = build_model(design, geometry)
    if plates_fail(design, model):
        return False
    for k, case in enumerate(design.load_cases):
        statics = solve_load_case(model, case, None if starts is None else starts[k])
        if solved is not None:
            solved[k] = statics
        if not case_holds(design, geometry, model, statics):
            return False
    return True


def plates_fail(design: Design, model: StaticsModel) -> bool:
    """Whether a plank checked as a plate (elastic model, ``statics.plates``) fails by its
    plate alone in some load case: its plate's sag over its span, or its stress, over
    the limit.  A plank's reading is its plate's where that is the larger
    (``plates._merged``), so the design is then invalid whatever its statics say, and a
    search that needs only the verdict (``is_valid``: a range's probes of a design whose
    shelves sag as plates) need not solve them.  The plates are found, factored and
    solved one at a time (``plates.each_plate``, ``plates.plate_cases``), up to the
    first that fails: a probe of a design whose bottom sags factors no more."""
    from furncheck.statics.plates import each_plate, plate_cases
    from furncheck.validity import bending_use, plank_limits

    if model.beams is None:
        return False
    cases = list(design.load_cases)
    sag_limit, creep, strength = plank_limits(design, model)
    for plate in each_plate(model):
        k = plate.local
        for sag, span, stress in plate_cases(design, plate, cases):
            used = bending_use(sag, span, stress, sag_limit[k], creep[k], strength[k])
            if max(float(used[0]), float(used[1])) > 1.0 + tol.CAPACITY_REL_TOL:
                return True
    return False


class Margin(NamedTuple):
    """What ``margin_of`` finds of a design: whether it is valid, its durability margin,
    each joint's utilization, and the load case (its index in ``design.load_cases``)
    that failed (an invalid design: the first that did) or has the smallest margin."""

    valid: bool
    margin: float
    utilization: np.ndarray
    case: int


def margin_of(design: Design, geometry: Geometry,
              starts: tuple[CaseStatics | None, ...] | None = None,
              model: StaticsModel | None = None, first: int | None = None,
              solved: dict[int, CaseStatics] | None = None) -> Margin:
    """The design's ``Margin``: the margin is the smallest 1 - utilization of any joint,
    anchor (and, elastic model, any plank's sag or stress) in any load case, -inf if a
    case is not stable; the utilization (``nail_groups.joint_utilization``) is per joint of
    ``geometry.joints``, the largest of the load cases (0 for a joint outside the
    statics).  Every case is solved, except that an unstable one ends the search.  The
    geometry must have no violations, and the design no planks drawn through each other
    (``drawn_through``: its callers refuse edits that cut into a plank).  ``model``: its
    statics model, if the caller already has it.

    With ``first`` (a case's index), for a search that needs of an invalid design only
    its verdict and a margin to interpolate: that case is solved first and the cases stop
    at the first that fails (a failing case cannot be made good by another), the margin
    and utilization then being those of the cases solved (at least the design's).  A
    valid design's cases are all solved, its ``Margin`` the same as without ``first``.
    ``starts`` and ``solved`` as for ``is_valid``."""
    model = model or build_model(design, geometry)
    order = list(range(len(design.load_cases)))
    if first is not None:
        order.insert(0, order.pop(first))
    rows = nail_rows([geometry.joints[j] for j in model.joints]) if model.joints else None
    wrenches: dict[int, np.ndarray] = {}
    parts: dict[int, np.ndarray] = {}       # the springs' wrenches of joints cut into parts
    plank_used = 0.0
    stable, stopped = True, False
    limiting, worst_used = order[0], -np.inf
    for k in order:
        statics = solve_load_case(model, design.load_cases[k],
                                  None if starts is None else starts[k])
        if solved is not None:
            solved[k] = statics
        if statics.stability != "stable":
            stable, limiting = False, k
            break
        used = max(worst_plank_utilization(design, model, statics),
                   anchor_utilization(design, geometry, model, statics))
        plank_used = max(plank_used, used)
        holds = used <= 1.0 + tol.CAPACITY_REL_TOL
        if statics.joint_wrenches is not None and model.joints:
            wrenches[k] = statics.joint_wrenches
            if statics.part_wrenches is not None:
                parts[k] = statics.part_wrenches
            joint_used, joint_holds = joint_utilization(design, geometry, model,
                                                        statics.joint_wrenches, rows,
                                                        statics.part_wrenches)
            used = max(used, float(joint_used.max()))
            holds = holds and bool(np.all(joint_holds))
        if used > worst_used:
            limiting, worst_used = k, used
        if first is not None and not holds:
            limiting, stopped = k, True
            break
    utilization = np.zeros(len(geometry.joints))
    valid = stable and not stopped
    if wrenches:        # the joints' utilization in all those cases at once
        used, holds = joint_utilization(
            design, geometry, model, np.stack([wrenches[k] for k in sorted(wrenches)]), rows,
            np.stack([parts[k] for k in sorted(wrenches)]) if len(parts) == len(wrenches)
            else None)
        utilization[np.asarray(model.joints, dtype=int)] = used.max(axis=0)
        valid = valid and bool(np.all(holds))
    if not stable:
        return Margin(False, -np.inf, utilization, limiting)
    valid = valid and plank_used <= 1.0 + tol.CAPACITY_REL_TOL
    worst = max(float(utilization.max(initial=0.0)), plank_used)
    return Margin(valid, 1.0 - worst, utilization, limiting)


def case_statics(design: Design, geometry: Geometry, model: StaticsModel | None = None
                 ) -> tuple[CaseStatics, ...]:
    """Each load case solved: the ``starts`` of ``is_valid`` and ``margin_of`` for edits
    of this design (``model``: its statics model, if the caller already has it)."""
    model = model or build_model(design, geometry)
    return tuple(solve_load_cases(model, design.load_cases))


def load_checked(path: str) -> Design:
    """``load_design``: the design of a file, its schema checked (a resting joint whose
    planks do not touch is no input error but a ``disconnected`` violation, as any
    listed joint's: contract section 2)."""
    from furncheck.design import load_design

    return refuse_overlapping(load_design(path))


def refuse_overlapping(design: Design) -> Design:
    """``design``, or DesignTooBig when its planks' boxes meet in more than
    MAX_MEETING_PAIRS pairs (``geometry.analysis.meeting_count``: planks drawn on top of
    one another), asked of each input design as it is read, before its geometry: not of
    the edits a search checks on the way (one that adds a pair is a design of its own,
    not the input's fault)."""
    from furncheck.geometry.analysis import meeting_count

    pairs = meeting_count(design)
    if pairs > tol.MAX_MEETING_PAIRS:
        raise DesignTooBig.of_pairs(design.source, pairs, len(design.planks),
                                    tol.MAX_MEETING_PAIRS)
    return design


def load_data(data: bytes, source: str, fmt: str) -> Design:
    """``load_checked`` of a document's bytes that come from no file (standard input, or a
    file read by another process): ``source`` names it, ``fmt`` is 'yaml' or 'json'."""
    from furncheck.design.load import parse_design_bytes

    return refuse_overlapping(parse_design_bytes(data, source, fmt))


def check_file(path: str, model: str | None = None) -> DesignReport:
    """Load and validate one file (in ``model``, 'elastic' or 'rigid', when given: the
    command line's ``--model`` over the file's); an unreadable, ill-formed or too big
    design gives an error report."""
    try:
        return _check_loaded(load_checked(path), model)
    except DesignError as error:        # unreadable, ill-formed or too big
        return _problems(path, error)


def check_data(data: bytes, source: str, fmt: str, model: str | None = None) -> DesignReport:
    """``check_file`` of a document's bytes (standard input, or a file read by another
    process: ``furncheck.cluster``): the name that reports give it (``source``) and its
    format ('yaml' or 'json')."""
    try:
        return _check_loaded(load_data(data, source, fmt), model)
    except DesignError as error:
        return _problems(source, error)


def _problems(path: str, error: DesignError) -> DesignReport:
    """The report of a file that cannot be checked: its problems, a line each."""
    first, *more = error.lines()
    return DesignReport(design=path, name=Path(path).stem, valid=None, error=first,
                        more_errors=tuple(more))


def _check_loaded(design: Design, model: str | None) -> DesignReport:
    """The report of a design read and checked against its schema: analysed, refused
    when too big (``DesignTooBig``, a DesignError), else checked in ``model``."""
    design = with_model(design, model)
    geometry = analyze(design)
    statics_model = build_model(design, geometry) if geometry.stands else None
    refuse_too_big(design, statics_model, geometry)
    return check_design(design, geometry, statics_model)
