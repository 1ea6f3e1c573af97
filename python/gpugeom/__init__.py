"""gpugeom: exact computational geometry on the GPU, with SciPy's names.

* ``Delaunay`` (2D, 3D), ``Voronoi`` (2D), ``ConvexHull`` (3D) as in ``scipy.spatial``;
* ``distance_transform_edt`` as in ``scipy.ndimage``, and ``voronoi_labels``;
* ``centroidal_voronoi`` and ``stipple``;
* ``mesh2d`` and ``triangulate``: quality meshes of 2D domains, as the ``triangle`` package;
* ``device_info()``, ``verify`` (the exact checkers);
* ``gpugeom.dask`` (imported on its own, needs Dask): Delaunay triangulations block by block on
  a Dask cluster, equal to the single run.

Every function takes NumPy arrays (computed on the GPU when there is one, through the library's
fast host path) or CuPy / PyTorch CUDA arrays (computed where they are, on the caller's current
stream, results on the GPU), and ``backend="auto" | "cuda" | "cpu"``. Bad input raises
ValueError or TypeError with what to change; degenerate input (too few distinct points, all on
one line or plane) raises DegenerateInputError, a ValueError.
"""
from ._core import CudaError, DegenerateInputError, UnsupportedError, __version__
from ._arrays import device_info
from . import verify
from .cells import VoronoiCells
from .cvd import CentroidalVoronoi, Progress, Stipple, centroidal_voronoi, stipple
from .mesh import Mesh2d, mesh2d, triangulate
from .ndimage import distance_transform_edt, voronoi_labels
from .spatial import ConstrainedDelaunay, ConvexHull, Delaunay, Voronoi


def built_with_cuda() -> bool:
    """True when this build has the CUDA executor (a GPU is then used where one is present)."""
    return _core.built_with_cuda()


def release_cached_device_memory() -> None:
    """Hands the GPU memory the library's own pool keeps for reuse back to the driver (calls on
    CuPy or PyTorch arrays take theirs from that framework's allocator instead)."""
    _core.release_cached_device_memory()


__all__ = [
    "Delaunay", "Voronoi", "ConvexHull", "ConstrainedDelaunay", "VoronoiCells",
    "distance_transform_edt", "voronoi_labels",
    "mesh2d", "triangulate", "Mesh2d",
    "centroidal_voronoi", "stipple", "CentroidalVoronoi", "Stipple", "Progress", "device_info",
    "built_with_cuda", "release_cached_device_memory", "verify", "DegenerateInputError",
    "UnsupportedError", "CudaError", "__version__",
]
