"""A ``Design`` -> a design document (plain dicts and lists) -> a YAML or JSON file.

The inverse of ``load``: lengths go back to the design's unit, masses are written as masses,
listed joints are kept and ``joints`` is left out when they are detected from geometry, a
load case keeps its ``include`` and writes only its own loads, so that ``parse_design`` of
the written text equals the design up to float round-off.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import yaml

from furncheck.design.materials import MATERIAL_KEYS, material_entry
from furncheck.design.model import Anchor, Design, JointSpec, Load, LoadCase, Plank
from furncheck.errors import DesignError

_Dumper = getattr(yaml, "CSafeDumper", yaml.SafeDumper)
_FORMATS = {".yaml": "yaml", ".yml": "yaml", ".json": "json"}
_SIGNIFICANT_DIGITS = 12
"""Digits kept when a length is converted back to the file unit, so 0.012 m is written
12.0 mm and not 11.999999999999998 mm.  Far below any physical meaning, far above the
loader's round-off."""


def design_to_document(design: Design) -> dict[str, Any]:
    """The design as a document in contract order (plain Python types, file units)."""
    scale = design.unit_scale
    doc: dict[str, Any] = {
        "furncheck": 1,
        "name": design.name,
        "units": design.units,
        "model": design.model,
        "material": _material_entry(design),
        "planks": [plank_entry(plank, design) for plank in design.planks],
    }
    if design.joints is not None:
        doc["joints"] = [_joint_entry(joint) for joint in design.joints]
    cases = list(design.load_cases)
    if cases and cases[0].name == "default" and not cases[0].includes:
        default = cases.pop(0)
        if default.loads or cases:
            doc["loads"] = _load_entries(default, scale)
    if cases:
        doc["load_cases"] = {case.name: _case_entry(case, scale) for case in cases}
    if design.walls:
        doc["walls"] = [{"point": _vector_in_unit(wall.point, scale),
                         "normal": [float(v) for v in wall.normal]} for wall in design.walls]
    if design.anchors:
        doc["anchors"] = [anchor_entry(anchor, design) for anchor in design.anchors]
    doc["safety_factor"] = design.safety_factor
    doc["tolerance"] = in_unit(design.tolerance, scale)
    return doc


def _material_entry(design: Design) -> dict[str, Any]:
    """Every material key, in file units (lengths in the design's unit, moduli N/mm^2,
    nail stiffnesses N/mm), so that the file says the model it was checked in."""
    material = design.material
    return material_entry({name: getattr(material, name) for name in MATERIAL_KEYS},
                          design.unit_scale)


def design_text(design: Design, fmt: str) -> str:
    """The design file's text: ``fmt`` 'yaml' or 'json'."""
    doc = design_to_document(design)
    if fmt == "json":
        import json  # for JSON files only: keeps ``import furncheck.design`` light

        return json.dumps(doc, indent=2, ensure_ascii=False) + "\n"
    return yaml.dump(doc, Dumper=_Dumper, sort_keys=False, default_flow_style=None,
                     allow_unicode=True, width=100)


def write_design(design: Design, path: str) -> None:
    """Write ``design`` to ``path`` as YAML (.yaml, .yml) or JSON (.json), UTF-8."""
    fmt = _FORMATS.get(Path(path).suffix.lower())
    if fmt is None:
        raise DesignError(path, "", None, f"unknown file type {Path(path).suffix!r}; "
                                          "design files end in .yaml, .yml or .json")
    Path(path).write_text(design_text(design, fmt), encoding="utf-8")


def in_unit(metres: float, scale: float) -> float:
    """A length (m) in the file unit (``scale`` m each), rounded to 12 significant digits
    (as a design file writes a length; the cut list reads its values the same way)."""
    return _rounded(metres / scale)


def _rounded(value: float) -> float:
    """``value`` to 12 significant digits (a unit conversion's round-off dropped)."""
    return float(f"{value:.{_SIGNIFICANT_DIGITS}g}")


def _vector_in_unit(metres, scale: float) -> list[float]:
    return _vector_rounded([float(v) / scale for v in metres])


def _vector_rounded(values: list[float]) -> list[float]:
    """A point, size or turn: each component to 12 significant digits of the largest (a
    centre at x = 1.3e-15 mm beside z = 456 mm is the round-off of 0: written 0)."""
    largest = max((abs(v) for v in values), default=0.0)
    if largest == 0.0:
        return [0.0 for _ in values]
    decimals = _SIGNIFICANT_DIGITS - 1 - math.floor(math.log10(largest))
    return [_rounded(round(v, decimals) + 0.0) for v in values]


def anchor_entry(anchor: Anchor, design: Design) -> dict[str, Any]:
    """An anchor as the design file writes it (its point in file units)."""
    return {"plank": anchor.plank, "at": _vector_in_unit(anchor.point, design.unit_scale),
            "wall": anchor.wall, "capacity": float(anchor.capacity)}


def plank_entry(plank: Plank, design: Design) -> dict[str, Any]:
    """A plank as the design file writes it (file units; thickness only when it is not
    the material's; its own material values when it has any)."""
    scale = design.unit_scale
    entry: dict[str, Any] = {
        "id": plank.id,
        "size": _vector_in_unit((plank.length, plank.width), scale),
        "center": _vector_in_unit(plank.center, scale),
        "rotation": _vector_rounded([float(v) for v in plank.rotation]),
    }
    if plank.thickness != design.material.thickness:
        entry["thickness"] = in_unit(plank.thickness, scale)
    if plank.material:
        entry["material"] = material_entry(dict(plank.material), scale)
    return entry


def _joint_entry(joint: JointSpec) -> list[str] | dict[str, Any]:
    if joint.rests:
        return {"planks": list(joint.planks), "type": "rests"}
    if joint.nails is None:
        return list(joint.planks)
    return {"planks": list(joint.planks), "nails": int(joint.nails)}


def _load_entries(case: LoadCase, scale: float) -> list[dict[str, Any]]:
    """The case's own loads (those it includes are written in their own cases)."""
    return [_load_entry(load, scale) for load in case.own_loads]


def _case_entry(case: LoadCase, scale: float) -> list[dict[str, Any]] | dict[str, Any]:
    """A list of loads, or ``{include: [...], loads: [...]}`` when the case includes
    others (``loads`` left out when it has none of its own)."""
    if not case.includes:
        return _load_entries(case, scale)
    entry: dict[str, Any] = {"include": list(case.includes)}
    if case.own_loads:
        entry["loads"] = _load_entries(case, scale)
    return entry


def _load_entry(load: Load, scale: float) -> dict[str, Any]:
    """``{plank, mass}`` when the file gave a mass, else ``{plank, force}`` (N); ``at`` in
    the file unit when the load has a point."""
    entry: dict[str, Any] = {"plank": load.plank}
    if load.mass is not None:
        entry["mass"] = float(load.mass)
    else:
        entry["force"] = [float(v) for v in load.force]
    if load.point is not None:
        entry["at"] = _vector_in_unit(load.point, scale)
    if load.spread:
        entry["spread"] = True
    return entry
