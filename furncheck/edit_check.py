"""Whether an edit of a design (``dofs.apply_dof``) is still the design: the same joints
and contacts (none lost, none gained but a near miss closing, a plank joined to nothing
or drawn through another coming to rest on the face its end cut into, or, for the
edits of an invalid design, a
plank coming to stand on the ground), no plank cutting into another, no plank shrunk to
nothing, no anchor moved off its wall.

``check_edit`` and ``check_edit_many`` (many edits' geometry measured together, for the
range search) say why not, or None; ``design_problem`` is the part that needs no geometry.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from furncheck.design.model import Design
from furncheck.geometry import (
    EditedTables,
    Geometry,
    analyze,
    cut_in_pairs,
    drawn_through_closing,
    interpenetrations,
)
from furncheck.plain import plain_number

_ANCHOR_EPS = 1e-9
"""m: round-off slack on top of the tolerance when an anchor's distance to its wall is
compared with the drawn one."""


def check_edit(original: Geometry, edited: Design, design: Design | None = None,
               stand: bool = False) -> tuple[str | None, Geometry | None]:
    """Why the edited design no longer has the original's joints and contacts (or None),
    and the edited design's geometry (None when a plank lost its length).  With the
    original ``design``, joints between unchanged planks are not detected again, and
    ``stand`` lets planks come to stand on the ground (``check_edit_many``)."""
    if design is not None:
        return check_edit_many(original, [edited], design, stand)[0]
    problem = design_problem(edited)
    if problem is not None:
        return problem, None
    geometry = analyze(edited)
    problem = _edit_problem(original, geometry) or _cut_problem(edited, interpenetrations(edited))
    return problem, geometry


def check_edit_many(original: Geometry, edits: list[Design], design: Design,
                    stand: bool = False) -> list[tuple[str | None, Geometry | None]]:
    """``check_edit`` of many edits of ``design`` (whose geometry is ``original``), their
    geometries and plank cuts measured together (``geometry.EditedTables``).  ``stand``:
    a plank may come to stand on the ground it did not touch (the edits of an invalid
    design, as ``suggest``'s: standing a hovering leg on the floor is the point; the
    ground contacts it had are still kept)."""
    out: list = [(design_problem(edited), None) for edited in edits]
    sized = [k for k, (problem, _) in enumerate(out) if problem is None]
    tables = EditedTables(design, original, [edits[k] for k in sized])
    geometries = tables.geometries()
    cut_in = cut_in_pairs(design, original) | drawn_through_closing(design, original)
    problems = [None if kept else _edit_problem(original, geometry, cut_in, stand)
                for kept, geometry in zip(tables.kept, geometries)]
    clear = [n for n, problem in enumerate(problems) if problem is None]
    for n, cutting in zip(clear, tables.cuts(clear)):
        problems[n] = _cut_problem(edits[sized[n]], cutting)
    for k, problem, geometry in zip(sized, problems, geometries):
        out[k] = (problem, geometry)
    return out


def standing_geometry(geometry: Geometry) -> Geometry:
    """The geometry without the ground contacts of planks that sink into the ground: such
    a plank does not stand on the floor, it is to be shortened or raised onto it (the
    constraint structure that edits of an invalid design keep, ``dofs.structure``)."""
    sunk = {v.where for v in geometry.violations if v.kind == "penetration"}
    if not sunk:
        return geometry
    return replace(geometry, contacts=tuple(c for c in geometry.contacts
                                            if c.plank not in sunk))


def design_problem(edited: Design) -> str | None:
    """What makes an edit no design at all: a plank with no length or width left (its
    box would read as a mirrored one of negative mass), or an anchor moved off its wall
    (or into it) by more than the tolerance from where it was drawn (``Anchor.gap``)."""
    for plank in edited.planks:
        if plank.length <= 0 or plank.width <= 0:
            return f"{plank.id} would have no length left"
    for i, anchor in enumerate(edited.anchors):
        moved = float(edited.walls[anchor.wall].distance(np.asarray(anchor.point))) - anchor.gap
        if abs(moved) > edited.tolerance + _ANCHOR_EPS:
            return (f"anchors[{i}] would move {plain_number(abs(moved) / edited.unit_scale, 3)} "
                    f"{edited.units} {'off' if moved > 0 else 'into'} wall {anchor.wall}")
    return None


def _cut_problem(edited: Design, cutting: list[tuple[str, str, float]]) -> str | None:
    if not cutting:
        return None
    a, b, depth = cutting[0]
    return f"{a} would cut {plain_number(depth / edited.unit_scale, 3)} {edited.units} into {b}"


def _edit_problem(original: Geometry, geometry: Geometry,
                  cut_in: set[tuple[str, str]] = frozenset(), stand: bool = False) -> str | None:
    """Why ``geometry`` (of an edit) no longer has the ``original``'s joints and contacts,
    or None.  ``cut_in``: the (face, edge) joints that planks joined to nothing, or drawn
    through another, may form with the faces their ends cut into (``geometry.cut_in_pairs``,
    ``drawn_through_closing``); ``stand``: planks may
    come to stand on the ground (``check_edit_many``)."""
    known = {(v.kind, v.where) for v in original.violations}
    problems = [v for v in geometry.violations if (v.kind, v.where) not in known]
    if problems:
        first = problems[0]
        return f"{first.kind} {first.where}: {first.message}"
    before = {(j.face, j.edge, j.edge_face) for j in original.joints}
    after = {(j.face, j.edge, j.edge_face) for j in geometry.joints}
    if before - after:
        face, edge, _ = sorted(before - after)[0]
        return f"joint {face}/{edge} would come apart"
    closing = {miss.planks for miss in original.near_misses}   # a near miss may close,
    listed = {frozenset(v.where.split("/")) for v in original.violations   # a listed joint
              if v.kind == "disconnected" and "/" in v.where}             # that is open too
    new = sorted((face, edge) for face, edge, _ in after - before
                 if (face, edge) not in closing and frozenset((face, edge)) not in listed
                 and (face, edge) not in cut_in)
    if new:
        return f"planks {new[0][0]}/{new[0][1]} would touch and form a new joint"
    # which planks stand on the ground and lean on which wall (anchors: design_problem);
    # a plank that misses the ground narrowly may come to stand on it, and with ``stand``
    # any plank
    held_before = {_support(c) for c in original.contacts if c.anchor is None}
    held_after = {_support(c) for c in geometry.contacts if c.anchor is None}
    changed = sorted((held_before ^ held_after)
                     - {(plank, None, None) for plank, *_ in held_after
                        if (plank,) in closing or stand}
                     - {(plank, None, on) for plank, _, on in held_after    # a listed
                        if on is not None and frozenset((plank, on)) in listed},  # rest,
                     # apart as drawn, that the edit closes
                     key=lambda key: (key[0], -1 if key[1] is None else key[1], key[2] or ""))
    if changed:
        plank, wall, on = changed[0]
        support = on if on is not None else "the ground" if wall is None else f"wall {wall}"
        leaves = changed[0] in held_before
        verb = ("leave" if leaves else "touch") if on is None else \
            ("lift off" if leaves else "come to rest on")
        return f"{plank} would {verb} {support}"
    return None


def _support(contact) -> tuple:
    """(plank, wall, the plank it rests on): what holds a plank at a contact."""
    return contact.plank, contact.wall, contact.on
