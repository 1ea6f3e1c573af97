"""gpugeom.dask.distance_transform_edt: slab by slab along axis 0, equal element for element to
the single run (distances, indices and their ties) and to SciPy's distances, in 1 to 4
dimensions, across 1 to 9 slabs, isotropic or not, on Dask's threads and on a LocalCluster (a
worker killed mid-run too)."""
import numpy as np
import pytest

import gpugeom
import gpugeom.ndimage as gn

dask = pytest.importorskip("dask")
da = pytest.importorskip("dask.array")
gd = pytest.importorskip("gpugeom.dask")
scipy_ndimage = pytest.importorskip("scipy.ndimage")


def _grids(rng):
    """Sparse and dense zeros, a lone zero far from most slabs, zeros at both ends only, and a
    lattice of zeros with exact ties between columns."""
    out = []
    for shape, p in [((40, 30, 20), 0.01), ((50, 17, 9), 0.002), ((33, 21), 0.02),
                     ((100,), 0.05), ((9, 8, 7, 6), 0.01), ((24, 10, 12), 0.5)]:
        a = (rng.random(shape) > p).astype(np.uint8)
        a.flat[rng.integers(a.size)] = 0
        out.append(a)
    lone = np.ones((64, 20, 20), np.float32)
    lone[3, 5, 5] = 0
    ends = np.ones((64, 20, 20), bool)
    ends[0, 0, 0] = ends[63, 19, 19] = False
    ties = np.ones((30, 9, 9), np.int32)
    ties[::6, ::4, ::4] = 0
    return out + [lone, ends, ties]


def _check(a, slabs, sampling=None, x=None):
    ref_d, ref_i = gn.distance_transform_edt(a, sampling=sampling, return_indices=True,
                                             backend="cpu")
    d, i = gd.distance_transform_edt(a if x is None else x, sampling=sampling,
                                     return_indices=True, slabs=slabs, backend="cpu")
    assert isinstance(d, da.Array) and isinstance(i, da.Array)
    assert d.shape == ref_d.shape and i.shape == ref_i.shape
    d, i = dask.compute(d, i)
    assert d.dtype == np.float64 and i.dtype == np.int32
    np.testing.assert_array_equal(d, ref_d)
    np.testing.assert_array_equal(i, ref_i)
    np.testing.assert_allclose(d, scipy_ndimage.distance_transform_edt(a, sampling=sampling),
                               rtol=1e-13, atol=0)


@pytest.mark.parametrize("slabs", [1, 2, 3, 9])
def test_equal_to_single_run_on_threads(slabs):
    rng = np.random.default_rng(slabs)
    with dask.config.set(scheduler="threads"):
        for a in _grids(rng):
            _check(a, min(slabs, a.shape[0]))
            _check(a, slabs, sampling=[1.5 + 0.25 * j for j in range(a.ndim)])


def test_each_backend(backend):
    """Slabs on the GPU where there is one: the CPU's single run, element for element."""
    rng = np.random.default_rng(7)
    a = (rng.random((90, 70, 60)) > 0.002).astype(np.uint8)
    a[45, 0, 0] = 0
    ref = gn.distance_transform_edt(a, return_indices=True, backend="cpu")
    with dask.config.set(scheduler="threads"):
        got = dask.compute(*gd.distance_transform_edt(a, return_indices=True, slabs=4,
                                                      backend=backend))
    for x, y in zip(got, ref):
        np.testing.assert_array_equal(x, y)


def test_cupy_chunks_stay_on_the_gpu():
    """A Dask array of CuPy chunks: every slab transformed on the GPU where it is, its results
    CuPy chunks there; the CPU's single run, element for element."""
    if not (gpugeom.built_with_cuda() and gpugeom.device_info()["available"]):
        pytest.skip("no usable CUDA device")
    cupy = pytest.importorskip("cupy")
    rng = np.random.default_rng(8)
    a = (rng.random((70, 40, 50)) > 0.002).astype(np.uint8)
    a[69, 39, 0] = 0
    ref = gn.distance_transform_edt(a, sampling=(1.0, 2.0, 0.5), return_indices=True,
                                    backend="cpu")
    x = da.from_array(cupy.asarray(a), chunks=((10, 25, 5, 30), 40, 50), asarray=False)
    with dask.config.set(scheduler="threads"):
        d, i = gd.distance_transform_edt(x, sampling=(1.0, 2.0, 0.5), return_indices=True)
        assert isinstance(d._meta, cupy.ndarray)
        d, i = dask.compute(d, i)
    assert isinstance(d, cupy.ndarray) and isinstance(i, cupy.ndarray)
    np.testing.assert_array_equal(d.get(), ref[0])
    np.testing.assert_array_equal(i.get(), ref[1])


def test_chunks_of_the_input_are_the_slabs():
    """A Dask array's chunks along axis 0 are the slabs, whatever its chunks along the others
    (they are merged), uneven ones and a slab with no zero of its own included."""
    a = np.ones((45, 16, 12), np.uint16)
    a[2, 3, 4] = a[40, 15, 0] = a[41, 0, 11] = 0
    x = da.from_array(a, chunks=((10, 1, 20, 14), (5, 11), (12,)))
    with dask.config.set(scheduler="threads"):
        _check(a, None, x=x)
        d = gd.distance_transform_edt(x, backend="cpu")
        assert d.chunks[0] == (10, 1, 20, 14)
        d32 = gd.distance_transform_edt(x, float64_distances=False, backend="cpu").compute()
        assert d32.dtype == np.float32
        np.testing.assert_array_equal(d32, gn.distance_transform_edt(
            a, float64_distances=False, backend="cpu"))
        i = gd.distance_transform_edt(x, return_distances=False, return_indices=True,
                                      backend="cpu").compute()
        np.testing.assert_array_equal(i, gn.distance_transform_edt(
            a, return_distances=False, return_indices=True, backend="cpu"))


def test_many_slabs_most_without_zeros():
    """17 slabs of one to four planes, zeros in three of them only: every slab's bounds come
    from slabs far away (the scans' longest reach), per column."""
    a = np.ones((45, 7, 6), np.uint8)
    a[3, 1, 2] = a[30, 6, 5] = a[44, 0, 0] = a[30, 0, 0] = 0
    x = da.from_array(a, chunks=((1, 4, 2, 3, 1, 4, 2, 3, 1, 4, 2, 3, 1, 4, 2, 3, 5), 7, 6))
    with dask.config.set(scheduler="threads"):
        _check(a, None, x=x)


def test_nan_counts_as_non_zero():
    a = np.ones((20, 6, 7))
    a[5, 1, 1] = 0
    a[10] = np.nan
    with dask.config.set(scheduler="threads"):
        _check(a, 4)


def test_same_arrays_every_run():
    a = (np.random.default_rng(3).random((60, 40, 30)) > 0.001).astype(np.uint8)
    with dask.config.set(scheduler="threads"):
        r1 = dask.compute(*gd.distance_transform_edt(a, return_indices=True, slabs=5,
                                                     backend="cpu", threads=1))
        r2 = dask.compute(*gd.distance_transform_edt(a, return_indices=True, slabs=5,
                                                     backend="cpu", threads=2))
    for x, y in zip(r1, r2):
        assert x.tobytes() == y.tobytes()


def test_local_cluster(cluster_client):
    rng = np.random.default_rng(29)
    a = (rng.random((80, 50, 40)) > 0.0005).astype(np.uint8)
    a[79, 49, 39] = 0
    _check(a, 6)
    b = (rng.random((70, 90)) > 0.01).astype(np.uint8)
    b[0, 0] = 0
    _check(b, 4, sampling=(0.5, 2.0))


def test_worker_killed_mid_run(kill_worker_once):
    a = (np.random.default_rng(31).random((60, 30, 20)) > 0.002).astype(np.uint8)
    a[0, 0, 0] = 0
    with kill_worker_once("_slab") as killed:
        _check(a, 4)
        assert killed()  # a worker did die, Dask ran its slab again


def test_bad_input_refused_at_the_call():
    with dask.config.set(scheduler="threads"):
        with pytest.raises(ValueError, match="no zero element"):
            gd.distance_transform_edt(np.ones((10, 4, 4)), slabs=2, backend="cpu")
        with pytest.raises(ValueError, match="empty"):
            gd.distance_transform_edt(da.zeros((0, 4, 4), chunks=1), backend="cpu")
        with pytest.raises(ValueError, match="1 to 8 dimensions"):
            gd.distance_transform_edt(np.zeros((2,) * 9), backend="cpu")
        with pytest.raises(ValueError, match="sampling"):
            gd.distance_transform_edt(np.zeros((4, 4, 4)), sampling=(1, 0, 1), backend="cpu")
        with pytest.raises(RuntimeError, match="input rank"):
            gd.distance_transform_edt(np.zeros((4, 4, 4)), sampling=(1, 1), backend="cpu")
        with pytest.raises(ValueError, match="65536"):
            gd.distance_transform_edt(da.zeros((65537, 2, 2), chunks=(4096, 2, 2)),
                                      backend="cpu")
        with pytest.raises(ValueError, match="slabs"):
            gd.distance_transform_edt(np.zeros((4, 4, 4)), slabs=0, backend="cpu")
        with pytest.raises(RuntimeError, match="at least one"):
            gd.distance_transform_edt(np.zeros((4, 4, 4)), return_distances=False,
                                      backend="cpu")
