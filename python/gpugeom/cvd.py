"""Weighted centroidal Voronoi diagrams of 2D / 3D densities (Lloyd's iteration on the digital
Voronoi diagram, exact integer decisions: the energy never increases and the iteration always
ends) and stipple drawings of images."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, NamedTuple, Optional

import numpy as np

from . import _arrays, _core

__all__ = ["centroidal_voronoi", "stipple", "CentroidalVoronoi", "Stipple", "Progress"]


class Progress(NamedTuple):
    """What a progress callback receives after each Lloyd iteration."""

    iteration: int  # 1-based
    energy: float  # of this iteration's diagram, before the sites moved
    max_move: float  # largest site move, in pixels
    moved: int  # sites that moved


@dataclass
class CentroidalVoronoi:
    """Sites (x = column, y = row[, z = slice], pixel centres at integers), each site's mass
    (density summed over its cell), the energy of every iteration."""

    sites: Any
    mass: Any
    energy: np.ndarray
    iterations: int
    converged: bool
    stats: dict = field(repr=False)


@dataclass
class Stipple(CentroidalVoronoi):
    """A stipple drawing: dots at the sites, ``radius`` each (image pixels)."""

    radius: Any = None
    shape: tuple = ()

    def plot(self, ax=None, color="black", **kwargs):
        """Draws the dots with matplotlib (image orientation: row 0 at the top)."""
        import matplotlib.pyplot as plt
        from matplotlib.collections import EllipseCollection

        ax = ax or plt.gca()
        s = np.asarray(self.sites)
        d = 2 * np.asarray(self.radius)
        ax.add_collection(EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=s,
                                            offset_transform=ax.transData, color=color,
                                            **kwargs))
        rows, cols = self.shape
        ax.set_xlim(-0.5, cols - 0.5)
        ax.set_ylim(rows - 0.5, -0.5)
        ax.set_aspect("equal")
        return ax


def _lloyd_callback(progress):
    cb = _arrays.progress_callback(progress)
    if cb is None:
        return None
    if cb is not progress:  # a progress bar
        return cb

    def call(iteration, energy, max_move, moved):
        r = progress(Progress(iteration, energy, max_move, moved))
        return None if r is None else bool(r)

    return call


def centroidal_voronoi(density, n_sites: int = 1000, *, initial_sites=None,
                       max_iterations: int = 200, tol: float = 0.1, energy_tol: float = 0.0,
                       supersample: int = 1, seed: int = 1,
                       progress: Optional[Callable] = None, backend: str = "auto",
                       threads: int = 0) -> CentroidalVoronoi:
    """Weighted centroidal Voronoi diagram of a 2D or 3D density (non-negative, finite, not all
    zero; any real dtype; NumPy, CuPy or PyTorch).

    ``n_sites`` sites are drawn with probability proportional to the density (``seed``), or
    ``initial_sites`` (n, ndim) are given. The iteration stops when no site moves farther than
    ``tol`` pixels, the energy falls by less than ``energy_tol`` (a fraction), or after
    ``max_iterations``. ``progress`` is called with a :class:`Progress` after each iteration
    (return False to stop), or is a tqdm bar (advanced by one per iteration).
    """
    _arrays.check_backend(backend)
    _arrays.check_threads(threads)
    if not _arrays.is_integer(n_sites) or n_sites < 1:
        raise ValueError(f"n_sites must be a positive integer, got {n_sites!r}")
    kind = _arrays.classify(density)
    arr, kind = _arrays.as_input(density, None, "density", kind)
    if str(arr.dtype).replace("torch.", "") not in ("uint8", "uint16", "int32", "int64",
                                                    "float32", "float64", "bool"):
        arr, kind = _arrays.as_input(density, np.float64, "density", kind)
    init = None
    if initial_sites is not None:
        init = np.ascontiguousarray(_arrays.to_host(initial_sites), dtype=np.float64)
        if init.ndim != 2 or init.shape[1] != arr.ndim:
            raise ValueError(f"initial_sites must have shape (n, {arr.ndim})")
    r = _core.centroidal_voronoi(arr, num_sites=int(n_sites), initial_sites=init,
                                 max_iterations=int(max_iterations), move_tolerance=float(tol),
                                 energy_tolerance=float(energy_tol), supersample=int(supersample),
                                 seed=int(seed), progress=_lloyd_callback(progress),
                                 backend=backend, stream=kind.stream, threads=threads)
    return CentroidalVoronoi(kind.back(r["sites"]), kind.back(r["mass"]), np.asarray(r["energy"]),
                             int(r["iterations"]), bool(r["converged"]), r["stats"])


def stipple(image, n: int = 20000, *, invert: bool = False, contrast: float = 1.0,
            gamma: float = 1.0, ink: float = 0.6, max_iterations: int = 200, tol: float = 0.1,
            energy_tol: float = 0.0, supersample: int = 1, seed: int = 1,
            progress: Optional[Callable] = None, backend: str = "auto",
            threads: int = 0) -> Stipple:
    """A stipple drawing of a 2D image (grey levels; uint8 / uint16 by their range, floats in
    [0, 1]): ``n`` dots at the sites of the centroidal Voronoi diagram of the image's darkness,
    each dot's area ``ink`` times the darkness of its cell. ``plot()`` draws it. Options as
    :func:`centroidal_voronoi`; ``invert`` puts dots where the image is bright, ``contrast``
    stretches darkness about mid-grey, ``gamma`` raises it to that power."""
    _arrays.check_backend(backend)
    _arrays.check_threads(threads)
    if not _arrays.is_integer(n) or n < 1:
        raise ValueError(f"n must be a positive integer, got {n!r}")
    img = np.ascontiguousarray(_arrays.to_host(image))
    if img.ndim == 3 and img.shape[2] in (3, 4):  # RGB(A): luminance
        img = img[..., 0] * 0.299 + img[..., 1] * 0.587 + img[..., 2] * 0.114
        img = img / (255.0 if np.asarray(image).dtype == np.uint8 else 1.0)
    if img.ndim != 2:
        raise ValueError(f"stipple takes a 2D (grey) or RGB image, got shape {img.shape}")
    if img.dtype.kind not in "biuf":
        raise TypeError(f"image must hold numbers, not {img.dtype}")
    if img.dtype.name not in ("bool", "uint8", "uint16", "int32", "int64", "float32", "float64"):
        img = img.astype(np.float64)
    r = _core.stipple(np.ascontiguousarray(img), num_sites=int(n), invert=bool(invert),
                      contrast=float(contrast), gamma=float(gamma), ink=float(ink),
                      max_iterations=int(max_iterations), move_tolerance=float(tol),
                      energy_tolerance=float(energy_tol), supersample=int(supersample),
                      seed=int(seed), progress=_lloyd_callback(progress), backend=backend,
                      threads=threads)
    return Stipple(r["sites"], r["mass"], np.asarray(r["energy"]), int(r["iterations"]),
                   bool(r["converged"]), r["stats"], r["radius"], tuple(img.shape))
