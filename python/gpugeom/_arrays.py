"""Arrays in and out (internal): the caller's NumPy, CuPy or PyTorch arrays as the extension
reads them, and results handed back as the same kind of array without a copy.

Host arrays (NumPy, array-likes, CPU tensors) go through the library's host path; CUDA arrays
(CuPy, PyTorch, or any object with ``__dlpack__`` / ``__cuda_array_interface__``) through its
device entry points, on the caller's current stream, and the results stay on the GPU.
"""
from __future__ import annotations

import numbers
from dataclasses import dataclass
from typing import Any, Callable, Optional

import numpy as np

from . import _core
from ._memory import call_stream

_BACKENDS = ("auto", "cuda", "cpu")
_KDL_CUDA = 2


@dataclass
class Kind:
    """Where an input lives and how results go back to the caller."""

    name: str  # "numpy", "torch-cpu", "cupy", "torch", "dlpack"
    device: bool
    # The extension's stream argument: a CUDA stream handle (0: the per-thread default stream),
    # or (handle, allocator) where the framework's allocator serves the call (_memory.py).
    stream: Any = 0
    torch_device: Any = None

    def back(self, a):
        """A result of the extension as the caller's kind of array (no copy)."""
        if a is None:
            return None
        if self.name == "cupy":
            import cupy

            return cupy.from_dlpack(a)
        if self.name == "torch":
            import torch

            return torch.from_dlpack(a)
        if self.name == "torch-cpu":
            import torch

            return torch.from_numpy(np.asarray(a))
        if self.name == "dlpack":
            try:
                import cupy

                return cupy.from_dlpack(a)
            except ImportError:
                return a
        return a

    def xp(self):
        """The array module for arithmetic on results of this kind: NumPy on the host, CuPy on
        the GPU (PyTorch tensors are viewed as CuPy arrays without a copy; without CuPy, GPU
        tensors are worked on through the host)."""
        if self.device:
            try:
                import cupy

                return cupy
            except ImportError:
                return np
        return np

    def to_xp(self, a):
        """A result of this kind as an array of xp() (no copy where both share memory)."""
        xp = self.xp()
        if self.name in ("torch", "torch-cpu"):
            if xp is np:
                return a.detach().cpu().numpy()
            return xp.from_dlpack(a)
        return a

    def from_xp(self, a):
        """An xp() array back as this kind."""
        if self.name == "torch-cpu":
            import torch

            return torch.from_numpy(np.asarray(a))
        if self.name == "torch":
            import torch

            if isinstance(a, np.ndarray):
                return torch.from_numpy(a).to(self.torch_device)
            return torch.from_dlpack(a)
        return a


def check_threads(threads) -> int:
    if not is_integer(threads) or threads < 0:
        raise ValueError(f"threads must be an integer >= 0 (0: all host threads), got {threads!r}")
    return int(threads)


def check_backend(backend: str) -> str:
    if not isinstance(backend, str) or backend.lower() not in _BACKENDS:
        raise ValueError(f"backend must be one of {_BACKENDS}, got {backend!r}")
    return backend.lower()


def _module_of(a) -> str:
    return type(a).__module__.split(".")[0]


def classify(a) -> Kind:
    mod = _module_of(a)
    if mod == "cupy":
        import cupy

        return Kind("cupy", True, call_stream("cupy", int(cupy.cuda.get_current_stream().ptr)))
    if mod == "torch":
        import torch

        if isinstance(a, torch.Tensor) and a.is_cuda:
            stream = int(torch.cuda.current_stream(a.device).cuda_stream)
            return Kind("torch", True, call_stream("torch", stream), a.device)
        if isinstance(a, torch.Tensor) and a.device.type == "cpu":
            return Kind("torch-cpu", False)
        raise TypeError(f"a torch tensor on {a.device} cannot be read: give a CPU or CUDA tensor")
    if not isinstance(a, np.ndarray):
        if hasattr(a, "__dlpack_device__") and a.__dlpack_device__()[0] == _KDL_CUDA:
            return Kind("dlpack", True)
        if hasattr(a, "__cuda_array_interface__"):
            return Kind("dlpack", True)
    return Kind("numpy", False)


def as_input(a, dtype, name: str, kind: Optional[Kind] = None):
    """(array the extension reads, Kind): C-contiguous, of `dtype` (None: keep the dtype),
    where it is."""
    kind = kind or classify(a)
    if kind.name == "cupy":
        import cupy

        return cupy.ascontiguousarray(a, dtype=dtype), kind
    if kind.name in ("torch", "torch-cpu"):
        import torch

        t = a
        if dtype is not None:
            t = t.to(dtype=getattr(torch, np.dtype(dtype).name))
        t = t.contiguous()
        if kind.name == "torch-cpu":
            return t.numpy(), kind
        return t, kind
    if kind.name == "dlpack":
        try:
            import cupy
        except ImportError:
            return a, kind
        return cupy.ascontiguousarray(cupy.asarray(a), dtype=dtype), kind
    if isinstance(a, (str, bytes)):
        raise TypeError(f"{name} must be numeric, got {type(a).__name__}")
    if hasattr(a, "dtype") and np.dtype(a.dtype).kind in "OSUV":
        raise TypeError(f"{name} must hold real numbers, not {np.dtype(a.dtype)}")
    try:
        arr = np.asarray(a)
    except (TypeError, ValueError) as e:
        raise TypeError(f"{name} must be an array of numbers: {e}") from None
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"{name} must hold real numbers, not {arr.dtype}")
    return np.ascontiguousarray(arr, dtype=dtype), kind


class ShapeError(ValueError, IndexError):
    """A query array of the wrong shape: a ValueError as gpugeom raises them, and an IndexError as
    SciPy's ``find_simplex`` raises it."""


def points_input(points, dims, backend: str, threads: int = 0):
    """Validated point coordinates: float64 (n, d) with d in dims."""
    check_backend(backend)
    check_threads(threads)
    if getattr(points, "ndim", 2) != 2:  # (before a 0-d array becomes 1-d below)
        want = " or ".join(f"(n, {d})" for d in dims)
        raise ValueError(f"points must have shape {want} (2 dimensions), got "
                         f"{tuple(points.shape)} ({points.ndim} dimensions)")
    arr, kind = as_input(points, np.float64, "points")
    shape = tuple(arr.shape)
    if len(shape) != 2 or shape[1] not in dims:
        want = " or ".join(f"(n, {d})" for d in dims)
        raise ValueError(f"points must have shape {want}, got {shape}")
    return arr, kind


def like(kind: Kind, ref, a):
    """Array `a` (as as_input returns it) moved to where `ref`, an array of `kind` as
    as_input returned it, lives: the host, or ref's GPU."""
    if not kind.device:
        return np.ascontiguousarray(to_host(a), dtype=np.float64)
    if kind.name == "torch":
        import torch

        if isinstance(a, torch.Tensor):
            return a.to(device=ref.device, dtype=torch.float64).contiguous()
        return torch.as_tensor(np.asarray(to_host(a)), dtype=torch.float64, device=ref.device)
    import cupy

    with cupy.cuda.Device(ref.device.id):
        return cupy.ascontiguousarray(cupy.asarray(a), dtype=cupy.float64)


def concatenate(kind: Kind, a, b):
    """Rows of b after those of a, both arrays of `kind` as as_input returns them."""
    if kind.name == "torch":
        import torch

        return torch.cat([a, b]).contiguous()
    if kind.device:
        import cupy

        return cupy.concatenate([a, b])
    return np.concatenate([a, b])


def to_host(a) -> np.ndarray:
    """A NumPy copy of any array (device arrays are copied over the bus)."""
    mod = _module_of(a)
    if mod == "cupy":
        import cupy

        return cupy.asnumpy(a)
    if mod == "torch":
        return a.detach().cpu().numpy()
    return np.asarray(a)


def is_integer(x) -> bool:
    return isinstance(x, numbers.Integral) and not isinstance(x, bool)


def device_list(devices, kind: Kind, why: str):
    """A devices= argument as the library takes it: None (one device), [] ("all": every one)
    or a list of device ordinals. `why`: why host arrays are needed, for the error."""
    if devices is None:
        return None
    if kind.device:
        raise ValueError(f"devices= takes host (NumPy) arrays: {why}")
    if isinstance(devices, str):
        if devices != "all":
            raise ValueError(f"devices must be a list of device ordinals or 'all', got "
                             f"{devices!r}")
        return []
    out = [int(d) for d in devices]
    if not out:
        raise ValueError("devices is empty: name at least one device, or 'all'")
    if any(d < 0 for d in out):
        raise ValueError(f"device ordinals are 0 or more, got {out}")
    return out


def progress_callback(progress) -> Optional[Callable]:
    """A progress argument as the extension calls it: a callable, or a tqdm-like bar (anything
    with update()), which advances by one per step."""
    if progress is None:
        return None
    if hasattr(progress, "update") and callable(progress.update):
        bar = progress

        def advance(*info):
            bar.update(1)
            return None

        return advance
    if not callable(progress):
        raise TypeError("progress must be a callable or a tqdm-like progress bar")
    return progress


def device_info(device: int = -1) -> dict:
    """The CUDA device the library would use (-1: the current one): name, compute capability,
    memory, whether it can run this build's kernels (and why not), and the architectures built."""
    return _core.device_info(device)
