// The CPU executor: the same members as CudaExec, run with OpenMP through CCCL's omp policies.
// This is what CI runs and what machines without a GPU use.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <omp.h>
#include <type_traits>
#include <vector>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <thrust/reduce.h>
#include <thrust/transform_reduce.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#include <thrust/system/omp/execution_policy.h>

#include "gpugeom/common.hpp"
#include "base/hd.hpp"
#include "exec/exec_context.hpp"
#include "exec/lanes.hpp"
#include "exec/positions.hpp"
#include "exec/tuning.hpp"

namespace gpugeom {

// Owning host array; uninitialised on allocation, like device memory.
template <class T>
class HostBuffer {
 public:
  HostBuffer() = default;
  explicit HostBuffer(std::size_t n) : n_(n) {
    if (n == 0) return;
    p_.reset(new (std::nothrow) T[n]);
    if (!p_)
      throw Error(ErrorCode::OutOfMemory,
                  "host allocation of " + std::to_string(n * sizeof(T)) + " bytes failed");
  }
  T* data() { return p_.get(); }
  const T* data() const { return p_.get(); }
  std::size_t size() const { return n_; }
  // As DeviceBuffer's: the array to the caller (the "device" entry points' results on this
  // executor, whose device memory is host memory).
  std::shared_ptr<T> hand_over() {
    n_ = 0;
    return std::shared_ptr<T>(p_.release(), std::default_delete<T[]>());
  }
  T& operator[](std::size_t i) { return p_[i]; }
  const T& operator[](std::size_t i) const { return p_[i]; }

 private:
  std::unique_ptr<T[]> p_;
  std::size_t n_ = 0;
};

// The CPU executor's team: the threads of one OpenMP parallel region.
struct CpuTeam {
  int rank, size;
  std::int64_t* shared;  // one slot per thread, for exclusive_scan
  void barrier() const {
#pragma omp barrier
  }

  // As CudaExec's Team: the sum of lower ranks' v, and the total (all threads call it).
  std::int64_t exclusive_scan(std::int64_t v, std::int64_t* total) const {
    shared[rank] = v;
    barrier();
    std::int64_t before = 0, all = 0;
    for (int r = 0; r < size; ++r) {
      if (r == rank) before = all;
      all += shared[r];
    }
    barrier();  // every thread has read the slots before the next scan writes them
    *total = all;
    return before;
  }
};

// Every member runs to completion before returning ("synchronises", in CudaExec's terms).
struct CpuExec {
  static constexpr Backend backend = Backend::Cpu;
  template <class T>
  using Buffer = HostBuffer<T>;

  CpuExec() = default;
  // run.threads > 0 sets the OpenMP thread count of the calling thread for the executor's
  // lifetime (restored after), which every parallel step here and in Thrust's omp policy uses.
  explicit CpuExec(const RunOptions& run) : tuning_(detail::tuning_of(run)) {
    if (run.threads > 0) {
      prev_threads_ = omp_get_max_threads();
      omp_set_num_threads(run.threads);
    }
  }
  // (The CPU executor shares nothing with an outer one: the thread count is run's, as there.)
  CpuExec(const RunOptions& run, const detail::ExecContext*) : CpuExec(run) {}
  detail::ExecContext context() const { return {}; }
  ~CpuExec() {
    if (prev_threads_) omp_set_num_threads(prev_threads_);
  }
  CpuExec(const CpuExec&) = delete;
  CpuExec& operator=(const CpuExec&) = delete;
  // The options a state kept across calls (DynamicDelaunay2d, ...) runs its later calls with:
  // as given (CudaExec pins the device).
  template <class Options>
  static Options kept_options(Options opt) {
    return opt;
  }
  // The call's internal knobs (exec/tuning.hpp), copied from its options.
  const detail::Tuning& tuning() const { return tuning_; }

  template <class T>
  Buffer<T> alloc(std::size_t n) {
    return Buffer<T>(n);
  }

  template <class F>
  void for_each_index(std::int64_t n, F f) {
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) f(i);
  }

  // f(i) for every i < per * *count (CudaExec reads the count on the device; here it is just
  // memory).
  template <int MinBlocks = 1, class F>  // (MinBlocks: CudaExec's register budget)
  void for_each_counted(const std::int64_t* count, std::int64_t /*bound*/, F f,
                        std::int64_t per = 1) {
    for_each_index(per * *count, f);
  }

  // Appends in index order, with no counter that the threads share: f(i, place) runs twice for
  // every i < n, over one static split of [0, n). The first time the place only counts what
  // index i appends to each of K lists (place.take(k, m): m entries of list k; kApply false);
  // the second time it hands the entries out, list k's entries of index i after those of every
  // index before i, from *base[k] on; *base[k] then grows by their total. f must append the
  // same both times. Why: a counter bumped by every append is one cache line moving between
  // the cores at each bump. 2D Delaunay's flips ran 2.6 times slower on two threads than on
  // one that way (docs/performance.md, issue 53), and the lists' order hung on timing.
  // CudaExec has no such member: there the appends are atomics aggregated per warp.
  template <int K, class F>
  void append_in_order(std::int64_t n, std::int64_t* const (&base)[K], F f) {
    if (n <= 0) return;
    constexpr std::int64_t kLeastPerThread = 4096;  // (below, one thread: a region costs more)
    const int nt = int(std::clamp<std::int64_t>(n / kLeastPerThread, 1, omp_get_max_threads()));
    if (nt == 1) {  // one thread: the places follow from the bases, no counting pass
      OrderedPlace<K> p;
      for (int k = 0; k < K; ++k) p.at[k] = *base[k];
      for (std::int64_t i = 0; i < n; ++i) f(i, p);
      for (int k = 0; k < K; ++k) *base[k] = p.at[k];
      return;
    }
    std::vector<std::int64_t> shared(
        static_cast<std::size_t>(nt));  // (CpuTeam::exclusive_scan's slots)
#pragma omp parallel num_threads(nt)
    {
      const CpuTeam team{omp_get_thread_num(), omp_get_num_threads(), shared.data()};
      const std::int64_t lo = n * team.rank / team.size, hi = n * (team.rank + 1) / team.size;
      CountingPlace<K> c;
      for (std::int64_t i = lo; i < hi; ++i) f(i, c);
      OrderedPlace<K> p;
      std::int64_t total[K];
      for (int k = 0; k < K; ++k) p.at[k] = *base[k] + team.exclusive_scan(c.n[k], &total[k]);
      for (std::int64_t i = lo; i < hi; ++i) f(i, p);
      team.barrier();  // (every thread has read the bases)
      if (team.rank == 0)
        for (int k = 0; k < K; ++k) *base[k] += total[k];
    }
  }
  // append_in_order's places: the first pass's, counting, and the second's, handing out.
  template <int K>
  struct CountingPlace {
    static constexpr bool kApply = false;
    std::int64_t n[K] = {};
    std::int64_t take(int k, std::int64_t m) {
      n[k] += m;
      return 0;
    }
  };
  template <int K>
  struct OrderedPlace {
    static constexpr bool kApply = true;
    std::int64_t at[K];
    std::int64_t take(int k, std::int64_t m) {
      const std::int64_t a = at[k];
      at[k] += m;
      return a;
    }
  };

  // f(i, lanes) for i < n (see exec/lanes.hpp): here an item is one thread's.
  using Lanes = SoloLanes;
  template <class F>
  void for_each_lanes(std::int64_t n, F f) {
    for_each_index(n, [&](std::int64_t i) { f(i, SoloLanes{}); });
  }

  // Threads that share barriers (see CudaExec::team).
  using Team = CpuTeam;
  template <int Threads = 0>  // (CudaExec's block size; here the team is every thread)
  int team_size() const {
    return omp_get_max_threads();
  }
  template <int Threads = 0, class F>
  void team(F f) {
    std::vector<std::int64_t> shared(static_cast<std::size_t>(omp_get_max_threads()));
    std::int64_t* sh = shared.data();
#pragma omp parallel
    f(CpuTeam{omp_get_thread_num(), omp_get_num_threads(), sh});
  }

  template <class T>
  void fill(T* p, std::int64_t n, T v) {
    for_each_index(n, [=](std::int64_t i) { p[i] = v; });
  }
  // Large copies on all threads: a result array's pages are first touched here (HostVector
  // leaves them untouched), and one thread faults them in at a fifth of the rate of sixteen.
  template <class T>
  void copy(const T* src, std::int64_t n, T* dst) {
    const std::size_t bytes = sizeof(T) * std::size_t(n > 0 ? n : 0);
    constexpr std::size_t kPiece = std::size_t(1) << 20;
    if (bytes < 4 * kPiece) {
      if (bytes) std::memcpy(dst, src, bytes);
      return;
    }
    const auto* s = reinterpret_cast<const char*>(src);
    auto* d = reinterpret_cast<char*>(dst);
    const std::int64_t pieces = std::int64_t((bytes + kPiece - 1) / kPiece);
#pragma omp parallel for schedule(static)
    for (std::int64_t k = 0; k < pieces; ++k) {
      const std::size_t a = std::size_t(k) * kPiece;
      std::memcpy(d + a, s + a, std::min(kPiece, bytes - a));
    }
  }
  template <class T>
  void to_host(const T* src, std::int64_t n, T* host) {
    copy(src, n, host);
  }
  // A host array of n copies of v (the executor's threads write it).
  template <class T>
  void fill_host(T* host, std::int64_t n, T v) {
    fill(host, n, v);
  }
  template <class T>
  void from_host(const T* host, std::int64_t n, T* dst) {
    copy(host, n, dst);
  }

  template <class T>
  void exclusive_scan(const T* in, T* out, std::int64_t n) {
    thrust::exclusive_scan(thrust::omp::par, in, in + n, out, T(0));
  }
  template <class F, class T>
  void exclusive_scan_of(std::int64_t n, F f, T* out) {
    thrust::counting_iterator<std::int64_t> first(0);
    thrust::exclusive_scan(thrust::omp::par, thrust::make_transform_iterator(first, f),
                           thrust::make_transform_iterator(first + n, f), out, T{});
  }
  template <class T>
  void inclusive_scan(const T* in, T* out, std::int64_t n) {
    thrust::inclusive_scan(thrust::omp::par, in, in + n, out);
  }
  template <class T, class Op>
  T reduce(const T* in, std::int64_t n, T init, Op op) {
    return thrust::reduce(thrust::omp::par, in, in + n, init, op);
  }
  template <class T, class F, class Op>
  void transform_reduce_into(std::int64_t n, F f, T init, Op op, T* out) {
    thrust::counting_iterator<std::int64_t> first(0);
    *out = thrust::transform_reduce(thrust::omp::par, first, first + n, f, init, op);
  }
  template <class K>
  void sort(K* keys, std::int64_t n) {
    thrust::sort(thrust::omp::par, keys, keys + n);
  }
  // Stable. Unsigned integer keys take a parallel LSD radix sort (Thrust's OpenMP merge sort
  // is an order of magnitude slower on the keys the algorithms sort: Hilbert keys, indices).
  // key_bits: the keys' low bits that may be set (the others are zero).
  template <class K, class V>
  void sort_by_key(K* keys, V* vals, std::int64_t n, int key_bits = int(8 * sizeof(K))) {
    if constexpr (std::is_integral_v<K> && std::is_unsigned_v<K>) {
      radix_sort_pairs(keys, vals, n, key_bits);
    } else {
      thrust::stable_sort_by_key(thrust::omp::par, keys, keys + n, vals);
    }
  }
  // Copies the elements satisfying pred, keeping their order; returns how many.
  template <class T, class Pred>
  std::int64_t copy_if(const T* in, std::int64_t n, T* out, Pred pred) {
    return kept_in_order<T>(
        n, [&](std::int64_t i) { return bool(pred(in[i])); }, [&](std::int64_t i) { return in[i]; },
        out);
  }
  // Writes the indices i in [0, n) with pred(i), in increasing order; returns how many.
  template <class Pred>
  std::int64_t compact_indices(std::int64_t n, Pred pred, std::int32_t* out) {
    detail::check_int32_positions(n);
    return kept_in_order<std::int32_t>(
        n, [&](std::int64_t i) { return bool(pred(i)); },
        [](std::int64_t i) { return std::int32_t(i); }, out);
  }
  // The two above: each thread tests its contiguous part of [0, n) once, keeping value(i) for
  // the i that pass in its own list, and copies the list to its place after those of the parts
  // before. Thrust's OpenMP copy_if made flag and scan arrays as long as the input: the 3D
  // output's hull facets, a few thousand of 2.7·10^7 faces, took 94 ms on two threads.
  template <class T, class Keep, class Value>
  std::int64_t kept_in_order(std::int64_t n, Keep keep, Value value, T* out) {
    if (n <= 0) return 0;
    constexpr std::int64_t kLeastPerThread = 1 << 15;  // (below, one thread: a region costs more)
    const int nt = int(std::clamp<std::int64_t>(n / kLeastPerThread, 1, omp_get_max_threads()));
    if (nt == 1) {
      std::int64_t c = 0;
      for (std::int64_t i = 0; i < n; ++i)
        if (keep(i)) out[c++] = value(i);
      return c;
    }
    std::vector<std::int64_t> shared(static_cast<std::size_t>(nt));
    std::int64_t all = 0;
#pragma omp parallel num_threads(nt)
    {
      const CpuTeam team{omp_get_thread_num(), omp_get_num_threads(), shared.data()};
      const std::int64_t lo = n * team.rank / team.size, hi = n * (team.rank + 1) / team.size;
      std::vector<T> mine;
      for (std::int64_t i = lo; i < hi; ++i)
        if (keep(i)) mine.push_back(value(i));
      std::int64_t total = 0;
      const std::int64_t at = team.exclusive_scan(std::int64_t(mine.size()), &total);
      std::copy(mine.begin(), mine.end(), out + at);
      if (team.rank == 0) all = total;
    }
    return all;
  }
  template <class T, class Pred>
  void copy_if_to(const T* in, std::int64_t n, T* out, Pred pred, std::int64_t* count) {
    *count = n > 0 ? copy_if(in, n, out, pred) : 0;
  }
  template <class Pred>
  void compact_indices_to(std::int64_t n, Pred pred, std::int32_t* out, std::int64_t* count) {
    *count = n > 0 ? compact_indices(n, pred, out) : 0;
  }
  void sync() {}
  // (CudaExec's direct reads of another device's memory: nothing here, all is host memory)
  struct NoPeer {};
  NoPeer peer_access(int) const {
    return {};
  }

  template <class K, class V>
  void radix_sort_pairs(K* keys, V* vals, std::int64_t n, int key_bits = int(8 * sizeof(K))) {
    if (n <= 1) return;
    constexpr int kBits = 8, kRadix = 1 << kBits;
    const int nt = omp_get_max_threads();
    HostBuffer<K> kb(n);
    HostBuffer<V> vb(n);
    std::vector<std::int64_t> hist(std::size_t(nt) * kRadix);
    K *sk = keys, *dk = kb.data();
    V *sv = vals, *dv = vb.data();
    auto chunk = [n, nt](int t, std::int64_t& lo, std::int64_t& hi) {
      lo = n * t / nt;
      hi = n * (t + 1) / nt;
    };
    for (int shift = 0; shift < std::min(key_bits, int(8 * sizeof(K))); shift += kBits) {
      std::fill(hist.begin(), hist.end(), 0);
#pragma omp parallel num_threads(nt)
      {
        const int t = omp_get_thread_num();
        std::int64_t lo, hi;
        chunk(t, lo, hi);
        std::int64_t* h = hist.data() + std::size_t(t) * kRadix;
        for (std::int64_t i = lo; i < hi; ++i) ++h[(sk[i] >> shift) & (kRadix - 1)];
      }
      // Offsets digit-major, thread-minor, so the scatter is stable. Skip a digit all keys share.
      std::int64_t sum = 0;
      bool trivial = false;
      for (int d = 0; d < kRadix; ++d) {
        std::int64_t total = 0;
        for (int t = 0; t < nt; ++t) {
          std::int64_t c = hist[std::size_t(t) * kRadix + d];
          hist[std::size_t(t) * kRadix + d] = sum + total;
          total += c;
        }
        trivial = trivial || total == n;
        sum += total;
      }
      if (trivial) continue;
#pragma omp parallel num_threads(nt)
      {
        const int t = omp_get_thread_num();
        std::int64_t lo, hi;
        chunk(t, lo, hi);
        std::int64_t* off = hist.data() + std::size_t(t) * kRadix;
        for (std::int64_t i = lo; i < hi; ++i) {
          const std::int64_t o = off[(sk[i] >> shift) & (kRadix - 1)]++;
          dk[o] = sk[i];
          dv[o] = sv[i];
        }
      }
      std::swap(sk, dk);
      std::swap(sv, dv);
    }
    if (sk != keys) {
      copy(sk, n, keys);
      copy(sv, n, vals);
    }
  }
  // How many independent work items keep every core busy (sizes scratch pools).
  std::int64_t concurrency() const {
    return std::int64_t(omp_get_max_threads()) * 4;
  }
  // Host memory is not budgeted: sizes that adapt to what is left take their largest.
  std::uint64_t available_memory() const {
    return ~std::uint64_t(0);
  }

 private:
  int prev_threads_ = 0;
  detail::Tuning tuning_;
};

}  // namespace gpugeom
