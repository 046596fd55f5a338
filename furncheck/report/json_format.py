"""``--format json``: exactly the schema of contract section 4.

Keys are written in the contract's order; floats are rounded by ``numbers.json_ready``
(REPORT_SIGNIFICANT_DIGITS significant digits, -0.0 as 0.0, nan/inf as null), so the same
batch always gives byte-identical text.  (The module is not called ``json.py`` so that it
does not shadow the standard library for tools that run from this folder.)
"""

from __future__ import annotations

import json
from typing import Any

from furncheck.report.numbers import json_ready
from furncheck.result import (
    BatchReport,
    CaseResult,
    ContactResult,
    DesignReport,
    JointResult,
    LoadResult,
    PlankResult,
)


def render(batch: BatchReport) -> str:
    """The batch as a JSON document: ``{"reports": [...], "summary": {...}}``, indent 2."""
    document = {
        "reports": [report_dict(report) for report in batch.reports],
        "summary": dict(batch.summary),
    }
    return json.dumps(json_ready(document), indent=2, allow_nan=False) + "\n"


def report_dict(report: DesignReport) -> dict[str, Any]:
    """One design's entry; an errored input has ``error`` and no ``valid``."""
    if report.error is not None:
        return {"design": report.design, "name": report.name, "error": report.error}
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
