"""Fuzzing the loader: whatever it is fed, ``parse_design`` (and ``load_design``) returns a
``Design`` or raises ``DesignError`` with a one-line message, never any other exception.

Inputs start from a valid design and are mutated (wrong types, stray keys, NaN and
infinities, huge and tiny numbers, deleted keys, random nesting), written as YAML or JSON;
also random text and random bytes.
"""

from __future__ import annotations

import json
import os
import tempfile

import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from furncheck import tolerances as tol
from furncheck.design import Design, design_to_document, load_design, parse_design
from furncheck.errors import DesignError

FUZZ = settings(deadline=None, max_examples=150, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

VALID = {
    "furncheck": 1,
    "name": "stool",
    "units": "mm",
    "material": {"thickness": 12, "density": 750, "nail_spacing": 20, "nail_pull": 700,
                 "nail_shear": 190, "friction": 0.5},
    "planks": [
        {"id": "seat", "size": [300, 300], "center": [0, 0, 406]},
        {"id": "leg1", "size": [400, 300], "center": [-144, 0, 200], "rotation": [0, 90, 0]},
        {"id": "leg2", "size": [400, 300], "center": [144, 0, 200], "rotation": [0, 90, 0],
         "thickness": 12},
    ],
    "joints": [["seat", "leg1"], {"planks": ["seat", "leg2"], "nails": 10}],
    "loads": [{"plank": "seat", "mass": 10},
              {"plank": "seat", "force": [10, 0, -50], "at": [0, 0, 412]}],
    "load_cases": {"sit": [{"plank": "seat", "mass": 80}], "empty": []},
    "safety_factor": 1.5,
    "tolerance": 0.5,
}

SPECIAL_NUMBERS = st.sampled_from([float("nan"), float("inf"), -float("inf"), 0, -0.0, -1,
                                   1e-300, 5e-324, 1e300, 1.7e308, 10**30, -10**30, 2**63,
                                   10**400, 0.5, 10.5, 1e-6, 1e6])
SCALARS = (st.none() | st.booleans() | st.integers() | SPECIAL_NUMBERS
           | st.floats(allow_nan=True, allow_infinity=True)
           | st.text(max_size=12) | st.sampled_from(["auto", "mm", "m", "seat", "leg1", "1e3",
                                                     ".nan", "yes", "400", "default"]))
VALUES = st.recursive(SCALARS, lambda inner: st.lists(inner, max_size=4)
                      | st.dictionaries(st.text(max_size=8) | st.sampled_from(list(VALID)),
                                        inner, max_size=4),
                      max_leaves=12)


def paths(node, prefix=()):
    """Every (path, node) inside a document; a path is a tuple of keys and indices."""
    yield prefix, node
    if isinstance(node, dict):
        for key, value in node.items():
            yield from paths(value, prefix + (key,))
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from paths(value, prefix + (index,))


def mutate(doc, data) -> object:
    """One random change somewhere in ``doc`` (in place where possible); returns the root."""
    path, node = data.draw(st.sampled_from(list(paths(doc))))
    action = data.draw(st.sampled_from(["replace", "number", "delete", "stray", "wrap",
                                        "quote", "truncate"]))
    if action == "replace":
        new = data.draw(VALUES)
    elif action == "number":
        new = data.draw(SPECIAL_NUMBERS)
    elif action == "wrap":
        new = data.draw(st.sampled_from([[node], {"value": node}, [node, node]]))
    elif action == "quote":
        new = str(node)
    elif action == "stray" and isinstance(node, dict):
        node[data.draw(st.text(max_size=10))] = data.draw(VALUES)
        return doc
    elif action == "truncate" and isinstance(node, list) and node:
        node.pop(data.draw(st.integers(0, len(node) - 1)))
        return doc
    elif action == "delete" and path:
        parent = doc
        for step in path[:-1]:
            parent = parent[step]
        del parent[path[-1]]
        return doc
    else:
        return doc
    if not path:
        return new
    parent = doc
    for step in path[:-1]:
        parent = parent[step]
    parent[path[-1]] = new
    return doc


def to_text(doc, fmt: str) -> str:
    if fmt == "json":
        return json.dumps(doc)
    return yaml.safe_dump(doc, sort_keys=False, allow_unicode=True)


def parse_or_design_error(text: str, fmt: str, source: str = "fuzz.yaml") -> Design | None:
    """The design, or None after a well-formed DesignError; anything else fails the test."""
    try:
        design = parse_design(text, source, fmt)
    except DesignError as error:
        lines = error.lines()                  # one line per problem of the file
        assert len(lines) == 1 + len(error.more) <= tol.MAX_INPUT_PROBLEMS + 1, lines
        for line, problem in zip(lines, (error, *error.more)):
            assert "\r" not in line and line == problem.one_line(), line
            assert line.startswith(source)
        return None
    assert isinstance(design, Design)
    return design


def test_the_seed_design_is_valid():
    for fmt in ("yaml", "json"):
        assert parse_or_design_error(to_text(VALID, fmt), fmt) is not None


@FUZZ
@given(data=st.data(), fmt=st.sampled_from(["yaml", "json"]), rounds=st.integers(1, 4))
def test_mutated_designs(data, fmt, rounds):
    doc = json.loads(json.dumps(VALID))
    for _ in range(rounds):
        doc = mutate(doc, data)
    design = parse_or_design_error(to_text(doc, fmt), fmt)
    if design is not None:
        # Whatever loads also writes back and loads again to the same design.
        again = parse_design(yaml.safe_dump(design_to_document(design), sort_keys=False),
                             "again.yaml", "yaml")
        assert [p.id for p in again.planks] == [p.id for p in design.planks]
        assert [c.name for c in again.load_cases] == [c.name for c in design.load_cases]


@FUZZ
@given(doc=VALUES, fmt=st.sampled_from(["yaml", "json"]))
def test_random_structures(doc, fmt):
    parse_or_design_error(to_text(doc, fmt), fmt)


YAML_PIECES = st.sampled_from([
    "furncheck: 1\n", "planks:\n", "  - id: a\n", "    size: [1, 2]\n", "center: [0, 0, 0]\n",
    "&x ", "*x ", "!!python/object:os.system ", "!!binary ", "? ", "- ", ": ", "[", "]", "{",
    "}", ",", "'", '"', "\t", "#", "---\n", "...\n", "%YAML 1.1\n", "<<: ", "\n", "  ", "|\n",
    ">-\n", "1e3", ".nan", "-.inf", "~", "yes", "0x1F", "0o17", "1_000", "1:30", "\ufeff",
    "\x85", "\u2028", "\x07", "\r\n"])


@FUZZ
@given(pieces=st.lists(YAML_PIECES | st.text(max_size=6), max_size=25),
       fmt=st.sampled_from(["yaml", "json"]))
def test_random_yaml_like_text(pieces, fmt):
    parse_or_design_error("".join(pieces), fmt)


@FUZZ
@given(text=st.text(max_size=200), fmt=st.sampled_from(["yaml", "json"]))
def test_random_text(text, fmt):
    parse_or_design_error(text, fmt)


@settings(deadline=None, max_examples=60, derandomize=True)
@given(data=st.binary(max_size=200), suffix=st.sampled_from([".yaml", ".json", ".yml"]))
def test_random_bytes_from_a_file(data, suffix):
    handle, path = tempfile.mkstemp(suffix=suffix)
    try:
        with os.fdopen(handle, "wb") as file:
            file.write(data)
        try:
            assert isinstance(load_design(path), Design)
        except DesignError as error:
            assert "\n" not in str(error) and str(error).startswith(path)
    finally:
        os.unlink(path)


@settings(deadline=None, max_examples=40, derandomize=True)
@given(depth=st.integers(1, 3000), fmt=st.sampled_from(["yaml", "json"]),
       opener=st.sampled_from(["[", "{\"a\": "]))
def test_deep_nesting(depth, fmt, opener):
    closer = "]" if opener == "[" else "}"
    parse_or_design_error(opener * depth + "1" + closer * depth, fmt)


def test_surrogates_and_control_characters():
    for text in ["\ud800", "name: \udfff\n", "furncheck: 1\x00", "\x1b[31m: 1", "\x00"]:
        for fmt in ("yaml", "json"):
            parse_or_design_error(text, fmt)
