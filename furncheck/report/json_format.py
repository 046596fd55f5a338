"""``--format json``: exactly the schema of contract section 4.

Keys are written in the contract's order; floats are rounded by ``numbers.json_ready``
(REPORT_SIGNIFICANT_DIGITS significant digits, -0.0 as 0.0, nan/inf as null), so the same
batch always gives byte-identical text.  (The module is not called ``json.py`` so that it
does not shadow the standard library for tools that run from this folder.)

The text is what ``json.dumps(json_ready(document), indent=2)`` writes for the document
of ``report_dict``s, but written straight from the result values by a writer that knows
the schema (``piece``): ``json.dumps`` with an indent runs in pure Python and, with the
rounding of every number through ``json_ready``, took 3.4 ms per design of the generated
catalog (``benchmarks/catalog.py``; a third of checking it), the writer about 0.9 ms.
Each design's entry is one ``piece``, made where the design was checked, and ``document``
writes the entries as they come.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Iterable, Iterator, Sequence
from json.encoder import encode_basestring_ascii
from typing import Any

from furncheck.files import readable
from furncheck.report.entries import Entry, Summary, is_text
from furncheck.report.numbers import json_ready, real_text
from furncheck.result import (
    AnchorResult,
    BatchReport,
    CaseResult,
    ContactResult,
    DesignReport,
    JointResult,
    LoadResult,
    PlankResult,
    Violation,
)


def _string(text: str) -> str:
    """A string as ``json.dumps(json_ready(text))`` writes it (``readable``)."""
    return encode_basestring_ascii(readable(text))


_STEP = "  "
_ENTRY_INDENT = 2 * _STEP          # a design's entry is an item of the "reports" list


def render(batch: BatchReport) -> str:
    """The batch as a JSON document: ``{"reports": [...], "summary": {...}}``, indent 2."""
    return "".join(document(Entry.of(report, piece(report)) for report in batch.reports))


def document(entries: Iterable[Entry]) -> Iterator[str]:
    """The document of ``entries`` (their pieces in order), written as they come."""
    summary = Summary()
    yield '{\n  "reports": ['
    for entry in entries:
        yield (",\n" if summary.designs else "\n") + summary.add(entry).piece
    yield ("\n  ]" if summary.designs else "]") + ',\n  "summary": ' \
        + _object([(key, str(count)) for key, count in summary.as_dict().items()], _STEP) \
        + "\n}\n"


is_piece = is_text
"""Whether a value is shaped as ``piece`` returns it (a cached piece is checked)."""


def piece(report: DesignReport) -> str:
    """The design's entry, indented as an item of the document's "reports" list (no line
    end after it): ``json.dumps`` of its ``report_dict``, to the byte."""
    return _ENTRY_INDENT + _report_text(report, _ENTRY_INDENT)


def report_dict(report: DesignReport) -> dict[str, Any]:
    """One design's entry; an errored input has ``error`` (its first problem) and no
    ``valid``, and ``errors`` (every problem, one line each) where it has several."""
    if report.error is not None:
        entry = {"design": report.design, "name": report.name, "error": report.error}
        if report.more_errors:
            entry["errors"] = list(report.errors)
        return entry
    return {
        "design": report.design,
        "name": report.name,
        "valid": report.valid,
        "violations": [
            {"kind": v.kind, "where": v.where, "case": v.case, "message": v.message}
            for v in report.violations
        ],
        "cases": [_case_dict(case) for case in report.cases],
    }


def _case_dict(case: CaseResult) -> dict[str, Any]:
    """A case; ``planks`` (sag and stress) only in the elastic model."""
    entry = {
        "name": case.name,
        "durable": case.durable,
        "stable": case.stable,
        "joints": [_joint_dict(joint) for joint in case.joints],
        "contacts": [_contact_dict(contact) for contact in case.contacts],
        "loads": [_load_dict(load) for load in case.loads],
    }
    if case.planks is not None:
        entry["planks"] = [_plank_dict(plank) for plank in case.planks]
    if case.anchors:
        entry["anchors"] = [{"plank": a.plank, "wall": a.wall, "point": list(a.point),
                             "force": list(a.force), "capacity": a.capacity,
                             "utilization": a.utilization} for a in case.anchors]
    return entry


def _load_dict(load: LoadResult) -> dict[str, Any]:
    """``{"plank", "mass" | "force", "at", "spread"?, "from"?}``: what the file says of the
    load (mass kg or force N, world frame; ``at`` in the design's unit, null at the plank
    centre); ``spread`` only when true, ``from`` only for a load of an included case."""
    entry: dict[str, Any] = {"plank": load.plank}
    if load.mass is not None:
        entry["mass"] = load.mass
    else:
        entry["force"] = list(load.force)
    entry["at"] = None if load.at is None else list(load.at)
    if load.spread:
        entry["spread"] = True
    if load.origin is not None:
        entry["from"] = load.origin
    return entry


def _plank_dict(plank: PlankResult) -> dict[str, Any]:
    return {"id": plank.id, "sag": plank.sag, "sag_allowed": plank.sag_allowed,
            "stress": plank.stress, "strength": plank.strength,
            "utilization": plank.utilization}


def _joint_dict(joint: JointResult) -> dict[str, Any]:
    return {
        "planks": list(joint.planks),
        "point": list(joint.point),
        "nails": joint.nails,
        "force": list(joint.force),
        "moment": list(joint.moment),
        "pull": joint.pull,
        "shear": joint.shear,
        "pull_capacity": joint.pull_capacity,
        "shear_capacity": joint.shear_capacity,
        "utilization": joint.utilization,
        "durable": joint.durable,
    }


def _contact_dict(contact: ContactResult) -> dict[str, Any]:
    entry = {"plank": contact.plank, "point": list(contact.point), "force": list(contact.force)}
    if contact.wall is not None:
        entry["wall"] = contact.wall
    if contact.on is not None:
        entry["on"] = contact.on
    return entry


# --- the writer: each function gives the JSON text of a value whose first line is already
# --- started (after a key or an item's indent) and whose last line is at ``indent``

def _object(pairs: Sequence[tuple[str, str]], indent: str) -> str:
    """``{"key": value, ...}`` from (key, value's text) pairs (keys: plain ASCII)."""
    if not pairs:
        return "{}"
    inner = "\n" + indent + _STEP
    return "{" + inner + ("," + inner).join(f'"{key}": {text}' for key, text in pairs) \
        + "\n" + indent + "}"


def _array(items: Sequence[str], indent: str) -> str:
    """``[item, ...]`` from the items' texts (each made at ``indent + _STEP``)."""
    if not items:
        return "[]"
    inner = "\n" + indent + _STEP
    return "[" + inner + ("," + inner).join(items) + "\n" + indent + "]"


def _values(values: Iterable[Any], indent: str) -> str:
    """A list of numbers or strings (a point, a force, a joint's planks)."""
    return _array([_value(value) for value in values], indent)


_REAL_TEXTS: dict[float, str] = {}
_REAL_TEXTS_MAX = 1 << 16
"""Texts of finite floats already written (joint capacities, zeros and repeated loads
recur), up to this many; +0.0 and -0.0 share one, as both are written 0.0."""


def _value(value: Any) -> str:
    """A scalar as ``json.dumps(json_ready(value))`` writes it: floats (numpy's too)
    rounded by ``round_significant`` (nan and inf: null), ints, bools, None and strings as
    they are."""
    kind = type(value)
    if kind is float or isinstance(value, float):
        text = _REAL_TEXTS.get(value)
        if text is None:
            text = real_text(float(value))
            if len(_REAL_TEXTS) < _REAL_TEXTS_MAX and text != "null":
                _REAL_TEXTS[float(value)] = text
        return text
    if kind is str:
        return _string(value)
    if kind is bool:
        return "true" if value else "false"
    if kind is int:
        return int.__repr__(value)
    if value is None:
        return "null"
    return json.dumps(json_ready(value), allow_nan=False)   # numpy scalars and the like


def _report_text(report: DesignReport, indent: str) -> str:
    if report.error is not None:
        pairs = [("design", _string(report.design)), ("name", _string(report.name)),
                 ("error", _string(report.error))]
        if report.more_errors:
            pairs.append(("errors", _array([_string(p) for p in report.errors],
                                           indent + _STEP)))
        return _object(pairs, indent)
    inner = indent + _STEP
    return _object([
        ("design", _string(report.design)),
        ("name", _string(report.name)),
        ("valid", _value(report.valid)),
        ("violations", _array([_violation_text(v, inner + _STEP)
                               for v in report.violations], inner)),
        ("cases", _array([_case_text(case, inner + _STEP) for case in report.cases], inner)),
    ], indent)


def _record(layout: tuple[tuple[str, int | None], ...], values: Iterable[Any],
            indent: str) -> str:
    """An object of scalars and lists of scalars: ``layout`` gives its keys in order, each
    with None for a scalar or the length of a list, and ``values`` the scalars in order
    (a list's items in place)."""
    return _template(layout, indent) % tuple(map(_value, values))


@functools.lru_cache(maxsize=256)
def _template(layout: tuple[tuple[str, int | None], ...], indent: str) -> str:
    """The text of a ``_record`` with ``%s`` for every scalar (the writer's own text holds
    no ``%``: its keys are plain words)."""
    inner = indent + _STEP
    return _object([(key, "%s" if length is None else _array(["%s"] * length, inner))
                    for key, length in layout], indent)


def _violation_text(violation: Violation, indent: str) -> str:
    return _record((("kind", None), ("where", None), ("case", None), ("message", None)),
                   (violation.kind, violation.where, violation.case, violation.message),
                   indent)


def _case_text(case: CaseResult, indent: str) -> str:
    inner = indent + _STEP
    item = inner + _STEP
    pairs = [
        ("name", _value(case.name)),
        ("durable", _value(case.durable)),
        ("stable", _value(case.stable)),
        ("joints", _array([_joint_text(joint, item) for joint in case.joints], inner)),
        ("contacts", _array([_contact_text(contact, item) for contact in case.contacts],
                            inner)),
        ("loads", _array([_load_text(load, item) for load in case.loads], inner)),
    ]
    if case.planks is not None:
        pairs.append(("planks", _array([_plank_text(plank, item) for plank in case.planks],
                                       inner)))
    if case.anchors:
        pairs.append(("anchors", _array([_anchor_text(anchor, item)
                                         for anchor in case.anchors], inner)))
    return _object(pairs, indent)


def _joint_text(joint: JointResult, indent: str) -> str:
    return _record((("planks", len(joint.planks)), ("point", len(joint.point)),
                    ("nails", None), ("force", len(joint.force)),
                    ("moment", len(joint.moment)), ("pull", None), ("shear", None),
                    ("pull_capacity", None), ("shear_capacity", None), ("utilization", None),
                    ("durable", None)),
                   (*joint.planks, *joint.point, joint.nails, *joint.force, *joint.moment,
                    joint.pull, joint.shear, joint.pull_capacity, joint.shear_capacity,
                    joint.utilization, joint.durable), indent)


def _contact_text(contact: ContactResult, indent: str) -> str:
    layout = [("plank", None), ("point", len(contact.point)), ("force", len(contact.force))]
    values = [contact.plank, *contact.point, *contact.force]
    if contact.wall is not None:
        layout.append(("wall", None))
        values.append(contact.wall)
    if contact.on is not None:
        layout.append(("on", None))
        values.append(contact.on)
    return _record(tuple(layout), values, indent)


def _load_text(load: LoadResult, indent: str) -> str:
    layout: list[tuple[str, int | None]] = [("plank", None)]
    values = [load.plank]
    if load.mass is not None:
        layout.append(("mass", None))
        values.append(load.mass)
    else:
        layout.append(("force", len(load.force)))
        values.extend(load.force)
    if load.at is None:
        layout.append(("at", None))
        values.append(None)
    else:
        layout.append(("at", len(load.at)))
        values.extend(load.at)
    if load.spread:
        layout.append(("spread", None))
        values.append(True)
    if load.origin is not None:
        layout.append(("from", None))
        values.append(load.origin)
    return _record(tuple(layout), values, indent)


def _plank_text(plank: PlankResult, indent: str) -> str:
    return _record((("id", None), ("sag", None), ("sag_allowed", None), ("stress", None),
                    ("strength", None), ("utilization", None)),
                   (plank.id, plank.sag, plank.sag_allowed, plank.stress, plank.strength,
                    plank.utilization), indent)


def _anchor_text(anchor: AnchorResult, indent: str) -> str:
    return _record((("plank", None), ("wall", None), ("point", len(anchor.point)),
                    ("force", len(anchor.force)), ("capacity", None), ("utilization", None)),
                   (anchor.plank, anchor.wall, *anchor.point, *anchor.force, anchor.capacity,
                    anchor.utilization), indent)
