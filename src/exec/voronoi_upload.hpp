// The Voronoi diagrams' host entries from a given triangulation, on an executor that does not
// read host memory (internal): the points and the triangulation go up once, and the diagram is
// made there; only it comes back.
#pragma once
#include <cstddef>
#include <cstdint>

#include "base/clock.hpp"
#include "exec/exec_context.hpp"
#include "exec/peak.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom::detail {

// The n points (D coordinates each) and the ns simplices (K vertices each, with their
// neighbours) and the duplicate map uploaded on a new executor of opt, timed as the phase
// "upload"; then run(points, simplices, neighbours, duplicates, context) on it. stats also gets
// the whole call's device peak.
template <int D, int K, class Exec, class Options, class Run>
void voronoi_on_upload(const double* p, std::int64_t n, const std::int32_t* simplices,
                       const std::int32_t* neighbors, const std::int32_t* dup, std::int64_t ns,
                       const Options& opt, RunStats& stats, Run run) {
  const auto t0 = Clock::now();
  Exec ex(opt);
  const DevicePeak<Exec> peak(ex, stats);
  auto d_p = ex.template alloc<double>(std::size_t(D * n));
  auto d_s = ex.template alloc<std::int32_t>(std::size_t(K * ns));
  auto d_nb = ex.template alloc<std::int32_t>(std::size_t(K * ns));
  auto d_dup = ex.template alloc<std::int32_t>(std::size_t(n));
  ex.from_host(p, D * n, d_p.data());
  ex.from_host(simplices, K * ns, d_s.data());
  ex.from_host(neighbors, K * ns, d_nb.data());
  ex.from_host(dup, n, d_dup.data());
  stats.phase_ms.push_back({"upload", ms_since(t0)});
  const ExecContext ctx = ex.context();
  run(d_p.data(), d_s.data(), d_nb.data(), d_dup.data(), &ctx);
}

}  // namespace gpugeom::detail
