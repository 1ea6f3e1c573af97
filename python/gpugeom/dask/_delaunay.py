"""The distributed Delaunay triangulation as a Dask computation: input pieces, blocks, rounds of
ghost growth, owned simplices and their neighbours across blocks."""
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


def _summary(pts):
    pts = _load(pts)
    if len(pts) == 0:
        return dict(n=0, bad=-1, lo=None, hi=None)
    r = _core.point_bounds(pts)  # one pass in C++ (NumPy's took 17 ms for 2.5·10^5 points)
    if r["first_bad"] >= 0:
        return dict(n=len(pts), bad=int(r["first_bad"]), lo=None, hi=None)
    return dict(n=len(pts), bad=-1, lo=np.array(r["lo"]), hi=np.array(r["hi"]))


def _split(pts, offset: int, grid: Grid, boxes: dict, asked: dict, bins: Grid, first: bool,
           sample: Grid, backend: str, threads: int):
    """A piece's points for a round: per block of ``boxes`` (a dict: block -> the boxes it takes
    this round), in increasing block order, the points it owns, those in its boxes and those in
    the bins it asked for (``asked``: block -> bin ids), as (points, global ids, owner blocks),
    None where it has none; in the first round, then the piece's hull candidates (its extreme
    points) likewise, its count of points per bin and its sample (``_sample``). Separate
    outputs, so that each block takes only its parts from the worker that split the piece, and
    no second task selects its ghosts from the other blocks' points (one hop, not two: on 4
    workers the hop cost more than the selection)."""
    pts = _load(pts)
    cell, order, cuts, points, cells = grid.split(pts, boxes, threads, gather=True,
                                                  requests=(bins, asked))
    ids = order + offset
    parts = []
    for b in sorted(boxes):
        at = slice(cuts[b], cuts[b + 1])
        parts.append((points[at], ids[at], cells[at]) if cuts[b + 1] > cuts[b] else None)
    if not first:
        return tuple(parts)
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
    return (*parts, (pts[cand], cand + offset, cell[cand]), counts, _sample(pts, offset, cell,
                                                                           sample, threads))


def _sample(pts, offset: int, cell, sample: Grid, threads: int):
    """The piece's first point in each cell of ``sample`` (points, global ids, owner blocks,
    sample cells): the piece's part of the sample every block holds (``_global_hull``)."""
    scell, order, cuts = sample.split(pts, threads=threads)
    first = order[cuts[:-1][np.diff(cuts) > 0]]
    return pts[first], first + offset, cell[first], scell[first]


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
    """The bins whose counts tell a block where the points it lacks may lie, and which it asks
    for whole: about one per 8 points, at most 2^16 (256 KiB a piece to sum)."""
    return _cubes(lo, hi, max(1, min(1 << 16, n // 8)))


def _sample_size(n: int) -> int:
    """The points of the sample every block holds: one per 256 points, at most 4096 (a block of
    uniform points in 8 gains 2-3 % local points)."""
    return max(1, min(4096, n // 256))


def _sample_grid(lo, hi, n: int) -> Grid:
    """The cells of the sample: 2 per sample point, so that where the points cluster (few cells
    hold any) each cluster still has several. (8 gave the same local points on clusters, and
    every piece of uniform points sent its lowest point in each of them: 21 MB and 160 ms on
    the critical path for 10^6 points in 16 pieces.)"""
    return _cubes(lo, hi, 2 * _sample_size(n))


def _global_hull(cands, samples, npoints: int, backend: str, threads: int):
    """The points every block holds from the first round: the global hull's extreme points
    (from the pieces' candidates) and a coarse sample of all the points (from the pieces'
    samples: per sample cell the point of lowest id, every k-th of those cells where more than
    ``_sample_size`` hold points). Without the sample a block's simplices at the side of a
    cluster reach to the hull's points, and their balls take the clusters between whole; with
    it they reach the nearest clusters' sides. Returns (points, ids increasing, owner blocks,
    the hull's facet planes pushed outwards by a margin)."""
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
    # the sample: per sample cell the lowest id, in the cells' order
    sp = np.concatenate([x[0] for x in samples])
    sid = np.concatenate([x[1] for x in samples])
    sblk = np.concatenate([x[2] for x in samples])
    scell = np.concatenate([x[3] for x in samples])
    o = np.lexsort((sid, scell))
    keep = o[np.concatenate([[True], scell[o][1:] != scell[o][:-1]])] if len(o) else o
    most = _sample_size(npoints)
    if len(keep) > most:
        keep = keep[::-(-len(keep) // most)]
    aid = np.concatenate([ids[v], sid[keep]])
    aid, at = np.unique(aid, return_index=True)
    apts = np.concatenate([pts[v], sp[keep]])[at]
    ablk = np.concatenate([blk[v], sblk[keep]])[at]
    return apts, aid, ablk, planes


def _meta(r: dict) -> dict:
    out = {k: v for k, v in r.items() if np.isscalar(v) or v is None or k in ("boxes", "bins")}
    if r["done"]:
        out["nsimplex"] = len(r["simplices"])
        out["owners"] = sorted(set(np.unique(r["req_owner"]).tolist()))
    return out


def _border(r: dict):
    """A block's owned simplices that have a neighbour owned elsewhere (a face with -2): the only
    ones another block can ask for. Their rows and their sorted vertices (from the block's
    output pass), alone: the only part of a block's result another block takes."""
    return r["border_rows"], r["border_keys"]


def _neighbors(r: dict, offsets: np.ndarray, block: int, owners: dict) -> np.ndarray:
    """The neighbours of block ``block``'s simplices in global simplex indices; ``owners``: per
    block asked, its border (``_border``). One C++ pass (``_core.block_neighbors``)."""
    borders = [(int(c), int(offsets[c]), rows, keys) for c, (rows, keys) in owners.items()]
    return _core.block_neighbors(r["nb_local"], int(offsets[block]), r["req_owner"],
                                 r["req_key"], r["req_pos"], borders)


class DistributedTriangulation:
    """A Delaunay triangulation computed block by block with Dask (``gpugeom.dask.delaunay``).

    Attributes
    ----------
    ndim, npoints, nsimplex : int
    simplices : dask.array (nsimplex, ndim + 1) of int64
        Global point indices, block by block (each block's owned simplices, in its local
        triangulation's order), each simplex positively oriented.
    neighbors : dask.array (nsimplex, ndim + 1) of int64
        ``neighbors[i, j]``: the simplex opposite vertex j of simplex i, in global simplex
        indices (across blocks), -1 on the hull, as SciPy's.
    blocks : tuple
        Cells per axis.
    block_stats : list of dict
        Per block: its ghost width, extra boxes along the hull, rounds, local points, owned
        simplices and simplices tested.
    timings : dict
        Milliseconds of the call's phases (client wall clock): ``check`` (shapes, finite
        coordinates, bounds), ``round1``... (each round: the pieces split to the blocks, the
        global hull in the first, the block triangulations). The neighbours are computed when
        asked for.

    The input points stay in the cluster's memory (read once) while the result is alive, for
    ``points()`` and ``gather()``.
    """

    def __init__(self, pieces, counts, results, offsets, neighbors, grid, stats):
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

        self.simplices = part(results, "simplices", np.int64)
        self.neighbors = part(neighbors, None, np.int64)

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
        return Delaunay._from_arrays(self.points(), simplices.astype(np.int32),
                                     neighbors.astype(np.int32),
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
    _vtu.write_piece(path, r["vertex_points"], r["vertices"], s,
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
    its points with a layer of ghost points around them (and the global hull's extreme points
    and a coarse sample of all the points), keeps the simplices no outside point can change,
    and asks for the points its other simplices' circumballs may hold (by bins of about 8
    points) until those include every simplex round its own points. Each simplex is output by
    the block owning its lowest-indexed vertex. The result is exactly
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
        The ghost width (default: 6 mean point spacings in 2D, 4 in 3D); a block asks for more
        points by bins as it needs, and doubles the width only where a circumcentre is not
        trusted. Blocks on the sides of the bounding box also take a strip along each side from
        the first round (4 ghost widths deep in 2D, half a width in 3D).
    backend : {"auto", "cuda", "cpu"}
        Where each block is triangulated (on each worker: "auto" takes its GPU).
    threads : int
        CPU threads per block. 0 (the default): OpenMP's default in the worker, that is its
        ``OMP_NUM_THREADS``, which Dask sets to 1 unless told otherwise (give each worker process
        its share of the cores there, as ``bench/dask_cluster.py`` does).

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
    summaries = dask.compute(*[delayed(_summary)(p) for p in pieces])
    lap("check")
    start = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
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
    width = {b: float(ghost) for b in all_blocks}
    # boxes along the hull a block asked for; from the first round, strips along the sides of
    # the bounding box its cell touches
    extras = {b: _side_strips(grid, b, _STRIP_DEPTH[d] * ghost) for b in all_blocks}
    rounds = {b: 0 for b in all_blocks}
    asked = {b: np.zeros(0, np.int64) for b in all_blocks}  # the bins a block asked for
    final, metas = {}, {}
    pending = list(all_blocks)
    bins = _bins(lo, hi, n)
    sample = _sample_grid(lo, hi, n)
    hull = total = None
    while pending:
        # each piece is split to the pending blocks' regions and boxes; in the first round the
        # pieces' hull candidates and counts per bin come too, and from them the global hull and
        # the counts of all points, which every round uses
        first = hull is None
        boxes = {b: [grid.region(b, width[b])] + list(extras[b].values()) for b in pending}
        # the bins asked for, one value in the graph that every split refers to (as literals
        # they were copied into each split task: pieces x blocks x up to 2^16 ids)
        wants = delayed({b: asked[b] for b in pending}, traverse=False)
        splits = [delayed(_split, nout=len(pending) + 3 * first)(
            p, int(o), grid, boxes, wants, bins, first, sample, **run)
            for p, o in zip(pieces, start)]
        if first:
            hull = delayed(_global_hull)([s[-3] for s in splits], [s[-1] for s in splits], n,
                                         **run)
            total = delayed(_total)([s[-2] for s in splits])
        tasks = []
        for i, b in enumerate(pending):
            tasks.append(delayed(triangulate_block)(
                b, grid, width[b], dict(extras[b]), [s[i] for s in splits], hull, (bins, total),
                backend, threads,
                dask_key_name=f"gpugeom-delaunay-block-{tag}-{rounds[b]}-{b}"))
            rounds[b] += 1
        # persisted together, so that the pieces are split once a round
        if first:
            *done, hull, total = dask.persist(*tasks, hull, total)
        else:
            done = dask.persist(*tasks)
        for b, r, m in zip(pending, done, dask.compute(*[delayed(_meta)(r) for r in done])):
            if m["done"]:
                final[b], metas[b] = r, m
                continue
            width[b] = m["next_ghost"]
            asked[b] = np.union1d(asked[b], m["bins"])
            for key, (lo, hi) in m["boxes"]:
                if key in extras[b]:
                    lo, hi = np.minimum(lo, extras[b][key][0]), np.maximum(hi, extras[b][key][1])
                extras[b][key] = (lo, hi)
            if rounds[b] >= 4:
                # every block ends: from the fifth round the ghost layer doubles too, until it
                # covers the bounding box, where every simplex is final
                width[b] = max(width[b], 2.0 * m["ghost"])
        pending = [b for b in pending if b not in final]
        lap(f"round{len(timings)}")

    order = [b for b in all_blocks if metas[b]["nlocal"] > 0]  # blocks with points
    sizes = [metas[b]["nsimplex"] for b in order]
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    index = {b: i for i, b in enumerate(order)}
    position = np.full(grid.nblocks, -1, dtype=np.int64)  # grid cell -> place among the results
    position[order] = np.arange(len(order))
    results = [final[b] for b in order]
    neighbors = []
    borders = {b: delayed(_border)(final[b]) for b in order}
    for i, b in enumerate(order):
        owners = {index[c]: borders[c] for c in metas[b]["owners"]}
        neighbors.append(delayed(_neighbors_of)(final[b], offsets, i, position, owners))
    stats = [dict(block=b, ghost=metas[b]["ghost"], extra_boxes=len(extras[b]), rounds=rounds[b],
                  nlocal=metas[b]["nlocal"],
                  nsimplex=metas[b]["nsimplex"], tested=metas[b]["tested"]) for b in order]
    out = DistributedTriangulation(pieces, counts, results, offsets, neighbors, grid, stats)
    out.timings = timings
    return out


def _neighbors_of(r, offsets, i, position, owners):
    # the requests name blocks by grid cell; the offsets go by place among the filled blocks
    r = dict(r)
    r["req_owner"] = position[r["req_owner"]]
    return _neighbors(r, offsets, i, owners)
