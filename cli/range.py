"""``furncheck range DESIGN [DOF...]``: the valid interval of each design DOF."""

from __future__ import annotations

import click

from furncheck.cli.output import (
    MODEL_OPTION,
    SCHEDULER_OPTION,
    STDIN_FILENAME_OPTION,
    WholeNumber,
    check_not_an_input,
    check_output,
    client_or_fail,
    config_or_fail,
    dofs_or_fail,
    fail,
    fail_as,
    load_or_fail,
    write_output,
)


@click.command("range")
@click.argument("design", metavar="DESIGN")
@click.argument("dofs", metavar="[DOF...]", nargs=-1)
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text",
              show_default=True, help="Report format.")
@click.option("--lock", "locks", metavar="DOF", multiple=True,
              help="A DOF that must not change, not even to keep joints together "
                   "(repeatable), e.g. --lock seat.z.")
@click.option("-o", "--output", metavar="FILE", default=None,
              help="Write the report to FILE instead of standard output.")
@click.option("-j", "--jobs", type=WholeNumber(1), default=None,
              help="Worker processes for many DOFs, at most the CPUs this run may use (its "
                   "affinity, a container's CPU quota); the output is the same.  [default: "
                   "all usable CPUs]")
@MODEL_OPTION
@SCHEDULER_OPTION
@STDIN_FILENAME_OPTION
def range_command(design: str, dofs: tuple[str, ...], fmt: str, locks: tuple[str, ...],
                  output: str | None, jobs: int | None, model: str | None,
                  scheduler: str | None, stdin_filename: str | None) -> None:
    """Valid interval of each DOF of DESIGN, the others held fixed (their neighbours
    adjusted to keep the joints).  DOFs are <plank>.x|y|z (translation, length unit),
    <plank>.rx|ry|rz (rotation about world axes, degrees) and <plank>.length|width;
    with none named, all are listed.

    Exit code 0: done; 2: unreadable or ill-formed design, unknown DOF or plank, a design
    too big to check, a Dask cluster (--scheduler) that cannot be used.
    """
    from furncheck.errors import ClusterError, DesignTooBig
    from furncheck.ranges import RangeFinder
    from furncheck.report.ranges import render_json, render_text
    from furncheck.workers import local_jobs

    config = config_or_fail((design,), stdin_filename)
    model = model or config.model
    check_output(output)
    check_not_an_input(output, (design,))
    loaded = load_or_fail(design, model, stdin_filename, fmt, output)
    design = loaded.source          # the path as given, or the name of standard input
    dofs_or_fail(design, loaded, (*dofs, *locks), fmt, output)
    client = client_or_fail(scheduler)
    try:
        finder = RangeFinder(loaded, tuple(locks))
        jobs = jobs or config.jobs
        ranges = finder.ranges(list(dofs) or None,
                               local_jobs(jobs) if client is None else jobs or 1, client)
    except ClusterError as error:
        fail(str(error))
    except DesignTooBig as error:
        fail_as(design, str(error), fmt, output)
    finally:
        if client is not None:
            client.close()
    render = render_json if fmt == "json" else render_text
    write_output(render(design, ranges), output)
