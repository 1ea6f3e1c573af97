// The split fast/exact evaluation of thesis 6.3, for any executor, in up to three tiers.
//
// Pass 1 runs the filter for every item and writes its sign, or 0 when the filter cannot tell.
// The undecided items are compacted into a list, and pass 2 runs the next stage on that list
// only, so the common case is never slowed by the exact code's registers and divergence. The
// exact stages need scratch memory (23.9 KB per in-sphere test up to the translated tier,
// 114.1 KB for the full expansion), on a bounded number of slots (exec/scratch_slots.hpp). With
// three tiers, pass 2 runs the middle stage (predicates.hpp's
// *_mid / *_sos_mid) on many small slots and may answer kUndecided; those items are compacted
// again and pass 3 runs the last stage on a few large slots.
//
// Deviation from the thesis: the lists are built by the executor's compaction (CUB select)
// instead of on-the-fly shared-memory compaction; one extra pass over n bytes.
#pragma once
#include <algorithm>
#include <cstdint>

#include "base/hd.hpp"
#include "exec/scratch_slots.hpp"
#include "predicates/translated.hpp"

namespace gpugeom {

struct SplitPassResult {
  std::int64_t exact_items = 0;  // how many items the filter could not decide
  std::int64_t last_items = 0;   // of those, how many the middle tier left to the last one
};

constexpr std::size_t kSplitPassScratchBudget = std::size_t(256) << 20;

namespace split_detail {
// Pass 1: the filter's sign for every item; the items it left (0) listed. Returns their count.
template <class Exec, class Fast>
std::int64_t filter(Exec& ex, std::int64_t n, std::int8_t* out, Fast fast, std::int32_t* list) {
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) { out[i] = std::int8_t(fast(i)); });
  const std::int8_t* o = out;
  return ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return o[i] == 0; }, list);
}
// A later pass: stage(i, scratch) for the m listed items, its result written over theirs.
template <class Exec, class Stage>
void on_list(Exec& ex, const std::int32_t* list, std::int64_t m, int doubles, std::size_t budget,
             std::int8_t* out, Stage stage) {
  if (m <= 0) return;
  // No wait: the scratch is released in stream order (CUDA) or after the synchronous loop
  // (CPU), and the next pass's compaction waits anyway.
  ScratchSlots<Exec>(ex, m, doubles, budget)
      .run(
          ex, m, GG_LAMBDA(std::int64_t j, double* s) {
            const std::int32_t i = list[j];
            out[i] = std::int8_t(stage(i, s));
          });
}
}  // namespace split_detail

// Two tiers. fast(i) -> int in {-1, 0, 1}; exact(i, double* scratch) -> int. out has n entries.
template <class Exec, class Fast, class Exact>
SplitPassResult split_pass(Exec& ex, std::int64_t n, std::int8_t* out, Fast fast, Exact exact,
                           int scratch_doubles,
                           std::size_t scratch_budget_bytes = kSplitPassScratchBudget) {
  SplitPassResult res;
  if (n <= 0) return res;
  auto list = ex.template alloc<std::int32_t>(std::size_t(n));
  res.exact_items = split_detail::filter(ex, n, out, fast, list.data());
  split_detail::on_list(ex, list.data(), res.exact_items, scratch_doubles, scratch_budget_bytes,
                        out, exact);
  ex.sync();  // [synchronises] the signs are final on return
  return res;
}

// Three tiers: mid(i, s) -> {-1, 0, 1} or exact::kUndecided with mid_doubles of scratch;
// last(i, s) -> {-1, 0, 1} with last_doubles, run only where mid was undecided.
template <class Exec, class Fast, class Mid, class Last>
SplitPassResult split_pass(Exec& ex, std::int64_t n, std::int8_t* out, Fast fast, Mid mid,
                           int mid_doubles, Last last, int last_doubles,
                           std::size_t scratch_budget_bytes = kSplitPassScratchBudget) {
  SplitPassResult res;
  if (n <= 0) return res;
  auto list = ex.template alloc<std::int32_t>(std::size_t(n));
  const std::int64_t m = res.exact_items = split_detail::filter(ex, n, out, fast, list.data());
  if (m == 0) return res;
  split_detail::on_list(ex, list.data(), m, mid_doubles, scratch_budget_bytes, out, mid);
  // The items the middle tier left, as item numbers (compacted positions in list, mapped back).
  auto rest = ex.template alloc<std::int32_t>(std::size_t(m));
  const std::int8_t* o = out;
  const std::int32_t* lp = list.data();
  std::int32_t* rp = rest.data();
  const std::int64_t r = res.last_items = ex.compact_indices(
      m, GG_LAMBDA(std::int64_t j) { return o[lp[j]] == exact::kUndecided; }, rp);
  if (r == 0) return res;
  ex.for_each_index(
      r, GG_LAMBDA(std::int64_t j) { rp[j] = lp[rp[j]]; });
  split_detail::on_list(ex, rp, r, last_doubles, scratch_budget_bytes, out, last);
  ex.sync();  // [synchronises] the signs are final on return
  return res;
}

}  // namespace gpugeom
