"""Curves through unorganized planar points (ConDT) and their exact Delaunay triangulation.

The functions take points as any ``(n, 2)`` array-like and give NumPy arrays back; every
index is an input position (the row of the point in the array given). They compute exactly
what the ``condt`` command line computes:

- ``reconstruct(points, *, paper=False, **params)``: the curves, as ``condt reconstruct``;
- ``triangulate(points)``: the Delaunay triangulation, as ``condt triangulate``;
- ``read_points(path, *, columns=None, input_format=None)``: the points of a file in any
  format the command line reads, with its ``--columns`` and ``--input-format``
  (``read_points_with_crs(path)``: and a GeoJSON input's ``crs``, for
  ``Reconstruction.to_geojson(crs=...)`` to carry on);
- ``score(points, output, truth)``: the metrics of ``condt score``;
- ``snap(points, distance)``: near-duplicate points moved onto earlier ones, as ``condt
  reconstruct --snap`` does first (shared borders exported twice with rounding differences);
- ``condt.dask.reconstruct(points, client, tiles, **params)``: any ConDT pipeline (the default,
  ``paper=True`` and their variants) tiled across a Dask cluster, with ``reconstruct``'s edges
  (``import condt.dask``; needs ``dask[distributed]``).

>>> import condt
>>> r = condt.reconstruct([(0, 0), (1, 0), (1, 1), (0, 1)])
>>> r.edges.tolist()
[[0, 1], [0, 3], [1, 2], [2, 3]]
"""

# The native module (Rust, python/src); this package only re-exports it, so that pure-Python
# modules (``condt.dask``, imported on its own as it needs dask[distributed]) can sit beside it.
from ._condt import (
    Curve,
    EdgeStory,
    Reconstruction,
    Triangulation,
    __version__,
    read_points,
    read_points_with_crs,
    reconstruct,
    score,
    snap,
    triangulate,
)

__all__ = [
    "Curve",
    "EdgeStory",
    "Reconstruction",
    "Triangulation",
    "__version__",
    "read_points",
    "read_points_with_crs",
    "reconstruct",
    "score",
    "snap",
    "triangulate",
]
