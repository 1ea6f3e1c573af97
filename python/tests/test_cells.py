"""gpugeom.VoronoiCells (issue 49) against independent computations: SciPy's Voronoi diagram
(Qhull) with each cell's volume as the convex hull of its vertices, 27 replicas for periodic
boxes, lattices, and freud where it is installed."""
import numpy as np
import pytest
import scipy.spatial as ss

import gpugeom


def _hull_volumes(points, inner):
    """Per index in `inner`, the volume of its Voronoi cell by SciPy (Qhull): the convex hull of
    the region's vertices; NaN where the region is unbounded."""
    v = ss.Voronoi(points)
    out = np.full(len(inner), np.nan)
    for k, i in enumerate(inner):
        reg = v.regions[v.point_region[i]]
        if -1 in reg or not reg:
            continue
        out[k] = ss.ConvexHull(v.vertices[reg]).volume
    return out


def _check_layout(c, n):
    fo = np.asarray(c.face_offsets)
    assert fo.shape == (n + 1,) and fo[0] == 0 and np.all(np.diff(fo) >= 0)
    assert len(c.neighbors) == fo[-1] == len(c.face_areas) == len(c.face_normals)
    fvo = np.asarray(c.face_vertex_offsets)
    assert fvo[-1] == len(c.faces) and np.all(np.diff(fvo) >= 3)
    assert np.allclose(np.linalg.norm(c.face_normals, axis=1), 1)
    # per cell, its surface area is the sum of its faces'
    assert np.allclose(np.add.reduceat(c.face_areas, fo[:-1])[np.diff(fo) > 0],
                       np.asarray(c.areas)[np.diff(fo) > 0], rtol=1e-12)


def test_bounded_cells_fill_the_box_and_match_qhull(backend, rng):
    p = rng.random((3000, 3))
    c = gpugeom.VoronoiCells(p, box=[0, 1], backend=backend)
    _check_layout(c, len(p))
    assert c.volumes.sum() == pytest.approx(1, rel=1e-12)
    assert np.all(c.volumes > 0)
    # cells the box does not cut: Qhull's regions, each measured as the hull of its vertices
    v = ss.Voronoi(p)
    inner = [i for i in range(len(p)) if -1 not in v.regions[v.point_region[i]]
             and np.all((v.vertices[v.regions[v.point_region[i]]] > 0)
                        & (v.vertices[v.regions[v.point_region[i]]] < 1))]
    assert len(inner) > 1000
    np.testing.assert_allclose(c.volumes[inner], _hull_volumes(p, inner), rtol=1e-9)


def test_periodic_cells_match_replicas(backend, rng):
    p = rng.random((500, 3)) * [1, 2, 3]
    c = gpugeom.VoronoiCells(p, box=[[0, 0, 0], [1, 2, 3]], periodic=True, backend=backend)
    _check_layout(c, len(p))
    assert c.volumes.sum() == pytest.approx(6, rel=1e-12)
    assert np.all(np.asarray(c.neighbors) >= 0)  # (no walls)
    shifts = np.array([(a, b, z) for a in (-1, 0, 1) for b in (-1, 0, 1) for z in (-1, 0, 1)])
    shifts = shifts[np.argsort(np.abs(shifts).sum(1), kind="stable")]  # (the original first)
    rep = np.concatenate([p + s * [1, 2, 3] for s in shifts])
    np.testing.assert_allclose(c.volumes, _hull_volumes(rep, range(len(p))), rtol=1e-9)
    # neighbours are symmetric, with equal face areas
    fo = np.asarray(c.face_offsets)
    owner = np.repeat(np.arange(len(p)), np.diff(fo))
    a = {}
    for i, j, s in zip(owner, np.asarray(c.neighbors), np.asarray(c.face_areas)):
        a[(i, j)] = a.get((i, j), 0) + s
    for (i, j), s in a.items():
        assert a[(j, i)] == pytest.approx(s, rel=1e-9)


@pytest.mark.parametrize("periodic", [False, True, (True, False, False)])
def test_lattice_cells_are_cubes(periodic, backend):
    m = 6
    g = (np.indices((m, m, m)).reshape(3, -1).T + 0.5) / m
    c = gpugeom.VoronoiCells(g, box=[0, 1], periodic=periodic, backend=backend)
    np.testing.assert_allclose(c.volumes, 1 / m**3, rtol=1e-13)
    assert np.all(np.diff(np.asarray(c.face_offsets)) == 6)  # (no sliver faces)
    np.testing.assert_allclose(c.centroids, g, atol=1e-15)
    np.testing.assert_allclose(c.face_areas, 1 / m**2, rtol=1e-13)


def test_cell_accessors_and_duplicates(backend, rng):
    p = rng.random((200, 3))
    p = np.concatenate([p, p[:1]])  # (a copy of point 0: an empty cell)
    c = gpugeom.VoronoiCells(p, box=(0.0, 1.0), backend=backend)
    assert c.volumes[-1] == 0 and len(c.cell_neighbors(200)) == 0
    faces = c.cell_faces(3)
    assert len(faces) == len(c.cell_neighbors(3)) and all(f.shape[1] == 3 for f in faces)
    # each face's vertices lie on the bisector plane of the point and its neighbour
    for f, q in zip(faces, np.asarray(c.cell_neighbors(3))):
        if q >= 0:
            d = np.linalg.norm(f - p[3], axis=1) - np.linalg.norm(f - p[q], axis=1)
            assert np.abs(d).max() < 1e-12
    assert "201 cells" in repr(c) and len(c) == 201
    # without polygons: the same measures and faces
    q = gpugeom.VoronoiCells(p, box=(0.0, 1.0), polygons=False, backend=backend)
    assert np.array_equal(q.volumes, c.volumes) and np.array_equal(q.neighbors, c.neighbors)
    assert np.array_equal(q.face_normals, c.face_normals) and q.vertices is None
    with pytest.raises(RuntimeError, match="polygons"):
        q.cell_faces(0)


def test_errors(backend):
    with pytest.raises(ValueError, match="box"):
        gpugeom.VoronoiCells(np.zeros((3, 3)), backend=backend)
    with pytest.raises(ValueError, match="periodic"):
        gpugeom.VoronoiCells(np.zeros((3, 3)), box=[0, 1], periodic=(True, False), backend=backend)
    with pytest.raises(ValueError, match="shape"):
        gpugeom.VoronoiCells(np.zeros((3, 2)), box=[0, 1], backend=backend)
    with pytest.raises(ValueError, match="outside the box"):
        gpugeom.VoronoiCells(np.full((3, 3), 2.0), box=[0, 1], backend=backend)
    with pytest.raises(ValueError, match="below hi"):
        gpugeom.VoronoiCells(np.zeros((3, 3)), box=[1, 0], backend=backend)
    # along a periodic axis any coordinate is taken into the box
    c = gpugeom.VoronoiCells(np.full((1, 3), 2.25), box=[0, 1], periodic=True, backend=backend)
    assert c.volumes[0] == pytest.approx(1)


def test_same_as_freud(rng):
    freud = pytest.importorskip("freud")
    # (freud keeps positions in float32: points it holds exactly, so both cut the same cells)
    p = (rng.random((2000, 3)) - 0.5).astype(np.float32).astype(np.float64)
    box = freud.box.Box.cube(1)
    fv = freud.locality.Voronoi()
    fv.compute((box, p))
    c = gpugeom.VoronoiCells(p, box=[-0.5, 0.5], periodic=True)
    # (1e-8: freud leaves out faces below its tolerance; on one cell here that moves its volume
    # by 1.3e-9, where Qhull's hull of the replicas' region agrees with ours to 6e-16)
    np.testing.assert_allclose(c.volumes, fv.volumes, rtol=1e-8)
    # every neighbour freud lists is one of ours, with the face's area (freud's weights are
    # float32). freud 3.4's list is not complete: it lists some pairs one way only and leaves out
    # some faces (up to a tenth of a cell's surface here) that its volumes do count
    fo = np.asarray(c.face_offsets)
    ours = {}
    for i, j, a in zip(np.repeat(np.arange(len(p)), np.diff(fo)), c.neighbors, c.face_areas):
        ours[(i, j)] = ours.get((i, j), 0) + a
    nl = fv.nlist
    theirs = {}
    for i, j, w in zip(nl.query_point_indices, nl.point_indices, nl.weights):
        theirs[(i, j)] = theirs.get((i, j), 0) + float(w)
    assert set(theirs) <= set(ours)
    for k, w in theirs.items():
        assert ours[k] == pytest.approx(w, rel=1e-5)
