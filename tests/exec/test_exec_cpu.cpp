#include <cuda/atomic>

#include "exec/cpu_exec.hpp"
#define EXEC gpugeom::CpuExec
#define SUITE CpuExecTest
#include "exec_suite.inl"

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <vector>

// CpuExec::append_in_order (the CPU executor's appends without a shared counter): every index's
// entries land after those of the indices before it, in each of the lists, from the lists'
// bases on, and the bases grow by the totals; the first pass writes nothing. Checked on one
// thread (one pass) and on several (a counting pass and a placing pass), with lists of
// different lengths per index, and an index that appends nothing.
TEST(CpuExecTest, AppendInOrderPlacesEachIndexAfterTheOnesBefore) {
  for (int threads : {1, 2, 3, 8}) {
    const int prev = omp_get_max_threads();
    omp_set_num_threads(threads);
    gpugeom::CpuExec ex;
    const std::int64_t n = 50000;  // (past append_in_order's least share per thread)
    auto a_of = [](std::int64_t i) { return int(i % 3); };          // 0, 1 or 2 entries of list a
    auto b_of = [](std::int64_t i) { return i % 5 == 0 ? 1 : 0; };  // every fifth: one of b
    std::int64_t na = 7, nb = 11;  // the lists' lengths before: entries go after them
    std::vector<std::int64_t> a(std::size_t(na + 2 * n), -1), b(std::size_t(nb + n), -1);
    std::int64_t* const base[2] = {&na, &nb};
    std::int64_t calls = 0;  // (one thread at a time writes it only when threads == 1)
    ex.append_in_order<2>(n, base, [&](std::int64_t i, auto& place) {
      using P = std::decay_t<decltype(place)>;
      if (threads == 1) ++calls;
      for (int c = 0; c < a_of(i); ++c) {
        const std::int64_t at = place.take(0, 1);
        if constexpr (P::kApply) a[std::size_t(at)] = i;
      }
      if (b_of(i)) {
        const std::int64_t at = place.take(1, 1);
        if constexpr (P::kApply) b[std::size_t(at)] = i;
      }
    });
    omp_set_num_threads(prev);
    std::int64_t ta = 0, tb = 0;
    for (std::int64_t i = 0; i < n; ++i) ta += a_of(i), tb += b_of(i);
    ASSERT_EQ(na, 7 + ta) << threads << " threads";
    ASSERT_EQ(nb, 11 + tb) << threads << " threads";
    if (threads == 1) EXPECT_EQ(calls, n);  // one pass
    // the entries in index order, each index's a-entries together, nothing written before
    // the bases or past the totals
    for (std::int64_t k = 0; k < 7; ++k) ASSERT_EQ(a[std::size_t(k)], -1);
    for (std::int64_t k = 0; k < 11; ++k) ASSERT_EQ(b[std::size_t(k)], -1);
    std::int64_t at = 7, bt = 11;
    for (std::int64_t i = 0; i < n; ++i) {
      for (int c = 0; c < a_of(i); ++c) ASSERT_EQ(a[std::size_t(at++)], i) << threads << " threads";
      if (b_of(i)) ASSERT_EQ(b[std::size_t(bt++)], i) << threads << " threads";
    }
    ASSERT_EQ(at, na);
    ASSERT_EQ(bt, nb);
    for (std::int64_t k = na; k < std::int64_t(a.size()); ++k) ASSERT_EQ(a[std::size_t(k)], -1);
  }
}
