"""Benchmark: instructions per check, in both models, for trees side by side (valgrind).

This machine's speed drifts by up to 2x from one minute to the next, so that timings of
two versions, even alternated, differ by more than most changes do.  The number of
machine instructions a check executes does not drift: this script counts them with
valgrind's callgrind tool (``valgrind`` must be installed; it runs the code about 50
times slower) and prints, per design, model and tree, the instructions of one in-process
``check_file`` (load, geometry, statics, verdicts of every case) in millions:

    python benchmarks/bench_instructions.py [--old TREE] [--repeat N] [DESIGN ...]

Each count is the difference between a process that checks the design 1 + N times and
one that checks it once (the imports, the first check's warm-up and valgrind's own start
cancel), divided by N (default 2).  Default designs: the catalog's cabinet and bookshelf,
whose elastic checks are the slow ones.  TREE is a source tree of furncheck (e.g. a git
worktree of an older commit), run under this Python; numpy runs with one BLAS thread, as
the command line runs it.  Instructions are not time (a cache miss costs more than an
addition), but a change that executes 10 % fewer instructions on the same numpy calls is
faster by about as much.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

NEW_TREE = Path(__file__).resolve().parents[1]
DEFAULT_DESIGNS = ("designs/cabinet-28.yaml", "designs/bookshelf-20.yaml")

CHECKS = """\
import os, sys
os.environ.update(OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
sys.path.insert(0, sys.argv[1])
from furncheck.check import check_file
path, model, count = sys.argv[2], sys.argv[3], int(sys.argv[4])
for _ in range(count):
    report = check_file(path, model)
    if report.error:
        raise SystemExit(report.error)
"""


def instructions(tree: Path, design: Path, model: str, checks: int) -> int:
    """Instructions that valgrind counts for a process checking ``design`` ``checks``
    times with ``tree``'s furncheck."""
    with tempfile.TemporaryDirectory() as folder:
        script = Path(folder) / "checks.py"
        script.write_text(CHECKS)
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
        env.pop("PYTHONPATH", None)
        result = subprocess.run(
            ["valgrind", "--tool=callgrind", f"--callgrind-out-file={folder}/out",
             sys.executable, str(script), str(tree), str(design), model, str(checks)],
            capture_output=True, text=True, env=env, check=False)
    found = re.search(r"Collected\s*:\s*(\d+)", result.stderr)
    if result.returncode != 0 or found is None:
        raise SystemExit(f"valgrind failed on {design} ({model}, {tree}):\n"
                         f"{result.stderr[-2000:]}")
    return int(found.group(1))


def per_check(tree: Path, design: Path, model: str, repeat: int) -> float:
    """Millions of instructions of one check (see the module docstring)."""
    once = instructions(tree, design, model, 1)
    more = instructions(tree, design, model, 1 + repeat)
    return (more - once) / repeat / 1e6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("designs", nargs="*", default=list(DEFAULT_DESIGNS))
    parser.add_argument("--old", type=Path, help="an older source tree to compare with")
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    if shutil.which("valgrind") is None:
        raise SystemExit("valgrind is not installed (apt-get install valgrind)")
    trees = {"new": NEW_TREE} if args.old is None else {"old": args.old.resolve(),
                                                        "new": NEW_TREE}
    columns = " | ".join(f"{side} rigid | {side} elastic | {side} ratio" for side in trees)
    print(f"| design | {columns} |")
    print("|---|" + "---:|" * (3 * len(trees)))
    for name in args.designs:
        design = (NEW_TREE / name) if not Path(name).is_absolute() else Path(name)
        cells = []
        for tree in trees.values():
            rigid = per_check(tree, design, "rigid", args.repeat)
            elastic = per_check(tree, design, "elastic", args.repeat)
            cells += [f"{rigid:.1f} M", f"{elastic:.1f} M", f"{elastic / rigid:.2f}"]
        print(f"| {design.name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
