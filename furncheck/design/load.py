"""Design files (YAML or JSON, contract section 1) -> a checked, frozen ``Design`` in SI.

Reading goes in three steps:

1. bytes -> text (``load_design``): the file must exist, be a regular file of at most
   ``MAX_FILE_BYTES``, hold no NUL bytes and be UTF-8;
2. text -> a plain tree of dicts, lists and scalars, with the line of every key path;
3. tree -> ``Design`` (``_design`` and the helpers below it, key by key as in the contract),
   converting lengths to metres.

Steps 1 and 2 are in ``furncheck.design.source`` (which refuses YAML aliases before anything
is expanded and duplicate keys, and keeps YAML scalars as ``_Scalar`` until the schema knows
whether a number or a text belongs there); ``furncheck.design.values`` reads typed values
from the tree (``_Doc``) and the quantities in SI; this module is step 3, the schema, with
the loads and load cases (``include``) in ``furncheck.design.cases`` and the top-level and
per-plank ``material`` in ``furncheck.design.materials``.

Every problem raises ``DesignError(file, key path, line, message)``.  Key paths read
``planks[1].size``, ``load_cases.sit[0].mass``; '' is the whole file.  For JSON, the line of
a key path is looked up only when an error is raised (by reading the text as YAML).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from furncheck import tolerances as tol
from furncheck.design.cases import load_cases
from furncheck.design.json_source import _read_json
from furncheck.design.materials import design_material, plank_material
from furncheck.design.model import Design, JointSpec, Material, Plank
from furncheck.design.source import (
    _NO_DOCUMENT,
    FORMATS,  # noqa: F401  (re-exported: still importable from here)
    _check_regular_file,
    _checked_text,
    _decode,
    _format_of,
    _one_line,
    _quote,
    _read_yaml,
    _too_large,
)
from furncheck.design.values import (
    _IDENTIFIER,
    _describe,
    _Doc,
    _identifier,
    _length,
    _plank_ref,
    _point,
    _quantity,
    _resolved,
    _Units,
    _vector,
)
from furncheck.design.walls import anchors as read_anchors
from furncheck.design.walls import walls as read_walls
from furncheck.errors import DesignError
from furncheck.plain import closest, plain_number

UNIT_SCALES = {"mm": 0.001, "m": 1.0}
"""Length unit -> metres per unit."""

TOP_KEYS = ("furncheck", "name", "units", "model", "material", "planks", "joints", "loads",
            "load_cases", "safety_factor", "tolerance", "walls", "anchors")
SHAPING_KEYS = ("units", "material", "tolerance", "safety_factor", "walls", "planks")
"""Top-level keys whose value the checks of loads, joints and anchors use: a misspelt one
leaves its default, and what names planks is then left unchecked (``_Doc.unsure``)."""
PLANK_KEYS = ("id", "size", "center", "rotation", "thickness", "material")
JOINT_KEYS = ("planks", "nails", "type")
JOINT_TYPES = ("nailed", "rests")


# --- public -------------------------------------------------------------------------------------

def load_design(path: str) -> Design:
    """Read and check the design file at ``path`` (format from its extension).

    Raises ``DesignError`` (file = ``path`` as given) for a missing, unreadable, binary,
    empty, oversized or ill-formed file.
    """
    data, fmt = read_design_file(path)
    return parse_design(_decode(data, path), path, fmt)


def read_design_file(path: str) -> tuple[bytes, str]:
    """The bytes of the design file at ``path`` and its format ('yaml' or 'json', from its
    extension), not yet parsed (``parse_design_bytes`` does that, also elsewhere: a Dask
    worker).  Raises ``DesignError`` as ``load_design`` does for a missing, unreadable,
    special or oversized file or an unknown extension."""
    _check_regular_file(path)
    fmt = _format_of(path)
    return _read_bytes(path), fmt


def parse_design_bytes(data: bytes, source: str, fmt: str) -> Design:
    """``parse_design`` of a document's bytes that come from no file (standard input):
    refuses oversized, binary and non-UTF-8 data as ``load_design`` does."""
    if len(data) > tol.MAX_FILE_BYTES:
        raise _too_large(source, len(data))
    return parse_design(_decode(data, source), source, fmt)


def parse_design(text: str, source: str, fmt: str) -> Design:
    """Check the design document ``text`` ('yaml' or 'json'); ``source`` names it in errors
    and becomes ``Design.source``.  Returns the ``Design`` in SI units."""
    if fmt not in ("yaml", "json"):
        raise DesignError(source, "", None, f"unknown format {_quote(str(fmt))}; use yaml or json")
    text = _checked_text(text, source)
    if fmt == "yaml":
        tree, lines = _read_yaml(text, source)
        doc = _Doc(source, fmt, text, lines)
    else:
        tree = _read_json(text, source)
        doc = _Doc(source, fmt, text, None)
    return _design(doc, tree)


# --- step 1: the file's bytes (the rest of steps 1-2 is in source.py) ---------------------------

def _read_bytes(path: str) -> bytes:
    """The file's bytes, at most ``MAX_FILE_BYTES`` of them.  (Kept here, where the file is
    opened, so that a test can replace this module's ``open``.)"""
    try:
        with open(path, "rb") as handle:
            data = handle.read(tol.MAX_FILE_BYTES + 1)
    except OSError as error:
        raise DesignError(path, "", None, f"cannot read file: {error.strerror}") from None
    if len(data) > tol.MAX_FILE_BYTES:
        raise _too_large(path, len(data))
    return data


# --- step 3: tree -> Design ---------------------------------------------------------------------

def _design(doc: _Doc, tree: Any) -> Design:
    """The Design of a document; its parts read under ``_Doc.collect`` where they do not
    depend on each other, so that one run reports every problem: the top level's own
    keys and values, each plank, the walls, then (what names planks) the joints, anchors
    and load cases, a part that names a plank which could not be read left unchecked."""
    try:
        return _read_design(doc, tree)
    except DesignError as error:            # one that stops the reading: after the others
        if error not in doc.problems:
            doc.problems.extend((error, *error.more))
        doc.raise_problems()
        raise


def _read_design(doc: _Doc, tree: Any) -> Design:
    top = _top_level(doc, tree)
    if any(closest(key, TOP_KEYS) in SHAPING_KEYS for key in tree if key not in TOP_KEYS):
        doc.unsure()                # a misspelt tolerance, material, ...: its default stands
    units = _units(doc, top)
    before = len(doc.problems)
    tolerance = doc.collect(_tolerance, doc, top, units, default=tol.DEFAULT_TOLERANCE)
    material = doc.collect(design_material, doc, top, units, default=Material())
    safety_factor = doc.collect(_safety_factor, doc, top, default=tol.DEFAULT_SAFETY_FACTOR)
    if len(doc.problems) > before:
        doc.unsure()                # what the planks' checks use is a default, not the file's
    name = doc.collect(_name, doc, top, default="design")
    model = doc.collect(_model, doc, top, default=tol.DEFAULT_MODEL)
    planks = _planks(doc, top["planks"], material, units)
    by_id = {plank.id: plank for plank in planks}
    walls = doc.collect(read_walls, doc, top["walls"], units, default=None) \
        if "walls" in top else ()
    joints = doc.collect(_joints, doc, top["joints"], by_id) if "joints" in top else None
    anchors = doc.collect(read_anchors, doc, top["anchors"], by_id, walls, units, tolerance,
                          default=()) if "anchors" in top and walls is not None else ()
    cases = doc.collect(load_cases, doc, top, by_id, units, tolerance)
    doc.raise_problems()
    return Design(
        name=name,
        planks=planks,
        load_cases=cases,
        material=material,
        joints=joints,
        safety_factor=safety_factor,
        tolerance=tolerance,
        units=units.name,
        unit_scale=units.scale,
        source=doc.source,
        model=model,
        walls=walls,
        anchors=anchors,
        lines=doc.design_lines(),
    )


def _tolerance(doc: _Doc, top: dict, units: _Units) -> float:
    if "tolerance" not in top:
        return tol.DEFAULT_TOLERANCE
    return _quantity(doc, top["tolerance"], "tolerance", 0.0, tol.MAX_LENGTH, units.scale,
                     units.name)


def _safety_factor(doc: _Doc, top: dict) -> float:
    if "safety_factor" not in top:
        return tol.DEFAULT_SAFETY_FACTOR
    return _quantity(doc, top["safety_factor"], "safety_factor", tol.MIN_SAFETY_FACTOR,
                     tol.MAX_SAFETY_FACTOR, positive=True)


def _top_level(doc: _Doc, tree: Any) -> dict:
    """The top mapping, its format version checked before its keys (a newer version may
    have keys this one does not know)."""
    if tree is _NO_DOCUMENT:
        doc.fail("", "empty file")
    if not isinstance(tree, dict):
        doc.fail("", f"the top level must be a mapping, got {_describe(tree)}")
    if "furncheck" not in tree:
        doc.fail("furncheck", 'missing required key "furncheck" (the format version: '
                              "write furncheck: 1)")
    version = doc.number(tree["furncheck"], "furncheck")
    if version != 1:
        doc.fail("furncheck", f"unsupported format version {plain_number(version, 6)}; this "
                              "furncheck reads "
                              "version 1")
    return doc.mapping(tree, "", TOP_KEYS, required=("planks",), keep_going=True)


def _name(doc: _Doc, top: dict) -> str:
    """The ``name`` key, or without one the file's stem, what is not printable in it (a
    byte that is not UTF-8, held as a surrogate; a line break) escaped ('bad\\udcffname'):
    a name is written into suggestion files and pages, which a surrogate failed."""
    if "name" not in top:
        return _one_line(Path(doc.source).stem) or "design"
    name = doc.text(top["name"], "name")
    if not name.strip() or not name.isprintable():
        doc.fail("name", "must be printable text on one line")
    return name


def _units(doc: _Doc, top: dict) -> _Units:
    name = doc.text(top["units"], "units") if "units" in top else "mm"
    if name not in UNIT_SCALES:
        doc.fail("units", f"unknown unit {_quote(name)}; use mm or m")
    return _Units(name, UNIT_SCALES[name])


def _model(doc: _Doc, top: dict) -> str:
    if "model" not in top:
        return tol.DEFAULT_MODEL
    name = doc.text(top["model"], "model")
    if name not in tol.MODELS:
        doc.fail("model", f"unknown model {_quote(name)}; use elastic or rigid")
    return name


def _planks(doc: _Doc, node: Any, material: Material, units: _Units) -> tuple[Plank, ...]:
    items = doc.sequence(node, "planks")
    if not items:
        doc.fail("planks", "a design needs at least one plank")
    first_index: dict[str, int] = {}
    planks = []
    for index, item in enumerate(items):
        key = f"planks[{index}]"
        before = len(doc.problems)
        plank = doc.collect(_plank, doc, item, key, material, units)
        if plank is None or len(doc.problems) > before:     # its problems kept (an unknown
            named = _resolved(item.get("id")) if isinstance(item, dict) else None   # key
            if isinstance(named, str) and _IDENTIFIER.fullmatch(named):     # too: a field
                doc.unsure(named)       # misspelt), what names it is left unchecked
            else:                       # which names are its is not known: none are checked
                doc.unsure()
            continue
        if plank.id in first_index:
            doc.problems.append(doc.error(f"{key}.id", f"duplicate plank id {_quote(plank.id)} "
                                          f"(planks[{first_index[plank.id]}] and {key})"))
            doc.unsure(plank.id)        # which of them a load means is not known
            continue
        first_index[plank.id] = index
        planks.append(plank)
    return tuple(plank for plank in planks if plank.id not in doc.unread_planks)


def _plank(doc: _Doc, node: Any, key: str, material: Material, units: _Units) -> Plank:
    fields = doc.mapping(node, key, PLANK_KEYS, required=("id", "size", "center"),
                         keep_going=True)
    plank_id = _identifier(doc, fields["id"], f"{key}.id", "plank id")
    length, width = _vector(doc, fields["size"], f"{key}.size", 2, tol.MIN_LENGTH,
                            tol.MAX_LENGTH, units.scale, units.name, positive=True)
    own = (plank_material(doc, fields["material"], f"{key}.material", units)
           if "material" in fields else {})
    thickness = own.pop("thickness", None)
    if "thickness" in fields:
        given = _length(doc, fields["thickness"], f"{key}.thickness", units)
        if thickness is not None and thickness != given:
            doc.fail(f"{key}.material.thickness",
                     f"thickness {plain_number(thickness / units.scale, 6)} {units.name} differs "
                     "from the "
                     f"plank's thickness: {plain_number(given / units.scale, 6)} {units.name}; "
                     "give it once")
        thickness = given
    rotation = (_vector(doc, fields["rotation"], f"{key}.rotation", 3, -tol.MAX_ROTATION_DEG,
                        tol.MAX_ROTATION_DEG, unit="degrees")
                if "rotation" in fields else (0.0, 0.0, 0.0))
    center = _point(doc, fields["center"], f"{key}.center", units)
    return Plank(plank_id, length, width, material.thickness if thickness is None else thickness,
                 center, rotation, tuple(own.items()))


# --- joints -------------------------------------------------------------------------------------

def _joints(doc: _Doc, node: Any, by_id: dict[str, Plank]) -> tuple[JointSpec, ...] | None:
    """None for ``auto`` (detected from geometry), else the listed joints (each read on
    its own: ``_Doc.collect``)."""
    if isinstance(_resolved(node), str) and doc.text(node, "joints") == "auto":
        return None
    if not isinstance(node, list):
        doc.fail("joints", f'expected "auto" or a list of joints, got {_describe(node)}')
    first_index: dict[frozenset, int] = {}
    joints = []
    for index, item in enumerate(node):
        key = f"joints[{index}]"
        joint = doc.collect(_joint, doc, item, key, by_id)
        if joint is None:
            continue
        pair = frozenset(joint.planks)
        if pair in first_index:
            doc.problems.append(doc.error(key, f"joint {'/'.join(joint.planks)} is listed "
                                               f"twice (joints[{first_index[pair]}] and {key})"))
            continue
        first_index[pair] = index
        joints.append(joint)
    return tuple(joints)


def _joint(doc: _Doc, node: Any, key: str, by_id: dict[str, Plank]) -> JointSpec:
    """``[a, b]`` or ``{planks: [a, b], nails: n, type: nailed | rests}``."""
    nails, rests = None, False
    if isinstance(node, dict):
        fields = doc.mapping(node, key, JOINT_KEYS, required=("planks",))
        pair_key, pair_node = f"{key}.planks", fields["planks"]
        if "type" in fields:
            kind = doc.text(fields["type"], f"{key}.type")
            if kind not in JOINT_TYPES:
                doc.fail(f"{key}.type", f"unknown joint type {_quote(kind)}; use nailed or "
                                        "rests")
            rests = kind == "rests"
        if "nails" in fields:
            if rests:
                doc.fail(f"{key}.nails", "a joint of type rests has no nails")
            nails = _nail_count(doc, fields["nails"], f"{key}.nails")
    elif isinstance(node, list):
        pair_key, pair_node = key, node
    else:
        doc.fail(key, f"expected [plank, plank] or {{planks: [plank, plank], nails: n}}, "
                      f"got {_describe(node)}")
    items = doc.sequence(pair_node, pair_key)
    if len(items) != 2:
        doc.fail(pair_key, f"expected 2 plank ids, got {len(items)}")
    first, second = (_plank_ref(doc, item, f"{pair_key}[{i}]", by_id).id
                     for i, item in enumerate(items))
    if first == second:
        doc.fail(key, f"a joint needs two different planks, got {_quote(first)} twice")
    return JointSpec((first, second), nails, rests)


def _nail_count(doc: _Doc, node: Any, key: str) -> int:
    value = doc.number(node, key)
    if not value.is_integer() or not 1 <= value <= tol.MAX_NAILS:
        doc.fail(key, f"must be a whole number of nails from 1 to "
                      f"{plain_number(tol.MAX_NAILS, 6)}, got {plain_number(value, 6)}")
    return int(value)


