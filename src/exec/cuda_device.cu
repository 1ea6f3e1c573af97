// Device resolution, the library's memory pools, and the query of what this build can run.
#include "exec/cuda_device.hpp"

#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "exec/cuda_check.cuh"
#include "gpugeom/memory.hpp"

#ifndef GPUGEOM_CUDA_ARCH_LIST
#define GPUGEOM_CUDA_ARCH_LIST "unknown"
#endif

namespace gpugeom {

namespace {

// A kernel whose attributes can be read only where the binary has code (or PTX) the device
// can run: the cheapest exact test of "no kernel image for this device".
__global__ void probe_kernel() {}

// "90;100-real" (CMake's list) -> "sm_90 compute_90 sm_100".
std::string describe_archs(const std::string& list) {
  std::string out, item;
  auto flush = [&] {
    if (item.empty()) return;
    std::string num = item, kind = "";
    const auto dash = item.find('-');
    if (dash != std::string::npos) {
      num = item.substr(0, dash);
      kind = item.substr(dash + 1);
    }
    auto add = [&](const std::string& s) { out += (out.empty() ? "" : " ") + s; };
    if (kind != "virtual") add("sm_" + num);
    if (kind != "real") add("compute_" + num);
    item.clear();
  };
  for (char c : list) {
    if (c == ';' || c == ',' || c == ' ')
      flush();
    else
      item += c;
  }
  flush();
  return out;
}

struct Pools {
  std::mutex m;
  std::vector<cudaMemPool_t> pool;  // per device ordinal; null until first use
};
Pools& pools() {
  static Pools* p = new Pools;  // never destroyed: pools live as long as the process
  return *p;
}

// The library's resource over those pools: the device is the current one (the executor's).
class PoolResource final : public DeviceMemoryResource {
 public:
  void* allocate(std::size_t bytes, std::size_t, void* stream) override {
    int dev = 0;
    GG_CUDA_CHECK(cudaGetDevice(&dev));
    const cudaStream_t s = cudaStream_t(stream);
    const cudaMemPool_t pool = cuda_device::pool(dev);
    void* p = nullptr;
    cudaError_t e = cudaMallocFromPoolAsync(&p, bytes, pool, s);
    if (e == cudaErrorMemoryAllocation) {
      // The pool keeps freed blocks; hand them back to the driver and retry once.
      (void)cudaGetLastError();
      GG_CUDA_CHECK(cudaStreamSynchronize(s));
      cuda_device::trim(dev);
      e = cudaMallocFromPoolAsync(&p, bytes, pool, s);
    }
    if (e == cudaErrorMemoryAllocation) {
      (void)cudaGetLastError();
      cuda_device::throw_out_of_memory(bytes, "device allocation");
    }
    GG_CUDA_CHECK(e);
    return p;
  }
  // (cudaFreeAsync, not the synchronous free: a pool's block freed that way stays counted as
  // used by the pool, measured on the H100, and the next call's memory check would refuse work
  // that fits.)
  void deallocate(void* p, std::size_t, std::size_t, void* stream) noexcept override {
    (void)cudaFreeAsync(p, cudaStream_t(stream));  // (a failure surfaces at the next check)
  }
  std::uint64_t cached_bytes(int device) const noexcept override {
    try {
      unsigned long long reserved = 0, used = 0;  // (cuuint64_t attributes)
      const cudaMemPool_t p = cuda_device::pool(device);
      if (cudaMemPoolGetAttribute(p, cudaMemPoolAttrReservedMemCurrent, &reserved) != cudaSuccess ||
          cudaMemPoolGetAttribute(p, cudaMemPoolAttrUsedMemCurrent, &used) != cudaSuccess) {
        (void)cudaGetLastError();
        return 0;
      }
      return reserved > used ? reserved - used : 0;
    } catch (...) {
      return 0;
    }
  }
};

}  // namespace

bool built_with_cuda() {
  return true;
}

std::string built_cuda_architectures() {
  return describe_archs(GPUGEOM_CUDA_ARCH_LIST);
}

DeviceInfo query_device(int device) {
  DeviceInfo d;
  int n = 0;
  cudaError_t e = cudaGetDeviceCount(&n);
  if (e != cudaSuccess || n == 0) {
    d.reason = e != cudaSuccess
                   ? std::string("no usable CUDA driver/device (") + cudaGetErrorString(e) + ")"
                   : std::string("no CUDA device found");
    (void)cudaGetLastError();  // not sticky: later calls start clean
    return d;
  }
  d.device_count = n;
  int dev = device;
  if (dev < 0 && (e = cudaGetDevice(&dev)) != cudaSuccess) {
    d.reason = std::string("cannot read the current device: ") + cudaGetErrorString(e);
    (void)cudaGetLastError();
    return d;
  }
  d.device = dev;
  if (dev >= n) {
    d.reason = "there is no CUDA device " + std::to_string(dev) + " (this machine has " +
               std::to_string(n) + ", numbered from 0)";
    return d;
  }
  cudaDeviceProp p{};
  if ((e = cudaGetDeviceProperties(&p, dev)) != cudaSuccess) {
    d.reason = std::string("cannot read device properties: ") + cudaGetErrorString(e);
    (void)cudaGetLastError();
    return d;
  }
  d.name = p.name;
  d.compute_major = p.major;
  d.compute_minor = p.minor;
  d.multiprocessors = p.multiProcessorCount;
  d.total_memory = p.totalGlobalMem;
  const std::string cc = std::to_string(p.major) + "." + std::to_string(p.minor);
  if (p.major < 8) {
    // The kernels use sm_80 features (warp reductions, cp.async-era shared memory sizes).
    d.reason = "compute capability " + cc + " is older than gpugeom supports (8.0 and up)";
    return d;
  }
  {
    cuda_device::Scope on(dev);
    std::size_t fr = 0, tot = 0;
    if (cudaMemGetInfo(&fr, &tot) == cudaSuccess) d.free_memory = fr;
    cudaFuncAttributes fa{};
    if ((e = cudaFuncGetAttributes(&fa, probe_kernel)) != cudaSuccess) {
      (void)cudaGetLastError();
      d.reason = "this build has device code for " + built_cuda_architectures() +
                 " only, and the " + d.name + " (compute capability " + cc +
                 ") can run none of it (" + cudaGetErrorString(e) +
                 "): rebuild with -DGPUGEOM_CUDA_ARCHS=" + std::to_string(p.major) +
                 std::to_string(p.minor) + " (or =all), or use the CPU backend";
      return d;
    }
  }
  (void)cudaGetLastError();
  d.available = true;
  return d;
}

namespace {
// The devices found usable, checked once per device and process (the answer cannot change
// while it runs): by prepare_device on its thread or by the first call that runs on one, so a
// command that started the device ahead does not query it again (a second
// cudaGetDeviceProperties and probe on its critical path).
struct Usable {
  std::mutex m;
  std::vector<int> ok;  // 0 unknown, 1 usable
  bool known(int dev) {
    std::lock_guard<std::mutex> lk(m);
    return std::size_t(dev) < ok.size() && ok[std::size_t(dev)];
  }
  void mark(int dev) {
    std::lock_guard<std::mutex> lk(m);
    if (ok.size() <= std::size_t(dev)) ok.resize(std::size_t(dev) + 1, 0);
    ok[std::size_t(dev)] = 1;
  }
};
Usable& usable() {
  static Usable u;
  return u;
}
}  // namespace

void prepare_device(int device) noexcept {
  try {
    const DeviceInfo d = query_device(device);
    if (!d.available) return;
    usable().mark(d.device);
    (void)cudaInitDevice(d.device, 0, 0);  // creates the device's primary context
    cuda_device::Scope on(d.device);
    (void)cuda_device::pool(d.device);
  } catch (...) {  // (a later call reports whatever went wrong here)
  }
  (void)cudaGetLastError();
}

std::shared_ptr<DeviceMemoryResource> library_memory_resource() {
  static const std::shared_ptr<DeviceMemoryResource> r = std::make_shared<PoolResource>();
  return r;
}

void release_cached_device_memory() {
  Pools& P = pools();
  std::lock_guard<std::mutex> lk(P.m);
  for (std::size_t i = 0; i < P.pool.size(); ++i)
    if (P.pool[i]) {
      cuda_device::Scope on(int(i));
      GG_CUDA_CHECK(cudaMemPoolTrimTo(P.pool[i], 0));
    }
}

namespace cuda_device {

Scope::Scope(int device) {
  GG_CUDA_CHECK(cudaGetDevice(&prev_));
  if (device >= 0 && device != prev_) {
    GG_CUDA_CHECK(cudaSetDevice(device));
    changed_ = true;
  }
}
Scope::~Scope() {
  if (changed_) (void)cudaSetDevice(prev_);
}

PeerScope::PeerScope(int device, int peer) : device_(device), peer_(peer) {
  if (device < 0 || peer < 0 || device == peer) return;
  int can = 0;
  GG_CUDA_CHECK(cudaDeviceCanAccessPeer(&can, device, peer));
  if (!can) return;
  Scope on(device);
  const cudaError_t e = cudaDeviceEnablePeerAccess(peer, 0);
  if (e == cudaErrorPeerAccessAlreadyEnabled) {  // (the caller's: left on)
    (void)cudaGetLastError();
    return;
  }
  GG_CUDA_CHECK(e);
  enabled_ = true;
}
PeerScope::~PeerScope() {
  if (!enabled_) return;
  int prev = -1;  // (a destructor does not throw: errors are left to the next checked call)
  (void)cudaGetDevice(&prev);
  if (prev != device_) (void)cudaSetDevice(device_);
  (void)cudaDeviceDisablePeerAccess(peer_);
  if (prev >= 0 && prev != device_) (void)cudaSetDevice(prev);
}

int resolve(const RunOptions& run) {
  int dev = run.device;
  if (dev < 0 && run.stream) GG_CUDA_CHECK(cudaStreamGetDevice(cudaStream_t(run.stream), &dev));
  if (dev < 0) GG_CUDA_CHECK(cudaGetDevice(&dev));
  if (usable().known(dev)) return dev;
  DeviceInfo d = query_device(dev);
  if (!d.available) {
    throw Error(dev >= d.device_count ? ErrorCode::InvalidArgument : ErrorCode::Unsupported,
                "CUDA device " + std::to_string(dev) + " cannot be used: " + d.reason);
  }
  usable().mark(dev);
  return dev;
}

cudaMemPool_t pool(int device) {
  Pools& P = pools();
  std::lock_guard<std::mutex> lk(P.m);
  if (P.pool.size() <= std::size_t(device)) P.pool.resize(std::size_t(device) + 1, nullptr);
  cudaMemPool_t& p = P.pool[std::size_t(device)];
  if (!p) {
    cudaMemPoolProps props{};
    props.allocType = cudaMemAllocationTypePinned;
    props.location.type = cudaMemLocationTypeDevice;
    props.location.id = device;
    GG_CUDA_CHECK(cudaMemPoolCreate(&p, &props));
    std::uint64_t keep = ~std::uint64_t(0);
    GG_CUDA_CHECK(cudaMemPoolSetAttribute(p, cudaMemPoolAttrReleaseThreshold, &keep));
  }
  return p;
}

void trim(int device) {
  GG_CUDA_CHECK(cudaMemPoolTrimTo(pool(device), 0));
}

std::uint64_t available_memory(const detail::CallMemory& mem) {
  std::size_t fr = 0, tot = 0;
  GG_CUDA_CHECK(cudaMemGetInfo(&fr, &tot));  // (the executor has made the device current)
  return std::uint64_t(fr) + mem.resource().cached_bytes(mem.device());
}

void require_memory(detail::CallMemory& mem, cudaStream_t s, std::uint64_t bytes,
                    const std::string& what) {
  const int device = mem.device();
  std::size_t fr = 0, tot = 0;
  GG_CUDA_CHECK(cudaMemGetInfo(&fr, &tot));
  if (bytes > fr && mem.is_library_pool()) {
    // A problem larger than the driver's free memory would run in the pool's blocks of
    // earlier calls (or of this call's earlier steps), which were cut for other sizes and
    // need not fit its largest arrays. The unused blocks go back to the driver first, so
    // that the arrays are cut afresh (once the call's own queued frees have run).
    GG_CUDA_CHECK(cudaStreamSynchronize(s));
    trim(device);
  }
  const std::uint64_t avail = available_memory(mem);
  if (bytes <= avail) return;
  GG_CUDA_CHECK(cudaMemGetInfo(&fr, &tot));
  const std::uint64_t cached = mem.resource().cached_bytes(device);
  auto gb = [](std::uint64_t b) {
    char t[32];
    std::snprintf(t, sizeof t, "%.1f GB", double(b) / 1e9);
    return std::string(t);
  };
  throw Error(ErrorCode::OutOfMemory,
              what + " needs at least " + gb(bytes) + " (" + std::to_string(bytes) +
                  " bytes) of GPU memory and " + gb(avail) + " (" + std::to_string(avail) +
                  " bytes) are free on device " + std::to_string(device) + " (of " + gb(tot) +
                  "; " + gb(cached) + " of it unused in the memory resource's cache)" +
                  ": use a smaller input, or the CPU backend (--backend cpu)");
}

void throw_out_of_memory(std::size_t bytes, const char* what) {
  std::size_t fr = 0, tot = 0;
  if (cudaMemGetInfo(&fr, &tot) != cudaSuccess) (void)cudaGetLastError();
  throw Error(ErrorCode::OutOfMemory,
              std::string(what) + ": " + std::to_string(bytes) + " bytes of GPU memory were " +
                  "needed and " + std::to_string(fr) + " of " + std::to_string(tot) +
                  " are free; the problem does not fit in GPU memory: use a smaller input, or " +
                  "the CPU backend (--backend cpu)");
}

}  // namespace cuda_device
}  // namespace gpugeom
