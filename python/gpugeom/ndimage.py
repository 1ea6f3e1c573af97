"""Exact Euclidean distance and feature transforms (``scipy.ndimage.distance_transform_edt``)
and digital Voronoi labels of grids of 1 to 8 dimensions (1D grids are taken as one row).

Ties between equally near sites go to the site first in C order, so results are deterministic
and the same on the CPU and the GPU. CuPy / PyTorch CUDA arrays stay on the GPU.
"""
from __future__ import annotations

import numbers
from typing import Optional, Sequence, Union

import numpy as np

from . import _arrays, _core

__all__ = ["distance_transform_edt", "voronoi_labels"]

# Element types the library reads as they are (anything else becomes bool first).
_DIRECT = {np.dtype(t) for t in (np.bool_, np.uint8, np.uint16, np.int32, np.int64)}


def _grid(input, name="input"):
    kind = _arrays.classify(input)
    arr, kind = _arrays.as_input(input, None, name, kind)
    dt = np.dtype(str(arr.dtype).replace("torch.", ""))
    if dt not in _DIRECT:
        # Floats and other integers: only zero / non-zero matters (NaN counts as non-zero, as in
        # SciPy); one byte per element also crosses the bus faster.
        arr = arr != 0
    nd = arr.ndim
    if not 1 <= nd <= 8:
        raise ValueError(f"{name} must have 1 to 8 dimensions, got {nd}")
    if any(int(e) == 0 for e in arr.shape):
        raise ValueError(f"{name} is empty (shape {tuple(arr.shape)})")
    return arr, kind, nd


def _sampling(sampling, nd) -> list:
    if sampling is None:
        return []
    if isinstance(sampling, numbers.Real):
        s = [float(sampling)] * nd
    else:
        s = [float(v) for v in sampling]
        if len(s) != nd:
            raise RuntimeError("sequence argument must have length equal to input rank")
    for v in s:
        if not (np.isfinite(v) and v > 0):
            raise ValueError(f"sampling must be finite and positive, got {sampling!r}")
    return s


def _slices(slices, shape):
    """The indices along axis 0 asked for (None: the whole array), negative ones counted from
    the end."""
    if slices is None:
        return None
    if len(shape) < 3:
        raise ValueError(f"slices apply to input of 3 or more dimensions, got {len(shape)}")
    zs = [int(z) for z in np.asarray(slices, dtype=np.int64).reshape(-1)]
    if not zs:
        raise ValueError("slices is empty: give at least one index along axis 0")
    out = []
    for z in zs:
        if not -shape[0] <= z < shape[0]:
            raise IndexError(f"slice {z} is out of bounds for axis 0 with size {shape[0]}")
        out.append(z + shape[0] if z < 0 else z)
    return out


def _c_contiguous(a) -> bool:
    if hasattr(a, "is_contiguous"):  # torch
        return bool(a.is_contiguous())
    return bool(a.flags.c_contiguous)


def _as_2d(arr, nd):
    """1D grids run as one row."""
    return arr.reshape(1, -1) if nd == 1 else arr


def distance_transform_edt(input, sampling: Union[float, Sequence[float], None] = None,
                           return_distances: bool = True, return_indices: bool = False,
                           distances=None, indices=None, *, float64_distances: bool = True,
                           slices: Optional[Sequence[int]] = None,
                           devices: Union[None, str, Sequence[int]] = None, backend: str = "auto",
                           threads: int = 0):
    """Exact Euclidean distance transform, as ``scipy.ndimage.distance_transform_edt``.

    For every non-zero element of ``input``, the distance to the nearest zero element (zeros get
    0), with ``sampling`` the spacing along each axis. ``return_indices`` gives the nearest
    zero's coordinates, shape ``(input.ndim,) + input.shape``, int32. ``distances`` / ``indices``
    are output arrays to write into instead (same kind and memory as ``input``; float64, or
    float32 distances, and int32 indices); as in SciPy, the outputs written there are not
    returned. ``float64_distances=False`` returns float32 distances (as CuPy's option).

    ``slices`` (input of 3 or more dimensions; not in SciPy): compute only these indices along
    axis 0, each exactly as the whole array would have it; the outputs' first axis is then
    ``len(slices)``. The device then holds the list of the zero elements and a few slices at a
    time, never the volume's outputs, so a volume of any size that fits the host (more than
    2**32 elements too) can be taken slice by slice.

    ``devices`` (host arrays; not in SciPy): several GPUs of this host, a list of CUDA device
    ordinals or ``"all"``: the array is split along axis 0 into one slab per device, every slab
    transformed at once on its device, straight into its place in the outputs; the same result.
    (With ``backend="cpu"`` each entry is a slab on the CPU.)

    Raises ValueError when ``input`` has no zero element (no nearest zero exists).
    """
    if not return_distances and not return_indices:
        raise RuntimeError("at least one of return_distances/return_indices must be True")
    if distances is not None and not return_distances:
        raise RuntimeError("distances given but return_distances is False")
    if indices is not None and not return_indices:
        raise RuntimeError("indices given but return_indices is False")
    _arrays.check_backend(backend)
    _arrays.check_threads(threads)
    arr, kind, nd = _grid(input)
    shape = tuple(int(e) for e in arr.shape)
    zs = _slices(slices, shape)
    if zs is not None:  # the outputs' shape
        shape = (len(zs),) + shape[1:]
    samp = _sampling(sampling, nd)
    bits = 0
    if return_distances:
        bits = 64 if float64_distances else 32
        if distances is not None:
            dd = np.dtype(str(distances.dtype).replace("torch.", ""))
            if dd not in (np.dtype(np.float64), np.dtype(np.float32)):
                raise RuntimeError("distances array must be float64 or float32")
            if tuple(distances.shape) != shape:
                raise RuntimeError(f"distances array has shape {tuple(distances.shape)}, "
                                   f"needs {shape}")
            bits = 64 if dd == np.dtype(np.float64) else 32
    if indices is not None:
        if tuple(indices.shape) != (nd,) + shape:
            raise RuntimeError(f"indices array has shape {tuple(indices.shape)}, needs "
                               f"{(nd,) + shape}")
        if np.dtype(str(indices.dtype).replace("torch.", "")) != np.dtype(np.int32):
            raise RuntimeError("indices array must be int32")
    g = _as_2d(arr, nd)
    samp2 = ([1.0] + samp) if (nd == 1 and samp) else samp
    # Output arrays the library can write into directly: C order (a 1D grid's indices come from
    # its (2, 1, n) result instead); others get the result copied in.
    d_direct = distances is not None and _c_contiguous(distances)
    f_direct = indices is not None and nd > 1 and _c_contiguous(indices)
    if devices is not None and zs is not None:
        raise ValueError("devices= and slices= cannot be combined (the devices split axis 0)")
    devs = _arrays.device_list(devices, kind, "each device copies in its slab")
    if devs is not None and nd < 3:  # slabs take 3 axes or more: (n, 1, 1) and (rows, 1, cols)
        g = arr.reshape((shape[0], 1, 1) if nd == 1 else (shape[0], 1, shape[1]))
        samp2 = ([samp[0], 1.0, 1.0] if nd == 1 else [samp[0], 1.0, samp[1]]) if samp else []
        f_direct = False
    r = _core.distance_transform(
        g, zero_sites=True, sampling=samp2, distance=bits, squared=False,
        features=bool(return_indices), labels=False,
        distances_out=distances.reshape(shape if zs is not None else g.shape) if d_direct
        else None,
        features_out=indices if f_direct else None, backend=backend, stream=kind.stream,
        threads=threads, slices=zs if zs is not None else [], devices=devs)
    result = []
    if return_distances:
        if distances is None:
            result.append(kind.back(r["distances"]).reshape(shape))
        elif not d_direct:
            distances[...] = kind.back(r["distances"]).reshape(shape)
    if return_indices:
        ft = kind.back(r["indices"]) if not f_direct else None
        if ft is not None and devs is not None and nd < 3:  # from (n, 1, 1) or (rows, 1, cols)
            ft = ft[[0] if nd == 1 else [0, 2]].reshape((nd,) + shape)
        elif ft is not None and nd == 1:
            ft = ft[1].reshape((1,) + shape)
        if indices is None:
            result.append(ft)
        elif not f_direct:
            indices[...] = ft
    if len(result) == 2:
        return tuple(result)
    if len(result) == 1:
        return result[0]
    return None


def voronoi_labels(input, sampling: Union[float, Sequence[float], None] = None, *,
                   return_distances: bool = False, return_sites: bool = False,
                   backend: str = "auto", threads: int = 0):
    """The digital Voronoi diagram of the non-zero elements of ``input``: every element gets the
    value of the nearest non-zero element (ties to the first in C order), so a label image grows
    each label over the region nearest to it (like ``skimage.segmentation.expand_labels``
    without a distance limit).

    Returns the labels (``input``'s dtype and shape); with ``return_distances`` also the float64
    distance to that element; with ``return_sites`` also its flat (C-order) index, int64.
    Raises ValueError when ``input`` has no non-zero element.
    """
    _arrays.check_backend(backend)
    _arrays.check_threads(threads)
    kind = _arrays.classify(input)
    values, kind = _arrays.as_input(input, None, "input", kind)
    arr, _, nd = _grid(values)
    shape = tuple(int(e) for e in arr.shape)
    g = _as_2d(arr, nd)
    samp = _sampling(sampling, nd)
    samp2 = ([1.0] + samp) if (nd == 1 and samp) else samp
    r = _core.distance_transform(g, zero_sites=False, sampling=samp2,
                                 distance=64 if return_distances else 0, squared=False,
                                 features=False, labels=True, backend=backend,
                                 stream=kind.stream, threads=threads)
    xp = kind.xp()
    rank = kind.to_xp(kind.back(r["labels"])).reshape(shape)
    flat_values = kind.to_xp(values).reshape(-1)
    sites = xp.flatnonzero(flat_values != 0)
    site_index = sites[rank]
    out = [kind.from_xp(flat_values[site_index])]
    if return_distances:
        out.append(kind.back(r["distances"]).reshape(shape))
    if return_sites:
        out.append(kind.from_xp(site_index.astype(xp.int64)))
    return out[0] if len(out) == 1 else tuple(out)
