"""The distributed exact distance transform: slabs along axis 0, each computed on its worker from
its own elements and, per column, the nearest zero on either side of it.

Why this is exact. The squared distance is separable: the nearest zero of a voxel is, over the
columns (lines along axis 0), the best of each column's nearest zero along axis 0, whatever the
other axes. So a slab's voxels need, of each column outside the slab, only its last zero before
the slab and its first zero after it: any other zero of that column lies farther along axis 0
from every voxel of the slab than one of these two, so it can neither be nearer nor win a tie
(ties go to the first zero in C order, and of two zeros in a column the nearer one along axis 0
is the one the whole volume's transform keeps too). The library computes a slab from these
(``EdtOptions::slab``), so every slab's outputs are the whole volume's, bit for bit.

What moves between workers is planes of one int32 per column, not the volume: every slab's first
and last zeros are reduced to every slab's bounds by scans along the slabs (the last zero before
each slab, the first after it), in log2(slabs) rounds of tasks that run side by side.
"""
from typing import Optional, Sequence, Union

import dask
import dask.array as da
import numpy as np
from dask import delayed

from .. import _arrays, _core
from ..ndimage import _grid, _sampling

_NONE = np.int32(-1)


def _as_grid(block):
    """A slab the library reads where it is (NumPy, or CuPy on the worker's GPU), in its own
    element type where it can, else zero / non-zero as bool (NaN counts as non-zero, as in
    SciPy): (array, its kind)."""
    arr, kind, _ = _grid(block)
    return arr, kind


def _zero_bounds(block, first: int, threads: int):
    """(first zero, last zero, columns with a zero) per column of a slab, as whole-volume indices
    along axis 0 (-1 where the column has none), int32 NumPy planes (indices below 65536, the
    transform's largest extent: half the bytes to move): one sweep of the slab where it is, on
    the worker's cores or its GPU."""
    g, kind = _as_grid(block)
    lo, hi, count = _core.column_site_bounds(g, zero_sites=True, offset=first, threads=threads,
                                             stream=kind.stream)
    return lo.astype(np.int32), hi.astype(np.int32), count


def _chunk_module(x):
    """NumPy, or CuPy where the Dask array's chunks are CuPy arrays."""
    if type(x._meta).__module__.split(".")[0] == "cupy":
        import cupy
        return cupy
    return np


def _nearest(farther, this):
    """Per column, the nearest zero beyond a slab: its neighbour's bound (that neighbour's last
    zero for the slab after it, its first for the slab before it) where the neighbour has one,
    else the bound from beyond the neighbour."""
    return np.where(this >= 0, this, farther)


def _scan(planes, forward: bool):
    """Every slab's nearest zero per column over it and the slabs before it (forward) or after
    it: a scan of _nearest in log2(k) rounds of tasks that run side by side (Hillis and
    Steele), where a chain along the slabs would hand one plane on k times in a row."""
    cur, step, k = list(planes), 1, len(planes)
    while step < k:
        nxt = list(cur)
        for i in range(k):
            j = i - step if forward else i + step  # the farther part
            if 0 <= j < k:
                nxt[i] = delayed(_nearest, pure=True)(cur[j], cur[i])
        cur, step = nxt, 2 * step
    return cur


def _slab(block, first, extent, before, after, sampling, bits, features, backend, threads):
    """The slab's outputs, where the slab is (a CuPy slab's stay on the GPU)."""
    g, kind = _as_grid(block)
    before, after = before.astype(np.int64), after.astype(np.int64)
    r = _core.distance_transform(
        g, zero_sites=True, sampling=sampling, distance=bits, squared=False,
        features=features, labels=False, backend=backend, stream=kind.stream, threads=threads,
        slab_extent=extent, slab_first=first, slab_before=before, slab_after=after)
    return kind.back(r.get("distances")), kind.back(r.get("indices"))


def distance_transform_edt(input, sampling: Union[float, Sequence[float], None] = None,
                           return_distances: bool = True, return_indices: bool = False, *,
                           float64_distances: bool = True, slabs: Optional[int] = None,
                           backend: str = "auto", threads: int = 0):
    """Exact Euclidean distance transform of a Dask array, as
    ``scipy.ndimage.distance_transform_edt``, slab by slab on the cluster's workers.

    The input is split along axis 0 (its chunks there, or ``slabs`` equal slabs), each slab whole
    along the other axes (the input is rechunked so: it moves once, in its own element type).
    Each slab runs ``gpugeom.ndimage.distance_transform_edt``'s transform on its worker's GPU (or
    CPU) with, per column along axis 0, the nearest zero before and after the slab. The result
    equals the single run's (``gpugeom.ndimage.distance_transform_edt``) element for element,
    indices and ties included.

    Parameters
    ----------
    input : dask.array or array-like, 1 to 8 dimensions
        Distances are to the nearest zero element. A NumPy array becomes one slab per ``slabs``.
    sampling : float or sequence of float, optional
        Spacing along each axis.
    return_distances, return_indices : bool
        As SciPy: the distances (float64, or float32 with ``float64_distances=False``) and the
        nearest zero's coordinates, shape ``(input.ndim,) + input.shape``, int32.
    slabs : int, optional
        Split axis 0 into this many slabs of equal extent (default: the input's chunks there).
    backend : {"auto", "cuda", "cpu"}
        Where each slab runs (on each worker: "auto" takes its GPU).
    threads : int
        Host threads per slab (0: OpenMP's default in the worker; Dask starts its workers with
        ``OMP_NUM_THREADS=1``, so give ``threads=`` or set that variable for the workers: the
        slab's sites are listed and its outputs copied back on them).

    Returns
    -------
    Dask arrays, as SciPy returns NumPy ones: the distances, the indices, or both (a tuple).
    Store them with ``dask.array.to_zarr`` to stay out of core.

    Raises
    ------
    ValueError
        At the call, before any slab is transformed: no zero element, an empty or wrongly shaped
        input, bad ``sampling``.
    """
    if not return_distances and not return_indices:
        raise RuntimeError("at least one of return_distances/return_indices must be True")
    _arrays.check_backend(backend)
    _arrays.check_threads(threads)
    if not isinstance(input, da.Array):
        a = np.asarray(input)
        if a.ndim == 0 or a.size == 0:
            raise ValueError(f"input must have 1 to 8 dimensions and elements, got shape "
                             f"{a.shape}")
        input = da.from_array(a, chunks=a.shape)
    nd = input.ndim
    if not 1 <= nd <= 8:
        raise ValueError(f"input must have 1 to 8 dimensions, got {nd}")
    shape = tuple(int(e) for e in input.shape)
    if any(np.isnan(e) for e in input.shape):
        raise ValueError("input has chunks of unknown size; call input.compute_chunk_sizes() "
                         "first")
    if any(e == 0 for e in shape):
        raise ValueError(f"input is empty (shape {shape})")
    samp = _sampling(sampling, nd)
    if slabs is not None and (int(slabs) != slabs or slabs < 1):
        raise ValueError(f"slabs must be a positive integer, got {slabs!r}")
    # 1D and 2D grids as 3D ones, (n, 1, 1) and (rows, 1, cols): the slab transform takes 3 to 8
    # axes, and a unit axis changes no distance.
    x = input
    if nd == 1:
        x = x[:, None, None]
        samp = (samp + [1.0, 1.0]) if samp else []
    elif nd == 2:
        x = x[:, None, :]
        samp = [samp[0], 1.0, samp[1]] if samp else []
    if slabs is not None:
        x = x.rechunk({0: max(1, -(-shape[0] // int(slabs)))})
    x = x.rechunk({a: -1 for a in range(1, x.ndim)})
    # the library's limits for slices, checked now rather than in the first slab
    if max(x.shape) > 65536:
        raise ValueError(f"input has an extent above 65536 (shape {shape}): the transform by "
                         f"slabs takes extents up to 65536")
    if int(np.prod(x.shape[1:])) >= 2**31 - 1:
        raise ValueError(f"input's elements along the axes after the first number 2^31 - 1 or "
                         f"more (shape {shape}): a slab's slice must hold fewer")
    rows = [int(c) for c in x.chunks[0]]
    starts = np.concatenate([[0], np.cumsum(rows)[:-1]]).astype(int).tolist()
    blocks = list(x.to_delayed().ravel())
    extent = shape[0]

    # Every slab's first and last zero per column, kept on the workers; only the counts come
    # back, to refuse an input without zeros now rather than in a slab.
    bounds = [delayed(_zero_bounds, nout=3, pure=True)(b, s, threads)
              for b, s in zip(blocks, starts)]
    bounds = dask.persist(*bounds)
    if sum(dask.compute(*[b[2] for b in bounds])) == 0:
        raise ValueError("input has no zero element: every distance would be infinite")
    k = len(blocks)
    plane = int(np.prod(x.shape[1:]))
    none = delayed(np.full, pure=True)(plane, _NONE, dtype=np.int32)
    last = _scan([b[1] for b in bounds], forward=True)  # the last zero of slabs 0..i
    first = _scan([b[0] for b in bounds], forward=False)  # the first zero of slabs i..k-1
    before = [none] + last[:-1]
    after = first[1:] + [none]

    bits = (64 if float64_distances else 32) if return_distances else 0
    dist_parts, idx_parts = [], []
    inner = tuple(int(e) for e in x.shape[1:])
    # the outputs' chunks are of the input's kind: CuPy slabs give CuPy results, on their GPU
    xp = _chunk_module(x)
    fdt = np.float64 if float64_distances else np.float32
    for i in range(k):
        d, f = delayed(_slab, nout=2, pure=True)(
            blocks[i], starts[i], extent, before[i], after[i], samp, bits,
            bool(return_indices), backend, threads)
        if return_distances:
            dist_parts.append(da.from_delayed(d, shape=(rows[i],) + inner, dtype=fdt,
                                              meta=xp.empty((0,) * x.ndim, fdt)))
        if return_indices:
            idx_parts.append(da.from_delayed(f, shape=(len(x.shape), rows[i]) + inner,
                                             dtype=np.int32,
                                             meta=xp.empty((0,) * (x.ndim + 1), np.int32)))
    result = []
    if return_distances:
        dist = da.concatenate(dist_parts, axis=0)
        result.append(dist.reshape(shape) if nd < 3 else dist)
    if return_indices:
        idx = da.concatenate(idx_parts, axis=1)
        if nd == 1:
            idx = idx[:1, :, 0, 0]
        elif nd == 2:
            idx = idx[[0, 2], :, 0, :]
        result.append(idx)
    return tuple(result) if len(result) == 2 else result[0]
