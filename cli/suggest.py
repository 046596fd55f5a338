"""``furncheck suggest DESIGN``: ranked changes that make an invalid design valid."""

from __future__ import annotations

import json

import click

from furncheck.cli.output import (
    MODEL_OPTION,
    STDIN_FILENAME_OPTION,
    WholeNumber,
    check_not_an_input,
    check_output,
    config_or_fail,
    dofs_or_fail,
    fail,
    fail_as,
    load_or_fail,
    write_output,
)
from furncheck.tolerances import MAX_COMBINED_DOFS


def _combined_dofs(value: int) -> int:
    """--max-dofs, refused outside 1..MAX_COMBINED_DOFS with the reason."""
    if value < 1:
        raise click.BadParameter(f"{value}: one suggestion changes 1 to {MAX_COMBINED_DOFS} "
                                 "DOFs together")
    if value > MAX_COMBINED_DOFS:
        raise click.BadParameter(
            f"{value}: one suggestion changes 1 to {MAX_COMBINED_DOFS} DOFs together (the "
            f"combinations of {MAX_COMBINED_DOFS + 1} of a large design's DOFs take minutes "
            f"to form; see the README)")
    return value


@click.command("suggest")
@click.argument("design", metavar="DESIGN")
@click.option("--max-dofs", "max_dofs", type=int, default=3, show_default=True,
              callback=lambda _ctx, _param, value: _combined_dofs(value),
              help=f"Most DOFs changed together by one suggestion, 1 to {MAX_COMBINED_DOFS} "
                   f"(their combinations grow as C(n, M): 5 takes minutes on a large "
                   f"design).")
@click.option("--max-suggestions", "max_suggestions", type=WholeNumber(1, 100),
              default=8, show_default=True, help="Most suggestions listed.")
@click.option("--lock", "locks", metavar="DOF", multiple=True,
              help="A DOF that must not change, not even to keep joints together "
                   "(repeatable), e.g. --lock seat.z.")
@click.option("--out", "out_dir", metavar="DIR", default=None,
              help="Write each suggestion there: suggestion-NN.yaml (a complete design "
                   "file), coloured .glb and .obj/.mtl meshes, a force-space plot and a "
                   "before/after view; and the design's "
                   "own view and meshes.  Files of an earlier run of the design there are "
                   "replaced; beside another design's, files are named after the design.")
@click.option("--no-plots", "no_plots", is_flag=True, default=False,
              help="With --out: write no pictures (PNG), only design files and meshes.")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text",
              show_default=True, help="Report format.")
@click.option("-o", "--output", metavar="FILE", default=None,
              help="Write the report to FILE instead of standard output.")
@MODEL_OPTION
@STDIN_FILENAME_OPTION
def suggest(design: str, max_dofs: int, max_suggestions: int, locks: tuple[str, ...],
            out_dir: str | None, no_plots: bool, fmt: str, output: str | None,
            model: str | None, stdin_filename: str | None) -> None:
    """Ranked suggestions that make DESIGN valid: small changes of one to --max-dofs
    plank positions, angles and sizes (continuous, paper section 6.4; symmetric changes of
    mirror planks first) and support planks to add (discrete, 6.5), each checked with the
    full statics and listed with its cut list (every plank it changes, from -> to).  A
    continuous suggestion's interval is where it is valid, both ends checked; its design
    is the smallest change plus a reserve.  Ranked by the shop's score: plausible
    proportions, the design's symmetry kept, the smallest relative change of the fewest
    planks.  Every file written with --out validates as valid.

    With fewer suggestions than --max-suggestions (none at all, too), it says what each
    violation would need (hand statics) and what the search tried.

    Exit code 0: done (also when the design is valid already, or no suggestion was
    found); 2: unreadable or ill-formed design, unknown DOF or plank, unwritable --out,
    a design too big to check.
    """
    from furncheck.check import refuse_too_big
    from furncheck.errors import DesignTooBig
    from furncheck.export.suggestions import (
        ExportUnavailable,
        prepare_out_dir,
        write_files,
        write_page,
    )
    from furncheck.report.suggestions import advice, render_json, render_text
    from furncheck.suggest import suggest_design

    config = config_or_fail((design,), stdin_filename)
    model = model or config.model
    check_output(output)
    check_not_an_input(output, (design,))
    loaded = load_or_fail(design, model, stdin_filename, fmt, output)
    design = loaded.source          # the path as given, or the name of standard input
    locked = dofs_or_fail(design, loaded, locks, fmt, output)
    if out_dir is not None:
        problem = prepare_out_dir(out_dir)
        if problem:
            fail(f"cannot write suggestions to {out_dir}: {problem}")
    try:
        refuse_too_big(loaded)
    except DesignTooBig as error:
        fail_as(design, str(error), fmt, output)
    result = suggest_design(loaded, max_dofs, max_suggestions, locked)
    written = {}
    if out_dir is not None:
        titles = {s.rank: advice(s, loaded) for s in result.suggestions}
        try:
            try:
                written = write_files(result, out_dir, loaded, not no_plots, titles)
            except ExportUnavailable as missing:    # (``pictures_missing``: raised before
                # any file is written) the files without their pictures, and a note
                click.echo(f"furncheck: pictures not written: {missing}", err=True)
                written = write_files(result, out_dir, loaded, False, titles)
        except OSError as error:
            fail(f"cannot write suggestions to {out_dir}: {error.strerror or error}")
        try:
            write_page(out_dir, loaded, result, written,
                       json.loads(render_json(result, loaded, written)))
        except OSError as error:
            fail(f"cannot write the report page to {out_dir}: {error.strerror or error}")
    render = render_json if fmt == "json" else render_text
    write_output(render(result, loaded, written), output)
