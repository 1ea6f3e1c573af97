// Device resolution, the library's memory pools, and the query of what this build can run.
#include "exec/cuda_device.hpp"

#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "exec/cuda_check.cuh"

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
    cuda_device::Scope on(d.device);
    (void)cudaFree(nullptr);  // creates the device's primary context
    (void)cuda_device::pool(d.device);
  } catch (...) {  // (a later call reports whatever went wrong here)
  }
  (void)cudaGetLastError();
}

void release_cached_device_memory() {
  Pools& P = pools();
  std::lock_guard<std::mutex> lk(P.m);
  for (std::size_t i = 0; i < P.pool.size(); ++i)
    if (P.pool[i]) {
      cuda_device::Scope on(int(i));
      GG_CUDA_CHECK(cudaDeviceSynchronize());  // blocks freed on streams still running
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

std::uint64_t available_memory(int device) {
  Scope on(device);
  std::size_t fr = 0, tot = 0;
  GG_CUDA_CHECK(cudaMemGetInfo(&fr, &tot));
  unsigned long long reserved = 0, used = 0;  // (cuuint64_t attributes)
  cudaMemPool_t p = pool(device);
  GG_CUDA_CHECK(cudaMemPoolGetAttribute(p, cudaMemPoolAttrReservedMemCurrent, &reserved));
  GG_CUDA_CHECK(cudaMemPoolGetAttribute(p, cudaMemPoolAttrUsedMemCurrent, &used));
  return std::uint64_t(fr) + (reserved > used ? reserved - used : 0);
}

void require_memory(int device, std::uint64_t bytes, const std::string& what) {
  {
    // A problem larger than the driver's free memory would run in the pool's blocks of
    // earlier calls (or of this call's earlier steps), which were cut for other sizes and
    // need not fit its largest arrays. The unused blocks go back to the driver first, so
    // that the arrays are cut afresh.
    Scope on(device);
    std::size_t fr = 0, tot = 0;
    GG_CUDA_CHECK(cudaMemGetInfo(&fr, &tot));
    if (bytes > fr) {
      GG_CUDA_CHECK(cudaDeviceSynchronize());  // (frees still queued on streams land first)
      trim(device);
    }
  }
  const std::uint64_t avail = available_memory(device);
  if (bytes <= avail) return;
  std::size_t fr = 0, tot = 0;
  unsigned long long reserved = 0, used = 0;
  {
    Scope on(device);
    GG_CUDA_CHECK(cudaMemGetInfo(&fr, &tot));
    GG_CUDA_CHECK(
        cudaMemPoolGetAttribute(pool(device), cudaMemPoolAttrReservedMemCurrent, &reserved));
    GG_CUDA_CHECK(cudaMemPoolGetAttribute(pool(device), cudaMemPoolAttrUsedMemCurrent, &used));
  }
  auto gb = [](std::uint64_t b) {
    char s[32];
    std::snprintf(s, sizeof s, "%.1f GB", double(b) / 1e9);
    return std::string(s);
  };
  throw Error(ErrorCode::OutOfMemory,
              what + " needs at least " + gb(bytes) + " (" + std::to_string(bytes) +
                  " bytes) of GPU memory and " + gb(avail) + " (" + std::to_string(avail) +
                  " bytes) are free on device " + std::to_string(device) + " (of " + gb(tot) +
                  "; this process holds " + gb(used) + " in arrays, " + gb(reserved - used) +
                  " more in its pool): use a smaller input, or the CPU backend (--backend cpu)");
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
