"""The library's independent exact checkers (exact predicates only, no algorithm of the
library): proof that a result is what it claims, for tests and for the sceptical."""
from __future__ import annotations

from typing import Tuple

import numpy as np

from . import _arrays, _core

__all__ = ["check_delaunay", "check_convex_hull", "check_constrained_delaunay", "check_mesh2d"]


def _host(a, dtype):
    return np.ascontiguousarray(_arrays.to_host(a), dtype=dtype)


def check_delaunay(points, simplices, duplicate_of=None) -> Tuple[bool, str]:
    """(ok, first violation): the simplices triangulate the distinct points, positively
    oriented, every distinct point a vertex, duplicates (``duplicate_of``) not, and every
    simplex empty of other points (exact in-circle / in-sphere)."""
    p = _host(points, np.float64)
    what = {2: "delaunay2d", 3: "delaunay3d"}.get(p.shape[1] if p.ndim == 2 else 0)
    if what is None:
        raise ValueError("points must have shape (n, 2) or (n, 3)")
    dup = None if duplicate_of is None else _host(duplicate_of, np.int32)
    return _core.check(what, p, _host(simplices, np.int32), dup)


def check_convex_hull(points, simplices) -> Tuple[bool, str]:
    """(ok, first violation): a closed, convex, outward-oriented surface with every point
    inside or on it and every vertex extreme (exact)."""
    return _core.check("hull3d", _host(points, np.float64), _host(simplices, np.int32))


def check_constrained_delaunay(points, simplices, segments,
                               duplicate_of=None) -> Tuple[bool, str]:
    """(ok, first violation): the triangles triangulate the convex hull of the distinct 2D
    points, every segment (pairs of point indices) is a chain of edges, and every other edge is
    locally Delaunay (exact in-circle)."""
    p = _host(points, np.float64)
    dup = None if duplicate_of is None else _host(duplicate_of, np.int32)
    seg = _host(segments, np.int32).reshape(-1, 2)
    return _core.check("cdt2d", p, _host(simplices, np.int32), dup, seg)



def check_mesh2d(mesh, segments, min_angle: float = 0.0, max_area: float = 0.0,
                 exempt=None) -> Tuple[bool, str]:
    """(ok, first violation) for a refined mesh (``mesh2d``'s result): counter-clockwise
    triangles, each directed edge once, every boundary edge on a segment, every other edge on no
    segment locally Delaunay (exact in-circle), each input segment one path of edges from end to
    end, and every triangle but ``exempt`` (default: the mesh's ``small_angles``) with its
    smallest angle >= ``min_angle`` degrees and its area <= ``max_area`` (when > 0)."""
    p = _host(mesh["vertices"], np.float64)
    seg = _host(np.zeros((0, 2)) if segments is None else segments, np.int32).reshape(-1, 2)
    if exempt is None:
        exempt = getattr(mesh, "small_angles", np.zeros(0, np.int32))
    return _core.check_refined2d(p, _host(mesh["triangles"], np.int32),
                                 _host(mesh.segment_of, np.int32), seg,
                                 _host(mesh.duplicate_of, np.int32), float(min_angle),
                                 float(max_area), _host(exempt, np.int32))
