#!/usr/bin/env python3
"""Files of another tool: meshio writes a triangulation and a tetrahedralisation as .vtu in
each encoding it has (ascii, base64 inline, zlib; appended raw is VTK's, covered by the
fixtures) and as .vtk (ascii, binary), with point and cell data; gpugeom reads each (`gpugeom
check` proves the mesh it read is the Delaunay one meshio was given); and meshio reads what
gpugeom writes (.vtu raw / zlib / ascii, .vtk binary / ascii), cells and duplicate map intact.
Usage: test_meshio_interop.py GPUGEOM_CLI   (exit 77: meshio not installed)"""
import os
import subprocess
import sys
import tempfile

import numpy as np

try:
    import meshio
except ImportError:
    print("meshio not installed: skipped")
    sys.exit(77)
from scipy.spatial import Delaunay

G = sys.argv[1]
fail = 0


def as_set(cells):
    return {tuple(sorted(c)) for c in np.asarray(cells).tolist()}


def run(*args):
    r = subprocess.run([G, *args], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


with tempfile.TemporaryDirectory() as d:
    rng = np.random.default_rng(4)
    for dim in (2, 3):
        p = rng.random((400, dim))
        cells = Delaunay(p).simplices.astype(np.int64)
        if dim == 3:  # positively oriented, as gpugeom check wants them (Qhull's are not)
            a, b, c, e = (p[cells[:, k]] for k in range(4))
            neg = np.einsum("ij,ij->i", np.cross(b - a, c - a), e - a) < 0
            cells[neg] = cells[neg][:, [1, 0, 2, 3]]
        kind = "triangle" if dim == 2 else "tetra"
        pts3 = np.column_stack([p, np.zeros(len(p))]) if dim == 2 else p
        mesh = meshio.Mesh(pts3, [(kind, cells)], point_data={"h": p[:, 0].copy()},
                           cell_data={"id": [np.arange(len(cells), dtype=np.int32)]})
        cases = [("vtu", dict(binary=False)), ("vtu", dict(binary=True, compression=None)),
                 ("vtu", dict(binary=True, compression="zlib")), ("vtk", dict(binary=False)),
                 ("vtk", dict(binary=True))]
        for i, (ext, kw) in enumerate(cases):
            f = os.path.join(d, f"m{dim}_{i}.{ext}")
            if ext == "vtu":
                meshio.vtu.write(f, mesh, **kw)
            else:
                meshio.vtk.write(f, mesh, **kw)
            rc, out = run("check", f)
            ok = rc == 0 and "valid delaunay" in out
            print(("ok" if ok else "FAIL") + f": gpugeom check {os.path.basename(f)} {kw}")
            if not ok:
                print(out)
                fail = 1
        # the other way: gpugeom writes, meshio reads
        src = os.path.join(d, f"p{dim}.npy")
        np.save(src, np.vstack([p, p[:3]]))  # three duplicates ride along as point data
        ref = os.path.join(d, f"ref{dim}.npy")
        cmd = "delaunay2d" if dim == 2 else "delaunay3d"
        rc, out = run(cmd, src, "-o", ref)
        want = np.load(ref)
        for ext, extra in (("vtu", []), ("vtu", ["--compress"]), ("vtu", ["--ascii"]),
                           ("vtk", []), ("vtk", ["--ascii"])):
            f = os.path.join(d, f"out{dim}.{ext}")
            rc, out = run(cmd, src, "-o", f, *extra)
            m = meshio.read(f)
            got = m.cells_dict.get(kind)
            dup = np.asarray(m.point_data.get("duplicate_of", [])).reshape(-1)
            # (as sets: the order of 3D Delaunay's tetrahedra may differ between runs, see
            # docs/design-notes.md, "phase 1's intermediate mesh depends on timing")
            ok = (rc == 0 and got is not None and as_set(got) == as_set(want) and
                  np.array_equal(dup[-3:], [0, 1, 2]) and np.all(dup[:-3] == -1))
            print(("ok" if ok else "FAIL") + f": meshio reads gpugeom's {ext} {extra}")
            if not ok:
                print(out)
                fail = 1
sys.exit(fail)
