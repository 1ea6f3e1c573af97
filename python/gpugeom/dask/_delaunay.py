"""The distributed Delaunay triangulation as a Dask computation: input pieces, blocks, a first
round with ghost layers and a second from the borders the blocks send each other, owned simplices
and their neighbours across blocks, matched by their faces."""
import operator
import os
import time
import uuid
from pathlib import Path
from typing import Optional, Sequence, Union

import dask
import dask.array as da
import numpy as np
from dask import delayed

from .. import _core
from ..spatial import ConvexHull, Delaunay
from . import _vtu
from ._blocks import Grid, choose_counts
from ._ghost import triangulate_block


# ---------------------------------------------------------------------------------------------
# Input: pieces of rows, each a delayed float64 (k, d) array, with their row offsets.


def _load(piece):
    if isinstance(piece, (str, os.PathLike)):
        piece = np.load(piece, mmap_mode="r")
    return np.ascontiguousarray(piece, dtype=np.float64)


def _npy_shape(path) -> tuple:
    try:
        return np.load(path, mmap_mode="r").shape
    except (OSError, ValueError) as e:
        raise ValueError(f"cannot read points from {str(path)!r} (a .npy file of shape (n, 2) "
                         f"or (n, 3) is expected): {e}") from None


def _pieces(points, nblocks: Optional[int]):
    """(list of delayed pieces, their row counts, the dimension)."""
    if isinstance(points, da.Array):
        if points.ndim != 2 or points.shape[1] not in (2, 3):
            raise ValueError(f"points must have shape (n, 2) or (n, 3), got {points.shape}")
        if any(np.isnan(c) for c in points.chunks[0]):
            raise ValueError("points has chunks of unknown size along axis 0; call "
                             "points.compute_chunk_sizes() first")
        if len(points.chunks[1]) != 1:
            raise ValueError(f"points is chunked along its coordinate axis (chunks "
                             f"{points.chunks[1]}); each chunk must hold whole points: use "
                             f"points.rechunk({{1: -1}})")
        if not np.issubdtype(points.dtype, np.number):
            raise TypeError(f"points must be numeric, got dtype {points.dtype}")
        return list(points.to_delayed().ravel()), [int(c) for c in points.chunks[0]], \
            int(points.shape[1])
    if isinstance(points, (list, tuple)):
        if not points:
            raise ValueError("points is an empty list")
        shapes = [_npy_shape(p) if isinstance(p, (str, os.PathLike)) else np.shape(p)
                  for p in points]
        widths = {s[1] if len(s) == 2 else None for s in shapes}
        if len(widths) != 1 or widths - {2, 3}:
            raise ValueError(f"every piece of points must have shape (k, 2) or (k, 3), all with "
                             f"the same width; got shapes {shapes}")
        return [delayed(_load)(p) for p in points], [int(s[0]) for s in shapes], widths.pop()
    arr = np.asarray(points)
    if arr.ndim != 2 or arr.shape[1] not in (2, 3):
        raise ValueError(f"points must have shape (n, 2) or (n, 3), got {arr.shape}")
    parts = np.array_split(np.arange(len(arr)), max(1, nblocks or 1))
    return ([delayed(np.ascontiguousarray)(arr[p[0]:p[-1] + 1], dtype=np.float64)
             for p in parts if len(p)], [len(p) for p in parts if len(p)], int(arr.shape[1]))


def _summary(pts, offset: int, stride: int):
    """A piece's count, its first bad row (-1: none), bounds and points in the sample of
    ``_on_convex_surface`` (those whose global ids are multiples of ``stride``)."""
    pts = _load(pts)
    if len(pts) == 0:
        return dict(n=0, bad=-1, lo=None, hi=None)
    r = _core.point_bounds(pts)  # one pass in C++ (NumPy's took 17 ms for 2.5·10^5 points)
    if r["first_bad"] >= 0:
        return dict(n=len(pts), bad=int(r["first_bad"]), lo=None, hi=None)
    return dict(n=len(pts), bad=-1, lo=np.array(r["lo"]), hi=np.array(r["hi"]),
                sample=pts[(-offset) % stride::stride].copy())


def _survey(pts, grid: Grid, bins: Grid, backend: str, threads: int):
    """A piece's hull candidates (its extreme points: rows) and its count of points per bin of
    ``bins``."""
    if pts.shape[1] == 2:
        # a 2D ConvexHull is a Delaunay triangulation of the piece; the filter is a few passes
        # on the host's threads, whatever runs the blocks
        cand = _core.hull_candidates2d(pts, threads)
    else:
        try:
            cand = np.asarray(ConvexHull(pts, backend=backend, threads=threads).vertices,
                              np.int64)
        except (_core.DegenerateInputError, ValueError):
            cand = np.arange(len(pts))  # too few or flat: every point may be extreme
    counts = _core.cell_counts(pts, bins.lo.tolist(), bins.width.tolist(), bins.counts.tolist(),
                               threads)
    return cand, counts


def _split(pts, offset: int, grid: Grid, boxes: dict, frontiers: Optional[dict], threads: int,
           first: Optional[tuple] = None):
    """A piece's points for a round: per block of ``boxes`` (a dict: block -> the boxes it takes
    this round), in increasing block order, the points it owns, those in its boxes and those in
    the bins ``frontiers`` gives it, as (points, global ids, owner blocks), None where it has
    none; with ``first`` (the bins, the backend), then the piece's hull candidates (points, ids,
    owner blocks) and its count of points per bin (the first round's split).
    Separate outputs, so that each block takes only its parts from the
    worker that split the piece, and no second task selects its ghosts from the other blocks'
    points (one hop, not two: on 4 workers the hop cost more than the selection)."""
    pts = _load(pts)
    cell, order, cuts, points, cells = grid.split(pts, boxes, threads, gather=True,
                                                  frontiers=frontiers)
    ids = order + offset
    parts = []
    for b in sorted(boxes):
        at = slice(cuts[b], cuts[b + 1])
        parts.append((points[at], ids[at], cells[at]) if cuts[b + 1] > cuts[b] else None)
    if first is None:
        return tuple(parts)
    cand, counts = _survey(pts, grid, first[0], first[1], threads)
    return (*parts, (pts[cand], cand + offset, cell[cand]), counts)


# Points on a convex surface go to one block, by the rule of the several devices of one host
# (src/blocks/convex_sample.hpp, with the same constants): at least half of a sample of at most
# ``_CONVEX_SAMPLE`` points (every ceil(n / _CONVEX_SAMPLE)-th, by global id) are extreme points of
# the sample's hull. On a circle, a sphere or a shell thinner than the sample's spacing every
# block holds most of the points (each holds the global hull's extreme points) and its balls span
# the hollow inside, where no ghost layer reaches: 4 blocks of 2·10^5 points on a sphere took
# 3.8 s. The rule decides only where the work runs: one block of every point gives the same
# triangulation.
_CONVEX_SAMPLE = 4096


def _sample_stride(n: int) -> int:
    return 1 if n <= _CONVEX_SAMPLE else -(-n // _CONVEX_SAMPLE)


def _on_convex_surface(samples) -> bool:
    """Whether the sample (the pieces' parts of it, from the check) says the points lie on a
    convex surface (decided in the client before any split: a hull of at most 4096 points)."""
    pts = np.concatenate(samples)
    if len(pts) < pts.shape[1] + 2:
        return False  # (too few to tell: the split handles them)
    try:
        h = ConvexHull(pts, backend="cpu", threads=1)  # (4096 points: one thread is enough)
    except (_core.DegenerateInputError, ValueError):
        return False  # (a flat sample)
    return 2 * len(h.vertices) >= len(pts)


def _one_block(parts, grid: Grid, ghost: float, backend: str, threads: int) -> dict:
    """The one block of points on a convex surface: block 0 owns and triangulates them all,
    untested (it holds every point) and with no border to send (no other block has a round).
    It is the call's only task, so with ``threads`` 0 it takes every core the worker's process
    may run on, not OpenMP's default there (1 under Dask: 10^6 points on a sphere took 11 s on
    one core of 4, where the single call on the 4 took 2.9)."""
    if threads <= 0:
        try:
            threads = len(os.sched_getaffinity(0))
        except AttributeError:  # (not Linux)
            threads = os.cpu_count() or 1
    d = grid.ndim
    nohull = (np.zeros((0, d)), np.zeros(0, np.int32), np.zeros(0, np.int32), None)
    return triangulate_block(0, grid, ghost, {}, parts, nohull, None, backend, threads, [])


def _whole(pts, offset: int):
    """A piece's points as a part of the one block that owns every point (block 0)."""
    pts = _load(pts)
    return pts, np.arange(offset, offset + len(pts), dtype=np.int32), np.zeros(len(pts), np.int32)


def _total_and_frontiers(counts, bins: Grid, grid: Grid, ghost: float, cap: int, threads: int):
    """The count of all points per bin, and from it the frontiers (one task: a hop less before
    the split)."""
    total = _total(counts)
    return total, _frontiers(total, bins, grid, ghost, cap, threads)


def _frontiers(total, bins: Grid, grid: Grid, ghost: float, cap: int, threads: int):
    """Per block the bins beside empty space its region reaches (``_core.empty_frontiers``),
    for the split of the first round; None where no block takes any."""
    regions = [grid.region(b, ghost) for b in range(grid.nblocks)]
    f = _core.empty_frontiers(total, bins.lo.tolist(), bins.width.tolist(), bins.counts.tolist(),
                              np.array([r[0] for r in regions], np.float64),
                              np.array([r[1] for r in regions], np.float64), int(cap),
                              band=float(ghost), threads=threads)
    return f if len(f["bins"]) else None


def _frontier_points(frontiers, nblocks: int):
    """The points each block took from its frontier bins."""
    return [0] * nblocks if frontiers is None else frontiers["points"].tolist()


def _total(counts):
    """The count of all points per bin."""
    return np.sum(counts, axis=0, dtype=np.int32)


def _cubes(lo, hi, target: int) -> Grid:
    """About ``target`` cells close to cubes over the box [lo, hi] (one along a flat axis)."""
    ext = hi - lo
    live = ext > 0
    counts = np.ones(len(lo), dtype=np.int64)
    if live.any():
        side = float(np.prod(ext[live]) / target) ** (1.0 / int(live.sum()))
        counts[live] = np.clip(np.ceil(ext[live] / side), 1, 4096).astype(np.int64)
    return Grid(lo, hi, counts)


def _bins(lo, hi, n: int) -> Grid:
    """The bins whose counts tell a block where the points it lacks may lie: about one per 8
    points, at most 2^16 (256 KiB a piece to sum)."""
    return _cubes(lo, hi, max(1, min(1 << 16, n // 8)))


def _global_hull(cands, backend: str, threads: int):
    """The global hull from the pieces' candidates: its extreme points (points, ids increasing,
    owner blocks) and its facet planes pushed outwards by a margin."""
    pts = np.concatenate([c[0] for c in cands])
    ids = np.concatenate([c[1] for c in cands])
    blk = np.concatenate([c[2] for c in cands])
    order = np.argsort(ids)
    pts, ids, blk = pts[order], ids[order], blk[order]
    try:
        h = ConvexHull(pts, backend=backend, threads=threads)
    except _core.DegenerateInputError as e:
        raise _core.DegenerateInputError(f"the points are degenerate as a whole: {e}") from None
    v = np.sort(np.asarray(h.vertices, np.int64))
    # the planes (unit outward normals) pushed out by a margin far above their rounding, so
    # that every point lies inside each of them
    planes = np.array(h.equations, dtype=np.float64)
    scale = float(np.abs(pts).max()) if len(pts) else 1.0
    planes[:, -1] -= 1e-9 * scale
    return pts[v], ids[v], blk[v], planes


def _meta(r: dict) -> dict:
    out = {k: v for k, v in r.items() if np.isscalar(v) or v is None}
    out["targets"] = sorted(r["borders"])
    if r["done"]:
        out["nsimplex"] = len(r["simplices"])
        out["owners"] = sorted(set(np.unique(r["req_owner"]).tolist()))
    return out


def _border_for(r: dict, target: int):
    """What a first-round result sends block ``target`` (None where nothing)."""
    return r["borders"].get(target)


def _faces_to(r: dict, offset: int, d1: int, matcher: int):
    """A block's face requests that block ``matcher`` pairs: their keys, global positions
    ((offset + row) * (d + 1) + face) and whether each is open (on the local hull)."""
    at = r["req_owner"] == matcher
    # (the positions widened: past 2^31 faces in all they pass a block's 32-bit rows)
    return (r["req_key"][at], offset * d1 + r["req_pos"][at].astype(np.int64),
            r["req_open"][at].view(bool))


def _faces_for(r: dict, offset: int, d1: int, matchers):
    """A block's face requests for each block of ``matchers`` (``_faces_to``), as one task's
    outputs: the scheduler places a task by its inputs' bytes against the worker's queue, and a
    task per matcher, each of whose input is the block's whole result, was sent to idle
    workers with that result (3D 10^6 points, 4 workers: 791 MiB and 1.3 s of transfers)."""
    return tuple(_faces_to(r, offset, d1, c) for c in matchers)


def _match(parts):
    """Pairs the face requests that come to one block from several (``_core.match_faces``):
    per part, in their order, (its positions, the positions across them, -1 for a face on the
    hull), so that each block takes back only its own answers."""
    keys = np.concatenate([p[0] for p in parts])
    pos = np.concatenate([p[1] for p in parts])
    open_ = np.concatenate([p[2] for p in parts])
    across = _core.match_faces(keys, pos, open_)
    cuts = np.cumsum([0] + [len(p[1]) for p in parts])
    return [(pos[a:b], across[a:b]) for a, b in zip(cuts[:-1], cuts[1:])]


def _neighbors_of(r: dict, offset: int, d1: int, answers, wide: bool = False) -> np.ndarray:
    """The neighbours of a block's simplices in global simplex indices, from its answers from
    the blocks that matched its faces (``_core.block_neighbors``): int32, or int64 where
    ``wide`` (2^31 simplices or more in all)."""
    pos = np.concatenate([a[0] for a in answers]) if answers else np.zeros(0, np.int64)
    across = np.concatenate([a[1] for a in answers]) if answers else np.zeros(0, np.int64)
    across = np.where(across >= 0, across // d1, -1)
    return _core.block_neighbors(r["nb_local"], int(offset), pos - offset * d1, across, wide)


class DistributedTriangulation:
    """A Delaunay triangulation computed block by block with Dask (``gpugeom.dask.delaunay``).

    Attributes
    ----------
    ndim, npoints, nsimplex : int
    simplices : dask.array (nsimplex, ndim + 1) of int32
        Global point indices, block by block (each block's owned simplices, in its local
        triangulation's order), each simplex positively oriented. int32 as SciPy's and
        ``gpugeom.Delaunay``'s (the call takes fewer than 2^31 - 1 points).
    neighbors : dask.array (nsimplex, ndim + 1) of int32, or int64 from 2^31 simplices
        ``neighbors[i, j]``: the simplex opposite vertex j of simplex i, in global simplex
        indices (across blocks), -1 on the hull, as SciPy's. (3D points make about 6.5 simplices
        a point: from about 3.3·10^8 points the indices need 64 bits.)
    blocks : tuple
        Cells per axis.
    block_stats : list of dict
        Per block: its ghost width, strips along the sides, rounds (1, or 2 where its first
        failed), the points it took in its first round from the bins beside empty space
        (``frontier``), local points (of its last round), owned simplices and simplices tested
        (in its first round: the second has no test), and ``why``: where the first round's
        test failed, a line on the balls that were not final (else empty).
        One entry (block 0, every point) where the points lie on a convex surface.
    timings : dict
        Milliseconds of the call's phases (client wall clock): ``check`` (shapes, finite
        coordinates, bounds), ``round1`` (the pieces split to the blocks, the global hull, the
        block triangulations and their borders) and, where a block needs it, ``round2``. The
        neighbours are computed when asked for.

    The input points stay in the cluster's memory (read once) while the result is alive, for
    ``points()`` and ``gather()``.
    """

    def __init__(self, pieces, counts, results, offsets, neighbors, grid, stats, index):
        self._pieces, self._counts, self._results = pieces, counts, results
        self._grid, self.block_stats = grid, stats
        self.ndim = grid.ndim
        self.npoints = int(sum(counts))
        self.blocks = tuple(int(c) for c in grid.counts)
        sizes = np.diff(offsets)
        self.nsimplex = int(offsets[-1])
        d1 = self.ndim + 1

        def part(objs, key, dtype):
            arrays = [da.from_delayed(delayed(operator.getitem)(o, key) if key else o,
                                      shape=(int(m), d1), dtype=dtype)
                      for o, m in zip(objs, sizes)]
            return da.concatenate(arrays) if arrays else da.zeros((0, d1), dtype=dtype)

        self.simplices = part(results, "simplices", np.int32)
        self.neighbors = part(neighbors, None, index)

    def points(self) -> np.ndarray:
        """All points, in input order (computed)."""
        return np.concatenate(dask.compute(*self._pieces)) if self._pieces else np.zeros(
            (0, self.ndim))

    def duplicate_of(self) -> np.ndarray:
        """Per point: -1, or the earlier point with the same coordinates (computed)."""
        dup = np.full(self.npoints, -1, dtype=np.int64)
        for c in dask.compute(*[delayed(operator.getitem)(r, "copies") for r in self._results]):
            dup[c[:, 0]] = c[:, 1]
        return dup

    def gather(self) -> Delaunay:
        """The whole triangulation as a ``gpugeom.Delaunay`` (on the host), when it fits."""
        if self.npoints >= 2**31 - 1:
            raise ValueError(f"{self.npoints} points do not fit a gpugeom.Delaunay's int32 "
                             "indices; use .simplices and .neighbors as Dask arrays")
        simplices, neighbors = dask.compute(self.simplices, self.neighbors)
        stats = {"blocks": float(len(self.block_stats)),
                 "rounds": float(max((s["rounds"] for s in self.block_stats), default=0))}
        if self.nsimplex >= 2**31:
            raise ValueError(f"{self.nsimplex} simplices do not fit a gpugeom.Delaunay's int32 "
                             "indices; use .simplices and .neighbors as Dask arrays")
        return Delaunay._from_arrays(self.points(), simplices, neighbors,
                                     self.duplicate_of().astype(np.int32), stats)

    def to_pvtu(self, path: Union[str, os.PathLike]) -> list:
        """Writes one ``.vtu`` piece per block (``<stem>_<block>.vtu`` beside ``path``, written by
        the workers) and the ``.pvtu`` ``path`` over them, which ParaView opens as one mesh.
        Point data ``global_id``, cell data ``simplex_id``. Returns the files written."""
        path = Path(path)
        if path.suffix != ".pvtu":
            raise ValueError(f"the path must end in .pvtu, got {str(path)!r}")
        if not path.parent.is_dir():
            raise ValueError(f"no folder {str(path.parent)!r} to write {path.name!r} into")
        names = [f"{path.stem}_{b}.vtu" for b in range(len(self._results))]
        offsets = np.concatenate([[0], np.cumsum([s["nsimplex"] for s in self.block_stats])])
        writes = [delayed(_write_piece)(str(path.parent / n), r, int(o))
                  for n, r, o in zip(names, self._results, offsets)]
        dask.compute(*writes)
        _vtu.write_index(str(path), names)
        return [str(path)] + [str(path.parent / n) for n in names]


def _write_piece(path: str, r: dict, offset: int) -> None:
    s = r["simplices"]
    at = np.argsort(r["vertices"], kind="stable")  # (the piece lists its points by global id)
    _vtu.write_piece(path, r["vertex_points"][at], r["vertices"][at], s,
                     np.arange(offset, offset + len(s), dtype=np.int64))


# The first round's ghost width in mean point spacings, and the depth of the strips along the
# bounding box's sides in ghost widths, per dimension. The simplices along the hull are long
# and flat: their balls reach far along the sides, beyond any ghost layer that costs little,
# and a block that holds only its layer fails there and runs a second round, which triangulates
# the block again. Measured on uniform points (2D 10^5-4·10^6, 3D 3·10^5-10^6; 2-8 blocks):
# 2.5 spacings and no strips took 2 rounds everywhere; these take 1, and the calls 0.55-0.7 of
# the time (docs/performance.md). In 3D half a width is enough (1 round on 3·10^5-10^6 in 2-27
# blocks; a quarter took 2) and a whole one cost 1.9 local points per point in 8 blocks where
# this costs 1.6.
_GHOST = {2: 6.0, 3: 4.0}
_STRIP_DEPTH = {2: 4.0, 3: 0.5}


def _workers() -> int:
    """The workers of the active distributed client (1 without one): a Dask array of one chunk
    on a LocalCluster of 4 workers is 4 blocks by default, not 1."""
    try:
        from distributed import get_client
        return max(1, len(get_client().scheduler_info().get("workers", {})))
    except (ImportError, ValueError):
        return 1


def _side_strips(grid: Grid, b: int, depth: float) -> dict:
    """Per side of the bounding box that block b's cell lies on, the slab of the bounding box
    ``depth`` deep along it (keyed by axis and side, as the strips a block asks for)."""
    clo, chi = grid.cell_box(b)
    out = {}
    for k in range(grid.ndim):
        if grid.hi[k] <= grid.lo[k]:
            continue
        for high in (False, True):
            if (chi[k] if high else clo[k]) != (grid.hi[k] if high else grid.lo[k]):
                continue
            lo, hi = grid.lo.copy(), grid.hi.copy()
            if high:
                lo[k] = grid.hi[k] - depth
            else:
                hi[k] = grid.lo[k] + depth
            out[(k, high)] = (lo, hi)
    return out


def delaunay(points, *, blocks: Union[None, int, Sequence[int]] = None,
             ghost: Optional[float] = None, backend: str = "auto",
             threads: int = 0) -> DistributedTriangulation:
    """Exact Delaunay triangulation of 2D or 3D points, block by block on a Dask cluster.

    The points are split into blocks by a grid over their bounding box; each block triangulates
    its points with a layer of ghost points around them, the global hull's extreme points and
    the points beside the empty space its layer reaches (between clusters: the points across
    a gap, where the balls spanning it end), and is done where no outside point can change a
    simplex round its own points. Every block also sends each other block its border: its own
    points that the other's simplices may use. A block not done is triangulated a second time,
    with its own points and the borders sent to it, and is then done without a test. Each
    simplex is output by the block owning its vertex first along the Hilbert curve of the
    points' bounding box (ties: the lowest index); neighbours across blocks
    are matched by their faces. Points on a convex surface (a circle, a sphere, a shell thinner
    than the spacing of a sample of 4096 of them: at least half the sample's points are its
    hull's extreme points) go to one block instead, which owns them all: split, every block would
    hold most of them. The result is exactly
    ``gpugeom.Delaunay(points)``'s set of simplices, degenerate input included (the
    perturbation depends on the points alone); the order differs.

    Parameters
    ----------
    points : dask.array (n, 2|3), NumPy array, or list of arrays or ``.npy`` paths
        A Dask array must hold whole points in each chunk (one chunk along axis 1).
    blocks : int or sequence of int, optional
        Blocks in all (split over the axes, cells kept close to cubes) or per axis. Default: one
        block per input chunk or file, or one per worker of the active distributed client where
        that is more (a block a worker measured best on uniform points: docs/performance.md).
    ghost : float, optional
        The ghost width of the first round (default: 6 mean point spacings in 2D, 4 in 3D).
        Blocks on the sides of the bounding box also take a strip along each side (4 ghost
        widths deep in 2D, half a width in 3D). Wider, more blocks are done in one round;
        narrower, each first round costs less.
    backend : {"auto", "cuda", "cpu"}
        Where each block is triangulated (on each worker: "auto" takes its GPU).
    threads : int
        CPU threads per block. 0 (the default): OpenMP's default in the worker, that is its
        ``OMP_NUM_THREADS``, which Dask sets to 1 unless told otherwise (give each worker process
        its share of the cores there, as ``bench/dask_cluster.py`` does). The one block of
        points on a convex surface, the call's only task, takes every core its worker may run
        on instead.

    Raises
    ------
    ValueError
        Before any block runs: bad shapes or chunks, NaN or infinite coordinates.
    gpugeom.DegenerateInputError
        The points are all on one line (2D) or plane (3D), or fewer than ndim + 1 are distinct.
    """
    pieces, counts, d = _pieces(points, blocks if isinstance(blocks, int) else None)
    n = int(sum(counts))
    if n >= 2**31 - 1:
        raise ValueError(f"{n} points: the distributed triangulation takes fewer than 2^31 - 1")
    clock = [time.perf_counter()]
    timings = {}

    def lap(name):
        clock.append(time.perf_counter())
        timings[name] = 1e3 * (clock[-1] - clock[-2])

    # the pieces are read (or made) once: the check, the split and gather() use the same
    pieces = list(dask.persist(*[delayed(_load)(p) for p in pieces]))
    start = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    stride = _sample_stride(n)
    summaries = dask.compute(*[delayed(_summary)(p, int(o), stride)
                               for p, o in zip(pieces, start)])
    lap("check")
    for i, s in enumerate(summaries):
        if s["bad"] >= 0:
            raise ValueError(f"point {start[i] + s['bad']} has a NaN or infinite coordinate")
        if s["n"] != counts[i]:
            raise ValueError(f"piece {i} holds {s['n']} points where its shape says {counts[i]}")
    filled = [s for s in summaries if s["n"] > 0]
    if not filled:
        raise ValueError("no points")
    lo = np.min([s["lo"] for s in filled], axis=0)
    hi = np.max([s["hi"] for s in filled], axis=0)
    if blocks is None:
        blocks = max(len(pieces), _workers())
    if isinstance(blocks, (int, np.integer)):
        if blocks < 1:
            raise ValueError(f"blocks must be at least 1, got {blocks}")
        cells = choose_counts(hi - lo, int(blocks))
    else:
        cells = tuple(int(b) for b in blocks)
        if len(cells) != d or min(cells) < 1:
            raise ValueError(f"blocks per axis must be {d} positive counts, got {blocks}")
    grid = Grid(lo, hi, cells)
    if ghost is None:
        ext = (hi - lo)[hi > lo]
        ghost = _GHOST[d] * float(np.prod(ext) / n) ** (1.0 / len(ext)) if len(ext) else 1.0
    elif not ghost > 0:
        raise ValueError(f"ghost must be positive, got {ghost}")

    run = dict(backend=backend, threads=threads)
    all_blocks = list(range(grid.nblocks))
    tag = uuid.uuid4().hex[:12]
    # from the first round, strips along the sides of the bounding box a block's cell touches
    extras = {b: _side_strips(grid, b, _STRIP_DEPTH[d] * ghost) for b in all_blocks}
    bins = _bins(lo, hi, n)

    # the first round: each piece is split to the blocks' regions and strips, and gives its hull
    # candidates and counts per bin, from which come the global hull and the counts of all
    # points. The counts also give each block the bins beside the empty space its region
    # reaches (at most a quarter of a block's share of the points), whose points a ghost layer
    # misses and the balls spanning that space need (design notes, "Bins beside empty
    # space"); where a block has some, the pieces are split again with them (uniform points
    # have none, and keep the one split). Every block is triangulated, tests its stars, and
    # takes its borders for the others.
    boxes = {b: [grid.region(b, float(ghost))] + list(extras[b].values()) for b in all_blocks}
    k = len(all_blocks)
    if grid.nblocks > 1 and _on_convex_surface([s["sample"] for s in filled]):
        # points on a convex surface: one block of every point (_one_block); no split, no
        # global hull (as costly as a triangulation there)
        all_blocks, extras, front, hull = [0], {0: {}}, None, None
        tasks = [delayed(_one_block)(
            [delayed(_whole)(p, int(o)) for p, o in zip(pieces, start)], grid, float(ghost),
            backend, threads, dask_key_name=f"gpugeom-delaunay-block-{tag}-0-0")]
    else:
        splits = [delayed(_split, nout=k + 2)(p, int(o), grid, boxes, None, threads,
                                              (bins, backend)) for p, o in zip(pieces, start)]
        hull = delayed(_global_hull)([s[-2] for s in splits], **run)
        total, frontiers = delayed(_total_and_frontiers, nout=2)(
            [s[-1] for s in splits], bins, grid, float(ghost), max(1, n // (4 * grid.nblocks)),
            threads)
        parts = [[s[i] for i in range(k)] for s in splits]
        *flat, hull, total, frontiers = dask.persist(*[x for p in parts for x in p], hull, total,
                                                     frontiers)
        parts = [flat[i * k:(i + 1) * k] for i in range(len(splits))]
        front = frontiers.compute()
        if front is not None:  # (the first split's parts are then let go)
            parts = [delayed(_split, nout=k)(p, int(o), grid, boxes, front, threads)
                     for p, o in zip(pieces, start)]
        del flat
        tasks = [delayed(triangulate_block)(
            b, grid, float(ghost), dict(extras[b]), [s[i] for s in parts], hull, (bins, total),
            backend, threads, dask_key_name=f"gpugeom-delaunay-block-{tag}-0-{b}")
            for i, b in enumerate(all_blocks)]
    taken = _frontier_points(front, grid.nblocks)
    first = dask.persist(*tasks)
    metas = dict(zip(all_blocks, dask.compute(*[delayed(_meta)(r) for r in first])))
    final = {b: r for b, r in zip(all_blocks, first) if metas[b]["done"]}
    rounds = {b: 1 for b in all_blocks}
    lap("round1")

    # the second round, for the blocks not done: their own points, the hull's and the borders
    # the others sent them (their stars are then final without a test)
    pending = [b for b in all_blocks if b not in final]
    if pending:
        own = {b: [] for b in pending}
        splits = [delayed(_split, nout=len(pending))(p, int(o), grid, own, None, threads)
                  for p, o in zip(pieces, start)]
        tasks = []
        for i, b in enumerate(pending):
            sent = [delayed(_border_for)(r, b) for c, r in zip(all_blocks, first)
                    if b in metas[c]["targets"]]
            # (no counts: the second round has no test)
            tasks.append(delayed(triangulate_block)(
                b, grid, float(ghost), {}, [s[i] for s in splits], hull, None, backend, threads,
                sent, dask_key_name=f"gpugeom-delaunay-block-{tag}-1-{b}"))
            rounds[b] = 2
        second = dask.persist(*tasks)
        for b, r, m in zip(pending, second, dask.compute(*[delayed(_meta)(r) for r in second])):
            # (round 1's test: the second has none)
            final[b], metas[b] = r, dict(m, tested=metas[b]["tested"], why=metas[b]["why"])
        lap("round2")

    order = [b for b in all_blocks if metas[b]["nlocal"] > 0]  # blocks with points
    sizes = [metas[b]["nsimplex"] for b in order]
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    results = [final[b] for b in order]
    # the neighbours across blocks: each block's face requests go to the blocks that match
    # them (by a face's lowest vertex), and the answers come back
    d1 = d + 1
    wide = int(offsets[-1]) >= 2**31  # (neighbours in int64 only where int32 cannot name them)
    at = {b: i for i, b in enumerate(order)}
    senders = {}
    for b in order:
        for c in metas[b]["owners"]:
            senders.setdefault(c, []).append(b)
    faces = {b: delayed(_faces_for, nout=len(metas[b]["owners"]))(
        final[b], int(offsets[at[b]]), d1, metas[b]["owners"]) for b in order}
    answers = {c: delayed(_match)([faces[b][metas[b]["owners"].index(c)] for b in senders[c]])
               for c in senders}
    neighbors = [delayed(_neighbors_of)(
        final[b], int(offsets[at[b]]), d1,
        [delayed(operator.getitem)(answers[c], senders[c].index(b)) for c in metas[b]["owners"]],
        wide) for b in order]
    stats = [dict(block=b, ghost=metas[b]["ghost"], extra_boxes=len(extras[b]), rounds=rounds[b],
                  frontier=int(taken[b]), nlocal=metas[b]["nlocal"],
                  nsimplex=metas[b]["nsimplex"], tested=metas[b]["tested"],
                  why=metas[b].get("why", "")) for b in order]
    out = DistributedTriangulation(pieces, counts, results, offsets, neighbors, grid, stats,
                                   np.int64 if wide else np.int32)
    out.timings = timings
    return out
