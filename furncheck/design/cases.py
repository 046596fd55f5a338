"""Loads and load cases of a design file (contract section 1), part of step 3 of reading it.

``loads`` is the case named 'default'; ``load_cases`` adds named cases, each a list of loads
or ``{include: [case, ...], loads: [...]}``.  The loads of the included cases act too:

- includes are followed through (a includes b includes default);
- each case's loads act once however many include paths lead to it (a case that includes
  b and c, which both include default, holds default's loads once).  Two equal loads written
  in two different cases are two loads, and both act where both cases are included;
- the order is deterministic: the included cases' loads first, in include order (each
  included case's own includes before its own loads), then the case's own loads.

Self-weight is not a load of any case: it acts in every case (contract section 1).

Problems raise ``DesignError`` with key path and line, like the rest of the schema: an
unknown included case (with the close name), a circular include (naming the cycle), an
include that is not a list of case names, a case mapping with unknown keys or none.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Load, LoadCase, Plank
from furncheck.design.source import _child, _quote
from furncheck.design.values import (
    _describe,
    _did_you_mean,
    _Doc,
    _identifier,
    _plank_ref,
    _point,
    _quantity,
    _resolved,
    _Skipped,
    _Units,
    _vector,
)
from furncheck.plain import plain_number

CASE_KEYS = ("include", "loads")
LOAD_KEYS = ("plank", "mass", "force", "at", "spread")
DEFAULT_CASE = "default"

_AXES = ("length", "width", "thickness")


@dataclass(frozen=True)
class _WrittenCase:
    """A case as its file entry gives it, before includes are followed.

    key      : its key path ('loads' or 'load_cases.<name>')
    own      : the loads its entry lists
    includes : the case names of its ``include``, each with its key path
    """

    name: str
    key: str
    own: tuple[Load, ...]
    includes: tuple[tuple[str, str], ...] = ()


def load_cases(doc: _Doc, top: dict, by_id: dict[str, Plank], units: _Units,
               tolerance: float) -> tuple[LoadCase, ...]:
    """'default' (from ``loads``) first, then ``load_cases`` in file order, includes
    resolved; a lone self-weight case 'default' when the file gives neither."""
    written = []
    if "loads" in top:
        written.append(_WrittenCase(DEFAULT_CASE, "loads",
                                    _loads(doc, top["loads"], "loads", by_id, units, tolerance)))
    if "load_cases" in top:
        for name, node in doc.mapping(top["load_cases"], "load_cases").items():
            key = _child("load_cases", name)
            _identifier(doc, name, key, "load case name")
            if name == DEFAULT_CASE and "loads" in top:
                doc.fail(key, 'case "default" is already given by "loads"; rename this case '
                              'or move its loads there')
            case = doc.collect(_written_case, doc, name, node, key, by_id, units, tolerance)
            if case is None:            # its problems kept: what includes it is unchecked
                return None
            written.append(case)
    if not written:
        return (LoadCase(DEFAULT_CASE),)
    by_name = {case.name: case for case in written}
    for case in written:
        _check_included_names(doc, case, by_name, "loads" in top)
    _refuse_cycles(doc, written, by_name)
    return tuple(_resolved_case(case, by_name) for case in written)


def _written_case(doc: _Doc, name: str, node: Any, key: str, by_id: dict[str, Plank],
                  units: _Units, tolerance: float) -> _WrittenCase:
    """A list of loads, or ``{include: [case, ...], loads: [...]}`` (at least one key)."""
    if isinstance(node, list):
        return _WrittenCase(name, key, _loads(doc, node, key, by_id, units, tolerance))
    if not isinstance(node, dict):
        doc.fail(key, f"expected a list of loads or a mapping {{include: [case, ...], loads: "
                      f"[...]}}, got {_describe(node)}")
    fields = doc.mapping(node, key, CASE_KEYS)
    if not fields:
        doc.fail(key, "an empty load case mapping: give include (cases whose loads act too) "
                      "and/or loads (its own), or write [] for self-weight alone")
    own = (_loads(doc, fields["loads"], f"{key}.loads", by_id, units, tolerance)
           if "loads" in fields else ())
    includes = _include_names(doc, fields["include"], f"{key}.include") \
        if "include" in fields else ()
    return _WrittenCase(name, key, own, includes)


def _include_names(doc: _Doc, node: Any, key: str) -> tuple[tuple[str, str], ...]:
    """(name, key path) of each case an ``include`` list names, each once."""
    if not isinstance(node, list):
        written = _resolved(node)
        hint = f" (write include: [{written}])" if isinstance(written, str) else ""
        doc.fail(key, f"expected a list of load case names, got {_describe(node)}{hint}")
    names: dict[str, str] = {}
    for index, item in enumerate(node):
        item_key = f"{key}[{index}]"
        if isinstance(item, (dict, list)):
            doc.fail(item_key, f"expected a load case name, got {_describe(item)}")
        name = doc.text(item, item_key)
        if name in names:
            doc.fail(item_key, f"case {_quote(name)} is included twice ({names[name]} and "
                               f"{item_key})")
        names[name] = item_key
    return tuple(names.items())


def _check_included_names(doc: _Doc, case: _WrittenCase, by_name: dict[str, _WrittenCase],
                          has_default: bool) -> None:
    """Every included name is a case of the file."""
    for name, key in case.includes:
        if name in by_name:
            continue
        if name == DEFAULT_CASE and not has_default:
            doc.fail(key, 'unknown load case "default": the file has no top-level "loads"')
        doc.fail(key, f"unknown load case {_quote(name)}{_did_you_mean(name, by_name)}; "
                      f"cases: {', '.join(by_name)}")


def _refuse_cycles(doc: _Doc, written: list[_WrittenCase],
                   by_name: dict[str, _WrittenCase]) -> None:
    """A circular include is an error at the ``include`` of the case where the cycle is
    first met (cases in file order, includes in include order): ``a -> b -> a``.  (Depth
    first with a stack of its own: a long chain of includes is no recursion.)"""
    done: set[str] = set()
    for start in written:
        if start.name in done:
            continue
        path, on_path, pending = [start.name], {start.name}, [iter(start.includes)]
        while pending:
            step = next(pending[-1], None)
            if step is None:
                pending.pop()
                done.add(path[-1])
                on_path.discard(path.pop())
                continue
            name = step[0]
            if name in on_path:
                cycle = path[path.index(name):] + [name]
                doc.fail(f"{by_name[name].key}.include",
                         f"circular include {' -> '.join(cycle)}")
            if name not in done:
                path.append(name)
                on_path.add(name)
                pending.append(iter(by_name[name].includes))


def _included_order(case: _WrittenCase, by_name: dict[str, _WrittenCase]) -> list[str]:
    """The cases whose loads ``case`` includes, directly or not, each once, in the order
    their loads act: depth first in include order, a case after the cases it includes."""
    order: list[str] = []
    seen, names, pending = {case.name}, [], [iter(case.includes)]
    while pending:
        step = next(pending[-1], None)
        if step is None:
            pending.pop()
            if names:
                order.append(names.pop())
            continue
        name = step[0]
        if name not in seen:
            seen.add(name)
            names.append(name)
            pending.append(iter(by_name[name].includes))
    return order


def _resolved_case(case: _WrittenCase, by_name: dict[str, _WrittenCase]) -> LoadCase:
    """The case with the loads of every case it includes (``_included_order``), then its
    own; ``origins`` names the case each load is written in."""
    if not case.includes:
        return LoadCase(case.name, case.own)
    order = _included_order(case, by_name)
    loads = [load for name in order for load in by_name[name].own]
    origins = [name for name in order for _ in by_name[name].own]
    return LoadCase(case.name, (*loads, *case.own),
                    includes=tuple(name for name, _ in case.includes),
                    origins=(*origins, *(case.name for _ in case.own)))


# --- loads --------------------------------------------------------------------------------------

def _loads(doc: _Doc, node: Any, key: str, by_id: dict[str, Plank], units: _Units,
           tolerance: float) -> tuple[Load, ...]:
    items = doc.sequence(node, key)
    loads = [doc.collect(_load, doc, item, f"{key}[{i}]", by_id, units, tolerance)
             for i, item in enumerate(items)]           # each on its own (``_Doc.collect``)
    return tuple(load for load in loads if load is not None)


def _load(doc: _Doc, node: Any, key: str, by_id: dict[str, Plank], units: _Units,
          tolerance: float) -> Load:
    """``{plank, mass | force, at? | spread?}``: mass kg, force N, ``at`` a world point on
    the plank, ``spread: true`` the load spread evenly along the plank's length.  Its mass
    or force is read whether or not its plank can be (an unknown plank, or one left
    unchecked: ``_Doc.unsure``), so that a 'mass: 100kg' on a plank whose own line has a
    problem is not kept back until that is fixed; its point, which needs the plank, once
    both are read."""
    fields = doc.mapping(node, key, LOAD_KEYS, required=("plank",))
    spread = "spread" in fields and doc.flag(fields["spread"], f"{key}.spread")
    if spread and "at" in fields:
        doc.fail(f"{key}.at", "a spread load acts along the whole plank: give no point")
    if "mass" in fields and "force" in fields:
        doc.fail(key, "give either mass (kg) or force ([fx, fy, fz] N), not both")
    if "mass" not in fields and "force" not in fields:
        doc.fail(key, "a load needs a mass (kg) or a force ([fx, fy, fz] N)")
    plank = doc.collect(_plank_ref, doc, fields["plank"], f"{key}.plank", by_id)
    value = doc.collect(_load_value, doc, fields, key)
    if plank is None or value is None:  # their problems kept, or a plank left unchecked
        raise _Skipped(key)
    point = (_point_on_plank(doc, fields["at"], f"{key}.at", plank, units, tolerance)
             if "at" in fields else None)
    if "mass" in fields:
        return Load.of_mass(plank.id, value, point, spread)
    return Load(plank.id, value, point, spread=spread)


def _load_value(doc: _Doc, fields: dict, key: str) -> float | tuple[float, float, float]:
    """A load's mass (kg) or force (N, [fx, fy, fz])."""
    if "mass" in fields:
        return _quantity(doc, fields["mass"], f"{key}.mass", 0.0, tol.MAX_MASS, unit="kg")
    return _vector(doc, fields["force"], f"{key}.force", 3, -tol.MAX_FORCE, tol.MAX_FORCE,
                   unit="N")


def _point_on_plank(doc: _Doc, node: Any, key: str, plank: Plank, units: _Units,
                    tolerance: float) -> tuple[float, float, float]:
    """m: a world point that lies on ``plank`` within ``tolerance`` (m) on every local axis."""
    point = _point(doc, node, key, units)
    local = plank.to_local(np.asarray(point, dtype=float))
    outside = np.abs(local) - plank.half_extents
    axis = int(np.argmax(outside))
    if outside[axis] > tolerance + tol.ON_PLANK_EPS:
        shown = ", ".join(plain_number(c / units.scale, 6) for c in point)
        doc.fail(key, f"point ({shown}) is not on plank {_quote(plank.id)}: "
                      f"{plain_number(outside[axis] / units.scale)} {units.name} beyond its "
                      f"{_AXES[axis]} (tolerance {plain_number(tolerance / units.scale, 6)} "
                      f"{units.name})")
    return point
