// The CPU executor: the same members as CudaExec, run with OpenMP through CCCL's omp policies.
// This is what CI runs and what machines without a GPU use.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <omp.h>
#include <thrust/copy.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#include <thrust/system/omp/execution_policy.h>

#include "gpugeom/common.hpp"
#include "exec/hd.hpp"

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
  T& operator[](std::size_t i) { return p_[i]; }
  const T& operator[](std::size_t i) const { return p_[i]; }

 private:
  std::unique_ptr<T[]> p_;
  std::size_t n_ = 0;
};

struct CpuExec {
  static constexpr Backend backend = Backend::Cpu;
  template <class T>
  using Buffer = HostBuffer<T>;

  template <class T>
  Buffer<T> alloc(std::size_t n) {
    return Buffer<T>(n);
  }

  template <class F>
  void for_each_index(std::int64_t n, F f) {
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) f(i);
  }

  template <class T>
  void fill(T* p, std::int64_t n, T v) {
    for_each_index(n, [=](std::int64_t i) { p[i] = v; });
  }
  template <class T>
  void copy(const T* src, std::int64_t n, T* dst) {
    if (n > 0) std::memcpy(dst, src, sizeof(T) * n);
  }
  template <class T>
  void to_host(const T* src, std::int64_t n, T* host) {
    copy(src, n, host);
  }
  template <class T>
  void from_host(const T* host, std::int64_t n, T* dst) {
    copy(host, n, dst);
  }

  template <class T>
  void exclusive_scan(const T* in, T* out, std::int64_t n) {
    thrust::exclusive_scan(thrust::omp::par, in, in + n, out, T(0));
  }
  template <class T>
  void inclusive_scan(const T* in, T* out, std::int64_t n) {
    thrust::inclusive_scan(thrust::omp::par, in, in + n, out);
  }
  template <class T, class Op>
  T reduce(const T* in, std::int64_t n, T init, Op op) {
    return thrust::reduce(thrust::omp::par, in, in + n, init, op);
  }
  template <class K>
  void sort(K* keys, std::int64_t n) {
    thrust::sort(thrust::omp::par, keys, keys + n);
  }
  template <class K, class V>
  void sort_by_key(K* keys, V* vals, std::int64_t n) {
    thrust::stable_sort_by_key(thrust::omp::par, keys, keys + n, vals);
  }
  // Copies the elements satisfying pred, keeping their order; returns how many.
  template <class T, class Pred>
  std::int64_t copy_if(const T* in, std::int64_t n, T* out, Pred pred) {
    return thrust::copy_if(thrust::omp::par, in, in + n, out, pred) - out;
  }
  // Writes the indices i in [0, n) with pred(i), in increasing order; returns how many.
  template <class Pred>
  std::int64_t compact_indices(std::int64_t n, Pred pred, std::int32_t* out) {
    thrust::counting_iterator<std::int32_t> first(0);
    auto by_index = [&](std::int32_t i) { return bool(pred(std::int64_t(i))); };
    return thrust::copy_if(thrust::omp::par, first, first + n, out, by_index) - out;
  }
  void sync() {}
  // How many independent work items keep every core busy (sizes scratch pools).
  std::int64_t concurrency() const {
    return std::int64_t(omp_get_max_threads()) * 4;
  }
};

}  // namespace gpugeom
