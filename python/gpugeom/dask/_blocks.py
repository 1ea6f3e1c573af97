"""The block decomposition of the distributed triangulation: a grid of cells over the points'
bounding box, each point owned by the cell it falls in, and the regions a block covers.

NumPy and the library's block passes: nothing here knows about Dask, so the rules can be tested
alone.
"""
import numpy as np

from .. import _core


def _prime_factors(n: int) -> list:
    out, p = [], 2
    while p * p <= n:
        while n % p == 0:
            out.append(p)
            n //= p
        p += 1
    if n > 1:
        out.append(n)
    return out


def choose_counts(extent, nblocks: int) -> tuple:
    """Cells per axis, their product ``nblocks``: each prime factor, largest first, splits the
    axis whose cells are then the longest (ties: the lower axis), so cells stay close to cubes.
    A flat axis (extent 0) is never split while another is not."""
    extent = np.asarray(extent, dtype=np.float64)
    counts = [1] * len(extent)
    for f in sorted(_prime_factors(int(nblocks)), reverse=True):
        k = int(np.argmax(extent / np.asarray(counts, dtype=np.float64)))
        counts[k] *= f
    return tuple(counts)


class Grid:
    """``counts[0] x ... x counts[d-1]`` cells over the closed box ``[lo, hi]`` of all points.

    A point belongs to the cell ``floor((x - lo) / width)`` (clamped), computed once per point in
    one place (``split``). Where floating point puts a point just outside its cell's box nothing
    breaks: a block always holds its own points, and the regions below only decide which *other*
    points a block takes, by exact comparisons of the coordinates.
    """

    def __init__(self, lo, hi, counts):
        self.lo = np.asarray(lo, dtype=np.float64)
        self.hi = np.asarray(hi, dtype=np.float64)
        self.counts = np.asarray(counts, dtype=np.int64)
        self.width = (self.hi - self.lo) / self.counts
        self.ndim = len(self.lo)

    @property
    def nblocks(self) -> int:
        return int(np.prod(self.counts))

    def split(self, pts: np.ndarray, boxes=None, threads: int = 0, gather: bool = False,
              frontiers=None):
        """The owning block of each point (row-major cell index: floor((x - lo) / width) per
        axis, clamped), and each block's points: those of its cell and, where ``boxes`` (a dict:
        block -> list of closed boxes (lo, hi)) is given, those in its boxes, each point once,
        in increasing order; only the blocks in ``boxes`` then; with ``frontiers`` (an
        ``_core.empty_frontiers`` dict) also those in its bins. One pass in C++
        (``_core.split_to_blocks``; the box tests are comparisons of the doubles). Returns
        (cell, order, cuts): block b's points are order[cuts[b]:cuts[b + 1]]; with ``gather``
        also the points and cells in that order (gathered in C++ on ``threads``)."""
        pts = np.ascontiguousarray(pts, dtype=np.float64)
        args = {}
        if boxes is not None:
            d = self.ndim
            if any(not 0 <= b < self.nblocks for b in boxes):
                raise ValueError(f"blocks {sorted(boxes)} outside a grid of {self.nblocks}")
            listed = [(b, lo, hi) for b in sorted(boxes) for lo, hi in boxes[b]]
            wanted = np.zeros(self.nblocks, dtype=bool)
            wanted[list(boxes)] = True
            args = dict(box_lo=np.array([x[1] for x in listed], np.float64).reshape(-1, d),
                        box_hi=np.array([x[2] for x in listed], np.float64).reshape(-1, d),
                        box_block=np.array([x[0] for x in listed], np.int64), wanted=wanted)
        r = _core.split_to_blocks(pts, self.lo.tolist(), self.width.tolist(),
                                  self.counts.tolist(), threads=threads, gather=gather,
                                  frontiers=frontiers, **args)
        if gather:
            return r["cell"], r["order"], r["cuts"], r["points"], r["cells"]
        return r["cell"], r["order"], r["cuts"]

    def cell_of(self, pts: np.ndarray) -> np.ndarray:
        """The owning block of each point (row-major cell index)."""
        return self.split(pts)[0]

    def cell_box(self, b: int):
        """The box of cell ``b`` (the last cell along an axis ends exactly at ``hi``)."""
        ijk = np.array(np.unravel_index(int(b), tuple(self.counts)), dtype=np.int64)
        lo = self.lo + ijk * self.width
        hi = np.where(ijk + 1 == self.counts, self.hi, self.lo + (ijk + 1) * self.width)
        return lo, hi

    def region(self, b: int, ghost: float):
        """The closed box a block with ghost width ``ghost`` covers: every point in it is one of
        the block's local points."""
        lo, hi = self.cell_box(b)
        return lo - ghost, hi + ghost

    def covers_all(self, b: int, ghost: float) -> bool:
        lo, hi = self.region(b, ghost)
        return bool(np.all(lo <= self.lo) and np.all(hi >= self.hi))
