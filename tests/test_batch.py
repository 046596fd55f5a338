"""``--jobs`` on real designs: the bundled catalog checked in worker processes gives the
bytes of one process (the fakes of ``test_cli`` cover the policy and every format)."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from furncheck import batch
from furncheck.cli.main import main

DESIGNS = Path(__file__).resolve().parents[1] / "designs"


@pytest.mark.parametrize("model", ["elastic", "rigid"])
def test_catalog_json_is_the_same_for_any_jobs(monkeypatch, model):
    """Workers forced from the second design on (PARALLEL_AFTER 0): with ``--jobs 2`` the
    catalog's JSON report is byte for byte the one of ``--jobs 1`` (which by then is
    checked in one process only: ``jobs`` 1 never starts workers).  The designs checked
    in this process are counted: with ``--jobs 2`` only the first is."""
    monkeypatch.setattr(batch, "PARALLEL_AFTER", 0.0)
    here: list[str] = []
    check_one = batch.check_one
    monkeypatch.setattr(batch, "check_one", lambda path, m=None: here.append(path)
                        or check_one(path, m))
    runner = CliRunner()
    count = len(list(DESIGNS.glob("*.yaml")))
    args = ["validate", str(DESIGNS), "--format", "json", "--model", model, "--no-cache"]
    one = runner.invoke(main, args + ["--jobs", "1"])
    assert len(here) == count
    two = runner.invoke(main, args + ["--jobs", "2"])
    assert len(here) == count + 1
    assert one.exit_code == two.exit_code == 1
    assert one.stdout == two.stdout
    assert one.stdout.count('"design": ') == count
