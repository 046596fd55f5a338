"""Benchmark: the pictures and meshes of ``suggest --out``, old version against new.

Three tables, each row a median over rounds that alternate between the versions (the
machine's speed drifts, so both meet the same phases):

* force-space plots: the time to draw and write one plot (``plot_force_space``, PNG)
  of a design change, per design, and per load case in it;
* ``suggest --out``: on the 28-plank cabinet made invalid (its 30 kg on the cap becomes
  230 kg at the cap's front right corner, which overloads a joint: the kick board's with
  side_r in the rigid model, 8 suggestions; the cap's with slat_12 in the elastic one,
  4 suggestions), what writing every suggestion's files adds to ``suggest`` alone,
  measured in a fresh process, so it includes importing matplotlib (and, elastic, the
  deflection solve of each view);
* ``validate --html``: what the catalog's report page adds to ``validate designs/`` (this
  version only, whole commands alternately, so imports and the designs' second check for
  the page are included), per design.

Each version runs in child processes with ``PYTHONPATH`` set to its source tree: this
one, and with ``--old PATH`` a worktree of an earlier commit (its library only: the
``--out`` step is its ``write_files``).  One BLAS thread, as the command line runs.

    python benchmarks/bench_pictures.py [--old PATH] [--rounds N]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve()
ROOT = HERE.parents[1]
DESIGNS = ROOT / "designs"
PLOTS = [  # (row name, design file, model, edit of the 'after' side)
    ("bench-tips, panels moved out", "bench-tips.yaml", "rigid", "bench"),
    ("table-slides", "table-slides.yaml", "rigid", None),
    ("cabinet-28", "cabinet-28.yaml", "elastic", None),
    ("cabinet-28, 230 kg on the cap", "cabinet-28.yaml", "rigid", "heavy"),
]
HEAVY_CAP = ("  - {plank: cap, mass: 30, at: [0, 0, 1012]}",
             "  - {plank: cap, mass: 230, at: [550, -180, 1012]}")


def heavy_cabinet(folder: Path) -> Path:
    """designs/cabinet-28.yaml with 230 kg at its cap's front right corner."""
    text = (DESIGNS / "cabinet-28.yaml").read_text()
    assert HEAVY_CAP[0] in text
    path = folder / "cabinet-28-heavy.yaml"
    path.write_text(text.replace(*HEAVY_CAP).replace("name: cabinet-28", "name: cabinet-heavy"))
    return path


# --- children: run in the version under test --------------------------------------------

def child_plots(folder: Path, repeat: int) -> dict:
    """Median seconds of one plot_force_space per PLOTS row (after a warm-up plot)."""
    import dataclasses

    import furncheck.cli  # noqa: F401  (one BLAS thread)
    from furncheck.check import check_design
    from furncheck.design import load_design
    from furncheck.design.model import with_model
    from furncheck.export.plots import plot_force_space

    times = {}
    for name, file, model, edit in PLOTS:
        path = heavy_cabinet(folder) if edit == "heavy" else DESIGNS / file
        design = with_model(load_design(str(path)), model)
        before = check_design(design)
        after = before
        if edit == "bench":
            bench = with_model(load_design(str(DESIGNS / "bench.yaml")), model)
            after = check_design(dataclasses.replace(bench, name=design.name,
                                                     load_cases=design.load_cases))
        plot_force_space(before, after, folder / "warm.png")
        runs = []
        for _ in range(repeat):
            start = time.perf_counter()
            plot_force_space(before, after, folder / "plot.png")
            runs.append(time.perf_counter() - start)
        times[name] = {"seconds": statistics.median(runs), "cases": len(before.cases)}
    return times


OUT_MODELS = ("rigid", "elastic")


def child_out(folder: Path, model: str) -> dict:
    """suggest_design's time, and writing every suggestion's files (cold imports)."""
    import inspect

    import furncheck.cli  # noqa: F401
    from furncheck.design import load_design
    from furncheck.design.model import with_model
    from furncheck.export import suggestions
    from furncheck.suggest import suggest_design

    design = with_model(load_design(str(heavy_cabinet(folder))), model)
    start = time.perf_counter()
    result = suggest_design(design)
    suggested = time.perf_counter() - start
    out = folder / "out"
    out.mkdir()
    start = time.perf_counter()
    if "design" in inspect.signature(suggestions.write_files).parameters:
        from furncheck.report.suggestions import advice

        titles = {s.rank: advice(s, design) for s in result.suggestions}
        suggestions.write_files(result, str(out), design, True, titles)
    else:
        suggestions.write_files(result, str(out))
    written = time.perf_counter() - start
    return {"suggest": suggested, "out": written, "suggestions": len(result.suggestions),
            "files": len(list(out.iterdir()))}


# --- parent -----------------------------------------------------------------------------

def run_child(tree: Path, job: str, repeat: int, model: str = "rigid") -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree), OPENBLAS_NUM_THREADS="1",
               OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as folder:
        done = subprocess.run([sys.executable, str(HERE), "--child", job, "--folder", folder,
                               "--repeat", str(repeat), "--model", model], env=env,
                              capture_output=True, text=True, check=True, cwd=folder)
    return json.loads(done.stdout)


def html_costs(rounds: int) -> None:
    """``validate designs/`` and ``validate designs/ --html FILE`` (this version, through
    the installed command line, no cache), alternately in fresh processes: what the page
    adds per design, medians of ``rounds`` runs each."""
    designs = sorted(DESIGNS.rglob("*.yaml"))
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    times: dict[str, list[float]] = {"validate": [], "validate --html": []}
    with tempfile.TemporaryDirectory() as folder:
        page = Path(folder) / "catalog.html"
        base = [sys.executable, "-m", "furncheck", "validate", str(DESIGNS), "--no-cache"]
        for _ in range(rounds + 1):           # the first round writes bytecode: not counted
            for name, command in (("validate", base),
                                  ("validate --html", [*base, "--html", str(page)])):
                start = time.perf_counter()
                subprocess.run(command, env=env, cwd=folder, capture_output=True, check=False)
                times[name].append(time.perf_counter() - start)
        size = page.stat().st_size
    alone, with_page = (statistics.median(times[name][1:]) for name in times)
    print(f"\nvalidate --html on the catalog ({len(designs)} designs; median of {rounds})\n")
    print("| validate alone (s) | with --html (s) | --html adds (s) | per design (ms) | "
          "page (kB) |")
    print("|---:|---:|---:|---:|---:|")
    print(f"| {alone:.2f} | {with_page:.2f} | {with_page - alone:.2f} | "
          f"{1000 * (with_page - alone) / len(designs):.1f} | {size / 1024:.0f} |")


def main(old: Path | None, rounds: int, repeat: int) -> None:
    versions = {"new": ROOT} | ({"old": old} if old else {})
    plots: dict[str, list[dict]] = {name: [] for name in versions}
    outs: dict[tuple, list[dict]] = {(name, model): [] for model in OUT_MODELS
                                     for name in versions}
    for _ in range(rounds):
        for name, tree in versions.items():
            plots[name].append(run_child(tree, "plots", repeat))
            for model in OUT_MODELS:
                outs[(name, model)].append(run_child(tree, "out", repeat, model))
    names = list(versions)
    print("force-space plot, one PNG (ms; median of "
          f"{rounds} x {repeat} runs per version)\n")
    print("| design | cases | " + " | ".join(f"{n} (ms) | {n} per case (ms)" for n in names)
          + " |")
    print("|---|---:|" + "---:|---:|" * len(names))
    for row, *_ in PLOTS:
        cells = []
        for name in names:
            ms = 1000 * statistics.median(run[row]["seconds"] for run in plots[name])
            cases = plots[name][0][row]["cases"]
            cells.append(f"{ms:.0f} | {ms / cases:.0f}")
        print(f"| {row} | {plots[names[0]][0][row]['cases']} | " + " | ".join(cells) + " |")
    print(f"\nsuggest --out on the cabinet with 230 kg on its cap (median of {rounds})\n")
    print("| model | version | suggestions | files | suggest alone (s) | --out adds (s) | "
          "per suggestion (ms) |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for model, name in ((model, name) for model in OUT_MODELS for name in names):
        runs = outs[(name, model)]
        out = statistics.median(run["out"] for run in runs)
        count = runs[0]["suggestions"]
        print(f"| {model} | {name} | {count} | {runs[0]['files']} | "
              f"{statistics.median(run['suggest'] for run in runs):.2f} | {out:.2f} | "
              f"{1000 * out / max(count, 1):.0f} |")
    html_costs(rounds)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old", type=Path, default=None,
                        help="source tree of the version to compare with")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--repeat", type=int, default=3,
                        help="plots timed per design in each child")
    parser.add_argument("--child", choices=["plots", "out"], help=argparse.SUPPRESS)
    parser.add_argument("--folder", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--model", default="rigid", help=argparse.SUPPRESS)
    arguments = parser.parse_args()
    if arguments.child == "plots":
        print(json.dumps(child_plots(arguments.folder, arguments.repeat)))
    elif arguments.child == "out":
        print(json.dumps(child_out(arguments.folder, arguments.model)))
    else:
        main(arguments.old, arguments.rounds, arguments.repeat)
