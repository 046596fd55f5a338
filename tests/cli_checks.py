"""Checks through the real command line that several test modules share."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from furncheck.cli.main import main


def assert_suggestions_validate(path: Path, *range_args: str) -> None:
    """``furncheck suggest`` on the design at ``path`` exits 0 and every design file it
    writes validates (the promise of contract section 4; it may write none); ``range`` of
    ``range_args`` (all DOFs when none) exits 0."""
    out = path.parent / "out"
    result = CliRunner().invoke(main, ["suggest", str(path), "--out", str(out),
                                       "--no-plots", "--format", "json"])
    assert result.exit_code == 0, result.output
    for suggestion in json.loads(result.output)["suggestions"]:
        check = CliRunner().invoke(main, ["validate", suggestion["design_file"]])
        assert check.exit_code == 0, check.output
    result = CliRunner().invoke(main, ["range", str(path), *range_args, "--format", "json"])
    assert result.exit_code == 0, result.output
