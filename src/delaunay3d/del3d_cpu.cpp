// 3D Delaunay tetrahedralisation compiled for the CPU executor.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "base/clock.hpp"
#include "delaunay3d/del3d_backend.hpp"
#include "delaunay3d/tet.hpp"
#include "edt/edt_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/cpu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/scratch_lease.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/compact.hpp"
#include "mesh/hole_refill.hpp"
#include "mesh/simplex_changes.hpp"
#include "mesh/kept_points.hpp"
#include "mesh/first_tetrahedron.hpp"
#include "mesh/flip_fix.hpp"
#include "mesh/history.hpp"
#include "mesh/prepare.hpp"
#include "mesh/priority.hpp"
#include "mesh/work_list.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::del3d::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "delaunay3d/impl/geometry.inl"
#include "delaunay3d/impl/link.inl"
#include "edt/impl/point_voronoi.inl"
#include "delaunay3d/digital/impl/working_sets.inl"
#include "delaunay3d/impl/stars.inl"
#include "delaunay3d/impl/repair.inl"
#include "delaunay3d/digital/impl/pipeline.inl"
#include "delaunay3d/impl/triangulate.inl"
#include "delaunay3d/impl/dynamic.inl"
std::unique_ptr<Kept> make_kept(const Delaunay3dOptions& opt) {
  return std::make_unique<KeptOn>(opt);
}
void triangulate(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt, Output& out,
                 Stats& stats) {
  triangulate_impl(xyz, n, opt, out, stats);
}
// Tests (del3d_backend.hpp): the stars after creation, or after splaying (two ways), on the host.
void digital_stars_for_testing(const double* xyz, std::int64_t n, std::int64_t grid, int splay,
                               StarsForTesting& out, std::int64_t first_requests) {
  Delaunay3dOptions opt;
  opt.backend = Backend::Cpu;
  Exec ex(opt);
  Stats st;
  Prepared P = prepare_points(ex, xyz, n, false, st);
  mesh::SortedPoints<Exec>& S = P.S;
  const mesh::Bounds<3>& box = P.box;
  const mesh::Tetra& first = P.first;
  DigitalStars D;
  out.built = digital_stars(ex, S, box, first, grid, st, D) &&
              (splay == 0 || digital_splay(ex, D, st, splay == 1, first_requests));
  if (!out.built) return;
  if (splay > 0) out.request_spills = st.counters.at("digital_splay_request_spills");
  const std::int64_t m = S.m;
  out.pts.resize(std::size_t(3 * m));
  ex.to_host(S.pts.data(), 3 * m, out.pts.data());
  std::vector<std::int64_t> off(static_cast<std::size_t>(m));
  std::vector<std::int32_t> cnt(static_cast<std::size_t>(m));
  std::vector<std::int32_t> nvt(static_cast<std::size_t>(m));
  std::vector<LinkTri> tri(static_cast<std::size_t>(D.T.slots));
  std::vector<LinkVert> vt(static_cast<std::size_t>(D.T.slots));
  ex.to_host(D.T.off.data(), m, off.data());
  ex.to_host(D.T.cnt.data(), m, cnt.data());
  ex.to_host(D.T.nvt.data(), m, nvt.data());
  ex.to_host(D.T.tri.data(), D.T.slots, tri.data());
  ex.to_host(D.T.vt.data(), D.T.slots, vt.data());
  out.start.assign(1, 0);
  out.table_start.assign(1, 0);
  for (std::int64_t v = 0; v < m; ++v) {
    const std::size_t o = std::size_t(off[std::size_t(v)]);
    for (std::int32_t i = 0; i < cnt[std::size_t(v)]; ++i) {
      const LinkTri& t = tri[o + std::size_t(i)];
      out.tri.insert(out.tri.end(), {t.a, t.b, t.c});
    }
    out.start.push_back(std::int64_t(out.tri.size() / 3));
    for (std::int32_t j = 0; j < nvt[std::size_t(v)]; ++j) {
      out.table_vertex.push_back(vt[o + std::size_t(j)].x);
      out.table_hash.push_back(vt[o + std::size_t(j)].h);
    }
    out.table_start.push_back(std::int64_t(out.table_vertex.size()));
  }
}

void triangulate_device(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                        DeviceOutput& out, Stats& stats) {
  triangulate_device_impl(xyz, n, opt, out, stats);
}
}  // namespace gpugeom::del3d::cpu_impl
