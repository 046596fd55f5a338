"""Discrete suggestions: fixes a woodworker makes by adding or changing a part (paper
section 6.5 and the shop's standard fixes), each checked in full like every suggestion.

    common     Fix, Candidate, Search (the one validation of every candidate), plank
               geometry (legs, parallel and facing planks), words
    supports   the paper's support plank under a failing joint, a stiffening rail under a
               bent plank
    brackets   a pair of brackets under a wall shelf, square to the rail it hangs on
    feet       against toppling: a support under the overhang, an outrigger foot
    anchors    a wall anchor where the design stands by a wall
    racking    aprons and stretchers between facing legs, back panels and diagonal braces
               across their edges
    turns      legs that rack across their thickness given a quarter turn about their length
    thicker    a thicker plank for one that sags, breaks or whose nails pull out; also
               finishes another rule's candidate that fails only by bending
    growth     how a thicker plank grows: which face stays, what moves or is cut with it
    reconnect  a near miss closed by lengthening or shortening the plank that misses
    nails      more nails in a listed joint that takes them
    nail_down  a loose part (type: rests) that lifts off or slides, nailed to what it
               lies on
    fixings    wall fixings rated for what they hold
    pads       non-slip pads under the feet of a piece that slides

``discrete_fixes`` runs the rules in order (``RULES``).  Each is tried only where the
report's violations are of the kinds it repairs, or some are and the others bend planks
too much in the elastic model (``common.Search.repairs``: thicker boards finish them; a
test of the report and the geometry, before any candidate is built), checks at most
``common.MAX_CANDIDATES`` candidates, its likeliest first, and gives at most one fix:
its first valid candidate.
"""

from __future__ import annotations

from dataclasses import replace

from furncheck.design.model import Design
from furncheck.dofs import Dof
from furncheck.geometry import Geometry
from furncheck.result import DesignReport
from furncheck.suggest.discrete.anchors import wall_anchors
from furncheck.suggest.discrete.brackets import wall_brackets
from furncheck.suggest.discrete.common import Fix, Search
from furncheck.suggest.discrete.feet import outriggers, overhang_supports
from furncheck.suggest.discrete.fixings import stronger_fixings
from furncheck.suggest.discrete.nail_down import nail_down
from furncheck.suggest.discrete.nails import more_nails
from furncheck.suggest.discrete.pads import non_slip_pads
from furncheck.suggest.discrete.racking import aprons, back_panels, braces, stretchers
from furncheck.suggest.discrete.reconnect import RECONNECT, reconnect_near_misses
from furncheck.suggest.discrete.supports import _reach, support_planks
from furncheck.suggest.discrete.thicker import thicker_planks
from furncheck.suggest.discrete.turns import quarter_turns
from furncheck.suggest.tried import FAILED, FOUND, Trial

__all__ = ["RULES", "Fix", "Search", "_reach", "discrete_fixes", "spares_no_board",
           "support_planks"]

RULES = (support_planks, wall_brackets, overhang_supports, outriggers, wall_anchors, aprons,
         stretchers, back_panels, braces, quarter_turns, thicker_planks, more_nails,
         nail_down, stronger_fixings, non_slip_pads)
"""The rules for a design that stands as drawn, in the order their fixes are listed: the
paper's support first, then added parts by how little they change the piece, then legs
turned (no part added), then a thicker board (a change of material), then more nails in
a listed joint that takes them, a loose part nailed down, wall fixings rated for what
they hold and non-slip pads under the feet (which change no part)."""


def spares_no_board(thickened: dict, alone: dict) -> bool:
    """Whether a fix that adds a part and thickens the planks ``thickened`` ({id: m})
    spares no board of the thicker rule's fix alone (``alone``): it thickens every plank
    that fix thickens, each at least as much (the part then only adds material; a part
    that lets one plank stay thinner is a different fix)."""
    return bool(thickened) and all(plank in thickened and thickened[plank] >= new
                                   for plank, new in alone.items())


def _fewest_boards(fixes: list[Fix]) -> list[Fix]:
    """The thicker boards fixes (the thicker rule's, and another rule's boards that hold
    without its part: ``thicker.boards_alone``) that no other one of them betters: a fix
    is left out where another thickens no plank it does not, none more, and is not the
    same (the same boards: the first is kept)."""
    kept = []
    for k, fix in enumerate(fixes):
        bettered = any(
            spares_no_board(fix.thickened, other.thickened)
            and (other.thickened != fix.thickened or j < k)
            for j, other in enumerate(fixes) if j != k)
        if not bettered:
            kept.append(fix)
    return kept


def _not_covered(search: Search) -> None:
    """The reconnect rule where the continuous search closed the gaps: no fix."""
    search.not_applicable(RECONNECT, "the continuous search closes the gaps")


SPARES_NO_BOARD = ("valid with thicker boards, but it needs every board the thicker board "
                  "fix alone needs, and adds a part: left out")


def _dropped(trials: list[Trial], tried: range, reason: str = SPARES_NO_BOARD) -> None:
    """The found trial among ``tried`` (the trials of the rule whose fix is left out: it
    spares no board of a thicker-board fix, or is one that another betters) told as
    failed for ``reason`` (the explanation must not count it found)."""
    for k in tried:
        trial = trials[k]
        if trial.outcome == FOUND:
            trials[k] = replace(trial, outcome=FAILED, reason=reason)


def discrete_fixes(design: Design, geometry: Geometry, report: DesignReport,
                   covered: bool = False, locked: tuple[Dof, ...] = (),
                   trials: list[Trial] | None = None) -> list[Fix]:
    """The working fixes of the rules for the invalid ``design`` (its geometry and
    report given), each with what it restores.  A design that does not stand as drawn
    gets ``reconnect`` only, and only when the continuous search found nothing
    (``covered`` False).  A fix that adds a part and thickens planks is dropped when it
    spares no board of a fix of thicker boards alone (``spares_no_board``), and so is
    a fix of thicker boards that another betters (``_fewest_boards``).  No fix
    changes a DOF of ``locked``.  Every rule's trials (each candidate, or why the rule
    does not apply) are appended to ``trials`` (``tried.Trial``)."""
    search = Search(design, geometry, report, locked, [] if trials is None else trials)
    reconnect = (_not_covered if covered and geometry.violations
                 else reconnect_near_misses)
    found, tried_by = [], []            # each rule's fix, and the trials it appended
    for rule in (*RULES, reconnect):
        start = len(search.trials)
        found.append(rule(search))
        tried_by.append(range(start, len(search.trials)))
    kept = [(fix, tried) for fix, tried in zip(found, tried_by, strict=True)
            if fix is not None]
    boards = _fewest_boards([fix for fix, _ in kept if fix.rule == "thicker"])
    found = []
    for fix, tried in kept:
        if fix.rule == "thicker":
            if any(fix is other for other in boards):
                found.append(fix)
            else:
                _dropped(search.trials, tried, "the same boards as another thicker-board "
                         "fix, or more: left out")
        elif any(spares_no_board(fix.thickened, other.thickened) for other in boards):
            _dropped(search.trials, tried)
        else:
            found.append(fix)
    restores = search.restores
    return [Fix(f.rule, f.advice, f.design, f.report, f.adds, f.between, restores,
                f.thickened) for f in found]
