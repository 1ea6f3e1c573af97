"""The library's independent exact checkers (exact predicates only, no algorithm of the
library): proof that a result is what it claims, for tests and for the sceptical."""
from __future__ import annotations

from typing import Tuple

import numpy as np

from . import _arrays, _core

__all__ = ["check_delaunay", "check_convex_hull", "check_constrained_delaunay"]


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

