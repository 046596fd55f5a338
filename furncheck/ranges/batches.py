"""A design's edits and their checks, answered in batches for searches run together.

A search (one side of a DOF's range, ``finder``) is a generator: it yields the evaluations
it needs and receives their results.  ``Evaluator._run`` advances many searches together;
each round, the evaluations they all wait for are answered as one batch (``_answer``): the
geometry checks of all edits in one vectorized pass (``edit_check.check_edit_many``), their
geometric margins in another (``geometry.edit_margins_many``), the full checks one by one.
"""

from __future__ import annotations

from collections.abc import Generator
from typing import NamedTuple

import numpy as np

from furncheck.check import case_statics, is_valid, margin_of, refuse_too_big
from furncheck.design.model import Design
from furncheck.dofs import (
    Blocked,
    Dof,
    OutOfReach,
    Structure,
    apply_dof,
    dof_value,
    parse_dof,
    structure,
)
from furncheck.edit_check import check_edit_many, standing_geometry
from furncheck.geometry import EditMargins, Geometry, analyze, edit_margins_many
from furncheck.ranges.estimates import _Probe
from furncheck.statics import LineStarts, build_model

SEARCHES_IN_FLIGHT = 64
"""Most searches (sides of DOFs) advanced together: their evaluations are batched, their
edits kept while they run."""

MARGIN_ROWS = 1 << 14
"""Most rows of geometric margins evaluated in one batch (each row 18 margins)."""


class _Kept(NamedTuple):
    """Evaluation request of a search: the design with ``dof`` changed by ``step`` and its
    geometry if that keeps the joints and contacts, else (None, None)."""

    dof: Dof
    step: float


class _Margins(NamedTuple):
    """Evaluation request: ``margins`` (an ``EditMargins``) of an edited ``design``."""

    margins: EditMargins
    design: Design


class _Statics(NamedTuple):
    """Evaluation request: the full check of an edited design that keeps the joints and
    contacts, ``check.margin_of`` (with ``first``: that load case solved first, the
    cases stopping at the first that fails) if ``margin`` else ``check.is_valid``; the
    design is the searched DOF changed by ``step``."""

    design: Design
    geometry: Geometry
    margin: bool
    step: float
    first: int | None = None


class Evaluator:
    """The edits of one design (a DOF changed by a step, its neighbours following) and
    their checks, for searches advanced together (``_run``)."""

    def __init__(self, design: Design, locked: tuple[str, ...] = ()):
        self.design = design
        self.geometry: Geometry = analyze(design)
        self.frame: Structure = structure(design, standing_geometry(self.geometry))
        self.locked_names = tuple(locked)
        self.locked = tuple(parse_dof(design, name) for name in locked)
        self.model = build_model(design, self.geometry)     # shared by the design's own
        refuse_too_big(design, self.model)                  # checks
        self.starts = case_statics(design, self.geometry, self.model)
        self._lines: dict[Generator, LineStarts] = {}   # where each search's edits start
        self._kept: dict[Dof, dict[float, tuple]] = {}
        self._edits: dict[Dof, dict[float, Design]] = {}
        self.evaluations = 0
        self.stand = False     # planks may come to stand on the ground (an invalid design)

    # -- running searches ----------------------------------------------------------------------
    def _run(self, searches: dict[tuple[int, float], Generator],
             dofs: list[Dof]) -> dict[tuple[int, float], object]:
        """Advance the ``searches`` ((DOF number, side) -> generator) until each returns or
        raises Blocked: every round, the evaluations they all wait for (``_Kept``,
        ``_Margins``, ``_Statics``) are made together (``_answer``) and sent back; at most
        SEARCHES_IN_FLIGHT run at a time (the others start as they end).  Once
        the lower side of a DOF is blocked its upper side is dropped (the lower side's
        reason is reported, as when the sides are searched one after the other).  A DOF's
        cached edits are dropped when its last search ends."""
        found: dict[tuple[int, float], object] = {}
        waiting: dict[tuple[int, float], object] = {}
        active = {dof: 0 for dof in dofs}
        for n, _ in searches:
            active[dofs[n]] += 1
        queued = list(searches)[::-1]

        def ended(key: tuple[int, float], result: object) -> None:
            found[key] = result
            self._lines.pop(searches[key], None)
            dof = dofs[key[0]]
            active[dof] -= 1
            if not active[dof]:
                self._edits.pop(dof, None)
                self._kept.pop(dof, None)

        def advance(key: tuple[int, float], answer: tuple) -> None:
            value, error = answer
            try:
                request = searches[key].send(value) if error is None else \
                    searches[key].throw(error)
            except StopIteration as stop:
                ended(key, stop.value)
            except Blocked as why:
                ended(key, why)
                upper = (key[0], 1.0)
                if key[1] < 0.0 and (upper in waiting or upper in queued):
                    searches[upper].close()
                    waiting.pop(upper, None)
                    if upper in queued:
                        queued.remove(upper)
                    ended(upper, None)
            else:
                waiting[key] = request

        while waiting or queued:
            while queued and len(waiting) < SEARCHES_IN_FLIGHT:
                advance(queued.pop(), (None, None))
            batch, waiting = waiting, {}
            answers = self._answer(list(batch.values()), [searches[key] for key in batch])
            for key, answer in zip(batch, answers):
                advance(key, answer)
        return found

    def _now(self, search: Generator, dof: Dof):
        """Run one search (a generator of evaluations) of ``dof`` to its end: its result."""
        return self._run({(0, 0.0): search}, [dof])[(0, 0.0)]

    def _answer(self, requests: list, asking: list[Generator]
                ) -> list[tuple[object, Exception | None]]:
        """(value, error) per request: ``_Kept`` checks all at once
        (``edit_check.check_edit_many``), ``_Margins`` all at once (``geometry.edit_margins_many``),
        then ``_Statics`` one by one, each load case's contact iterations starting where
        the case settled in the nearest edit that the search asking (``asking``, per
        request) has checked so far, or in the design (``statics.LineStarts``, one per
        search: its starts depend on its own probes alone, whatever else the batch holds,
        and a DOF named twice is searched twice alike)."""
        answers: list = [None] * len(requests)
        kept = [k for k, request in enumerate(requests) if isinstance(request, _Kept)]
        for k, answer in zip(kept, self._kept_many([requests[k] for k in kept])):
            answers[k] = answer
        measured = [k for k, request in enumerate(requests) if isinstance(request, _Margins)]
        while measured:         # at most MARGIN_ROWS rows at a time (memory)
            rows = np.cumsum([len(requests[k].margins.edge) for k in measured])
            count = max(1, int(np.searchsorted(rows, MARGIN_ROWS, side="right")))
            chunk, measured = measured[:count], measured[count:]
            for k, values in zip(chunk, edit_margins_many([requests[k] for k in chunk])):
                answers[k] = (values, None)
        for k, request in enumerate(requests):
            if isinstance(request, _Statics):
                if asking[k] not in self._lines:
                    self._lines[asking[k]] = LineStarts(self.starts)
                line = self._lines[asking[k]]
                starts, solved = line.near(request.step), {}
                if request.margin:
                    answers[k] = (margin_of(request.design, request.geometry, starts,
                                            first=request.first, solved=solved), None)
                else:
                    answers[k] = (is_valid(request.design, request.geometry, starts,
                                           solved=solved), None)
                line.keep(request.step, solved)
        return answers

    def _kept_many(self, requests: list[_Kept]) -> list[tuple[object, Exception | None]]:
        """Per request: the design with its DOF changed by its step and the geometry if
        it keeps the joints and ground contacts, else (None, None); Blocked as the error
        if the step would change a locked DOF.  Answers are kept per DOF (while its
        search runs): the full check of a geometric reach follows the geometry check
        that found it."""
        answers: list = [None] * len(requests)
        todo = []
        for k, (dof, step) in enumerate(requests):
            known = self._kept.setdefault(dof, {})
            if step in known:
                answers[k] = (known[step], None)
                continue
            try:
                edited = apply_dof(self.design, self.frame, dof, step)
            except OutOfReach:
                known[step] = (None, None)
                answers[k] = (known[step], None)
                continue
            except Blocked as why:
                answers[k] = (None, why)
                continue
            moved_lock = next((lock for lock in self.locked if abs(
                dof_value(edited, lock) - dof_value(self.design, lock)) > 1e-9), None)
            if moved_lock is not None:
                answers[k] = (None, Blocked(f"it would change the locked {moved_lock.name}"))
                continue
            todo.append((k, dof, step, edited))
        self.evaluations += len(todo)
        checks = check_edit_many(self.geometry, [edited for *_, edited in todo], self.design,
                                 self.stand)
        for (k, dof, step, edited), (problem, geometry) in zip(todo, checks):
            self._kept[dof][step] = (None, None) if problem is not None else (edited, geometry)
            answers[k] = (self._kept[dof][step], None)
        return answers

    # -- validity of one step (searches: generators of evaluations) ---------------------------
    def _valid_at(self, dof: Dof, step: float, full: bool = True):
        """Whether the design with ``dof`` changed by ``step`` keeps its joints and ground
        contacts and (``full``) is valid in every load case."""
        edited, geometry = yield _Kept(dof, step)
        if geometry is None:
            return False
        if not full:
            return True
        return (yield _Statics(edited, geometry, False, step))

    def _probe(self, dof: Dof, sign: float, step: float, first: int | None = None):
        """The full check of one step (>= 0) in direction ``sign``, with the design's
        margin (``check.margin_of``; with ``first``, that load case solved first and an
        invalid step's cases stopping at the first that fails): a ``_Probe``."""
        edited, geometry = yield _Kept(dof, sign * step)
        if geometry is None:
            return _Probe(step, False, -np.inf, None, None)
        valid, margin, utilization, case = yield _Statics(edited, geometry, True,
                                                          sign * step, first)
        return _Probe(step, valid, margin, utilization, geometry, case)

    def _edited(self, dof: Dof, step: float) -> Design:
        """The design with ``dof`` changed by ``step``, kept while the DOF's searches run
        (both sides and both turn horizons make the same margin probes)."""
        if not step:
            return self.design
        edits = self._edits.setdefault(dof, {})
        if step not in edits:
            edits[step] = apply_dof(self.design, self.frame, dof, step)
        return edits[step]
