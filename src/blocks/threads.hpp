// The OpenMP thread count of the calling thread while a block pass runs (src/blocks/).
#pragma once
#include <omp.h>

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

}  // namespace gpugeom::blocks_detail
