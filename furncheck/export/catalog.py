"""``furncheck validate --views DIR``: the view of every design of a catalog.

Each design that could be read gets ``DIR/<name>-view.png`` (``views.design_view_png``:
coloured by utilization, the loads of its governing case, failing joints and contacts,
the deflected shape in the elastic model; ``<name>`` the design's name made a file name,
``folders.file_stem``); a second design of the same name gets ``<name>-2-view.png``, the
next free number where that is taken (by a design named ``<name>-2``), in the order of
the report.  The views are drawn in worker processes, one per core
(``suggestions.draw_in_parallel``).
"""

from __future__ import annotations

from functools import partial
from pathlib import Path

from furncheck.result import DesignReport


def view_names(reports: list[DesignReport] | tuple[DesignReport, ...]) -> list[str | None]:
    """Per report, the file name of its view (None for a design that could not be read),
    no two the same, not even but for case (a folder may ignore it)."""
    from furncheck.export.folders import file_stem

    taken: set[str] = set()
    names: list[str | None] = []
    for report in reports:
        if report.valid is None:
            names.append(None)
            continue
        stem, count = file_stem(report.name), 1
        name = f"{stem}-view.png"
        while name.casefold() in taken:
            count += 1
            name = f"{stem}-{count}-view.png"
        taken.add(name.casefold())
        names.append(name)
    return names


def write_catalog_views(reports: list[DesignReport] | tuple[DesignReport, ...], out_dir: str,
                        model: str | None = None) -> list[str]:
    """Write the view of every readable design of ``reports`` (validated in ``model``
    when given: the command line's ``--model``) into the existing folder ``out_dir``;
    return the paths written, in report order."""
    from furncheck.check import load_checked
    from furncheck.design.model import with_model
    from furncheck.errors import DesignError
    from furncheck.export.suggestions import draw_in_parallel
    from furncheck.export.views import view_figure_modules

    view_figure_modules()          # imported once here, not in every worker
    jobs = []
    for report, name in zip(reports, view_names(reports)):
        if name is None:
            continue
        try:
            design = with_model(load_checked(report.design), model)
        except DesignError:      # changed since it was checked: its report says enough
            continue
        jobs.append(partial(_write_view, design, report, Path(out_dir) / name))
    return [path for (path,) in draw_in_parallel(jobs)]


def _write_view(design, report: DesignReport, path: Path) -> tuple[str]:
    from furncheck.export.views import design_view_png
    from furncheck.files import write_atomically

    write_atomically(str(path), design_view_png(design, report))
    return (str(path),)


def write_catalog_page(reports: list[DesignReport] | tuple[DesignReport, ...], path: str,
                       title: str = "furncheck catalog") -> None:
    """``validate --html FILE``: the catalog page (``report.pages.catalog_page``) of
    ``reports``, each readable design read again for its view, written atomically (an
    interrupted run leaves an earlier page whole)."""
    from furncheck.check import load_checked
    from furncheck.errors import DesignError
    from furncheck.files import utf8, write_atomically
    from furncheck.report.pages import CatalogEntry, catalog_page

    entries = []
    for report in reports:
        design = None
        if report.error is None and Path(report.design).is_file():
            try:
                design = load_checked(report.design)
            except DesignError:  # changed since it was checked: its report says enough
                design = None
        entries.append(CatalogEntry(report, design))
    write_atomically(path, utf8(catalog_page(entries, title)))
