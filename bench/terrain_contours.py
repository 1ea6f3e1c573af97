#!/usr/bin/env python3
"""A real contour-line point set for the 2D Delaunay benchmark (terrain modelling input).

Takes matplotlib's sample digital elevation model of the Jacksboro fault (344 x 403 samples,
30 m spacing, metres), smooths and upsamples it bicubically, traces contour lines at evenly
spaced elevations (contourpy, matplotlib's contouring engine) and writes every contour vertex
as (x, y) in metres to an N x 2 float64 .npy. The zoom factor is chosen so the set holds about
--n points. Such sets are hard for insertion algorithms: long runs of nearly collinear,
closely spaced points along each line, wide empty bands between lines.
"""
import argparse, sys

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=float, default=1e6, help="about how many points")
    ap.add_argument("--levels", type=int, default=120)
    ap.add_argument("-o", required=True)
    ap.add_argument("--segments", help="also write the contour lines' edges as an int32 (m, 2) "
                    ".npy of point indices (every edge a segment: the constrained benchmark)")
    a = ap.parse_args()
    import numpy as np
    import contourpy
    import matplotlib.cbook as cbook
    from scipy import ndimage
    dem = cbook.get_sample_data("jacksboro_fault_dem.npz")
    z = dem["elevation"].astype(np.float64)
    dx, dy = float(dem["dx"]), float(dem["dy"])
    levels = np.linspace(z.min(), z.max(), a.levels + 2)[1:-1]

    def trace(zoom):
        zz = ndimage.zoom(ndimage.gaussian_filter(z, 1.0), zoom, order=3)
        ys = np.arange(zz.shape[0]) * dy / zoom
        xs = np.arange(zz.shape[1]) * dx / zoom
        gen = contourpy.contour_generator(xs, ys, zz, line_type="Separate")
        parts = []
        for lev in levels:
            for line in gen.lines(lev):
                line = np.asarray(line)
                closed = len(line) > 2 and np.array_equal(line[0], line[-1])
                parts.append((line[:-1] if closed else line, closed))
        return parts

    def points(parts):
        return np.concatenate([p for p, _ in parts]) if parts else np.zeros((0, 2))

    def edges(parts):
        out, first = [], 0
        for p, closed in parts:
            k = len(p)
            i = np.arange(first, first + k - 1, dtype=np.int32)
            e = np.stack([i, i + 1], axis=1)
            if closed and k > 2:
                e = np.concatenate([e, np.array([[first + k - 1, first]], dtype=np.int32)])
            out.append(e)
            first += k
        return np.concatenate(out) if out else np.zeros((0, 2), dtype=np.int32)

    probe = trace(1.0)
    zoom = max(1.0, a.n / max(1, len(points(probe))))
    parts = trace(zoom) if zoom > 1.0 else probe
    pts = points(parts)
    np.save(a.o, np.ascontiguousarray(pts, dtype=np.float64))
    print(f"{len(pts)} contour points ({a.levels} levels, zoom {zoom:.2f}) -> {a.o}")
    if a.segments:
        e = edges(parts)
        np.save(a.segments, np.ascontiguousarray(e, dtype=np.int32))
        print(f"{len(e)} contour edges as segments -> {a.segments}")
    return 0

if __name__ == "__main__":
    sys.exit(main())
