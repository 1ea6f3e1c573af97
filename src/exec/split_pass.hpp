// The split fast/exact evaluation of thesis 6.3, for any executor, in up to three tiers.
//
// Pass 1 runs the filter for every item and writes its sign, or 0 when the filter cannot tell.
// The undecided items are compacted into a list, and pass 2 runs the next stage on that list
// only, so the common case is never slowed by the exact code's registers and divergence. The
// exact stages need scratch memory (about 24 KB per in-sphere test up to the translated tier,
// 111 KB for the full expansion); rather than give every GPU thread a local frame that size,
// a pass uses a bounded number of slots, each owning a slice of one global scratch buffer and
// striding over its list. With three tiers, pass 2 runs the middle stage (predicates.hpp's
// *_mid / *_sos_mid) on many small slots and may answer kUndecided; those items are compacted
// again and pass 3 runs the last stage on a few large slots.
//
// Deviation from the thesis: the lists are built by the executor's compaction (CUB select)
// instead of on-the-fly shared-memory compaction; one extra pass over n bytes.
#pragma once
#include <algorithm>
#include <cstdint>

#include "base/hd.hpp"
#include "predicates/translated.hpp"

namespace gpugeom {

struct SplitPassResult {
  std::int64_t exact_items = 0;  // how many items the filter could not decide
  std::int64_t last_items = 0;   // of those, how many the middle tier left to the last one
};

constexpr std::size_t kSplitPassScratchBudget = std::size_t(256) << 20;

namespace split_detail {
// Runs f(j, scratch) for every j < m on as many slots of `doubles` scratch as the budget and
// the executor's concurrency allow.
template <class Exec, class F>
void on_slots(Exec& ex, std::int64_t m, int doubles, std::size_t budget, F f) {
  const std::int64_t per_slot = std::int64_t(doubles) * std::int64_t(sizeof(double));
  std::int64_t slots = std::min<std::int64_t>(m, ex.concurrency());
  slots = std::max<std::int64_t>(1, std::min<std::int64_t>(slots, std::int64_t(budget) / per_slot));
  auto scratch = ex.template alloc<double>(std::size_t(slots) * doubles);
  double* sp = scratch.data();
  const std::int64_t nslots = slots;
  ex.for_each_index(
      nslots, GG_LAMBDA(std::int64_t t) {
        for (std::int64_t j = t; j < m; j += nslots) f(j, sp + t * doubles);
      });
  ex.sync();  // the scratch is released on return
}
}  // namespace split_detail

// Two tiers. fast(i) -> int in {-1, 0, 1}; exact(i, double* scratch) -> int. out has n entries.
template <class Exec, class Fast, class Exact>
SplitPassResult split_pass(Exec& ex, std::int64_t n, std::int8_t* out, Fast fast, Exact exact,
                           int scratch_doubles,
                           std::size_t scratch_budget_bytes = kSplitPassScratchBudget) {
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
  const std::int32_t* lp = list.data();
  split_detail::on_slots(
      ex, m, scratch_doubles, scratch_budget_bytes, GG_LAMBDA(std::int64_t j, double* s) {
        const std::int32_t i = lp[j];
        out[i] = std::int8_t(exact(i, s));
      });
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
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) { out[i] = std::int8_t(fast(i)); });
  auto list = ex.template alloc<std::int32_t>(std::size_t(n));
  const std::int8_t* o = out;
  const std::int64_t m = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return o[i] == 0; }, list.data());
  res.exact_items = m;
  if (m == 0) return res;
  const std::int32_t* lp = list.data();
  split_detail::on_slots(
      ex, m, mid_doubles, scratch_budget_bytes, GG_LAMBDA(std::int64_t j, double* s) {
        const std::int32_t i = lp[j];
        out[i] = std::int8_t(mid(i, s));
      });
  auto rest = ex.template alloc<std::int32_t>(std::size_t(m));
  const std::int64_t r = ex.compact_indices(
      m, GG_LAMBDA(std::int64_t j) { return o[lp[j]] == exact::kUndecided; }, rest.data());
  res.last_items = r;
  if (r == 0) return res;
  const std::int32_t* rp = rest.data();
  split_detail::on_slots(
      ex, r, last_doubles, scratch_budget_bytes, GG_LAMBDA(std::int64_t j, double* s) {
        const std::int32_t i = lp[rp[j]];
        out[i] = std::int8_t(last(i, s));
      });
  return res;
}

}  // namespace gpugeom
