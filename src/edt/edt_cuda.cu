// The distance transform compiled for the CUDA executor.
#include <chrono>
#include <cuda/atomic>
#include <cstdlib>
#include <functional>
#include <cmath>
#include <string>
#include <type_traits>

#include "edt/edt_backend.hpp"
#include "exec/cuda_exec.cuh"

namespace gpugeom::edt::cuda_impl {
using Exec = CudaExec;
#include "edt/impl/pba.inl"
#include "edt/impl/jfa.inl"
// A warp per row: 32 consecutive voxels per step (coalesced), a warp max-scan gives each voxel
// the nearest site at or left of it (carried across tiles); a backward sweep with a min-scan
// gives the nearest at or right of it and picks the nearer (ties: left, the smaller x).
__global__ void x_pass_warps(Layout L, std::uint32_t* feat, std::int32_t* left, std::int64_t rows) {
  const unsigned full = 0xffffffffu;
  const int lane = threadIdx.x & 31;
  const std::int64_t warps = std::int64_t(gridDim.x) * blockDim.x / 32;
  const std::int32_t nx = std::int32_t(L.n[0]), ny = std::int32_t(L.n[1]);
  for (std::int64_t row = (std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x) / 32; row < rows;
       row += warps) {
    std::uint32_t* f = feat + row * nx;
    std::int32_t* lf = left + row * nx;
    std::int32_t carry = -1;
    for (std::int32_t x0 = 0; x0 < nx; x0 += 32) {
      const std::int32_t x = x0 + lane;
      std::int32_t v = (x < nx && f[x] != kNone) ? x : -1;
      for (int o = 1; o < 32; o *= 2) {
        const std::int32_t u = __shfl_up_sync(full, v, o);
        if (lane >= o) v = max(v, u);
      }
      v = max(v, carry);
      carry = __shfl_sync(full, v, 31);
      if (x < nx) lf[x] = v;
    }
    const std::uint32_t y = std::uint32_t(row % ny), z = std::uint32_t(row / ny);
    carry = 0x7fffffff;
    for (std::int32_t x0 = ((nx - 1) / 32) * 32; x0 >= 0; x0 -= 32) {
      const std::int32_t x = x0 + lane;
      std::int32_t r = (x < nx && f[x] != kNone) ? x : 0x7fffffff;
      for (int o = 1; o < 32; o *= 2) {
        const std::int32_t u = __shfl_down_sync(full, r, o);
        if (lane + o < 32) r = min(r, u);
      }
      r = min(r, carry);
      carry = __shfl_sync(full, r, 0);
      if (x < nx) {
        const std::int32_t l = lf[x];
        std::int32_t s = -1;
        if (l >= 0 && r < nx)
          s = (x - l <= r - x) ? l : r;
        else if (l >= 0)
          s = l;
        else if (r < nx)
          s = r;
        f[x] = s < 0 ? kNone : L.pack(std::uint32_t(s), y, z);
      }
    }
  }
}

void x_pass_rows(Exec& ex, const Layout& L, const Metric&, const PassGeom&, std::uint32_t* feat,
                 std::uint32_t* scratch, std::int32_t*, std::int32_t*) {
  const std::int64_t rows = L.count() / L.n[0];
  std::int64_t blocks = (rows * 32 + 255) / 256;
  int dev = 0, sms = 0;
  GG_CUDA_CHECK(cudaGetDevice(&dev));
  GG_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, dev));
  if (blocks > std::int64_t(sms) * 16) blocks = std::int64_t(sms) * 16;
  x_pass_warps<<<unsigned(blocks), 256, 0, ex.stream()>>>(
      L, feat, reinterpret_cast<std::int32_t*>(scratch), rows);
  GG_CUDA_CHECK_LAUNCH("x_pass_warps");
}

#include "edt/impl/run.inl"
void run(const Request& req, Output& out, Stats& stats) {
  run_impl(req, out, stats);
}
}  // namespace gpugeom::edt::cuda_impl
