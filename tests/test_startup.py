"""Start-up: ``furncheck validate`` imports only the scipy its designs need.

scipy takes several times as long to import as a small design takes to check, so it is
imported where it is used: scipy.sparse for designs above the dense limit
(DENSE_PLANKS_MAX plank displacements), scipy.optimize for the feasibility programs (a
design that may slide or lift off); a small design needs neither, and its Cholesky and LU
come from scipy's compiled LAPACK module, loaded without the packages around it
(``furncheck.statics.lapack``).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

SCRIPT = """
import contextlib, io, json, sys
from furncheck.cli.main import main

def loaded():
    return sorted(m for m in sys.modules
                  if m.split(".")[0] in ("scipy", "trimesh", "matplotlib", "pathspec", "dask",
                                         "distributed") or m == "numpy.ma")

RARE = ("furncheck.cli.suggest", "furncheck.cli.range", "furncheck.statics.feasibility",
        "furncheck.statics.newton", "furncheck.geometry.edits", "furncheck.design.write",
        "furncheck.ignores", "furncheck.detect", "tomllib")
seen = {"import": [None, loaded()]}
with contextlib.redirect_stdout(io.StringIO()):
    main(["validate", "designs/stool.yaml", "--no-cache"], standalone_mode=False)
seen["no cache"] = "furncheck.cache" in sys.modules
for label, args in [("stool rigid", ["designs/stool.yaml", "--model", "rigid"]),
                    ("stool elastic", ["designs/stool.yaml"]),
                    ("cabinet elastic", ["designs/cabinet-28.yaml"]),
                    ("table slides", ["designs/table-slides.yaml", "--model", "rigid"])]:
    with contextlib.redirect_stdout(io.StringIO()):
        code = main(["validate", *args, "--format", "json"], standalone_mode=False)
    seen[label] = [code, loaded()]
    if label == "stool elastic":
        from furncheck.statics.lapack import routines
        seen["lapack"] = routines().source
        seen["rare"] = sorted(m for m in RARE if m in sys.modules)
print(json.dumps(seen))
"""


def test_validate_imports_only_the_scipy_a_design_needs():
    """The stool (4 planks, both models) is checked without any scipy package imported:
    only scipy's compiled LAPACK module is loaded, from its file; the 28-plank cabinet in
    the elastic model (hundreds of beam nodes: above the dense limit) brings scipy.sparse
    and its LU, but
    no scipy.optimize (it stands: no feasibility program runs); the table that slides
    (rigid) brings scipy.optimize for its linear programs.  Nothing loads trimesh or
    matplotlib, nor pathspec (gitignore patterns: folders only) or Dask (--scheduler
    only); the stool not even numpy.ma (12 ms, which numpy 2's np.unique imports), nor
    furncheck's own modules that other commands or rarer cases need (the other commands,
    the feasibility programs and Newton's method, the edits' geometry, the design writer,
    the gitignore rules, the test for design files that folder scans read: a named file
    is checked whatever it holds) or tomllib (this repository's pyproject.toml has no
    [tool.furncheck] table, and says so without being parsed); with --no-cache, not the
    result cache either (a run that neither caches nor scans a folder needs no cache
    folder: some 8 ms of a cold start)."""
    output = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                            check=True, cwd=ROOT).stdout
    seen = json.loads(output.splitlines()[-1])
    assert seen["import"] == [None, []]
    assert seen["no cache"] is False        # a named file, no cache: its folder not looked up
    assert seen["stool rigid"] == [0, ["scipy.linalg._flapack"]]
    assert seen["stool elastic"] == [1, ["scipy.linalg._flapack"]]
    assert seen["lapack"] == "file"
    assert seen["rare"] == []
    code, cabinet = seen["cabinet elastic"]
    assert "scipy.sparse.linalg" in cabinet
    assert not any(m.startswith("scipy.optimize") for m in cabinet)
    code, table = seen["table slides"]
    assert code == 1 and "scipy.optimize" in table
    assert not any(m.split(".")[0] in ("trimesh", "matplotlib", "pathspec", "dask",
                                       "distributed") for m in cabinet + table)


def test_the_console_script_is_main_freezing_what_survives_it(monkeypatch):
    """``furncheck`` and ``python -m furncheck`` run ``cli.main.run``: ``main`` with its
    exit code, then every live object frozen (``gc.freeze``) so that the interpreter's
    last collection on exit skips them; ``main`` alone, as the tests call it, freezes
    nothing.  The installed script names ``run``."""
    import gc
    import tomllib

    from click.testing import CliRunner

    from furncheck.cli.main import main, run

    frozen = []
    monkeypatch.setattr(gc, "freeze", lambda: frozen.append(True))
    monkeypatch.setattr(sys, "argv", ["furncheck", "validate", str(ROOT / "designs/stool.yaml"),
                                      "--no-cache", "--format", "json"])
    try:
        run()
    except SystemExit as exit_:
        code = exit_.code
    assert code == 1 and frozen == [True]          # the stool sags: invalid
    assert CliRunner().invoke(main, ["--version"]).exit_code == 0 and frozen == [True]
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts == {"furncheck": "furncheck.cli.main:run"}
    import furncheck.__main__ as module_main

    assert module_main.run is run


def test_every_package_is_installed():
    """pyproject.toml lists the packages a (non-editable) install copies: every folder of
    furncheck/ and cli/ holding an __init__.py is there, under its import name.
    (furncheck/dofs/, a package since it was split from dofs.py, was missing: a normal
    install's suggest and range ended in 'No module named furncheck.dofs'; the editable
    install of the tests and the Quick start did not show it.)"""
    import tomllib

    setuptools = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    folders = {name: ROOT / path for name, path in setuptools["package-dir"].items()}
    found = set()
    for top in ("furncheck", "furncheck.cli"):
        for init in sorted(folders[top].rglob("__init__.py")):
            parts = init.parent.relative_to(folders[top]).parts
            found.add(".".join((top, *parts)))
    assert found == set(setuptools["packages"])
