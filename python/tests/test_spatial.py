"""Delaunay, Voronoi, ConvexHull against SciPy (general position: the same structures) and the
exact checkers (degenerate input: valid structures)."""
import types

import numpy as np
import pytest
import scipy.spatial as ss

import gpugeom
from gpugeom import verify


def simplex_set(s):
    return {tuple(sorted(t)) for t in np.asarray(s).tolist()}


@pytest.mark.parametrize("n", [3, 10, 1000, 20000])
def test_delaunay2d_equals_scipy(n, backend, rng):
    p = rng.random((n, 2))
    g = gpugeom.Delaunay(p, backend=backend)
    s = ss.Delaunay(p)
    assert g.simplices.dtype == np.int32 and g.simplices.shape == s.simplices.shape
    assert simplex_set(g.simplices) == simplex_set(s.simplices)
    assert g.neighbors.shape == s.neighbors.shape and g.neighbors.dtype == np.int32
    assert g.npoints == n and g.ndim == 2 and g.nsimplex == len(s.simplices)
    np.testing.assert_array_equal(g.points, p)
    # neighbors: the simplex opposite vertex k shares the other two vertices
    for t in range(min(g.nsimplex, 200)):
        for k in range(3):
            o = g.neighbors[t, k]
            if o >= 0:
                shared = set(g.simplices[t]) - {g.simplices[t, k]}
                assert shared <= set(g.simplices[o])
    # convex hull edges and vertex_to_simplex
    assert {tuple(sorted(e)) for e in g.convex_hull.tolist()} == \
        {tuple(sorted(e)) for e in s.convex_hull.tolist()}
    vts = g.vertex_to_simplex
    assert all(i in g.simplices[vts[i]] for i in range(n))
    assert g.coplanar.shape == (0, 3)
    ip, ind = g.vertex_neighbor_vertices
    rip, rind = s.vertex_neighbor_vertices
    np.testing.assert_array_equal(ip, rip)
    for k in range(0, n, max(1, n // 50)):
        assert sorted(ind[ip[k]:ip[k + 1]]) == sorted(rind[rip[k]:rip[k + 1]])


def test_delaunay3d_equals_scipy(backend, rng):
    p = rng.random((3000, 3))
    g = gpugeom.Delaunay(p, backend=backend)
    s = ss.Delaunay(p)
    assert g.simplices.shape == s.simplices.shape
    assert simplex_set(g.simplices) == simplex_set(s.simplices)
    assert {tuple(sorted(f)) for f in g.convex_hull.tolist()} == \
        {tuple(sorted(f)) for f in s.convex_hull.tolist()}
    ok, msg = verify.check_delaunay(p, g.simplices)
    assert ok, msg
    vts = g.vertex_to_simplex
    assert all(i in g.simplices[vts[i]] for i in range(len(p)))


def test_transform_as_scipy(backend, rng):
    for d in (2, 3):
        p = rng.random((300, d))
        g = gpugeom.Delaunay(p, backend=backend)
        s = ss.Delaunay(p)
        # the same simplex (as a vertex set) gets the same barycentric map, up to the order of
        # its vertices: compare the barycentric coordinates of random points per vertex
        order = {tuple(sorted(t)): i for i, t in enumerate(s.simplices.tolist())}
        q = rng.random((50, d))
        for i in range(0, g.nsimplex, 17):
            j = order[tuple(sorted(g.simplices[i].tolist()))]
            def bary(T, x):
                c = T[:d] @ (x - T[d])
                return np.append(c, 1 - c.sum())
            for x in q[:5]:
                a = dict(zip(g.simplices[i].tolist(), bary(g.transform[i], x)))
                b = dict(zip(s.simplices[j].tolist(), bary(s.transform[j], x)))
                for v in a:
                    assert a[v] == pytest.approx(b[v], rel=1e-9, abs=1e-9)


def test_find_simplex_2d_and_3d(backend, rng):
    for d in (2, 3):
        p = rng.random((500, d))
        g = gpugeom.Delaunay(p, backend=backend)
        s = ss.Delaunay(p)
        q = rng.random((2000, d)) * 1.2 - 0.1
        mine = g.find_simplex(q)
        ref = s.find_simplex(q)
        assert mine.shape == (2000,)
        # SciPy may answer near boundaries with a tolerance; the exact answer must contain q
        assert np.array_equal(mine >= 0, ref >= 0)
        for i in np.nonzero(mine >= 0)[0][:300]:
            t = p[g.simplices[mine[i]]]
            bary = np.linalg.solve(np.vstack([t.T, np.ones(d + 1)]), np.append(q[i], 1.0))
            assert bary.min() > -1e-9
        # vertices are located exactly, shape (..., d) kept
        assert np.all(g.find_simplex(p[:10].reshape(2, 5, d)).reshape(-1) >= 0)


def test_degenerate_grid_and_duplicates(backend):
    # An integer grid (every square cocircular) plus duplicates: valid and exact.
    x, y = np.meshgrid(np.arange(40.0), np.arange(30.0))
    p = np.column_stack([x.ravel(), y.ravel()])
    p = np.vstack([p, p[:50]])
    g = gpugeom.Delaunay(p, backend=backend)
    ok, msg = verify.check_delaunay(p, g.simplices, g.duplicate_of)
    assert ok, msg
    assert g.nsimplex == 2 * 39 * 29
    assert g.coplanar.shape == (50, 3)
    np.testing.assert_array_equal(g.coplanar[:, 0], np.arange(1200, 1250))
    np.testing.assert_array_equal(g.coplanar[:, 2], np.arange(50))
    # points on a circle
    t = np.linspace(0, 2 * np.pi, 500, endpoint=False)
    c = np.column_stack([np.cos(t), np.sin(t)])
    ok, msg = verify.check_delaunay(c, gpugeom.Delaunay(c, backend=backend).simplices)
    assert ok, msg


def test_degenerate_3d_grid(backend):
    g3 = np.stack(np.meshgrid(*[np.arange(8.0)] * 3), -1).reshape(-1, 3)
    d = gpugeom.Delaunay(g3, backend=backend)
    ok, msg = verify.check_delaunay(g3, d.simplices)
    assert ok, msg
    assert d.stats["counters"]["distinct_points"] == 512


def _same_voronoi_as_scipy(g, s, every=1):
    """The same vertices (up to Qhull's rounding), ridges and regions as SciPy's diagram. In 3D
    Qhull leaves out the unbounded ridges with one finite vertex (a wedge between two rays, as
    between two points on a hull edge), which gpugeom lists: they are compared apart."""
    assert g.vertices.shape == s.vertices.shape and g.vertices.dtype == np.float64
    if g.ndim == 3:
        wedge = [len(r) == 2 for r in g.ridge_vertices]
        assert all(r[0] == -1 for r, w in zip(g.ridge_vertices, wedge) if w)
        assert not any(len(r) == 2 for r in s.ridge_vertices)
        keep = ~np.asarray(wedge, bool)
        g = types.SimpleNamespace(
            points=g.points, vertices=g.vertices, regions=g.regions, point_region=g.point_region,
            ridge_points=np.asarray(g.ridge_points)[keep],
            ridge_vertices=[r for r, w in zip(g.ridge_vertices, wedge) if not w])
    assert g.ridge_points.shape == s.ridge_points.shape
    # map our vertices to SciPy's by nearest neighbour
    d, m = ss.cKDTree(s.vertices).query(g.vertices)
    assert np.all(d <= 1e-9 * np.maximum(1, np.abs(g.vertices).max(axis=1)))
    assert len(set(m.tolist())) == len(m)

    def ends(rv, mapping):
        return tuple(sorted(mapping(v) if v >= 0 else -1 for v in rv))

    # the same ridges between the same points, with the same ends
    gv = {tuple(sorted(rp)): ends(rv, lambda v: int(m[v]))
          for rp, rv in zip(g.ridge_points.tolist(), g.ridge_vertices)}
    sv = {tuple(sorted(rp)): ends(rv, int)
          for rp, rv in zip(s.ridge_points.tolist(), s.ridge_vertices)}
    assert gv == sv
    # regions: the same vertex sets per point
    for i in range(0, len(g.points), every):
        assert ends(g.regions[g.point_region[i]], lambda v: int(m[v])) == \
            ends(s.regions[s.point_region[i]], int)


def test_voronoi_equals_scipy(backend, rng):
    p = rng.random((2000, 2))
    _same_voronoi_as_scipy(gpugeom.Voronoi(p, backend=backend), ss.Voronoi(p), every=37)


def test_voronoi3d_equals_scipy(backend, rng):
    # issue 49: the 3D diagram, SciPy's layout (ridges as vertex lists, regions as vertex sets)
    p = rng.random((1500, 3))
    g = gpugeom.Voronoi(p, backend=backend)
    _same_voronoi_as_scipy(g, ss.Voronoi(p), every=7)
    off = np.asarray(g.ridge_offsets)
    assert off[0] == 0 and off[-1] == len(g.ridge_vertices_flat) and np.all(np.diff(off) >= 2)


@pytest.mark.parametrize("shape", [(3, 3, 3), (5, 4, 3)])
def test_voronoi3d_grid_is_cubes_as_scipy(shape, backend):
    # the eight corners of each grid cube lie on one sphere: one vertex per cube, as SciPy's, and
    # ridges only between neighbours along an axis
    p = np.array(np.meshgrid(*[np.arange(k, dtype=float) for k in shape], indexing="ij"))
    p = p.reshape(3, -1).T
    g = gpugeom.Voronoi(p, backend=backend)
    _same_voronoi_as_scipy(g, ss.Voronoi(p))
    assert len(g.vertices) == np.prod([k - 1 for k in shape])
    d = np.abs(p[np.asarray(g.ridge_points)[:, 0]] - p[np.asarray(g.ridge_points)[:, 1]]).sum(1)
    assert np.all(d == 1)


GRID = np.array([(i, j) for i in range(3) for j in range(3)], float)
CIRCLE = np.array([(5, 0), (-5, 0), (0, 5), (0, -5), (3, 4), (-3, 4), (3, -4), (-3, -4), (4, 3),
                   (-4, 3), (4, -3), (-4, -3)], float)  # (all on the circle of radius 5, exactly)


@pytest.mark.parametrize("case", ["grid3", "grid", "circle", "circles", "lattice"])
def test_voronoi_merges_cocircular_triangles_as_scipy(case, backend, rng):
    # issue 49: triangles that share a circle exactly give one Voronoi vertex, so no ridge has
    # length zero (a 3x3 grid: 4 vertices, as SciPy's, not 8)
    p = {"grid3": GRID,
         "grid": np.array([(i, j) for i in range(17) for j in range(11)], float),
         "circle": CIRCLE,
         "circles": np.concatenate([CIRCLE, 3 * CIRCLE + [40, 0], CIRCLE / 2 + [0, 30]]),
         "lattice": np.unique(rng.integers(0, 30, (600, 2)), axis=0).astype(float)}[case]
    g = gpugeom.Voronoi(p, backend=backend)
    _same_voronoi_as_scipy(g, ss.Voronoi(p))
    if case == "grid3":
        assert len(g.vertices) == 4 and len(g.ridge_points) == 12
        assert sorted(g.regions[g.point_region[4]]) == [0, 1, 2, 3]
    if case == "circle":
        assert len(g.vertices) == 1 and all(g.regions[g.point_region[i]] == [-1, 0]
                                            for i in range(len(p)))
    rv = np.asarray(g.ridge_vertices_array)
    assert np.all(rv[:, 0] != rv[:, 1])  # no ridge of length zero
    for r in g.regions:
        assert all(a != b for a, b in zip(r, r[1:] + r[:1])) or len(r) < 2
    # each Delaunay triangle's Voronoi vertex is its circumcentre
    t = np.asarray(g.delaunay_simplices)
    centre = np.asarray(g.vertices)[np.asarray(g.simplex_vertex)]
    radius = np.linalg.norm(p[t] - centre[:, None, :], axis=2)
    np.testing.assert_allclose(radius, radius[:, :1].repeat(3, axis=1), rtol=1e-12)


@pytest.mark.parametrize("shape", ["ball", "cube"])
def test_convex_hull_equals_scipy(shape, backend, rng):
    p = rng.normal(size=(20000, 3))
    if shape == "ball":
        p /= np.linalg.norm(p, axis=1)[:, None] ** 0.7
    else:
        p = rng.random((20000, 3))
    g = gpugeom.ConvexHull(p, backend=backend)
    s = ss.ConvexHull(p)
    np.testing.assert_array_equal(g.vertices, np.sort(s.vertices))
    assert simplex_set(g.simplices) == simplex_set(s.simplices)
    assert g.equations.shape == s.equations.shape
    np.testing.assert_allclose(g.area, s.area, rtol=1e-12)
    np.testing.assert_allclose(g.volume, s.volume, rtol=1e-12)
    # equations: unit outward normals, every point inside up to rounding
    np.testing.assert_allclose(np.linalg.norm(g.equations[:, :3], axis=1), 1, rtol=1e-12)
    assert (p @ g.equations[:, :3].T + g.equations[:, 3]).max() < 1e-12
    ok, msg = verify.check_convex_hull(p, g.simplices)
    assert ok, msg


def test_convex_hull_2d_equals_scipy(backend, rng):
    for p in (rng.random((5000, 2)), rng.normal(size=(20000, 2))):
        g = gpugeom.ConvexHull(p, backend=backend)
        s = ss.ConvexHull(p)
        # the same vertices, counter-clockwise, up to where the cycle starts
        v = list(g.vertices)
        k = v.index(s.vertices[0])
        assert v[k:] + v[:k] == list(s.vertices)
        assert {tuple(sorted(e)) for e in g.simplices.tolist()} == \
            {tuple(sorted(e)) for e in s.simplices.tolist()}
        np.testing.assert_allclose(g.area, s.area, rtol=1e-12)
        np.testing.assert_allclose(g.volume, s.volume, rtol=1e-12)
        assert (p @ g.equations[:, :2].T + g.equations[:, 2]).max() < 1e-12
        for i in range(g.nsimplex):  # neighbors: the facet opposite vertex k shares the other
            for k in range(2):
                other = g.simplices[i, 1 - k]
                assert other in g.simplices[g.neighbors[i, k]]
    # collinear points on hull edges are not vertices (exact), a square grid has 4
    x, y = np.meshgrid(np.arange(10.0), np.arange(7.0))
    sq = gpugeom.ConvexHull(np.column_stack([x.ravel(), y.ravel()]), backend=backend)
    assert sorted(sq.vertices.tolist()) == [0, 9, 60, 69]
    assert sq.volume == 54.0 and sq.area == 30.0


def test_convex_hull_degenerate_cube_grid(backend):
    g3 = np.stack(np.meshgrid(*[np.arange(6.0)] * 3), -1).reshape(-1, 3)
    h = gpugeom.ConvexHull(g3, backend=backend)
    # only the 8 corners are extreme; the flat faces are triangulated (12 triangles)
    assert len(h.vertices) == 8 and h.nsimplex == 12
    assert h.volume == pytest.approx(125.0)
    ok, msg = verify.check_convex_hull(g3, h.simplices)
    assert ok, msg


def test_float32_and_lists_are_accepted(backend):
    p = np.random.default_rng(1).random((100, 2)).astype(np.float32)
    g = gpugeom.Delaunay(p, backend=backend)
    assert g.points.dtype == np.float64
    g2 = gpugeom.Delaunay(p.tolist(), backend=backend)
    assert simplex_set(g.simplices) == simplex_set(g2.simplices)


def test_progress_callback_3d(backend, rng):
    seen = []
    gpugeom.Delaunay(rng.random((5000, 3)), backend=backend,
                     progress=lambda phase, inserted, total, batch: seen.append(phase))
    assert "insert_flip" in seen and seen[-1] == "output"

    class Stop(Exception):
        pass

    def stop(*a):
        raise Stop()

    with pytest.raises(Stop):
        gpugeom.Delaunay(rng.random((5000, 3)), backend=backend, progress=stop)


def _star_polygon(rng, m):
    """m points sorted by angle around the centre: a simple polygon (its edges cross nothing)."""
    ang = np.sort(rng.random(m) * 2 * np.pi)
    rad = 0.5 + 0.4 * rng.random(m)
    return np.column_stack([0.5 + rad * np.cos(ang) / 2, 0.5 + rad * np.sin(ang) / 2])


def _area(points, simplices):
    p = points[simplices]
    return float(np.sum(((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                         - (p[:, 1, 1] - p[:, 0, 1]) * (p[:, 2, 0] - p[:, 0, 0])) / 2))


def test_constrained_delaunay(backend, rng):
    m = 60
    poly = _star_polygon(rng, m)
    inner = 0.5 + (rng.random((400, 2)) - 0.5) * 0.9
    pts = np.vstack([poly, inner])
    segs = np.column_stack([np.arange(m), (np.arange(m) + 1) % m])
    c = gpugeom.ConstrainedDelaunay(pts, segs, backend=backend)
    ok, msg = gpugeom.verify.check_constrained_delaunay(pts, c.simplices, segs, c.duplicate_of)
    assert ok, msg
    assert c.stats["counters"]["segments_recovered"] > 0
    assert ((c.segment_of >= -1) & (c.segment_of < m)).all()
    # the plain Delaunay triangulation is no CDT of these segments
    d = gpugeom.Delaunay(pts, backend=backend)
    assert not gpugeom.verify.check_constrained_delaunay(pts, d.simplices, segs)[0]
    # enclosed: the polygon's area (shoelace); a hole at its centre leaves the hull minus it
    x, y = poly[:, 0], poly[:, 1]
    poly_area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    hull_area = _area(pts, c.simplices)
    e = gpugeom.ConstrainedDelaunay(pts, segs, domain="enclosed", backend=backend)
    assert np.isclose(_area(pts, e.simplices), poly_area, rtol=1e-12)
    h = gpugeom.ConstrainedDelaunay(pts, segs, holes=[[0.5, 0.5]], backend=backend)
    assert np.isclose(_area(pts, h.simplices), hull_area - poly_area, rtol=1e-12)
    assert h.stats["counters"]["removed_triangles"] == c.nsimplex - h.nsimplex
    r = gpugeom.ConstrainedDelaunay(pts, segs, regions=[[0.5, 0.5, 3.0]], backend=backend)
    assert np.isclose(_area(pts, r.simplices[r.attributes == 3.0]), poly_area, rtol=1e-12)
    with pytest.raises(ValueError, match="cross"):
        gpugeom.ConstrainedDelaunay([[0, 0], [1, 1], [0, 1], [1, 0]], [[0, 1], [2, 3]],
                                    backend=backend)
    with pytest.raises(ValueError, match="domain"):
        gpugeom.ConstrainedDelaunay(pts, segs, domain="inside")
    # crossings="split": a vertex where the two diagonals cross, each the chain through it
    s = gpugeom.ConstrainedDelaunay([[0, 0], [1, 1], [0, 1], [1, 0]], [[0, 1], [2, 3]],
                                    crossings="split", backend=backend)
    assert s.new_points.tolist() == [[0.5, 0.5]] and s.new_point_segments.tolist() == [[0, 1]]
    assert s.points.shape == (5, 2) and s.nsimplex == 4 and (s.simplices == 4).any(axis=1).all()
    assert s.stats["counters"]["crossings"] == 1
    assert sorted(s.segment_of[s.segment_of >= 0].tolist()) == [0, 0, 0, 0, 1, 1, 1, 1]
    with pytest.raises(ValueError, match="crossings"):
        gpugeom.ConstrainedDelaunay(pts, segs, crossings="maybe")


def test_delaunay2d_digital_method_equals_incremental(backend, rng):
    pts = np.concatenate([rng.random((3000, 2)), np.repeat(rng.random((5, 2)), 40, axis=0)])
    a = gpugeom.Delaunay(pts, backend=backend)
    for grid in (0, 64):
        b = gpugeom.Delaunay(pts, backend=backend, method="digital", grid=grid)
        assert b.stats["counters"]["digital_fallback"] == 0
        assert simplex_set(a.simplices) == simplex_set(b.simplices)
        assert np.array_equal(a.duplicate_of, b.duplicate_of)
    with pytest.raises(ValueError, match="method"):
        gpugeom.Delaunay(pts, method="magic")


def test_delaunay3d_digital_method_equals_incremental(backend, rng):
    pts = np.concatenate([rng.random((3000, 3)), np.repeat(rng.random((5, 3)), 40, axis=0)])
    a = gpugeom.Delaunay(pts, backend=backend)
    for grid in (0, 32):
        b = gpugeom.Delaunay(pts, backend=backend, method="digital", grid=grid)
        assert b.stats["counters"]["digital_fallback"] == 0
        assert b.stats["counters"]["digital_splay_rounds"] > 0
        assert simplex_set(a.simplices) == simplex_set(b.simplices)
        assert np.array_equal(a.duplicate_of, b.duplicate_of)
    with pytest.raises(ValueError, match="16..1024"):
        gpugeom.Delaunay(pts, method="digital", grid=8)


def test_convex_hull_digital_method_equals_incremental(backend, rng):
    ball = rng.standard_normal((20000, 3))
    ball /= np.linalg.norm(ball, axis=1, keepdims=True)
    ball *= rng.random((20000, 1)) ** (1 / 3)
    cube = np.array([[x, y, z] for x in range(5) for y in range(5) for z in range(5)], float)
    for pts in (ball, cube):
        a = gpugeom.ConvexHull(pts, backend=backend)
        for grid in (0, 16):
            b = gpugeom.ConvexHull(pts, backend=backend, method="digital", grid=grid)
            assert b.stats["counters"]["digital_fallback"] == 0
            assert simplex_set(a.simplices) == simplex_set(b.simplices)
            assert np.array_equal(a.vertices, b.vertices)
    b = gpugeom.ConvexHull(ball, backend=backend, method="digital")
    assert b.stats["counters"]["hull_input"] < len(ball) // 2  # the depth test dropped points
    with pytest.raises(ValueError, match="grid"):
        gpugeom.ConvexHull(ball, method="digital", grid=8)
    with pytest.raises(ValueError, match="3D"):
        gpugeom.ConvexHull(rng.random((50, 2)), method="digital")


def _circle_holds_all(p, tri):
    """Whether each triangle's circumcircle holds every point (to rounding)."""
    a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
    d = 2 * ((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
    bb, cc = ((b - a) ** 2).sum(1), ((c - a) ** 2).sum(1)
    ux = ((c - a)[:, 1] * bb - (b - a)[:, 1] * cc) / d
    uy = ((b - a)[:, 0] * cc - (c - a)[:, 0] * bb) / d
    centre = a + np.stack([ux, uy], 1)
    r2 = ((a - centre) ** 2).sum(1)
    far = ((p[None, :, :] - centre[:, None, :]) ** 2).sum(2).max(1)
    return np.all(far <= r2 * (1 + 1e-9))


@pytest.mark.parametrize("case", ["uniform", "circle", "square"])
def test_furthest_site_delaunay_equals_scipy(case, backend, rng):
    # issue 49: the furthest-site triangulation of the extreme points, exact
    if case == "uniform":
        p = rng.random((400, 2))
    elif case == "circle":  # (every point extreme and cocircular: any triangulation is valid)
        p = CIRCLE
    else:
        p = np.array([(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0.5), (0.5, 0), (1, 1)], float)
    g = gpugeom.Delaunay(p, furthest_site=True, backend=backend)
    assert g.furthest_site
    s = np.asarray(g.simplices)
    assert _circle_holds_all(p, s)
    hull = ss.ConvexHull(p)
    # the triangles tile the hull: their areas add up to its area, all counter-clockwise
    a = ((p[s[:, 1]] - p[s[:, 0]])[:, 0] * (p[s[:, 2]] - p[s[:, 0]])[:, 1]
         - (p[s[:, 1]] - p[s[:, 0]])[:, 1] * (p[s[:, 2]] - p[s[:, 0]])[:, 0]) / 2
    assert np.all(a > 0) and a.sum() == pytest.approx(hull.volume)
    assert set(np.unique(s)) == set(hull.vertices)
    if case == "uniform":  # (general position: the one triangulation, as SciPy's)
        want = ss.Delaunay(p, furthest_site=True).simplices
        assert sorted(map(tuple, np.sort(s, 1).tolist())) == \
            sorted(map(tuple, np.sort(want, 1).tolist()))
    # a point that is not an extreme point (or a copy of one) has no simplex
    vts, dup = np.asarray(g.vertex_to_simplex), np.asarray(g.duplicate_of)
    assert np.all((vts >= 0) == (np.isin(np.arange(len(p)), hull.vertices) | (dup >= 0)))


def test_furthest_site_voronoi_equals_scipy(backend, rng):
    p = rng.random((300, 2))
    g = gpugeom.Voronoi(p, furthest_site=True, backend=backend)
    s = ss.Voronoi(p, furthest_site=True)
    assert g.furthest_site and len(g.regions) == len(s.regions)  # (no Qz region, as SciPy's)
    gv, sv = np.asarray(g.vertices), s.vertices
    assert len(gv) == len(sv)
    order = np.lexsort(gv.T)
    np.testing.assert_allclose(gv[order], sv[np.lexsort(sv.T)], rtol=1e-12)
    assert sorted(map(tuple, np.sort(g.ridge_points, 1).tolist())) == \
        sorted(map(tuple, np.sort(s.ridge_points, 1).tolist()))
    # regions: every extreme point's is unbounded, the others' empty, as SciPy's
    for i in range(len(p)):
        gr, sr = g.regions[g.point_region[i]], s.regions[s.point_region[i]]
        assert len(gr) == len(sr) and (-1 in gr) == (-1 in sr)
    # the rays run into the hull: from each unbounded ridge's vertex, along its direction, the
    # two points it separates stay the furthest
    vx = np.asarray(g.vertices)
    for (a, b), (u, w), d in zip(np.asarray(g.ridge_points), g.ridge_vertices,
                                 np.asarray(g.ridge_directions)):
        if u >= 0 and w >= 0:
            continue
        x = vx[max(u, w)] + 10 * d
        far = np.sort(((p - x) ** 2).sum(1))[-2:]
        assert ((p[[a, b]] - x) ** 2).sum(1) == pytest.approx(far[::-1], rel=1e-9) or \
            ((p[[a, b]] - x) ** 2).sum(1) == pytest.approx(far, rel=1e-9)


def test_furthest_site_refusals():
    with pytest.raises(ValueError, match="2D"):
        gpugeom.Delaunay(np.random.rand(10, 3), furthest_site=True)
    with pytest.raises(ValueError, match="incremental"):
        gpugeom.Voronoi(np.random.rand(10, 2), furthest_site=True, incremental=True)
    with pytest.raises(gpugeom.DegenerateInputError):
        gpugeom.Delaunay(np.array([(0, 0), (1, 1), (2, 2.0)]), furthest_site=True)


@pytest.mark.parametrize("dim", [2, 3])
def test_delaunay_several_devices_equal_one(dim, backend, rng):
    """devices=: one block per entry (on the CPU backend, a CPU block each), the arrays of one
    call, on random points, a grid with copies, and points on a sphere."""
    g = np.stack(np.meshgrid(*[np.arange(7.0)] * dim, indexing="ij"), -1).reshape(-1, dim)
    s = rng.normal(size=(400, dim))
    cases = [rng.random((3000, dim)), np.concatenate([g, g[::5]]),
             s / np.linalg.norm(s, axis=1, keepdims=True)]
    for p in cases:
        one = gpugeom.Delaunay(p, backend=backend)
        for devices in ([0, 0], [0, 0, 0], [0], "all"):
            d = gpugeom.Delaunay(p, backend=backend, devices=devices)
            for name in ("simplices", "neighbors", "vertex_to_simplex", "duplicate_of"):
                np.testing.assert_array_equal(getattr(d, name), getattr(one, name),
                                              err_msg=f"{name} in {devices}")
            np.testing.assert_array_equal(d.convex_hull, one.convex_hull)


def test_delaunay_several_devices_refusals(backend, rng):
    p = rng.random((100, 3))
    for kw, what in ((dict(incremental=True), "incremental"), (dict(method="digital"), "digital"),
                     (dict(progress=lambda *a: None), "progress")):
        with pytest.raises(ValueError, match=what):
            gpugeom.Delaunay(p, backend=backend, devices=[0, 0], **kw)
    with pytest.raises(ValueError, match="ordinals"):
        gpugeom.Delaunay(p, backend=backend, devices=[0, -1])
    with pytest.raises(ValueError, match="empty"):
        gpugeom.Delaunay(p, backend=backend, devices=[])
    bad = p.copy()
    bad[7, 1] = np.nan
    with pytest.raises(ValueError, match="NaN|infinite|Inf"):
        gpugeom.Delaunay(bad, backend=backend, devices=[0, 0])
