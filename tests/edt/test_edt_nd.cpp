// The exact distance transform of grids of 4 to 8 axes (thesis 4.2.6) on the CPU executor,
// against the brute-force reference: shapes, densities, samplings, axes of length 1, one site,
// all sites, site lists with duplicates, 32- and 64-bit site indices, the device entry, the
// caller's arrays, and the errors.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "edt_cases.hpp"

using namespace gpugeom;
using gg_edt::all_outputs;
using gg_edt::expect_exact;
using gg_edt::random_grid;

namespace {

std::string name_of(const std::vector<std::int64_t>& shape) {
  std::string s;
  for (auto e : shape) s += (s.empty() ? "" : "x") + std::to_string(e);
  return s;
}

io::Grid constant_grid(const std::vector<std::int64_t>& shape, std::uint8_t v) {
  io::Grid g;
  g.shape = shape;
  g.type = io::ScalarType::U8;
  g.data.assign(std::size_t(g.count()), v);
  return g;
}

void expect_same(const EdtResult& a, const EdtResult& b, const std::string& what) {
  EXPECT_EQ(a.shape, b.shape) << what;
  EXPECT_TRUE(a.sqdist_int == b.sqdist_int) << what;
  EXPECT_TRUE(a.sqdist_real == b.sqdist_real) << what;
  EXPECT_TRUE(a.distance64 == b.distance64) << what;
  EXPECT_TRUE(a.features == b.features) << what;
  EXPECT_TRUE(a.labels == b.labels) << what;
}

}  // namespace

TEST(EdtNd, ShapesAndDensities) {
  const std::vector<std::vector<std::int64_t>> shapes{{5, 6, 7, 8},
                                                      {9, 1, 8, 7},
                                                      {1, 1, 1, 13},
                                                      {3, 4, 5, 4, 3},
                                                      {2, 3, 2, 3, 2, 2},
                                                      {3, 2, 3, 2, 3, 2, 2},
                                                      {2, 3, 2, 3, 2, 2, 3, 2},
                                                      {1, 1, 1, 1},
                                                      {16, 1, 16, 1},
                                                      {2, 2, 2, 2, 2, 2, 2, 2}};
  unsigned seed = 7;
  for (auto& s : shapes)
    for (double density : {0.002, 0.05, 0.3})
      expect_exact(random_grid(s, density, seed++), all_outputs(),
                   name_of(s) + " density " + std::to_string(density));
}

TEST(EdtNd, TiesOnSymmetricGrids) {
  // Sites at the corners and the centre of a 4D box: many voxels are equally near to several.
  const std::vector<std::int64_t> shape{7, 5, 9, 7};
  io::Grid g = constant_grid(shape, 0);
  auto at = [&](std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) -> std::uint8_t& {
    return g.data[std::size_t(((a * 5 + b) * 9 + c) * 7 + d)];
  };
  for (std::int64_t a : {0, 6})
    for (std::int64_t b : {0, 4})
      for (std::int64_t c : {0, 8})
        for (std::int64_t d : {0, 6}) at(a, b, c, d) = 1;
  at(3, 2, 4, 3) = 1;
  expect_exact(g, all_outputs(), "corners and centre");
  // Every other voxel along each axis: ties everywhere.
  for (std::int64_t i = 0; i < g.count(); ++i) g.data[std::size_t(i)] = (i % 2) == 0;
  expect_exact(g, all_outputs(), "alternate voxels");
}

TEST(EdtNd, AnisotropicSampling) {
  unsigned seed = 31;
  for (auto& sampling : std::vector<std::vector<double>>{
           {1, 2, 0.5, 3}, {0.3, 1.7, 2.9, 0.1}, {1, 1, 1, 2}, {2, 2, 2, 2}}) {
    auto o = all_outputs();
    o.sampling = sampling;
    for (double density : {0.01, 0.2})
      expect_exact(random_grid({6, 7, 5, 8}, density, seed++), o, "4D sampling");
  }
  auto o = all_outputs();
  o.sampling = {1.5, 0.5, 2, 1, 0.75};
  expect_exact(random_grid({4, 5, 3, 6, 4}, 0.05, 3), o, "5D sampling");
}

TEST(EdtNd, OneSiteAllSitesAndLists) {
  io::Grid one = constant_grid({4, 3, 5, 6}, 0);
  one.data[17] = 1;
  expect_exact(one, all_outputs(), "one site");
  expect_exact(constant_grid({3, 3, 3, 3, 3}, 1), all_outputs(), "all sites");
  // A list with duplicates equals the grid of its sites (labels: the first index of each).
  const std::vector<std::int64_t> shape{5, 4, 6, 3};
  const std::vector<std::int64_t> sites{1, 2, 3, 0, 4, 0, 5, 2, 1, 2, 3, 0, 0, 3, 0, 1};
  const auto r = distance_transform_sites(shape, sites, all_outputs());
  io::Grid g = constant_grid(shape, 0);
  for (std::size_t i = 0; i < sites.size(); i += 4)
    g.data[std::size_t(((sites[i] * 4 + sites[i + 1]) * 6 + sites[i + 2]) * 3 + sites[i + 3])] = 1;
  auto rg = distance_transform(g, SiteRule::NonZero, all_outputs());
  EXPECT_TRUE(r.features == rg.features);
  EXPECT_TRUE(r.sqdist_int == rg.sqdist_int);
  // Grid labels are raster ranks; the list's are list indices: sites (4,0,5,2) = index 1 has
  // rank 2 of 3, (1,2,3,0) = indices 0 and 2 has rank 1, (0,3,0,1) = index 3 has rank 0.
  const std::int32_t of_rank[3] = {3, 0, 1};
  for (std::size_t i = 0; i < r.labels.size(); ++i)
    ASSERT_EQ(r.labels[i], of_rank[rg.labels[i]]) << i;
}

TEST(EdtNd, WideIndicesSameResults) {
  for (auto& sampling : std::vector<std::vector<double>>{{}, {1, 0.5, 2, 1, 1.25}}) {
    auto o = all_outputs();
    o.sampling = sampling;
    const io::Grid g = random_grid({5, 4, 6, 3, 7}, 0.02, 9);
    const auto narrow = distance_transform(g, SiteRule::NonZero, o);
    o.wide_indices = true;
    const auto wide = distance_transform(g, SiteRule::NonZero, o);
    EXPECT_EQ(narrow.stats.index_bits, 32);
    EXPECT_EQ(wide.stats.index_bits, 64);
    expect_same(narrow, wide, "64-bit indices");
  }
}

TEST(EdtNd, ZeroRuleDeviceEntryAndCallerArrays) {
  const io::Grid g = random_grid({6, 5, 4, 7}, 0.9, 4);  // zeros are the sites: 10 %
  EdtOptions o;
  o.distance = 64;
  o.features = true;
  const auto host = distance_transform(g, SiteRule::Zero, o);
  io::Grid inv = g;
  for (auto& v : inv.data) v = v == 0;
  expect_same(host, distance_transform(inv, SiteRule::NonZero, o), "zero rule");
  // The device entry on the CPU executor writes the same values.
  o.backend = Backend::Cpu;
  const auto dev = distance_transform_device(view_of(g), SiteRule::Zero, o);
  ASSERT_EQ(dev.backend, Backend::Cpu);
  const std::int64_t n = g.count();
  for (std::int64_t i = 0; i < n; ++i) ASSERT_EQ(dev.distance64.get()[i], host.distance64[i]);
  for (std::int64_t i = 0; i < 4 * n; ++i) ASSERT_EQ(dev.features.get()[i], host.features[i]);
  // The caller's arrays are written, and absent from the result.
  std::vector<double> d(std::size_t(n), -1);
  std::vector<std::int32_t> f(std::size_t(4 * n), -1);
  o.into.distance64 = {d.data(), n};
  o.into.features = {f.data(), 4 * n};
  const auto into = distance_transform(g, SiteRule::Zero, o);
  EXPECT_TRUE(into.distance64.empty() && into.features.empty());
  EXPECT_TRUE(std::equal(d.begin(), d.end(), host.distance64.begin()));
  EXPECT_TRUE(std::equal(f.begin(), f.end(), host.features.begin()));
}

TEST(EdtNd, ClearErrors) {
  auto code = [](auto&& f) -> std::optional<ErrorCode> {
    try {
      f();
    } catch (const Error& e) {
      return e.code();
    }
    return std::nullopt;
  };
  const io::Grid none = constant_grid({3, 3, 3, 3}, 0);
  EXPECT_EQ(code([&] { distance_transform(none, SiteRule::NonZero, all_outputs()); }),
            ErrorCode::InvalidInput);
  EXPECT_EQ(code([&] {
              distance_transform(constant_grid(std::vector<std::int64_t>(9, 2), 1),
                                 SiteRule::NonZero, all_outputs());
            }),
            ErrorCode::InvalidInput);
  EXPECT_EQ(code([&] { distance_transform(constant_grid({5}, 1), SiteRule::NonZero, {}); }),
            ErrorCode::InvalidInput);
  auto o = all_outputs();
  o.sampling = {1, 2, 3};
  EXPECT_EQ(code([&] {
              distance_transform(constant_grid({2, 2, 2, 2}, 1), SiteRule::NonZero, o);
            }),
            ErrorCode::InvalidArgument);
  o = all_outputs();
  o.slices = {2};  // outside the grid
  EXPECT_EQ(code([&] {
              distance_transform(constant_grid({2, 2, 2, 2}, 1), SiteRule::NonZero, o);
            }),
            ErrorCode::InvalidArgument);
  o = all_outputs();
  o.method = EdtMethod::Jfa;
  EXPECT_EQ(code([&] {
              distance_transform(constant_grid({2, 2, 2, 2}, 1), SiteRule::NonZero, o);
            }),
            ErrorCode::InvalidArgument);
  EXPECT_EQ(code([&] {
              distance_transform_sites({3, 3, 3, 3}, {0, 0, 0, 3}, all_outputs());
            }),
            ErrorCode::InvalidInput);
  // An extent past 65536.
  EXPECT_EQ(code([&] {
              distance_transform_sites({2, 2, 2, 70000}, {0, 0, 0, 0}, all_outputs());
            }),
            ErrorCode::InvalidInput);
  try {
    distance_transform(none, SiteRule::NonZero, all_outputs());
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no site"), std::string::npos) << e.what();
  }
}

TEST(EdtNd, SlicesEqualWholeVolume) {
  // Slices along C axis 0 (in order, out of order, repeated), several per block or one, from a
  // grid and from a site list, isotropic and not, 32- and 64-bit indices.
  const std::vector<std::vector<std::int64_t>> shapes{{9, 5, 6, 7}, {7, 4, 3, 5, 4}};
  unsigned seed = 60;
  for (auto& shape : shapes)
    for (auto& sampling :
         std::vector<std::vector<double>>{{}, std::vector<double>(shape.size(), 1.5)}) {
      const io::Grid g = random_grid(shape, 0.01, seed++);
      auto o = all_outputs();
      o.sampling = sampling;
      const auto whole = distance_transform(g, SiteRule::NonZero, o);
      std::vector<std::int64_t> list;
      for (std::int64_t i = 0, n = g.count(); i < n; ++i) {
        if (!g.data[std::size_t(i)]) continue;
        std::int64_t c[8], r = i;
        for (int j = int(shape.size()) - 1; j >= 0; --j) c[j] = r % shape[j], r /= shape[j];
        list.insert(list.end(), c, c + shape.size());
      }
      const auto whole_list = distance_transform_sites(shape, list, o);
      const std::int64_t plane = g.count() / shape[0];
      for (auto& slices : std::vector<std::vector<std::int64_t>>{
               {0, 1, 2, 3, 4, 5, 6}, {6, 0, 3}, {2, 2, 5}, {shape[0] - 1}}) {
        for (std::int64_t block : {0, 1, 2}) {
          for (bool wide : {false, true}) {
            auto so = o;
            so.slices = slices;
            so.slice_block = block * plane;
            so.wide_indices = wide;
            const std::string what = name_of(shape) + " slices " + std::to_string(slices[0]) +
                                     "... block " + std::to_string(block);
            expect_same(distance_transform(g, SiteRule::NonZero, so),
                        gg_edt::slices_of(whole, slices), what);
            expect_same(distance_transform_sites(shape, list, so),
                        gg_edt::slices_of(whole_list, slices), what + " list");
          }
        }
      }
    }
}
