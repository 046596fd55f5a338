"""Benchmark: a 2,000-plank design through ``validate``, ``suggest`` and a one-DOF ``range``.

The design is a shelving wall (``shelving``: 41 sides, 40 bays of 49 shelves, 2,001
planks, 3,920 joints) whose middle shelf carries 20 kg instead of 8 kg: in the default
elastic model that shelf sags beyond span / 400, the one violation, so ``suggest`` has
something to repair and ``range`` of that shelf's width searches where validity begins.
Each command runs as its own process under an address-space cap (``--cap``, default
6 GB, so that a version that runs away fails with a MemoryError instead of driving the
shared machine out of memory) with one BLAS thread, as the command line runs; the table
gives its wall time and peak resident memory (the child's own ``wait4`` rusage), medians
of ``--repeat`` runs.  With ``--old TREE`` (a checkout of another version) the same
commands run from that tree too, alternately with this one, so both meet the same phases
of a busy machine.

    python benchmarks/bench_big.py [--repeat N] [--old TREE] [--cap BYTES]
                                   [--columns C] [--rows R] [--scaling] [--loose N]

``--scaling`` times ``validate`` alone on walls of about 250, 500, 1,000 and 2,000 planks
in both models instead, with the exponent of time in planks between the two largest (the
command's start, about 0.5 s, weighs on the smaller ones).  ``--loose N`` instead runs the
three commands on N boards stacked face to face and joined to nothing (a generated file
gone wrong: a ``disconnected`` line per board, each looking for an end cut into its
neighbours' faces), ``range`` of one board's x.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
TREE = HERE.parent
COMMANDS = {
    "validate": ["validate", "{file}", "--format", "json"],
    "suggest": ["suggest", "{file}", "--format", "json"],
    "range (1 DOF)": ["range", "{file}", "{dof}", "--format", "json", "--jobs", "1"],
}


def _child(tree: str, args: list[str]) -> None:
    """Run ``furncheck ARGS`` from the source tree ``tree`` (its ``furncheck`` package and
    its ``cli`` folder as ``furncheck.cli``, whichever version is installed)."""
    import importlib.util

    sys.path.insert(0, tree)
    cli = os.path.join(tree, "cli")
    spec = importlib.util.spec_from_file_location(
        "furncheck.cli", os.path.join(cli, "__init__.py"), submodule_search_locations=[cli])
    module = importlib.util.module_from_spec(spec)
    sys.modules["furncheck.cli"] = module
    spec.loader.exec_module(module)
    from furncheck.cli.main import main

    main(args)


def _uncached(tree: Path, args: list[str]) -> list[str]:
    """``args`` with ``--no-cache`` for a ``validate`` of a version that caches results
    (every run must check the design, not read its last result)."""
    source = tree / "cli" / "validate.py"
    if args[0] == "validate" and source.exists() and "--no-cache" in source.read_text():
        return [*args, "--no-cache"]
    return args


def _run(tree: Path, args: list[str], cap: int) -> tuple[float, float, str]:
    """(wall seconds, peak RSS MB, outcome) of one command in a child process."""
    args = _uncached(tree, args)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    env.pop("PYTHONPATH", None)

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))

    start = time.perf_counter()
    child = subprocess.Popen([sys.executable, str(Path(__file__).resolve()), "--child",
                              str(tree), "--", *args], env=env, preexec_fn=limit,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(child.pid, 0)
    seconds = time.perf_counter() - start
    error = child.stderr.read().decode(errors="replace").strip().splitlines()
    child.stderr.close()
    code = os.waitstatus_to_exitcode(status)
    outcome = f"exit {code}"
    if code < 0:
        outcome = f"killed by signal {-code}"
    elif code not in (0, 1) or any(line.startswith("Traceback") for line in error):
        kind, _, message = (error[-1] if error else "").rpartition(": ")
        outcome += f": {kind.rsplit('.', 1)[-1]}: {message}" if kind else f": {message}"
    return seconds, usage.ru_maxrss / 1024.0, outcome


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--old", default=None, help="source tree of the version to compare")
    parser.add_argument("--cap", type=int, default=6_000_000_000,
                        help="address-space limit of each command, bytes")
    parser.add_argument("--columns", type=int, default=40)
    parser.add_argument("--rows", type=int, default=49)
    parser.add_argument("--only", action="append", default=None, choices=list(COMMANDS),
                        help="run only these commands (repeatable)")
    parser.add_argument("--scaling", action="store_true",
                        help="validate walls of 250 to 2,000 planks, both models")
    parser.add_argument("--loose", type=int, default=0, metavar="N",
                        help="N boards stacked face to face, joined to nothing, instead")
    args = parser.parse_args()
    if args.scaling:
        _scaling(args)
        return

    sys.path.insert(0, str(HERE))
    sys.path.insert(0, str(TREE))
    from shelving import shelving_wall

    from furncheck.design import write_design

    trees = [("this", TREE)] + ([("old", Path(args.old).resolve())] if args.old else [])
    commands = args.only or list(COMMANDS)
    with tempfile.TemporaryDirectory() as tmp:
        if args.loose:
            path, dof = Path(tmp) / f"loose-{args.loose}.yaml", "b1.x"
            path.write_text("furncheck: 1\nplanks:\n" + "".join(
                f"  - {{id: b{k}, size: [400, 300], center: [0, 0, {6 + 12 * k}]}}\n"
                for k in range(args.loose)))
            planks = args.loose
        else:
            design = shelving_wall(args.columns, args.rows, heavy_kg=20.0)
            dof = f"shelf{args.columns // 2}_{args.rows // 2}.width"
            path = Path(tmp) / f"shelving-{len(design.planks)}.yaml"
            write_design(design, str(path))
            planks = len(design.planks)
        print(f"{path.name}: {planks} planks, elastic model; one DOF: "
              f"{dof}; cap {args.cap / 1e9:.1f} GB; medians of {args.repeat}\n")
        print("| command       | version | time (s) | peak RSS (MB) | outcome |")
        print("|---------------|---------|---------:|--------------:|---------|")
        for name in commands:
            argv = [part.format(file=path, dof=dof) for part in COMMANDS[name]]
            runs: dict[str, list] = {label: [] for label, _ in trees}
            for _ in range(args.repeat):
                for label, tree in trees:
                    if any(run[2] not in ("exit 0", "exit 1", "exit 2")
                           for run in runs[label]):
                        continue        # failed once: not again
                    runs[label].append(_run(tree, argv, args.cap))
            for label, _ in trees:
                done = runs[label]
                seconds = statistics.median(r[0] for r in done)
                peak = statistics.median(r[1] for r in done)
                print(f"| {name:<13} | {label:<7} | {seconds:>8.1f} | {peak:>13.0f} | "
                      f"{done[-1][2]} |", flush=True)


SCALING_SIZES = ((10, 24), (20, 24), (20, 49), (40, 49))
"""(columns, rows) of the walls of ``--scaling``: 251, 501, 1,001 and 2,001 planks."""


def _scaling(args) -> None:
    """``validate`` time and peak memory by wall size, both models, each tree; the
    exponent k of time ~ planks^k between the two largest walls."""
    import math

    sys.path.insert(0, str(HERE))
    sys.path.insert(0, str(TREE))
    from shelving import shelving_wall

    from furncheck.design import write_design

    trees = [("this", TREE)] + ([("old", Path(args.old).resolve())] if args.old else [])
    print(f"validate, medians of {args.repeat}\n")
    print("| model   | planks | version | time (s) | peak RSS (MB) |")
    print("|---------|-------:|---------|---------:|--------------:|")
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for columns, rows in SCALING_SIZES:
            design = shelving_wall(columns, rows)
            path = Path(tmp) / f"shelving-{len(design.planks)}.yaml"
            write_design(design, str(path))
            paths.append((len(design.planks), path))
        for model in ("rigid", "elastic"):
            times: dict[str, list[float]] = {label: [] for label, _ in trees}
            for planks, path in paths:
                argv = ["validate", str(path), "--format", "json", "--model", model]
                runs: dict[str, list] = {label: [] for label, _ in trees}
                for _ in range(args.repeat):
                    for label, tree in trees:
                        runs[label].append(_run(tree, argv, args.cap))
                for label, _ in trees:
                    seconds = statistics.median(r[0] for r in runs[label])
                    peak = statistics.median(r[1] for r in runs[label])
                    times[label].append(seconds)
                    print(f"| {model:<7} | {planks:>6} | {label:<7} | {seconds:>8.2f} | "
                          f"{peak:>13.0f} |", flush=True)
            span = math.log(paths[-1][0] / paths[-2][0])
            for label, _ in trees:
                exponent = math.log(times[label][-1] / times[label][-2]) / span
                print(f"| {model:<7} | exponent | {label:<7} | {exponent:>8.2f} | |")


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--child":
        _child(sys.argv[2], sys.argv[4:])
    else:
        main()
