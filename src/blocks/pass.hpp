// What every block pass (src/blocks/) shares: the OpenMP thread count of the calling thread
// while it runs, and the check of the dimension.
#pragma once
#include <omp.h>

#include <string>

#include "gpugeom/common.hpp"

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

}  // namespace gpugeom::blocks_detail
