"""Quality triangular meshes of 2D domains (Delaunay refinement, Triangle's ``-q`` and ``-a``).

``mesh2d`` takes points, segments, holes and regions and returns the dict ``triangle.triangulate``
returns (``vertices``, ``triangles``, ``segments``, ``triangle_attributes``, ...), so a user of
the ``triangle`` package can switch by changing the import; ``triangulate(tri, opts)`` takes
Triangle's own dict and option string.
"""
from __future__ import annotations

import re

import numpy as np

from . import _arrays, _core

__all__ = ["Mesh2d", "mesh2d", "triangulate", "MAX_MIN_ANGLE"]

#: The largest ``min_angle`` accepted (degrees): Triangle's bound, above which refinement need
#: not end.
MAX_MIN_ANGLE = 33.8

_REASONS = {1: "input angle", 2: "shell", 3: "limit"}


class Mesh2d(dict):
    """A refined mesh: a dict with ``triangle.triangulate``'s keys, and a few attributes.

    Keys
    ----
    vertices : (n, 2) float64
        The input points (in their order), then the Steiner points added.
    vertex_markers : (n, 1) int32
        The input's markers where given, else 1 for a vertex on a segment or the boundary and 0
        for the others (Triangle's convention).
    triangles : (m, 3) int32
        Counter-clockwise.
    neighbors : (m, 3) int32
        The triangle opposite vertex k (-1 on the boundary).
    segments, segment_markers : (s, 2) int32 and (s, 1) int32
        The subsegments: the pieces of the input segments (and of the convex hull's edges,
        without ``domain="enclosed"``) between vertices; markers are the input segment's marker
        where given, else 1.
    triangle_attributes : (m, 1) float64
        With regions: the attribute of the region holding each triangle.
    holes, regions
        As given.

    Attributes
    ----------
    segment_of : (m, 3) int32
        The input segment the edge opposite vertex k lies on (-2 for a hull edge, -1 for none).
    small_angles : (k,) int32
        Triangles left with an angle below ``min_angle``, and ``small_angle_reasons`` why:
        ``"input angle"`` (two segments meet at that angle), ``"shell"`` (the triangle sits in
        such a corner, between concentric-shell vertices: Shewchuk's terminator), ``"limit"``
        (``max_steiner`` reached, or no double where the point belongs).
    large_triangles : (k,) int32
        Triangles left above their area bound (only when ``max_steiner`` stopped refinement).
    stats : dict
        Phases (``triangulate``, ``decide``, ``insert`` (with the flips), ``output``, ``refine``,
        ``to_host``) and counters (``rounds``, ``steiner_points``, ``segment_splits``,
        ``rejected_points``: new points not inserted because they would encroach upon a
        subsegment, which was split instead; ``flips``, ``flip_passes``, ``triangles``).
    """

    segment_of: np.ndarray
    small_angles: np.ndarray
    small_angle_reasons: list
    large_triangles: np.ndarray
    stats: dict

    def to_meshio(self):
        """The mesh as a ``meshio.Mesh`` (triangles, with ``triangle_attributes`` as cell data
        ``"attribute"``); needs meshio."""
        import meshio

        cell_data = {}
        if "triangle_attributes" in self:
            cell_data["attribute"] = [np.asarray(self["triangle_attributes"])[:, 0]]
        pts = np.column_stack([self["vertices"], np.zeros(len(self["vertices"]))])
        return meshio.Mesh(pts, [("triangle", np.asarray(self["triangles"]))],
                           cell_data=cell_data)

    def to_pyvista(self):
        """The mesh as a ``pyvista.PolyData`` (z = 0), attributes as cell data; needs PyVista."""
        import pyvista

        tri = np.asarray(self["triangles"], dtype=np.int64)
        faces = np.column_stack([np.full(len(tri), 3), tri]).ravel()
        pts = np.column_stack([self["vertices"], np.zeros(len(self["vertices"]))])
        mesh = pyvista.PolyData(pts, faces)
        if "triangle_attributes" in self:
            mesh.cell_data["attribute"] = np.asarray(self["triangle_attributes"])[:, 0]
        return mesh

    def __repr__(self):
        return (f"<gpugeom.Mesh2d: {len(self['vertices'])} vertices, "
                f"{len(self['triangles'])} triangles>")


def _float_array(a, cols, name):
    if a is None:
        return np.zeros((0, cols))
    a = np.ascontiguousarray(_arrays.to_host(a), dtype=np.float64)
    if a.size == 0:
        return np.zeros((0, cols))
    if a.ndim != 2 or a.shape[1] != cols:
        raise ValueError(f"{name} must have shape (k, {cols}), got {a.shape}")
    return a


def _regions(regions):
    """(x, y, attribute[, max_area]) rows; a missing or negative area is no bound."""
    if regions is None:
        return np.zeros((0, 4))
    g = np.asarray(_arrays.to_host(regions), dtype=np.float64)
    if g.size == 0:
        return np.zeros((0, 4))
    if g.ndim != 2 or g.shape[1] not in (3, 4):
        raise ValueError(f"regions must have shape (k, 3) or (k, 4): x, y, attribute[, max "
                         f"area], got {g.shape}")
    if g.shape[1] == 3:
        g = np.column_stack([g, np.zeros(len(g))])
    return np.ascontiguousarray(g)


def _sizing(max_area):
    """(global bound, grid, extent, function) from max_area: a number, a callable f(x, y), or
    (grid, extent)."""
    if max_area is None:
        return 0.0, None, None, None
    if callable(max_area):
        return 0.0, None, None, max_area
    if isinstance(max_area, tuple) and len(max_area) == 2:
        grid = np.ascontiguousarray(_arrays.to_host(max_area[0]), dtype=np.float64)
        extent = tuple(float(v) for v in max_area[1])
        return 0.0, grid, extent, None
    a = float(max_area)
    if not (a > 0) or not np.isfinite(a):
        raise ValueError(f"max_area must be a finite area > 0 (or None), got {max_area!r}")
    return a, None, None, None


def mesh2d(points, segments=None, *, holes=None, regions=None, min_angle: float = 20.0,
           max_area=None, domain: str = "enclosed", crossings: str = "refuse",
           max_steiner: int | None = None, segment_markers=None, vertex_markers=None,
           backend: str = "auto", threads: int = 0) -> Mesh2d:
    """A quality mesh of a 2D domain by Delaunay refinement: every angle at least ``min_angle``
    and every triangle within its area bound, except where the input forces a smaller angle
    (reported in ``small_angles``).

    The result is exact: a constrained Delaunay triangulation (exact predicates) covering every
    segment, the same on every backend and thread count.

    Parameters
    ----------
    points : (n, 2) array of float
    segments : (s, 2) array of int, optional
        Point indices; the domain's boundary and any inner constraints.
    holes : (h, 2) array of float, optional
        A point in each hole.
    regions : (r, 3) or (r, 4) array of float, optional
        ``(x, y, attribute[, max_area])``: triangles reachable from the point get the attribute,
        and, where the fourth value is > 0, that area bound (Triangle's ``-A`` and ``-a``).
    min_angle : float
        Degrees, 0 (no angle bound) to 33.8 (Triangle's limit); default 20.
    max_area : float, callable, or (grid, extent), optional
        A global area bound; or a function ``f(x, y)`` giving the largest area at a point
        (called on the host at triangle centroids); or a sizing grid (rows, cols) of areas with
        its extent ``(xmin, ymin, xmax, ymax)``, bilinear between samples.
    domain : {"enclosed", "hull"}
        "enclosed" (Triangle's ``-p``) meshes what the segments enclose; "hull" the convex hull
        (its edges become segments, Triangle's ``-c``).
    crossings : {"refuse", "split"}
        As ``ConstrainedDelaunay``.
    max_steiner : int, optional
        At most this many Steiner points (Triangle's ``-S``).
    segment_markers, vertex_markers : arrays of int, optional
        Carried to the output as Triangle carries them.
    backend : {"auto", "cuda", "cpu"}
    threads : int
        CPU threads (0: all).

    Returns
    -------
    Mesh2d
        A dict with ``triangle.triangulate``'s keys.
    """
    _arrays.check_backend(backend)
    _arrays.check_threads(threads)
    if domain not in ("hull", "enclosed"):
        raise ValueError(f"domain must be 'enclosed' or 'hull', got {domain!r}")
    if crossings not in ("refuse", "split"):
        raise ValueError(f"crossings must be 'refuse' or 'split', got {crossings!r}")
    angle = float(min_angle)
    if not (0 <= angle <= MAX_MIN_ANGLE):
        raise ValueError(f"min_angle must be between 0 and {MAX_MIN_ANGLE} degrees (above it "
                         f"refinement need not end), got {min_angle!r}")
    h = _float_array(holes, 2, "holes")
    g = _regions(regions)
    area, grid, extent, fn = _sizing(max_area)
    steiner = -1 if max_steiner is None else int(max_steiner)
    if segment_markers is not None and segments is not None and \
            len(np.asarray(segment_markers).reshape(-1)) != len(_arrays.to_host(segments)):
        raise ValueError("segment_markers must have one marker per segment")
    kind = _arrays.classify(points)
    if kind.device:
        # CuPy / PyTorch CUDA points: refined where they are, the mesh left there.
        if crossings == "split" or fn is not None:
            raise ValueError("crossings='split' and a max_area function run on the host: give "
                             "host (NumPy) arrays for them")
        arr, kind = _arrays.points_input(points, (2,), backend, threads)
        seg = np.zeros((0, 2), np.int32) if segments is None else segments
        if not _arrays.classify(seg).device:
            seg = np.asarray(seg)
            if seg.size and not np.issubdtype(seg.dtype, np.integer):
                raise TypeError("segments must be integer point indices")
            seg = kind.from_xp(kind.xp().asarray(
                np.ascontiguousarray(seg, dtype=np.int32).reshape(-1, 2)))
        sarr, _ = _arrays.as_input(seg, np.int32, "segments", kind)
        r = _core.refine2d_device(arr, sarr.reshape(-1, 2), h, g, enclosed=domain == "enclosed",
                                  min_angle=angle, max_area=area, grid=grid, extent=extent,
                                  max_steiner=steiner, backend=backend, stream=kind.stream,
                                  threads=threads)
        for k in ("points", "simplices", "neighbors", "segment_of", "duplicate_of", "attribute",
                  "subsegments", "subsegment_of"):
            if k in r:
                r[k] = kind.to_xp(kind.back(r[k]))
        return _as_mesh(r, int(arr.shape[0]), h, g, segment_markers, vertex_markers,
                        kind.xp(), kind)
    p = np.ascontiguousarray(_arrays.to_host(points), dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"points must have shape (n, 2), got {p.shape}")
    seg = np.zeros((0, 2), dtype=np.int32) if segments is None else np.asarray(
        _arrays.to_host(segments))
    if seg.size and not np.issubdtype(seg.dtype, np.integer):
        raise TypeError("segments must be integer point indices")
    seg = np.ascontiguousarray(seg, dtype=np.int32).reshape(-1, 2)
    r = _core.refine2d(p, seg, h, g, enclosed=domain == "enclosed", split=crossings == "split",
                       min_angle=angle, max_area=area, grid=grid, extent=extent, sizing=fn,
                       max_steiner=steiner, backend=backend, threads=threads)
    return _as_mesh(r, len(p), h, g, segment_markers, vertex_markers)


def _as_mesh(r, n, holes, regions, segment_markers, vertex_markers, xp=np,
             kind=None) -> Mesh2d:
    """The extension's result as Triangle's dict; xp: the arrays' module (NumPy, or CuPy for a
    device result, given back as the caller's kind)."""
    pts, tri, seg_of = r["points"], r["simplices"], r["segment_of"]
    nbr = r["neighbors"]
    # The subsegments (each marked edge once, listed by the library) and their segments.
    sub, which = r["subsegments"], r["subsegment_of"]
    if segment_markers is not None:
        sm = xp.asarray(np.asarray(segment_markers, dtype=np.int32).reshape(-1))
        sub_markers = xp.where(which >= 0, sm[xp.clip(which, 0, max(len(sm) - 1, 0))], 1)
    else:
        sub_markers = xp.ones(len(sub), dtype=xp.int32)
    vm = xp.zeros(len(pts), dtype=xp.int32)
    vm[sub.ravel()] = 1
    if vertex_markers is not None:
        given = xp.asarray(np.asarray(vertex_markers, dtype=np.int32).reshape(-1))
        if len(given) != n:
            raise ValueError(f"vertex_markers: {len(given)} for {n} points")
        vm[:n] = xp.where(given != 0, given, vm[:n])
    back = (lambda v: v) if kind is None else kind.from_xp
    m = Mesh2d()
    m["vertices"] = back(pts)
    m["vertex_markers"] = back(vm.reshape(-1, 1))
    m["triangles"] = back(tri)
    m["neighbors"] = back(nbr)
    m["segments"] = back(sub)
    m["segment_markers"] = back(sub_markers.astype(xp.int32).reshape(-1, 1))
    if "attribute" in r:
        m["triangle_attributes"] = back(r["attribute"].reshape(-1, 1))
    if len(holes):
        m["holes"] = holes
    if len(regions):
        m["regions"] = regions
    m.segment_of = back(seg_of)
    m.small_angles = np.asarray(r["small_angles"])
    m.small_angle_reasons = [_REASONS.get(int(v), "?") for v in r["small_angle_reasons"]]
    m.large_triangles = np.asarray(r["large_triangles"])
    m.duplicate_of = back(r["duplicate_of"])
    m.stats = r["stats"]
    m.stats["counters"]["removed_triangles"] = int(r["removed_triangles"])
    return m


# Triangle's switches gpugeom.triangulate understands; the rest are refused by name.
_OPTION = re.compile(r"([A-Za-z])([0-9]*\.?[0-9]*(?:[eE][-+]?[0-9]+)?)")
_IGNORED = {"Q": "quiet", "V": "verbose", "z": "zero-based indices (always)",
            "j": "unused vertices", "B": "no boundary markers", "P": "no segments out",
            "N": "no nodes out", "E": "no elements out", "I": "no iteration numbers",
            "O": "no holes", "F": "Fortune's sweep", "i": "incremental", "l": "vertical cuts",
            "X": "no exact arithmetic"}


def triangulate(tri: dict, opts: str = "", *, backend: str = "auto", threads: int = 0) -> dict:
    """``triangle.triangulate`` with gpugeom's exact GPU meshing: the same dict in, the same
    keys out.

    Understood switches: ``p`` (mesh the segments' domain), ``q[angle]`` (default 20), ``a[area]``
    (a number: global; alone: the regions' fourth column), ``A`` (regional attributes), ``c``
    (the convex hull), ``e`` (edges out), ``n`` (neighbors out), ``S[count]``, and the output
    and verbosity switches (``Q``, ``V``, ``z``, ...), which change nothing here. ``D``, ``Y``,
    ``o2``, ``r``, ``u``, ``v``, ``s``, ``C`` and ``g`` raise ``ValueError``.

    Without ``p`` the segments are ignored and the result is the points' Delaunay triangulation
    (refined when ``q`` or ``a`` is given), as Triangle does.
    """
    if not isinstance(tri, dict) or "vertices" not in tri:
        raise ValueError("tri must be a dict with at least 'vertices'")
    flags = {}
    pos = 0
    for m in _OPTION.finditer(opts.replace(" ", "")):
        if m.start() != pos:
            raise ValueError(f"cannot read option string {opts!r} at {opts[pos:]!r}")
        pos = m.end()
        letter, value = m.group(1), m.group(2)
        if letter == "o" and value == "2":
            raise ValueError("option 'o2' (quadratic elements) is not supported by "
                             "gpugeom.triangulate")
        if letter in _IGNORED:
            continue
        if letter not in "pqaAcenS":
            raise ValueError(f"option {letter!r} is not supported by gpugeom.triangulate "
                             "(supported: p, q, a, A, c, e, n, S, and Q, V, z and the other "
                             "output switches)")
        if letter == "a":
            # A number: one bound everywhere; bare: the regions' fourth column (Triangle's -a).
            flags["a_global" if value else "a_bare"] = value
        flags[letter] = value
    if pos != len(opts.replace(" ", "")):
        raise ValueError(f"cannot read option string {opts!r}")
    pts = np.asarray(tri["vertices"], dtype=np.float64)
    plsg = "p" in flags
    segs = tri.get("segments") if plsg else None
    holes = tri.get("holes") if plsg else None
    regions = tri.get("regions") if plsg else None
    quality = "q" in flags or "a" in flags
    angle = float(flags["q"]) if flags.get("q") else (20.0 if "q" in flags else 0.0)
    area = float(flags["a_global"]) if "a_global" in flags else None
    if regions is not None:
        regions = np.asarray(regions, dtype=np.float64)
        if regions.ndim == 2 and regions.shape[1] == 4 and "a_bare" not in flags:
            regions = regions.copy()
            regions[:, 3] = 0  # (their areas bound only with a bare 'a', as Triangle reads them)
    domain = "enclosed" if plsg and "c" not in flags else "hull"
    if not quality:
        angle = 0.0
    m = mesh2d(pts, segs, holes=holes, regions=regions, min_angle=angle, max_area=area,
               domain=domain, max_steiner=int(flags["S"]) if flags.get("S") else None,
               segment_markers=tri.get("segment_markers") if segs is not None else None,
               vertex_markers=tri.get("vertex_markers"), backend=backend, threads=threads)
    out = {k: v for k, v in m.items() if k not in ("neighbors",)}
    if "A" not in flags:
        out.pop("triangle_attributes", None)
    if not plsg:
        out.pop("segments", None)
        out.pop("segment_markers", None)
    if "n" in flags:
        out["neighbors"] = m["neighbors"]
    if "e" in flags:
        tri_ = m["triangles"]
        e = np.sort(np.concatenate([tri_[:, [1, 2]], tri_[:, [2, 0]], tri_[:, [0, 1]]]), axis=1)
        out["edges"] = np.unique(e, axis=0).astype(np.int32)
    return out
