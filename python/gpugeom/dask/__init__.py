"""gpugeom on a Dask cluster: problems larger than one GPU, and several GPUs at once.

``delaunay(points)`` triangulates a ``dask.array`` (or a list of arrays or ``.npy`` files) block by
block on the cluster's workers, each block on its worker's GPU (or CPU), and returns a
``DistributedTriangulation``: its simplices and neighbours as Dask arrays in global indices,
``gather()`` for a ``gpugeom.Delaunay`` and ``to_pvtu()`` for ParaView. The result is exactly the
single-run triangulation of the same points.

``distance_transform_edt(array)`` is SciPy's exact distance transform of a ``dask.array``, slab by
slab along axis 0, returning Dask arrays equal to the single run's element for element.

Needs ``dask`` (and ``distributed`` for a cluster; ``dask-cuda`` gives one worker per GPU):
``pip install "dask[array]" distributed``.
"""
try:
    import dask  # noqa: F401
    import dask.array  # noqa: F401  (dask[array]: NumPy and toolz too)
except ImportError as e:  # pragma: no cover - depends on the environment
    raise ImportError("gpugeom.dask needs Dask: pip install \"dask[array]\" distributed") from e

from ._delaunay import DistributedTriangulation, delaunay
from ._edt import distance_transform_edt

__all__ = ["delaunay", "DistributedTriangulation", "distance_transform_edt"]
