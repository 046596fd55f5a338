"""``furncheck suggest DESIGN``: ranked changes that make an invalid design valid."""

from __future__ import annotations

import click

from furncheck.cli.output import (
    MODEL_OPTION,
    check_output,
    dofs_or_fail,
    fail,
    load_or_fail,
    write_output,
)


@click.command("suggest")
@click.argument("design", metavar="DESIGN")
@click.option("--max-dofs", "max_dofs", type=click.IntRange(1, 4), default=3,
              show_default=True, help="Most DOFs changed together by one suggestion.")
@click.option("--max-suggestions", "max_suggestions", type=click.IntRange(1, 100),
              default=8, show_default=True, help="Most suggestions listed.")
@click.option("--lock", "locks", metavar="DOF", multiple=True,
              help="A DOF that must not change, not even to keep joints together "
                   "(repeatable), e.g. --lock seat.z.")
@click.option("--out", "out_dir", metavar="DIR", default=None,
              help="Write each suggestion there: suggestion-NN.yaml (a complete design "
                   "file), .glb and .obj meshes and a force-space plot (meshes and plots "
                   "need the export extra).")
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text",
              show_default=True, help="Report format.")
@click.option("-o", "--output", metavar="FILE", default=None,
              help="Write the report to FILE instead of standard output.")
@MODEL_OPTION
def suggest(design: str, max_dofs: int, max_suggestions: int, locks: tuple[str, ...],
            out_dir: str | None, fmt: str, output: str | None, model: str | None) -> None:
    """Ranked suggestions that make DESIGN valid: small changes of one to --max-dofs
    plank positions, angles and sizes (continuous, paper section 6.4), then support
    planks to add (discrete, 6.5), each checked with the full statics.  A continuous
    suggestion's design is the middle of its valid interval; every file written with
    --out validates as valid.

    Exit code 0: done (also when the design is valid already, or no suggestion was
    found); 2: unreadable or ill-formed design, unknown DOF or plank, unwritable --out,
    a design too big to check.
    """
    from furncheck.check import refuse_too_big
    from furncheck.errors import DesignTooBig
    from furncheck.export.suggestions import ExportUnavailable, prepare_out_dir, write_files
    from furncheck.report.suggestions import render_json, render_text
    from furncheck.suggest import suggest_design

    check_output(output)
    loaded = load_or_fail(design, model)
    locked = dofs_or_fail(design, loaded, locks)
    if out_dir is not None:
        problem = prepare_out_dir(out_dir)
        if problem:
            fail(f"cannot write suggestions to {out_dir}: {problem}")
    try:
        refuse_too_big(loaded)
    except DesignTooBig as error:
        fail(str(error))
    result = suggest_design(loaded, max_dofs, max_suggestions, locked)
    written = {}
    if out_dir is not None:
        try:
            written = write_files(result, out_dir)
        except ExportUnavailable as missing:
            written = write_files(result, out_dir, meshes=False)
            click.echo(f"furncheck: meshes and plots not written: {missing}", err=True)
        except OSError as error:
            fail(f"cannot write suggestions to {out_dir}: {error.strerror or error}")
    render = render_json if fmt == "json" else render_text
    write_output(render(result, loaded, written), output)
