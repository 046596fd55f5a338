"""What ``furncheck suggest`` produces: ``Suggestion`` and ``SuggestionReport`` values."""

from __future__ import annotations

from dataclasses import dataclass, field

from furncheck.design.model import Design, Plank
from furncheck.result import DesignReport
from furncheck.suggest.cutlist import AnchorMove, LoadMove, LoadSpread, PlankEdit
from furncheck.suggest.explain import Explanation
from furncheck.suggest.score import ShopScore


@dataclass(frozen=True)
class Suggestion:
    """One ranked suggestion, continuous (changed DOFs) or discrete (added planks).

    dofs      : DOF names; ``direction`` (unit, scaled units) over them (continuous)
    range     : (low, high) valid steps along the direction, scaled units, or None: both
                ends valid, a step one resolution beyond each invalid -- or, ``limited``,
                ``high`` is where the search stopped (half the design's size, 28.6 degrees)
    step      : the representative step (the smallest change plus a reserve), or None
    changes   : each DOF's change at ``step``, its own unit (file length unit or degrees)
    adds      : planks added (discrete); ``between`` the planks a support joins
    rule      : the discrete rule that made it ('support', 'rail', 'apron', 'stretcher',
                'back panel', 'brace', 'outrigger', 'anchor', 'thicker', 'reconnect', 'nails',
                'fixings', 'pads', 'bracket');
                ``advice`` its sentence
    restores  : the kinds of violation it removes ('durability', 'stability', 'geometry',
                'stiffness' for sag, 'strength' for bending stress)
    design    : the representative design, parsed from ``text`` (its YAML file), and
                ``report`` its validation (valid: suggestions that are not are dropped)
    edits     : its cut list: every plank of the input it changes, adds or removes
                (``cutlist.plank_edits`` of the input and ``design``)
    loads_moved : the loads at a point it carries along with their planks
                (``cutlist.load_moves``)
    loads_spread : the spread loads whose planks it resizes (``cutlist.load_spreads``)
    anchors_moved : the input's wall fixings it carries along with their planks
                (``cutlist.anchor_moves``)
    score     : the shop's score it is ranked by (``score.ShopScore``)
    """

    rank: int
    kind: str
    restores: tuple[str, ...]
    design: Design
    text: str
    report: DesignReport
    dofs: tuple[str, ...] = ()
    direction: tuple[float, ...] = ()
    range: tuple[float, float] | None = None
    step: float | None = None
    changes: tuple[float, ...] = ()
    units: tuple[str, ...] = ()
    adds: tuple[Plank, ...] = ()
    between: tuple[str, ...] = ()
    rule: str = ""
    advice: str = ""
    limited: bool = False
    edits: tuple[PlankEdit, ...] = ()
    score: ShopScore | None = None
    loads_moved: tuple[LoadMove, ...] = ()
    loads_spread: tuple[LoadSpread, ...] = ()
    anchors_moved: tuple[AnchorMove, ...] = ()


@dataclass(frozen=True)
class SuggestionReport:
    """Everything ``furncheck suggest`` says about one design."""

    design: str
    name: str
    report: DesignReport
    suggestions: tuple[Suggestion, ...]
    searched: int = 0          # directions line-searched
    checks: int = 0            # full validity checks of continuous candidates
    seconds: dict[str, float] = field(default_factory=dict, compare=False)
    """Wall time of the phases ('candidates': margins, sensitivities and directions;
    'line search': line searches; 'discrete': support planks), for benchmarks; never
    reported."""
    explanation: Explanation | None = None
    """Which violations remain, what was tried and what each violation would need (None
    for a valid design)."""

    @property
    def valid(self) -> bool:
        return bool(self.report.valid)
