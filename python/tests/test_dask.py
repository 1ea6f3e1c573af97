"""gpugeom.dask: the distributed triangulation equals the single run, simplex for simplex and
neighbour for neighbour, on uniform, clustered and degenerate input across 2, 3 and 8 blocks, on
a LocalCluster of CPU workers (one of them killed mid-run) and on Dask's threads."""
import os

import numpy as np
import pytest

import gpugeom
from gpugeom import _core

dask = pytest.importorskip("dask")
da = pytest.importorskip("dask.array")
distributed = pytest.importorskip("distributed")
gd = pytest.importorskip("gpugeom.dask")
from gpugeom.dask._blocks import Grid, choose_counts  # noqa: E402


def _keys(simplices):
    return np.sort(np.asarray(simplices, dtype=np.int64), axis=1)


def _relation(simplices, neighbors):
    """Every (simplex, vertex, neighbour across the opposite face) as sorted vertex tuples, so
    two triangulations compare whatever their order."""
    s = np.asarray(simplices, dtype=np.int64)
    nb = np.asarray(neighbors, dtype=np.int64)
    key = _keys(s)
    d1 = s.shape[1]
    rows = []
    for j in range(d1):
        other = np.where(nb[:, j:j + 1] >= 0, key[np.maximum(nb[:, j], 0)], -1)
        rows.append(np.concatenate([key, s[:, j:j + 1], other], axis=1))
    r = np.concatenate(rows)
    return r[np.lexsort(r.T[::-1])]


def _same_as_single(pts, dt):
    ref = gpugeom.Delaunay(pts, backend="cpu")
    g = dt.gather()
    assert g.nsimplex == ref.nsimplex == dt.nsimplex
    np.testing.assert_array_equal(_relation(g.simplices, g.neighbors),
                                  _relation(ref.simplices, ref.neighbors))
    np.testing.assert_array_equal(g.duplicate_of, ref.duplicate_of)
    # every simplex positively oriented, as the single run's
    s = np.asarray(g.simplices)
    e = pts[s[:, 1:]] - pts[s[:, :1]]
    assert (np.linalg.det(e) > 0).all()
    return g


def _families(d, rng):
    n = 3000 if d == 2 else 2500
    centres = rng.random((6, d))
    k = 8 if d == 2 else 6
    grid = np.stack(np.meshgrid(*[np.arange(float(k * (4 - d)))] * d, indexing="ij"),
                    -1).reshape(-1, d)
    sphere = rng.normal(size=(400, d))
    sphere /= np.linalg.norm(sphere, axis=1)[:, None]
    uniform = rng.random((n, d))
    copies = np.concatenate([uniform[:500], uniform[:50]])
    return {
        "uniform": uniform,
        "clustered": (centres[rng.integers(0, 6, n)] + 0.02 * rng.normal(size=(n, d))),
        "grid": grid,
        "sphere": sphere,
        "copies": copies,
    }


@pytest.mark.parametrize("d", [2, 3])
def test_equal_to_single_run_on_threads(d):
    rng = np.random.default_rng(7 + d)
    with dask.config.set(scheduler="threads"):
        for name, pts in _families(d, rng).items():
            for blocks in (2, 3, 8):
                dt = gd.delaunay(pts, blocks=blocks, backend="cpu")
                assert len(dt.block_stats) <= blocks, name
                _same_as_single(pts, dt)


def test_each_backend(backend):
    """The blocks on the GPU (a block's tests in CuPy where it is installed) and on the CPU."""
    rng = np.random.default_rng(23)
    with dask.config.set(scheduler="threads"):
        for d in (2, 3):
            fam = _families(d, rng)
            for name in ("uniform", "grid", "copies"):
                _same_as_single(fam[name], gd.delaunay(fam[name], blocks=5, backend=backend))


def test_judged_in_pieces(monkeypatch):
    """A block tests its simplices in pieces (to bound the temporaries): the same result."""
    from gpugeom.dask import _ghost
    pts = np.random.default_rng(29).random((3000, 3))
    with dask.config.set(scheduler="threads"):
        whole = gd.delaunay(pts, blocks=4, backend="cpu")
        monkeypatch.setattr(_ghost, "_PIECE", 97)
        pieces = gd.delaunay(pts, blocks=4, backend="cpu")
        a, b = dask.compute(whole.simplices, pieces.simplices)
    np.testing.assert_array_equal(a, b)
    assert [s["rounds"] for s in whole.block_stats] == [s["rounds"] for s in pieces.block_stats]


def test_inputs_as_dask_array_list_and_files(tmp_path):
    rng = np.random.default_rng(3)
    pts = rng.random((4000, 3))
    ref = _relation(*(lambda t: (t.simplices, t.neighbors))(gpugeom.Delaunay(pts, backend="cpu")))
    files = []
    for i, part in enumerate(np.array_split(pts, 3)):
        files.append(str(tmp_path / f"part{i}.npy"))
        np.save(files[-1], part)
    with dask.config.set(scheduler="threads"):
        for points in (da.from_array(pts, chunks=(1000, 3)), list(np.array_split(pts, 4)),
                       files):
            dt = gd.delaunay(points, backend="cpu")
            g = dt.gather()
            np.testing.assert_array_equal(_relation(g.simplices, g.neighbors), ref)
            # the Dask arrays themselves: global indices, neighbours across blocks
            s, nb = dask.compute(dt.simplices, dt.neighbors)
            assert s.dtype == np.int64 and s.shape == (dt.nsimplex, 4)
            np.testing.assert_array_equal(_relation(s, nb), ref)
        assert gd.delaunay(files, backend="cpu").blocks == (1, 1, 3)


def test_same_arrays_every_run():
    pts = np.random.default_rng(5).random((3000, 2))
    with dask.config.set(scheduler="threads"):
        a = dask.compute(gd.delaunay(pts, blocks=6, backend="cpu").simplices)[0]
        b = dask.compute(gd.delaunay(pts, blocks=6, backend="cpu").simplices)[0]
    np.testing.assert_array_equal(a, b)


def test_local_cluster(cluster_client):
    rng = np.random.default_rng(11)
    for d in (2, 3):
        pts = rng.random((5000, d))
        dt = gd.delaunay(da.from_array(pts, chunks=(1250, d)), blocks=8, backend="cpu")
        assert len(dt.block_stats) == 8
        _same_as_single(pts, dt)
    # by default a block a worker where the array has fewer chunks
    dt = gd.delaunay(da.from_array(pts, chunks=-1), backend="cpu")
    assert len(dt.block_stats) == 2
    _same_as_single(pts, dt)


def test_worker_killed_mid_run(kill_worker_once):
    with kill_worker_once("gpugeom-delaunay-block") as killed:
        pts = np.random.default_rng(13).random((4000, 3))
        dt = gd.delaunay(da.from_array(pts, chunks=(1000, 3)), blocks=4, backend="cpu")
        assert killed()  # a worker did die, Dask ran its task again
        _same_as_single(pts, dt)


def test_to_pvtu(tmp_path):
    meshio = pytest.importorskip("meshio")
    pts = np.random.default_rng(17).random((3000, 3))
    with dask.config.set(scheduler="threads"):
        dt = gd.delaunay(pts, blocks=4, backend="cpu")
        files = dt.to_pvtu(tmp_path / "mesh.pvtu")
    assert len(files) == 5 and files[0].endswith("mesh.pvtu")
    text = open(files[0]).read()
    assert text.count("<Piece Source=") == 4
    cells = []
    for f in files[1:]:
        m = meshio.read(f)
        gid = np.asarray(m.point_data["global_id"]).ravel()
        np.testing.assert_array_equal(m.points, pts[gid])
        cells.append(gid[m.cells_dict["tetra"]])
    got = np.concatenate(cells)
    want = dask.compute(dt.simplices, scheduler="threads")[0]
    np.testing.assert_array_equal(got, want)
    assert not [f for f in os.listdir(tmp_path) if ".tmp" in f]
    with pytest.raises(ValueError, match="pvtu"):
        dt.to_pvtu(tmp_path / "mesh.vtu")


def test_bad_input_refused_before_any_block_runs():
    pts = np.random.default_rng(19).random((1000, 3))
    bad = pts.copy()
    bad[617, 1] = np.nan
    with dask.config.set(scheduler="threads"):
        with pytest.raises(ValueError, match="point 617 has a NaN"):
            gd.delaunay(da.from_array(bad, chunks=(300, 3)), blocks=4, backend="cpu")
        with pytest.raises(ValueError, match="rechunk"):
            gd.delaunay(da.from_array(pts, chunks=(500, 2)), backend="cpu")
        with pytest.raises(ValueError, match="same width"):
            gd.delaunay([pts, pts[:, :2]], backend="cpu")
        with pytest.raises(ValueError, match=r"shape \(n, 2\) or \(n, 3\)"):
            gd.delaunay(np.zeros((10, 4)), backend="cpu")
        with pytest.raises(ValueError, match="blocks"):
            gd.delaunay(pts, blocks=0, backend="cpu")
        with pytest.raises(ValueError, match="unknown size"):
            x = da.from_array(pts, chunks=(500, 3))
            gd.delaunay(x[x[:, 0] > 0.5], backend="cpu")
        with pytest.raises(gpugeom.DegenerateInputError):
            flat = pts.copy()
            flat[:, 2] = 0.25
            gd.delaunay(flat, blocks=4, backend="cpu")


def test_blocks_and_rows():
    assert choose_counts([1.0, 1.0, 1.0], 8) == (2, 2, 2)
    assert choose_counts([4.0, 1.0], 8) == (8, 1)
    assert choose_counts([1.0, 0.0], 3) == (3, 1)
    g = Grid([0, 0], [1, 1], (2, 2))
    np.testing.assert_array_equal(g.cell_of(np.array([[0.0, 0.0], [1.0, 1.0], [0.5, 0.2]])),
                                  [0, 3, 2])
    assert g.covers_all(0, 1.0) and not g.covers_all(0, 0.4)
    pts = np.random.default_rng(47).random((5000, 2)) * 1.2 - 0.1  # some outside: clamped
    cell, order, cuts = g.split(pts, threads=2)
    want = (np.clip(np.floor(pts[:, 0] / 0.5), 0, 1) * 2 + np.clip(np.floor(pts[:, 1] / 0.5), 0, 1))
    np.testing.assert_array_equal(cell, want.astype(np.int64))
    np.testing.assert_array_equal(order, np.argsort(cell, kind="stable"))
    np.testing.assert_array_equal(cuts, np.searchsorted(cell[order], np.arange(5)))


def test_split_to_blocks():
    """The split of a piece to the blocks of a round (``Grid.split`` with boxes: each block's
    own points and those in its boxes, in order) against NumPy: boxes that reach past the
    grid, that touch points exactly, that overlap within one block, and a block left out."""
    rng = np.random.default_rng(48)
    g = Grid([0, 0], [3, 2], (3, 2))
    pts = rng.random((20000, 2)) * [3.4, 2.4] - 0.2  # some outside the grid: clamped
    pts[:50] = np.round(pts[:50] * 4) / 4  # on the boxes' sides
    boxes = {0: [(np.array([-1.0, -1.0]), np.array([1.25, 1.25]))],
             2: [(np.array([0.75, -1.0]), np.array([2.25, 1.25])),
                 (np.array([1.0, 0.5]), np.array([1.5, 3.0])), (pts[7], pts[7])],
             3: [], 5: [(np.array([-5.0, 1.75]), np.array([5.0, 5.0]))]}
    cell = g.cell_of(pts)
    ref = {}
    for b, bs in boxes.items():
        keep = cell == b
        for lo, hi in bs:
            keep |= np.all((pts >= lo) & (pts <= hi), axis=1)
        ref[b] = np.nonzero(keep)[0]
    for threads in (1, 2, 3):
        c, order, cuts, points, cells = g.split(pts, boxes, threads=threads, gather=True)
        np.testing.assert_array_equal(c, cell)
        np.testing.assert_array_equal(points, pts[order])
        np.testing.assert_array_equal(cells, cell[order])
        for b in range(g.nblocks):
            np.testing.assert_array_equal(order[cuts[b]:cuts[b + 1]],
                                          ref.get(b, np.zeros(0, np.int64)))
    with pytest.raises(ValueError):
        g.split(pts, {9: [(np.zeros(2), np.ones(2))]})
    for block in ([1, 0], [0, 7]):  # out of order, outside the grid
        with pytest.raises(ValueError):
            _core.split_to_blocks(pts, [0.0, 0.0], [1.0, 1.0], [3, 2], box_lo=np.zeros((2, 2)),
                                  box_hi=np.ones((2, 2)), box_block=np.array(block, np.int64))


def _bins_of(pts, bins):
    """Each point's bin as ``_core.cell_counts`` counts it (row-major)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.floor((pts - bins.lo) / bins.width)
    k = np.where(bins.width > 0, np.clip(np.nan_to_num(k), 0, bins.counts - 1), 0)
    return np.ravel_multi_index(tuple(k.astype(np.int64).T), tuple(bins.counts))


def test_split_to_blocks_with_bins():
    """Blocks that ask for whole bins (``Grid.split`` with requests) get every point of those
    bins, once, whether a box or their cell gave it to them already, in order; and the bins are
    the ones ``_core.cell_counts`` counts the points in."""
    rng = np.random.default_rng(50)
    g = Grid([0, 0], [3, 2], (3, 2))
    bins = Grid([0, 0], [3, 2], (30, 16))
    pts = rng.random((20000, 2)) * [3, 2]
    pts[:40] = np.round(pts[:40] * 10) / 10  # on the bins' sides
    pts[40:60] = [3.0, 2.0]  # on the last bins' far sides
    counts = _core.cell_counts(pts, bins.lo.tolist(), bins.width.tolist(), bins.counts.tolist())
    of = _bins_of(pts, bins)
    np.testing.assert_array_equal(counts.ravel(), np.bincount(of, minlength=480))
    boxes = {0: [(np.array([-1.0, -1.0]), np.array([1.25, 1.25]))], 1: [], 4: []}
    asked = {0: np.array([5, 17, 17, 200, 479]), 1: np.arange(0, 480, 7), 4: np.zeros(0, int)}
    cell = g.cell_of(pts)
    for threads in (1, 2, 3):
        c, order, cuts = g.split(pts, boxes, threads=threads, requests=(bins, asked))
        for b in range(g.nblocks):
            keep = np.zeros(len(pts), bool)
            if b in boxes:
                keep = (cell == b) | np.isin(of, asked[b])
                for lo, hi in boxes[b]:
                    keep |= np.all((pts >= lo) & (pts <= hi), axis=1)
            np.testing.assert_array_equal(order[cuts[b]:cuts[b + 1]], np.nonzero(keep)[0])
    with pytest.raises(ValueError):  # a bin outside the grid of bins
        g.split(pts, {0: []}, requests=(bins, {0: np.array([480])}))


@pytest.mark.parametrize("d", [2, 3])
def test_balls_in_bins(d):
    """The test of balls cut to boxes against the bins with outside points
    (``_core.balls_in_bins``) against NumPy: each marked bin whose box, grown by the margin,
    meets the cut box and lies within reach of the centre."""
    rng = np.random.default_rng(51 + d)
    counts = np.array([12, 9, 7][:d])
    lo, width = np.zeros(d), np.full(d, 0.5)
    marked = rng.random(int(np.prod(counts))) < 0.3
    m = 300
    centre = rng.random((m, d)) * counts * 0.5
    reach = rng.random(m) * 1.5
    reach[:5] = np.inf
    blo = centre - rng.random((m, d)) * 2
    bhi = centre + rng.random((m, d)) * 2
    bhi[5:10] = blo[5:10] - 1  # empty
    margin = 1e-9
    k = np.stack(np.unravel_index(np.arange(marked.size), tuple(counts)), 1)
    clo, chi = lo + k * width - margin, lo + (k + 1) * width + margin
    want = np.zeros((m, marked.size), bool)
    for i in range(m):
        meets = np.all((clo <= bhi[i]) & (chi >= blo[i]), axis=1) & marked
        if np.isfinite(reach[i]):
            gap = np.maximum(np.maximum(clo - centre[i], centre[i] - chi), 0)
            meets &= np.sqrt((gap ** 2).sum(axis=1)) <= reach[i]
        want[i] = meets
    for threads in (1, 3):
        r = _core.balls_in_bins(centre, reach, blo, bhi, lo.tolist(), width.tolist(),
                                counts.tolist(), marked, margin, collect=True, threads=threads)
        np.testing.assert_array_equal(r["meets"].view(bool), want.any(axis=1))
        np.testing.assert_array_equal(r["cells"], np.nonzero(want.any(axis=0))[0])
        q = _core.balls_in_bins(centre, reach, blo, bhi, lo.tolist(), width.tolist(),
                                counts.tolist(), marked, margin, collect=False, threads=threads)
        np.testing.assert_array_equal(q["meets"], r["meets"])
        assert len(q["cells"]) == 0


def test_clustered_blocks_ask_for_bins():
    """Clusters apart: a block asks for the bins its balls between clusters meet, not for a
    wider layer that takes the clusters round it whole (here that took 5.2 local points a
    point, this 2.5; 1.1 on 10^6 points); points on a sphere in 3D, where every ball is the
    sphere's (the caps along the hull cost simplices times hull planes: 8 s a block at 2·10^4
    points)."""
    rng = np.random.default_rng(52)
    centres = rng.random((24, 2))
    pts = centres[rng.integers(0, 24, 40000)] + 0.01 * rng.normal(size=(40000, 2))
    sphere = rng.normal(size=(6000, 3))
    sphere /= np.linalg.norm(sphere, axis=1)[:, None]
    with dask.config.set(scheduler="threads"):
        dt = gd.delaunay(pts, blocks=6, backend="cpu")
        _same_as_single(pts, dt)
        assert sum(s["nlocal"] for s in dt.block_stats) < 3.0 * len(pts)
        assert max(s["rounds"] for s in dt.block_stats) >= 2  # the clusters did ask
        _same_as_single(sphere, gd.delaunay(sphere, blocks=4, backend="cpu"))


def test_coarse_paths_are_exact(monkeypatch):
    """The paths that trade points for work: no caps along the hull (past ``_CAP_WORK``) and a
    ball that asks for every bin with outside points (past ``_ASK_ALL``). Forced everywhere,
    they give the same triangulation, with no fewer local points."""
    from gpugeom.dask import _ghost
    rng = np.random.default_rng(53)
    centres = rng.random((10, 2))
    flat = centres[rng.integers(0, 10, 8000)] + 0.01 * rng.normal(size=(8000, 2))
    cube = rng.random((4000, 3))
    with dask.config.set(scheduler="threads"):
        fine = [gd.delaunay(p, blocks=4, backend="cpu") for p in (flat, cube)]
        monkeypatch.setattr(_ghost, "_CAP_WORK", 0)
        monkeypatch.setattr(_ghost, "_ASK_ALL", 0.0)
        for p, f in zip((flat, cube), fine):
            dt = gd.delaunay(p, blocks=4, backend="cpu")
            _same_as_single(p, dt)
            assert sum(s["nlocal"] for s in dt.block_stats) >= \
                sum(s["nlocal"] for s in f.block_stats)
        assert max(s["rounds"] for s in fine[0].block_stats) >= 2


def test_local_points():
    """A block's local points from its parts and the hull's extreme points (``_local_points``,
    by slices between the hull points' places) against a concatenation and a stable sort:
    parts missing or empty, hull points already among the parts, before, between and after."""
    from gpugeom.dask._ghost import _local_points
    rng = np.random.default_rng(49)
    for _ in range(300):
        parts, base = [], 0
        for _ in range(rng.integers(1, 6)):
            m = int(rng.integers(0, 30))
            ids = np.sort(rng.choice(np.arange(base, base + 60), m, replace=False)).astype(np.int64)
            base += 60
            parts.append((rng.random((m, 2)), ids, rng.integers(0, 5, m))
                         if m or rng.random() < 0.5 else None)
        h_ids = np.sort(rng.choice(base + 5, int(rng.integers(0, 12)), replace=False))
        h_pts, h_blk = rng.random((len(h_ids), 2)), rng.integers(0, 5, len(h_ids))
        for p in (p for p in parts if p is not None):  # a point present has its coordinates
            at = np.searchsorted(p[1], h_ids)
            hit = np.nonzero((at < len(p[1])) & (p[1][np.minimum(at, max(len(p[1]) - 1, 0))]
                                                 == h_ids))[0] if len(p[1]) else []
            h_pts[hit], h_blk[hit] = p[0][at[hit]], p[2][at[hit]]
        got = [p for p in parts if p is not None]
        ids = np.concatenate([p[1] for p in got] + [np.zeros(0, np.int64)])
        keep = ~np.isin(h_ids, ids)
        all_ids = np.concatenate([ids, h_ids[keep]])
        order = np.argsort(all_ids, kind="stable")
        want = (all_ids[order],
                np.concatenate([p[0] for p in got] + [h_pts[keep]])[order],
                np.concatenate([p[2] for p in got] + [h_blk[keep]])[order])
        for a, b in zip(_local_points(parts, (h_pts, h_ids, h_blk)), want):
            np.testing.assert_array_equal(a, b)


def test_block_neighbors():
    """A block's neighbours across blocks (``_core.block_neighbors``): its own rows shifted by its
    offset, -1 kept, each request found by its key in its owner's border whatever the order of
    the border's rows; a key or an owner that is not there is a bug, reported as one."""
    nb_local = np.array([[1, -1, -2], [0, -2, -1], [-2, 0, -1]], np.int64)
    req_owner = np.array([4, 7, 4], np.int64)
    req_key = np.array([[1, 5, 9], [2, 3, 8], [0, 5, 6]], np.int64)
    req_pos = np.array([2, 4, 6], np.int64)
    borders = [(4, 100, np.array([3, 8, 11], np.int64),
                np.array([[0, 5, 6], [1, 5, 9], [1, 5, 8]], np.int64)),
               (7, 500, np.array([2], np.int64), np.array([[2, 3, 8]], np.int64))]
    got = _core.block_neighbors(nb_local, 20, req_owner, req_key, req_pos, borders, 2)
    np.testing.assert_array_equal(got, [[21, -1, 108], [20, 502, -1], [103, 20, -1]])
    with pytest.raises(RuntimeError, match="not found"):
        _core.block_neighbors(nb_local, 20, req_owner, req_key + 1, req_pos, borders)
    with pytest.raises(RuntimeError, match="not found"):
        _core.block_neighbors(nb_local, 20, req_owner, req_key, req_pos, borders[:1])
    with pytest.raises(ValueError, match="req_pos"):
        _core.block_neighbors(nb_local, 20, req_owner, req_key, req_pos + 3, borders)


def test_bulk_circumball_test():
    """The C++ first test of a block's simplices (_core.circumballs_inside_region) accepts only
    simplices whose circumball, computed exactly, holds no point outside the region, and agrees
    with the NumPy test it stands in for (the same centre, bound and slabs)."""
    from fractions import Fraction

    from gpugeom.dask import _ghost
    for d in (2, 3):
        pts = np.random.default_rng(31 + d).random((1500, d))
        s = np.asarray(gpugeom.Delaunay(pts, backend="cpu").simplices, dtype=np.int64)
        lo, hi = np.full(d, 0.25), np.full(d, 0.75)
        box_lo, box_hi = pts.min(axis=0), pts.max(axis=0)
        rows = np.arange(len(s), dtype=np.int64)
        got = _core.circumballs_inside_region(pts, s, rows, lo.tolist(), hi.tolist(),
                                              box_lo.tolist(), box_hi.tolist(), 1.0, 2)
        assert got.dtype == np.uint8 and got.shape == (len(s),)
        assert 0 < int(got.sum()) < len(s)
        centre, radius, err = _ghost._circumcentres(pts, s)
        reach = radius + 2.0 * err + 64.0 * _ghost._EPS * (1.0 + np.abs(centre).max(axis=1)
                                                           + radius)
        slabs = _ghost._slabs(lo, hi, box_lo, box_hi)
        want = _ghost._ball_misses(centre, reach, slabs)
        assert int((want != got.astype(bool)).sum()) <= len(s) // 1000
        # exact: no point outside the region in an accepted simplex's closed circumball
        outside = pts[~np.all((pts >= lo) & (pts <= hi), axis=1)]
        for i in np.nonzero(got)[0][:: max(1, int(got.sum()) // 40)]:
            v = [[Fraction(float(c)) for c in pts[j]] for j in s[i]]
            a = [[v[k + 1][m] - v[0][m] for m in range(d)] for k in range(d)]
            b = [sum(x * x for x in row) / 2 for row in a]
            x = _solve(a, b)
            r2 = sum(t * t for t in x)
            c = [v[0][m] + x[m] for m in range(d)]
            near = outside[np.sum((outside - np.array([float(t) for t in c])) ** 2, axis=1)
                           < float(r2) * 1.01]
            for q in near:
                assert sum((Fraction(float(q[m])) - c[m]) ** 2 for m in range(d)) > r2
        with pytest.raises(ValueError, match="rows"):
            _core.circumballs_inside_region(pts, s, np.array([len(s)], np.int64), lo.tolist(),
                                            hi.tolist(), box_lo.tolist(), box_hi.tolist(), 1.0)


def test_hull_candidates2d():
    """A 2D piece's hull candidates (``_core.hull_candidates2d``) hold every extreme point, on
    points in general position, on a circle and on a grid (where many lie on the polygon's
    edges); most interior points go."""
    rng = np.random.default_rng(53)
    t = rng.random(2000) * 2 * np.pi
    grid = np.stack(np.meshgrid(np.arange(30.0), np.arange(20.0)), -1).reshape(-1, 2)
    for pts in (rng.random((20000, 2)), np.stack([np.cos(t), np.sin(t)], 1), grid,
                rng.normal(size=(5000, 2)) * [1e-3, 1e3]):
        cand = _core.hull_candidates2d(pts, 2)
        assert np.all(np.diff(cand) > 0)
        hull = np.asarray(gpugeom.ConvexHull(pts, backend="cpu").vertices)
        assert set(hull.tolist()) <= set(cand.tolist())
    assert len(_core.hull_candidates2d(rng.random((20000, 2)))) < 1000
    np.testing.assert_array_equal(_core.hull_candidates2d(np.zeros((3, 2))), [0, 1, 2])


def test_block_passes_in_cpp_and_numpy():
    """A block's required simplices and its output from C++ (``_core.block_required`` and
    ``_core.block_output``, which every block runs), against references in NumPy: the same
    arrays, on random blocks of 2D and 3D triangulations; bad indices refused."""
    from gpugeom.dask import _ghost
    rng = np.random.default_rng(43)
    for d in (2, 3):
        pts = rng.random((3000, d))
        tri = gpugeom.Delaunay(pts, backend="cpu")
        s = np.asarray(tri.simplices, dtype=np.int64)
        nb = np.asarray(tri.neighbors, dtype=np.int64)
        blk = rng.integers(0, 3, len(pts)).astype(np.int64)
        blk[pts[:, 0] < 0.4] = 1  # a region of one block, and mixed ones elsewhere
        ids = np.sort(rng.choice(10**6, len(pts), replace=False)).astype(np.int64)
        owned = blk == 1
        r = _core.block_required(s, nb, owned, 2)
        mine, required = _required_reference(s, nb, owned)
        np.testing.assert_array_equal(r["owned_rows"], mine)
        np.testing.assert_array_equal(r["required"].view(bool), required)
        got = _ghost._emit(ids, pts, blk, s, nb, mine, 2)
        want = _emit_reference(ids, pts, blk, s, nb, mine, d)
        assert set(got) == set(want) and len(got["req_pos"]) > 0
        for k in want:
            np.testing.assert_array_equal(got[k], want[k], err_msg=k)
        # int32 indices, as a triangulation gives them, give the same
        s32, nb32 = s.astype(np.int32), nb.astype(np.int32)
        r32 = _core.block_required(s32, nb32, owned, 2)
        for k in ("owned_rows", "required"):
            np.testing.assert_array_equal(r32[k], r[k], err_msg=k)
        got32 = _ghost._emit(ids, pts, blk, s32, nb32, mine, 2)
        for k in want:
            np.testing.assert_array_equal(got32[k], want[k], err_msg=k)
        with pytest.raises(ValueError, match="neighbors"):
            _core.block_required(s32, nb, owned)
        bad = s.copy()
        bad[5, 1] = len(pts)
        with pytest.raises(ValueError, match="simplices"):
            _core.block_required(bad, nb, owned)
        with pytest.raises(ValueError, match="rows"):
            _core.block_output(s, nb, np.array([len(s)], np.int64), ids, blk)


def _required_reference(s, nb, owned):
    """What a block requires, in NumPy: the owned simplices (lowest vertex owned) and the mask
    of the stars of the owned points and of each owned simplex's neighbour opposite its lowest
    vertex."""
    low = s.min(axis=1)
    mine = np.nonzero(owned[low])[0]
    ring = nb[mine, np.argmin(s[mine], axis=1)]
    required = owned[s].any(axis=1)
    required[ring[ring >= 0]] = True
    return mine, required


def _emit_reference(ids, pts, blk, s, nb, rows, d, xp=np):
    """The owned simplices' output in array code (NumPy here), as the C++ pass must give it."""
    d1 = d + 1
    pos = xp.full(len(s), -1, dtype=xp.int64)
    pos[rows] = xp.arange(len(rows))
    nbr = nb[rows]
    # the rows are all the simplices whose lowest vertex is owned: a neighbour is a row here
    # exactly where it is owned here, so only the few faces whose neighbour is not need its
    # lowest vertex (its owner)
    nb_local = xp.where(nbr >= 0, pos[xp.maximum(nbr, 0)], -1)
    fi, fj = xp.nonzero((nbr >= 0) & (nb_local < 0))
    other = nbr[fi, fj]
    nb_local[fi, fj] = -2
    tau = np.asarray(s[other])
    mark = xp.zeros(len(ids), dtype=bool)
    mark[s[rows].ravel()] = True
    used = np.asarray(xp.nonzero(mark)[0])
    simplices = ids[np.asarray(s[rows])]
    border = np.nonzero((np.asarray(nb_local) == -2).any(axis=1))[0]
    return dict(simplices=simplices, nb_local=np.asarray(nb_local),
                req_owner=blk[tau.min(axis=1)] if len(tau) else np.zeros(0, np.int64),
                req_key=np.sort(ids[tau], axis=1), req_pos=np.asarray(fi * d1 + fj),
                vertices=ids[used], vertex_points=pts[used], border_rows=border,
                border_keys=np.sort(simplices[border], axis=1))


def _solve(a, b):
    """Gaussian elimination over Fractions (exact)."""
    n = len(b)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = next(r for r in range(c, n) if m[r][c] != 0)
        m[c], m[p] = m[p], m[c]
        for r in range(n):
            if r != c and m[r][c] != 0:
                f = m[r][c] / m[c][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [m[i][n] / m[i][i] for i in range(n)]
