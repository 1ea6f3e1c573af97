"""Delaunay triangulations, Voronoi diagrams and convex hulls with ``scipy.spatial``'s names,
shapes and dtypes, computed exactly (exact predicates with simulation of simplicity: degenerate
input gets a valid answer, never a failure or a wrong one).

Arrays come back as the kind that went in: NumPy for NumPy (and array-likes), CuPy for CuPy,
PyTorch tensors for PyTorch tensors; GPU inputs stay on the GPU and run on the caller's current
stream.
"""
from __future__ import annotations

from functools import cached_property
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np

from . import _arrays, _core

__all__ = ["Delaunay", "Voronoi", "ConvexHull", "ConstrainedDelaunay"]


def _index_list(indices, n):
    """A 1-D int32 array of point indices (host, or the GPU it is on), checked to be integers
    that int32 holds (the range against n is checked by the library)."""
    arr, kind = _arrays.as_input(indices, None, "indices")
    if len(arr.shape) != 1:
        raise ValueError(f"indices must be 1-D, got shape {tuple(arr.shape)}")
    if arr.shape[0] == 0:  # (an empty list has no integer dtype)
        return np.zeros(0, np.int32)
    dt = str(arr.dtype)
    if "bool" in dt:
        raise TypeError("indices must be integers (a boolean mask is not taken: use its nonzero())")
    if "int" not in dt:
        raise TypeError(f"indices must be integers, got {dt}")
    lo, hi = int(arr.min()), int(arr.max())  # (before int32: a wider index must not wrap)
    if lo < 0 or hi >= n:
        raise ValueError(f"indices must lie in 0 .. {n - 1}, got {lo if lo < 0 else hi}")
    if kind.name == "torch":
        import torch

        return arr.to(dtype=torch.int32)
    if kind.device:
        return arr.astype("int32")
    return np.ascontiguousarray(_arrays.to_host(arr), dtype=np.int32)


def _inverse(t):
    """The inverses of a stack of 2x2 or 3x3 matrices by their adjugates (no error where one is
    singular in floating point: its entries are then inf or NaN)."""
    if t.shape[-1] == 2:
        a, b, c, d = t[:, 0, 0], t[:, 0, 1], t[:, 1, 0], t[:, 1, 1]
        det = a * d - b * c
        rows = [[d, -b], [-c, a]]
    else:
        m = [[t[:, i, j] for j in range(3)] for i in range(3)]

        def cof(i, j):  # the cofactor of entry (i, j)
            r = [k for k in range(3) if k != i]
            c = [k for k in range(3) if k != j]
            v = m[r[0]][c[0]] * m[r[1]][c[1]] - m[r[0]][c[1]] * m[r[1]][c[0]]
            return v if (i + j) % 2 == 0 else -v

        det = m[0][0] * cof(0, 0) + m[0][1] * cof(0, 1) + m[0][2] * cof(0, 2)
        rows = [[cof(j, i) for j in range(3)] for i in range(3)]  # (transposed)
    inv = t.copy() if hasattr(t, "copy") else t.clone()
    for i, row in enumerate(rows):
        for j, v in enumerate(row):
            inv[:, i, j] = v / det
    return inv


def _split(offsets, flat) -> list:
    """CSR arrays (any kind) as a list of lists."""
    off = _arrays.to_host(offsets).tolist()
    vals = _arrays.to_host(flat).tolist()
    return [vals[off[i]:off[i + 1]] for i in range(len(off) - 1)]


def _as_kind(kind, host):
    """A host NumPy array as an array of `kind` (NumPy, CuPy, PyTorch)."""
    xp = kind.xp()
    return kind.from_xp(host if xp is np else xp.asarray(host))


# Qhull's options are accepted where they leave the exact result as it is (they scale the input,
# set Qhull's precision handling or its output); QG, which selects Qhull's "good" facets, is
# refused. QJ (joggle: Qhull's way round its rounding) is accepted, as the predicates are exact,
# except where it would also turn copies of a point into vertices (_refuse_joggled_copies).
def _check_qhull_options(opts: Optional[str]):
    for tok in (opts or "").split():
        if tok.startswith("QG"):
            raise ValueError(f"qhull_options {tok!r} is not offered by gpugeom (Qhull's 'good' "
                             "facets and the attribute good)")


def _refuse_joggled_copies(opts: Optional[str], duplicate_of):
    if "QJ" in (opts or "").split() and bool((_arrays.to_host(duplicate_of) >= 0).any()):
        raise ValueError("qhull_options 'QJ' would make every copy of a point a vertex (Qhull "
                         "joggles them apart): gpugeom is exact and keeps one copy, listing the "
                         "others in duplicate_of; remove the copies or the option")


def _furthest_site(furthest_site, ndim, incremental) -> bool:
    """Checks furthest_site=True (2D only, not incremental) and returns it as a bool."""
    if not furthest_site:
        return False
    if ndim != 2:
        raise ValueError("furthest_site=True is offered for 2D points only (the furthest-site "
                         f"Delaunay triangulation and Voronoi diagram), got {ndim}D points")
    if incremental:
        raise ValueError("furthest_site=True cannot be combined with incremental=True")
    return True


def _furthest_result(arr, run, voronoi: bool) -> dict:
    """The furthest-site structures, made on the host threads (the hull's extreme points are
    few) from host copies of the points."""
    return _core.furthest_site2d(np.ascontiguousarray(_arrays.to_host(arr), dtype=np.float64),
                                 threads=run["threads"], voronoi=voronoi)


def _not_supported(name, value, default):
    if value != default:
        raise ValueError(f"{name}={value!r} is not supported by gpugeom (SciPy's default only)")


class _OfPoints:
    """What the three structures share: the points as the caller's kind of array, and SciPy's
    incremental mode (``incremental=True``, ``add_points``, ``close``).

    A subclass computes with ``_compute(arr)`` (a dict of results for points ``arr``) and takes
    them with ``_take(r)``; in incremental mode ``_insert(new, both)`` may bring a kept state up to
    date instead (its results read by ``_kept_result``; None: compute on all points). A call that raises leaves
    the object as it was: everything is computed before anything is assigned.
    """

    _incremental = False
    _dyn = None  # the kept state in incremental mode, where the structure has one
    _cached = ()  # cached properties that depend on the results (cleared when they change)

    def _take_points(self, points, dims, backend, threads=0):
        arr, kind = _arrays.points_input(points, dims, backend, threads)
        self._kind = kind
        self._run = dict(backend=backend, stream=kind.stream, threads=threads)
        self._set_points(arr)
        return arr, kind

    def _set_points(self, arr):
        self._arr = arr
        self.points = self._kind.back(arr) if self._kind.name == "torch-cpu" else arr
        self.ndim = int(arr.shape[1])
        self.npoints = int(arr.shape[0])

    def add_points(self, points, restart: bool = False):
        """Adds points (incremental mode, as SciPy's): they take the indices after the current
        ones. ``restart=True`` computes the result from all points afresh; either way the result
        is exactly that of a new object on all points (the same arrays for a 2D ``Delaunay``,
        whose simplices come in an order that depends on the points alone; elsewhere the order
        of simplices may differ).

        ``Delaunay`` brings its kept triangulation up to date (C++ ``DynamicDelaunay2d`` and
        ``DynamicDelaunay3d``); ``ConvexHull`` makes the hull of its vertices and the new points
        only in 3D (C++ ``DynamicHull3d``), and computes again in 2D; ``Voronoi`` keeps its
        Delaunay triangulation and reads the diagram from it.

        Raises RuntimeError after ``close()`` or without ``incremental=True``, ValueError for
        points of another shape; a call that raises leaves the object unchanged.
        """
        if not self._incremental:
            raise RuntimeError("incremental mode not enabled or already closed")
        new = self._more_points(points)
        both = _arrays.concatenate(self._kind, self._arr, new)
        r = None if restart else self._insert(new, both)
        if r is None:
            r = self._compute(both, restart=True)
        self._set_points(both)
        for name in self._cached:
            self.__dict__.pop(name, None)
        self._take(r)

    def move(self, points):
        """gpugeom's own (issue 47), in incremental mode: new coordinates for every point
        (shape (npoints, ndim), the same kinds of arrays as add_points takes). The result is
        exactly that of a new object on the moved points. ``Delaunay`` repairs its kept
        triangulation where it is still one with the points moved (2D: flips, 3D: star
        splaying), else makes it afresh (``stats["counters"]["move_rebuilt"]``); ``ConvexHull``
        makes the hull of the moved points (any may have become extreme); ``Voronoi`` moves its
        kept triangulation as ``Delaunay`` does.
        Errors as add_points; a call that raises leaves the object unchanged."""
        if not self._incremental:
            raise RuntimeError("incremental mode not enabled or already closed")
        new = self._more_points(points)
        if new.shape[0] != self.npoints:
            raise ValueError(f"points must have shape ({self.npoints}, {self.ndim}): new "
                             f"coordinates for every point, got {tuple(new.shape)}")
        r = self._moved(new)
        if r is None:
            r = self._compute(new, restart=True)
        self._set_points(new)
        for name in self._cached:
            self.__dict__.pop(name, None)
        self._take(r)

    def _start_kept(self, make, arr, **kw):
        """The kept state on arr (a _core.Dynamic* class), with change tracking carried over."""
        dyn = make(arr, **kw, **self._run)
        if getattr(self, "_tracking", False):
            dyn.track_changes(True)
        r = self._kept_result(dyn, arr)
        self._dyn = dyn
        return r

    def _kept_result(self, dyn, arr):
        """The results of the kept state dyn, whose points are now arr."""
        return dyn.result()

    def _moved(self, new):
        if self._dyn is None:
            return None
        self._dyn.move(new)
        return self._kept_result(self._dyn, new)

    def _need_kept(self):
        if self._dyn is None:
            raise ValueError(f"this {type(self).__name__} keeps no state between calls (remove, "
                             "track_changes and changes need incremental=True, and for Delaunay "
                             "method='incremental'; a ConvexHull of 2D points keeps none)")

    def remove(self, indices):
        """gpugeom's own (issue 47), in incremental mode: removes the points with the given
        indices (1-D integers, each once, none removed before; NumPy, CuPy or PyTorch). The
        result is exactly that of a new object on the points left; the removed points keep
        their rows of ``points`` and their indices but are no vertices (``Delaunay``:
        ``duplicate_of`` reads -2 there and ``vertex_to_simplex`` -1; an equal point given
        before or after is a vertex in its place).

        Raises RuntimeError after ``close()`` or without ``incremental=True``, ValueError for a
        bad index list (out of range, repeated, removed before) or where the points left have no
        triangulation or hull, TypeError for non-integer indices; a call that raises leaves the
        object unchanged."""
        if not self._incremental:
            raise RuntimeError("incremental mode not enabled or already closed")
        self._need_kept()
        idx = _index_list(indices, self.npoints)
        self._dyn.remove(idx)
        r = self._kept_result(self._dyn, self._arr)
        for name in self._cached:
            self.__dict__.pop(name, None)
        self._take(r)

    def track_changes(self, on: bool = True):
        """gpugeom's own (issue 47), in incremental mode: from the next ``add_points``, ``move``
        or ``remove`` on, keep what each replaces, so that ``changes()`` can say which simplices
        it changed (a second copy of the results is held between calls; ``on=False``
        frees it). Raises RuntimeError after ``close()`` or without ``incremental=True``."""
        if not self._incremental:
            raise RuntimeError("incremental mode not enabled or already closed")
        self._need_kept()
        self._dyn.track_changes(bool(on))
        self._tracking = bool(on)

    def changes(self):
        """gpugeom's own (issue 47): which simplices (``ConvexHull``: facets) the last
        ``add_points``, ``move`` or ``remove`` changed, as ``(previous_index, removed)`` (int32
        arrays of the points' kind): per row of ``simplices``, its row before that call or -1 where it is new; and the rows
        before it that are gone. Data kept per simplex carries over as
        ``new = where(previous_index >= 0, old[previous_index], recompute)``. A simplex is the
        same where its vertices are. Raises ValueError where no update ran since
        ``track_changes()`` (an ``add_points(restart=True)`` starts over: changes follow from
        the next call)."""
        if not self._incremental:
            raise RuntimeError("incremental mode not enabled or already closed")
        self._need_kept()
        r = self._dyn.changes()
        return self._kind.back(r["previous_index"]), self._kind.back(r["removed"])

    def close(self):
        """Ends incremental mode, releasing its kept state (as SciPy's); add_points then
        raises RuntimeError. The results stay readable."""
        self._incremental = False
        self._dyn = None

    def _insert(self, new, both):
        if self._dyn is None:
            return None
        self._dyn.insert(new)
        return self._kept_result(self._dyn, both)

    def _more_points(self, points):
        """New points as the same kind and place as the current ones, shape (n, ndim)."""
        if getattr(points, "ndim", 2) != 2:
            raise ValueError(f"points must have shape (n, {self.ndim}) like the points already "
                             f"given, got {tuple(points.shape)}")
        arr, kind = _arrays.as_input(points, np.float64, "points")
        if len(arr.shape) != 2 or arr.shape[1] != self.ndim:
            raise ValueError(f"points must have shape (n, {self.ndim}) like the points already "
                             f"given, got {tuple(arr.shape)}")
        return _arrays.like(self._kind, self._arr, arr)


class Delaunay(_OfPoints):
    """Exact Delaunay triangulation of points in 2D or 3D (``scipy.spatial.Delaunay``).

    Parameters
    ----------
    points : (npoints, 2) or (npoints, 3) array of float
        NumPy, CuPy or PyTorch (CPU or CUDA); converted to float64.
    backend : {"auto", "cuda", "cpu"}
        Where it runs; "auto" takes the GPU when there is one. GPU arrays always run on the GPU.
    threads : int
        CPU threads (0: all).
    progress : callable, optional
        3D only: called as ``progress(phase, inserted, total, batch)`` after each insertion
        batch (a tqdm bar works too); raising ends the run.
    method : {"incremental", "digital"}
        How it is computed; the simplices are the same. "digital" is the thesis' digital
        method: in 2D a digital Voronoi diagram on a grid, its dual shifted to the points (from
        host points); in 3D (DigiDel3D) working sets of neighbours from the digital diagram, a
        star per point from its set, star splaying until the stars agree. Neither is the faster
        one yet.
    grid : int
        method="digital": the grid's size along the points' longest extent (2D: 4..46338
        pixels, 3D: 16..1024 cells; 0: chosen from the number of points).
    incremental : bool
        SciPy's incremental mode: ``add_points`` and ``close``. The triangulation is kept where
        the points are and brought up to date by each ``add_points`` (new points located by
        walks, inserted by flips; ``progress`` is not called then). The simplices are those of a
        new object on all points.
    devices : list of int or "all", optional
        Several GPUs of this host (host points; not in SciPy): the points are split into one
        block per entry (a device may be named twice), every block triangulated at once on its
        device, and the result is the arrays of one call, byte for byte. Points on a convex
        surface (a circle, a sphere, a shell thinner than the spacing of a sample of 4096 of
        them) are not split: that is one call on the first device. With ``backend="cpu"``
        each entry is a block on the CPU. Not with ``incremental``, ``furthest_site``,
        ``method="digital"`` or ``progress``.

    Attributes
    ----------
    points, simplices, neighbors, vertex_to_simplex, vertex_neighbor_vertices, convex_hull,
    coplanar, transform, ndim, npoints, nsimplex, stats, duplicate_of.  Duplicate points are not vertices; they are listed in ``coplanar`` as
    SciPy lists the points Qhull left out: ``[point, simplex, vertex it coincides with]``.
    """

    _cached = ("vertex_to_simplex", "convex_hull", "transform", "vertex_neighbor_vertices",
               "coplanar", "_paraboloid", "equations")
    _devices = None  # devices= (several devices of this host), or None

    def __init__(self, points, furthest_site: bool = False, incremental: bool = False,
                 qhull_options: Optional[str] = None, *, backend: str = "auto",
                 threads: int = 0, progress: Optional[Callable] = None,
                 method: str = "incremental", grid: int = 0,
                 devices: Union[None, str, Sequence[int]] = None):
        _check_qhull_options(qhull_options)
        arr, kind = self._take_points(points, (2, 3), backend, threads)
        self.furthest_site = _furthest_site(furthest_site, self.ndim, incremental)
        if method not in ("incremental", "digital"):
            raise ValueError(f"method must be 'incremental' or 'digital', got {method!r}")
        self._devices = _arrays.device_list(devices, kind,
                                            "each device copies in its block's points")
        if self._devices is not None:
            for name, bad in (("incremental=True", incremental),
                              ("furthest_site=True", self.furthest_site),
                              ("method='digital'", method != "incremental"),
                              ("progress", progress is not None)):
                if bad:
                    raise ValueError(f"devices= does not take {name} (the blocks are "
                                     f"triangulated at once, by the incremental method)")
        self._method, self._grid, self._progress = method, grid, progress
        self._incremental = bool(incremental)
        self._dyn = None
        r = self._compute(arr)
        _refuse_joggled_copies(qhull_options, self._kind.back(r["duplicate_of"]))
        self._take(r)

    def _compute(self, arr, restart=False):
        if self.furthest_site:
            return _furthest_result(arr, self._run, voronoi=False)
        if self._incremental and self._method == "incremental":
            # kept between calls (DynamicDelaunay2d / 3d): add_points brings it up to date
            make = _core.DynamicDelaunay2d if self.ndim == 2 else _core.DynamicDelaunay3d
            return self._start_kept(make, arr)
        if self.ndim == 2:
            return _core.delaunay2d(arr, method=self._method, grid=self._grid,
                                    devices=self._devices, **self._run)
        return _core.delaunay3d(arr, progress=_arrays.progress_callback(self._progress),
                                method=self._method, grid=self._grid, devices=self._devices,
                                **self._run)

    @classmethod
    def _from_arrays(cls, points, simplices, neighbors, duplicate_of, stats):
        """A host triangulation from its arrays (``gpugeom.dask``'s gather), as if computed."""
        self = cls.__new__(cls)
        arr, kind = _arrays.points_input(points, (2, 3), "cpu", 0)
        self._kind = kind
        self._run = dict(backend="cpu", stream=kind.stream, threads=0)
        self._set_points(arr)
        self.furthest_site = False
        self._method, self._grid, self._progress = "incremental", 0, None
        self._incremental, self._dyn = False, None
        self._take(dict(simplices=simplices, neighbors=neighbors, duplicate_of=duplicate_of,
                        stats=stats))
        return self

    def _take(self, r):
        kind = self._kind
        self.simplices = kind.back(r["simplices"])
        self.neighbors = kind.back(r["neighbors"])
        self._duplicate_of = kind.back(r["duplicate_of"])
        self._vts = kind.back(r["vertex_to_simplex"]) if "vertex_to_simplex" in r else None
        self._hull = kind.back(r["hull_facets"]) if "hull_facets" in r else None
        self.stats = r["stats"]

    @property
    def nsimplex(self) -> int:
        """The number of simplices (triangles in 2D, tetrahedra in 3D)."""
        return int(self.simplices.shape[0])

    @property
    def duplicate_of(self):
        """Per input point: -1 for a vertex, else the earlier point with the same coordinates."""
        return self._duplicate_of

    def _xp(self):
        return self._kind.xp()

    @cached_property
    def vertex_to_simplex(self):
        """For each point, a simplex that has it as a vertex (a duplicate: that of its twin)."""
        if self._vts is not None:
            return self._vts
        xp = self._xp()
        s = self._as_xp(self.simplices)
        dup = self._as_xp(self._duplicate_of)
        vts = xp.full(self.npoints, -1, dtype=xp.int32)
        vts[s.ravel()] = xp.repeat(xp.arange(s.shape[0], dtype=xp.int32), s.shape[1])
        d = xp.nonzero(dup >= 0)[0]
        vts[d] = vts[dup[d]]
        return self._back(vts)

    @cached_property
    def convex_hull(self):
        """Hull facets: (nfacet, ndim) vertex indices (edges in 2D, triangles in 3D)."""
        if self._hull is not None:
            return self._hull
        xp = self._xp()
        s = self._as_xp(self.simplices)
        nb = self._as_xp(self.neighbors)
        tri, k = xp.nonzero(nb < 0)  # 2D: the edge opposite vertex k of a hull triangle
        a = s[tri, (k + 1) % 3]
        b = s[tri, (k + 2) % 3]
        return self._back(xp.stack([a, b], axis=1).astype(xp.int32))

    @cached_property
    def transform(self):
        """Affine transforms to barycentric coordinates, as SciPy's: for simplex i,
        ``c = transform[i, :ndim] @ (x - transform[i, ndim])`` gives the first ndim barycentric
        coordinates of x (the last is 1 - sum(c)); shape (nsimplex, ndim + 1, ndim), float64.
        Every simplex has positive volume; as SciPy's, a simplex so thin that its matrix is
        ill-conditioned in floating point (reciprocal 1-norm condition number below 1000 eps)
        has NaN rows, since its transform could not be trusted."""
        xp = self._xp()
        p = self._as_xp(self.points)
        s = self._as_xp(self.simplices)
        d = self.ndim
        last = p[s[:, d]]
        t = xp.stack([p[s[:, k]] - last for k in range(d)], axis=2)  # columns v_k - v_d
        out = xp.empty((s.shape[0], d + 1, d), dtype=xp.float64)

        def norm1(m):  # the largest column sum of each matrix
            return xp.abs(m).sum(axis=1).max(axis=1)

        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            inv = _inverse(t)  # (inf or NaN where the rounded determinant is 0)
            bad = ~(1.0 / (norm1(t) * norm1(inv)) >= 1000 * np.finfo(np.float64).eps)
        inv[bad] = np.nan
        out[:, :d, :] = inv
        out[:, d, :] = last
        out[bad, d, :] = np.nan
        return self._back(out)

    @cached_property
    def _paraboloid(self):
        # (as Qhull's Qbb, which SciPy's Delaunay uses: the lifted coordinate scaled to [0, m],
        # m the largest absolute coordinate)
        p = _arrays.to_host(self.points)
        z = (p * p).sum(axis=1)
        lo, hi = float(z.min()), float(z.max())
        m = float(np.abs(p).max())
        scale = m / (hi - lo) if hi > lo and m > 0 else 1.0
        return scale, -lo * scale

    @property
    def paraboloid_scale(self) -> float:
        """As SciPy's: the lifted coordinate is ``sum(x**2) * paraboloid_scale +
        paraboloid_shift``."""
        return self._paraboloid[0]

    @property
    def paraboloid_shift(self) -> float:
        """As SciPy's: added to the scaled sum of squares in the lifted coordinate."""
        return self._paraboloid[1]

    def lift_points(self, x):
        """As SciPy's: the points x (shape (..., ndim)) lifted onto the paraboloid, shape
        (..., ndim + 1)."""
        q, qkind = _arrays.as_input(x, np.float64, "x")
        x = _arrays.to_host(q)
        z = (x * x).sum(axis=-1) * self.paraboloid_scale + self.paraboloid_shift
        return _as_kind(qkind, np.concatenate([x, z[..., None]], axis=-1))

    @cached_property
    def equations(self):
        """As SciPy's: per simplex, the hyperplane of its lifted vertices, ``[normal, offset]``
        (unit normal with a negative last component; shape (nsimplex, ndim + 2)), so that
        ``plane_distance`` is the signed distance to it. Floating point (the lift rounds)."""
        p = self.lift_points(np.asarray(_arrays.to_host(self.points)))
        s = _arrays.to_host(self.simplices)
        d = self.ndim
        v = p[s]  # (nsimplex, d + 1, d + 1)
        e = v[:, :d, :] - v[:, d:, :]  # d edge vectors in d + 1 dimensions
        cols = range(d + 1)
        # the normal by cofactors: orthogonal to every edge
        n = np.stack([(-1) ** j * np.linalg.det(e[:, :, [c for c in cols if c != j]])
                      for j in cols], axis=1)
        n /= np.linalg.norm(n, axis=1)[:, None]
        n *= -np.sign(n[:, d:])
        off = -(n * v[:, d, :]).sum(axis=1)
        return _as_kind(self._kind, np.concatenate([n, off[:, None]], axis=1))

    def plane_distance(self, xi):
        """As SciPy's: the signed distance of each lifted point of xi (shape (..., ndim)) to every
        simplex's hyperplane (``equations``), shape (..., nsimplex)."""
        q, qkind = _arrays.as_input(xi, np.float64, "xi")
        x = _arrays.to_host(q)
        if x.ndim == 0 or x.shape[-1] != self.ndim:
            raise ValueError(f"xi must have shape (..., {self.ndim}), got {x.shape}")
        eq = _arrays.to_host(self.equations)
        return _as_kind(qkind, self.lift_points(x) @ eq[:, :-1].T + eq[:, -1])

    @cached_property
    def vertex_neighbor_vertices(self):
        """(indptr, indices) as SciPy's: the Delaunay neighbours of vertex k are
        ``indices[indptr[k]:indptr[k + 1]]`` (sorted; none for a duplicate)."""
        xp = self._xp()
        s = self._as_xp(self.simplices).astype(xp.int64)
        d = s.shape[1]
        a = xp.concatenate([s[:, i] for i in range(d) for j in range(d) if i != j])
        b = xp.concatenate([s[:, j] for i in range(d) for j in range(d) if i != j])
        key = xp.unique(a * self.npoints + b)  # each directed edge once, sorted by (a, b)
        src, dst = key // self.npoints, key % self.npoints
        indptr = xp.zeros(self.npoints + 1, dtype=xp.int32)
        indptr[1:] = xp.cumsum(xp.bincount(src, minlength=self.npoints))
        return self._back(indptr), self._back(dst.astype(xp.int32))

    @cached_property
    def coplanar(self):
        """Duplicates, as SciPy lists the points Qhull did not use: (n, 3) int32 rows of
        [point index, a simplex holding its twin, the twin's index]."""
        xp = self._xp()
        dup = self._as_xp(self._duplicate_of)
        i = xp.nonzero(dup >= 0)[0].astype(xp.int32)
        vts = self._as_xp(self.vertex_to_simplex)
        return self._back(xp.stack([i, vts[dup[i]], dup[i]], axis=1).astype(xp.int32))

    def find_simplex(self, xi, bruteforce: bool = False, tol: Optional[float] = None):
        """The simplex holding each point of xi (shape (..., ndim)), -1 outside the hull.

        Exact: a point on a shared edge or face gets one of the simplices holding it; there is no
        tolerance (``tol`` must be None). Runs on the host threads; GPU triangulations are copied
        to the host for it.
        """
        if tol is not None:
            raise ValueError("find_simplex is exact: tol must be None")
        if np.shape(xi) == ():
            raise _arrays.ShapeError(f"xi must have shape (..., {self.ndim}), got a scalar")
        q, qkind = _arrays.as_input(xi, np.float64, "xi")
        qh = _arrays.to_host(q)
        if qh.ndim == 0 or qh.shape[-1] != self.ndim:
            raise _arrays.ShapeError(f"xi must have shape (..., {self.ndim}), got {qh.shape}")
        lead = qh.shape[:-1]
        flat = np.ascontiguousarray(qh.reshape(-1, self.ndim))
        r = _core.find_simplex(np.ascontiguousarray(_arrays.to_host(self.points), np.float64),
                               np.ascontiguousarray(_arrays.to_host(self.simplices), np.int32),
                               np.ascontiguousarray(_arrays.to_host(self.neighbors), np.int32),
                               flat)
        return _as_kind(qkind, np.asarray(r).reshape(lead))

    def _as_xp(self, a):
        return self._kind.to_xp(a)

    def _back(self, a):
        return self._kind.from_xp(a)

    def __repr__(self):
        return (f"<gpugeom.Delaunay: {self.npoints} points in {self.ndim}D, "
                f"{self.nsimplex} simplices>")


class Voronoi(_OfPoints):
    """Exact Voronoi diagram of 2D or 3D points (``scipy.spatial.Voronoi``), dual to the exact
    Delaunay triangulation: one vertex per circle (sphere) of its simplices, their circumcentre.
    Simplices whose points lie on one circle or sphere exactly (the exact predicate decides)
    share one vertex, as SciPy's, so no ridge is degenerate (a 3x3 grid has 4 vertices, a 3x3x3
    grid 8, and its ridges are the squares between neighbours along an axis).

    Attributes
    ----------
    points, vertices, ridge_points, ridge_vertices, regions, point_region, ndim, npoints, and
    beyond SciPy: ``ridge_directions`` (the outward unit direction of each unbounded ridge),
    ``ridge_vertices_array`` (the ridges as an (nridges, 2) array), ``delaunay_simplices``,
    ``simplex_vertex`` (per row of ``delaunay_simplices``, its Voronoi vertex); in 3D
    ``ridge_offsets`` and ``ridge_vertices_flat`` (the ridges' vertex lists as CSR arrays), and
    in both ``region_offsets`` and ``region_vertices_flat`` (the regions, one per point, as CSR
    arrays). In 2D regions list their vertices counter-clockwise, in 3D in increasing order; an
    unbounded one starts with -1. A 3D ridge lists its vertices in cyclic order, an unbounded
    one starting with -1. Duplicate points share the region of their twin.

    Incremental mode (``incremental=True``): the Delaunay triangulation is kept between calls
    (C++ ``DynamicDelaunay2d``, ``DynamicDelaunay3d``) and brought up to date by ``add_points``, ``move`` and ``remove``
    (a removed point keeps its index and has an empty region); the diagram is then read from it.
    ``track_changes()`` / ``changes()`` say which Delaunay triangles changed, per row of
    ``delaunay_simplices`` (``simplex_vertex`` gives each one's Voronoi vertex).
    """

    _cached = ("ridge_vertices", "regions", "point_region", "ridge_dict")

    def __init__(self, points, furthest_site: bool = False, incremental: bool = False,
                 qhull_options: Optional[str] = None, *, backend: str = "auto",
                 threads: int = 0):
        _check_qhull_options(qhull_options)
        arr, kind = self._take_points(points, (2, 3), backend, threads)
        self.furthest_site = _furthest_site(furthest_site, self.ndim, incremental)
        self._incremental = bool(incremental)
        # Qhull's Qz (in SciPy's default options) adds a point at infinity, whose region is an
        # empty one that no point_region names: SciPy's regions then have one entry more
        # (SciPy's furthest-site default options have no Qz)
        self._empty_region = ("Qz" in qhull_options.split() if qhull_options is not None
                              else not self.furthest_site)
        r = self._compute(arr)
        _refuse_joggled_copies(qhull_options, self._kind.back(r["duplicate_of"]))
        self._take(r)

    def _compute(self, arr, restart=False):
        if self.furthest_site:
            return _furthest_result(arr, self._run, voronoi=True)
        if self._incremental:
            # the triangulation kept between calls (DynamicDelaunay2d / 3d), the diagram made
            # from it
            make = _core.DynamicDelaunay2d if self.ndim == 2 else _core.DynamicDelaunay3d
            return self._start_kept(make, arr)
        return (_core.voronoi2d if self.ndim == 2 else _core.voronoi3d)(arr, **self._run)

    def _kept_result(self, dyn, arr):
        return dyn.voronoi(arr)

    def _take(self, r):
        kind = self._kind
        self.vertices = kind.back(r["vertices"])
        self.ridge_points = kind.back(r["ridge_points"])
        if self.ndim == 2:
            self.ridge_vertices_array = kind.back(r["ridge_vertices"])
            d = r["ridge_directions"]
            # (furthest-site rays run into the hull: away from the points they lie furthest from)
            self.ridge_directions = kind.back(-d if self.furthest_site else d)
        else:
            self.ridge_offsets = kind.back(r["ridge_offsets"])
            self.ridge_vertices_flat = kind.back(r["ridge_vertices"])
        self.delaunay_simplices = kind.back(r["simplices"])
        self.simplex_vertex = kind.back(r["simplex_vertex"])
        self.region_offsets = kind.back(r["cell_offsets"])
        self.region_vertices_flat = kind.back(r["cell_vertices"])
        self.stats = r["stats"]

    @cached_property
    def ridge_vertices(self) -> list:
        """As SciPy: per ridge the list of its vertices (2D: two; 3D: its polygon in cyclic
        order), -1 for the vertex at infinity."""
        if self.ndim == 2:
            return _arrays.to_host(self._kind.back(self.ridge_vertices_array)).tolist()
        return _split(self.ridge_offsets, self.ridge_vertices_flat)

    @cached_property
    def regions(self) -> list:
        """Per point (see point_region): its Voronoi vertices (2D: counter-clockwise; 3D: in
        increasing order); -1 first for an unbounded region."""
        return [[]] * self._empty_region + _split(self.region_offsets, self.region_vertices_flat)

    @cached_property
    def point_region(self):
        """Index into regions of each point's region: its own index, plus one where the regions
        start with SciPy's empty region of the point at infinity (Qhull's ``Qz``, SciPy's
        default)."""
        return np.arange(self.npoints, dtype=np.intp) + int(self._empty_region)

    @cached_property
    def ridge_dict(self) -> dict:
        """``{(p, q): ridge vertices}`` for every ridge, as SciPy's (built on first use)."""
        rp = _arrays.to_host(self.ridge_points).tolist()
        return {tuple(p): v for p, v in zip(rp, self.ridge_vertices)}

    def __repr__(self):
        return f"<gpugeom.Voronoi: {self.npoints} points, {len(self.vertices)} vertices>"


class ConvexHull(_OfPoints):
    """Exact convex hull of 2D or 3D points (``scipy.spatial.ConvexHull``): only extreme points
    are vertices (points inside a face or on an edge are not).

    3D: facets counter-clockwise seen from outside, flat faces triangulated, in one order on
    either backend and any thread count (along the points' Hilbert curve; Qhull's order differs).
    2D: the hull of the
    exact Delaunay triangulation's boundary; ``vertices`` counter-clockwise (as SciPy's),
    ``simplices`` its edges, ``area`` the perimeter and ``volume`` the enclosed area (SciPy's
    convention in 2D).

    Attributes
    ----------
    points, simplices, neighbors, vertices, equations (unit outward normal and offset, as
    Qhull's), area, volume, ndim, npoints, nsimplex, coplanar (always empty: no point is dropped
    for precision), stats.

    Parameters beyond SciPy's
    -------------------------
    method : {"incremental", "digital"}
        3D only. "digital": the thesis' DigiHull3D (a slice of the points' digital Voronoi
        diagram on each face of a grid gives a first hull; a digital depth test keeps the points
        that may lie outside it; their hull is the hull). The same facets either way.
    grid : int
        method="digital": the faces' grid side (16..8192; 0: chosen from the point count).

    Incremental mode (``incremental=True``): in 3D the hull is kept between calls (C++
    ``DynamicHull3d``): ``add_points`` makes the hull of the current vertices and the new points
    only (a point that is not extreme never becomes so when points join), ``remove`` keeps the
    hull where no vertex goes, and ``move``, ``track_changes`` and ``changes`` work as
    ``Delaunay``'s, on facets. In 2D each call computes again from all points.
    """

    _cached = ("area", "volume")

    def __init__(self, points, incremental: bool = False, qhull_options: Optional[str] = None, *,
                 backend: str = "auto", threads: int = 0, method: str = "incremental",
                 grid: int = 0):
        _check_qhull_options(qhull_options)
        if method not in ("incremental", "digital"):
            raise ValueError(f"method must be 'incremental' or 'digital', got {method!r}")
        arr, kind = self._take_points(points, (2, 3), backend, threads)
        if self.ndim == 2 and method != "incremental":
            raise ValueError("method='digital' is for 3D hulls (a 2D hull comes from the "
                             "Delaunay triangulation; use Delaunay(method='digital'))")
        self._method, self._grid = method, grid
        self._incremental = bool(incremental)
        self.coplanar = np.zeros((0, 3), dtype=np.int32)
        self._take(self._compute(arr))

    def _compute(self, arr, restart=False):
        if self.ndim == 2:
            return self._hull2d(arr, self._kind)
        if self._incremental:
            # kept between calls (DynamicHull3d): add_points makes the hull of the vertices and
            # the new points only
            return self._start_kept(_core.DynamicHull3d, arr, method=self._method, grid=self._grid)
        return _core.convex_hull3d(arr, method=self._method, grid=self._grid, **self._run)

    def _take(self, r):
        for k in ("simplices", "neighbors", "vertices", "equations"):
            setattr(self, k, r[k] if self.ndim == 2 else self._kind.back(r[k]))
        if self.ndim == 2:
            self._perimeter, self._area2d = r["perimeter"], r["area"]
        self.stats = r["stats"]

    def _hull2d(self, arr, kind):
        r = _core.delaunay2d(arr, **self._run)
        host = np.ascontiguousarray(_arrays.to_host(arr), dtype=np.float64)
        v = np.asarray(_core.hull2d_vertices(host, np.asarray(_arrays.to_host(kind.back(r["simplices"]))),
                                             np.asarray(_arrays.to_host(kind.back(r["neighbors"])))))
        h = len(v)
        edges = np.stack([v, np.roll(v, -1)], axis=1).astype(np.int32)
        a, b = host[edges[:, 0]], host[edges[:, 1]]
        d = b - a
        length = np.hypot(d[:, 0], d[:, 1])
        normal = np.stack([d[:, 1], -d[:, 0]], axis=1) / length[:, None]  # outward: CCW hull
        eq = np.column_stack([normal, -(normal * a).sum(axis=1)])
        nbr = np.stack([(np.arange(h) + 1) % h, (np.arange(h) - 1) % h], axis=1).astype(np.int32)
        xp = kind.xp()
        put = (lambda x: kind.from_xp(xp.asarray(x))) if kind.device else kind.from_xp
        return {"simplices": put(edges), "neighbors": put(nbr), "vertices": put(v.astype(np.int32)),
                "equations": put(eq), "perimeter": float(length.sum()),
                "area": float(0.5 * (a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]).sum()),
                "stats": r["stats"]}

    @property
    def nsimplex(self) -> int:
        """The number of facets (edges in 2D, triangles in 3D)."""
        return int(self.simplices.shape[0])

    def _facets(self):
        p = np.asarray(_arrays.to_host(self.points), dtype=np.float64)
        s = np.asarray(_arrays.to_host(self.simplices))
        c = p[np.asarray(_arrays.to_host(self.vertices))].mean(axis=0)
        return p[s[:, 0]] - c, p[s[:, 1]] - c, p[s[:, 2]] - c

    @cached_property
    def area(self) -> float:
        """The hull's surface area (in 2D its perimeter, as SciPy's)."""
        if self.ndim == 2:
            return self._perimeter
        a, b, c = self._facets()
        return float(0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())

    @cached_property
    def volume(self) -> float:
        """The hull's volume (in 2D its area, as SciPy's)."""
        if self.ndim == 2:
            return self._area2d
        a, b, c = self._facets()
        return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)

    def __repr__(self):
        return f"<gpugeom.ConvexHull: {self.npoints} points, {len(self.vertices)} vertices>"


class ConstrainedDelaunay:
    """Exact constrained Delaunay triangulation of 2D points and segments (as Triangle's ``-p``
    and CGAL's ``Constrained_Delaunay_triangulation_2``).

    Every segment is a chain of triangle edges (a segment through other points runs along the
    edges between them), and every other edge is locally Delaunay (exact in-circle).

    Parameters
    ----------
    points : (npoints, 2) array of float
        NumPy, or CuPy / PyTorch CUDA arrays: then the segments join them on the device and the
        results stay there (CuPy arrays, or tensors on the points' device).
    segments : (nsegments, 2) array of int
        Point indices. Zero-length and repeated segments are dropped (counted in ``stats``);
        segments that cross inside both raise ``ValueError`` naming them, unless
        ``crossings="split"``.
    holes : (nholes, 2) array of float, optional
        The triangles reachable from each point without crossing a segment are removed.
    regions : (nregions, 3) array of float, optional
        ``(x, y, attribute)``: the triangles reachable from each point get ``attribute``
        (``attributes``; the first region wins where regions meet).
    domain : {"hull", "enclosed"}
        "hull" keeps the convex hull's triangles (less holes); "enclosed" also removes those
        outside the segments, reachable from the hull (Triangle's default for ``.poly`` files).
    crossings : {"refuse", "split"}
        "split" adds a vertex where two segments cross (their intersection rounded to doubles)
        and makes each segment the chain through its new vertices (as Triangle does).
    backend : {"auto", "cuda", "cpu"}
        Where the triangulation and the segments' recovery run.

    Attributes
    ----------
    points (the input points, then ``new_points``), segments, simplices (ntri, 3,
    counter-clockwise), neighbors (-1 across the boundary), segment_of (ntri, 3: the input
    segment edge k, opposite vertex k, lies on, or -1), attributes (ntri, or None),
    duplicate_of, new_points (k, 2: the vertices added where segments cross), new_point_segments
    (k, 2: the two segments crossing at each), stats (its counters: segments_present,
    segments_recovered, cavity_triangles, recovery_rounds, crossings, segments_split,
    zero_length_segments, repeated_segments, removed_triangles, ...).
    """

    def __init__(self, points, segments, *, holes=None, regions=None, domain: str = "hull",
                 crossings: str = "refuse", backend: str = "auto", threads: int = 0):
        _arrays.check_backend(backend)
        _arrays.check_threads(threads)
        if domain not in ("hull", "enclosed"):
            raise ValueError(f"domain must be 'hull' or 'enclosed', got {domain!r}")
        if crossings not in ("refuse", "split"):
            raise ValueError(f"crossings must be 'refuse' or 'split', got {crossings!r}")
        h = np.ascontiguousarray(np.zeros((0, 2)) if holes is None else _arrays.to_host(holes),
                                 dtype=np.float64).reshape(-1, 2)
        g = np.ascontiguousarray(np.zeros((0, 3)) if regions is None
                                 else _arrays.to_host(regions), dtype=np.float64).reshape(-1, 3)
        kind = _arrays.classify(points)
        if kind.device:
            # CuPy / PyTorch CUDA points: the segments join them on the device, and the result
            # stays there (cdt2d_device).
            if crossings == "split":
                raise ValueError("crossings='split' reads the segments on the host: give host "
                                 "(NumPy) arrays for it")
            arr, kind = _arrays.points_input(points, (2,), backend, threads)
            seg = segments
            if not _arrays.classify(seg).device:
                seg = np.asarray(seg)
                if seg.size and not np.issubdtype(seg.dtype, np.integer):
                    raise TypeError("segments must be integer point indices")
                seg = np.ascontiguousarray(seg, dtype=np.int32).reshape(-1, 2)
                if kind.name == "torch":
                    import torch

                    seg = torch.as_tensor(seg, device=kind.torch_device)
                else:
                    import cupy

                    seg = cupy.asarray(seg)
            sarr, _ = _arrays.as_input(seg, np.int32, "segments", kind)
            sarr = sarr.reshape(-1, 2)
            r = _core.cdt2d_device(arr, sarr, h, g, enclosed=domain == "enclosed",
                                   backend=backend, stream=kind.stream, threads=threads)
            self.points, self.segments = arr, sarr
            self.simplices = kind.back(r["simplices"])
            self.neighbors = kind.back(r["neighbors"])
            self.segment_of = kind.back(r["segment_of"])
            self.duplicate_of = kind.back(r["duplicate_of"])
            self.attributes = kind.back(r.get("attribute"))
            self.new_points = np.zeros((0, 2))
            self.new_point_segments = np.zeros((0, 2), dtype=np.int32)
        else:
            self.points = np.ascontiguousarray(_arrays.to_host(points), dtype=np.float64)
            if self.points.ndim != 2 or self.points.shape[1] != 2:
                raise ValueError(f"points must have shape (n, 2), got {self.points.shape}")
            seg = np.asarray(_arrays.to_host(segments))
            if seg.size and not np.issubdtype(seg.dtype, np.integer):
                raise TypeError("segments must be integer point indices")
            self.segments = np.ascontiguousarray(seg, dtype=np.int32).reshape(-1, 2)
            r = _core.cdt2d(self.points, self.segments, h, g, enclosed=domain == "enclosed",
                            split=crossings == "split", backend=backend, threads=threads)
            self.new_points = r["new_points"]
            self.new_point_segments = r["new_point_segments"]
            if len(self.new_points):
                self.points = np.concatenate([self.points, self.new_points])
            self.simplices = r["simplices"]
            self.neighbors = r["neighbors"]
            self.segment_of = r["segment_of"]
            self.duplicate_of = r["duplicate_of"]
            self.attributes = r.get("attribute")
        self.stats = r["stats"]
        for k in ("zero_length_segments", "repeated_segments", "removed_triangles"):
            self.stats["counters"][k] = int(r[k])
        self.ndim = 2
        self.npoints = int(self.points.shape[0])
        self.nsimplex = int(self.simplices.shape[0])

