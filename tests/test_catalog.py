"""Data-driven tests over the bundled catalog ``designs/``: every file with its expected verdict.

Each design file starts with a comment block saying what it is and why it should be valid or
invalid, with the hand calculation.  ``EXPECTED`` below is that verdict: (valid, the exact set
of violation kinds).  A new file without an entry here fails ``test_every_design_has_an_
expectation``; the catalog must show every violation kind at least once.

The geometry of every file is also checked independently of furncheck (``catalog_tools``,
numpy only): no two planks interpenetrate, and the joints furncheck detects are exactly the
narrow-face-on-broad-face touches found by the independent check.
"""

from __future__ import annotations

from pathlib import Path

import catalog_tools
import numpy as np
import pytest

from furncheck.result import VIOLATION_KINDS

DESIGNS = Path(__file__).resolve().parents[1] / "designs"

EXPECTED: dict[str, tuple[bool, frozenset[str]]] = {
    "stool.yaml": (True, frozenset()),
    "table.yaml": (True, frozenset()),
    "chair-upright.yaml": (True, frozenset()),
    "chair-tilted.yaml": (True, frozenset()),
    "bench.yaml": (True, frozenset()),
    "shelf-cantilever.yaml": (True, frozenset()),
    "magazine-rack.yaml": (True, frozenset()),
    "coffee-table-splayed.yaml": (True, frozenset()),
    "bookshelf-20.yaml": (True, frozenset()),
    "cabinet-28.yaml": (True, frozenset()),
    "l-shelf-pushed.yaml": (True, frozenset()),
    "bookshelf-gap.yaml": (False, frozenset({"disconnected"})),
    "bench-long-leg.yaml": (False, frozenset({"penetration"})),
    "side-table-hovering.yaml": (False, frozenset({"floating"})),
    "shelf-cantilever-overloaded.yaml": (False, frozenset({"non-durable"})),
    "bench-tips.yaml": (False, frozenset({"lift-off"})),
    "table-slides.yaml": (False, frozenset({"sliding"})),
    "bookcase-sagging.yaml": (False, frozenset({"sagging"})),
    "particleboard-shelf-overloaded.yaml": (False, frozenset({"sagging", "overstressed"})),
}

KNOWN_DISAGREEMENTS: dict[str, str] = {
    # file name -> why the solver's verdict differs from the hand calculation in its header;
    # kept as a strict xfail so the test starts failing (XPASS) once the solver agrees.
}


def design_files() -> list[str]:
    return sorted(p.name for p in DESIGNS.iterdir()
                  if p.suffix in (".yaml", ".yml", ".json"))


def _params(names):
    return [pytest.param(name, marks=pytest.mark.xfail(reason=KNOWN_DISAGREEMENTS[name],
                                                       strict=True))
            if name in KNOWN_DISAGREEMENTS else name for name in names]


@pytest.mark.parametrize("name", _params(sorted(EXPECTED)))
def test_catalog_verdict(name: str) -> None:
    """check_file gives the verdict and exactly the violation kinds the header explains."""
    from furncheck.check import check_file

    valid, kinds = EXPECTED[name]
    report = check_file(str(DESIGNS / name))
    assert report.error is None, report.error
    found = {v.kind for v in report.violations}
    messages = [f"{v.kind} {v.where} [{v.case}]: {v.message}" for v in report.violations]
    assert (report.valid, found) == (valid, set(kinds)), messages


def test_every_design_has_an_expectation() -> None:
    """A design file added to designs/ without an expected verdict here fails."""
    files = design_files()
    assert len(files) >= 14
    assert sorted(set(files) - set(EXPECTED)) == []
    assert sorted(set(EXPECTED) - set(files)) == []


def test_catalog_shows_every_violation_kind() -> None:
    shown = set().union(*(kinds for _, kinds in EXPECTED.values()))
    assert shown == set(VIOLATION_KINDS)
    assert any(valid for valid, _ in EXPECTED.values())


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_no_planks_interpenetrate(name: str) -> None:
    """Independent box-overlap check: planks touch at most (within the tolerance)."""
    assert catalog_tools.overlaps(catalog_tools.load(DESIGNS / name)) == []


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_detected_joints_match_independent_touches(name: str) -> None:
    """The joints furncheck reports are the face-on-face touches that catalog_tools finds
    (for files with listed joints: the listed joints that touch)."""
    from furncheck.check import check_file

    design = catalog_tools.load(DESIGNS / name)
    report = check_file(str(DESIGNS / name))
    if "floating" in EXPECTED[name][1]:
        pytest.skip("no grounded planks: no joint results to compare")
    touching = {frozenset((t.edge, t.face)) for t in catalog_tools.touches(design)}
    if design.get("joints"):
        listed = {frozenset(j if isinstance(j, list) else j["planks"])
                  for j in design["joints"]}
        touching &= listed
    detected = {frozenset(j.planks) for j in report.cases[0].joints}
    assert detected == touching


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_nail_counts_match_independent_touches(name: str) -> None:
    """Nail counts are floor(touch length / nail spacing) (20 mm unless the file's material
    says), the touch length measured independently."""
    from furncheck.check import check_file

    design = catalog_tools.load(DESIGNS / name)
    report = check_file(str(DESIGNS / name))
    if not report.cases:
        pytest.skip("no load cases solved")
    spacing = float((design.get("material") or {}).get("nail_spacing", 20.0))
    nails = {frozenset((t.edge, t.face)): max(1, int(np.floor(t.length / spacing * (1 + 1e-6))))
             for t in catalog_tools.touches(design)}
    for joint in report.cases[0].joints:
        assert joint.nails == nails[frozenset(joint.planks)], joint.planks
