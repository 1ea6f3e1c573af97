// The CUDA executor's own passes of a whole grid (the x pass over ballot bits, the windowed
// pass); included by edt_cuda.cu after grid_transform.inl, once for each site packing.

// The x pass: a row is cut into segments of up to 32*K voxels and each warp holds one segment
// as bits in registers (K coalesced loads per lane, all in flight at once); each voxel takes
// the nearer of the nearest sites at or left of it and at or right of it (ties: the left one,
// the smaller x). The sites are read once (a byte per voxel from a mask) and the row written
// once. Rows longer than one segment first get, per segment, the last site before it and the
// first site after it (x_seg_bounds + x_seg_carries).
constexpr int kSegK = 32;  // 1024 voxels per segment: 32 loads in flight per lane

struct XSegs {
  std::int64_t rows;
  std::int32_t nx, per_row, seg_len;
  std::int32_t* first;  // per segment: first / last site x in it (-1: none); then carries
  std::int32_t* last;
};

// Where the x pass finds its sites: a byte mask (a quarter of the feature array's bytes) or
// the packed features themselves.
struct MaskSites {
  const std::uint8_t* m;
  __device__ bool operator()(std::int64_t i) const { return m[i] != 0; }
};
struct FeatSites {
  const std::uint32_t* f;
  __device__ bool operator()(std::int64_t i) const { return f[i] != kNone; }
};

template <class Src>
__global__ void x_seg_bounds(Src src, XSegs S) {
  const std::int64_t seg = (std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x) / 32;
  const int lane = threadIdx.x & 31;
  if (seg >= S.rows * S.per_row) return;
  const std::int64_t row = seg / S.per_row;
  const std::int32_t x0 = std::int32_t(seg % S.per_row) * S.seg_len;
  const std::int32_t x1 = min(x0 + S.seg_len, S.nx);
  const std::int64_t r0 = row * S.nx;
  std::int32_t lo = 0x7fffffff, hi = -1;
  for (std::int32_t x = x0 + lane; x < x1; x += 32)
    if (src(r0 + x)) lo = min(lo, x), hi = max(hi, x);
  lo = __reduce_min_sync(0xffffffffu, lo);
  hi = __reduce_max_sync(0xffffffffu, hi);
  if (lane == 0) S.first[seg] = lo == 0x7fffffff ? -1 : lo, S.last[seg] = hi;
}

// Over a warp's lanes: the largest `last` on the lanes before this one (-1 if none) and the
// smallest `first` on the lanes after it (0x7fffffff if none).
__device__ __forceinline__ void warp_neighbours(std::int32_t last, std::int32_t first, int lane,
                                                std::int32_t& before, std::int32_t& after) {
  for (int o = 1; o < 32; o *= 2) {  // inclusive scans: max from the left, min from the right
    const std::int32_t u = __shfl_up_sync(0xffffffffu, last, o);
    const std::int32_t w = __shfl_down_sync(0xffffffffu, first, o);
    if (lane >= o) last = max(last, u);
    if (lane + o < 32) first = min(first, w);
  }
  const std::int32_t up = __shfl_up_sync(0xffffffffu, last, 1);
  const std::int32_t down = __shfl_down_sync(0xffffffffu, first, 1);
  before = lane > 0 ? up : -1;
  after = lane < 31 ? down : 0x7fffffff;
}

// Per row, turns (first, last) of each segment into (last site before it, first site after
// it): a warp per row, 32 segments at a time (a thread per row walked them one by one, 41 us
// for the 1000 rows of a 1000 x 67108 grid on the H100).
__global__ void x_seg_carries(XSegs S) {
  const std::int64_t row = (std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x) / 32;
  const int lane = threadIdx.x & 31;
  if (row >= S.rows) return;  // whole warps leave together
  std::int32_t* fi = S.first + row * S.per_row;
  std::int32_t* la = S.last + row * S.per_row;
  std::int32_t carry = -1;  // last site of the chunks to the left
  for (std::int32_t k0 = 0; k0 < S.per_row; k0 += 32) {
    const std::int32_t k = k0 + lane;
    const std::int32_t l = k < S.per_row ? la[k] : -1;
    std::int32_t before, after;
    warp_neighbours(l, 0x7fffffff, lane, before, after);
    if (k < S.per_row) la[k] = max(before, carry);
    carry = max(carry, __reduce_max_sync(0xffffffffu, l));
  }
  carry = 0x7fffffff;  // first site of the chunks to the right
  for (std::int32_t k0 = (S.per_row - 1) / 32 * 32; k0 >= 0; k0 -= 32) {
    const std::int32_t k = k0 + lane;
    const std::int32_t f = k < S.per_row && fi[k] >= 0 ? fi[k] : 0x7fffffff;
    std::int32_t before, after;
    warp_neighbours(-1, f, lane, before, after);
    if (k < S.per_row) fi[k] = min(after, carry);
    carry = min(carry, __reduce_min_sync(0xffffffffu, f));
  }
}

// A warp per segment of 32*K voxels. The k-th coalesced load of the warp (offsets k*32 + lane)
// becomes one ballot word, so the segment's sites are K words of bits (one register a lane,
// where the position scans this replaces held K positions: 34 registers instead of 80, and a
// few shuffles per 32 voxels instead of ten). A voxel's nearest site on the left is then the
// highest set bit at or below it in its word, else the last site of the words before (or the
// carry from earlier segments); on the right, the lowest set bit at or above it, else the
// first site of the words after. Reads every site of the segment before writing: out may be
// the features src reads.
template <int K, class Src>
__global__ void x_pass_segments(Layout L, Src src, std::uint32_t* out, XSegs S) {
  const std::int64_t seg = (std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x) / 32;
  const int lane = threadIdx.x & 31;
  if (seg >= S.rows * S.per_row) return;  // whole warps leave together
  const std::int64_t row = seg / S.per_row;
  const std::int32_t x0 = std::int32_t(seg % S.per_row) * S.seg_len;
  const std::int32_t x1 = min(x0 + S.seg_len, S.nx);
  const std::int64_t r0 = row * S.nx;
  bool site[K];  // every load in flight before the first ballot waits for one
#pragma unroll
  for (int k = 0; k < K; ++k) {
    const std::int32_t x = x0 + k * 32 + lane;
    site[k] = x < x1 && src(r0 + x);
  }
  std::uint32_t mine = 0;  // lane j < K keeps word j
#pragma unroll
  for (int k = 0; k < K; ++k) {
    const std::uint32_t b = __ballot_sync(0xffffffffu, site[k]);
    if (lane == k) mine = b;
  }
  // Lane j < K owns word j: the last site before it and the first site after it come from
  // one exclusive scan each over the lanes (carries from the other segments at the ends), and
  // each word is broadcast with its pair when its voxels are written (K words or positions
  // held in every lane's registers would cost warps per SM).
  const std::int32_t wbase = x0 + lane * 32;
  std::int32_t before_w, after_w;
  warp_neighbours(mine ? wbase + 31 - __clz(mine) : -1, mine ? wbase + __ffs(mine) - 1 : 0x7fffffff,
                  lane, before_w, after_w);
  if (S.per_row > 1) before_w = max(before_w, S.last[seg]), after_w = min(after_w, S.first[seg]);
  const std::uint32_t at_or_below = 0xffffffffu >> (31 - lane), at_or_above = 0xffffffffu << lane;
  const std::int32_t ny = std::int32_t(L.n[1]);
  const std::uint32_t y = std::uint32_t(row % ny), z = std::uint32_t(row / ny);
  std::uint32_t* f = out + r0;
#pragma unroll
  for (int k = 0; k < K; ++k) {
    const std::int32_t x = x0 + k * 32 + lane, base = x0 + k * 32;
    const std::int32_t before = __shfl_sync(0xffffffffu, before_w, k);
    const std::int32_t after = __shfl_sync(0xffffffffu, after_w, k);
    const std::uint32_t word = __shfl_sync(0xffffffffu, mine, k);
    const std::uint32_t lo = word & at_or_below, hi = word & at_or_above;
    const std::int32_t l = lo ? base + 31 - __clz(lo) : before;
    const std::int32_t r = hi ? base + __ffs(hi) - 1 : after;
    if (x < x1) {
      std::int32_t s = -1;  // ties: the left one, the smaller x
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

template <int K, class Src>
void launch_x_segments(cudaStream_t st, const Layout& L, Src src, std::uint32_t* out,
                       const XSegs& S) {
  const std::int64_t blocks = (S.rows * S.per_row * 32 + 255) / 256;
  x_pass_segments<K><<<unsigned(blocks), 256, 0, st>>>(L, src, out, S);
  GG_CUDA_CHECK_LAUNCH("x_pass_segments");
}

template <class Src>
void x_pass_from(Exec& ex, const Layout& L, Src src, std::uint32_t* out, std::uint32_t* scratch) {
  XSegs S;
  S.nx = std::int32_t(L.n[0]);
  S.rows = L.count() / L.n[0];
  // The smallest register tile (K steps of 32) that holds a whole row, up to 1024 voxels: a row
  // just past a power of two (516 wide, say) then costs one more step, not a second segment
  // and the carry passes (measured: a 500x520x516 volume 25 % slower than 512^3 with 512-voxel
  // segments). Longer rows take 1024-voxel segments.
  static constexpr int kTiles[] = {1, 2, 4, 8, 10, 12, 14, 16, 17, 18, 20, 22, 24, 28, 32};
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
    x_seg_bounds<<<unsigned(blocks), 256, 0, st>>>(src, S);
    GG_CUDA_CHECK_LAUNCH("x_seg_bounds");
    x_seg_carries<<<unsigned((S.rows * 32 + 255) / 256), 256, 0, st>>>(S);
    GG_CUDA_CHECK_LAUNCH("x_seg_carries");
  } else {
    S.first = S.last = nullptr;
  }
  switch (k) {
    case 1:
      return launch_x_segments<1>(st, L, src, out, S);
    case 2:
      return launch_x_segments<2>(st, L, src, out, S);
    case 4:
      return launch_x_segments<4>(st, L, src, out, S);
    case 8:
      return launch_x_segments<8>(st, L, src, out, S);
    case 10:
      return launch_x_segments<10>(st, L, src, out, S);
    case 12:
      return launch_x_segments<12>(st, L, src, out, S);
    case 14:
      return launch_x_segments<14>(st, L, src, out, S);
    case 16:
      return launch_x_segments<16>(st, L, src, out, S);
    case 17:
      return launch_x_segments<17>(st, L, src, out, S);
    case 18:
      return launch_x_segments<18>(st, L, src, out, S);
    case 20:
      return launch_x_segments<20>(st, L, src, out, S);
    case 22:
      return launch_x_segments<22>(st, L, src, out, S);
    case 24:
      return launch_x_segments<24>(st, L, src, out, S);
    case 28:
      return launch_x_segments<28>(st, L, src, out, S);
    default:
      return launch_x_segments<kSegK>(st, L, src, out, S);
  }
}

void x_pass_rows(Exec& ex, const Layout& L, const Metric&, const PassGeom&,
                 const std::uint8_t* mask, const std::uint32_t* in, std::uint32_t* out,
                 std::uint32_t* scratch, std::int32_t*, std::int32_t*) {
  if (mask)
    x_pass_from(ex, L, MaskSites{mask}, out, scratch);
  else
    x_pass_from(ex, L, FeatSites{in}, out, scratch);
}

// The windowed pass (pba.inl, window_pass_t) as a kernel of its own. Each thread takes T
// consecutive voxels of one line, positions t0 .. t0+T-1, and widens one window around all of
// them: each step loads the two positions just outside it and tests each candidate against
// all T voxels, its distance to the line (the other axes) computed once. So a step costs two
// loads and two decodes for T voxels, where a thread per voxel paid that for each. A voxel is
// settled once d*d exceeds its best cost, d being the distance every position not yet seen
// lies from it (everything nearer was seen: the window reaches at least d-1 past both ends).
// Blocks are 32 x 8 threads (x fastest, so every load is a coalesced row), ordered so that
// the rows a window reads are still in L2 when the next blocks read them (the generic loop
// strides the grid with a fixed number of blocks, and each wave of them re-read most of the
// array from DRAM: 4.1 GB read for a 1 GB array at 16384^2, measured). The axis and dimension
// are template arguments, so coordinates stay in registers, and a candidate's cost and its
// packed site form one 64-bit key: the nearest site with ties to the smaller packed value is
// the minimum key. H100, 10 % sites: 6 blocks per SM (40 registers) and the z-fastest order
// along z took 1024^3 from 21.0 to 18.4 ms and 16384^2 from 2.97 to 2.77 ms; then loading the
// first step's two positions with the thread's own four, and dropping the z term where every
// candidate lies in the voxel's plane (the y pass of a whole volume), 1024^3 17.9 -> 17.1 ms.
// A candidate's (cost, site) as the window kernel orders them. Narrow: costs in 32 bits, so
// both fit one 64-bit integer (cost in the high word) and the order is one comparison; exact
// where every cost the window can meet is below 2^32 - 1 (none's cost word). Where it is not
// (a row longer than 2^16, e.g. 1000 x 67108), Clamped counts a coordinate difference as at
// most M = 32767: a cost below M^2 stays exact, a larger one stays at least M^2, and none
// overflows (two clamped squares and d^2 are below 2^32 - 1). A voxel whose best is below
// M^2 is then decided exactly; one whose best is not never settles (d <= reach + 1 <= M)
// and, as its window cannot span its line (len > T + 2 * reach, checked on the host), flags
// the line for the exact banded pass. Wide keeps 64-bit costs for the rest (short lines in
// such grids).
template <bool Clamped>
struct NarrowKey {
  using T = std::uint64_t;
  using C = std::uint32_t;  // cost arithmetic: 32-bit (a third of the instructions of 64-bit)
  static constexpr std::int32_t kM = 32767;
  static constexpr T none() { return ~T(0); }
  __device__ static C square_add(C c, std::int32_t e) {
    if (Clamped) e = min(abs(e), kM);
    return c + C(e) * C(e);  // wraps for e < 0, squares right
  }
  __device__ static T make(C c, std::uint32_t s) { return std::uint64_t(c) << 32 | s; }
  __device__ static T add(T k, C d2) { return k + (std::uint64_t(d2) << 32); }
  __device__ static T least(T a, T b) { return a < b ? a : b; }
  // Nothing at squared distance d2 or more can beat k (never true of none).
  __device__ static bool beyond(C d2, T k) { return std::uint64_t(d2) << 32 > k; }
  static constexpr int kBlocks = 6;  // per SM: 40 registers
  __device__ static std::uint32_t site(T k) { return std::uint32_t(k); }
  __device__ static bool is_none(T k) { return k == none(); }
};
struct WideKey {
  struct T {
    std::uint64_t c;
    std::uint32_t s;
  };
  using C = std::uint64_t;
  static constexpr T none() { return {~std::uint64_t(0), kNone}; }
  __device__ static C square_add(C c, std::int32_t e) { return c + C(std::int64_t(e) * e); }
  __device__ static T make(std::uint64_t c, std::uint32_t s) { return {c, s}; }
  __device__ static T add(T k, std::uint64_t d2) { return {k.c + d2, k.s}; }
  __device__ static T least(T a, T b) { return a.c < b.c || (a.c == b.c && a.s < b.s) ? a : b; }
  __device__ static bool beyond(C d2, T k) { return d2 > k.c; }
  static constexpr int kBlocks = 4;  // per SM: 64 registers, as 40 spill
  __device__ static std::uint32_t site(T k) { return k.s; }
  __device__ static bool is_none(T k) { return k.s == kNone; }
};

constexpr std::uint32_t kWinRows = 8;  // threadIdx.y: groups along y (A = 1) or y (A = 2)

template <int ND, int A, int T, class Key, bool InPlane>
__global__ void __launch_bounds__(256, Key::kBlocks)
    window_kernel(Layout L, std::int32_t R, std::uint32_t xtiles, std::uint32_t nb1,
                  std::uint32_t ngroups, const std::uint32_t* __restrict__ cand, std::uint32_t* out,
                  std::uint8_t* flags) {
  // Block order: x tiles fastest, then (A = 1) groups along y, then z; or (A = 2) groups along z
  // fastest, then x tiles, then y, so that a group's window rows (whole planes apart) are read
  // again by the next block, not a plane's worth of blocks later.
  const std::uint32_t bb = blockIdx.x;
  const std::uint32_t b = A == 2 ? bb / ngroups : bb;
  const std::uint32_t rest = b / xtiles, b1 = A == 2 ? rest : rest % nb1;
  const std::uint32_t b2 = A == 2 ? bb % ngroups : rest / nb1;
  const std::uint32_t nx = std::uint32_t(L.n[0]), ny = std::uint32_t(L.n[1]);
  const std::uint32_t x = (b - rest * xtiles) * 32 + threadIdx.x;
  // A = 1: threadIdx.y and b1 pick the group along y, b2 is z. A = 2: they pick y, b2 the
  // group along z.
  const std::uint32_t u = b1 * kWinRows + threadIdx.y;
  const std::uint32_t g = A == 1 ? u : b2;
  const std::uint32_t y = A == 1 ? g * T : u, z = A == 1 ? b2 : g * T;
  const std::int32_t len = std::int32_t(L.n[A]);
  if (x >= nx || (A == 1 ? y : z) >= std::uint32_t(len) || (A == 2 && y >= ny)) return;
  const std::int32_t v[3] = {std::int32_t(x), std::int32_t(y), std::int32_t(z)};
  const std::int32_t t0 = std::int32_t(A == 1 ? y : z);
  const std::int64_t stride = A == 1 ? std::int64_t(nx) : std::int64_t(nx) * ny;
  const std::uint32_t* c0 = cand + (std::int64_t(z) * ny + y) * nx + x;  // position t0
  const std::int32_t n = min(T, len - t0);                               // voxels held
  using K = typename Key::T;
  // A candidate's squared distance to the line (the other axes) with its site.
  using C = typename Key::C;
  auto line_key = [&](std::uint32_t s) {
    C c = 0;
#pragma unroll
    for (int k = 0; k < ND; ++k)
      if (k != A && !(InPlane && k == 2)) {
        c = Key::square_add(c, std::int32_t(L.coord(s, k)) - v[k]);
      }
    return s == kNone ? Key::none() : Key::make(c, s);
  };
  // Candidate at offset p (from t0) to voxel j: its line key plus (p - j)^2. kNone's key is
  // never offered (adding a distance would wrap it).
  auto offer = [](K& best, K k, std::int32_t dist) {
    best = Key::least(best, Key::add(k, C(dist) * C(dist)));
  };
  // The first step's two positions are needed by nearly every thread: loaded with its own.
  const std::uint32_t pre_l = R >= 1 && t0 >= 1 ? c0[-stride] : kNone;
  const std::uint32_t pre_h = R >= 1 && t0 + n < len ? c0[n * stride] : kNone;
  K best[T];
#pragma unroll
  for (int j = 0; j < T; ++j) best[j] = Key::none();
#pragma unroll
  for (int p = 0; p < T; ++p)
    if (p < n) {
      const K k = line_key(c0[p * stride]);
#pragma unroll
      for (int j = 0; j < T; ++j)
        if (!Key::is_none(k)) offer(best[j], k, p - j);
    }
  auto settled = [&](std::int32_t d) {
    bool all = true;
#pragma unroll
    for (int j = 0; j < T; ++j) all = all && (j >= n || Key::beyond(C(d) * C(d), best[j]));
    return all;
  };
  auto finish = [&]() {
#pragma unroll
    for (int j = 0; j < T; ++j)
      if (j < n) out[c0 - cand + j * stride] = Key::site(best[j]);
  };
  std::int32_t d = 1;
  for (; d <= R; ++d) {
    if (settled(d)) return finish();
    const std::int32_t lo = t0 - d, hi = t0 + n - 1 + d;
    const std::uint32_t rl = d == 1 ? pre_l : (lo >= 0 ? c0[-d * stride] : kNone);
    const std::uint32_t rh = d == 1 ? pre_h : (hi < len ? c0[(n - 1 + d) * stride] : kNone);
    const K kl = line_key(rl);
    const K kh = line_key(rh);
#pragma unroll
    for (int j = 0; j < T; ++j) {
      if (!Key::is_none(kl)) offer(best[j], kl, d + j);
      if (!Key::is_none(kh)) offer(best[j], kh, n - 1 + d - j);
    }
  }
  // Settled, or the whole line seen (kNone where it holds no site at all).
  if (settled(d) || (t0 - R <= 0 && t0 + n - 1 + R >= len - 1)) return finish();
  flags[A == 1 ? z * nx + x : y * nx + x] = 1;  // every writer writes 1
}

template <int ND, int A, int T, class Key>
void launch_window(Exec& ex, const Layout& L, std::int32_t R, const std::uint32_t* cand,
                   std::uint32_t* out, std::uint8_t* flags, bool in_plane) {
  const std::uint32_t nx = std::uint32_t(L.n[0]), ny = std::uint32_t(L.n[1]);
  const std::uint32_t nz = std::uint32_t(L.n[2]), xtiles = (nx + 31) / 32;
  const std::uint32_t groups = ((A == 1 ? ny : nz) + T - 1) / T;
  const std::uint32_t nb1 = ((A == 1 ? groups : ny) + kWinRows - 1) / kWinRows;
  const std::uint64_t blocks = std::uint64_t(xtiles) * nb1 * (A == 1 ? nz : groups);
  auto go = [&](auto kernel) {
    kernel<<<unsigned(blocks), dim3(32, kWinRows), 0, ex.stream()>>>(L, R, xtiles, nb1, groups,
                                                                     cand, out, flags);
  };
  if constexpr (A == 1 && ND == 3) {
    if (in_plane)
      go(window_kernel<ND, A, T, Key, true>);
    else
      go(window_kernel<ND, A, T, Key, false>);
  } else {
    go(window_kernel<ND, A, T, Key, false>);
  }
  GG_CUDA_CHECK_LAUNCH("window_kernel");
}

bool window_pass_kernel(Exec& ex, const Layout& L, int a, std::int64_t R, const std::uint32_t* cand,
                        std::uint32_t* out, std::uint8_t* flags, bool in_plane) {
  if (L.nd < 2 || a < 1 || a >= L.nd) return false;
  // Past len - 1 every window already spans its whole line; so d stays below 2^16 where the
  // keys are narrow, and d * d fits their 32-bit costs.
  if (R > L.n[a] - 1) R = L.n[a] - 1;
  // 4 voxels a thread: measured on the H100 at 10 % sites against 1, 2 and 8 (8192^2 1.05 /
  // 0.83 / 0.81 / 0.93 ms for 1 / 2 / 4 / 8; 1024^3 28.6 / 21.2 / 20.8 / 22.0 ms).
  constexpr int T = 4;
  const std::int32_t reach = std::int32_t(R);
  auto launch = [&](auto key) {
    using Key = decltype(key);
    if (L.nd == 2)
      launch_window<2, 1, T, Key>(ex, L, reach, cand, out, flags, in_plane);
    else if (a == 1)
      launch_window<3, 1, T, Key>(ex, L, reach, cand, out, flags, in_plane);
    else
      launch_window<3, 2, T, Key>(ex, L, reach, cand, out, flags, in_plane);
  };
  // The largest cost the window can meet: its farthest position along the line, and the
  // farthest any site can lie from the line.
  const std::uint64_t along = std::uint64_t(std::min<std::int64_t>(L.n[a] - 1, R + T - 1));
  std::uint64_t most = along * along;
  for (int k = 0; k < L.nd; ++k)
    if (k != a) most += std::uint64_t(L.n[k] - 1) * std::uint64_t(L.n[k] - 1);
  if (most < 0xffffffffull)
    launch(NarrowKey<false>{});
  else if (L.n[a] > T + 2 * R && R + 1 <= NarrowKey<true>::kM)
    launch(NarrowKey<true>{});
  else
    launch(WideKey{});
  return true;
}
