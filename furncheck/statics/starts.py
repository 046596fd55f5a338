"""Where the contact iterations of a search's edits start: ``LineStarts``.

A search (one side of a DOF's range, a suggestion's line search) checks designs a step
along one line of edits from a design.  Each load case of such an edit is solved from the
same case as it settled in the design, or in an edit already checked nearer along the
line (``solve_case``'s ``near``): its friction phase then starts from those caps and
displacements instead of from the edit's own normal phase, to the same equilibrium within
the iterations' tolerances, in fewer Newton steps.
"""

from __future__ import annotations

from furncheck.statics.model import CaseStatics


def settled_start(statics: CaseStatics | None) -> CaseStatics | None:
    """What a later solve of an edit needs of a solved case to start near it
    (``solve_case``'s ``near``): its stability, holding contacts, contact forces and
    grounded nodes' displacements, without its joint forces, full displacements and
    planks (a search keeps one per probe); None where it did not settle."""
    if statics is None or statics.ground is None:
        return None
    return CaseStatics(statics.stability, None, statics.contact_forces,
                       holding=statics.holding, ground=statics.ground)


class LineStarts:
    """The load cases solved along one line of edits (steps in one unit, the design at
    step 0), and where the next edit's cases start (``near``)."""

    def __init__(self, design: tuple[CaseStatics | None, ...]):
        """``design``: the design's own cases solved (``check.case_statics``)."""
        self.design = tuple(settled_start(statics) for statics in design)
        self._solved: dict[float, dict[int, CaseStatics]] = {}

    def near(self, step: float) -> tuple[CaseStatics | None, ...]:
        """Per load case, the case as it settled in the checked edit nearest to ``step``
        (the first of equally near ones), or in the design where none is nearer.  A
        search's probes close in on where validity ends, so the last one is mostly the
        nearest.  An edit on the other side of the design is never nearer than the
        design: the start of a step depends only on the steps checked on its side."""
        starts, distance = list(self.design), [abs(step)] * len(self.design)
        for other, cases in self._solved.items():
            for case, start in cases.items():
                if abs(other - step) < distance[case]:
                    starts[case], distance[case] = start, abs(other - step)
        return tuple(starts)

    def keep(self, step: float, solved: dict[int, CaseStatics]) -> None:
        """Remember the cases solved (by index) in the edit at ``step``."""
        kept = {case: settled_start(statics) for case, statics in solved.items()}
        self._solved[step] = {case: start for case, start in kept.items() if start is not None}
