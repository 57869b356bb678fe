"""Septa: exact surface networks, non-manifold implicit shapes and planar
cut-cell meshes, from Python.

>>> import septa
>>> g = septa.grid.box(4, [[0, 0, 0], [1, 1, 1]])
>>> g.vertices.shape, g.tets.shape
((125, 3), (320, 4))
>>> values = septa.shapes.sphere([0.5, 0.5, 0.5], 0.3)(g.vertices)
>>> values.shape
(125,)

Results load from any job output folder (``network.json``) with
:func:`septa.load`, save to .ply/.obj/.json/.vtu/.msh, convert to meshio,
trimesh and pyvista, and open in the browser viewer with :func:`septa.view`.
"""
from ._septa import InputError, __version__
from . import grid, shapes
from .network import Network, load
from .jobs import arrangement, material_interface, region_surfaces, label_surfaces, cut_mesh
from .viewer import view
from . import continuation, distributed, stream

__all__ = [
    "__version__",
    "InputError",
    "grid",
    "shapes",
    "Network",
    "load",
    "arrangement",
    "material_interface",
    "region_surfaces",
    "label_surfaces",
    "cut_mesh",
    "view",
    "distributed",
    "continuation",
    "stream",
]
