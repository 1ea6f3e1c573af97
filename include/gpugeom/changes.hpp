/// @file
/// Which simplices an update of a triangulation that follows its points changed
/// (DynamicDelaunay2d / DynamicDelaunay3d::changes, issue 47), for callers that keep data per
/// simplex (a finite-element matrix, a Voronoi vertex, a cell's volume) and want to update only
/// what the update touched.
#pragma once
#include <cstdint>
#include <memory>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// A simplex is the same where its vertex indices are (its orientation, the order of its
/// vertices and its neighbours do not matter). Derived data carries over as
///   now[i] = previous_index[i] >= 0 ? before[previous_index[i]] : compute(i).
struct SimplexChanges {
  /// Per simplex of the current result, in the order of its arrays: the index of the same
  /// simplex in the result before the last update, -1 where it is new.
  HostVector<std::int32_t> previous_index;
  /// The indices, in the result before the last update, of its simplices that are gone
  /// (increasing).
  HostVector<std::int32_t> removed;
  std::int64_t num_simplices = 0;  ///< in the current result
  std::int64_t num_previous = 0;   ///< in the result before the last update
  std::int64_t num_new = 0;        ///< entries -1 in previous_index
  std::int64_t num_removed = 0;    ///< entries of removed
};

/// The same in executor memory (device memory on CUDA, host memory on the CPU executor), freed
/// when the last copy of a pointer goes.
struct DeviceSimplexChanges {
  std::int64_t num_simplices = 0, num_previous = 0, num_new = 0, num_removed = 0;
  std::shared_ptr<std::int32_t> previous_index;  ///< num_simplices
  std::shared_ptr<std::int32_t> removed;         ///< num_removed
  Backend backend = Backend::Cuda;
};

}  // namespace gpugeom
