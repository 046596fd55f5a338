"""The Table 1 benchmark designs (benchmarks/table1_designs.py): the paper's plank and joint
counts, exactly one non-durable joint in both statics models, and the same verdict after a
round trip through a YAML file.  The geometry is also checked with the independent
``catalog_tools``."""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import catalog_tools
import pytest

from furncheck.check import check_design
from furncheck.design.load import load_design
from furncheck.design.model import with_model
from furncheck.design.write import write_design
from furncheck.geometry import analyze

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import table1_designs  # noqa: E402

SIZES = sorted(table1_designs.TABLE1)


def test_table1_sizes_are_the_papers() -> None:
    assert table1_designs.TABLE1 == {9: (13, 110), 10: (13, 123), 20: (33, 880),
                                     28: (49, 2420)}


@pytest.mark.parametrize("planks", SIZES)
def test_plank_and_joint_counts(planks: int) -> None:
    design = table1_designs.table1_design(planks)
    assert len(design.planks) == planks
    assert len(analyze(design).joints) == table1_designs.TABLE1[planks][0]
    assert design.name.startswith(f"table1-{planks}-")


@pytest.mark.parametrize("planks", SIZES)
def test_listed_joints_are_the_detected_ones(planks: int) -> None:
    """The joints are listed only to give the ledge its few nails: the same pairs as
    detection finds, every other joint with the spacing rule's nails."""
    design = table1_designs.table1_design(planks)
    listed, detected = analyze(design).joints, analyze(replace(design, joints=None)).joints
    assert [j.planks for j in listed] == [j.planks for j in detected]
    explicit = [(j.planks, j.nails) for j, spec in zip(listed, design.joints) if spec.nails]
    assert len(explicit) == 1 and explicit[0][1] in (2, 3)
    assert sum(j.nails != d.nails for j, d in zip(listed, detected)) == 1


@pytest.mark.parametrize("model", table1_designs.MODELS)
@pytest.mark.parametrize("planks", SIZES)
def test_exactly_one_non_durable_joint(planks: int, model: str) -> None:
    """In both models, the paper's rigid one (whose Table 1 these designs re-create) and
    the elastic default: one failing joint, the ledge's, everything else well within
    capacity; in the elastic model no plank sags or is overstressed, each with margin."""
    report = check_design(with_model(table1_designs.table1_design(planks), model))
    assert report.valid is False
    assert [v.kind for v in report.violations] == ["non-durable"]
    (where,) = {v.where for v in report.violations}
    assert where.split("/")[1] in ("ledge", "side_shelf", "desk_leaf")
    assert all(case.stable for case in report.cases)
    worst, *others = table1_designs.utilizations(report)
    assert 1.2 <= worst <= 1.6
    assert max(others) < 0.8
    bent = table1_designs.plank_utilizations(report)
    if model == "elastic":
        assert len(bent) == planks and max(bent) < 0.8
    else:
        assert bent == []


def test_the_sagging_bookshelf_fails_all_over_in_the_elastic_model() -> None:
    """The first, all-12-mm 20-plank design: only its ledge joint fails in the rigid model,
    20 places (ledge joint, shelves, sides, dividers, ledge) in the elastic one (shelf_b3
    too since the shelves are checked as plates as well, ``statics.plates``: held along
    their ends, a plate's free edges bend further than its beam's section)."""
    design = table1_designs.sagging_bookshelf_20()
    assert len(design.planks) == 20 and len(analyze(design).joints) == 33
    rigid = check_design(with_model(design, "rigid"))
    assert [(v.kind, v.where) for v in rigid.violations] == [("non-durable", "side_r/ledge")]
    elastic = check_design(with_model(design, "elastic"))
    kinds = {v.kind for v in elastic.violations}
    assert kinds == {"non-durable", "sagging"}
    assert len({v.where for v in elastic.violations}) == 20


@pytest.mark.parametrize("planks", SIZES)
def test_written_file_round_trips(planks: int, tmp_path: Path) -> None:
    design = table1_designs.table1_design(planks)
    path = tmp_path / f"{design.name}.yaml"
    write_design(design, str(path))
    written = load_design(str(path))
    for model in table1_designs.MODELS:
        before = check_design(with_model(design, model))
        after = check_design(with_model(written, model))
        assert table1_designs.verdict(after) == table1_designs.verdict(before)
        assert table1_designs.utilizations(after) == pytest.approx(
            table1_designs.utilizations(before), rel=1e-6, abs=1e-9)
        assert table1_designs.plank_utilizations(after) == pytest.approx(
            table1_designs.plank_utilizations(before), rel=1e-6, abs=1e-9)
    document = catalog_tools.load(path)
    assert catalog_tools.overlaps(document) == []
    touching = {frozenset((t.edge, t.face)) for t in catalog_tools.touches(document)}
    assert touching == {frozenset(j.planks) for j in after.cases[0].joints}


def test_unknown_size_is_refused() -> None:
    with pytest.raises(ValueError, match="not 11"):
        table1_designs.table1_design(11)


def test_main_prints_the_table(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert table1_designs.main(["--write", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    for planks in SIZES:
        assert (tmp_path / f"{table1_designs.table1_design(planks).name}.yaml").is_file()
    assert "table1-28-cabinet" in out and "non-durable" in out
    assert "elastic" in out and "sagging" not in out
