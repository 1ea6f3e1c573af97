"""Quality meshing (mesh2d, triangulate): Triangle's classic domains judged by the exact checker
with their bounds, the triangle package's dict and switches (its own results as the reference
where it is installed), sizing functions and grids, regions, limits and bad options."""
import re

import numpy as np
import pytest

import gpugeom
from gpugeom import verify


def square_with_hole():
    v = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [.3, .3], [.7, .3], [.7, .7], [.3, .7]], float)
    s = np.array([[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]])
    return dict(vertices=v, segments=s, holes=np.array([[.5, .5]]))


def letter_a():
    outer = [[0, 0], [.2, 0], [.3, .3], [.7, .3], [.8, 0], [1, 0], [.6, 1], [.4, 1]]
    inner = [[.37, .45], [.63, .45], [.5, .8]]
    v = np.array(outer + inner, float)
    s = [[i, (i + 1) % 8] for i in range(8)] + [[8 + i, 8 + (i + 1) % 3] for i in range(3)]
    return dict(vertices=v, segments=np.array(s), holes=np.array([[.5, .6]]))


def wedge(degrees=5.0, spokes=7):
    """Spokes from the origin `degrees` apart, closed by chords: small input angles."""
    a = np.radians(degrees) * np.arange(spokes)
    v = np.vstack([[0, 0], np.column_stack([np.cos(a), np.sin(a)])])
    s = [[0, i + 1] for i in range(spokes)] + [[i + 1, i + 2] for i in range(spokes - 1)]
    return dict(vertices=v, segments=np.array(s))


def coastline(m=600, seed=3):
    rng = np.random.default_rng(seed)
    t = 2 * np.pi * np.arange(m) / m
    r = 1 + 0.25 * np.sin(7 * t) + 0.1 * np.sin(53 * t + 1) + 0.004 * rng.uniform(-1, 1, m)
    v = np.column_stack([r * np.cos(t), r * np.sin(t)])
    return dict(vertices=v, segments=np.column_stack([np.arange(m), (np.arange(m) + 1) % m]))


DOMAINS = {"square with a hole": square_with_hole, "letter A": letter_a, "coastline": coastline}


def smallest_angles(v, t):
    p = v[t]
    ang = []
    for k in range(3):
        a, b, c = p[:, k], p[:, (k + 1) % 3], p[:, (k + 2) % 3]
        u, w = b - a, c - a
        cos = (u * w).sum(1) / np.linalg.norm(u, axis=1) / np.linalg.norm(w, axis=1)
        ang.append(np.degrees(np.arccos(np.clip(cos, -1, 1))))
    return np.min(ang, axis=0)


def areas(v, t):
    p = v[t]
    u, w = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    return 0.5 * (u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0])


@pytest.mark.parametrize("name", sorted(DOMAINS))
@pytest.mark.parametrize("angle,area", [(20, None), (30, 0.002), (33.8, 0.0005)])
def test_classic_domains_meet_their_bounds(name, angle, area, backend):
    d = DOMAINS[name]()
    m = gpugeom.mesh2d(d["vertices"], d["segments"], holes=d.get("holes"), min_angle=angle,
                       max_area=area, backend=backend)
    ok, why = verify.check_mesh2d(m, d["segments"], angle, area or 0)
    assert ok, why
    assert len(m.small_angles) == 0 and len(m.large_triangles) == 0
    v, t = m["vertices"], m["triangles"]
    np.testing.assert_array_equal(v[:len(d["vertices"])], d["vertices"])
    assert smallest_angles(v, t).min() >= angle - 1e-9
    if area:
        assert areas(v, t).max() <= area * (1 + 1e-12)
    assert m.stats["counters"]["triangles"] == len(t)


def test_small_input_angles_are_reported_not_refined_forever(backend):
    d = wedge(5.0)
    m = gpugeom.mesh2d(d["vertices"], d["segments"], min_angle=30, max_area=0.005,
                       backend=backend)
    ok, why = verify.check_mesh2d(m, d["segments"], 30, 0.005)
    assert ok, why
    assert len(m.small_angles) > 0
    assert set(m.small_angle_reasons) <= {"input angle", "shell"}
    # The 5-degree sectors keep thin triangles all along their spokes (between shell vertices),
    # as Triangle's do: the same counts where the triangle package is at hand.
    try:
        import triangle
    except ImportError:
        return
    t = triangle.triangulate(d, "pq30a0.005")
    small = (smallest_angles(t["vertices"], t["triangles"]) < 30 - 1e-9).sum()
    assert abs(len(m.small_angles) - small) <= 0.1 * small
    assert abs(len(m["triangles"]) - len(t["triangles"])) <= 0.1 * len(t["triangles"])


def test_same_result_on_every_thread_count(backend):
    d = coastline(400)
    kw = dict(holes=None, min_angle=30, max_area=0.003, backend=backend)
    a = gpugeom.mesh2d(d["vertices"], d["segments"], threads=1, **kw)
    b = gpugeom.mesh2d(d["vertices"], d["segments"], **kw)
    for k in ("vertices", "triangles", "neighbors", "segments"):
        np.testing.assert_array_equal(a[k], b[k])


HAVE_GPU = gpugeom.built_with_cuda() and gpugeom.device_info()["available"]


@pytest.mark.skipif(not HAVE_GPU, reason="no usable GPU")
def test_backends_agree():
    d = letter_a()
    r = [gpugeom.mesh2d(d["vertices"], d["segments"], holes=d["holes"], min_angle=32,
                        max_area=1e-4, backend=b) for b in ("cpu", "cuda")]
    for k in ("vertices", "triangles", "neighbors", "segments"):
        np.testing.assert_array_equal(r[0][k], r[1][k])


def test_sizing_function_grid_and_regions(backend):
    d = square_with_hole()
    f = lambda x, y: 1e-4 + 0.01 * x  # noqa: E731  (fine on the left, coarse on the right)
    m = gpugeom.mesh2d(d["vertices"], d["segments"], holes=d["holes"], min_angle=25,
                       max_area=f, backend=backend)
    assert verify.check_mesh2d(m, d["segments"], 25)[0]
    c = m["vertices"][m["triangles"]].mean(1)
    assert (areas(m["vertices"], m["triangles"]) <= f(c[:, 0], c[:, 1]) * (1 + 1e-12)).all()
    grid = np.array([[1e-3, 1e-3], [1e-4, 1e-4]])  # fine at the top
    g = gpugeom.mesh2d(d["vertices"], d["segments"], holes=d["holes"], min_angle=25,
                       max_area=(grid, (0, 0, 1, 1)), backend=backend)
    c = g["vertices"][g["triangles"]].mean(1)
    assert (areas(g["vertices"], g["triangles"]) <= 1e-3 - 9e-4 * c[:, 1] + 1e-15).all()
    # Two regions split by a segment: each its attribute and area bound.
    v = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [.5, 0], [.5, 1]], float)
    s = np.array([[0, 4], [4, 1], [1, 2], [2, 5], [5, 3], [3, 0], [4, 5]])
    r = gpugeom.mesh2d(v, s, regions=[[.25, .5, 1.0, 1e-3], [.75, .5, 2.0, 0]], min_angle=20,
                       backend=backend)
    at = r["triangle_attributes"][:, 0]
    a = areas(r["vertices"], r["triangles"])
    assert set(np.unique(at)) == {1.0, 2.0}
    assert a[at == 1].max() <= 1e-3 * (1 + 1e-12) and a[at == 2].max() > 1e-3
    assert abs(a[at == 1].sum() - 0.5) < 1e-12 and abs(a[at == 2].sum() - 0.5) < 1e-12


def test_steiner_limit(backend):
    d = square_with_hole()
    m = gpugeom.mesh2d(d["vertices"], d["segments"], holes=d["holes"], min_angle=30,
                       max_area=1e-4, max_steiner=50, backend=backend)
    assert len(m["vertices"]) <= 8 + 50
    assert len(m.large_triangles) > 0
    assert verify.check_mesh2d(m, d["segments"], exempt=np.arange(len(m["triangles"])))[0]


def test_bad_options_are_refused():
    d = square_with_hole()
    with pytest.raises(ValueError, match="33.8"):
        gpugeom.mesh2d(d["vertices"], d["segments"], min_angle=40)
    with pytest.raises(ValueError, match="max_area"):
        gpugeom.mesh2d(d["vertices"], d["segments"], max_area=-1)
    with pytest.raises(ValueError, match="'D'"):
        gpugeom.triangulate(d, "pqD")
    with pytest.raises(ValueError, match="option string"):
        gpugeom.triangulate(d, "pq30a0.1#")
    with pytest.raises(ValueError, match="outside"):
        gpugeom.mesh2d(d["vertices"], [[0, 9]])


# --- the triangle package's interface, with its own results where it is installed ---

@pytest.mark.parametrize("opts", ["p", "pq", "pq30a0.01", "pq33a0.001", "pq20a0.0005An", "pc",
                                  "", "q", "pqe", "pa0.01"])
def test_triangulate_matches_the_triangle_package(opts, backend):
    triangle = pytest.importorskip("triangle")
    for make in (square_with_hole, letter_a):
        d = make()
        g = gpugeom.triangulate(d, opts, backend=backend)
        t = triangle.triangulate(d, opts)
        assert set(g) == set(t) - {"edge_markers"}, opts
        for k in g:
            assert g[k].ndim == t[k].ndim and g[k].shape[1:] == t[k].shape[1:], (opts, k)
        nt, ng = len(t["triangles"]), len(g["triangles"])
        if "q" in opts or "a" in opts:
            # Other Steiner points, as many within a tolerance: 15 % (or 10 triangles) on these
            # small meshes, 10 % on larger ones (test_triangle_counts_on_a_large_mesh).
            assert abs(ng - nt) <= max(10, 0.15 * nt), (opts, ng, nt)
        else:
            assert ng == nt, opts
        if "p" in opts:
            q = re.search(r"q([0-9.]*)", opts)
            a = re.search(r"a([0-9.]*)", opts)
            angle = float(q.group(1) or 20) if q else 0
            area = float(a.group(1) or 0) if a else 0
            m = gpugeom.mesh2d(d["vertices"], d["segments"], holes=d["holes"], min_angle=angle,
                               max_area=area or None, backend=backend)
            ok, why = verify.check_mesh2d(m, d["segments"], angle, area)
            assert ok, why


@pytest.mark.parametrize("opts", ["pq30a0.00005", "pq33.8a0.0002"])
def test_triangle_counts_on_a_large_mesh(opts, backend):
    triangle = pytest.importorskip("triangle")
    for make in (square_with_hole, coastline):
        d = make()
        g = gpugeom.triangulate(d, opts, backend=backend)
        t = triangle.triangulate(d, opts)
        nt, ng = len(t["triangles"]), len(g["triangles"])
        assert abs(ng - nt) <= 0.1 * nt, (opts, ng, nt)


def test_meshio_and_pyvista():
    d = square_with_hole()
    m = gpugeom.mesh2d(d["vertices"], d["segments"], holes=d["holes"], min_angle=30,
                       max_area=0.01)
    meshio = pytest.importorskip("meshio")
    mm = m.to_meshio()
    assert isinstance(mm, meshio.Mesh) and len(mm.cells[0].data) == len(m["triangles"])


@pytest.mark.skipif(not HAVE_GPU, reason="no usable GPU")
def test_device_arrays_stay_on_the_device():
    cupy = pytest.importorskip("cupy")
    d = letter_a()
    host = gpugeom.mesh2d(d["vertices"], d["segments"], holes=d["holes"], min_angle=30,
                          max_area=1e-3)
    dev = gpugeom.mesh2d(cupy.asarray(d["vertices"]), cupy.asarray(d["segments"]),
                         holes=d["holes"], min_angle=30, max_area=1e-3)
    for k in ("vertices", "triangles", "neighbors", "segments", "segment_markers",
              "vertex_markers"):
        assert isinstance(dev[k], cupy.ndarray), k
        np.testing.assert_array_equal(cupy.asnumpy(dev[k]), host[k])
    torch = pytest.importorskip("torch")
    t = gpugeom.mesh2d(torch.as_tensor(d["vertices"], device="cuda"), d["segments"],
                       holes=d["holes"], min_angle=30, max_area=1e-3)
    assert t["triangles"].is_cuda
    np.testing.assert_array_equal(t["triangles"].cpu().numpy(), host["triangles"])
