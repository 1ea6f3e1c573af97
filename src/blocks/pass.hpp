// What every block pass (src/blocks/) shares on the host: the OpenMP thread count of the calling
// thread while it runs, the check of the dimension, and ordered listing (a point's cell,
// cell_along, in_box and a box's cells, cells_along, are simplex_rules.hpp's: the device passes
// need them too).
#pragma once
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/simplex_rules.hpp"

namespace gpugeom::blocks_detail {

// Sets the count for the scope's life (0: leaves OpenMP's default) and restores it after.
class ThreadScope {
 public:
  explicit ThreadScope(int threads) : saved_(omp_get_max_threads()), set_(threads > 0) {
    if (set_) omp_set_num_threads(threads);
  }
  ~ThreadScope() {
    if (set_) omp_set_num_threads(saved_);
  }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int saved_;
  bool set_;
};

// Error(InvalidArgument) naming the pass where dim is not 2 or 3.
inline void check_dim(int dim, const char* pass) {
  if (dim != 2 && dim != 3)
    throw Error(ErrorCode::InvalidArgument,
                std::string(pass) + ": dim must be 2 or 3, got " + std::to_string(dim));
}

// Calls emit(i, rank) for each i in [0, n) with keep(i), rank counting them from 0 in
// increasing i, on the OpenMP threads of the caller's scope; `sized(total)` runs once between
// the counting and the emitting (to size the outputs). Each thread takes a contiguous range,
// counts, then emits from its offset, so the ranks do not depend on the thread count. keep must
// answer the same both times it is asked. Returns the count. (On one thread the passes that list
// owned rows, requests and vertices took seconds for the 3.4·10^7 simplices of a GPU block.)
template <class Keep, class Sized, class Emit>
std::int64_t ordered_compact(std::int64_t n, Keep&& keep, Sized&& sized, Emit&& emit) {
  const int most = std::max(1, omp_get_max_threads());
  std::vector<std::int64_t> start(std::size_t(most) + 1, 0);
  std::int64_t total = 0;
#pragma omp parallel num_threads(most)
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
    const std::int64_t a = n * t / threads, b = n * (t + 1) / threads;
    std::int64_t c = 0;
    for (std::int64_t i = a; i < b; ++i) c += keep(i) ? 1 : 0;
    start[std::size_t(t) + 1] = c;
#pragma omp barrier
#pragma omp single
    {
      for (int u = 0; u < threads; ++u) start[std::size_t(u) + 1] += start[std::size_t(u)];
      total = start[std::size_t(threads)];
      sized(total);
    }
    std::int64_t r = start[std::size_t(t)];
    for (std::int64_t i = a; i < b; ++i)
      if (keep(i)) emit(i, r++);
  }
  return total;
}

}  // namespace gpugeom::blocks_detail
