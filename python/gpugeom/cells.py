"""Voronoi cells of 3D particles in a box, bounded or periodic (C++ ``voronoi_cells``), with
the measures particle codes use: volumes, surface areas, centroids, neighbours with the area and
normal of each shared face, and the face polygons, as flat arrays.
"""
from typing import Optional, Sequence, Union

import numpy as np

from . import _arrays, _core


def _box(box, points_host):
    if box is None:
        raise ValueError("box=[lo, hi] is needed: the cells are cut by (or wrap round) it")
    b = np.asarray(box, dtype=np.float64)
    if b.shape == (2,):
        b = np.repeat(b[:, None], 3, axis=1)
    if b.shape != (2, 3):
        raise ValueError(f"box must be [lo, hi] with lo and hi numbers or 3-vectors, got shape "
                         f"{b.shape}")
    return b[0].tolist(), b[1].tolist()


def _periodic(periodic) -> list:
    if isinstance(periodic, (bool, np.bool_)):
        return [bool(periodic)] * 3
    p = list(periodic)
    if len(p) != 3 or not all(isinstance(x, (bool, np.bool_)) for x in p):
        raise ValueError(f"periodic must be a bool or three bools (x, y, z), got {periodic!r}")
    return [bool(x) for x in p]


class VoronoiCells:
    """Every point's Voronoi cell within a box (like Voro++'s containers and
    ``freud.locality.Voronoi``): along an axis that is not periodic the cells are cut by the
    box's walls and the points must lie in the box; along a periodic one coordinates are taken
    modulo the box and cells meet the images of points across it.

    The neighbours are exact: they are the ridges of the exact Delaunay tetrahedralisation, so
    points on a lattice (many on one sphere) give clean cells, without slivers. The measures are
    computed in double precision: from the diagram's circumcentres for a cell no wall cuts (in a
    periodic box, all), from the box cut by the neighbours' bisector planes otherwise.

    Parameters
    ----------
    points : (n, 3) array (NumPy, CuPy, PyTorch): device arrays are computed on their GPU, and
        the results stay there.
    box : [lo, hi], each a number or a 3-vector.
    periodic : bool or (bool, bool, bool).
    polygons : whether to compute the vertices and the faces' vertex lists (``False``: the
        measures, neighbours, face areas and normals only, sooner; the polygon attributes are
        None).
    backend, threads : as everywhere in gpugeom.

    Attributes
    ----------
    volumes (n,), areas (n,) (surface areas, walls included), centroids (n, 3).
    Per cell its faces ``face_offsets[i]:face_offsets[i + 1]`` (the same slices index
    ``neighbors``); per face: ``neighbors`` (a point, or a wall: -1/-2 the low/high x wall, -3/-4
    y, -5/-6 z, Voro++'s numbering), ``face_areas``, ``face_normals`` (outward unit normals),
    and its vertices ``faces[face_vertex_offsets[f]:face_vertex_offsets[f + 1]]``
    (counter-clockwise seen from outside), indices into ``vertices`` (each cell holds its own:
    ``vertex_offsets[i]:vertex_offsets[i + 1]``). In a periodic box a point may meet several
    images of one neighbour: one face each. A duplicate point has an empty cell.
    ``neighbor_offsets`` is ``face_offsets``; ``cell_faces(i)`` and ``cell_neighbors(i)`` slice
    one cell; ``stats`` as everywhere.
    """

    def __init__(self, points, box: Union[Sequence, np.ndarray, None] = None,
                 periodic: Union[bool, Sequence[bool]] = False, *, polygons: bool = True,
                 backend: str = "auto", threads: int = 0):
        arr, kind = _arrays.points_input(points, (3,), backend, threads)
        lo, hi = _box(box, arr)
        per = _periodic(periodic)
        self._kind = kind
        self.npoints = int(arr.shape[0])
        self.box = np.array([lo, hi])
        self.periodic = tuple(per)
        r = _core.voronoi_cells(arr, lo, hi, per, bool(polygons), backend=backend,
                                stream=kind.stream, threads=threads)
        back = kind.back
        self.volumes = back(r["volumes"])
        self.areas = back(r["areas"])
        self.centroids = back(r["centroids"])
        self.face_offsets = back(r["face_offsets"])
        self.neighbor_offsets = self.face_offsets
        self.neighbors = back(r["neighbors"])
        self.face_areas = back(r["face_areas"])
        self.face_normals = back(r["face_normals"])
        self.polygons = bool(polygons)
        poly = (lambda k: back(r[k])) if polygons else (lambda k: None)
        self.face_vertex_offsets = poly("face_vertex_offsets")
        self.faces = poly("face_vertices")
        self.vertex_offsets = poly("vertex_offsets")
        self.vertices = poly("vertices")
        self.stats = r["stats"]

    def _slice(self, i: int):
        if not 0 <= i < self.npoints:
            raise IndexError(f"cell {i} out of range for {self.npoints} points")
        fo = _arrays.to_host(self.face_offsets)
        return int(fo[i]), int(fo[i + 1])

    def cell_neighbors(self, i: int):
        """Cell i's neighbours, one per face (negative: walls)."""
        a, b = self._slice(i)
        return self.neighbors[a:b]

    def cell_faces(self, i: int) -> list:
        """Cell i's faces, each an array of (k, 3) vertex coordinates, counter-clockwise seen
        from outside."""
        if not self.polygons:
            raise RuntimeError("the cells were computed with polygons=False")
        a, b = self._slice(i)
        fvo = _arrays.to_host(self.face_vertex_offsets)
        fv = _arrays.to_host(self.faces)
        vx = _arrays.to_host(self.vertices)
        return [vx[fv[fvo[f]:fvo[f + 1]]] for f in range(a, b)]

    def __len__(self):
        return self.npoints

    def __repr__(self):
        per = "".join(a for a, p in zip("xyz", self.periodic) if p) or "none"
        return f"<gpugeom.VoronoiCells: {self.npoints} cells, periodic: {per}>"
