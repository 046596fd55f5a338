"""The one error of the export package: its optional dependencies are missing.

trimesh and matplotlib are the ``export`` extra of the package; ``validate`` and ``range``
never need them, so they are imported only inside the functions that draw or write meshes,
and their absence is reported as a typed error that the CLI turns into one line.
"""

from __future__ import annotations

from furncheck.errors import FurncheckError

EXPORT_HINT = "meshes and plots need the export extra: pip install 'furncheck[export]'"


class ExportUnavailable(FurncheckError):
    """trimesh or matplotlib is not installed.

    module : the module whose import failed ('trimesh' or 'matplotlib')
    """

    def __init__(self, module: str):
        self.module = module
        super().__init__(EXPORT_HINT)
