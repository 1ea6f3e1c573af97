"""CUDA arrays in, CUDA arrays out (CuPy and PyTorch): computed on the GPU on the caller's
stream, the same results as from NumPy. Skipped without a usable GPU and the array library."""
import numpy as np
import pytest

import gpugeom

if not (gpugeom.built_with_cuda() and gpugeom.device_info()["available"]):
    pytest.skip("no usable CUDA device", allow_module_level=True)

cupy = pytest.importorskip("cupy")


def simplex_set(s):
    return {tuple(sorted(t)) for t in np.asarray(s).tolist()}


def test_delaunay_cupy(rng):
    p = rng.random((50000, 2))
    d = gpugeom.Delaunay(cupy.asarray(p))
    assert isinstance(d.simplices, cupy.ndarray) and d.simplices.dtype == cupy.int32
    h = gpugeom.Delaunay(p)
    assert simplex_set(cupy.asnumpy(d.simplices)) == simplex_set(h.simplices)
    assert isinstance(d.convex_hull, cupy.ndarray)
    assert isinstance(d.vertex_to_simplex, cupy.ndarray)
    np.testing.assert_array_equal(cupy.asnumpy(d.find_simplex(cupy.asarray(p[:100]))) >= 0, True)


def test_delaunay3d_hull_voronoi_cupy(rng):
    p = rng.random((20000, 3))
    d = gpugeom.Delaunay(cupy.asarray(p))
    assert isinstance(d.simplices, cupy.ndarray)
    assert simplex_set(cupy.asnumpy(d.simplices)) == simplex_set(gpugeom.Delaunay(p).simplices)
    h = gpugeom.ConvexHull(cupy.asarray(p))
    assert isinstance(h.vertices, cupy.ndarray)
    h2 = gpugeom.ConvexHull(cupy.asarray(p[:, :2]))
    assert isinstance(h2.vertices, cupy.ndarray)
    np.testing.assert_array_equal(cupy.asnumpy(h2.vertices), gpugeom.ConvexHull(p[:, :2]).vertices)
    np.testing.assert_array_equal(cupy.asnumpy(h.vertices), gpugeom.ConvexHull(p).vertices)
    assert h.volume == pytest.approx(gpugeom.ConvexHull(p).volume, rel=1e-12)
    v = gpugeom.Voronoi(cupy.asarray(p[:, :2]))
    vh = gpugeom.Voronoi(p[:, :2])
    assert isinstance(v.vertices, cupy.ndarray)
    np.testing.assert_array_equal(cupy.asnumpy(v.vertices), vh.vertices)
    assert v.regions == vh.regions


def test_edt_cupy_on_a_stream(rng):
    a = rng.random((300, 200)) > 0.1
    a[0, 0] = False
    ref_d, ref_i = gpugeom.distance_transform_edt(a, return_indices=True, backend="cpu")
    s = cupy.cuda.Stream(non_blocking=True)
    with s:
        ga = cupy.asarray(a)
        d, i = gpugeom.distance_transform_edt(ga, return_indices=True)
        assert isinstance(d, cupy.ndarray) and isinstance(i, cupy.ndarray)
        np.testing.assert_array_equal(cupy.asnumpy(d), ref_d)
        np.testing.assert_array_equal(cupy.asnumpy(i), ref_i)
        out = cupy.empty(a.shape, dtype=cupy.float64)
        assert gpugeom.distance_transform_edt(ga, distances=out) is None
        np.testing.assert_array_equal(cupy.asnumpy(out), ref_d)
    lab = gpugeom.voronoi_labels(cupy.asarray(a.astype(np.int32)))
    assert isinstance(lab, cupy.ndarray)


@pytest.mark.parametrize("shape", [(20, 18, 16, 22), (9, 8, 10, 7, 6)])
def test_edt_nd_cupy_and_torch(shape, rng):
    """N-D grids on the device (CuPy and PyTorch): the same as the CPU executor's, slices too."""
    a = rng.random(shape) > 0.02
    a.flat[0] = False
    ref_d, ref_i = gpugeom.distance_transform_edt(a, return_indices=True, backend="cpu")
    d, i = gpugeom.distance_transform_edt(cupy.asarray(a), return_indices=True)
    assert isinstance(d, cupy.ndarray) and d.shape == shape
    np.testing.assert_array_equal(cupy.asnumpy(d), ref_d)
    np.testing.assert_array_equal(cupy.asnumpy(i), ref_i)
    ds = gpugeom.distance_transform_edt(cupy.asarray(a), slices=[shape[0] - 1, 2])
    np.testing.assert_array_equal(cupy.asnumpy(ds), ref_d[[shape[0] - 1, 2]])
    lab = a.astype(np.int32) * 0
    lab.flat[[5, 77, 300]] = [3, 1, 2]
    ref = gpugeom.voronoi_labels(lab, backend="cpu")
    np.testing.assert_array_equal(cupy.asnumpy(gpugeom.voronoi_labels(cupy.asarray(lab))), ref)
    torch = pytest.importorskip("torch")
    t = torch.as_tensor(a, device="cuda")
    dt = gpugeom.distance_transform_edt(t)
    assert isinstance(dt, torch.Tensor) and dt.is_cuda
    np.testing.assert_array_equal(dt.cpu().numpy(), ref_d)


def test_cvd_cupy(rng):
    y, x = np.mgrid[0:64, 0:80]
    dens = np.exp(-((x - 40) ** 2 + (y - 30) ** 2) / 400.0) + 0.05
    r = gpugeom.centroidal_voronoi(cupy.asarray(dens), 100, max_iterations=20)
    assert isinstance(r.sites, cupy.ndarray)
    h = gpugeom.centroidal_voronoi(dens, 100, max_iterations=20, backend="cpu")
    np.testing.assert_array_equal(cupy.asnumpy(r.sites), h.sites)


def test_torch_cuda(rng):
    torch = pytest.importorskip("torch")
    p = rng.random((30000, 2))
    t = torch.as_tensor(p, device="cuda")
    d = gpugeom.Delaunay(t)
    assert isinstance(d.simplices, torch.Tensor) and d.simplices.is_cuda
    assert simplex_set(d.simplices.cpu().numpy()) == simplex_set(gpugeom.Delaunay(p).simplices)
    assert isinstance(d.convex_hull, torch.Tensor) and d.convex_hull.is_cuda
    a = torch.as_tensor(rng.random((128, 96)) > 0.1, device="cuda")
    a[0, 0] = False
    dist = gpugeom.distance_transform_edt(a)
    assert isinstance(dist, torch.Tensor) and dist.is_cuda
    np.testing.assert_array_equal(dist.cpu().numpy(),
                                  gpugeom.distance_transform_edt(a.cpu().numpy(), backend="cpu"))
    # a CPU tensor comes back as a CPU tensor
    dc = gpugeom.Delaunay(torch.as_tensor(p[:1000]))
    assert isinstance(dc.simplices, torch.Tensor) and not dc.simplices.is_cuda


def test_constrained_delaunay_cupy(rng):
    # points and segments on the device: the result stays there, equal to the host run's
    n = 20000
    p = rng.random((n, 2))
    poly = np.array([[0.2, 0.2], [0.8, 0.2], [0.8, 0.8], [0.2, 0.8]])
    p[:4] = poly
    segs = np.array([[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]], dtype=np.int32)
    h = gpugeom.ConstrainedDelaunay(p, segs, domain="enclosed")
    d = gpugeom.ConstrainedDelaunay(cupy.asarray(p), cupy.asarray(segs), domain="enclosed")
    assert isinstance(d.simplices, cupy.ndarray) and isinstance(d.segment_of, cupy.ndarray)
    assert (cupy.asnumpy(d.simplices) == h.simplices).all()
    assert (cupy.asnumpy(d.segment_of) == h.segment_of).all()
    assert d.stats["counters"]["removed_triangles"] == h.stats["counters"]["removed_triangles"] > 0
    # segments from the host join device points; split needs host arrays
    e = gpugeom.ConstrainedDelaunay(cupy.asarray(p), segs)
    assert isinstance(e.simplices, cupy.ndarray)
    with pytest.raises(ValueError, match="host"):
        gpugeom.ConstrainedDelaunay(cupy.asarray(p), segs, crossings="split")


def test_incremental_delaunay_stays_on_the_gpu(rng):
    # issue 47: new points of another kind are moved to the GPU; the triangulation is kept there
    p = rng.random((40000, 2))
    d = gpugeom.Delaunay(cupy.asarray(p[:20000]), incremental=True)
    d.add_points(cupy.asarray(p[20000:30000]))
    assert d.stats["counters"]["inserted_points"] == 10000  # kept, not computed afresh
    d.add_points(p[30000:])  # NumPy points join the GPU triangulation
    assert isinstance(d.simplices, cupy.ndarray) and isinstance(d.points, cupy.ndarray)
    assert d.npoints == 40000
    assert simplex_set(cupy.asnumpy(d.simplices)) == simplex_set(gpugeom.Delaunay(p).simplices)
    q = p + rng.normal(0, 1e-6, p.shape)
    d.move(cupy.asarray(q))
    assert simplex_set(cupy.asnumpy(d.simplices)) == simplex_set(gpugeom.Delaunay(q).simplices)
    d.remove(cupy.asarray([5, 9, 30001]))  # indices on the GPU stay there
    live = np.setdiff1d(np.arange(len(q)), [5, 9, 30001])
    f = gpugeom.Delaunay(q[live])
    assert simplex_set(cupy.asnumpy(d.simplices)) == simplex_set(live[f.simplices])
    assert (cupy.asnumpy(d.duplicate_of)[[5, 9, 30001]] == -2).all()


def test_incremental_delaunay_torch_cuda(rng):
    torch = pytest.importorskip("torch")
    p = rng.random((40000, 2))
    t = torch.as_tensor(p[:20000], device="cuda")
    dt = gpugeom.Delaunay(t, incremental=True)
    dt.add_points(torch.as_tensor(p[20000:], device="cuda"))
    assert isinstance(dt.simplices, torch.Tensor) and dt.simplices.is_cuda
    assert simplex_set(dt.simplices.cpu().numpy()) == simplex_set(gpugeom.Delaunay(p).simplices)


def test_incremental_hull_and_voronoi_stay_on_the_gpu(rng):
    # issue 47: a 3D ConvexHull and a Voronoi diagram kept on the GPU (DynamicHull3d,
    # DynamicDelaunay2d): results stay CuPy arrays and equal a fresh host call's
    p = rng.standard_normal((30000, 3))
    h = gpugeom.ConvexHull(cupy.asarray(p[:20000]), incremental=True)
    h.track_changes()
    h.add_points(cupy.asarray(p[20000:]))
    assert isinstance(h.simplices, cupy.ndarray) and isinstance(h.vertices, cupy.ndarray)
    f = gpugeom.ConvexHull(p)
    assert simplex_set(cupy.asnumpy(h.simplices)) == simplex_set(f.simplices)
    prev, gone = h.changes()
    assert isinstance(prev, cupy.ndarray) and prev.shape == (h.nsimplex,)
    v = np.asarray(cupy.asnumpy(h.vertices))
    h.remove(cupy.asarray(v[:5].astype(np.int32)))
    live = np.setdiff1d(np.arange(len(p)), v[:5])
    assert simplex_set(cupy.asnumpy(h.simplices)) == simplex_set(live[gpugeom.ConvexHull(p[live]).simplices])
    q2 = rng.random((20000, 2))
    vor = gpugeom.Voronoi(cupy.asarray(q2[:15000]), incremental=True)
    vor.add_points(cupy.asarray(q2[15000:]))
    vor.remove(cupy.asarray(np.array([3, 15001], np.int32)))
    assert isinstance(vor.vertices, cupy.ndarray)
    keep = np.setdiff1d(np.arange(len(q2)), [3, 15001])
    fv = gpugeom.Voronoi(q2[keep])
    assert simplex_set(cupy.asnumpy(vor.delaunay_simplices)) == simplex_set(keep[fv.delaunay_simplices])
    assert vor.regions[vor.point_region[3]] == [] and len(vor.regions[vor.point_region[4]]) > 0
