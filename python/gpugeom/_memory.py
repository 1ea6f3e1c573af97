"""The caller's allocator (internal): when CuPy arrays or PyTorch tensors come in, the library
takes its device memory from that framework's caching allocator, so that one pool serves the
process: ``torch.cuda.memory_allocated()`` and CuPy's pool count the library's arrays, and
neither cache holds memory the other needs (issue 48).

Each class gives the extension ``allocate(nbytes, stream) -> pointer``,
``deallocate(pointer, nbytes, stream)`` and ``cached_bytes(device)``; the extension calls them
with the call's device current, taking the GIL. ``stream`` is the call's CUDA stream handle:
the framework's current stream, with its default stream passed as the legacy default stream
(handle 1, which is what the framework's handle 0 is).
"""
from __future__ import annotations

_LEGACY = 1  # cudaStreamLegacy


def _framework_stream(stream: int) -> int:
    # The framework knows its default stream as handle 0.
    return 0 if stream == _LEGACY else stream


class TorchAllocator:
    """PyTorch's caching allocator (``torch.cuda.caching_allocator_alloc``): blocks are tied to
    the call's stream, as PyTorch's own are, and freed in order on it."""

    def __init__(self):
        import torch

        self._torch = torch
        # What torch.cuda.caching_allocator_alloc / _delete call, without the device context
        # manager around it: the extension has made the call's device current already, and
        # a call takes tens to hundreds of blocks (bench/python_memory.py).
        self._raw_alloc = getattr(torch._C, "_cuda_cudaCachingAllocator_raw_alloc", None)
        self._raw_delete = getattr(torch._C, "_cuda_cudaCachingAllocator_raw_delete", None)

    def allocate(self, nbytes: int, stream: int) -> int:
        s = _framework_stream(stream)
        if self._raw_alloc is not None:
            return int(self._raw_alloc(nbytes, s))
        return int(self._torch.cuda.caching_allocator_alloc(nbytes, stream=s))

    def deallocate(self, ptr: int, nbytes: int, stream: int) -> None:
        if self._raw_delete is not None:
            self._raw_delete(ptr)
        else:
            self._torch.cuda.caching_allocator_delete(ptr)

    def cached_bytes(self, device: int) -> int:
        # The allocator's statistics as it keeps them (10 us on the H200), not through
        # torch.cuda.memory_reserved, which flattens every statistic first (150 us).
        stats = getattr(self._torch._C, "_cuda_memoryStats", None)
        if stats is not None:
            s = stats(device)
            return int(s["reserved_bytes"]["all"]["current"] - s["allocated_bytes"]["all"]["current"])
        cuda = self._torch.cuda
        return int(cuda.memory_reserved(device) - cuda.memory_allocated(device))


class CupyAllocator:
    """CuPy's current allocator (``cupy.cuda.alloc``: the default memory pool unless the program
    set another), on CuPy's current stream, which is the call's."""

    def __init__(self):
        import cupy

        self._cupy = cupy
        self._held = {}  # pointer -> MemoryPointer: the block lives while the library holds it

    def allocate(self, nbytes: int, stream: int) -> int:
        mem = self._cupy.cuda.alloc(nbytes)
        self._held[mem.ptr] = mem
        return int(mem.ptr)

    def deallocate(self, ptr: int, nbytes: int, stream: int) -> None:
        self._held.pop(ptr, None)

    def cached_bytes(self, device: int) -> int:
        pool = self._cupy.get_default_memory_pool()
        if self._cupy.cuda.get_allocator() != pool.malloc:
            return 0  # a program's own allocator: its cache is unknown
        with self._cupy.cuda.Device(device):
            return int(pool.free_bytes())


_allocators = {}


def allocator(name: str):
    """The allocator of framework ``name`` ("torch" or "cupy"), made once per process."""
    a = _allocators.get(name)
    if a is None:
        a = TorchAllocator() if name == "torch" else CupyAllocator()
        _allocators[name] = a
    return a


def call_stream(name: str, stream: int):
    """What the extension's ``stream`` argument takes for a call on framework ``name``'s
    current stream ``stream``: the stream (its default stream as the legacy one) and the
    framework's allocator."""
    return (stream if stream else _LEGACY, allocator(name))
