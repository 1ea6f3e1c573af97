// The distance transform compiled for the CUDA executor.
#include <chrono>
#include <cuda/atomic>
#include <cstdlib>
#include <functional>
#include <cmath>
#include <string>
#include <type_traits>

#include "edt/edt_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/cuda_exec.cuh"

namespace gpugeom::edt::cuda_impl {
using Exec = CudaExec;
#include "edt/impl/pba.inl"
#include "edt/impl/jfa.inl"
// The x pass: a row is cut into segments of up to 32*K voxels and each warp holds one segment
// in registers (K coalesced loads per lane, all in flight at once). A forward warp max-scan
// gives each voxel the nearest site at or left of it, a backward min-scan the nearest at or
// right of it, and the nearer wins (ties: the left one, the smaller x). The row is read and
// written once. Rows longer than one segment first get, per segment, the last site before it
// and the first site after it (x_seg_bounds + x_seg_carries), which seed the scans.
constexpr int kSegK = 16;  // 512 voxels per segment: 16 registers per lane for the sites

struct XSegs {
  std::int64_t rows;
  std::int32_t nx, per_row, seg_len;
  std::int32_t* first;  // per segment: first / last site x in it (-1: none); then carries
  std::int32_t* last;
};

__device__ __forceinline__ std::int32_t warp_max_scan(std::int32_t v, int lane) {
  for (int o = 1; o < 32; o *= 2) {
    const std::int32_t u = __shfl_up_sync(0xffffffffu, v, o);
    if (lane >= o) v = max(v, u);
  }
  return v;
}
__device__ __forceinline__ std::int32_t warp_min_scan_down(std::int32_t v, int lane) {
  for (int o = 1; o < 32; o *= 2) {
    const std::int32_t u = __shfl_down_sync(0xffffffffu, v, o);
    if (lane + o < 32) v = min(v, u);
  }
  return v;
}

__global__ void x_seg_bounds(const std::uint32_t* feat, XSegs S) {
  const std::int64_t seg = (std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x) / 32;
  const int lane = threadIdx.x & 31;
  if (seg >= S.rows * S.per_row) return;
  const std::int64_t row = seg / S.per_row;
  const std::int32_t x0 = std::int32_t(seg % S.per_row) * S.seg_len;
  const std::int32_t x1 = min(x0 + S.seg_len, S.nx);
  const std::uint32_t* f = feat + row * S.nx;
  std::int32_t lo = 0x7fffffff, hi = -1;
  for (std::int32_t x = x0 + lane; x < x1; x += 32)
    if (f[x] != kNone) lo = min(lo, x), hi = max(hi, x);
  lo = __reduce_min_sync(0xffffffffu, lo);
  hi = __reduce_max_sync(0xffffffffu, hi);
  if (lane == 0) S.first[seg] = lo == 0x7fffffff ? -1 : lo, S.last[seg] = hi;
}

// Per row, turns (first, last) of each segment into (last site before it, first site after it).
__global__ void x_seg_carries(XSegs S) {
  const std::int64_t row = std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (row >= S.rows) return;
  std::int32_t* fi = S.first + row * S.per_row;
  std::int32_t* la = S.last + row * S.per_row;
  std::int32_t before = -1;
  for (std::int32_t k = 0; k < S.per_row; ++k) {  // last becomes "last site before segment k"
    const std::int32_t l = la[k];
    la[k] = before;
    if (l >= 0) before = l;
  }
  std::int32_t after = 0x7fffffff;
  for (std::int32_t k = S.per_row - 1; k >= 0; --k) {  // first becomes "first site after"
    const std::int32_t f = fi[k];
    fi[k] = after;
    if (f >= 0) after = f;
  }
}

template <int K>
__global__ void x_pass_segments(Layout L, std::uint32_t* feat, XSegs S) {
  const std::int64_t seg = (std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x) / 32;
  const int lane = threadIdx.x & 31;
  if (seg >= S.rows * S.per_row) return;  // whole warps leave together
  const std::int64_t row = seg / S.per_row;
  const std::int32_t x0 = std::int32_t(seg % S.per_row) * S.seg_len;
  const std::int32_t x1 = min(x0 + S.seg_len, S.nx);
  std::uint32_t* f = feat + row * S.nx;
  std::int32_t p[K];
#pragma unroll
  for (int k = 0; k < K; ++k) {
    const std::int32_t x = x0 + k * 32 + lane;
    p[k] = (x < x1 && f[x] != kNone) ? x : -1;
  }
  std::int32_t carry = S.per_row > 1 ? S.last[seg] : -1;
  std::int32_t left[K];
#pragma unroll
  for (int k = 0; k < K; ++k) {
    const std::int32_t v = max(warp_max_scan(p[k], lane), carry);
    carry = __shfl_sync(0xffffffffu, v, 31);
    left[k] = v;
  }
  const std::int32_t ny = std::int32_t(L.n[1]);
  const std::uint32_t y = std::uint32_t(row % ny), z = std::uint32_t(row / ny);
  carry = S.per_row > 1 ? S.first[seg] : 0x7fffffff;
#pragma unroll
  for (int k = K - 1; k >= 0; --k) {
    const std::int32_t r = min(warp_min_scan_down(p[k] >= 0 ? p[k] : 0x7fffffff, lane), carry);
    carry = __shfl_sync(0xffffffffu, r, 0);
    const std::int32_t x = x0 + k * 32 + lane;
    if (x < x1) {
      const std::int32_t l = left[k];
      std::int32_t s = -1;
      if (l >= 0 && r < S.nx)
        s = (x - l <= r - x) ? l : r;
      else if (l >= 0)
        s = l;
      else if (r < S.nx)
        s = r;
      f[x] = s < 0 ? kNone : L.pack(std::uint32_t(s), y, z);
    }
  }
}

template <int K>
void launch_x_segments(cudaStream_t st, const Layout& L, std::uint32_t* feat, const XSegs& S) {
  const std::int64_t blocks = (S.rows * S.per_row * 32 + 255) / 256;
  x_pass_segments<K><<<unsigned(blocks), 256, 0, st>>>(L, feat, S);
  GG_CUDA_CHECK_LAUNCH("x_pass_segments");
}

void x_pass_rows(Exec& ex, const Layout& L, const Metric&, const PassGeom&, std::uint32_t* feat,
                 std::uint32_t* scratch, std::int32_t*, std::int32_t*) {
  XSegs S;
  S.nx = std::int32_t(L.n[0]);
  S.rows = L.count() / L.n[0];
  // The smallest register tile (K steps of 32) that holds a whole row, up to 768 voxels: a row
  // just past a power of two (516 wide, say) then costs one more step, not a second segment
  // and the carry passes (measured: a 500x520x516 volume 25 % slower than 512^3 with 512-voxel
  // segments). Longer rows take 512-voxel segments.
  static constexpr int kTiles[] = {1, 2, 4, 8, 10, 12, 14, 16, 17, 18, 20, 22, 24};
  const int need = (S.nx + 31) / 32;
  int k = kSegK;
  for (int t : kTiles)
    if (t >= need) {
      k = t;
      break;
    }
  S.seg_len = 32 * k;
  S.per_row = (S.nx + S.seg_len - 1) / S.seg_len;
  const cudaStream_t st = ex.stream();
  if (S.per_row > 1) {  // 2 ints per segment: at most count/256 of the scratch's count
    S.first = reinterpret_cast<std::int32_t*>(scratch);
    S.last = S.first + S.rows * S.per_row;
    const std::int64_t blocks = (S.rows * S.per_row * 32 + 255) / 256;
    x_seg_bounds<<<unsigned(blocks), 256, 0, st>>>(feat, S);
    GG_CUDA_CHECK_LAUNCH("x_seg_bounds");
    x_seg_carries<<<unsigned((S.rows + 255) / 256), 256, 0, st>>>(S);
    GG_CUDA_CHECK_LAUNCH("x_seg_carries");
  } else {
    S.first = S.last = nullptr;
  }
  switch (k) {
    case 1:
      launch_x_segments<1>(st, L, feat, S);
      break;
    case 2:
      launch_x_segments<2>(st, L, feat, S);
      break;
    case 4:
      launch_x_segments<4>(st, L, feat, S);
      break;
    case 8:
      launch_x_segments<8>(st, L, feat, S);
      break;
    case 10:
      launch_x_segments<10>(st, L, feat, S);
      break;
    case 12:
      launch_x_segments<12>(st, L, feat, S);
      break;
    case 14:
      launch_x_segments<14>(st, L, feat, S);
      break;
    case 17:
      launch_x_segments<17>(st, L, feat, S);
      break;
    case 18:
      launch_x_segments<18>(st, L, feat, S);
      break;
    case 20:
      launch_x_segments<20>(st, L, feat, S);
      break;
    case 22:
      launch_x_segments<22>(st, L, feat, S);
      break;
    case 24:
      launch_x_segments<24>(st, L, feat, S);
      break;
    default:
      launch_x_segments<kSegK>(st, L, feat, S);
      break;
  }
}

// Passes along y and z on tiles: a block takes 32 neighbouring lines (consecutive x, so every
// global access is coalesced), loads them whole into shared memory with all loads in flight,
// and runs the banded algorithm there (bands stacks in place, merges, colouring) with a warp
// per band; only the colouring writes back to global memory. The stacks never leave the chip:
// the pass reads and writes each voxel once.
template <bool Iso>
__global__ void line_pass_tile_kernel(Layout L, Metric M, int a, std::int32_t len,
                                      std::int32_t bands, std::int32_t band_len,
                                      std::int64_t stride, const std::uint32_t* cand,
                                      std::uint32_t* out, const std::uint8_t* flags) {
  extern __shared__ std::uint32_t tile[];  // [position][lane], then lo[band][lane], hi[band][lane]
  std::int32_t* lo = reinterpret_cast<std::int32_t*>(tile + std::int64_t(len) * 32);
  std::int32_t* hi = lo + bands * 32;
  const int lane = threadIdx.x & 31, band = threadIdx.x >> 5;
  const std::int64_t nx = L.n[0], xblocks = (nx + 31) / 32;
  const std::int64_t x = (blockIdx.x % xblocks) * 32 + lane;
  const bool live = x < nx;
  const std::int64_t l = (blockIdx.x / xblocks) * nx + x;  // lines are numbered x fastest
  const std::int64_t base = live ? line_base(L, a, l) : 0;
  if (flags && !__syncthreads_or(live && flags[l])) return;  // none of the 32 lines is asked for
#pragma unroll 8
  for (std::int32_t p = band; p < len; p += bands)
    tile[p * 32 + lane] = live ? cand[base + p * stride] : kNone;
  __syncthreads();
  std::int64_t v[3];
  line_coords(L, a, live ? l : 0, v);
  const std::int32_t t0 = band * band_len, t1 = min(t0 + band_len, len);
  lo[band * 32 + lane] = 0;
  hi[band * 32 + lane] = t0 < t1 ? band_stack<Iso>(L, M, a, v, tile, tile, lane, 32, t0, t1) : 0;
  const Segs S{tile, lane, 32, band_len, 32, lane, lo, hi};
  for (std::int32_t width = 1; width < bands; width *= 2) {
    __syncthreads();
    const std::int32_t bl = band * 2 * width, br = bl + width;
    if (br < bands) merge_groups<Iso>(L, M, a, v, S, bl, br, min(br + width, bands));
  }
  __syncthreads();
  if (live && t0 < t1) colour_band<Iso>(L, M, a, v, S, bands, t0, t1, out, base, stride);
}

constexpr std::int64_t kTileSmemMax = 160 * 1024;  // leaves room for a second block per SM

bool line_pass_tiled(Exec& ex, const Layout& L, const Metric& M, int a, std::int64_t bands,
                     std::uint32_t* cand, std::uint32_t* out, const std::uint8_t* flags) {
  const std::int64_t len = L.n[a], nx = L.n[0];
  const std::int64_t lines = L.count() / len, blocks = lines / nx * ((nx + 31) / 32);
  int dev = 0, sms = 0;
  GG_CUDA_CHECK(cudaGetDevice(&dev));
  GG_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, dev));
  // Whole 32-line tiles must fit on chip, x rows must fill them, and there must be blocks
  // enough for every SM (a 2D grid's few long columns take the global banded pass).
  // GPUGEOM_EDT_TILES=0 never uses tiles, =1 whenever they fit (tests cover small grids so).
  const char* force = std::getenv("GPUGEOM_EDT_TILES");
  const int mode = force && *force ? std::atoi(force) : -1;
  if (a == 0 || mode == 0) return false;
  if (mode != 1 && (nx < 32 || blocks < 4 * sms)) return false;
  if (bands <= 0) {  // bands of about 64 positions, at most 16 (512 threads)
    bands = 1;
    while (bands < 16 && bands * 64 < len) bands *= 2;
  }
  bands = std::min<std::int64_t>(std::max<std::int64_t>(bands, 1), std::min<std::int64_t>(len, 32));
  const std::int64_t stride = L.stride(a);
  auto launch = [&](auto kernel) {
    // A warp per band: the block may not exceed what the kernel's registers allow (the
    // anisotropic variant needs more than 64 per thread, so 1024 threads do not fit).
    cudaFuncAttributes attr;
    GG_CUDA_CHECK(cudaFuncGetAttributes(&attr, kernel));
    while (bands > 1 && 32 * bands > attr.maxThreadsPerBlock) bands = (bands + 1) / 2;
    const std::int64_t band_len = (len + bands - 1) / bands;
    const std::int64_t smem = (len * 32 + 2 * bands * 32) * 4;
    if (smem > kTileSmemMax) return false;
    GG_CUDA_CHECK(
        cudaFuncSetAttribute(kernel, cudaFuncAttributeMaxDynamicSharedMemorySize, int(smem)));
    kernel<<<unsigned(blocks), unsigned(32 * bands), std::size_t(smem), ex.stream()>>>(
        L, M, a, std::int32_t(len), std::int32_t(bands), std::int32_t(band_len), stride, cand, out,
        flags);
    GG_CUDA_CHECK_LAUNCH("line_pass_tile_kernel");
    return true;
  };
  return M.iso ? launch(line_pass_tile_kernel<true>) : launch(line_pass_tile_kernel<false>);
}

#include "edt/impl/run.inl"
}  // namespace gpugeom::edt::cuda_impl
