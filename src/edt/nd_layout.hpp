// Grids of 4 to 8 axes (thesis 4.2.6: one line pass per axis, each over independent lines).
// A site is its voxel's raster index, so packed order is raster order and ties go to the first
// site in C order, as in 2D and 3D (edt_common.hpp). S, the index type, is uint32 where the grid
// has fewer than 2^32 - 1 voxels (coordinates decoded by multiply-high divisions), else uint64.
#pragma once
#include <cstdint>

#include "edt/edt_common.hpp"

namespace gpugeom::edt {

// The shape of an N-D request, internal axis order (axis 0 = C's last), as the entry checks it.
struct NdShape {
  int nd = 0;  // 0: not an N-D request
  std::int64_t n[kMaxAxes] = {1, 1, 1, 1, 1, 1, 1, 1};
  bool wide = false;  // 64-bit site indices
  std::int64_t count() const {
    std::int64_t c = 1;
    for (int k = 0; k < nd; ++k) c *= n[k];
    return c;
  }
};

template <class S>
struct NdLayout {
  static constexpr int kAxes = kMaxAxes;
  static constexpr S kNoSite = S(~S(0));
  int nd = 4;
  std::int64_t n[kMaxAxes] = {1, 1, 1, 1, 1, 1, 1, 1};
  std::int64_t stride[kMaxAxes] = {1, 1, 1, 1, 1, 1, 1, 1};
  Divider by[kMaxAxes];  // by n[k] (32-bit indices only)
  NdLayout() = default;
  explicit NdLayout(const NdShape& s) : nd(s.nd) {
    std::int64_t st = 1;
    for (int k = 0; k < nd; ++k) {
      n[k] = s.n[k];
      stride[k] = st;
      st *= n[k];
      by[k] = Divider::of(std::uint32_t(n[k] < 0xFFFFFFFF ? n[k] : 1));
    }
  }
  std::int64_t count() const { return stride[nd - 1] * n[nd - 1]; }
  // Every coordinate of site (or voxel) s.
  GG_INLINE void coords(S s, std::int64_t c[]) const {
    for (int k = 0; k < nd - 1; ++k) {
      S q;
      if constexpr (sizeof(S) == 4)
        q = by[k].div(s);
      else
        q = s / S(n[k]);
      c[k] = std::int64_t(s - q * S(n[k]));
      s = q;
    }
    c[nd - 1] = std::int64_t(s);
  }
  GG_INLINE std::int64_t coord(S s, int a) const {
    for (int k = 0; k < a; ++k) {
      if constexpr (sizeof(S) == 4)
        s = by[k].div(s);
      else
        s = s / S(n[k]);
    }
    if (a == nd - 1) return std::int64_t(s);
    S q;
    if constexpr (sizeof(S) == 4)
      q = by[a].div(s);
    else
      q = s / S(n[a]);
    return std::int64_t(s - q * S(n[a]));
  }
  GG_INLINE std::int64_t voxel_of(S s) const { return std::int64_t(s); }
  GG_INLINE bool before(S q, S p) const { return q < p; }
};

}  // namespace gpugeom::edt
