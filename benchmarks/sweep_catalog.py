"""The physics checks of ``tests/test_invariants.py`` and ``tests/test_stability_programs.py``
over a generated catalog: far more designs than the suite can afford.

    python benchmarks/sweep_catalog.py [--count N] [--seed S] [--every K] [--jobs J]
                                       [--edits E] [--edit-size F] [--edit-turn D]
                                       [--edit-dofs M] [--keep DIR]

Writes N designs (``benchmarks/catalog.py``, default 1,000: shelving walls of 5 to 30
planks, two thirds with a second case that pushes the top) and, with ``--edits``, E edits
of every design of ``designs/`` (one to M random DOFs moved, default 2: up to F of the
design's size, default 0.04, or D degrees, default 5; tables, chairs, walls, anchors,
resting planks), and checks each in both models:

- motion: turned about the vertical by 37 degrees and moved by (0.8, -1.7 m), and by
  -123.4 degrees and (-2.1, 0.3 m): the same verdicts, forces turned with it, the same
  per-nail forces;
- units: moved (71.3 degrees, 2.2 m) and written in metres: the same, and (elastic
  model) every plank's sag scaled by 1000, the same stress and utilization;
- json: the same design as JSON: the same report;
- mirror: its mirror image in the plane x = 0: the same verdicts, per-nail forces and
  (elastic model) sags and stresses, forces and points mirrored, moments as axial vectors;
- order: its planks written in the reverse order: the same;
- balance: every case's ground forces balance the loads, every plank its own forces;
- pushes (every K-th design, default 10; 0: none): a sideways push of 15 to 200 N in three
  directions on the top plank: the verdict is the feasibility programs' own, stable
  cases balance.

It needs the ``test`` extra (``pip install -e '.[test]'``: the checks are the suite's).
Prints a table: checks made and failed per kind, then each failure; with ``--keep`` the
failing design files are copied into DIR (the sweep's own folder is temporary; a second
sweep into the same DIR may overwrite them).  The tolerances are the tests' (relative
1e-6 of the forces, 1e-3 of the loads for balance).  Designs are checked in J processes
(default 2); the output is the same for any J.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

if __name__ == "__main__":      # run as a script: one BLAS thread, as the command line runs
    for _threads in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[_threads] = "1"

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "tests"))

import numpy as np  # noqa: E402
import yaml  # noqa: E402
from catalog import write_catalog  # noqa: E402

try:                        # the suite's own checks: they need the test extra
    import test_invariants as invariants
    from test_stability_programs import _unbalanced
except ImportError as missing:
    sys.exit(f"sweep_catalog.py runs the test suite's checks and needs its packages "
             f"({missing.name} is missing): pip install -e '.[test]'")

from furncheck.check import check_design  # noqa: E402
from furncheck.design import parse_design  # noqa: E402
from furncheck.design.model import Load, with_model  # noqa: E402
from furncheck.design.write import write_design  # noqa: E402
from furncheck.dofs import (  # noqa: E402
    Blocked,
    OutOfReach,
    all_dofs,
    apply_dof,
    design_size,
    structure,
)
from furncheck.errors import DesignError  # noqa: E402
from furncheck.geometry import analyze  # noqa: E402
from furncheck.statics import feasibility  # noqa: E402
from furncheck.statics.contacts import _force_scale, solve_case  # noqa: E402
from furncheck.statics.model import build_model, external_forces  # noqa: E402

KINDS = ("motion", "units", "json", "mirror", "order", "balance", "pushes")
MODELS = ("elastic", "rigid")


def sweep_one(path: str, pushes: bool) -> tuple[dict[str, int], list[tuple[str, str]]]:
    """(checks made per kind, failures as (kind, what)) of one design file."""
    data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    made = dict.fromkeys(KINDS, 0)
    failures: list[tuple[str, str]] = []

    def attempt(kind: str, label: str, check, *arguments) -> None:
        made[kind] += 1
        try:
            check(*arguments)
        except Exception as error:  # noqa: BLE001 - any error is a finding, the sweep goes on
            first = (str(error).splitlines() or [""])[0][:200]
            what = "" if isinstance(error, AssertionError) else f"{type(error).__name__}: "
            failures.append((kind, f"{Path(path).name} {label}: {what}{first}"))

    for model in MODELS:
        try:
            report = invariants.check(data, model=model)
        except Exception as error:  # noqa: BLE001
            failures.append(("motion", f"{Path(path).name} {model}: cannot be checked: "
                                       f"{type(error).__name__}: {error}"))
            continue
        for motion in ((37.0, 0.8, -1.7), (-123.4, -2.1, 0.3)):
            attempt("motion", f"{model} turned {motion[0]}", _same_moved, data, report, model,
                    motion, False)
        attempt("units", f"{model} in metres", _same_moved, data, report, model,
                (71.3, 2.2, -1.1), True)
        attempt("json", f"{model} as JSON", _same_as_json, data, report, model)
        attempt("mirror", f"{model} mirrored", _same_mirrored, data, report, model)
        attempt("order", f"{model} planks reversed", _same_reordered, data, report, model)
        design = with_model(parse_design(invariants.pd.to_text(data), path, "yaml"), model)
        attempt("balance", f"{model} balance", _balanced, design)
        if pushes:
            for label, forces, model_of in _pushes(design):
                attempt("pushes", f"{model} {label}", _agrees_with_programs, model_of, forces)
    return made, failures


def _same_moved(data: dict, report, model: str, motion: tuple[float, float, float],
                in_metres: bool) -> None:
    """The design turned by phi degrees and moved by (tx, ty) m (``motion``), and written
    in metres (``in_metres``), gives ``report`` seen through that motion."""
    pd = invariants.pd
    moved, rotation, where = invariants.moved(data, *motion)
    factor = 1.0
    if in_metres:
        converted = pd.convert_units(moved, "m")
        factor = pd.unit_factor(converted) / pd.unit_factor(data)
        moved = converted
    other = invariants.check(moved, model=model)
    invariants.assert_same_physics(report, other, invariants.force_scale(data), rotation,
                                   lambda p: where(p) * factor,
                                   point_tol=1e-9 * pd.unit_factor(moved))
    if model == "elastic" and all(case.planks for case in report.cases):
        invariants.assert_same_planks(report, other, factor)   # where every case is solved


def _same_mirrored(data: dict, report, model: str) -> None:
    """The design's mirror image in x = 0 gives ``report`` mirrored."""
    invariants.assert_same_mirrored(
        data, report, invariants.check(invariants.pd.mirrored(data), model=model))


def _same_reordered(data: dict, report, model: str) -> None:
    """The design with its planks in the reverse order gives ``report``."""
    invariants.assert_same_reordered(
        data, report, invariants.check(invariants.reversed_planks(data), model=model))


def _same_as_json(data: dict, report, model: str) -> None:
    invariants.assert_same_physics(report, invariants.check(data, "json", model=model),
                                   invariants.force_scale(data), point_tol=0.0)


def _balanced(design) -> None:
    checked = check_design(design)
    invariants.assert_contacts_balance_loads(design, checked)
    invariants.assert_planks_balance(design, checked)


def _pushes(design):
    """(label, forces, statics model) of each push on the top plank of ``design``'s first
    case (none where its geometry has violations)."""
    geometry = analyze(design)
    if geometry.violations:
        return
    model = build_model(design, geometry)
    top = max(design.planks, key=lambda plank: plank.center[2])
    first = design.load_cases[0]
    for size in (15.0, 40.0, 90.0, 200.0):
        for angle in (0.0, 0.7, 1.9):
            push = Load(top.id, (size * np.cos(angle), size * np.sin(angle), 0.0), None)
            case = dataclasses.replace(first, name="push", loads=(*first.loads, push))
            yield f"push {size:g} N at {angle} rad", external_forces(model, case), model


def _agrees_with_programs(model, forces: np.ndarray) -> None:
    """The verdict is the feasibility programs' own; a stable case's ground forces balance
    its loads (1e-6 of them)."""
    statics = solve_case(model, forces)
    upright = feasibility.unilateral_feasible(model, forces).exists
    held = feasibility.cone_solution(model, forces).exists
    expected = "stable" if held else "sliding" if upright else "lift-off"
    assert statics.stability == expected, f"{statics.stability}, not {expected}"
    if expected == "stable":
        assert _unbalanced(model, statics, forces) <= 1e-6 * _force_scale(model, forces), \
            "ground forces off balance"


def write_edits(folder: Path, count: int, seed: int, size: float = 0.04, turn: float = 5.0,
                most: int = 2) -> list[Path]:
    """``count`` random edits of each design of ``designs/`` written into ``folder``: one
    to ``most`` DOFs, each moved by up to ``size`` of the design's size (4 %) or ``turn``
    degrees (5) (``apply_dof``: the joints kept); an edit that a DOF cannot make, or that
    leaves a plank without size, is left out.  The same files for the same arguments."""
    import random

    from furncheck.design import load_design

    rng = random.Random(seed)
    paths = []
    for source in sorted((HERE.parent / "designs").glob("*.yaml")):
        base = load_design(str(source))
        for k in range(count):
            design = base
            try:
                for _ in range(rng.randint(1, most)):
                    dof = rng.choice(all_dofs(design))
                    step = rng.uniform(-turn, turn) if dof.is_rotation else \
                        rng.uniform(-size, size) * design_size(design)
                    design = apply_dof(design, structure(design, analyze(design)), dof, step)
                path = folder / f"{source.stem}-edit-{k:02d}.yaml"
                write_design(design, str(path))
                parse_design(path.read_text(encoding="utf-8"), str(path), "yaml")
            except (Blocked, OutOfReach, DesignError):
                continue
            paths.append(path)
    return paths


def _keep_failing(paths: list[str], results: list, folder: Path) -> None:
    """Copy the design files with a failure (``results`` per path) into ``folder``, so that
    they outlive the sweep's temporary folder."""
    import shutil

    folder.mkdir(parents=True, exist_ok=True)
    for path, (_, failed) in zip(paths, results):
        if failed:
            shutil.copy(path, folder / Path(path).name)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=16)
    parser.add_argument("--every", type=int, default=10, help="pushes on every K-th design")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--edits", type=int, default=0,
                        help="random DOF edits of each design of designs/")
    parser.add_argument("--edit-size", type=float, default=0.04,
                        help="largest move of an edit, a fraction of the design's size")
    parser.add_argument("--edit-turn", type=float, default=5.0,
                        help="largest turn of an edit, degrees")
    parser.add_argument("--edit-dofs", type=int, default=2, help="most DOFs of one edit")
    parser.add_argument("--keep", metavar="DIR",
                        help="copy every design file with a failure into DIR")
    args = parser.parse_args()
    if args.edit_dofs < 1:
        parser.error("--edit-dofs must be at least 1")
    with tempfile.TemporaryDirectory() as folder:
        paths = [str(p) for p in write_catalog(folder, args.count, args.seed)]
        paths += [str(p) for p in write_edits(Path(folder), args.edits, args.seed,
                                              args.edit_size, args.edit_turn,
                                              args.edit_dofs)]
        pushes = [args.every > 0 and k % args.every == 0 for k in range(len(paths))]
        with ProcessPoolExecutor(args.jobs) as pool:
            results = list(pool.map(sweep_one, paths, pushes, chunksize=8))
        if args.keep:
            _keep_failing(paths, results, Path(args.keep))
    made = dict.fromkeys(KINDS, 0)
    failures = []
    for counts, failed in results:
        for kind in KINDS:
            made[kind] += counts[kind]
        failures += failed
    edits = len(paths) - args.count
    print(f"{args.count} generated designs and {edits} edits of the catalog's (seed "
          f"{args.seed}), both models\n")
    print("| check | made | failed |")
    print("|-------|-----:|-------:|")
    for kind in KINDS:
        failed = sum(1 for found, _ in failures if found == kind)
        print(f"| {kind} | {made[kind]} | {failed} |")
    for _, line in failures:
        print(line)


if __name__ == "__main__":
    main()
