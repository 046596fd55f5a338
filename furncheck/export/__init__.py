"""Exports of a design: plank meshes (GLB, OBJ) and the force-space plot of a change.

    meshes   design_mesh, design_scene, write_meshes   (trimesh)
    plots    plot_force_space, force_space_figure      (matplotlib)
    errors   ExportUnavailable: the ``export`` extra is not installed

trimesh and matplotlib are imported only inside the functions that use them, so importing
this package stays cheap and works without the extra; calling an export without it raises
``ExportUnavailable``.
"""

from furncheck.export.errors import ExportUnavailable
from furncheck.export.meshes import design_mesh, design_scene, write_meshes
from furncheck.export.plots import force_space_figure, plot_force_space

__all__ = ["ExportUnavailable", "design_mesh", "design_scene", "force_space_figure",
           "plot_force_space", "write_meshes"]
