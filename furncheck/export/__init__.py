"""Pictures and meshes of designs and suggestions.

    colours      the utilization scale and the marks of changed and added planks
    findings     what they show: plank utilizations, governing case, failing joints and
                 contacts, changed planks (values only)
    meshes       GLB (metres, Y-up) and OBJ + MTL (file unit), coloured   (numpy only)
    deflection   an elastic design's deflected shape in its governing case
    projection   the fixed oblique view: planks as depth-sorted faces
    labels       Picture (a figure and its text), Label, Sheet: text written with Pillow
    views        design views and before/after views of a suggestion (PNG, matplotlib)
    plots        the force space of a change (PNG, matplotlib)
    suggestions  the files of ``suggest --out``; catalog: ``validate --views``
    folders      the checks before any work: output folder usable, matplotlib there
    errors       ExportUnavailable: matplotlib cannot be imported

matplotlib is imported only inside the functions that draw, so importing this package
stays cheap and works without it; drawing without it raises ``ExportUnavailable``.
"""

from furncheck.export.errors import ExportUnavailable
from furncheck.export.meshes import glb_bytes, mtl_text, obj_text, write_meshes
from furncheck.export.plots import force_space_picture, force_space_png, plot_force_space

__all__ = ["ExportUnavailable", "force_space_picture", "force_space_png", "glb_bytes",
           "mtl_text", "obj_text", "plot_force_space", "write_meshes"]
