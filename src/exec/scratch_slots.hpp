// Exact stages on a bounded number of scratch slots, for every module with an exact pass
// (split_pass, delaunay2d's flip rounds, hull3d's construction and Flip-Flop).
//
// An exact predicate needs kilobytes of scratch (predicates.hpp gives the doubles per test).
// Rather than give every GPU thread a local frame that size, a pass runs on a bounded number of
// slots, each owning a slice of one buffer, and each slot strides over the pass's items: slot t
// takes items t, t + slots, ... The items are few (what the filter could not decide), so fewer
// threads than items cost little, and the buffer stays a fixed size however long the list.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom {

// Slots of one scratch buffer, as device code sees them.
struct SlotView {
  double* base = nullptr;
  std::int64_t slots = 0;
  std::int64_t doubles = 0;  // per slot
  GG_HD double* operator[](std::int64_t t) const { return base + t * doubles; }
};

// A pass length read on the executor: per * min(*at, cap).
struct CountAt {
  const std::int64_t* at;
  std::int64_t per = 1;
  std::int64_t cap = INT64_MAX;
  GG_HD std::int64_t operator()() const { return per * (*at < cap ? *at : cap); }
};

// (kernel argument types must be at namespace scope, not private members)
namespace slots_detail {
struct Fixed {
  std::int64_t m;
  GG_HD std::int64_t operator()() const { return m; }
};
struct NoOnce {
  GG_HD void operator()() const {}
};
// Thread t of `threads` (at most the slots) takes items t, t + threads, ...; thread 0 first
// runs once().
template <class F, class Count, class Once>
struct Strided {
  SlotView v;
  std::int64_t threads;
  Count count;
  F f;
  Once once;
  GG_HD void operator()(std::int64_t t) const {
    if (t == 0) once();
    const std::int64_t n = count();
    for (std::int64_t j = t; j < n; j += threads) f(j, v[t]);
  }
};
}  // namespace slots_detail

template <class Exec>
class ScratchSlots {
 public:
  ScratchSlots() = default;
  // At most `want` slots of `doubles` each: no more than the executor runs at once, and no
  // more than fit in budget_bytes (at least one).
  ScratchSlots(Exec& ex, std::int64_t want, std::int64_t doubles,
               std::size_t budget_bytes = std::size_t(1) << 40) {
    const std::int64_t per_slot = doubles * std::int64_t(sizeof(double));
    std::int64_t s = std::min<std::int64_t>(want, ex.concurrency());
    s = std::min<std::int64_t>(s, std::int64_t(budget_bytes) / std::max<std::int64_t>(per_slot, 1));
    v_.slots = std::max<std::int64_t>(1, s);
    v_.doubles = doubles;
    buf_ = ex.template alloc<double>(std::size_t(v_.slots * doubles));
    v_.base = buf_.data();
  }
  std::int64_t slots() const { return v_.slots; }
  SlotView view() const { return v_; }

  // f(j, scratch) for every j < m (m known on the host).
  template <class F>
  void run(Exec& ex, std::int64_t m, F f) const {
    run_counted(ex, m, slots_detail::Fixed{m}, f);
  }
  // f(j, scratch) for every j < count(), where count() reads a length on the executor when the
  // pass runs (a list a kernel before it appended to: no wait for the host), and at most bound;
  // once() runs on the first slot (unordered with the others: it must not write what they
  // read), for a pass's bookkeeping without a launch of its own.
  template <class Count, class F, class Once = slots_detail::NoOnce>
  void run_counted(Exec& ex, std::int64_t bound, Count count, F f, Once once = {}) const {
    if (bound <= 0) return;
    const std::int64_t T = std::min(bound, v_.slots);
    ex.for_each_index(T, slots_detail::Strided<F, Count, Once>{v_, T, count, f, once});
  }

 private:
  SlotView v_;
  typename Exec::template Buffer<double> buf_;
};

}  // namespace gpugeom
