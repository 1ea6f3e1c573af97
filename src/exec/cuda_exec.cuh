// The CUDA executor: one device and one stream given by the caller, stream-ordered allocation
// from the caller's memory resource or the library's own pool on that device, CUB for scans, sorts,
// selection and reductions. Same members as CpuExec. Members marked [synchronises] wait for the
// stream; every other member only queues work. Only for nvcc translation units.
#pragma once
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_select.cuh>
#include <cuda_runtime.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>

#include "exec/cuda_check.cuh"
#include "exec/cuda_device.hpp"
#include "exec/device_memory.hpp"
#include "exec/exec_context.hpp"
#include "exec/host_staging.hpp"
#include "exec/lanes.hpp"
#include "exec/positions.hpp"
#include "exec/tuning.hpp"
#include "base/hd.hpp"

namespace gpugeom {

template <class T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  // Stream-ordered from the call's memory (the caller's resource or the library's pool).
  DeviceBuffer(std::size_t n, cudaStream_t s, std::shared_ptr<detail::CallMemory> mem)
      : n_(n), s_(s) {
    if (!n) return;
    p_ = static_cast<T*>(mem->allocate(n * sizeof(T), s));
    mem_ = std::move(mem);
  }
  DeviceBuffer(DeviceBuffer&& o) noexcept { swap(o); }
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    DeviceBuffer tmp(std::move(o));
    swap(tmp);
    return *this;
  }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  // Stream-ordered: work queued on the stream before the free may still use the block.
  ~DeviceBuffer() {
    if (p_) mem_->deallocate(p_, n_ * sizeof(T), s_);
  }
  T* data() { return p_; }
  const T* data() const { return p_; }
  std::size_t size() const { return n_; }
  // Hands the buffer to the caller (the device entry points' results) as a shared pointer whose
  // last copy gives the block back to the call's memory resource, stream-ordered on the call's
  // stream (the per-thread default stream of the thread dropping it, where the call had none):
  // the caller orders its own uses on other streams before that, as with rmm::device_buffer or
  // a PyTorch tensor. Nothing waits for the device. Call after the stream was synchronised.
  std::shared_ptr<T> hand_over() {
    if (!p_) return {};
    const std::size_t bytes = n_ * sizeof(T);
    const cudaStream_t s = s_;
    std::shared_ptr<detail::CallMemory> mem = std::move(mem_);
    T* p = p_;
    p_ = nullptr;
    n_ = 0;
    return std::shared_ptr<T>(p, [mem, bytes, s](T* q) {
      int prev = -1;  // a deleter must not throw: errors are left to the next checked call
      (void)cudaGetDevice(&prev);
      const int dev = mem->device();
      if (prev != dev) (void)cudaSetDevice(dev);
      mem->deallocate(q, bytes, s);
      if (prev >= 0 && prev != dev) (void)cudaSetDevice(prev);
    });
  }

 private:
  void swap(DeviceBuffer& o) noexcept {
    std::swap(p_, o.p_);
    std::swap(n_, o.n_);
    std::swap(s_, o.s_);
    std::swap(mem_, o.mem_);
  }
  T* p_ = nullptr;
  std::size_t n_ = 0;
  cudaStream_t s_ = nullptr;
  std::shared_ptr<detail::CallMemory> mem_;
};

namespace cuda_detail {
template <class F>
__global__ void for_each_kernel(std::int64_t n, F f) {
  const std::int64_t stride = std::int64_t(gridDim.x) * blockDim.x;
  for (std::int64_t i = std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x; i < n; i += stride)
    f(i);
}
// f(i) for i < *count, the count read when the kernel runs. MinBlocks > 1 asks the compiler for
// that many resident blocks of 256 a multiprocessor (at most 65 536 / (256 MinBlocks)
// registers a thread; see CudaExec::for_each_counted).
template <class F, int MinBlocks>
__global__ void __launch_bounds__(256, MinBlocks)
    for_each_counted_kernel(const std::int64_t* count, std::int64_t per, F f) {
  const std::int64_t n = per * *count;
  const std::int64_t stride = std::int64_t(gridDim.x) * blockDim.x;
  for (std::int64_t i = std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x; i < n; i += stride)
    f(i);
}
// One block running f(team) on every thread: loops of short rounds with no kernel boundary.
constexpr int kTeamThreads = 1024;
struct Team {
  int rank, size;
  __host__ __device__ void barrier() const {  // (host side only so that GG_LAMBDA can call it)
#ifdef __CUDA_ARCH__
    __syncthreads();
#endif
  }
  // Every thread passes v; each gets the sum of the v of lower ranks, and *total the sum of all.
  // Called by all threads together (it has barriers). Warp scans by shuffles, then one warp
  // scans the warp sums in shared memory.
  __host__ __device__ std::int64_t exclusive_scan(std::int64_t v, std::int64_t* total) const {
#ifdef __CUDA_ARCH__
    __shared__ std::int64_t warp_sum[kTeamThreads / 32];
    const int lane = rank & 31, w = rank >> 5, warps = size >> 5;
    std::int64_t x = v;
    for (int d = 1; d < 32; d <<= 1) {
      const std::int64_t y = __shfl_up_sync(0xffffffffu, x, d);
      if (lane >= d) x += y;
    }
    __syncthreads();  // the previous scan's readers are done with warp_sum
    if (lane == 31) warp_sum[w] = x;
    __syncthreads();
    if (w == 0) {
      std::int64_t z = lane < warps ? warp_sum[lane] : 0;
      for (int d = 1; d < 32; d <<= 1) {
        const std::int64_t y = __shfl_up_sync(0xffffffffu, z, d);
        if (lane >= d) z += y;
      }
      if (lane < warps) warp_sum[lane] = z;
    }
    __syncthreads();
    *total = warp_sum[warps - 1];
    return (w > 0 ? warp_sum[w - 1] : 0) + x - v;
#else
    (void)v;
    *total = 0;
    return 0;
#endif
  }
};
// A warp as Lanes (exec/lanes.hpp). (Host members only so that GG_LAMBDA can call them.)
struct WarpLanes {
  int rank;
  static constexpr int size = 32;
  __host__ __device__ void sync() const {
#ifdef __CUDA_ARCH__
    __syncwarp();
#endif
  }
  __host__ __device__ std::uint32_t ballot(bool b) const {
#ifdef __CUDA_ARCH__
    return __ballot_sync(0xffffffffu, b);
#else
    return b ? 1u : 0u;
#endif
  }
  __host__ __device__ bool any(bool b) const {
    return ballot(b) != 0;
  }
  __host__ __device__ int below(std::uint32_t mask) const {
#ifdef __CUDA_ARCH__
    return __popc(mask & ((1u << rank) - 1u));
#else
    return 0;
#endif
  }
  __host__ __device__ static int count(std::uint32_t mask) {
#ifdef __CUDA_ARCH__
    return __popc(mask);
#else
    return int(mask & 1u);
#endif
  }
  __host__ __device__ int exclusive_scan(int v, int* total) const {
#ifdef __CUDA_ARCH__
    int x = v;
    for (int d = 1; d < 32; d <<= 1) {
      const int y = __shfl_up_sync(0xffffffffu, x, d);
      if (rank >= d) x += y;
    }
    *total = __shfl_sync(0xffffffffu, x, 31);
    return x - v;
#else
    *total = v;
    return 0;
#endif
  }
  template <class T>
  __host__ __device__ T broadcast(T v) const {
#ifdef __CUDA_ARCH__
    return __shfl_sync(0xffffffffu, v, 0);
#else
    return v;
#endif
  }
};
// f(i, lanes) with a warp per i (every lane of it calls f with the same i).
template <class F>
__global__ void for_each_lanes_kernel(std::int64_t n, F f) {
  const std::int64_t warps = std::int64_t(gridDim.x) * (blockDim.x / 32);
  const WarpLanes L{int(threadIdx.x & 31)};
  for (std::int64_t i = std::int64_t(blockIdx.x) * (blockDim.x / 32) + threadIdx.x / 32; i < n;
       i += warps)
    f(i, L);
}
template <int Threads, class F>
__global__ void __launch_bounds__(Threads) team_kernel(F f) {
  f(Team{int(threadIdx.x), int(blockDim.x)});
}
// Resident blocks of `block` threads per SM for `kernel` on device dev (at least 1), computed
// on first use per kernel and device.
constexpr int kMaxDevices = 64;
template <auto Kernel>
int resident_blocks(int block, int dev) {
  static std::atomic<int> cache[kMaxDevices] = {};
  std::atomic<int>* c = dev < kMaxDevices ? &cache[dev] : nullptr;
  if (c) {
    const int v = c->load(std::memory_order_relaxed);
    if (v) return v;
  }
  int n = 0;
  GG_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&n, Kernel, block, 0));
  n = n > 0 ? n : 1;
  if (c) c->store(n, std::memory_order_relaxed);
  return n;
}
template <class F, class T>
struct IndexMap {
  F f;
  __device__ T operator()(std::int64_t i) const { return f(i); }
};
template <class F>
struct IndexPred {
  F f;
  __device__ bool operator()(std::int32_t i) const { return f(std::int64_t(i)); }
};
}  // namespace cuda_detail

class CudaExec {
 public:
  static constexpr Backend backend = Backend::Cuda;
  template <class T>
  using Buffer = DeviceBuffer<T>;

  // Binds the executor to the device and stream of `run` (cuda_device::resolve) for its
  // lifetime: the calling thread's current device is that device until the executor is
  // destroyed, then restored. One executor is used by one host thread.
  explicit CudaExec(const RunOptions& run = {}) : CudaExec(run, nullptr) {}
  // With `outer` (another executor's context(), exec/exec_context.hpp): on its device and
  // stream, taking memory through its call's count; the knobs are still run's.
  CudaExec(const RunOptions& run, const detail::ExecContext* outer)
      : dev_(outer ? outer->device : cuda_device::resolve(run)),
        on_(dev_),
        s_(outer        ? cudaStream_t(outer->stream)
           : run.stream ? cudaStream_t(run.stream)
                        : cudaStreamPerThread),
        mem_(outer ? outer->memory : std::make_shared<detail::CallMemory>(run.memory, dev_)),
        tuning_(detail::tuning_of(run)),
        nested_(outer != nullptr) {
    GG_CUDA_CHECK(cudaDeviceGetAttribute(&sms_, cudaDevAttrMultiProcessorCount, dev_));
  }
  // What a capability this one calls runs on (its entry's `outer`).
  detail::ExecContext context() const { return {dev_, (void*)s_, mem_}; }
  CudaExec(const CudaExec&) = delete;
  CudaExec& operator=(const CudaExec&) = delete;
  // The options a state kept across calls (DynamicDelaunay2d, ...) runs its later calls with:
  // pinned to the device this one resolves to, whatever the calling thread's current device is
  // at those later calls.
  template <class Options>
  static Options kept_options(Options opt) {
    opt.device = cuda_device::resolve(opt);
    return opt;
  }
  // The call's internal knobs (exec/tuning.hpp), copied from its options.
  const detail::Tuning& tuning() const { return tuning_; }
  cudaStream_t stream() const { return s_; }
  // See cuda_device::require_memory: refuses, before any launch, a problem that cannot fit.
  void require_memory(std::uint64_t bytes, const std::string& what) {
    cuda_device::require_memory(*mem_, s_, bytes, what);
  }
  // Memory a call may still take (cuda_device::available_memory).
  std::uint64_t available_memory() const { return cuda_device::available_memory(*mem_); }
  // The most device memory this executor's arrays held at once from reset_peak() on
  // (exec/peak.hpp), whatever other calls held from the same resource.
  void reset_peak() { mem_->reset_peak(); }
  // Built from an outer executor's context: the peak is the outer call's to reset.
  bool nested() const { return nested_; }
  std::int64_t peak_bytes() const { return mem_->peak(); }
  int device() const { return dev_; }
  // Direct reads of device `peer`'s memory by this executor's device while the result lives
  // (cuda_device::PeerScope): for copies from arrays another device made.
  cuda_device::PeerScope peer_access(int peer) const { return cuda_device::PeerScope(dev_, peer); }

  template <class T>
  Buffer<T> alloc(std::size_t n) {
    return Buffer<T>(n, s_, mem_);
  }

  // f(i) for i < n.
  template <class F>
  void for_each_index(std::int64_t n, F f) {
    if (n <= 0) return;
    constexpr int kBlock = 256;
    const std::int64_t blocks = grid<cuda_detail::for_each_kernel<F>>(kBlock, n);
    cuda_detail::for_each_kernel<F><<<unsigned(blocks), kBlock, 0, s_>>>(n, f);
    GG_CUDA_CHECK_LAUNCH_OF("for_each_kernel", F);
  }

  // f(i) for every i < per * *count, where count lives on the device and is read when the kernel
  // runs, so the host need not wait for the work that produces it; bound >= per * *count sizes
  // the grid as for_each_index(bound) would (blocks past the count return at once).
  // MinBlocks: resident blocks of 256 threads a multiprocessor to compile for (1: as many
  // registers as the code wants). For latency-bound kernels whose rare paths are out of line
  // (the exact predicates' tiers), so those spill rather than the common path's occupancy.
  template <int MinBlocks = 1, class F>
  void for_each_counted(const std::int64_t* count, std::int64_t bound, F f, std::int64_t per = 1) {
    if (bound <= 0) return;
    constexpr int kBlock = 256;
    const std::int64_t blocks =
        grid<cuda_detail::for_each_counted_kernel<F, MinBlocks>>(kBlock, bound);
    cuda_detail::for_each_counted_kernel<F, MinBlocks>
        <<<unsigned(blocks), kBlock, 0, s_>>>(count, per, f);
    GG_CUDA_CHECK_LAUNCH_OF("for_each_counted_kernel", F);
  }

  // f(i, lanes) for i < n, a group of lanes (a warp) per i: see exec/lanes.hpp.
  using Lanes = cuda_detail::WarpLanes;
  template <class F>
  void for_each_lanes(std::int64_t n, F f) {
    if (n <= 0) return;
    constexpr int kBlock = 256;
    const std::int64_t blocks =
        grid<cuda_detail::for_each_lanes_kernel<F>>(kBlock, n * Lanes::size);
    cuda_detail::for_each_lanes_kernel<F><<<unsigned(blocks), kBlock, 0, s_>>>(n, f);
    GG_CUDA_CHECK_LAUNCH_OF("for_each_lanes_kernel", F);
  }

  // A team: threads that share barriers (one thread block here), for iterations so short that a
  // kernel launch per step would cost more than the step. f(const Team&) runs on each thread;
  // team.barrier() makes every thread's writes visible to all the others.
  // Threads (a multiple of 32, at most kTeamThreads) trades threads for registers: a team of
  // 1024 gets 64 registers a thread, one of 512 gets 128.
  using Team = cuda_detail::Team;
  template <int Threads = cuda_detail::kTeamThreads>
  int team_size() const {
    return Threads;
  }
  template <int Threads = cuda_detail::kTeamThreads, class F>
  void team(F f) {
    static_assert(Threads % 32 == 0 && Threads <= cuda_detail::kTeamThreads, "team size");
    cuda_detail::team_kernel<Threads><<<1, Threads, 0, s_>>>(f);
    GG_CUDA_CHECK_LAUNCH_OF("team_kernel", F);
  }

  template <class T>
  void fill(T* p, std::int64_t n, T v) {
    for_each_index(n, [=] __device__(std::int64_t i) { p[i] = v; });
  }
  template <class T>
  void copy(const T* src, std::int64_t n, T* dst) {
    if (n > 0) GG_CUDA_CHECK(cudaMemcpyAsync(dst, src, sizeof(T) * n, cudaMemcpyDefault, s_));
  }
  // [synchronises] Host copies complete before returning, so the host array may be used or
  // freed at once (and everything queued before them has run).
  template <class T>
  void to_host(const T* src, std::int64_t n, T* host) {
    if (std::size_t(n) * sizeof(T) >= staging::kMinBytes && is_pageable(host)) {
      staging::to_host(host, src, std::size_t(n) * sizeof(T), s_);
      return;
    }
    if (std::size_t(n) * sizeof(T) <= staging::kMailBytes && is_pageable(host)) {
      staging::small_to_host(host, src, std::size_t(n) * sizeof(T), s_);
      return;
    }
    copy(src, n, host);
    sync();
  }
  // [synchronises] A host array of n copies of v: filled on the device and copied back, so
  // that its pages are touched at the copy's rate, not by one host thread.
  template <class T>
  void fill_host(T* host, std::int64_t n, T v) {
    if (n <= 0) return;
    auto b = alloc<T>(std::size_t(n));
    fill(b.data(), n, v);
    to_host(b.data(), n, host);
  }
  // [synchronises] as to_host.
  template <class T>
  void from_host(const T* host, std::int64_t n, T* dst) {
    if (std::size_t(n) * sizeof(T) >= staging::kMinBytes && is_pageable(host)) {
      staging::from_host(dst, host, std::size_t(n) * sizeof(T), s_);
      return;
    }
    copy(host, n, dst);
    sync();
  }

  template <class T>
  void exclusive_scan(const T* in, T* out, std::int64_t n) {
    sum_scan(in, out, n, false);
  }
  // out[i] = f(0) + ... + f(i-1): the scan reads f's values straight from the function.
  template <class F, class T>
  void exclusive_scan_of(std::int64_t n, F f, T* out) {
    sum_scan(thrust::make_transform_iterator(thrust::counting_iterator<std::int64_t>(0),
                                             cuda_detail::IndexMap<F, T>{f}),
             out, n, false);
  }
  template <class T>
  void inclusive_scan(const T* in, T* out, std::int64_t n) {
    sum_scan(in, out, n, true);
  }
  // The prefix sums of n values read from `in` (a pointer or an iterator) into out.
  template <class It, class T>
  void sum_scan(It in, T* out, std::int64_t n, bool inclusive) {
    if (n <= 0) return;
    run_cub([&](void* tmp, std::size_t& bytes) {
      return inclusive ? cub::DeviceScan::InclusiveSum(tmp, bytes, in, out, n, s_)
                       : cub::DeviceScan::ExclusiveSum(tmp, bytes, in, out, n, s_);
    });
  }
  // [synchronises] returns the value on the host.
  template <class T, class Op>
  T reduce(const T* in, std::int64_t n, T init, Op op) {
    Buffer<T> res = alloc<T>(1);
    T* r = res.data();
    run_cub([&](void* tmp, std::size_t& bytes) {
      return cub::DeviceReduce::Reduce(tmp, bytes, in, r, n, op, init, s_);
    });
    T h;
    to_host(r, 1, &h);
    return h;
  }
  // *out = op-reduction of f(0), ..., f(n-1) and init, written on the device without waiting
  // (so that several results can come back in one copy).
  template <class T, class F, class Op>
  void transform_reduce_into(std::int64_t n, F f, T init, Op op, T* out) {
    auto it = thrust::make_transform_iterator(thrust::counting_iterator<std::int64_t>(0),
                                              cuda_detail::IndexMap<F, T>{f});
    run_cub([&](void* tmp, std::size_t& bytes) {
      return cub::DeviceReduce::Reduce(tmp, bytes, it, out, n, op, init, s_);
    });
  }
  template <class K>
  void sort(K* keys, std::int64_t n) {
    if (n <= 1) return;
    Buffer<K> alt = alloc<K>(n);
    cub::DoubleBuffer<K> kb(keys, alt.data());
    run_cub([&](void* tmp, std::size_t& bytes) {
      return cub::DeviceRadixSort::SortKeys(tmp, bytes, kb, n, 0, int(sizeof(K) * 8), s_);
    });
    if (kb.Current() != keys) copy(kb.Current(), n, keys);
  }
  // key_bits: the keys' low bits that may be set (the others are zero; fewer radix passes).
  template <class K, class V>
  void sort_by_key(K* keys, V* vals, std::int64_t n, int key_bits = int(8 * sizeof(K))) {
    if (n <= 1) return;
    Buffer<K> ka = alloc<K>(n);
    Buffer<V> va = alloc<V>(n);
    cub::DoubleBuffer<K> kb(keys, ka.data());
    cub::DoubleBuffer<V> vb(vals, va.data());
    run_cub([&](void* tmp, std::size_t& bytes) {
      return cub::DeviceRadixSort::SortPairs(tmp, bytes, kb, vb, n, 0,
                                             std::min(key_bits, int(sizeof(K) * 8)), s_);
    });
    if (kb.Current() != keys) copy(kb.Current(), n, keys);
    if (vb.Current() != vals) copy(vb.Current(), n, vals);
  }
  // [synchronises] returns the count on the host (copy_if_to does not wait).
  template <class T, class Pred>
  std::int64_t copy_if(const T* in, std::int64_t n, T* out, Pred pred) {
    if (n <= 0) return 0;
    Buffer<std::int64_t> cnt = alloc<std::int64_t>(1);
    copy_if_to(in, n, out, pred, cnt.data());
    std::int64_t h = 0;
    to_host(cnt.data(), 1, &h);
    return h;
  }
  // The same, leaving the count on the device (in *count) without waiting for it.
  template <class T, class Pred>
  void copy_if_to(const T* in, std::int64_t n, T* out, Pred pred, std::int64_t* count) {
    if (n <= 0) {
      fill(count, 1, std::int64_t(0));
      return;
    }
    run_cub([&](void* tmp, std::size_t& bytes) {
      return cub::DeviceSelect::If(tmp, bytes, in, out, count, n, pred, s_);
    });
  }
  // [synchronises] returns the count on the host (compact_indices_to does not wait).
  template <class Pred>
  std::int64_t compact_indices(std::int64_t n, Pred pred, std::int32_t* out) {
    if (n <= 0) return 0;
    Buffer<std::int64_t> cnt = alloc<std::int64_t>(1);
    compact_indices_to(n, pred, out, cnt.data());
    std::int64_t h = 0;
    to_host(cnt.data(), 1, &h);
    return h;
  }
  // The same, leaving the count on the device (in *count) without waiting for it.
  template <class Pred>
  void compact_indices_to(std::int64_t n, Pred pred, std::int32_t* out, std::int64_t* count) {
    if (n <= 0) {
      fill(count, 1, std::int64_t(0));
      return;
    }
    detail::check_int32_positions(n);
    thrust::counting_iterator<std::int32_t> first(0);
    cuda_detail::IndexPred<Pred> ip{pred};
    run_cub([&](void* tmp, std::size_t& bytes) {
      return cub::DeviceSelect::If(tmp, bytes, first, out, count, n, ip, s_);
    });
  }
  // [synchronises] waits for everything queued on the executor's stream.
  void sync() { GG_CUDA_CHECK(cudaStreamSynchronize(s_)); }
  // Plain host memory (not pinned, not managed): large copies then go through staging.
  static bool is_pageable(const void* p) {
    cudaPointerAttributes a;
    if (cudaPointerGetAttributes(&a, p) != cudaSuccess) {
      (void)cudaGetLastError();
      return true;
    }
    return a.type == cudaMemoryTypeUnregistered;
  }
  // How many independent work items fill the device (sizes scratch pools).
  std::int64_t concurrency() const { return std::int64_t(sms_) * 1024; }

 private:
  // Blocks for a grid-stride kernel over `items`: one item a thread up to a cap of whole waves
  // (the resident blocks per SM for this kernel, times the SMs, times as many waves as fit 32
  // blocks per SM), so the last wave of a capped grid is never partial whatever the kernel's
  // occupancy. The occupancy is read once per kernel and device.
  template <auto Kernel>
  std::int64_t grid(int block, std::int64_t items) const {
    const std::int64_t want = (items + block - 1) / block;
    const std::int64_t per_sm = cuda_detail::resident_blocks<Kernel>(block, dev_);
    const std::int64_t waves = std::max<std::int64_t>(1, 32 / per_sm);
    return std::min(want, std::int64_t(sms_) * per_sm * waves);
  }
  // CUB's two-call protocol: ask for the temporary size, allocate it stream-ordered, run.
  template <class Call>
  void run_cub(Call call) {
    std::size_t bytes = 0;
    GG_CUDA_CHECK(call(nullptr, bytes));
    Buffer<unsigned char> tmp = alloc<unsigned char>(bytes ? bytes : 1);
    GG_CUDA_CHECK(call(tmp.data(), bytes));
  }
  int dev_;
  cuda_device::Scope on_;
  cudaStream_t s_;
  std::shared_ptr<detail::CallMemory> mem_;
  detail::Tuning tuning_;
  bool nested_;
  int sms_ = 1;
};

}  // namespace gpugeom
