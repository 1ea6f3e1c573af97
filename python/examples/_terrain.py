"""The terrain both terrain examples draw: contour lines of matplotlib's sample elevation model
(the Jacksboro fault, 3 arc-second samples) in metres."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.cbook as cbook
import matplotlib.pyplot as plt
import numpy as np


def contour_lines(levels):
    """[(points (k, 2) in metres, elevation)] per traced contour line, as matplotlib traces them
    (a closed line repeats its first point at the end)."""
    dem = cbook.get_sample_data("jacksboro_fault_dem.npz")
    z = dem["elevation"].astype(np.float64)
    # The grid is in degrees (3 arc-seconds); metres at the tile's latitude.
    lat = np.radians(0.5 * (float(dem["ymin"]) + float(dem["ymax"])))
    dy = float(dem["dy"]) * 111320.0
    dx = float(dem["dx"]) * 111320.0 * np.cos(lat)
    xs, ys = np.arange(z.shape[1]) * dx, np.arange(z.shape[0]) * dy
    cs = plt.figure().add_subplot().contour(xs, ys, z, levels=levels)
    lines = [(np.asarray(s), lev) for lev, segs in zip(cs.levels, cs.allsegs) for s in segs]
    plt.close("all")
    return lines
