// The CUDA executor's banded pass on tiles in shared memory (pba.inl's line_pass_tiled), for
// whole grids and slices alike; included by edt_cuda.cu after pba.inl, once per site packing.

// Passes on tiles: a block takes 32 neighbouring lines (along y and z: consecutive x, so every
// global access is coalesced; along x, the x pass of slices: 32 rows, whose loads the L1 cache
// gathers), loads them whole into shared memory with all loads in flight, and runs the banded
// algorithm there (bands stacks in place, merges, colouring) with a warp per band; only the
// colouring writes back to global memory. The stacks never leave the chip: the pass reads and
// writes each voxel once.
template <bool Iso>
__global__ void line_pass_tile_kernel(Layout L, Metric M, int a, std::int32_t len,
                                      std::int32_t bands, std::int32_t band_len,
                                      std::int64_t stride, std::int64_t group,
                                      const std::uint32_t* cand, std::uint32_t* out,
                                      const std::uint8_t* flags) {
  extern __shared__ std::uint32_t tile[];  // [position][lane], then lo[band][lane], hi[band][lane]
  std::int32_t* lo = reinterpret_cast<std::int32_t*>(tile + std::int64_t(len) * 32);
  std::int32_t* hi = lo + bands * 32;
  const int lane = threadIdx.x & 31, band = threadIdx.x >> 5;
  // A block's 32 lines are consecutive within a group of `group` lines: a row of x for the y
  // and z passes (so loads are coalesced), every row for the x pass (each line its own row).
  const std::int64_t xblocks = (group + 31) / 32;
  const std::int64_t x = (blockIdx.x % xblocks) * 32 + lane;
  const bool live = x < group;
  const std::int64_t l = (blockIdx.x / xblocks) * group + x;
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
                     int tiles, std::uint32_t* cand, std::uint32_t* out,
                     const std::uint8_t* flags) {
  const std::int64_t len = L.n[a];
  const std::int64_t lines = L.count() / len, group = a == 0 ? lines : L.n[0];
  const std::int64_t blocks = lines / group * ((group + 31) / 32);
  const int dev = ex.device();
  int sms = 0;
  GG_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, dev));
  // Whole 32-line tiles must fit on chip, x rows must fill them, and there must be blocks
  // enough for every SM (a 2D grid's few long columns take the global banded pass).
  // tiles = 0 never uses tiles, 1 whenever they fit (tests cover small grids so).
  const int mode = tiles;
  if (mode == 0) return false;
  if (mode != 1 && (group < 32 || blocks < 4 * sms)) return false;
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
    // The device's opt-in limit per block (227 KB on the H100, 163 KB on an A100, 99 KB on
    // sm_86/89): lines whose tiles do not fit take the banded pass in global memory instead.
    int optin = 0;
    GG_CUDA_CHECK(cudaDeviceGetAttribute(&optin, cudaDevAttrMaxSharedMemoryPerBlockOptin, dev));
    if (smem > kTileSmemMax || smem + std::int64_t(attr.sharedSizeBytes) > optin) return false;
    GG_CUDA_CHECK(
        cudaFuncSetAttribute(kernel, cudaFuncAttributeMaxDynamicSharedMemorySize, int(smem)));
    kernel<<<unsigned(blocks), unsigned(32 * bands), std::size_t(smem), ex.stream()>>>(
        L, M, a, std::int32_t(len), std::int32_t(bands), std::int32_t(band_len), stride, group,
        cand, out, flags);
    GG_CUDA_CHECK_LAUNCH("line_pass_tile_kernel");
    return true;
  };
  return M.iso ? launch(line_pass_tile_kernel<true>) : launch(line_pass_tile_kernel<false>);
}
