// One suite for every executor: included by test_exec_cpu.cpp (CpuExec) and
// test_exec_cuda.cu (CudaExec) with EXEC and SUITE defined. Data is random, never zeros,
// and outputs are poisoned first so an unwritten element shows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <thrust/functional.h>

namespace {

// nvcc forbids extended lambdas in TestBody (a private member): each test's body is a free
// function.

template <class T>
std::vector<T> to_vec(EXEC& ex, const T* d, std::int64_t n) {
  std::vector<T> h(n);
  ex.to_host(d, n, h.data());
  return h;
}
template <class B, class T>
void upload(EXEC& ex, B& buf, const std::vector<T>& h) {
  ex.from_host(h.data(), std::int64_t(h.size()), buf.data());
}

void ForEachIndexAndFill_body();
TEST(SUITE, ForEachIndexAndFill) {
  ForEachIndexAndFill_body();
}
void ForEachIndexAndFill_body() {
  EXEC ex;
  for (std::int64_t n : {1, 255, 256, 257, 100000, 3000001}) {
    auto b = ex.template alloc<std::int64_t>(n);
    ex.fill(b.data(), n, std::int64_t(-7));
    std::int64_t* p = b.data();
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          if (i % 3) p[i] = i * 5 + 1;
        });
    auto h = to_vec(ex, b.data(), n);
    for (std::int64_t i = 0; i < n; ++i)
      ASSERT_EQ(h[i], i % 3 ? i * 5 + 1 : -7) << "n=" << n << " i=" << i;
  }
}

// Scans and reductions over a function of the index (nothing materialised), results left on
// the device: several of them come back in one copy.
void FunctionScanAndReduce_body();
TEST(SUITE, FunctionScanAndReduce) {
  FunctionScanAndReduce_body();
}
void FunctionScanAndReduce_body() {
  EXEC ex;
  for (std::int64_t n : {1, 777, 1 << 20}) {
    auto out = ex.template alloc<std::int32_t>(n);
    auto sums = ex.template alloc<double>(2);
    ex.fill(out.data(), n, std::int32_t(-1));
    ex.exclusive_scan_of(
        n, GG_LAMBDA(std::int64_t i)->std::int32_t { return (i * 7) % 5 == 1 ? 1 : 0; },
        out.data());
    ex.transform_reduce_into(
        n, GG_LAMBDA(std::int64_t i)->double { return double(i % 1000) * 0.5; }, 0.0,
        thrust::plus<double>(), sums.data());
    ex.transform_reduce_into(
        n, GG_LAMBDA(std::int64_t i)->double { return double(i % 13); }, -1.0,
        thrust::maximum<double>(), sums.data() + 1);
    const auto h = to_vec(ex, out.data(), n);
    const auto r = to_vec(ex, sums.data(), 2);
    std::int32_t run = 0;
    double total = 0;
    for (std::int64_t i = 0; i < n; ++i) {
      ASSERT_EQ(h[i], run) << "n=" << n << " i=" << i;
      run += (i * 7) % 5 == 1;
      total += double(i % 1000) * 0.5;
    }
    EXPECT_EQ(r[0], total);  // halves of integers below 2^53: exact in any order
    EXPECT_EQ(r[1], n >= 13 ? 12.0 : double(n - 1));
  }
}

void ScansReduceAndCopies_body();
TEST(SUITE, ScansReduceAndCopies) {
  ScansReduceAndCopies_body();
}
void ScansReduceAndCopies_body() {
  EXEC ex;
  std::mt19937 g(11);
  for (std::int64_t n : {1, 1000, 1 << 20}) {
    std::vector<std::int32_t> in(n);
    for (auto& v : in) v = std::int32_t(g() % 100) - 30;
    auto a = ex.template alloc<std::int32_t>(n), b = ex.template alloc<std::int32_t>(n);
    upload(ex, a, in);
    ex.exclusive_scan(a.data(), b.data(), n);
    auto h = to_vec(ex, b.data(), n);
    std::int32_t s = 0;
    for (std::int64_t i = 0; i < n; ++i) {
      ASSERT_EQ(h[i], s) << i;
      s += in[i];
    }
    ex.inclusive_scan(a.data(), b.data(), n);
    h = to_vec(ex, b.data(), n);
    ASSERT_EQ(h[n - 1], s);
    const std::int32_t mx = ex.reduce(
        a.data(), n, std::numeric_limits<std::int32_t>::min(),
        GG_LAMBDA(std::int32_t x, std::int32_t y) { return x > y ? x : y; });
    ASSERT_EQ(mx, *std::max_element(in.begin(), in.end()));
    auto c = ex.template alloc<std::int32_t>(n);
    ex.copy(a.data(), n, c.data());
    ASSERT_EQ(to_vec(ex, c.data(), n), in);
  }
}

void SortByKeyIsStableAndComplete_body();
TEST(SUITE, SortByKeyIsStableAndComplete) {
  SortByKeyIsStableAndComplete_body();
}
void SortByKeyIsStableAndComplete_body() {
  EXEC ex;
  std::mt19937_64 g(5);
  for (std::int64_t n : {2, 777, 1 << 20}) {
    std::vector<std::uint64_t> k(n);
    std::vector<std::int32_t> v(n);
    for (std::int64_t i = 0; i < n; ++i)
      k[i] = g() % std::uint64_t(n / 2 + 1), v[i] = std::int32_t(i);
    auto dk = ex.template alloc<std::uint64_t>(n);
    auto dv = ex.template alloc<std::int32_t>(n);
    upload(ex, dk, k);
    upload(ex, dv, v);
    ex.sort_by_key(dk.data(), dv.data(), n);
    auto hk = to_vec(ex, dk.data(), n);
    auto hv = to_vec(ex, dv.data(), n);
    std::vector<std::int32_t> ref(n);
    std::iota(ref.begin(), ref.end(), 0);
    std::stable_sort(ref.begin(), ref.end(), [&](int a, int b) { return k[a] < k[b]; });
    for (std::int64_t i = 0; i < n; ++i) {
      ASSERT_EQ(hv[i], ref[i]) << i;
      ASSERT_EQ(hk[i], k[ref[i]]) << i;
    }
    ex.sort(dk.data(), n);  // already sorted keys stay sorted
    ASSERT_TRUE(std::is_sorted(hk.begin(), hk.end()));
  }
}

void CompactionKeepsOrder_body();
TEST(SUITE, CompactionKeepsOrder) {
  CompactionKeepsOrder_body();
}
void CompactionKeepsOrder_body() {
  EXEC ex;
  std::mt19937 g(3);
  const std::int64_t n = 1 << 20;
  std::vector<std::int32_t> in(n);
  for (auto& v : in) v = std::int32_t(g() % 1000);
  auto a = ex.template alloc<std::int32_t>(n), o = ex.template alloc<std::int32_t>(n);
  upload(ex, a, in);
  ex.fill(o.data(), n, std::int32_t(-1));
  const std::int64_t m = ex.copy_if(
      a.data(), n, o.data(), GG_LAMBDA(std::int32_t x) { return x % 7 == 0; });
  std::vector<std::int32_t> ref;
  for (auto x : in)
    if (x % 7 == 0) ref.push_back(x);
  ASSERT_EQ(m, std::int64_t(ref.size()));
  auto h = to_vec(ex, o.data(), m);
  ASSERT_EQ(h, ref);
  const std::int32_t* ap = a.data();
  const std::int64_t m2 = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return ap[i] < 10; }, o.data());
  std::vector<std::int32_t> ri;
  for (std::int64_t i = 0; i < n; ++i)
    if (in[i] < 10) ri.push_back(std::int32_t(i));
  ASSERT_EQ(m2, std::int64_t(ri.size()));
  ASSERT_EQ(to_vec(ex, o.data(), m2), ri);
  // The variants that leave the count on the executor, and a loop over that count.
  auto cnt = ex.template alloc<std::int64_t>(2);
  std::int64_t* cn = cnt.data();
  ex.copy_if_to(
      a.data(), n, o.data(), GG_LAMBDA(std::int32_t x) { return x % 7 == 0; }, cn);
  ex.compact_indices_to(
      n, GG_LAMBDA(std::int64_t i) { return ap[i] < 10; }, o.data() + m, cn + 1);
  std::int64_t hc[2];
  ex.to_host(cn, 2, hc);  // a small read: through the pinned mailbox on CUDA
  ASSERT_EQ(hc[0], m);
  ASSERT_EQ(hc[1], m2);
  std::vector<std::int32_t> both = ref;
  both.insert(both.end(), ri.begin(), ri.end());
  ASSERT_EQ(to_vec(ex, o.data(), m + m2), both);
  std::int32_t* op = o.data();
  ex.for_each_counted(
      cn, n, GG_LAMBDA(std::int64_t i) { op[i] = -op[i] - 1; });  // only the first m
  auto neg = to_vec(ex, o.data(), m + 1);
  for (std::int64_t i = 0; i < m; ++i) ASSERT_EQ(neg[i], -ref[i] - 1);
  ASSERT_EQ(neg[m], ri[0]);
  // Past 2^31 - 1 items the int32 positions cannot name them: refused before the pass runs (the
  // predicate would read far outside ap), on both forms, with a typed error.
  const std::int64_t huge = std::int64_t(INT32_MAX) + 1;
  for (int form = 0; form < 2; ++form) {
    try {
      if (form == 0)
        ex.compact_indices(
            huge, GG_LAMBDA(std::int64_t i) { return ap[i] < 10; }, o.data());
      else
        ex.compact_indices_to(
            huge, GG_LAMBDA(std::int64_t i) { return ap[i] < 10; }, o.data(), cn);
      FAIL() << "compact_indices took " << huge << " items";
    } catch (const gpugeom::Error& e) {
      EXPECT_EQ(e.code(), gpugeom::ErrorCode::Internal);
      EXPECT_NE(std::string(e.what()).find("32-bit"), std::string::npos) << e.what();
    }
  }
  ex.sync();  // nothing was launched: the stream is still sound
  ASSERT_EQ(to_vec(ex, o.data(), 1)[0], neg[0]);
}

// A team runs rounds separated by barriers: each round every thread reads what all the others
// wrote in the round before (a wrong barrier shows as a wrong sum).
void TeamBarriersOrderRounds_body();
TEST(SUITE, TeamBarriersOrderRounds) {
  TeamBarriersOrderRounds_body();
}
void TeamBarriersOrderRounds_body() {
  EXEC ex;
  const int T = ex.team_size();
  ASSERT_GE(T, 1);
  auto buf = ex.template alloc<std::int64_t>(2 * std::size_t(T));
  std::int64_t* b = buf.data();
  ex.fill(b, 2 * std::int64_t(T), std::int64_t(1));
  constexpr int kRounds = 40;
  ex.team(GG_LAMBDA(const EXEC::Team& t) {
    for (int r = 0; r < kRounds; ++r) {
      const std::int64_t* src = b + (r & 1) * t.size;
      std::int64_t* dst = b + ((r + 1) & 1) * t.size;
      // dst[i] = src[i] + src[i + 1] (cyclic): after r rounds every entry is 2^r
      dst[t.rank] = src[t.rank] + src[(t.rank + 1) % t.size];
      t.barrier();
    }
  });
  auto h = to_vec(ex, b + (kRounds & 1) * T, T);
  for (int i = 0; i < T; ++i) ASSERT_EQ(h[i], std::int64_t(1) << kRounds) << "thread " << i;
}

// The team's scan, called many times in a row (a slot reused too early shows as a wrong
// offset): thread r passes v(r, call), gets the sum over lower ranks and the total.
template <int Threads>
void TeamScanGivesOffsets_body();
TEST(SUITE, TeamScanGivesOffsets) {
  TeamScanGivesOffsets_body<1024>();
  TeamScanGivesOffsets_body<512>();  // a smaller team (more registers a thread on the GPU)
}
template <int Threads>
void TeamScanGivesOffsets_body() {
  EXEC ex;
  const int T = ex.template team_size<Threads>();
  constexpr int kCalls = 7;
  auto buf = ex.template alloc<std::int64_t>(std::size_t(2 * kCalls * T));
  std::int64_t* b = buf.data();
  ex.template team<Threads>(GG_LAMBDA(const EXEC::Team& t) {
    for (int c = 0; c < kCalls; ++c) {
      std::int64_t total = -1;
      const std::int64_t v = (std::int64_t(t.rank) * 7919 + c * 31) % 13;
      b[2 * (c * t.size + t.rank)] = t.exclusive_scan(v, &total);
      b[2 * (c * t.size + t.rank) + 1] = total;
    }
  });
  auto h = to_vec(ex, b, 2 * kCalls * T);
  for (int c = 0; c < kCalls; ++c) {
    std::int64_t sum = 0, all = 0;
    for (int r = 0; r < T; ++r) all += (std::int64_t(r) * 7919 + c * 31) % 13;
    for (int r = 0; r < T; ++r) {
      ASSERT_EQ(h[2 * (c * T + r)], sum) << "call " << c << " thread " << r;
      ASSERT_EQ(h[2 * (c * T + r) + 1], all) << "call " << c << " thread " << r;
      sum += (std::int64_t(r) * 7919 + c * 31) % 13;
    }
  }
}

void AtomicsCountEveryIncrement_body();
TEST(SUITE, AtomicsCountEveryIncrement) {
  AtomicsCountEveryIncrement_body();
}
void AtomicsCountEveryIncrement_body() {
  EXEC ex;
  const std::int64_t n = 1 << 20;
  auto c = ex.template alloc<std::int32_t>(16);
  ex.fill(c.data(), 16, std::int32_t(0));
  std::int32_t* cp = c.data();
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> r(cp[i % 16]);
        r.fetch_add(1, cuda::memory_order_relaxed);
      });
  auto h = to_vec(ex, c.data(), 16);
  for (auto v : h) ASSERT_EQ(v, n / 16);
}

// Host copies of every size class: below the staging threshold, around a 4 MB part, and over
// several 32 MB chunks (both staging buffers reused), each checked word for word after the
// round trip and against the device's own view of the data.
void LargeCopiesRoundTrip_body();
TEST(SUITE, LargeCopiesRoundTrip) {
  LargeCopiesRoundTrip_body();
}
void LargeCopiesRoundTrip_body() {
  EXEC ex;
  std::mt19937_64 rng(11);
  const std::int64_t part = (std::int64_t(4) << 20) / 8;
  for (std::int64_t n : {std::int64_t(1000), part - 1, part + 1, 9 * part + 3, 33 * part / 2}) {
    std::vector<std::uint64_t> h(static_cast<std::size_t>(n));
    for (auto& v : h) v = rng() | 1;
    auto d = ex.template alloc<std::uint64_t>(std::size_t(n));
    upload(ex, d, h);
    // On the device: each word is odd and the last is where it belongs.
    auto bad = ex.template alloc<std::int64_t>(1);
    const std::uint64_t* dp = d.data();
    ex.transform_reduce_into(
        n, GG_LAMBDA(std::int64_t i)->std::int64_t { return (dp[i] & 1) ? 0 : 1; }, std::int64_t(0),
        thrust::plus<std::int64_t>(), bad.data());
    ASSERT_EQ(to_vec(ex, bad.data(), 1)[0], 0) << "n=" << n;
    const auto back = to_vec(ex, d.data(), n);
    for (std::int64_t i = 0; i < n; ++i) ASSERT_EQ(back[i], h[i]) << "n=" << n << " i=" << i;
  }
}

}  // namespace
