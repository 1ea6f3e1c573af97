// Exact Euclidean distance transform by brute force (small grids only: O(voxels * sites)).
#include "verify_common.hpp"

namespace gpugeom::verify {

Report check_edt(const std::vector<std::int64_t>& shape, const std::vector<std::int64_t>& sites,
                 const std::int64_t* sqdist, const std::int32_t* nearest) {
  Report r;
  const int d = int(shape.size());
  if (d < 2 || d > 8) return r.fail("the grid must have 2 to 8 axes"), r;
  if (sites.empty() || sites.size() % d)
    return r.fail("no sites, or a site list not a multiple of the dimension"), r;
  const std::int64_t ns = std::int64_t(sites.size()) / d;
  std::int64_t total = 1;
  for (auto s : shape) total *= s;
  std::int64_t bad = -1;
  std::string why;
#pragma omp parallel for
  for (std::int64_t i = 0; i < total; ++i) {
    std::int64_t c[8], rem = i;
    for (int k = d - 1; k >= 0; --k) c[k] = rem % shape[k], rem /= shape[k];
    std::int64_t best = INT64_MAX;
    for (std::int64_t s = 0; s < ns; ++s) {
      std::int64_t q = 0;
      for (int k = 0; k < d; ++k) {
        const std::int64_t e = c[k] - sites[s * d + k];
        q += e * e;
      }
      best = q < best ? q : best;
    }
    bool ok = sqdist[i] == best;
    if (ok && nearest) {
      const std::int32_t s = nearest[i];
      if (s < 0 || s >= ns) {
        ok = false;
      } else {
        std::int64_t q = 0;
        for (int k = 0; k < d; ++k) {
          const std::int64_t e = c[k] - sites[s * d + k];
          q += e * e;
        }
        ok = q == best;
      }
    }
    if (!ok) {
#pragma omp critical
      if (bad < 0 || i < bad) {
        bad = i;
        why = "voxel " + std::to_string(i) + ": squared distance " + std::to_string(best) +
              " expected, got " + std::to_string(sqdist[i]) +
              (nearest ? ", nearest site " + std::to_string(nearest[i]) : "");
      }
    }
  }
  if (bad >= 0) return r.fail(why), r;
  r.notes.push_back("all " + std::to_string(total) + " voxels match the brute-force EDT");
  return r;
}

}  // namespace gpugeom::verify
