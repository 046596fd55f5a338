"""The one error of the export package: its optional dependencies are missing.

matplotlib is the ``export`` extra of the package; ``validate`` and ``range`` never need
it, so it is imported only inside the functions that draw, and its absence is reported
as a typed error that the CLI turns into one line.  (Meshes are written with numpy.)
"""

from __future__ import annotations

from furncheck.errors import FurncheckError

EXPORT_HINT = "pictures need the export extra: pip install 'furncheck[export]'"


class ExportUnavailable(FurncheckError):
    """matplotlib is not installed.

    module : the module whose import failed ('matplotlib')
    """

    def __init__(self, module: str):
        self.module = module
        super().__init__(EXPORT_HINT)
