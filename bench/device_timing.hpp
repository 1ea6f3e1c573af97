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

template <class P, class Run>
double device_resident_ms(const std::vector<P>& p, int reps, Run run) {
#ifdef GPUGEOM_HAVE_CUDA
  double* d = nullptr;
  const std::size_t bytes = p.size() * sizeof(P);
  if (cudaMalloc(&d, bytes) != cudaSuccess) return -1;
  if (cudaMemcpy(d, p.data(), bytes, cudaMemcpyHostToDevice) != cudaSuccess) {
    cudaFree(d);
    return -1;
  }
  run(d, std::int64_t(p.size()));  // warm-up
  std::vector<double> t;
  for (int k = 0; k < reps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    run(d, std::int64_t(p.size()));
    t.push_back(ms_since(t0));
  }
  cudaFree(d);
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
#else
  (void)p, (void)reps, (void)run;
  return -1;
#endif
}

}  // namespace gpugeom::bench
