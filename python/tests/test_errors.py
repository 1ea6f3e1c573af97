"""Bad input: typed Python errors with messages a user can act on, never a crash."""
import numpy as np
import pytest

import gpugeom


def test_shape_and_dtype_errors():
    with pytest.raises(ValueError, match=r"shape \(n, 2\) or \(n, 3\)"):
        gpugeom.Delaunay(np.zeros((10, 4)))
    with pytest.raises(ValueError, match="shape"):
        gpugeom.Delaunay(np.zeros(10))
    with pytest.raises(TypeError):
        gpugeom.Delaunay(np.array([["a", "b"]] * 5))
    with pytest.raises(TypeError):
        gpugeom.Delaunay(np.zeros((5, 2), dtype=complex))
    with pytest.raises(ValueError, match="backend"):
        gpugeom.Delaunay(np.random.random((10, 2)), backend="gpu")
    with pytest.raises(ValueError, match=r"got \(\)"):
        gpugeom.Delaunay(np.float64(3))
    with pytest.raises(gpugeom.DegenerateInputError, match="fewer than 3"):
        gpugeom.Delaunay(np.zeros((0, 2)))  # (an empty array is no layout error)
    with pytest.raises(TypeError, match="object"):
        gpugeom.distance_transform_edt(np.array([[None, 1]]))
    with pytest.raises(ValueError, match="threads"):
        gpugeom.Delaunay(np.random.random((10, 2)), threads=-3)
    with pytest.raises(ValueError, match="furthest_site"):  # (2D only)
        gpugeom.Delaunay(np.random.random((10, 3)), furthest_site=True)


def test_qhull_options():
    # issue 49: options that leave the exact result as it is are accepted, QG is refused, and QJ
    # is refused only where Qhull would joggle copies of a point into vertices
    p = np.random.default_rng(3).random((50, 2))
    for make in (gpugeom.Delaunay, gpugeom.Voronoi, gpugeom.ConvexHull):
        make(p, qhull_options="Qbb Qc Qz Qx Q12 Pp")
        make(p, qhull_options="QJ Pp")
        with pytest.raises(ValueError, match="'QG4'.*good"):
            make(p, qhull_options="QG4")
    for make in (gpugeom.Delaunay, gpugeom.Voronoi):
        with pytest.raises(ValueError, match="'QJ'.*copy of a point.*duplicate_of"):
            make(np.concatenate([p, p[:3]]), qhull_options="QJ")
    # find_simplex on something that is not points: an error that is both gpugeom's ValueError
    # and SciPy's IndexError
    tri = gpugeom.Delaunay(p)
    for bad in (1, tri, np.zeros((4, 3))):
        with pytest.raises(ValueError, match="xi must have shape"):
            tri.find_simplex(bad)
        with pytest.raises(IndexError):
            tri.find_simplex(bad)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite(bad, backend):
    p = np.random.default_rng(0).random((50, 3))
    p[7, 1] = bad
    with pytest.raises(ValueError, match="NaN|infinite|Inf"):
        gpugeom.Delaunay(p[:, :2], backend=backend)
    with pytest.raises(ValueError, match="NaN|infinite|Inf"):
        gpugeom.ConvexHull(p, backend=backend)


def test_degenerate_input(backend):
    with pytest.raises(gpugeom.DegenerateInputError):
        gpugeom.Delaunay(np.array([[0.0, 0], [1, 1], [2, 2], [3, 3]]), backend=backend)
    with pytest.raises(ValueError):  # it is a ValueError too
        gpugeom.Delaunay(np.zeros((2, 2)), backend=backend)
    with pytest.raises(gpugeom.DegenerateInputError, match="plane|coplanar"):
        gpugeom.ConvexHull(np.column_stack([np.random.random((50, 2)), np.zeros(50)]),
                           backend=backend)


def test_edt_errors(backend):
    with pytest.raises(ValueError):
        gpugeom.distance_transform_edt(np.ones((8, 8)), backend=backend)  # no zero element
    with pytest.raises(RuntimeError):
        gpugeom.distance_transform_edt(np.ones((8, 8)), return_distances=False)
    with pytest.raises(ValueError, match="1 to 8 dimensions"):
        gpugeom.distance_transform_edt(np.ones((2,) * 9))
    with pytest.raises(ValueError, match="no zero element|no site"):  # 4D, no site
        gpugeom.distance_transform_edt(np.ones((2, 3, 2, 3)), backend=backend)
    with pytest.raises(ValueError, match="slices"):
        gpugeom.distance_transform_edt(np.zeros((2, 3)), slices=[0])
    with pytest.raises(IndexError):
        gpugeom.distance_transform_edt(np.zeros((2, 3, 2, 3)), slices=[2])
    with pytest.raises(RuntimeError, match="shape"):
        gpugeom.distance_transform_edt(np.ones((8, 8)), distances=np.zeros((8, 9)))
    with pytest.raises(ValueError, match="sampling"):
        gpugeom.distance_transform_edt(np.ones((8, 8)), sampling=-1)


def test_cvd_errors(backend):
    with pytest.raises(ValueError):
        gpugeom.centroidal_voronoi(np.zeros((16, 16)), 10, backend=backend)  # all zero
    d = np.ones((16, 16))
    d[3, 3] = np.nan
    with pytest.raises(ValueError):
        gpugeom.centroidal_voronoi(d, 10, backend=backend)
    with pytest.raises(ValueError, match="n_sites"):
        gpugeom.centroidal_voronoi(np.ones((16, 16)), 0)


def test_unsupported_backend_message():
    if gpugeom.built_with_cuda() and gpugeom.device_info()["available"]:
        pytest.skip("a GPU is present")
    with pytest.raises(gpugeom.UnsupportedError):
        gpugeom.Delaunay(np.random.random((10, 2)), backend="cuda")


def test_device_info_and_version():
    d = gpugeom.device_info()
    assert {"available", "name", "reason", "architectures"} <= set(d)
    if not d["available"]:
        assert d["reason"]
    assert gpugeom.__version__.count(".") == 2


def test_ctrl_c_ends_a_long_run_and_leaves_the_interpreter_usable(backend):
    """A SIGINT during a run with a progress callback ends it with KeyboardInterrupt at the next
    callback; the next call works."""
    import signal

    def interrupt(p):
        if p.iteration == 2:
            signal.raise_signal(signal.SIGINT)

    dens = np.ones((64, 64))
    with pytest.raises(KeyboardInterrupt):
        gpugeom.centroidal_voronoi(dens, 50, progress=interrupt, tol=0, max_iterations=50,
                                   backend=backend)
    r = gpugeom.centroidal_voronoi(dens, 50, max_iterations=3, backend=backend)
    assert r.iterations == 3


def test_calls_from_threads_run_at_once(backend):
    """The interpreter lock is released while the library works: calls from several threads
    give the same answers as one after another."""
    from concurrent.futures import ThreadPoolExecutor

    rng = np.random.default_rng(5)
    sets = [rng.random((20000, 2)) for _ in range(4)]
    alone = [gpugeom.Delaunay(p, backend=backend).simplices for p in sets]
    with ThreadPoolExecutor(4) as ex:
        together = list(ex.map(lambda p: gpugeom.Delaunay(p, backend=backend).simplices, sets))
    for a, b in zip(alone, together):
        np.testing.assert_array_equal(a, b)
