"""One allocator for the process (issue 48): with CuPy arrays or PyTorch tensors in, the library
takes its GPU memory from that framework's caching allocator, so the framework counts it, and
the results are the same as with the library's own pool. Skipped without a usable GPU and the
array library."""
import numpy as np
import pytest

import gpugeom
from gpugeom import _memory

if not (gpugeom.built_with_cuda() and gpugeom.device_info()["available"]):
    pytest.skip("no usable CUDA device", allow_module_level=True)


class Recording:
    """A framework allocator with every call counted, to see that the library used it."""

    def __init__(self, inner):
        self.inner = inner
        self.live = {}
        self.allocs = 0
        self.streams = set()

    def allocate(self, nbytes, stream):
        p = self.inner.allocate(nbytes, stream)
        self.live[p] = nbytes
        self.allocs += 1
        self.streams.add(stream)
        return p

    def deallocate(self, ptr, nbytes, stream):
        assert self.live.pop(ptr) == nbytes
        self.inner.deallocate(ptr, nbytes, stream)

    def cached_bytes(self, device):
        return self.inner.cached_bytes(device)


@pytest.fixture
def recording(monkeypatch):
    """The framework allocators wrapped in Recording, per framework name."""
    made = {}

    def allocator(name):
        if name not in made:
            made[name] = Recording(_memory.TorchAllocator() if name == "torch" else _memory.CupyAllocator())
        return made[name]

    monkeypatch.setattr(_memory, "allocator", allocator)
    return made


def with_library_pool(f):
    """f() with the framework's allocator not lent: the library's own pool serves the call."""
    saved = gpugeom._arrays.call_stream
    gpugeom._arrays.call_stream = lambda name, stream: stream
    try:
        return f()
    finally:
        gpugeom._arrays.call_stream = saved


def test_torch_counts_the_librarys_memory(rng, recording):
    torch = pytest.importorskip("torch")
    p = rng.random((200000, 3))
    t = torch.from_numpy(p).cuda()
    torch.cuda.synchronize()
    before = torch.cuda.memory_allocated()
    torch.cuda.reset_peak_memory_stats()
    d = gpugeom.Delaunay(t)
    assert d.simplices.is_cuda
    rec = recording["torch"]
    assert rec.allocs > 10 and rec.live, "the library did not allocate through PyTorch"
    # The result's arrays are PyTorch's blocks, counted by memory_allocated while they live.
    held = torch.cuda.memory_allocated() - before
    assert held >= d.simplices.numel() * 4 + d.neighbors.numel() * 4
    assert held >= sum(rec.live.values())
    # All the work's temporaries went through PyTorch too: its peak covers ours.
    assert torch.cuda.max_memory_allocated() - before >= 40 * p.shape[0]
    # The same arrays as from the library's own pool.
    h = with_library_pool(lambda: gpugeom.Delaunay(t))
    assert torch.equal(d.simplices, h.simplices) and torch.equal(d.neighbors, h.neighbors)
    del h
    del d
    torch.cuda.synchronize()
    assert not rec.live, "blocks still held after the result was dropped"
    assert torch.cuda.memory_allocated() == before


def test_torch_on_a_side_stream(rng, recording):
    torch = pytest.importorskip("torch")
    a = rng.random((128, 96, 80)) > 0.02
    want_d, want_i = gpugeom.distance_transform_edt(a, return_indices=True, backend="cpu")
    s = torch.cuda.Stream()
    with torch.cuda.stream(s):
        ta = torch.from_numpy(a).cuda()
        d, i = gpugeom.distance_transform_edt(ta, return_indices=True)
        np.testing.assert_array_equal(d.cpu().numpy(), want_d)
        np.testing.assert_array_equal(i.cpu().numpy(), want_i)
    # Every block was taken on the caller's stream.
    assert recording["torch"].streams == {s.cuda_stream}


def test_torch_refusal_is_a_memory_error(rng):
    torch = pytest.importorskip("torch")
    torch.cuda.synchronize()
    free, _ = torch.cuda.mem_get_info()
    total = torch.cuda.get_device_properties(0).total_memory
    # Let PyTorch hand out a few MB more than it holds now: the call's arrays do not fit.
    frac = (torch.cuda.memory_reserved() + (8 << 20)) / total
    torch.cuda.set_per_process_memory_fraction(frac)
    try:
        t = torch.from_numpy(rng.random((2000000, 3))).cuda() if free > (1 << 30) else None
        if t is None:
            pytest.skip("too little free GPU memory for the test")
        with pytest.raises(MemoryError, match="allocator refused"):
            gpugeom.Delaunay(t)
    finally:
        torch.cuda.set_per_process_memory_fraction(1.0)
    torch.cuda.synchronize()
    # The library can still run after the refusal.
    assert gpugeom.Delaunay(torch.from_numpy(rng.random((1000, 3))).cuda()).simplices.is_cuda


def test_cupy_pool_counts_the_librarys_memory(rng, recording):
    cupy = pytest.importorskip("cupy")
    pool = cupy.get_default_memory_pool()
    p = rng.random((100000, 2))
    g = cupy.asarray(p)
    cupy.cuda.Device().synchronize()
    before = pool.used_bytes()
    d = gpugeom.Delaunay(g)
    rec = recording["cupy"]
    assert rec.allocs > 10 and rec.live
    assert pool.used_bytes() - before >= d.simplices.nbytes + d.neighbors.nbytes
    h = with_library_pool(lambda: gpugeom.Delaunay(g))
    np.testing.assert_array_equal(cupy.asnumpy(d.simplices), cupy.asnumpy(h.simplices))
    del d, h
    cupy.cuda.Device().synchronize()
    assert not rec.live
    assert pool.used_bytes() == before
