// The split fast/exact evaluation of thesis 6.3, for any executor.
//
// Pass 1 runs the filter for every item and writes its sign, or 0 when the filter cannot tell.
// The undecided items are compacted into a list, and pass 2 runs the exact (or SoS) stage on
// that list only, so the common case is never slowed by the exact code's registers and
// divergence. The exact stage needs large scratch (up to ~100 KB for in-sphere); rather than
// give every GPU thread a local frame that size, pass 2 uses a bounded number of slots, each
// owning a slice of one global scratch buffer and striding over the list.
//
// Deviation from the thesis: the list is built by the executor's compaction (CUB select)
// instead of on-the-fly shared-memory compaction; one extra pass over n bytes.
#pragma once
#include <algorithm>
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom {

struct SplitPassResult {
  std::int64_t exact_items = 0;  // how many items the filter could not decide
};

// fast(i) -> int in {-1, 0, 1}; exact(i, double* scratch) -> int. out has n entries.
template <class Exec, class Fast, class Exact>
SplitPassResult split_pass(Exec& ex, std::int64_t n, std::int8_t* out, Fast fast, Exact exact,
                           int scratch_doubles,
                           std::size_t scratch_budget_bytes = std::size_t(256) << 20) {
  SplitPassResult res;
  if (n <= 0) return res;
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) { out[i] = std::int8_t(fast(i)); });
  auto list = ex.template alloc<std::int32_t>(std::size_t(n));
  const std::int8_t* o = out;
  const std::int64_t m = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return o[i] == 0; }, list.data());
  res.exact_items = m;
  if (m == 0) return res;
  const std::int64_t per_slot = std::int64_t(scratch_doubles) * std::int64_t(sizeof(double));
  std::int64_t slots = std::min<std::int64_t>(m, ex.concurrency());
  slots = std::max<std::int64_t>(
      1, std::min<std::int64_t>(slots, std::int64_t(scratch_budget_bytes) / per_slot));
  auto scratch = ex.template alloc<double>(std::size_t(slots) * scratch_doubles);
  const std::int32_t* lp = list.data();
  double* sp = scratch.data();
  const std::int64_t nslots = slots;
  ex.for_each_index(
      nslots, GG_LAMBDA(std::int64_t t) {
        for (std::int64_t j = t; j < m; j += nslots) {
          const std::int32_t i = lp[j];
          out[i] = std::int8_t(exact(i, sp + t * scratch_doubles));
        }
      });
  ex.sync();
  return res;
}

}  // namespace gpugeom
