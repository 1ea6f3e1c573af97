// Median time of run(device_points, n) with the points uploaded once beforehand: the
// "on device" column of the drivers whose library calls take points already on the GPU.
// -1 in builds without CUDA or when the upload fails.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "bench_csv.hpp"
#ifdef GPUGEOM_HAVE_CUDA
#include <cuda_runtime.h>
#endif

namespace gpugeom::bench {

// The least time `bytes` can take over the bus: the pinned rate both ways on the lent H100
// machine (54 GB/s, gpugeom_bench_bus). Each driver prints it for its input plus its output.
inline double bus_floor_ms(double bytes) {
  return bytes / 54e9 * 1e3;
}

// Median time of run(device_copy) for `bytes` of host data uploaded once beforehand.
template <class Run>
double device_resident_ms(const void* host, std::size_t bytes, int reps, Run run) {
#ifdef GPUGEOM_HAVE_CUDA
  void* d = nullptr;
  if (cudaMalloc(&d, bytes) != cudaSuccess) return -1;
  if (cudaMemcpy(d, host, bytes, cudaMemcpyHostToDevice) != cudaSuccess) {
    cudaFree(d);
    return -1;
  }
  // (freed also when a run throws: a refusal for memory leaves the device as it found it)
  struct Free {
    void* d;
    ~Free() { cudaFree(d); }
  } keep{d};
  run(static_cast<const void*>(d));  // warm-up
  std::vector<double> t;
  for (int k = 0; k < reps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    run(static_cast<const void*>(d));
    t.push_back(ms_since(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
#else
  (void)host, (void)bytes, (void)reps, (void)run;
  return -1;
#endif
}

template <class P, class Run>
double device_resident_ms(const std::vector<P>& p, int reps, Run run) {
  return device_resident_ms(p.data(), p.size() * sizeof(P), reps, [&](const void* d) {
    run(static_cast<const double*>(d), std::int64_t(p.size()));
  });
}

}  // namespace gpugeom::bench
