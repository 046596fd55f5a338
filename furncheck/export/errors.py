"""The one error of the export package: matplotlib cannot be imported.

matplotlib is a dependency of the package, but ``validate`` and ``range`` never need it,
so it is imported only inside the functions that draw; where it is missing all the same
(an environment installed without dependencies, a broken install) that is reported as a
typed error that the CLI turns into one line.  (Meshes are written with numpy.)
"""

from __future__ import annotations

from furncheck.errors import FurncheckError

EXPORT_HINT = "pictures need matplotlib, which cannot be imported: pip install matplotlib"


class ExportUnavailable(FurncheckError):
    """matplotlib cannot be imported.

    module : the module whose import failed ('matplotlib')
    """

    def __init__(self, module: str):
        self.module = module
        super().__init__(EXPORT_HINT)
