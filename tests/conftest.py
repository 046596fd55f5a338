"""Shared test set-up: every test gets its own result cache directory; the fake checker;
``suggest`` on the invalid catalog designs, computed once per session and only for the
(design, model) pairs a test asks for; ``without_matplotlib`` for the tests of a machine
that cannot draw; ``whole_joints`` for the tests whose premise was found with every elastic
nail joint one spring.

``furncheck validate`` caches results in the user cache directory by default; a test that
runs it must neither write to the developer's cache nor be served a result that another
test computed (several tests replace part of the checker).  ``FURNCHECK_CACHE_DIR`` points
the default at a fresh folder per test, for the CLI in this process and in subprocesses.

Every hypothesis test is derandomized: the profile loaded here is the default that each
test's own ``settings`` inherit, so the same examples run in every run and CI never fails
on an example that no earlier run met (most tests also say so in their own settings).
"""

from __future__ import annotations

import math
import sys
import types
from pathlib import Path

import pytest
from hypothesis import settings

import furncheck.cli  # noqa: F401  (first: one BLAS thread, as the command line runs)
from furncheck import tolerances as tol
from furncheck.design import load_design
from furncheck.design.model import with_model
from furncheck.suggest import suggest_design

settings.register_profile("furncheck", derandomize=True)
settings.load_profile("furncheck")


@pytest.fixture(autouse=True)
def _own_cache_directory(tmp_path_factory: pytest.TempPathFactory,
                         monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("FURNCHECK_CACHE_DIR", str(tmp_path_factory.mktemp("cache")))


@pytest.fixture
def whole_joints(monkeypatch: pytest.MonkeyPatch) -> None:
    """The elastic model with every nail joint one spring at its point, as before joints
    along a beam were cut into parts (``elastic.joint_part_counts``): for tests whose
    premise (a case that cycles, a plank held at one node) was found on such a model and
    whose subject is another part of the statics."""
    monkeypatch.setattr(tol, "JOINT_PART_LENGTH", math.inf)
    monkeypatch.setattr(tol, "JOINT_PART_SHARE", math.inf)


@pytest.fixture
def floor_at_corners(monkeypatch: pytest.MonkeyPatch) -> None:
    """The elastic model with the floor and the walls holding a plank at its corners
    alone, as before support stations (``statics.stations``): a plank on its long edge
    on the floor then spans between its end corners, as on two narrow feet.  For tests
    whose premise (a beam simply supported at its ends, a plank bowed between its feet, a
    case found on such a model) needs that and whose subject is another part of the
    statics."""
    import numpy as np

    from furncheck.statics import elastic

    monkeypatch.setattr(elastic, "support_edges",
                        lambda *args: (np.zeros((0, 3), dtype=int), np.zeros(0)))


@pytest.fixture
def checked_paths(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """``furncheck.check`` replaced by the fake checker of ``test_cli`` (the verdict comes
    from the file name: valid*, bad*, boom*, garbage*); returns the paths it checks, in
    order, so a test sees which files the command chose and which it took from the cache."""
    from test_cli import fake_check_file

    seen: list[str] = []

    def check_file(path: str, model: str | None = None):
        seen.append(path)
        return fake_check_file(path, model)

    fake = types.ModuleType("furncheck.check")
    fake.check_file = check_file
    monkeypatch.setitem(sys.modules, "furncheck.check", fake)
    return seen

CATALOG = Path(__file__).resolve().parents[1] / "designs"


@pytest.fixture(scope="session")
def catalog_suggestions():
    """``get(name, model)`` -> (the catalog design in that model, its ``SuggestionReport``),
    each computed on first use (the line searches are the slow part)."""
    cache: dict[tuple[str, str], tuple] = {}

    def get(name: str, model: str):
        if (name, model) not in cache:
            design = with_model(load_design(str(CATALOG / name)), model)
            cache[(name, model)] = (design, suggest_design(design))
        return cache[(name, model)]

    return get


def without_matplotlib(how: str | None, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Make matplotlib unusable for the rest of a test: ``how`` None, not installed
    (``find_spec`` finds nothing); 'top', installed but failing at its own import; 'deep',
    failing in a module drawing imports (``backends.backend_agg``: a missing shared
    library, as a broken install fails)."""
    import importlib.util

    if how is None:
        real = importlib.util.find_spec
        monkeypatch.setattr(importlib.util, "find_spec",
                            lambda name, *args: None if name == "matplotlib"
                            else real(name, *args))
        return
    fake = tmp_path / "fake" / "matplotlib"
    (fake / "backends").mkdir(parents=True)
    (fake / "__init__.py").write_text("raise ImportError('broken here')\n" if how == "top"
                                      else "")
    (fake / "backends" / "__init__.py").write_text("")
    (fake / "backends" / "backend_agg.py").write_text(
        "raise OSError('libfreetype.so.6: cannot open shared object file')\n")
    monkeypatch.syspath_prepend(str(tmp_path / "fake"))
    for name in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        monkeypatch.delitem(sys.modules, name)
