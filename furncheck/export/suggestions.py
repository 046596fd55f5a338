"""The files of ``furncheck suggest --out DIR``: the design's own view and meshes, and per
suggestion its design file (the very text that was validated), its coloured meshes, its
force-space plot and its before/after view.

    DIR/<name>-view.png  DIR/<name>.glb  DIR/<name>.obj  DIR/<name>.mtl     the design
    DIR/suggestion-01.yaml  .glb  .obj  .mtl  -forces.png  -view.png        suggestion 1
    DIR/index.html        the report page (``write_page``: the design, every suggestion)

``<name>`` is the design's name made a file name (``folders.file_stem``: nothing outside
DIR), ``design-<name>`` where it would read as a suggestion's.  The folder is the run's:
before writing, the files an earlier run of the same design wrote there are removed (only
names this run would write: a stale suggestion-04.yaml does not stay beside a new 01-03),
and nothing else is touched.
When the folder holds another design's suggestion-NN.yaml (its ``name`` says whose it
is), this run names its suggestion files after its design, ``<name>-suggestion-01.yaml``
and so on, so several designs can share a folder.  Pictures (PNG) need matplotlib (imported
only to draw) and can be left out (``pictures=False``); meshes and design files need
nothing beyond numpy.  Pictures take most of the time: with several suggestions they are
drawn in worker processes, one per core (``draw_in_parallel``).
"""

from __future__ import annotations

import multiprocessing
import os
import re
from collections.abc import Callable
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

from furncheck.design.model import Design
from furncheck.export.errors import ExportUnavailable
from furncheck.export.findings import changed_planks
from furncheck.export.folders import file_stem, pictures_missing, prepare_out_dir
from furncheck.export.meshes import write_meshes
from furncheck.files import utf8, write_atomically
from furncheck.workers import pool_options, process_pool, usable_cpus

if TYPE_CHECKING:
    from furncheck.suggest import SuggestionReport

__all__ = ["ExportUnavailable", "Written", "pictures_missing", "prepare_out_dir",
           "suggestion_prefix", "write_files", "write_page"]

SUGGESTION_FILE = re.compile(
    r"^(?P<prefix>.*?)suggestion-(?P<rank>\d{2,})(?:\.yaml|\.glb|\.obj|\.mtl|-forces\.png"
    r"|-view\.png)$")
"""Names of the files written for a suggestion, after the optional '<name>-' prefix."""
DESIGN_SUFFIXES = (".glb", ".obj", ".mtl", "-view.png", "-index.html")
"""Suffixes of the files written for the design itself, after its name."""
NAME_LINE = re.compile(r"^name:\s*(['\"]?)(?P<name>.*?)\1\s*$", re.MULTILINE)
HEAD_BYTES = 4096
"""How much of a suggestion file is read to find its ``name``."""


@dataclass(frozen=True)
class Written:
    """Files written for one suggestion (or, under rank 0, for the design itself); paths
    as strings, under the DIR given.  ``plots``: its pictures, the force-space plot then
    the view."""

    design_file: str | None = None
    meshes: tuple[str, ...] = ()
    plots: tuple[str, ...] = ()


def design_stem(name: str) -> str:
    """The stem of the files of design ``name`` itself (module docstring)."""
    stem = file_stem(name)
    return f"design-{stem}" if SUGGESTION_FILE.match(f"{stem}.yaml") else stem


def suggestion_prefix(out_dir: str, name: str) -> str:
    """'' when the plain names suggestion-NN.* are free for design ``name`` in
    ``out_dir`` (no other design's suggestion-NN.yaml there), else '<name>-' (its
    ``design_stem``)."""
    for entry in _entries(out_dir):
        match = SUGGESTION_FILE.match(entry)
        if match and not match["prefix"] and entry.endswith(".yaml") \
                and _owner(Path(out_dir) / entry) != f"{name}-suggestion-{match['rank']}":
            return f"{design_stem(name)}-"
    return ""


def stale_files(out_dir: str, name: str, prefix: str) -> list[str]:
    """The files of earlier runs of design ``name`` in ``out_dir`` (sorted names): its
    own view and meshes, its '<name>-suggestion-NN' files, and, when this run uses the
    plain names (``prefix`` ''), the plain suggestion-NN files."""
    stem = design_stem(name)
    stale = []
    for entry in _entries(out_dir):
        match = SUGGESTION_FILE.match(entry)
        if match and match["prefix"] in {f"{stem}-", prefix}:
            stale.append(entry)
        elif any(entry == f"{stem}{suffix}" for suffix in DESIGN_SUFFIXES):
            stale.append(entry)
    return stale


def write_files(result: SuggestionReport, out_dir: str, design: Design,
                pictures: bool = True, titles: dict[int, str] | None = None
                ) -> dict[int, Written]:
    """Write the design's and every suggestion's files (module docstring); rank ->
    what was written, rank 0 the design's own files.  ``design``: the design suggested
    for (``result.report`` is its validation); ``titles``: per rank, what the suggestion
    changes (the plots' headings).  Raises ExportUnavailable, before writing anything,
    when pictures are wanted and matplotlib is missing."""
    if pictures and (missing := pictures_missing()) is not None:
        raise missing
    titles = titles or {}
    prefix = suggestion_prefix(out_dir, design.name)
    for entry in stale_files(out_dir, design.name, prefix):
        os.remove(Path(out_dir) / entry)

    own = Path(out_dir) / design_stem(design.name)
    written = {0: Written(None, tuple(write_meshes(design, own, result.report)))}
    jobs = []
    for suggestion in result.suggestions:
        stem = Path(out_dir) / f"{prefix}suggestion-{suggestion.rank:02d}"
        design_file = f"{stem}.yaml"
        write_atomically(design_file, utf8(suggestion.text))
        marks = changed_planks(design, suggestion.design)
        meshes = tuple(write_meshes(suggestion.design, stem, suggestion.report, marks))
        written[suggestion.rank] = Written(design_file, meshes)
        jobs.append(partial(_pictures, design, result, suggestion, marks, stem,
                            titles.get(suggestion.rank)))
    if not pictures:
        return written
    from furncheck.export.views import design_panel, view_png

    before = design_panel(design, result.report)       # its deflection solved once
    view = Path(f"{own}-view.png")
    write_atomically(str(view), view_png([before]))   # (and every import made, once)
    written[0] = Written(None, written[0].meshes, (str(view),))
    for suggestion, plots in zip(result.suggestions,
                                 draw_in_parallel([partial(job, before) for job in jobs])):
        written[suggestion.rank] = replace(written[suggestion.rank], plots=plots)
    return written


_JOBS: list[Callable[[], tuple[str, ...]]] = []
"""The jobs of ``draw_in_parallel``, for its forked workers (which inherit them)."""


def draw_in_parallel(jobs: list[Callable[[], tuple[str, ...]]]) -> list[tuple[str, ...]]:
    """Run the jobs (each draws and writes pictures, returning their paths) and return
    their results in order: in worker processes forked from this one, one per usable CPU
    (``workers.usable_cpus``; the
    jobs need not be pickled: the workers inherit them), or here, one after the other,
    with one core, one job, or no fork on this system.  A job's OSError reaches the
    caller either way."""
    workers = min(len(jobs), usable_cpus())
    if workers < 2 or "fork" not in multiprocessing.get_all_start_methods():
        return [job() for job in jobs]
    global _JOBS
    _JOBS = jobs
    try:
        with process_pool(max_workers=workers, mp_context=multiprocessing.get_context("fork"),
                          **pool_options()) as pool:
            return list(pool.map(_run_job, range(len(jobs))))
    except BrokenProcessPool:            # a worker died: draw here instead
        return [job() for job in jobs]
    finally:
        _JOBS = []


def _run_job(index: int) -> tuple[str, ...]:
    return _JOBS[index]()


def _pictures(design: Design, result: SuggestionReport, suggestion, marks: dict[str, str],
              stem: Path, title: str | None, before) -> tuple[str, str]:
    """The force-space plot and the before/after view of one suggestion."""
    from furncheck.export.plots import force_space_png
    from furncheck.export.views import suggestion_view_png

    heading = f"{design.name}, suggestion {suggestion.rank}" + (f": {title}" if title else "")
    forces = Path(f"{stem}-forces.png")
    change = f"suggestion {suggestion.rank}" + (f": {title}" if title else "")
    write_atomically(str(forces), force_space_png(result.report, suggestion.report,
                                       design.material.friction, change,
                                       suggestion.design.material.friction))
    view = Path(f"{stem}-view.png")
    write_atomically(str(view), suggestion_view_png(design, result.report, suggestion.design,
                                         suggestion.report, heading, marks, before))
    return str(forces), str(view)


def _entries(out_dir: str) -> list[str]:
    try:
        with os.scandir(out_dir) as entries:
            return sorted(entry.name for entry in entries if entry.is_file())
    except OSError:
        return []


def _owner(path: Path) -> str | None:
    """The ``name`` a suggestion's design file gives (None when it has none)."""
    try:
        with open(path, encoding="utf-8", errors="replace") as stream:
            head = stream.read(HEAD_BYTES)
    except OSError:
        return None
    match = NAME_LINE.search(head)
    return match["name"] if match else None


def write_page(out_dir: str, design: Design, result: SuggestionReport,
               written: dict[int, Written], document: dict) -> str:
    """Write the folder's report page (``report.pages.suggestion_page``): ``index.html``,
    or ``<name>-index.html`` where the suggestion files are named after the design; its
    path.  ``document``: the suggest JSON (parsed).  The meshes written are embedded in
    it, the pictures linked by their names (they sit beside it)."""
    from furncheck.report.pages import PageDesign, suggestion_page

    def shown(rank: int, report, shown_design: Design) -> PageDesign:
        files = written.get(rank, Written())
        glb = next((Path(path).read_bytes() for path in files.meshes
                    if path.endswith(".glb")), None)
        return PageDesign(report, shown_design, glb,
                          tuple(Path(path).name for path in files.plots))

    page = suggestion_page(document, shown(0, result.report, design),
                           {s.rank: shown(s.rank, s.report, s.design)
                            for s in result.suggestions})
    path = Path(out_dir) / f"{suggestion_prefix(out_dir, design.name)}index.html"
    write_atomically(str(path), utf8(page))
    return str(path)
