"""Centroidal Voronoi diagrams and stippling from Python: the energy never increases, the same
result on every backend, progress callbacks (callables and tqdm-like bars) and stopping."""
import numpy as np
import pytest

import gpugeom


def density(rng):
    y, x = np.mgrid[0:64, 0:80]
    return np.exp(-((x - 40) ** 2 + (y - 30) ** 2) / 400.0) + 0.05


def test_cvd_basic(backend, rng):
    r = gpugeom.centroidal_voronoi(density(rng), 200, backend=backend, max_iterations=50)
    assert r.sites.shape == (200, 2) and r.mass.shape == (200,)
    assert r.iterations == len(r.energy) and r.iterations >= 1
    assert np.all(np.diff(r.energy) <= 0)
    assert r.sites[:, 0].max() < 80 and r.sites[:, 1].max() < 64
    np.testing.assert_allclose(r.mass.sum(), density(rng).sum(), rtol=1e-3)


def test_cvd_same_on_cpu_and_backend(backend, rng):
    a = gpugeom.centroidal_voronoi(density(rng), 100, backend="cpu", max_iterations=20)
    b = gpugeom.centroidal_voronoi(density(rng).astype(np.float32), 100, backend=backend,
                                   max_iterations=20)
    c = gpugeom.centroidal_voronoi(density(rng), 100, backend=backend, max_iterations=20)
    np.testing.assert_array_equal(a.sites, c.sites)
    assert b.sites.shape == a.sites.shape


def test_cvd_progress_and_stop(backend, rng):
    seen = []

    def cb(p):
        seen.append(p)
        return p.iteration < 3

    r = gpugeom.centroidal_voronoi(density(rng), 100, progress=cb, backend=backend)
    assert r.iterations == 3 and [p.iteration for p in seen] == [1, 2, 3]
    assert seen[0].energy >= seen[-1].energy

    class Bar:  # what tqdm offers
        n = 0

        def update(self, k=1):
            self.n += k

    bar = Bar()
    r = gpugeom.centroidal_voronoi(density(rng), 50, progress=bar, max_iterations=5,
                                   backend=backend)
    assert bar.n == r.iterations


def test_cvd_initial_sites_and_3d(backend, rng):
    init = np.array([[10.0, 10.0], [60.0, 40.0], [30.0, 20.0]])
    r = gpugeom.centroidal_voronoi(density(rng), 3, initial_sites=init, backend=backend)
    assert r.sites.shape == (3, 2)
    vol = np.ones((12, 14, 16))
    r3 = gpugeom.centroidal_voronoi(vol, 20, backend=backend, max_iterations=10)
    assert r3.sites.shape == (20, 3)


def test_stipple(backend, rng):
    img = np.tile(np.linspace(0, 255, 90, dtype=np.uint8), (60, 1))
    s = gpugeom.stipple(img, 300, backend=backend, max_iterations=20)
    assert s.sites.shape == (300, 2) and s.radius.shape == (300,)
    # darker (left) dots are larger on average
    left = s.radius[s.sites[:, 0] < 30].mean()
    right = s.radius[s.sites[:, 0] > 60].mean()
    assert left > right
    np.testing.assert_allclose(s.radius, np.sqrt(0.6 * s.mass / np.pi))
    rgb = np.stack([img] * 3, axis=-1)
    s2 = gpugeom.stipple(rgb, 300, backend=backend, max_iterations=20)
    assert s2.sites.shape == (300, 2)
