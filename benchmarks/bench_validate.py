"""Benchmark: in-process `validate` time by design size, and the cold command.

Prints a table: planks, joints, contacts, load cases, median time of ``check_file`` on a
YAML file (load + geometry + statics + verdicts, all cases) in the rigid and in the
elastic model, side by side in one run, and their ratio; then the median wall time of
``furncheck validate`` on one small catalog file as a fresh process.

    python benchmarks/bench_validate.py [--repeat N]

Targets on the project's 2-core machine: a 28-plank design <= 20 ms (rigid), the elastic
model at most 2x the rigid one on the 28-plank cabinet, a 400-plank design <= 1 s in both,
the cold command on a small file at most 1.5x ``python -c "import numpy, yaml, click"``
(printed beside it, both after a warm-up run that writes their bytecode).  numpy runs with
one BLAS thread, as the command line runs it: set here whatever the environment says,
before numpy is imported (``benchmarks/bench_catalog.py`` has the cold start of the old
and new trees side by side).
"""

from __future__ import annotations

import os

for _threads in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_threads] = "1"      # one BLAS thread, as the command line runs

import argparse  # noqa: E402
import shutil  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from shelving import SIZES, shelving_wall  # noqa: E402

from furncheck.check import check_file  # noqa: E402
from furncheck.design import write_design  # noqa: E402

CATALOG = HERE.parent / "designs"


def _median_seconds(action, repeat: int) -> float:
    action()                                   # warm-up: imports, caches
    samples = []
    for _ in range(repeat):
        _forget_plates()
        start = time.perf_counter()
        action()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def _forget_plates() -> None:
    """Empty the factored plates and their readings kept from the run before
    (``statics.plate_mesh``, ``statics.plates``), so that each run pays for its own, as
    the first check of a design in a process does (a tree without plates, or without
    kept readings, has nothing to empty)."""
    try:
        from furncheck.statics.plate_mesh import plate_grid
    except ImportError:
        try:                                    # a tree before plate_mesh was split off
            from furncheck.statics.plates import _plate_grid as plate_grid
        except ImportError:
            return
    plate_grid.cache_clear()
    from furncheck.statics import plates

    readings = getattr(plates, "_READINGS", None)
    if readings is not None:
        readings.clear()


def _row(label: str, path: Path, repeat: int) -> str:
    report = check_file(str(path), "rigid")
    if report.error:
        raise SystemExit(f"{path}: {report.error}")
    times = {}
    for model in ("rigid", "elastic"):
        times[model] = _median_seconds(lambda m=model: check_file(str(path), m), repeat)
    case = report.cases[0]
    joints = len(case.joints)
    planks = len({p for j in case.joints for p in j.planks}) or 1
    return (f"| {label:<28} | {planks:>6} | {joints:>6} | {len(case.contacts):>8} | "
            f"{len(report.cases):>5} | {times['rigid'] * 1000:>10.1f} | "
            f"{times['elastic'] * 1000:>12.1f} | {times['elastic'] / times['rigid']:>5.2f} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=15)
    args = parser.parse_args()
    print("| design                       | planks | joints | contacts | cases | rigid (ms) |"
          " elastic (ms) | ratio |")
    print("|------------------------------|-------:|-------:|---------:|------:|-----------:|"
          "-------------:|------:|")
    with tempfile.TemporaryDirectory() as tmp:
        for target, (columns, rows) in SIZES.items():
            path = Path(tmp) / f"shelving-{target}.yaml"
            write_design(shelving_wall(columns, rows), str(path))
            print(_row(f"shelving wall ~{target}", path, args.repeat if target < 400 else 5))
    for name in ("cabinet-28.yaml", "bookshelf-20.yaml"):
        if (CATALOG / name).exists():
            print(_row(f"designs/{name}", CATALOG / name, args.repeat))

    beside = Path(sys.executable).with_name("furncheck")
    command = str(beside) if beside.exists() else shutil.which("furncheck")
    small = CATALOG / "stool.yaml"
    if command and small.exists():
        env = dict(os.environ)
        env.pop("PYTHONDONTWRITEBYTECODE", None)        # as after a first run
        commands = {"floor": [sys.executable, "-c", "import numpy, yaml, click"],
                    "validate": [command, "validate", str(small)],
                    "validate --no-cache": [command, "validate", str(small), "--no-cache"]}
        runs: dict[str, list[float]] = {name: [] for name in commands}
        for k in range(8):                              # the first run warms up
            for name, line in commands.items():
                start = time.perf_counter()
                subprocess.run(line, capture_output=True, check=False, env=env)
                if k:
                    runs[name].append(time.perf_counter() - start)
        floor = statistics.median(runs["floor"])
        print()
        for name in ("validate", "validate --no-cache"):
            cold = statistics.median(runs[name])
            what = "its result cached by the warm-up run" if name == "validate" else \
                "checked anew"
            print(f"cold `furncheck {name} designs/{small.name}` ({what}): median "
                  f"{cold * 1000:.0f} ms over {len(runs[name])} runs, {cold / floor:.2f}x "
                  f"`python -c \"import numpy, yaml, click\"` ({floor * 1000:.0f} ms) in "
                  f"the same runs")


if __name__ == "__main__":
    main()
