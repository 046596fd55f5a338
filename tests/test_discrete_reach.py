"""Which discrete candidates are built and checked (``suggest.discrete.supports._reach``): a support
or rail comes near every failing place or is not tried."""

from __future__ import annotations

import sys
from pathlib import Path

from furncheck.check import check_design
from furncheck.design.model import with_model
from furncheck.geometry import analyze
from furncheck.suggest.discrete import Search, support_planks
from furncheck.suggest.discrete.supports import _reach

ROOT = Path(__file__).resolve().parents[1]


def test_reach_is_one_joint_from_the_ends():
    """A support nailed to shelf and base comes near the post jointed to both, and near a
    failing post/shelf joint; not near a plank two joints away."""
    neighbours = {"shelf": ["post"], "base": ["post"], "post": ["shelf", "base", "cap"],
                  "cap": ["post", "top"], "top": ["cap"]}
    assert _reach(["shelf", "post"], neighbours)({"shelf", "base"})
    assert _reach(["post/shelf"], neighbours)({"shelf", "base"})
    assert not _reach(["shelf", "top"], neighbours)({"shelf", "base"})
    assert not _reach(["cap/top"], neighbours)({"shelf", "base"})


def test_a_bookcase_that_sags_all_over_gets_no_support_checked(monkeypatch):
    """The first, all-12-mm version of the 20-plank Table-1 bookcase in the elastic model:
    its 18 sagging planks and its ledge joint lie on all three bays, which no one added
    plank comes near, so not one candidate design is checked (each would be a full
    elastic check that fails)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from table1_designs import sagging_bookshelf_20

    design = with_model(sagging_bookshelf_20(), "elastic")
    geometry = analyze(design)
    report = check_design(design, geometry)
    assert len({v.where for v in report.violations}) > 10
    checked = []
    monkeypatch.setattr(Search, "verdict", lambda self, *args, **kw: checked.append(args))
    assert support_planks(Search(design, geometry, report)) is None
    assert checked == []
