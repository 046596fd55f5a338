"""How two planks fail to meet, for the messages that say so: the gap or depth between an
end face and the face it faces (``end_gap``, ``end_depth``), an end bearing on too narrow
a band for nails (``end_bearing``), ends cut into neighbours' faces (``cut_ins``), planks
lying face to face; and the length, point and count phrases of geometry messages.
"""

from __future__ import annotations

import numpy as np

from furncheck.design.model import Design
from furncheck.geometry.boxes import meeting_pairs
from furncheck.geometry.faces import _bearing, _bears, _best_touches, _bounding_boxes, _Touch
from furncheck.geometry.model import _GEOMETRY_EPS, Geometry
from furncheck.geometry.near import near_band
from furncheck.plain import plain_length, plain_number


def end_bearing(design: Design, i: int, j: int) -> tuple[float, float] | None:
    """(the band's width m, the edge plank's thickness m) where an end face of one of
    planks i, j lies on the other's face within the tolerance but over a band too narrow
    for nails (``faces._bears``); None otherwise."""
    touch = _nearest_touch(design, i, j)
    if touch is None or _bears(touch) or abs(touch.gap) > design.tolerance + _GEOMETRY_EPS:
        return None
    return _bearing(touch), touch.edge.thickness


def end_gap(design: Design, i: int, j: int, signed: bool = False) -> float | None:
    """How far (m) the end face of one of planks i, j is from the broad face of the other
    that it faces (its gap, or its depth when it cuts in; with ``signed``, a depth is
    negative), None when neither plank's end faces the other: what keeps a listed joint
    from closing."""
    touch = _nearest_touch(design, i, j)
    if touch is None:
        return None
    return float(touch.gap) if signed else abs(float(touch.gap))


def _nearest_touch(design: Design, i: int, j: int) -> _Touch | None:
    return _best_touches(design.planks, np.array([[i, j]]), slack=np.inf,
                         keep_deep=False, bearing=0.0).get((i, j))


def _apart_message(design: Design, i: int, j: int) -> str:
    """Why two listed planks form no joint, with the gap between the end face and the face
    it should rest on when one faces the other."""
    touch = _nearest_touch(design, i, j)
    if touch is not None and touch.gap > 0:
        return (f"planks do not touch: the end of {touch.edge.id} is "
                f"{_fmt_len(touch.gap, design)} from the face of {touch.face.id} "
                f"(tolerance {_fmt_len(design.tolerance, design)})")
    a, b = design.planks[i], design.planks[j]
    flat = _lying_on(design, a, b) or _lying_on(design, b, a)
    if flat is not None:
        return (f"{flat[0]} lies flat on {flat[1]}, face to face: a joint is an end (a "
                f"narrow face) of one plank on a face of the other; faces lying on each "
                f"other are not modelled (stand the upper one on its edge, or leave the "
                f"joint out)")
    diff = a.corners[:, None, :] - b.corners[None, :, :]
    gap = float(np.sqrt((diff ** 2).sum(axis=2)).min())
    return (f"planks do not touch: no end face of one lies on a face of the other "
            f"(closest corners {_fmt_len(gap, design)} apart)")


FACE_TO_FACE_COSINE = 1.0 - 1e-6
"""Two planks whose face normals' cosine is at least this lie face to face (messages)."""


def _lying_on(design: Design, upper, lower) -> tuple[str, str] | None:
    """(upper id, lower id) when ``upper``'s broad face lies on ``lower``'s (parallel
    faces within the tolerance of each other, their outlines overlapping), else None."""
    normal = lower.rotation_matrix[:, 2]
    if abs(float(upper.rotation_matrix[:, 2] @ normal)) < FACE_TO_FACE_COSINE:
        return None
    lower_top = float(normal @ lower.center_array) + 0.5 * lower.thickness
    lower_bottom = lower_top - lower.thickness
    heights = upper.corners @ normal
    near_top = abs(float(heights.min()) - lower_top) <= design.tolerance
    near_bottom = abs(float(heights.max()) - lower_bottom) <= design.tolerance
    if not (near_top or near_bottom):
        return None
    local = (upper.corners - lower.center_array) @ lower.rotation_matrix[:, :2]
    half = 0.5 * np.array([lower.length, lower.width])
    overlaps = (local.min(axis=0) < half) & (local.max(axis=0) > -half)
    return (upper.id, lower.id) if bool(overlaps.all()) else None


def _cut_in_phrase(design: Design, index: int, neighbours: np.ndarray | None = None) -> str:
    """For a plank joined to nothing: '; its end cuts 15 mm into the face of side_l (and
    of side_r)' where its end faces sink into neighbours' faces deeper than a near miss
    (``cut_ins``), else ''."""
    deep = cut_ins(design, index, neighbours)
    if not deep:
        return ""
    depth, face = deep[0]
    rest = "".join(f" and of {design.planks[other].id}" for _, other in deep[1:])
    more = f" (and {len(deep) - 1} more)" if len(deep) > 3 else rest
    return (f"; its end cuts {_fmt_len(depth, design)} into the face of "
            f"{design.planks[face].id}{more}: shorten or move it to rest on "
            f"{'that face' if len(deep) == 1 else 'those faces'}")


def box_neighbours(design: Design) -> list[np.ndarray]:
    """Per plank, the other planks whose world boxes meet its own (``cut_ins``' candidates),
    found for all planks at once by sort and sweep (``boxes.meeting_pairs``)."""
    pairs = meeting_pairs(*_bounding_boxes(design.planks), 0.0)
    ends = np.concatenate([pairs, pairs[:, ::-1]])
    ends = ends[np.lexsort((ends[:, 1], ends[:, 0]))]
    cuts = np.searchsorted(ends[:, 0], np.arange(1, len(design.planks)))
    return np.split(ends[:, 1], cuts)


def cut_ins(design: Design, index: int,
            neighbours: np.ndarray | None = None) -> list[tuple[float, int]]:
    """(depth m, face plank index) of each neighbour whose broad face an end face of plank
    ``index`` sinks into deeper than a near miss, deepest first (then by the face's id):
    a board cut too long, the real reason a plank joined to nothing forms no joint.  Its
    own end faces only: where the neighbour's end also cuts into it (a seat's end into a
    leg that pokes up through the seat), the leg's end still counts.

    Only the neighbours whose boxes meet this plank's are measured (``neighbours``: their
    indices, ``box_neighbours``' entry for it, found here if not given): an end face sunk
    into a face lies over it and the plank runs on through its plane, so their boxes
    overlap.  Measuring every other plank made a design of a thousand planks joined to
    nothing take seconds (5,000 boards lying apart: 99 s), and so did finding each one's
    neighbours among all the others (a stack of 80,000 loose boards)."""
    others = np.asarray(box_neighbours(design)[index] if neighbours is None else neighbours,
                        dtype=int)
    if not len(others):
        return []
    pairs = np.column_stack([np.full(len(others), index), others])
    touches = _best_touches(design.planks, pairs, slack=np.inf, keep_deep=True, one_way=True,
                            bearing=0.0)
    _, band = near_band(design)
    deep = sorted((float(touch.gap), touch.face.id) for touch in touches.values()
                  if touch.gap < -band)
    return [(-gap, design.plank_index[face]) for gap, face in deep]


def cut_in_pairs(design: Design, geometry: Geometry,
                 among: set[str] | None = None) -> set[tuple[str, str]]:
    """(face, edge) plank ids of the joints that the planks joined to nothing (those of
    ``among``, where given) would form with the faces their ends cut into (``cut_ins``):
    the joints a repair that shortens or moves such a plank may add (as it may close a
    near miss), and the cut-ins that their violations' messages tell."""
    loose = [design.plank_index[violation.where] for violation in geometry.violations
             if violation.kind == "disconnected" and "/" not in violation.where
             and (among is None or violation.where in among)]
    neighbours = box_neighbours(design) if loose else []
    return {(design.planks[face].id, design.planks[index].id)
            for index in loose for _, face in cut_ins(design, index, neighbours[index])}


def end_depth(design: Design, face: int, edge: int) -> float | None:
    """How far (m) an end face of plank ``edge`` lies from the broad face of plank ``face``
    that it faces, above it (> 0) or sunk into it (< 0), however deep; None when no end
    of it faces that face."""
    touch = _best_touches(design.planks, np.array([[edge, face]]), slack=np.inf,
                          keep_deep=True, one_way=True, bearing=0.0).get((edge, face))
    return None if touch is None else float(touch.gap)


# --- formatting helpers for messages ----------------------------------------------------------

def _fmt_len(value_m: float, design: Design) -> str:
    return plain_length(value_m, design.unit_scale, design.units)


def _fmt_point(point_m: np.ndarray, design: Design) -> str:
    coords = ", ".join(plain_number(v / design.unit_scale) for v in point_m)
    return f"({coords}) {design.units}"


def _plural(n: int, word: str) -> str:
    return f"{n} {word}s" if n != 1 else f"1 {word}"
