"""``python -m furncheck``: the ``furncheck`` command."""

from furncheck.cli.main import run

if __name__ == "__main__":
    run()
