// What the triangulations that follow their points share (internal; DynamicDelaunay2d and
// DynamicDelaunay3d, issue 47): the kept state behind an executor-independent interface (Kept:
// insert, points), its insertions checked and timed, and the stats of the last call that
// succeeded.
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {

template <class Kept>
struct DynamicState {
  std::unique_ptr<Kept> kept;
  Backend backend = Backend::Cpu;
  Stats stats;

  // Appends n points (executor memory when on_device); check(total) refuses a total count the
  // structure cannot take. The stats are replaced only once the insertion succeeded.
  template <class Check>
  void insert(const double* p, std::int64_t n, bool on_device, Check check) {
    if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
    check(kept->points() + n);
    Stats st;
    st.backend = backend;
    const auto t0 = std::chrono::steady_clock::now();
    kept->insert(p, n, on_device, st);
    st.phase_ms.push_back(
        {"total",
         std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()});
    stats = std::move(st);
  }
  // New coordinates for all n points (n must be the count kept).
  void move(const double* p, std::int64_t n, bool on_device) {
    if (n != kept->points())
      throw Error(ErrorCode::InvalidArgument,
                  "move: " + std::to_string(n) + " points given for a triangulation of " +
                      std::to_string(kept->points()) + " (give new coordinates for every point)");
    Stats st;
    st.backend = backend;
    const auto t0 = std::chrono::steady_clock::now();
    kept->move(p, on_device, st);
    st.phase_ms.push_back(
        {"total",
         std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()});
    stats = std::move(st);
  }
};

}  // namespace gpugeom::detail
