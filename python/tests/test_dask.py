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
            # (int32, as SciPy's and a single call's: fewer than 2^31 points and simplices)
            assert s.dtype == np.int32 and nb.dtype == np.int32 and s.shape == (dt.nsimplex, 4)
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
    # points on a sphere: one block in a worker process, on the cores it may run on
    sphere = rng.normal(size=(5000, 3))
    sphere /= np.linalg.norm(sphere, axis=1)[:, None]
    dt = gd.delaunay(da.from_array(sphere, chunks=(1250, 3)), blocks=8, backend="cpu")
    assert [s["block"] for s in dt.block_stats] == [0]
    _same_as_single(sphere, dt)


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


def test_cell_counts():
    """The count of points per bin (``_core.cell_counts``, the test's "outside" bins) against
    NumPy: points on the bins' sides and on the last bins' far sides, a flat axis."""
    rng = np.random.default_rng(50)
    pts = rng.random((20000, 2)) * [3, 2]
    pts[:40] = np.round(pts[:40] * 10) / 10  # on the bins' sides
    pts[40:60] = [3.0, 2.0]  # on the last bins' far sides
    for bins, p in ((Grid([0, 0], [3, 2], (30, 16)), pts),
                    (Grid([0, 1], [3, 1], (30, 1)), np.stack([pts[:, 0], np.ones(len(pts))], 1))):
        for threads in (1, 3):
            counts = _core.cell_counts(p, bins.lo.tolist(), bins.width.tolist(),
                                       bins.counts.tolist(), threads)
            np.testing.assert_array_equal(counts.ravel(),
                                          np.bincount(_bins_of(p, bins), minlength=counts.size))


def _frontiers_reference(counts, regions, cap, near=None):
    """``_core.empty_frontiers`` by SciPy: the empty bins' components (sides, edges and corners
    connect), those an empty bin of a block's region is in, the occupied bins beside them but not
    strictly inside the region's bins; past the cap only those in the bins ``near`` (per block
    its ranges within the band), and past it still none."""
    from scipy import ndimage
    d = counts.ndim
    empty = counts == 0
    lab, _ = ndimage.label(empty, structure=np.ones((3,) * d))
    out = []
    for first, last in regions:
        box = tuple(slice(a, b + 1) for a, b in zip(first, last))
        seeds = np.unique(lab[box])
        beside = ndimage.binary_dilation(np.isin(lab, seeds[seeds > 0]),
                                         structure=np.ones((3,) * d)) & ~empty
        inner = np.zeros_like(beside)
        inner[tuple(slice(a + 1, b) for a, b in zip(first, last))] = True
        bins = np.nonzero((beside & ~inner).ravel())[0]
        out.append(bins)
    for b, bins in enumerate(out):
        if counts.ravel()[bins].sum() > cap and near is not None:
            at = np.stack(np.unravel_index(bins, counts.shape), 1)
            bins = bins[np.all((at >= near[b][0]) & (at <= near[b][1]), axis=1)]
        out[b] = bins if counts.ravel()[bins].sum() <= cap else bins[:0]
    return out


@pytest.mark.parametrize("d", [2, 3])
def test_empty_frontiers_maze(d):
    """The empty bins' components are labelled in parallel (a forest linked from higher bins to
    lower): near the percolation threshold the empty space is a maze of components of every size
    and shape, long thin ones across many threads' rows included; small regions scattered over it
    each reach some of them. Every thread count gives SciPy's answer."""
    rng = np.random.default_rng(90 + d)
    shape, p_empty = ((300, 200), 0.40) if d == 2 else ((40, 30, 35), 0.10)
    counts = np.where(rng.random(shape) < p_empty, 0, rng.integers(1, 5, shape)).astype(np.int32)
    lo, width = [0.0] * d, [1.0] * d
    rlo = rng.random((12, d)) * (np.array(shape) - 6)
    rhi = rlo + rng.random((12, d)) * 5
    regions = [(np.floor(a).astype(int), np.floor(b).astype(int)) for a, b in zip(rlo, rhi)]
    want = _frontiers_reference(counts, regions, int(counts.sum()))
    assert len({len(w) for w in want}) > 3  # the regions reach different parts of the maze
    for threads in (1, 2, 4):
        f = _core.empty_frontiers(counts, lo, width, list(shape), rlo, rhi, int(counts.sum()),
                                  threads=threads)
        for b, w in enumerate(want):
            np.testing.assert_array_equal(f["bins"][f["offsets"][b]:f["offsets"][b + 1]], w)


@pytest.mark.parametrize("d", [2, 3])
def test_empty_frontiers(d):
    """The bins beside empty space a block's region reaches (``_core.empty_frontiers``) against
    SciPy's labels: clusters apart, a region inside a cluster (reaching no empty bin), regions
    past the grid, the cap; then the split gives each block those bins' points once (a point in
    one of its boxes too is not listed twice)."""
    rng = np.random.default_rng(70 + d)
    centres = rng.random((9, d))
    pts = centres[rng.integers(0, 9, 6000)] + 0.03 * rng.normal(size=(6000, d))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    bins = Grid(lo, hi, (24,) * d if d == 2 else (12,) * d)
    counts = _core.cell_counts(pts, bins.lo.tolist(), bins.width.tolist(), bins.counts.tolist())
    grid = Grid(lo, hi, (2,) + (1,) * (d - 1))
    regions = [grid.region(b, 0.05) for b in range(grid.nblocks)]
    # a region inside the densest bin, reaching no empty bin, and one past the whole grid
    core = np.array(np.unravel_index(int(np.argmax(counts)), counts.shape))
    at = bins.lo + (core + 0.5) * bins.width
    regions += [(at, at), (lo - 1.0, hi + 1.0)]
    rlo = np.array([r[0] for r in regions], np.float64)
    rhi = np.array([r[1] for r in regions], np.float64)
    def ranges(grow):
        out = []
        for a, b in zip(rlo - grow, rhi + grow):
            f = np.clip(np.floor((a - bins.lo) / bins.width), 0, bins.counts - 1).astype(int)
            la = np.clip(np.floor((b - bins.lo) / bins.width), 0, bins.counts - 1).astype(int)
            out.append((f, la))
        return out

    band = 2.5 * float(bins.width.max())
    sizes = {}
    for cap, bd in ((len(pts), 0.0), (300, 0.0), (300, band), (900, band)):
        want = _frontiers_reference(counts, ranges(0.0), cap, ranges(bd) if bd else None)
        sizes[cap, bd] = [len(w) for w in want]
        for threads in (1, 3):
            f = _core.empty_frontiers(counts, bins.lo.tolist(), bins.width.tolist(),
                                      bins.counts.tolist(), rlo, rhi, cap, band=bd,
                                      threads=threads)
            for b, w in enumerate(want):
                got = f["bins"][f["offsets"][b]:f["offsets"][b + 1]]
                np.testing.assert_array_equal(got, w)
                assert f["points"][b] == counts.ravel()[w].sum()
    full = sizes[len(pts), 0.0]
    # the cases are there: the blocks' and the whole grid's bins, the core's none, the cap hit,
    # and the band keeping a part where the cap took all
    assert min(full[0], full[1], full[3]) > 0 and full[2] == 0
    assert any(c == 0 < f for c, f in zip(sizes[300, 0.0], full))
    if d == 2:  # (3D's 12^3 bins: every block's bins near it are past 300 points too)
        assert any(c == 0 < k < f for c, k, f in zip(sizes[300, 0.0], sizes[300, band], full))
    # the split: the two blocks of `grid` (its own regions only) with a box each
    f = _core.empty_frontiers(counts, bins.lo.tolist(), bins.width.tolist(),
                              bins.counts.tolist(), rlo[:2], rhi[:2], len(pts))
    assert len(f["bins"]) > 0
    boxes = {b: [regions[b]] for b in range(2)}
    cell, bin_of = grid.cell_of(pts), _bins_of(pts, bins)
    for threads in (1, 3):
        _, order, cuts = grid.split(pts, boxes, threads=threads, frontiers=f)
        for b in range(2):
            keep = (cell == b) | np.all((pts >= regions[b][0]) & (pts <= regions[b][1]), axis=1)
            keep |= np.isin(bin_of, f["bins"][f["offsets"][b]:f["offsets"][b + 1]])
            np.testing.assert_array_equal(order[cuts[b]:cuts[b + 1]], np.nonzero(keep)[0])
    bad = dict(f, bins=np.array([10**6], np.int64), offsets=np.array([0, 1, 1], np.int64))
    with pytest.raises(ValueError):
        grid.split(pts, boxes, frontiers=bad)


def test_clusters_done_in_one_round(monkeypatch):
    """Clusters apart in 2D: the bins beside the empty space between them give every block the
    points across it, so the first round is enough (without them every block takes two), and
    the result is the single run's."""
    from gpugeom.dask import _delaunay
    rng = np.random.default_rng(71)
    centres = rng.random((16, 2))
    pts = centres[rng.integers(0, 16, 100000)] + 0.01 * rng.normal(size=(100000, 2))
    with dask.config.set(scheduler="threads"):
        dt = gd.delaunay(pts, blocks=4, backend="cpu")
        _same_as_single(pts, dt)
        assert [s["rounds"] for s in dt.block_stats] == [1] * 4
        assert all(0 < s["frontier"] < 0.1 * len(pts) for s in dt.block_stats)
        monkeypatch.setattr(_delaunay, "_frontiers", lambda *a, **k: None)
        without = gd.delaunay(pts, blocks=4, backend="cpu")
        assert max(s["rounds"] for s in without.block_stats) == 2
        assert all(s["frontier"] == 0 for s in without.block_stats)


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
                                counts.tolist(), marked, margin, threads=threads)
        np.testing.assert_array_equal(r.view(bool), want.any(axis=1))


def test_clustered_blocks_take_borders(monkeypatch):
    """Clusters apart: a block whose first round fails is sent the others' borders and is done
    in the second, holding few points beyond its own (asking for the bins its balls met took
    whole clusters: 2.5 local points a point here, 4.5 on 10^6 3D points); points on a sphere
    in 3D, where every ball is the sphere's (the caps along the hull cost simplices times hull
    planes: 8 s a block at 2·10^4 points). Without the bins beside empty space, which would
    make the first round enough."""
    from gpugeom.dask import _delaunay
    monkeypatch.setattr(_delaunay, "_frontiers", lambda *a, **k: None)
    # (the sphere split, as it would be without the rule that gives it to one block)
    monkeypatch.setattr(_delaunay, "_on_convex_surface", lambda *a, **k: False)
    rng = np.random.default_rng(52)
    sphere = rng.normal(size=(6000, 3))
    sphere /= np.linalg.norm(sphere, axis=1)[:, None]
    with dask.config.set(scheduler="threads"):
        for d, n in ((2, 40000), (3, 20000)):
            centres = rng.random((24, d))
            pts = centres[rng.integers(0, 24, n)] + 0.01 * rng.normal(size=(n, d))
            dt = gd.delaunay(pts, blocks=6, backend="cpu")
            _same_as_single(pts, dt)
            assert sum(s["nlocal"] for s in dt.block_stats) < 1.5 * len(pts)
            assert max(s["rounds"] for s in dt.block_stats) == 2  # the borders were sent
        _same_as_single(sphere, gd.delaunay(sphere, blocks=4, backend="cpu"))


def test_convex_surface_in_one_block():
    """Points on a circle or a sphere, or on a shell thinner than the sample's spacing, go to one
    block that owns them all (split, every block would hold most of them); a thicker shell and
    a ball are split. Each is the single run's triangulation."""
    rng = np.random.default_rng(63)
    cases = []
    for d, n in ((2, 20000), (3, 8000)):
        surface = rng.normal(size=(n, d))
        surface /= np.linalg.norm(surface, axis=1)[:, None]
        thin = surface * (1 + 1e-6 * rng.random((n, 1)))
        thick = surface * (0.6 + 0.4 * rng.random((n, 1)))
        cases += [(surface, True), (thin, True), (thick, False), (rng.random((n, d)), False)]
    with dask.config.set(scheduler="threads"):
        for pts, one in cases:
            dt = gd.delaunay(pts, blocks=4, backend="cpu")
            _same_as_single(pts, dt)
            if one:
                assert [(s["block"], s["nlocal"]) for s in dt.block_stats] == [(0, len(pts))]
            else:
                assert len(dt.block_stats) == 4
    # a sample that is flat, too small or in convex position
    from gpugeom.dask import _delaunay
    line = np.stack([np.arange(50.0), np.zeros(50)], axis=1)
    assert not _delaunay._on_convex_surface([line[:20], line[20:]])
    assert not _delaunay._on_convex_surface([line[:3]])
    assert _delaunay._on_convex_surface([cases[0][0][:100], cases[0][0][100:300]])
    assert _delaunay._sample_stride(4096) == 1 and _delaunay._sample_stride(4097) == 2


@pytest.mark.parametrize("d", [2, 3])
def test_second_round_is_exact_everywhere(d, monkeypatch):
    """Every block's first round failed on purpose: the second, from the borders alone, gives
    the single run's triangulation on every family (degenerate ones included: a grid turned off
    the axes has its hull's sides full of collinear or coplanar points), across 2, 3 and 8
    blocks."""
    from gpugeom.dask import _delaunay, _ghost
    # (the sphere split too, as it would be without the rule that gives it to one block)
    monkeypatch.setattr(_delaunay, "_on_convex_surface", lambda *a, **k: False)
    rng = np.random.default_rng(60 + d)
    fam = _families(d, rng)
    turn = np.eye(d) * 5
    turn[:2, :2] = [[4, -3], [3, 4]]  # (exact in doubles: the grid stays a lattice)
    fam["turned grid"] = fam["grid"] @ turn.T
    monkeypatch.setattr(_ghost, "_judge", lambda *a, **k: False)
    second = 0
    with dask.config.set(scheduler="threads"):
        for name, pts in fam.items():
            ext = np.ptp(pts, axis=0)
            spacing = float(np.prod(ext) / len(pts)) ** (1 / d)
            for blocks in (2, 3, 8):
                # a thin ghost layer, so that no block holds every point (one that does is
                # done without a test)
                dt = gd.delaunay(pts, blocks=blocks, backend="cpu", ghost=0.5 * spacing)
                _same_as_single(pts, dt)
                rounds = {s["rounds"] for s in dt.block_stats}
                # (a block that holds every point, as on a sphere, is done untested)
                assert rounds <= {1, 2}, name
                second += 2 in rounds
    assert second >= 15


def test_first_round_without_a_triangulation(monkeypatch):
    """A block whose first round cannot triangulate (degenerate local points, which the hull's
    points rule out in practice) sends all its own points to every block; the others' second
    rounds and its own are still exact."""
    from gpugeom.dask import _delaunay, _ghost
    pts = np.random.default_rng(62).random((4000, 2))
    real_block, real_tri = _delaunay.triangulate_block, _ghost._triangulated
    failing = []

    def tri(*args, **kwargs):
        if failing:
            raise _core.DegenerateInputError("forced")
        return real_tri(*args, **kwargs)

    def block(b, *args, **kwargs):
        failing[:] = [True] if b == 1 and len(args) < 9 else []  # block 1's first round
        try:
            return real_block(b, *args, **kwargs)
        finally:
            failing.clear()

    monkeypatch.setattr(_ghost, "_triangulated", tri)
    monkeypatch.setattr(_delaunay, "triangulate_block", block)
    with dask.config.set(scheduler="synchronous"):
        dt = gd.delaunay(pts, blocks=4, backend="cpu", ghost=0.01)
    _same_as_single(pts, dt)
    assert [s["rounds"] for s in dt.block_stats][1] == 2


def test_coarse_paths_are_exact(monkeypatch):
    """The path that trades work for a coarser test: no caps along the hull (past
    ``_CAP_WORK``). Forced everywhere, it gives the same triangulation, in no fewer rounds
    (without the bins beside empty space, so that the clusters take a second round)."""
    from gpugeom.dask import _delaunay, _ghost
    monkeypatch.setattr(_delaunay, "_frontiers", lambda *a, **k: None)
    rng = np.random.default_rng(53)
    centres = rng.random((10, 2))
    flat = centres[rng.integers(0, 10, 8000)] + 0.01 * rng.normal(size=(8000, 2))
    cube = rng.random((4000, 3))
    with dask.config.set(scheduler="threads"):
        fine = [gd.delaunay(p, blocks=4, backend="cpu") for p in (flat, cube)]
        monkeypatch.setattr(_ghost, "_CAP_WORK", 0)
        for p, f in zip((flat, cube), fine):
            dt = gd.delaunay(p, blocks=4, backend="cpu")
            _same_as_single(p, dt)
            assert sum(s["rounds"] for s in dt.block_stats) >= \
                sum(s["rounds"] for s in f.block_stats)
        assert max(s["rounds"] for s in fine[0].block_stats) == 2
        # a block's second round keeps its first round's count of tested simplices
        assert all(s["tested"] > 0 for s in fine[0].block_stats if s["rounds"] == 2)
        # and says why its test failed; a block done in its first round says nothing
        for st in fine[0].block_stats:
            if st["rounds"] == 2:
                assert "tested balls in a piece not final; the first: radius" in st["why"]
            else:
                assert st["why"] == ""


def test_clip_to_slab_holds_every_point():
    """The box round a box's part in a slab (``_clip_to_slab``) holds every point of that part
    (sampled), is inside the box, and is tight where the slab is thin: a slab across a box
    leaves at most its width plus the tilt times the box."""
    from gpugeom.dask import _ghost
    rng = np.random.default_rng(61)
    for d in (2, 3):
        m = 400
        lo = rng.normal(size=(m, d))
        hi = lo + rng.random((m, d)) * 3
        n = rng.normal(size=(m, d))
        n[:20, 0] = 0.0  # no part along an axis
        n[20:40] *= 1e-12  # nearly no normal: nothing to cut
        mid = rng.random((m, d)) * (hi - lo) + lo
        a = np.einsum("mi,mi->m", n, mid) - rng.random(m) * 0.1
        b = a + rng.random(m) * 0.2
        clo, chi = _ghost._clip_to_slab(lo, hi, n, a, b)
        assert np.all(clo >= lo) and np.all(chi <= hi)
        x = lo[:, None, :] + rng.random((m, 4000, d)) * (hi - lo)[:, None, :]
        nx = np.einsum("mi,mki->mk", n, x)
        inside = (nx >= a[:, None]) & (nx <= b[:, None])
        assert inside.any(axis=1).mean() > 0.9  # (the check below is not empty)
        for i in range(m):
            xi = x[i][inside[i]]
            assert np.all(xi >= clo[i]) and np.all(xi <= chi[i]), i
        # a thin slab across the middle of a wide box, tilted by 1e-3: a band round it
        box_lo, box_hi = np.zeros((1, 3)), np.array([[1.0, 1.0, 50.0]])
        tilt = np.array([[0.0, 1.0, 1e-3]]) / np.hypot(1.0, 1e-3)
        clo, chi = _ghost._clip_to_slab(box_lo, box_hi, tilt, np.array([0.5]),
                                        np.array([0.501]))
        assert chi[0, 1] - clo[0, 1] < 0.001 + 0.05 + 1e-9
        # empty and unbounded boxes are left as they are
        e_lo, e_hi = np.array([[1.0, 0.0, 0.0]]), np.array([[0.0, 1.0, 1.0]])
        for blo, bhi in ((e_lo, e_hi), (np.full((1, 3), -np.inf), np.full((1, 3), np.inf))):
            got = _ghost._clip_to_slab(blo, bhi, tilt, np.array([0.5]), np.array([0.501]))
            np.testing.assert_array_equal(got[0], blo)
            np.testing.assert_array_equal(got[1], bhi)


def test_flat_simplex_on_the_hull_is_final():
    """A flat tetrahedron on the hull's side y = 1, its vertices nearly on one line (from 2·10^6
    uniform points in 4 blocks): its circumball is 7·10^4 wide, tilted by 4·10^-3 against the
    side. The box round its cap spans 0.12 across the side, far past the strip along it (0.016);
    the cap's slab keeps it within 2·10^-3, so the simplex is final where it was not (its block
    took a second round for it). A ball that reaches across the region's side stays not final."""
    from gpugeom.dask import _ghost
    verts = np.array([[0.006196691991378622, 0.9999943487233235, 0.9288728859114753],
                      [0.012402157640862166, 0.9999989638929876, 0.8219888570473232],
                      [0.022246983395277642, 0.9999931208083044, 0.5795842167141266],
                      [0.03596863124237437, 0.9999651081762093, 0.12310216675855123]])
    box_lo = np.array([1.1209902754938383e-06, 3.572479676527962e-07, 6.092990755268701e-07])
    box_hi = np.array([0.9999994684391201, 0.9999998646762783, 0.9999997582373656])
    region_lo = np.array([-0.03174686834144134, 0.4682521216304062, -0.03174738003264131])
    region_hi = np.array([1.031747457770837, 1.0317478540079952, 0.5317481730999375])
    strip = 0.0158746
    extras = []
    for k in (0, 2):
        hi = box_hi.copy()
        hi[k] = box_lo[k] + strip
        extras.append((box_lo.copy(), hi))
        lo = box_lo.copy()
        lo[k] = box_hi[k] - strip
        extras.append((lo, box_hi.copy()))
    lo = box_lo.copy()
    lo[1] = box_hi[1] - strip
    extras.append((lo, box_hi.copy()))
    # the hull's planes beside the simplex (outward unit normals, n.x + t <= 0 inside), pushed
    # out as the hull's are, and the box's other sides
    planes = [[-0.0037645354884382155, 0.9999928987316017, -0.00017538222471990823,
               -0.9998010130349306],
              [-0.0035306732050515532, 0.9999937531263215, -0.00016749642509279237,
               -0.9998112498650924],
              [-0.004688895147044331, 0.9999889851178827, -0.00020953569358114546,
               -0.9997596472400498]]
    for k in range(3):
        n = np.zeros(3)
        n[k] = -1.0
        planes.append(list(n) + [box_lo[k] - 1e-9])
        if k != 1:
            n = np.zeros(3)
            n[k] = 1.0
            planes.append(list(n) + [-box_hi[k] - 1e-9])
    planes = np.array(planes)
    assert np.all(verts @ planes[:, :3].T + planes[:, 3] <= 0)
    # a small ball across the region's side z = 0.53, inside the box away from every strip
    ball = np.array([[0.5, 0.7, 0.52], [0.53, 0.7, 0.52], [0.5, 0.73, 0.52], [0.5, 0.7, 0.55]])
    pts = np.concatenate([verts, ball])
    s = np.array([[0, 1, 2, 3], [4, 5, 6, 7]])
    nbs = np.array([[-1, 7, -1, 7], [9, 9, 9, 9]])
    ok = _ghost.final_simplices(pts, s, region_lo, region_hi, box_lo, box_hi, planes, extras,
                                nbs)
    assert ok.tolist() == [True, False]
    # without its hull faces and planes it is not (nothing tells the cap from the ball)
    ok = _ghost.final_simplices(pts, s, region_lo, region_hi, box_lo, box_hi, planes[:0],
                                extras, np.full((2, 4), 9))
    assert ok.tolist() == [False, False]


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


def test_faces_matched_and_neighbors():
    """The neighbours across blocks: the face requests that come to a block paired by their keys
    (``_core.match_faces``), whatever their order, an open one alone answered -1 (a face on
    the hull); a block's neighbours (``_core.block_neighbors``) its own rows shifted by its
    offset, -1 kept, each -2 answered; keys of either width (a block's are int32), neighbours
    int32 or, asked for, int64 (past 2^31 simplices in all). A key that comes once (not open) or
    three times, a face without an answer, an answer for another face, or a global index past
    the output's width is a bug or a misuse, reported as one."""
    keys = np.array([[1, 5], [2, 3], [1, 5], [0, 9], [2, 3]], np.int64)
    pos = np.array([40, 11, 7, 3, 62], np.int64)
    open_ = np.array([False, False, False, True, False])
    for order in ([0, 1, 2, 3, 4], [4, 3, 2, 1, 0], [2, 0, 4, 3, 1]):
        for k in (keys, keys.astype(np.int32)):
            got = _core.match_faces(k[order], pos[order], open_[order], 2)
            np.testing.assert_array_equal(got, np.array([7, 62, 40, -1, 11])[order])
    with pytest.raises(RuntimeError, match="comes 1 times"):
        _core.match_faces(keys, pos, np.zeros(5, bool))
    with pytest.raises(RuntimeError, match="comes 3 times"):
        _core.match_faces(np.concatenate([keys, keys[:1]]), np.append(pos, 99),
                          np.append(open_, False))
    nb_local = np.array([[1, -1, -2], [0, -2, -1], [-2, 0, -2]], np.int32)
    got = _core.block_neighbors(nb_local, 20, np.array([2, 4, 6, 8]),
                                np.array([108, 502, 103, -1]), False, 2)
    assert got.dtype == np.int32
    np.testing.assert_array_equal(got, [[21, -1, 108], [20, 502, -1], [103, 20, -1]])
    big = 2**31 + 5  # (a block past 2^31 simplices: int64 names it, int32 refuses)
    got = _core.block_neighbors(nb_local, big, np.array([2, 4, 6, 8]),
                                np.array([108, 502, big + 2**31, -1]), True)
    assert got.dtype == np.int64
    np.testing.assert_array_equal(
        got, [[big + 1, -1, 108], [big, 502, -1], [big + 2**31, big, -1]])
    with pytest.raises(ValueError, match="32-bit"):
        _core.block_neighbors(nb_local, big, np.array([2, 4, 6, 8]),
                              np.array([108, 502, 103, -1]))
    with pytest.raises(ValueError, match="32-bit"):
        _core.block_neighbors(nb_local, 20, np.array([2, 4, 6, 8]),
                              np.array([108, 502, 2**31, -1]))
    with pytest.raises(ValueError, match="nb_local"):
        _core.block_neighbors(nb_local.astype(np.int64), 20, np.array([2, 4, 6, 8]),
                              np.array([108, 502, 103, -1]))
    with pytest.raises(RuntimeError, match="no answer"):
        _core.block_neighbors(nb_local, 20, np.array([2, 4, 6]), np.array([108, 502, 103]))
    with pytest.raises(ValueError, match="not a face"):
        _core.block_neighbors(nb_local, 20, np.array([0]), np.array([5]))


@pytest.mark.parametrize("d", [2, 3])
def test_block_borders(d):
    """What a block sends the others (``_core.block_borders``) against NumPy: per other block,
    the own vertices of the simplices whose circumball meets its cell, and of the hull faces
    whose plane meets it; a ball within a hair of a cell may go either way (the pass grows
    balls and cells by rounding bounds and a margin), so the reference is taken with radii a
    hair smaller and larger. On 1 and 3 threads, from int32 and int64 indices."""
    rng = np.random.default_rng(61 + d)
    pts = rng.random((1500, d))
    tri = gpugeom.Delaunay(pts, backend="cpu")
    s = np.asarray(tri.simplices, dtype=np.int64)
    nb = np.asarray(tri.neighbors, dtype=np.int64)
    g = Grid(np.zeros(d), np.ones(d), (3, 2, 2)[:d])
    cell = g.cell_of(pts)
    block = 1
    own = cell == block
    a = pts[s[:, 1:]] - pts[s[:, :1]]
    centre = pts[s[:, 0]] + np.linalg.solve(a, 0.5 * np.einsum("mij,mij->mi", a, a)[..., None])[
        ..., 0]
    radius = np.linalg.norm(centre - pts[s[:, 0]], axis=1)
    for threads, s_, nb_ in ((1, s, nb), (3, s.astype(np.int32), nb.astype(np.int32))):
        got = _core.block_borders(pts, s_, nb_, own, block, [0.0] * d, g.width.tolist(),
                                  g.counts.tolist(), 1e-9, 1.0, threads=threads)
        assert block not in got["targets"].tolist()
        sent = {int(t): got["vertices"][got["offsets"][k]:got["offsets"][k + 1]]
                for k, t in enumerate(got["targets"])}
        for t in range(g.nblocks):
            if t == block:
                continue
            lo, hi = g.cell_box(t)
            gap = np.linalg.norm(np.maximum(np.maximum(lo - centre, centre - hi), 0), axis=1)
            want = []
            for grow in (-1e-7, 1e-7):
                hit = own[s] & ((gap <= radius + grow) & own[s].any(axis=1))[:, None]
                for j in range(d + 1):  # hull faces whose plane meets the cell
                    on = nb[:, j] < 0
                    f = s[on][:, [k for k in range(d + 1) if k != j]]
                    e = pts[f[:, 1:]] - pts[f[:, :1]]
                    n_ = (np.stack([-e[:, 0, 1], e[:, 0, 0]], 1) if d == 2
                          else np.cross(e[:, 0], e[:, 1]))
                    n_ /= np.linalg.norm(n_, axis=1)[:, None]
                    corners = np.stack(np.meshgrid(*zip(lo, hi), indexing="ij"), -1).reshape(-1, d)
                    h = (np.einsum("cd,md->mc", corners, n_)
                         - np.einsum("md,md->m", pts[f[:, 0]], n_)[:, None])
                    meets = (h.min(axis=1) <= -grow) & (h.max(axis=1) >= grow)
                    face = np.ones((on.sum(), d + 1), bool)
                    face[:, j] = False
                    hit[np.nonzero(on)[0]] |= own[s[on]] & face & meets[:, None]
                want.append(np.unique(s[hit]))
            v = sent.get(t, np.zeros(0, np.int64))
            assert np.all(np.diff(v) > 0)
            assert set(want[0].tolist()) <= set(v.tolist()) <= set(want[1].tolist()), t
        assert len(got["vertices"]) > 0
        # with a region, the first finality test of the stars on the same balls: as the bulk
        # test gives it (0 off the stars)
        rlo, rhi = g.cell_box(block)
        rlo, rhi = rlo - 0.05, rhi + 0.05
        both = _core.block_borders(pts, s_, nb_, own, block, [0.0] * d, g.width.tolist(),
                                   g.counts.tolist(), 1e-9, 1.0, rlo.tolist(), rhi.tolist(),
                                   [0.0] * d, [1.0] * d, threads=threads)
        np.testing.assert_array_equal(both["vertices"], got["vertices"])
        star = np.nonzero(own[s].any(axis=1))[0]
        want = np.zeros(len(s), np.uint8)
        want[star] = _core.circumballs_inside_region(pts, s_, star, rlo.tolist(), rhi.tolist(),
                                                     [0.0] * d, [1.0] * d, 1.0, threads)
        np.testing.assert_array_equal(both["inside"], want)
        assert 0 < want.sum() < len(star)
    with pytest.raises(ValueError, match="outside"):
        _core.block_borders(pts, s, nb, own, g.nblocks, [0.0] * d, g.width.tolist(),
                            g.counts.tolist(), 1e-9, 1.0)


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
        blk = rng.integers(0, 3, len(pts)).astype(np.int32)
        blk[pts[:, 0] < 0.4] = 1  # a region of one block, and mixed ones elsewhere
        ids = np.sort(rng.choice(10**6, len(pts), replace=False)).astype(np.int32)
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
            assert got[k].dtype != np.int64, k  # (32-bit indices, as a single call's)
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
        with pytest.raises(ValueError, match="ids"):  # (64-bit ids: the output is 32-bit)
            _core.block_output(s, nb, mine, ids.astype(np.int64), blk)


def _required_reference(s, nb, owned):
    """What a block requires, in NumPy: the owned simplices (lowest vertex owned) and the mask
    of the stars of the owned points."""
    low = s.min(axis=1)
    return np.nonzero(owned[low])[0], owned[s].any(axis=1)


def _emit_reference(ids, pts, blk, s, nb, rows, d, xp=np):
    """The owned simplices' output in array code (NumPy here), as the C++ pass must give it."""
    d1 = d + 1
    pos = xp.full(len(s), -1, dtype=xp.int64)
    pos[rows] = xp.arange(len(rows))
    nbr = nb[rows]
    sr = s[rows]
    # the rows are all the simplices whose lowest vertex is owned: a neighbour is a row here
    # exactly where it is owned here; a face on the local hull without an own vertex is asked
    # for too (open)
    block = blk[sr.min(axis=1)]
    own = blk[sr] == block[:, None]
    own_face = (own.sum(axis=1)[:, None] - own) > 0
    nb_local = xp.where(nbr >= 0, pos[xp.maximum(nbr, 0)], -1)
    ask = (nbr >= 0) & (nb_local < 0)
    open_ = (nbr < 0) & ~own_face
    fi, fj = xp.nonzero(ask | open_)
    nb_local[fi, fj] = -2
    faces = np.array([[k for k in range(d1) if k != j] for j in range(d1)])
    fv = sr[fi[:, None], faces[fj]]  # the faces' local vertices
    mark = xp.zeros(len(ids), dtype=bool)
    mark[sr.ravel()] = True
    used = np.asarray(xp.nonzero(mark)[0])
    return dict(simplices=ids[np.asarray(sr)], nb_local=np.asarray(nb_local),
                req_owner=blk[fv.min(axis=1)] if len(fv) else np.zeros(0, np.int64),
                req_key=np.sort(ids[fv], axis=1), req_pos=np.asarray(fi * d1 + fj),
                req_open=open_[fi, fj].astype(np.uint8), vertices=ids[used],
                vertex_points=pts[used])


def test_curve_order_over_the_global_box():
    """A block's local points go along the Hilbert curve of their bounding box, and the passes
    take the vertex first on it as a simplex's owner: every block must lay the curve over the
    same box (each holds the global hull's extreme points, which span it). Two blocks then
    order their shared points alike; a block whose points did not span the box is refused as
    the bug it would be."""
    from gpugeom.dask import _ghost
    rng = np.random.default_rng(71)
    pts = rng.random((4000, 3))
    grid = Grid(pts.min(axis=0), pts.max(axis=0), (2, 1, 1))
    ext = np.unique(np.concatenate([pts.argmin(axis=0), pts.argmax(axis=0)]))
    ids = np.arange(len(pts), dtype=np.int32)
    blk = grid.cell_of(pts).astype(np.int32)
    orders = []
    for b in (0, 1):  # each block's points: its cell's, a band of the other's, the extremes
        near = np.abs(pts[:, 0] - 0.5) < 0.1
        keep = np.union1d(np.nonzero((blk == b) | near)[0], ext)
        got = _ghost._curve_order(ids[keep], pts[keep], blk[keep], grid)[0]
        orders.append(got[np.isin(got, np.nonzero(near)[0])])
    np.testing.assert_array_equal(orders[0], orders[1])  # the shared band in one order
    inner = np.setdiff1d(np.arange(len(pts)), ext)
    with pytest.raises(RuntimeError, match="bounding box"):
        _ghost._curve_order(ids[inner], pts[inner], blk[inner], grid)
