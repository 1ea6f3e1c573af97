// The several devices' block entry (blocks/block_pass_on.hpp, run through the module's table on
// the CPU executor) against gpugeom.dask's host passes (block_required, block_borders,
// block_output) over the same triangulation: the rows, the simplices to test, the borders and
// the face requests must be the same, since both apply simplex_rules.hpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "blocks/block_pass.hpp"
#include "delaunay3d/del3d_backend.hpp"

namespace {

using namespace gpugeom;

TEST(BlockPass, SameAsTheHostPasses) {
  const std::int64_t n = 4000;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> p(static_cast<std::size_t>(3 * n));
  for (auto& x : p) x = u(rng);
  // three blocks along x; block 1 (the middle) is this one, its region grown by 0.05
  CellGrid grid;
  grid.counts[0] = 3;
  grid.width[0] = 1.0 / 3.0, grid.width[1] = 1.0, grid.width[2] = 1.0;
  const double margin = 1e-9, scale = 1.0;
  BlockBoxes boxes;
  boxes.region_lo[0] = 1.0 / 3.0 - 0.05, boxes.region_hi[0] = 2.0 / 3.0 + 0.05;
  for (int j = 0; j < 3; ++j) {
    if (j) boxes.region_lo[j] = 0.0, boxes.region_hi[j] = 1.0;
    boxes.bounds_lo[j] = 0.0, boxes.bounds_hi[j] = 1.0;
  }
  boxes.scale = scale;
  const std::int64_t block = 1;
  const auto size = static_cast<std::size_t>(n);
  std::vector<std::int32_t> blk(size), ids(size);
  std::vector<std::uint8_t> owned(size);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t c = std::min<std::int64_t>(2, std::int64_t(p[std::size_t(3 * i)] * 3.0));
    blk[std::size_t(i)] = std::int32_t(c);
    ids[std::size_t(i)] = std::int32_t(7 * i);  // (any names)
    owned[std::size_t(i)] = c == block;
  }

  // the entry, on the CPU executor
  Delaunay3dOptions o;
  o.backend = Backend::Cpu;
  blocks_detail::BorderCells cells{grid, 3, margin};
  blocks_detail::BlockTask t;
  t.points = p.data(), t.n = n, t.ids = ids.data(), t.blk = blk.data(), t.block = block;
  t.cells = &cells, t.scale = scale, t.boxes = &boxes;
  blocks_detail::BlockRows got;
  bool asked = false;
  del3d::cpu_impl::assembly.block(
      o, t, [&](const blocks_detail::BlockRows&) { return asked = true; }, got);
  ASSERT_TRUE(asked);
  ASSERT_TRUE(got.final);

  // the host passes over the same triangulation
  const Triangulation3d tri = delaunay3d(p.data(), n, o);
  const std::int64_t m = tri.num_tetrahedra;
  const std::int32_t* s = tri.tetrahedra.data();
  const std::int32_t* nb = tri.neighbors.data();
  const BlockRequired req = block_required(s, nb, m, 3, owned.data());
  std::vector<std::uint8_t> inside(static_cast<std::size_t>(m));
  const BlockBorders bd = block_borders(p.data(), 3, s, nb, m, n, owned.data(), block, grid, margin,
                                        scale, &boxes, inside.data());
  std::vector<std::int32_t> test;
  for (std::int64_t i = 0; i < m; ++i)
    if (req.required[std::size_t(i)] && !inside[std::size_t(i)])
      test.insert(test.end(), s + 4 * i, s + 4 * i + 4);
  EXPECT_FALSE(test.empty());  // (the region's edge cuts balls: the test has work)
  EXPECT_EQ(std::vector<std::int32_t>(got.test.begin(), got.test.end()), test);
  ASSERT_EQ(got.borders.size(), bd.targets.size());
  EXPECT_EQ(bd.targets.size(), 2u);
  for (std::size_t k = 0; k < bd.targets.size(); ++k) {
    EXPECT_EQ(got.borders[k].first, bd.targets[k]);
    const std::vector<std::int64_t> want(bd.vertices.begin() + bd.offsets[k],
                                         bd.vertices.begin() + bd.offsets[k + 1]);
    EXPECT_EQ(std::vector<std::int64_t>(got.borders[k].second.begin(), got.borders[k].second.end()),
              want);
  }
  const std::int64_t count = std::int64_t(req.owned_rows.size());
  const BlockOutput out =
      block_output(s, nb, m, 3, req.owned_rows.data(), count, ids.data(), blk.data(), nullptr, n);
  ASSERT_EQ(got.count, count);
  const std::int32_t* gs = got.simplices.get();
  const std::int32_t* gn = got.neighbors.get();
  EXPECT_EQ(std::vector<std::int32_t>(gs, gs + 4 * count),
            std::vector<std::int32_t>(out.simplices.begin(), out.simplices.end()));
  EXPECT_EQ(std::vector<std::int32_t>(gn, gn + 4 * count),
            std::vector<std::int32_t>(out.neighbors.begin(), out.neighbors.end()));
  auto wide = [](const auto& v) { return std::vector<std::int64_t>(v.begin(), v.end()); };
  EXPECT_FALSE(out.request_pos.empty());
  EXPECT_EQ(wide(got.request_pos), wide(out.request_pos));
  EXPECT_EQ(wide(got.request_key), wide(out.request_key));
  EXPECT_EQ(wide(got.request_owner), wide(out.request_owner));
  EXPECT_EQ(wide(got.request_open), wide(out.request_open));
}

}  // namespace
