"""Joints, ground contacts and connectivity of a design (contract section 2).

A nail joint joins an *edge plank* (one of its four narrow faces rests on the other plank)
to a *face plank* (its broad face receives the nails).  Everything here is SI (metres) and
works for arbitrary plank rotations: faces are handled as oriented rectangles, the touching
region is the edge face's projection clipped to the face plank's face.

The package, by job:

    model     Joint, Contact, NearMiss, Geometry (what the statics needs) and the
              numeric slack
    near      near misses: joints and ground contacts missed by a little (contract
              section 2), reported instead of left out
    faces     face tables of planks, touching regions of a narrow face on a broad face,
              bounding boxes and box overlaps
    analysis  analyze (joints detected or checked, ground contacts, components,
              violations), follow / follow_many (a structure's joints on edited designs),
              interpenetrations and the design's own (drawn_through)
    fit       how two planks fail to meet: gaps, depths, narrow bearings and cut-ins, and
              the phrases of the messages that say so
    edits     what decides whether an edit keeps the joints: many edits checked at
              once (EditedTables) and the edits' continuous margins (EditMargins,
              edit_margins_many)
    support   the support polygon on the floor: convex hull of the floor contacts and
              how far a point lies outside it
"""

from furncheck.geometry.analysis import (
    analyze,
    drawn_through,
    drawn_through_closing,
    follow,
    follow_many,
    interpenetrations,
    nail_count,
)
from furncheck.geometry.fit import (
    box_neighbours,
    cut_in_pairs,
    cut_ins,
    end_bearing,
    end_depth,
    end_gap,
)
from furncheck.geometry.model import Contact, Geometry, Joint, NearMiss

_EDITS = ("EditMargins", "EditedTables", "edit_margins_many")


def __getattr__(name: str):
    """The edits' names, imported on first use: a plain validate needs none of them."""
    if name in _EDITS:
        from furncheck.geometry import edits

        return getattr(edits, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["Contact", "EditMargins", "EditedTables", "Geometry", "Joint", "NearMiss", "analyze",
           "box_neighbours", "cut_in_pairs", "cut_ins", "drawn_through",
           "drawn_through_closing", "edit_margins_many",
           "end_bearing",
           "end_depth", "end_gap", "follow", "follow_many", "interpenetrations", "nail_count"]
