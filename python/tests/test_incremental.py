"""SciPy's incremental mode (issue 47): Delaunay, ConvexHull and Voronoi built with
``incremental=True`` and fed ``add_points`` equal the same structure built on all points at once;
errors as SciPy's; a refused call leaves the object as it was."""
import numpy as np
import pytest

import gpugeom


def simplex_set(s):
    return {tuple(sorted(t)) for t in np.asarray(s).tolist()}


def chunks(p, rng, first):
    out, k = [p[:first]], first
    while k < len(p):
        step = int(rng.integers(1, max(2, (len(p) - k) // 2 + 1)))
        out.append(p[k:k + step])
        k += step
    return out


@pytest.mark.parametrize("dist", ["uniform", "grid", "circle", "duplicates"])
def test_delaunay2d_add_points_equals_fresh(backend, rng, dist):
    n = 3000
    if dist == "uniform":
        p = rng.random((n, 2))
    elif dist == "grid":
        g = np.arange(55.0)
        p = np.stack(np.meshgrid(g, g), axis=-1).reshape(-1, 2)
    elif dist == "circle":
        a = rng.random(n) * 2 * np.pi
        p = np.stack([np.cos(a), np.sin(a)], axis=1)
    else:
        p = np.round(rng.random((n, 2)) * 8) / 8
    p = p[rng.permutation(len(p))]
    d = gpugeom.Delaunay(p[:50], incremental=True, backend=backend)
    for c in chunks(p, rng, 50)[1:]:
        d.add_points(c)
        f = gpugeom.Delaunay(np.asarray(d.points), backend=backend)
        assert simplex_set(d.simplices) == simplex_set(f.simplices)
        np.testing.assert_array_equal(d.duplicate_of, f.duplicate_of)
        assert gpugeom.verify.check_delaunay(d.points, d.simplices, d.duplicate_of)[0]
    assert d.npoints == len(p) and d.points.shape == p.shape
    # the derived properties follow the new points
    assert len(d.vertex_to_simplex) == len(p)
    assert d.convex_hull.shape[1] == 2
    r = gpugeom.Delaunay(p[:50], incremental=True, backend=backend)
    r.add_points(p[50:], restart=True)
    assert simplex_set(r.simplices) == simplex_set(d.simplices)


def test_delaunay3d_hull_voronoi_add_points(backend, rng):
    p = rng.random((2000, 3))
    d = gpugeom.Delaunay(p[:30], incremental=True, backend=backend)
    h = gpugeom.ConvexHull(p[:30], incremental=True, backend=backend)
    h2 = gpugeom.ConvexHull(p[:30, :2], incremental=True, backend=backend)
    v = gpugeom.Voronoi(p[:30, :2], incremental=True, backend=backend)
    vol = h.volume  # a cached property: recomputed after add_points
    for c in chunks(p, rng, 30)[1:]:
        d.add_points(c)
        h.add_points(c)
        h2.add_points(c[:, :2])
        v.add_points(c[:, :2])
    assert simplex_set(d.simplices) == simplex_set(gpugeom.Delaunay(p, backend=backend).simplices)
    fh = gpugeom.ConvexHull(p, backend=backend)
    np.testing.assert_array_equal(np.sort(h.vertices), np.sort(fh.vertices))
    assert h.volume == pytest.approx(fh.volume, rel=1e-12) and h.volume > vol
    np.testing.assert_array_equal(h2.vertices, gpugeom.ConvexHull(p[:, :2], backend=backend).vertices)
    fv = gpugeom.Voronoi(p[:, :2], backend=backend)
    assert len(v.regions) == len(p) + 1 and len(v.vertices) == len(fv.vertices)  # (SciPy's Qz)
    assert simplex_set(v.delaunay_simplices) == simplex_set(fv.delaunay_simplices)


def test_errors_as_scipy(rng):
    p = rng.random((100, 2))
    for make in (gpugeom.Delaunay, gpugeom.ConvexHull, gpugeom.Voronoi):
        plain = make(p)
        with pytest.raises(RuntimeError, match="incremental mode not enabled or already closed"):
            plain.add_points(p[:3])
        obj = make(p, incremental=True)
        with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
            obj.add_points(rng.random((4, 3)))
        with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
            obj.add_points(rng.random(4))
        obj.close()
        with pytest.raises(RuntimeError, match="already closed"):
            obj.add_points(p[:3])
        assert obj.npoints == 100  # the results stay readable


def test_a_refused_call_leaves_the_object_as_it_was(rng):
    p = rng.random((500, 2))
    for make in (gpugeom.Delaunay, gpugeom.ConvexHull, gpugeom.Voronoi):
        obj = make(p[:300], incremental=True)
        before = {k: (np.array(v, copy=True) if isinstance(v, np.ndarray) else v)
                  for k, v in vars(obj).items() if k not in ("_dyn", "_run", "_kind")}
        bad = p[300:].copy()
        bad[17, 1] = np.inf
        with pytest.raises(ValueError, match="NaN, infinite"):
            obj.add_points(bad)
        for k, v in before.items():
            now = vars(obj)[k]
            if isinstance(v, np.ndarray):
                np.testing.assert_array_equal(now, v, err_msg=k)
            else:
                assert now == v or k == "stats", k
        obj.add_points(p[300:])  # and it goes on working
        assert obj.npoints == 500


def test_move_gives_the_fresh_result(backend, rng):
    p = rng.random((4000, 2))
    d = gpugeom.Delaunay(p, incremental=True, backend=backend)
    q3 = rng.random((500, 3))
    d3 = gpugeom.Delaunay(q3, incremental=True, backend=backend)
    spacing = 1 / np.sqrt(len(p))
    for scale in (1e-4, 0.3, 5.0):
        q = p + rng.normal(0, scale * spacing, p.shape)
        d.move(q)
        f = gpugeom.Delaunay(q, backend=backend)
        assert simplex_set(d.simplices) == simplex_set(f.simplices)
        np.testing.assert_array_equal(d.points, q)
        assert d.convex_hull.shape == f.convex_hull.shape
        d3.move(q3 + rng.normal(0, scale * 0.1, q3.shape))
        assert simplex_set(d3.simplices) == simplex_set(gpugeom.Delaunay(np.asarray(d3.points), backend=backend).simplices)
    with pytest.raises(ValueError, match=r"shape \(4000, 2\)"):
        d.move(p[:10])
    bad = p.copy()
    bad[3] = np.nan
    before = d.simplices.copy()
    with pytest.raises(ValueError):
        d.move(bad)
    np.testing.assert_array_equal(d.simplices, before)
    with pytest.raises(RuntimeError):
        gpugeom.Delaunay(p).move(p)


@pytest.mark.parametrize("ndim", [2, 3])
def test_remove_gives_the_fresh_result(backend, rng, ndim):
    # issue 47: removed points keep their rows and indices but are no vertices (duplicate_of -2)
    p = np.round(rng.random((3000, ndim)) * 12) / 12  # a grid with copies
    d = gpugeom.Delaunay(p, incremental=True, backend=backend)
    gone = np.zeros(len(p), bool)
    for k in range(3):
        live = np.nonzero(~gone)[0]
        r = rng.choice(live, size=len(live) // 5, replace=False)
        d.remove(r if k else r.tolist())  # arrays and lists
        gone[r] = True
        live = np.nonzero(~gone)[0]
        f = gpugeom.Delaunay(p[live], backend=backend)
        assert d.npoints == len(p) and d.points.shape == p.shape
        assert simplex_set(d.simplices) == simplex_set(live[f.simplices])
        want = np.full(len(p), -2, np.int32)
        want[live] = np.where(f.duplicate_of >= 0, live[np.maximum(f.duplicate_of, 0)], -1)
        assert (np.asarray(d.duplicate_of) == want).all()
        assert (np.asarray(d.vertex_to_simplex)[gone] == -1).all()
        assert not np.isin(np.asarray(d.coplanar)[:, 0], np.nonzero(gone)[0]).any()
    d.add_points(p[:10])  # equal to removed and to kept points
    live = np.nonzero(np.concatenate([~gone, np.ones(10, bool)]))[0]
    allp = np.concatenate([p, p[:10]])
    f = gpugeom.Delaunay(allp[live], backend=backend)
    assert simplex_set(d.simplices) == simplex_set(live[f.simplices])


def test_remove_errors_leave_the_object_as_it_was(rng):
    p = rng.random((500, 2))
    d = gpugeom.Delaunay(p, incremental=True)
    d.remove([3, 4])
    before = np.array(d.simplices)
    for bad, err in (([500], ValueError), ([-1], ValueError), ([5, 5], ValueError),
                     ([3], ValueError), ([0.5], TypeError), (np.ones((2, 2), int), ValueError),
                     (np.ones(3, bool), TypeError),
                     (np.setdiff1d(np.arange(500), [0, 1, 3, 4]), ValueError)):
        with pytest.raises(err):
            d.remove(bad)
        assert (np.array(d.simplices) == before).all()
    assert (np.asarray(d.duplicate_of)[[3, 4]] == -2).all()
    d.remove(np.array([], np.int64))  # nothing to remove
    d.remove([])
    assert (np.array(d.simplices) == before).all()
    d.close()
    with pytest.raises(RuntimeError):
        d.remove([7])
    with pytest.raises(RuntimeError):
        gpugeom.Delaunay(p).remove([7])


@pytest.mark.parametrize("ndim", [2, 3])
def test_changes_say_which_simplices_changed(backend, rng, ndim):
    # issue 47: after each update, previous_index maps every simplex that stayed onto its old row
    # (the same vertices), -1 marks the new ones, and removed lists the old rows that went
    p = rng.random((4000, ndim))
    d = gpugeom.Delaunay(p[:3000], incremental=True, backend=backend)
    with pytest.raises(ValueError):
        d.changes()  # (no update with tracking on yet)
    d.track_changes()
    before = np.array(np.asarray(d.simplices))
    steps = [lambda: d.add_points(p[3000:]), lambda: d.move(p + 1e-4 * rng.standard_normal(p.shape)),
             lambda: d.remove(rng.choice(4000, 300, replace=False))]
    for step in steps:
        step()
        prev, gone = (np.asarray(x) for x in d.changes())
        now = np.asarray(d.simplices)
        assert prev.shape == (len(now),) and prev.dtype == np.int32
        kept = prev >= 0
        assert (np.sort(now[kept], axis=1) == np.sort(before[prev[kept]], axis=1)).all()
        assert not simplex_set(now[~kept]) & simplex_set(before)
        assert (gone == np.setdiff1d(np.arange(len(before)), prev[kept])).all()
        assert 0 < kept.sum() < len(now)
        before = np.array(now)
    d.track_changes(False)
    with pytest.raises(ValueError):
        d.changes()


def facet_set(s):
    return {tuple(sorted(t)) for t in np.asarray(s).tolist()}


@pytest.mark.parametrize("dist", ["ball", "grid"])
def test_hull3d_keeps_its_state(backend, rng, dist):
    # issue 47: ConvexHull(incremental=True) in 3D keeps a DynamicHull3d. add_points makes the hull
    # of the vertices and the new points only; remove keeps it where no vertex goes; every result
    # is a fresh hull's of the points left (a grid with copies: flat faces, first copy a vertex)
    if dist == "ball":
        p = rng.standard_normal((5000, 3))
    else:
        p = np.round(rng.random((5000, 3)) * 6) / 6
    h = gpugeom.ConvexHull(p[:2000], incremental=True, backend=backend)
    h.track_changes()
    gone = np.zeros(len(p), bool)

    def same_as_fresh():
        live = np.nonzero(~gone[:h.npoints])[0]
        f = gpugeom.ConvexHull(np.asarray(h.points)[live], backend=backend)
        assert facet_set(h.simplices) == facet_set(live[np.asarray(f.simplices)])
        np.testing.assert_array_equal(h.vertices, live[np.asarray(f.vertices)])
        assert h.volume == pytest.approx(f.volume, rel=1e-12)
        prev, _ = (np.asarray(x) for x in h.changes())
        assert prev.shape == (h.nsimplex,)

    nv = len(h.vertices)
    h.add_points(p[2000:])
    out = h.stats["counters"]["outside_points"]
    assert 0 < out <= 3000 and h.stats["counters"]["hull_candidates"] == nv + out
    same_as_fresh()
    inside = np.setdiff1d(np.arange(len(p)), np.asarray(h.vertices))[:100]
    simplices = np.array(h.simplices)
    h.remove(inside)
    gone[inside] = True
    assert h.stats["counters"]["removed_vertices"] == 0
    np.testing.assert_array_equal(h.simplices, simplices)
    prev, removed = (np.asarray(x) for x in h.changes())
    assert (prev == np.arange(len(prev))).all() and len(removed) == 0
    vs = np.asarray(h.vertices)[::3]
    h.remove(vs)
    gone[vs] = True
    assert h.stats["counters"]["removed_vertices"] == len(vs)
    same_as_fresh()
    h.move(np.asarray(h.points) * np.array([1.0, 0.5, 2.0]))  # (exact: flat faces stay flat)
    same_as_fresh()


def test_hull3d_kept_refusals(rng):
    p = rng.random((400, 3))
    h = gpugeom.ConvexHull(p, incremental=True)
    before = np.array(h.simplices)
    for bad, err in (([400], ValueError), ([5, 5], ValueError), (np.arange(398), ValueError)):
        with pytest.raises(err):
            h.remove(bad)
        np.testing.assert_array_equal(h.simplices, before)
    flat = p.copy()
    flat[:, 2] = 0.5
    with pytest.raises(ValueError, match="plane"):
        h.move(flat)
    np.testing.assert_array_equal(h.simplices, before)
    np.testing.assert_array_equal(h.points, p)
    with pytest.raises(ValueError, match="keeps no state"):
        gpugeom.ConvexHull(p[:, :2], incremental=True).remove([1])


def test_voronoi_keeps_its_triangulation(backend, rng):
    # issue 47: Voronoi(incremental=True) keeps a DynamicDelaunay2d; after add_points, move and
    # remove the diagram is a fresh one's of the points left (a removed point: empty region), and
    # changes() speaks of its Delaunay triangles (simplex_vertex: their Voronoi vertices)
    p = np.round(rng.random((3000, 2)) * 40) / 40  # cocircular points and copies
    v = gpugeom.Voronoi(p[:2000], incremental=True, backend=backend)
    v.track_changes()
    v.add_points(p[2000:])
    gone = np.zeros(len(p), bool)

    def same_as_fresh():
        live = np.nonzero(~gone)[0]
        f = gpugeom.Voronoi(np.asarray(v.points)[live], backend=backend)
        assert simplex_set(v.delaunay_simplices) == simplex_set(live[np.asarray(f.delaunay_simplices)])
        assert len(v.vertices) == len(f.vertices)
        rp = {tuple(sorted(r)) for r in np.asarray(v.ridge_points).tolist()}
        assert rp == {tuple(sorted(r)) for r in live[np.asarray(f.ridge_points)].tolist()}
        for j, i in enumerate(live[:200]):
            assert len(v.regions[v.point_region[i]]) == len(f.regions[f.point_region[j]])
        assert all(v.regions[v.point_region[i]] == [] for i in np.nonzero(gone)[0])
        prev, _ = (np.asarray(x) for x in v.changes())
        assert prev.shape == (len(v.delaunay_simplices),)

    same_as_fresh()
    r = rng.choice(len(p), 300, replace=False)
    v.remove(r)
    gone[r] = True
    same_as_fresh()
    v.move(np.asarray(v.points) * 2.0)  # (exact: cocircular points stay so)
    same_as_fresh()
    assert v.npoints == len(p)
