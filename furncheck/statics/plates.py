"""A plank held along lines, checked as a plate as well as by its beam.

Contract 3a gives each plank one beam, whose cross-section stays straight.  Where panels
hold the plank along lines (a step box's top nailed to its four sides, a shelf nailed
along its back edge to slats and at its ends to sides, a nightstand top on sides
shallower than it is deep), the beam held along them shows little of the plank's
bending, which happens across it, between the lines: a top nailed all round read 0.01
mm where a plate sags 0.71 to 1.53 mm (``benchmarks/compare_plate.py``), and a beam
spreads a point load over its whole width (a load at a top's free front edge read as
at its centre).  So such a plank is also solved as a plate, on its own:

* which planks (``plate_supports``): those not standing on the floor whose joint lines,
  held straight by their other planks (``elastic._holds_straight``: a panel, not a
  rail), cover at least PLATE_HELD_SHARE of one of its sides on one line or one side of
  its middle, and hold it somewhere off that line too, or that one joint alone holds,
  along its beam (a shelf nailed by its back edge onto a rail: hung on that line, its
  row's grip its only hold against turning, ``plate_mesh._hinge``); and whose weight or
  loads push across its face;
* the plate (``statics.plate_mesh``): Mindlin, bilinear elements with selectively
  reduced shear integration, on a grid through every support line's ends and the edges
  of the load patches of the case it is read in (each case on its own grid: ``_solved``),
  about PLATE_CELLS elements across its shorter side, factored as a band (LAPACK's
  pbtrf, the nodes numbered across the shorter direction first);
* its supports: those joint lines, simply supported, with each nail row's grip against
  turning about its line as a spring (contract 3a's n nail_withdrawal (t/2)^2, spread
  along the line), as the beams have it;
* its loads: its own weight and the case's spread loads over its face, each point load
  spread over a square PLATE_LOAD_PATCH wide (kept on the plank), the components across
  its face only.  Forces that other planks bring through its joints (a divider standing
  on a cabinet's bottom) are not the plate's: its beam carries them.

Its sag is the plate's largest deflection between its supports (the supports do not
move; an overhang beyond them is its beam's, measured from the tangent at its support;
a plate hung on one line is all overhang, its deflections measured from the tangent at
that line),
its span the distance between the outermost supports on either side of that point
along the plank's axes, the shorter way (``_span_at``, as contract 3a has a beam's),
and its stress the largest principal moment's 6 |M| / t^2 at
the elements' centres (and, hung on one line, of the moments at that line,
``plate_mesh._line_moments``).
Where these exceed the beam's they are the plank's (``with_plates``); the joints' and
contacts' forces stay the beam model's.  The sensitivities of ``range`` and ``suggest``
read a plate's changes where its reading is its plank's and near its limit
(``plate_readings``, ``derivatives._plate_sides``); every range end and suggestion is
checked in full, plate included.
Planks alike (a bookcase's shelves), cases with the same patches on one plank, and a
plank that an edit leaves as it was share one factored plate (``plate_for``: its inputs
rounded to a nanometre).
"""

from __future__ import annotations

import weakref
from collections import OrderedDict
from collections.abc import Iterator
from typing import NamedTuple

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, Load, LoadCase, Plank
from furncheck.statics.plate_mesh import PlateGrid, plate_grid, plate_solutions, sag_span
from furncheck.statics.plate_supports import force_across, held_planks


class PlatePlank(NamedTuple):
    """One plank checked as a plate: its local index in the model, the plank, its
    ``PlateGrid`` on its first case's patches (``_first_patches``) and that grid's inputs
    (``_plate_key``: each case's grid is this key with its own patches, ``_grid_key``)."""

    local: int
    plank: Plank
    grid: PlateGrid
    key: tuple


def plate_planks(model) -> tuple[PlatePlank, ...]:
    """The model's planks to check as plates, each with its factored plate; kept in
    ``model.plank_cache`` (load-independent)."""
    cached = model.plank_cache.get("plates")
    if cached is None:
        for _ in each_plate(model):
            pass
        cached = model.plank_cache["plates"]
    return cached


def each_plate(model) -> Iterator[PlatePlank]:
    """``plate_planks``, one at a time, in the model's order, each found and factored as
    it is asked for (a search that stops at the first plate that fails finds no more);
    kept in ``model.plank_cache`` once all have been."""
    cached = model.plank_cache.get("plates")
    if cached is not None:
        yield from cached
        return
    found = []
    first = _first_case_loads(model.design)
    for k, plank, lines, rails in held_planks(model):
        plate = _plate(model, k, plank, lines, rails, first.get(plank.id, ()))
        if plate is not None:
            found.append(plate)
            yield plate
    model.plank_cache["plates"] = tuple(found)


def _first_case_loads(design: Design) -> dict[str, list]:
    """Per plank id, the first load case's loads on it (``_first_patches``)."""
    return _by_plank(design.load_cases[0]) if design.load_cases else {}


def _by_plank(case: LoadCase) -> dict[str, list]:
    """Per plank id, the case's loads on it, in order."""
    loads: dict[str, list] = {}
    for load in case.loads:
        loads.setdefault(load.plank, []).append(load)
    return loads


def _first_patches(design: Design, plank: Plank, loads) -> list:
    """The patches of the first load case's point loads on ``plank`` (``loads``: its
    entry of ``_first_case_loads``) that push across its face (``_load_patches``): the
    grid a plate plank is found on, the first case's."""
    return _load_patches(_case_loads(design, loads, plank))


class PlateReading(NamedTuple):
    """A plate's sag (m), span (m) and stress (Pa) in one load case, and its grid lines
    (x, y: ``PlateGrid.xs``, ``ys``), for the force sensitivities (``plate_readings``)."""

    sag: float
    span: float
    stress: float
    lines: tuple


def plate_readings(model, case: LoadCase, only: set[int]) -> dict[int, PlateReading]:
    """Per local plank of ``only`` that the model checks as a plate: its plate's reading
    in ``case``, the sag, span and stress that ``plate_results`` gives, each plank found
    and solved on its own: the force sensitivities read the plates of a design's stepped
    edits, where the planks a step leaves as they were read as the design's
    (``derivatives._plate_sides``).  A stepped design is linearized in every load case,
    each time a model of its own, and each of its plates is new to the PLATE_CACHE
    factored plates, which do not keep it long: so which planks of a design are plates,
    and their plates' inputs, are kept per design object (``_KEYS``, the last
    PLATE_DESIGNS asked; a design's stepped edits live as long as its search, one object
    each, and their joints followed through the step are theirs alone), and a plate
    asked for is read for every case's loads on it at once (``_solved``: kept by the
    plate's inputs and its loads): a case asked later reads it without finding or
    factoring the plate again.  Each reading is a function of the plate and its loads,
    bit for bit, whatever else was asked.  ``case`` is one of the design's own."""
    design = model.design
    entry = _KEYS.get(id(design))
    if entry is None or entry[0]() is not design:       # (an id freed and reused: anew)
        entry = _KEYS[id(design)] = (weakref.ref(design), {})
        while len(_KEYS) > tol.PLATE_DESIGNS:
            _KEYS.popitem(last=False)
    _KEYS.move_to_end(id(design))
    known = entry[1]
    missing = only - known.keys()
    found_all = model.plank_cache.get("plates")
    if missing and found_all is not None:       # the model's own plates, found already
        for k in missing:
            known[k] = None
        known.update((plate.local, (plate.plank, plate.key)) for plate in found_all
                     if plate.local in missing)
    elif missing:
        for k in missing:
            known[k] = None
        first = _first_case_loads(design)
        for k, plank, lines, rails in held_planks(model, missing):
            patches = _first_patches(design, plank, first.get(plank.id, ()))
            known[k] = (plank, _plate_key(plank, design.material_of(plank), lines, patches,
                                          rails))
    found = {}
    for k in sorted(only):
        if known[k] is None:
            continue
        plank, key = known[k]
        reading = _reading(design, plank, key, case)
        if reading is not None:
            found[k] = reading
    return found


def _reading(design: Design, plank: Plank, key: tuple, case: LoadCase) -> PlateReading | None:
    """``plate_readings``' reading of the plate of inputs ``key`` in ``case`` (None where
    its supports leave it free): ``_solved`` for the loads on the plank of every case
    read on the same grid as ``case`` (a case asked later finds its reading kept; one
    with other patches factors its own grid when it is asked for)."""
    cases = list(design.load_cases)
    index = next(i for i, one in enumerate(cases) if one.name == case.name)
    loads = _plank_loads(design, plank, cases)
    grid_key = _grid_key(key, loads[index])
    alike = [i for i, one in enumerate(loads) if _grid_key(key, one) == grid_key]
    return _solved(key, None, [loads[i] for i in alike])[alike.index(index)]


def _solved(key: tuple, grid: PlateGrid | None, loads: list) -> list[PlateReading | None]:
    """The readings of the plate of inputs ``key`` under each of ``loads``
    (``_case_loads``), each on the grid through its own load's patches: the plate of
    ``key`` with the patches of ``key`` replaced by that load's (``_grid_key``; ``grid``,
    the factored plate of ``key`` itself, or None: found by its key where asked for), so
    that a case's reading is a function of its own loads, whatever the other cases load
    (with every case's patches in one grid, one case's sag moved by a percent or two
    when another case's load was added).  Each reading is kept by its grid's inputs and
    its loads (``_READINGS``, the last PLATE_READINGS asked, with the tolerance
    ``sag_span`` reads that the key leaves out): those missing are solved together per
    grid, in batches of PLATE_BATCH, and each is a function of the plate and its loads
    alone (``plate_solutions`` solves each load bit for bit as alone:
    ``tests/test_plates.py``), whatever was asked with it or before it.  None where the
    supports leave the plate free."""
    wanted = [(_grid_key(key, one), tol.NODE_MERGE_ROUNDOFF, _load_key(one)) for one in loads]
    found = {want: _READINGS.get(want, _MISSING) for want in wanted}
    missing = dict((want, one) for want, one in zip(wanted, loads)
                   if found[want] is _MISSING)                  # each distinct load once
    by_grid: dict[tuple, list] = {}
    for want, one in missing.items():
        by_grid.setdefault(want[0], []).append((want, one))
    for grid_key, asked in by_grid.items():
        on = grid if grid is not None and grid_key == key else plate_grid(*grid_key)
        for start in range(0, len(asked), tol.PLATE_BATCH):
            some = asked[start:start + tol.PLATE_BATCH]
            solutions = [None] * len(some) if on is None else \
                plate_solutions(on, [one for _, one in some])
            for (want, _), solution in zip(some, solutions):
                found[want] = None if solution is None else \
                    PlateReading(*sag_span(on, solution[0]), solution[1], (on.xs, on.ys))
    for want in found:
        _READINGS[want] = found[want]
        _READINGS.move_to_end(want)
    while len(_READINGS) > tol.PLATE_READINGS:
        _READINGS.popitem(last=False)
    return [found[want] for want in wanted]


def _grid_key(key: tuple, loads: tuple) -> tuple:
    """``key`` (``_plate_key``) with its patches those of ``loads`` (``_load_patches``)."""
    return (*key[:-2], _patch_key(_load_patches(loads)), key[-1])


def _load_patches(loads: tuple) -> list:
    """The patches of a plate's loads (``_case_loads``) whose forces push across its face
    (their edges are its grid's lines; a force along the face has none)."""
    return [patch for patch, force in loads[1] if force != 0.0]


_MISSING = object()


def same_grid(reading: PlateReading, other: PlateReading) -> bool:
    """Whether two readings' plates have the same grid but for lines moved by at most
    PLATE_STEP_LINES (a support line that a sensitivity's step moves): their difference
    is then the plate's, not a cell more or less (a step of a few hundredths of a
    micrometre can add one, where an interval between lines is a whole number of cells:
    its sag read 3,000 times its rate)."""
    return all(len(a) == len(b) and float(np.abs(a - b).max(initial=0.0)) <= tol.PLATE_STEP_LINES
               for a, b in zip(reading.lines, other.lines))


def plate_governs(reading, beam_sag: float, beam_span: float, beam_stress: float,
                  replaces: bool = False) -> tuple[bool, bool]:
    """Whether a plate's (sag, span, stress) ``reading`` is its plank's sag and span (its
    sag over its span the larger: the sag rule's share, a beam's short overhang may use
    more of its allowed sag than the plate's larger sag over its longer span), and
    whether its stress (the larger): ``_merged``'s rule; both where it ``replaces`` the
    beam's (``whole_rows_hung``)."""
    if replaces:
        return True, True
    sag, span, stress = reading[:3]
    beam = beam_sag / beam_span if beam_span > 0.0 else 0.0      # no span: no sag rule
    return span > 0.0 and sag / span > beam, stress > beam_stress


_KEYS: OrderedDict = OrderedDict()
"""id(design) -> (a weak reference to the design, {local plank: (plank, ``_plate_key``)
or None where it is no plate}) (``plate_readings``), the most recently asked last; an
entry whose design is gone, its id another's, is made anew."""

_READINGS: OrderedDict = OrderedDict()
"""(``_grid_key``, NODE_MERGE_ROUNDOFF, ``_load_key``) -> ``PlateReading``, or None where
the supports leave the plate free (``_solved``: every reading of a plate), the most
recently asked last."""


_ATTACHED: dict = {}
"""id(design) -> (a weak reference to the design, {plank id: ((point, force), ...)}): the
weights of the leaves of each plank hung on one row (``plate_supports._hanging``), which
its plate carries at their rows' middles (``_case_loads``).  An entry lives as long as
its design (the reference's callback removes it), so that a design's plates read the same
whatever was read in between; an id freed and reused starts anew."""


def attach(design: Design, plank_id: str, weights: tuple) -> None:
    """Record ``weights`` ((point, force) per leaf, m and N) as the loads that the planks
    hanging on ``plank_id`` alone put on its plate (``_ATTACHED``); a plank found hung
    again (a stepped design's, another case's) records the same."""
    key = id(design)
    entry = _ATTACHED.get(key)
    if entry is None or entry[0]() is not design:
        def gone(ref, key=key):
            if key in _ATTACHED and _ATTACHED[key][0] is ref:
                del _ATTACHED[key]
        entry = _ATTACHED[key] = (weakref.ref(design, gone), {})
    entry[1][plank_id] = weights


def _attached(design: Design, plank_id: str) -> tuple:
    """The weights ``attach`` recorded for the plank of ``design`` (none where none were)."""
    entry = _ATTACHED.get(id(design))
    return entry[1].get(plank_id, ()) if entry is not None and entry[0]() is design else ()


def _load_key(loads: tuple) -> tuple:
    """A plate's loads (``_case_loads``: pressure, [(patch, N)]) as a key."""
    uniform, points = loads
    return float(uniform), tuple((tuple(patch), float(force)) for patch, force in points)


def _plate(model, k: int, plank: Plank, segments, stiffeners,
           first_loads) -> PlatePlank | None:
    """The factored plate of plank ``plank`` (local ``k``) on ``segments``, stiffened by
    ``stiffeners``, on the grid of the first load case (``first_loads``: that case's loads
    on it, ``_first_patches``; each case is read on its own grid, ``_solved``)."""
    design = model.design
    return plate_for(plank, design.material_of(plank), segments,
                     _first_patches(design, plank, first_loads), k, stiffeners)


def plate_for(plank: Plank, material, segments, patches, local: int = 0,
              stiffeners=()) -> PlatePlank | None:
    """The factored plate of ``plank`` (its sizes and thickness; ``material``: E and G)
    simply supported on ``segments`` (((x0, y0), (x1, y1), grip N m / rad per m),
    plank-local, along its axes), with the nail rows' grip against turning about them;
    its grid passes through the segments' ends and the ``patches`` ((x0, x1, y0, y1),
    plank-local) edges.  ``stiffeners`` (((x0, y0), (x1, y1), E I N m^2)): rails along
    its axes, beams that bend with it along their lines (``plate_supports``).  None
    where the segments leave it free to move.  Its numbers are those of the inputs
    rounded to a nanometre (and the grips and stiffnesses to nine digits), so that planks
    alike (a bookcase's shelves) and the same plank in a design's edits
    share one factored plate (``plate_grid``, kept for the last PLATE_CACHE asked)."""
    key = _plate_key(plank, material, segments, patches, stiffeners)
    grid = plate_grid(*key)
    return None if grid is None else PlatePlank(local, plank, grid, key)


def _plate_key(plank: Plank, material, segments, patches, stiffeners) -> tuple:
    """``plate_grid``'s arguments for ``plate_for``'s inputs: the tolerances it follows,
    then the inputs rounded to a nanometre (the grips and stiffnesses to nine digits)."""
    def nm(value: float) -> float:
        return round(float(value), 9)

    segments = [(*sorted((tuple(a), tuple(b))), value) for a, b, value in segments]
    stiffeners = [(*sorted((tuple(a), tuple(b))), value) for a, b, value in stiffeners]
    return (tol.PLATE_CELLS, tol.PLATE_CELL_FLOOR, tol.PLATE_PATCH_CELLS, tol.PLATE_POISSON,
            tol.NODE_MERGE, tol.PLATE_GRID_LINES, tol.PLATE_CELL_SLACK, nm(plank.length),
            nm(plank.width), nm(plank.thickness),
            float(material.elastic_modulus), float(material.shear_modulus),
            tuple(((nm(a[0]), nm(a[1])), (nm(b[0]), nm(b[1])), float(f"{grip:.9g}"))
                  for a, b, grip in segments),
            _patch_key(patches),
            tuple(((nm(a[0]), nm(a[1])), (nm(b[0]), nm(b[1])), float(f"{rigidity:.9g}"))
                  for a, b, rigidity in stiffeners))


def _patch_key(patches) -> tuple:
    """Patches ((x0, x1, y0, y1) m each) as a key: each rounded to a nanometre, each once,
    in order (the grid they make does not depend on their order)."""
    return tuple(sorted({tuple(round(float(v), 9) for v in patch) for patch in patches}))


def _patch(plank: Plank, load) -> tuple[float, float, float, float]:
    """(x0, x1, y0, y1) m, plank-local: where a point load presses, a PLATE_LOAD_PATCH
    square about its point (the plank's centre where it has none), clipped to the plank."""
    point = plank.center_array if load.point is None else np.asarray(load.point, dtype=float)
    x, y = plank.to_local(point[None, :])[0, :2]
    a = tol.PLATE_LOAD_PATCH / 2.0
    hx, hy = plank.length / 2.0, plank.width / 2.0
    x0 = max(-hx, min(x - a, hx - 2.0 * a))   # on the plank, along its edge at most
    y0 = max(-hy, min(y - a, hy - 2.0 * a))
    x1, y1 = x0 + min(2.0 * a, 2.0 * hx), y0 + min(2.0 * a, 2.0 * hy)
    return float(x0), float(x1), float(y0), float(y1)


def plate_results(model, cases: list[LoadCase]) -> list[list[tuple[int, float, float, float]]]:
    """Per case, (local plank, sag m, span m, stress Pa) of each plate plank of the model
    (see the module docstring): ``_solved``, the planks that share a factored plate
    (planks alike) for all the cases at once."""
    design = model.design
    on_plank = [_by_plank(case) for case in cases]
    groups: dict[tuple, list[PlatePlank]] = {}
    for plate in plate_planks(model):
        groups.setdefault(plate.key, []).append(plate)
    found: dict[int, list] = {}
    for key, plates in groups.items():
        loads = [_case_loads(design, by_plank.get(plate.plank.id, ()), plate.plank)
                 for plate in plates for by_plank in on_plank]
        readings = iter(_solved(key, plates[0].grid, loads))
        for plate in plates:
            found[plate.local] = [_entry(plate.local, next(readings)) for _ in cases]
    return [[found[plate.local][c] for plate in plate_planks(model)
             if found[plate.local][c] is not None] for c in range(len(cases))]


def _entry(local: int, reading: PlateReading | None) -> tuple | None:
    """(local plank, sag, span, stress) of a reading; None where the case's grid leaves
    the plate free (its supports on one line: as on the first case's grid, but for a
    factoring that fails by round-off)."""
    return None if reading is None else (local, *reading[:3])


def plate_cases(design: Design, plate: PlatePlank,
                cases: list[LoadCase]) -> list[tuple[float, float, float]]:
    """Per case of ``cases``, the (sag m, span m, stress Pa) of one plate plank
    (``_solved``: the numbers ``plate_results`` gives; none for a case whose grid leaves
    the plate free)."""
    return [reading[:3] for reading in
            _solved(plate.key, plate.grid, _plank_loads(design, plate.plank, cases))
            if reading is not None]


def _plank_loads(design: Design, plank: Plank, cases: list[LoadCase]) -> list:
    """``_case_loads`` of the plank in each of ``cases``."""
    return [_case_loads(design, [load for load in case.loads if load.plank == plank.id],
                        plank) for case in cases]


def _case_loads(design: Design, loads, plank: Plank) -> tuple[float, list]:
    """(Pa, [(patch, N)]): the pressure across the plank's face of its weight and the
    spread ones of ``loads`` (a case's loads on it), and each of its point loads, its
    force across the face and its patch (``_patch``), the weights of its leaves first
    (``attach``: the planks that hang on a hung plank alone, a lip); along the face
    normal, positive.
    A force across the face of PLATE_SLANT of itself or less is along the face
    (``plate_supports.force_across``): its patch makes no grid lines
    (``_load_patches``)."""
    normal = np.asarray(plank.axes[2])
    area = plank.length * plank.width
    uniform = -design.plank_mass(plank) * tol.GRAVITY * normal[2] / area
    points = [(_patch(plank, Load(plank.id, force, point)), force_across(force, normal))
              for point, force in _attached(design, plank.id)]
    for load in loads:
        across = force_across(load.force, normal)
        if load.spread:
            uniform += across / area
        else:
            points.append((_patch(plank, load), across))
    return uniform, points


def plate_solution(plate: PlatePlank, uniform: float, points) -> tuple[np.ndarray, float]:
    """The plate's node deflections (m, along the plank's face normal; row-major, x
    fastest) under a ``uniform`` pressure (Pa) and forces spread over patches
    (``points``: ((x0, x1, y0, y1), N) each, shared by the elements by their overlap with
    the square: its edges are grid lines, or within a millimetre of one), and its largest
    bending stress (Pa), 6 |M| / t^2 of the largest principal moment at an element's
    centre."""
    return plate_solutions(plate.grid, [(uniform, points)])[0]


def with_plates(model, cases: list[LoadCase], planks: list) -> list:
    """``planks`` (a ``bending.PlankStatics`` per case of ``cases``) with each plate
    plank's sag, span and stress the plate's where they exceed the beam's, or where the
    plate replaces the beam's reading (``_merged``, ``whole_rows_hung``)."""
    if not plate_planks(model):
        return planks
    whole = whole_rows_hung(model)
    hinged = frozenset(plate.local for plate in plate_planks(model)
                       if plate.grid.hinge is not None)
    return [_merged(one, found, whole, hinged)
            for one, found in zip(planks, plate_results(model, cases))]


def whole_rows_hung(model) -> frozenset[int]:
    """The local planks checked as plates hung on their one row (``plate_mesh._hinge``)
    whose row is left whole (the plank at its other side keeps it whole, a wide upright
    panel under a board, or it has too few nails to cut: ``elastic.joint_part_counts``):
    their beam, held at the row's middle alone, reads overhangs along its length that
    the plank, hung along the whole row, does not have, so the plate's sag, span and
    stress are the plank's (the plate holds every load on it: nothing rests on it, and
    what is nailed to it alone, its leaves, weighs on the plate, ``attach``).  Kept in
    ``model.plank_cache``."""
    cached = model.plank_cache.get("whole_rows_hung")
    if cached is None:
        from furncheck.statics.elastic import model_hung_planks

        counts = model.plank_cache.get("joint_part_counts")
        hung = model_hung_planks(model)
        found = set()
        for plate in plate_planks(model):
            if plate.grid.hinge is None or counts is None or plate.plank.id not in hung:
                continue
            if int(counts[hung[plate.plank.id][0]]) == 1:
                found.add(plate.local)
        cached = model.plank_cache["whole_rows_hung"] = frozenset(found)
    return cached


def _merged(planks, found, whole: frozenset[int] = frozenset(),
            hinged: frozenset[int] = frozenset()):
    """``planks`` (one case's ``PlankStatics``) with the plates' ``found`` (local plank,
    sag, span, stress) where they exceed it: the plate's sag and span where its sag over
    its span is the larger (the sag rule's share: a beam's short overhang may use more
    of its allowed sag than the plate's larger sag over its longer span), the larger
    stress; all three the plate's for the planks of ``whole`` (``whole_rows_hung``).  A
    plate's reading is an overhang's where the plate hangs on one line (``hinged``: its
    span is twice its overhang, and the sagging message says so), else a span's."""
    from dataclasses import replace

    sag, span, stress = planks.sag.copy(), planks.span.copy(), planks.stress.copy()
    overhang = None if planks.overhang is None else planks.overhang.copy()
    by_plate = set()
    for k, plate_sag, plate_span, plate_stress in found:
        if plate_governs((plate_sag, plate_span, plate_stress), sag[k], span[k],
                         stress[k], k in whole)[0]:
            sag[k], span[k] = plate_sag, plate_span
            by_plate.add(k)
            if overhang is not None:
                overhang[k] = k in hinged
        stress[k] = plate_stress if k in whole else max(stress[k], plate_stress)
    beam_sideways = planks.sideways

    def sideways(k: int) -> bool:       # a plate's sag is across its face: not sideways
        return False if k in by_plate else beam_sideways(k)

    return replace(planks, sag=sag, span=span, stress=stress, overhang=overhang,
                   sideways=sideways if beam_sideways is not None and by_plate
                   else beam_sideways)
