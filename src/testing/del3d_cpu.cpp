// The 3D test entry (testing.hpp: digital_stars) on the CPU executor: the module's algorithm
// (its own unit.inl, as the library compiles it), and the stars brought to the host.
#include "exec/cpu_exec.hpp"
#include "delaunay3d/impl/unit.hpp"
#include "testing/testing.hpp"

namespace gpugeom::del3d::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "delaunay3d/impl/unit.inl"
}  // namespace gpugeom::del3d::cpu_impl

namespace gpugeom::testing {
void digital_stars(const double* xyz, std::int64_t n, std::int64_t grid, int splay, Stars& out,
                   std::int64_t first_requests) {
  using namespace del3d::cpu_impl;
  Delaunay3dOptions opt;
  opt.backend = Backend::Cpu;
  Exec ex(opt);
  Delaunay3dStats st;
  Prepared P = prepare_points(ex, xyz, n, false, st);
  mesh::SortedPoints<Exec>& S = P.S;
  const mesh::Bounds<3>& box = P.box;
  const mesh::Tetra& first = P.first;
  DigitalStars D;
  out.built = digital_stars(ex, S, box, first, grid, st, D) &&
              (splay == 0 || digital_splay(ex, D, st, splay == 1, first_requests));
  if (!out.built) return;
  if (splay > 0) out.request_spills = st.digital_splay_request_spills;
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
}  // namespace gpugeom::testing
