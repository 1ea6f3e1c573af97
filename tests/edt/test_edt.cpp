// The exact distance transform on the CPU executor against a brute-force rational reference,
// for many shapes, densities and samplings; slice mode against the whole volume; band counts;
// SciPy-style zero sites; errors.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>

#include "edt/edt_backend.hpp"
#include "edt_cases.hpp"
#include "gpugeom/multi_gpu.hpp"
#include "verify.hpp"

using namespace gpugeom;
using gg_edt::brute_force;
using gg_edt::random_grid;

using gg_edt::all_outputs;
using gg_edt::expect_exact;
using gg_edt::Slab;
using gg_edt::slab_of;
using gg_edt::slices_of;

TEST(Edt, ShapesAndDensities2d) {
  const std::vector<std::vector<std::int64_t>> shapes{{1, 1},   {1, 37},  {41, 1}, {7, 13},
                                                      {32, 32}, {33, 65}, {64, 17}};
  unsigned seed = 1;
  for (auto& s : shapes)
    for (double d : {0.001, 0.02, 0.1, 0.5, 0.9, 1.0})
      expect_exact(random_grid(s, d, seed++), all_outputs(), "2d");
}

TEST(Edt, ShapesAndDensities3d) {
  const std::vector<std::vector<std::int64_t>> shapes{
      {1, 1, 9}, {5, 1, 1}, {3, 7, 5}, {9, 8, 17}, {16, 16, 16}};
  unsigned seed = 100;
  for (auto& s : shapes)
    for (double d : {0.001, 0.05, 0.3, 0.9})
      expect_exact(random_grid(s, d, seed++), all_outputs(), "3d");
}

TEST(Edt, TiesOnSymmetricGrids) {
  // Sites on a coarse lattice make many exact ties: the first site in raster order must win.
  for (auto shape : {std::vector<std::int64_t>{31, 29}, std::vector<std::int64_t>{9, 11, 13}}) {
    io::Grid g = random_grid(shape, 0, 7);
    std::fill(g.data.begin(), g.data.end(), 0);
    for (std::int64_t i = 0; i < g.count(); i += 6) g.data[i] = 1;
    expect_exact(g, all_outputs(), "lattice");
  }
}

TEST(Edt, AnisotropicSampling) {
  for (auto sampling :
       {std::vector<double>{1.5, 0.5}, std::vector<double>{0.1, 0.3}, std::vector<double>{2, 1}}) {
    EdtOptions o = all_outputs();
    o.sampling = sampling;
    expect_exact(random_grid({23, 31}, 0.05, 3), o, "aniso2d");
    io::Grid g = random_grid({20, 20}, 0, 3);
    std::fill(g.data.begin(), g.data.end(), 0);
    for (std::int64_t i = 0; i < g.count(); i += 7) g.data[i] = 1;
    expect_exact(g, o, "aniso2d lattice");
  }
  EdtOptions o = all_outputs();
  o.sampling = {0.7, 1.3, 2.0};
  expect_exact(random_grid({9, 14, 11}, 0.05, 4), o, "aniso3d");
}

TEST(Edt, BandCountsDoNotChangeTheResult) {
  io::Grid g = random_grid({67, 45, 38}, 0.03, 11);
  EdtOptions base = all_outputs();
  const auto ref = distance_transform(g, SiteRule::NonZero, base);
  for (std::int64_t k : {1, 2, 3, 5, 16, 64}) {
    EdtOptions o = base;
    o.bands[0] = o.bands[1] = o.bands[2] = k;
    const auto r = distance_transform(g, SiteRule::NonZero, o);
    ASSERT_EQ(r.labels, ref.labels) << "bands " << k;
    ASSERT_EQ(r.sqdist_int, ref.sqdist_int) << "bands " << k;
  }
}

// The windowed y/z passes settle a voxel within R positions or hand its line to the banded
// pass: any reach gives the exact transform, with few lines handed over (large R, dense
// sites) or nearly all (R = 1, sparse sites), or none windowed at all (0).
TEST(Edt, WindowReachDoesNotChangeTheResult) {
  unsigned seed = 40;
  for (auto shape : {std::vector<std::int64_t>{30, 41}, std::vector<std::int64_t>{1, 90},
                     std::vector<std::int64_t>{90, 1}, std::vector<std::int64_t>{13, 17, 19}})
    for (double d : {0.002, 0.05, 0.6})
      for (int reach : {0, 1, 3, 16, 1000}) {
        EdtOptions base = all_outputs();
        base.window_reach = reach;
        const io::Grid g = random_grid(shape, d, seed++);
        expect_exact(g, base, "reach " + std::to_string(reach));
        for (bool slices : {false, true})
          if (slices && shape.size() == 3) {
            EdtOptions o = base;
            o.slices = {0, 9, 12};
            const auto whole = distance_transform(g, SiteRule::NonZero, base);
            const auto sl = distance_transform(g, SiteRule::NonZero, o);
            const std::int64_t plane = shape[1] * shape[2];
            for (std::size_t k = 0; k < o.slices.size(); ++k)
              for (std::int64_t i = 0; i < plane; ++i)
                ASSERT_EQ(sl.labels[k * plane + i], whole.labels[o.slices[k] * plane + i]);
          }
      }
}

TEST(Edt, SlicesEqualWholeVolume) {
  io::Grid g = random_grid({21, 18, 25}, 0.02, 5);
  EdtOptions o = all_outputs();
  const auto whole = distance_transform(g, SiteRule::NonZero, o);
  o.slices = {0, 7, 20, 3};
  const auto part = distance_transform(g, SiteRule::NonZero, o);
  const std::int64_t plane = 18 * 25, n = g.count();
  ASSERT_EQ(part.shape, (std::vector<std::int64_t>{4, 18, 25}));
  for (std::size_t k = 0; k < o.slices.size(); ++k)
    for (std::int64_t i = 0; i < plane; ++i) {
      const std::int64_t w = o.slices[k] * plane + i, p = std::int64_t(k) * plane + i;
      ASSERT_EQ(part.labels[p], whole.labels[w]);
      ASSERT_EQ(part.sqdist_int[p], whole.sqdist_int[w]);
      for (int j = 0; j < 3; ++j)
        ASSERT_EQ(part.features[j * part.count() + p], whole.features[j * n + w]);
    }
}

// A slab of a grid with its columns' nearest sites on either side (EdtOptions::slab, the
// distributed transform's block) gives the whole grid's outputs for its indices, features in the
// whole grid's coordinates: 3D and 4D, sparse and dense, both rules, isotropic or not, slabs at
// either end, in the middle and whole, and slabs whose columns hold no site of their own.
TEST(Edt, SlabEqualsWholeGrid) {
  unsigned seed = 70;
  for (auto shape : {std::vector<std::int64_t>{40, 13, 11}, std::vector<std::int64_t>{23, 7, 5, 6}})
    for (double d : {0.004, 0.1, 0.7})
      for (SiteRule rule : {SiteRule::NonZero, SiteRule::Zero})
        for (bool aniso : {false, true}) {
          const io::Grid g = random_grid(shape, d, seed++);
          EdtOptions o = all_outputs();
          o.labels = false;
          if (aniso)
            for (std::size_t a = 0; a < shape.size(); ++a) o.sampling.push_back(0.5 + 0.75 * a);
          const auto whole = distance_transform(g, rule, o);
          const std::int64_t n0 = shape[0];
          for (auto [first, count] : {std::pair<std::int64_t, std::int64_t>{0, 1},
                                      {0, 9},
                                      {5, 3},
                                      {n0 / 2, n0 / 3},
                                      {n0 - 4, 4},
                                      {0, n0}}) {
            const Slab sl = slab_of(g, first, count, rule);
            EdtOptions so = o;
            so.slab = sl.bounds;
            std::vector<std::int64_t> zs;
            for (std::int64_t z = first; z < first + count; ++z) zs.push_back(z);
            const auto want = slices_of(whole, zs);
            const auto got = distance_transform(sl.grid, rule, so);
            // the device entry (host memory on the CPU executor) lists the slab's sites itself
            const auto dev = distance_transform_device(view_of(sl.grid), rule, so);
            const std::int64_t m = got.count();
            EXPECT_EQ(dev.shape, want.shape);
            EXPECT_EQ(bool(dev.sqdist_int), !want.sqdist_int.empty());
            EXPECT_EQ(bool(dev.sqdist_real), !want.sqdist_real.empty());
            if (dev.sqdist_int)
              EXPECT_TRUE(
                  std::equal(want.sqdist_int.begin(), want.sqdist_int.end(), dev.sqdist_int.get()));
            if (dev.sqdist_real)
              EXPECT_TRUE(std::equal(want.sqdist_real.begin(), want.sqdist_real.end(),
                                     dev.sqdist_real.get()));
            EXPECT_TRUE(dev.features &&
                        std::equal(want.features.begin(), want.features.end(), dev.features.get()));
            EXPECT_EQ(std::int64_t(want.features.size()), m * std::int64_t(shape.size()));
            const std::string what = "shape " + std::to_string(shape.size()) + "D d " +
                                     std::to_string(d) + " slab " + std::to_string(first) + "+" +
                                     std::to_string(count);
            EXPECT_EQ(got.shape, want.shape) << what;
            EXPECT_EQ(got.sqdist_int, want.sqdist_int) << what;
            EXPECT_EQ(got.sqdist_real, want.sqdist_real) << what;
            EXPECT_EQ(got.distance64, want.distance64) << what;
            EXPECT_EQ(got.features, want.features) << what;
          }
        }
}

// Every column's first and last site along axis 0 (what slabs hand each other), on 1, 3 and all
// threads, for grids of 1 to 4 axes and float grids; NaN refused.
TEST(Edt, ColumnSiteBounds) {
  unsigned seed = 80;
  for (auto shape : {std::vector<std::int64_t>{50}, std::vector<std::int64_t>{30, 9000},
                     std::vector<std::int64_t>{17, 11, 13}, std::vector<std::int64_t>{6, 5, 4, 3}})
    for (double d : {0.01, 0.3})
      for (SiteRule rule : {SiteRule::NonZero, SiteRule::Zero})
        for (int threads : {0, 1, 3}) {
          const io::Grid g = random_grid(shape, d, seed++);
          const std::int64_t plane = g.count() / shape[0], offset = 7;
          RunOptions run;
          run.threads = threads;
          GridView v;
          v.data = g.data.data();
          v.type = g.type;
          v.shape = shape;
          const auto b = column_site_bounds(v, rule, offset, run);
          RunOptions cpu = run;
          cpu.backend = Backend::Cpu;  // the device entry on host memory: the same
          const auto bd = column_site_bounds_device(v, rule, offset, cpu);
          EXPECT_EQ(bd.first, b.first);
          EXPECT_EQ(bd.last, b.last);
          ASSERT_EQ(std::int64_t(b.first.size()), plane);
          std::int64_t with = 0;
          for (std::int64_t c = 0; c < plane; ++c) {
            std::int64_t lo = -1, hi = -1;
            for (std::int64_t z = 0; z < shape[0]; ++z)
              if ((g.data[std::size_t(z * plane + c)] != 0) == (rule == SiteRule::NonZero)) {
                if (lo < 0) lo = z + offset;
                hi = z + offset;
              }
            with += lo >= 0;
            ASSERT_EQ(b.first[std::size_t(c)], lo) << "column " << c;
            ASSERT_EQ(b.last[std::size_t(c)], hi) << "column " << c;
          }
          EXPECT_EQ(b.columns_with_sites, with);
        }
  std::vector<double> f{1, 0, 2, 0, 0, 3};  // columns (1, 2, 0) and (0, 0, 3)
  GridView v;
  v.data = f.data();
  v.type = io::ScalarType::F64;
  v.shape = {3, 2};
  const auto b = column_site_bounds(v, SiteRule::Zero);
  EXPECT_EQ(std::vector<std::int64_t>(b.first.begin(), b.first.end()),
            (std::vector<std::int64_t>{2, 0}));
  EXPECT_EQ(std::vector<std::int64_t>(b.last.begin(), b.last.end()),
            (std::vector<std::int64_t>{2, 1}));
  f[4] = std::nan("");
  EXPECT_THROW(column_site_bounds(v, SiteRule::Zero), Error);
}

// Split into slabs (distance_transform_devices on the CPU executor: one slab per entry), the
// whole grid's outputs exactly, into the caller's arrays too; bad requests refused.
TEST(Edt, SlabsOfSeveralDevicesEqualOneCall) {
  unsigned seed = 85;
  for (auto shape : {std::vector<std::int64_t>{29, 14, 12}, std::vector<std::int64_t>{3, 40, 41},
                     std::vector<std::int64_t>{11, 4, 5, 6}})
    for (double d : {0.002, 0.2})
      for (std::size_t slabs : {1, 2, 3, 5}) {
        const io::Grid g = random_grid(shape, d, seed++);
        EdtOptions o = all_outputs();
        o.labels = false;
        o.distance = 32;
        if (seed % 2)
          for (std::size_t a = 0; a < shape.size(); ++a) o.sampling.push_back(1.0 + 0.5 * a);
        const auto want = distance_transform(g, SiteRule::Zero, o);
        const std::vector<int> devices(slabs, 0);
        const auto got = distance_transform_devices(view_of(g), SiteRule::Zero, devices, o);
        EXPECT_EQ(got.shape, want.shape);
        EXPECT_EQ(got.sqdist_int, want.sqdist_int);
        EXPECT_EQ(got.sqdist_real, want.sqdist_real);
        EXPECT_EQ(got.distance32, want.distance32);
        EXPECT_EQ(got.features, want.features);
        EXPECT_EQ(got.stats.slabs, std::min<std::int64_t>(std::int64_t(slabs), shape[0]));
        EdtOptions into = o;
        into.squared = false;
        std::vector<float> dist(std::size_t(g.count()));
        std::vector<std::int32_t> feat(shape.size() * std::size_t(g.count()));
        into.into.distance32 = {dist.data(), g.count()};
        into.into.features = {feat.data(), std::int64_t(feat.size())};
        const auto in = distance_transform_devices(view_of(g), SiteRule::Zero, devices, into);
        EXPECT_TRUE(in.distance32.empty() && in.features.empty());
        EXPECT_TRUE(std::equal(dist.begin(), dist.end(), want.distance32.begin()));
        EXPECT_TRUE(std::equal(feat.begin(), feat.end(), want.features.begin()));
      }
  const io::Grid g = random_grid({6, 5, 4}, 0.3, 1);
  EdtOptions o;
  o.backend = Backend::Cpu;
  o.distance = 64;
  o.labels = true;
  EXPECT_THROW(distance_transform_devices(view_of(g), SiteRule::Zero, {0, 0}, o), Error);
  o.labels = false;
  o.slices = {1};
  EXPECT_THROW(distance_transform_devices(view_of(g), SiteRule::Zero, {0, 0}, o), Error);
  o.slices = {};
  std::vector<double> wrong(7);
  o.into.distance64 = {wrong.data(), 7};
  EXPECT_THROW(distance_transform_devices(view_of(g), SiteRule::Zero, {0, 0}, o), Error);
  o.into = {};
  io::Grid flat = g;
  flat.shape = {30, 4};
  EXPECT_THROW(distance_transform_devices(view_of(flat), SiteRule::Zero, {0, 0}, o), Error);
  io::Grid ones = g;
  std::fill(ones.data.begin(), ones.data.end(), 1);
  EXPECT_THROW(distance_transform_devices(view_of(ones), SiteRule::Zero, {0, 0}, o), Error);
}

// A slab's bad options get typed errors that say what to change.
TEST(Edt, SlabErrors) {
  const io::Grid g = random_grid({12, 5, 4}, 0.2, 3);
  const Slab sl = slab_of(g, 4, 5, SiteRule::NonZero);
  EdtOptions o;
  o.distance = 64;
  o.slab = sl.bounds;
  auto code = [&](const io::Grid& grid, const EdtOptions& opt) -> std::optional<ErrorCode> {
    try {
      distance_transform(grid, SiteRule::NonZero, opt);
    } catch (const Error& e) {
      return e.code();
    }
    return std::nullopt;
  };
  EXPECT_EQ(code(sl.grid, o), std::nullopt);
  EdtOptions bad = o;
  bad.labels = true;
  EXPECT_EQ(code(sl.grid, bad), ErrorCode::InvalidArgument);
  bad = o;
  bad.slices = {5};
  EXPECT_EQ(code(sl.grid, bad), ErrorCode::InvalidArgument);
  bad = o;
  bad.slab.first = 8;  // 8 + 5 > 12
  EXPECT_EQ(code(sl.grid, bad), ErrorCode::InvalidArgument);
  bad = o;
  bad.slab.before.pop_back();
  EXPECT_EQ(code(sl.grid, bad), ErrorCode::InvalidArgument);
  bad = o;
  bad.slab.before[0] = 4;  // inside the slab
  EXPECT_EQ(code(sl.grid, bad), ErrorCode::InvalidArgument);
  bad = o;
  bad.slab.after[0] = 12;  // past the grid
  EXPECT_EQ(code(sl.grid, bad), ErrorCode::InvalidArgument);
  io::Grid flat = sl.grid;
  flat.shape = {5, 20};
  EXPECT_EQ(code(flat, o), ErrorCode::InvalidArgument);
  io::Grid empty = sl.grid;
  std::fill(empty.data.begin(), empty.data.end(), 0);
  EdtOptions none = o;
  std::fill(none.slab.before.begin(), none.slab.before.end(), -1);
  std::fill(none.slab.after.begin(), none.slab.after.end(), -1);
  EXPECT_EQ(code(empty, none), ErrorCode::InvalidInput);
  EXPECT_THROW(distance_transform_sites({12, 5, 4}, {0, 0, 0}, o), Error);
}

TEST(Edt, ExplicitSitesAndZeroRule) {
  const std::vector<std::int64_t> shape{12, 15};
  const std::vector<std::int64_t> sites{3, 4, 10, 14, 3, 4, 0, 0};  // a duplicate keeps index 0
  EdtOptions o = all_outputs();
  const auto r = distance_transform_sites(shape, sites, o);
  std::vector<std::int64_t> flat{3, 4, 10, 14, 0, 0};
  std::vector<std::int64_t> sq(r.sqdist_int.begin(), r.sqdist_int.end());
  std::vector<std::int32_t> near(r.labels.size());
  for (std::size_t i = 0; i < near.size(); ++i)
    near[i] = r.labels[i] == 3 ? 2 : (r.labels[i] == 2 ? -1 : r.labels[i]);
  EXPECT_TRUE(verify::check_edt(shape, flat, sq.data(), near.data()).ok);
  for (auto l : r.labels) EXPECT_NE(l, 2) << "the duplicate of site 0 must never be reported";
  // Zero rule: SciPy's convention (distance to the nearest zero element).
  io::Grid g = random_grid({10, 10}, 0.9, 2);
  const auto a = distance_transform(g, SiteRule::Zero, o);
  for (auto& v : g.data) v = !v;
  const auto b = distance_transform(g, SiteRule::NonZero, o);
  EXPECT_EQ(a.sqdist_int, b.sqdist_int);
}

TEST(Edt, JfaIsApproximateButClose) {
  io::Grid g = random_grid({64, 64}, 0.01, 9);
  EdtOptions o;
  o.backend = Backend::Cpu;
  o.squared = true;
  const auto exact = distance_transform(g, SiteRule::NonZero, o);
  o.method = EdtMethod::Jfa;
  const auto jfa = distance_transform(g, SiteRule::NonZero, o);
  std::int64_t wrong = 0;
  for (std::size_t i = 0; i < exact.sqdist_int.size(); ++i) {
    EXPECT_GE(jfa.sqdist_int[i], exact.sqdist_int[i]);  // never better than exact
    wrong += jfa.sqdist_int[i] != exact.sqdist_int[i];
  }
  EXPECT_LT(wrong, std::int64_t(exact.sqdist_int.size()) / 20);
}

TEST(Edt, ClearErrors) {
  io::Grid empty = random_grid({5, 5}, 0, 1);
  std::fill(empty.data.begin(), empty.data.end(), 0);
  EXPECT_THROW(distance_transform(empty, SiteRule::NonZero), Error);
  io::Grid g = random_grid({5, 5}, 0.5, 1);
  EdtOptions o;
  o.backend = Backend::Cpu;
  o.sampling = {1, -2};
  EXPECT_THROW(distance_transform(g, SiteRule::NonZero, o), Error);
  o.sampling = {1};
  EXPECT_THROW(distance_transform(g, SiteRule::NonZero, o), Error);
  o.sampling = {};
  o.slices = {1};
  EXPECT_THROW(distance_transform(g, SiteRule::NonZero, o), Error);  // 2D
  EXPECT_THROW(distance_transform_sites({4, 4}, {4, 0}, o), Error);  // outside
  try {
    distance_transform(empty, SiteRule::NonZero);
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(ErrorCode::InvalidInput));
    EXPECT_NE(std::string(e.what()).find("no site"), std::string::npos);
  }
}

namespace {
// The grid g (0/1 bytes) in another element type: sites hold `one`, the rest zero.
template <class T>
std::vector<T> typed(const io::Grid& g, T one) {
  std::vector<T> v(g.data.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = g.data[i] ? one : T(0);
  return v;
}
template <class T>
GridView view_of(const std::vector<T>& v, io::ScalarType t, const std::vector<std::int64_t>& s) {
  GridView w;
  w.data = v.data();
  w.type = t;
  w.shape = s;
  return w;
}
}  // namespace

// Every element type is read where it is, with either rule, whole and slice by slice, and gives
// the uint8 grid's transform; a NaN anywhere is refused.
TEST(Edt, TypedGridsAndNaN) {
  for (const auto& shape :
       {std::vector<std::int64_t>{37, 41}, std::vector<std::int64_t>{9, 13, 11}})
    for (int sl = 0; sl < (shape.size() == 3 ? 2 : 1); ++sl) {
      const io::Grid g = random_grid(shape, 0.05, 5);
      io::Grid inv = g;
      for (auto& b : inv.data) b = !b;
      EdtOptions o = all_outputs();
      if (sl) o.slices = {0, 4, 8};
      const auto ref = distance_transform(g, SiteRule::NonZero, o);
      auto same = [&](const EdtResult& r, const char* what) {
        EXPECT_EQ(r.sqdist_int, ref.sqdist_int) << what;
        EXPECT_EQ(r.labels, ref.labels) << what;
        EXPECT_EQ(r.features, ref.features) << what;
        EXPECT_EQ(r.shape, ref.shape) << what;
      };
      const auto u16 = typed<std::uint16_t>(g, 300);
      const auto i32 = typed<std::int32_t>(g, -7);
      const auto i64 = typed<std::int64_t>(g, std::int64_t(1) << 40);
      const auto f32 = typed<float>(g, -0.25f);
      const auto f64 = typed<double>(g, 1e-300);
      same(distance_transform(view_of(u16, io::ScalarType::U16, shape), SiteRule::NonZero, o),
           "u16");
      same(distance_transform(view_of(i32, io::ScalarType::I32, shape), SiteRule::NonZero, o),
           "i32");
      same(distance_transform(view_of(i64, io::ScalarType::I64, shape), SiteRule::NonZero, o),
           "i64");
      same(distance_transform(view_of(f32, io::ScalarType::F32, shape), SiteRule::NonZero, o),
           "f32");
      same(distance_transform(view_of(f64, io::ScalarType::F64, shape), SiteRule::NonZero, o),
           "f64");
      same(distance_transform(view_of(g.data, io::ScalarType::Bool, shape), SiteRule::NonZero, o),
           "bool");
      same(distance_transform(inv, SiteRule::Zero, o), "u8, zero rule");
      const auto f32inv = typed<float>(inv, 2.5f);
      same(distance_transform(view_of(f32inv, io::ScalarType::F32, shape), SiteRule::Zero, o),
           "f32, zero rule");
      auto nan = f32;
      nan[nan.size() / 2] = std::nanf("");
      try {
        distance_transform(view_of(nan, io::ScalarType::F32, shape), SiteRule::NonZero, o);
        ADD_FAILURE() << "a NaN was accepted";
      } catch (const Error& e) {
        EXPECT_EQ(int(e.code()), int(ErrorCode::InvalidInput));
        EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
      }
    }
}

// Outputs written into the caller's arrays (SciPy's distances= / indices=): the same values,
// the result's own arrays empty; wrong lengths and arrays for outputs not asked for refused.
TEST(Edt, CallerBuffers) {
  const std::vector<std::int64_t> shape{10, 12, 14};
  const io::Grid g = random_grid(shape, 0.02, 3);
  EdtOptions o = all_outputs();
  o.distance = 32;
  for (int sl = 0; sl < 2; ++sl) {
    if (sl) o.slices = {2, 9};
    const auto ref = distance_transform(g, SiteRule::NonZero, o);
    const std::int64_t n = ref.count();
    std::vector<float> d(n, -1);
    std::vector<std::int32_t> f(3 * n, -1), l(n, -1);
    EdtOptions w = o;
    w.into.distance32 = {d.data(), n};
    w.into.features = {f.data(), 3 * n};
    w.into.labels = {l.data(), n};
    const auto r = distance_transform(g, SiteRule::NonZero, w);
    EXPECT_TRUE(r.distance32.empty() && r.features.empty() && r.labels.empty());
    EXPECT_EQ(r.sqdist_int, ref.sqdist_int);  // (not given: the library's array)
    EXPECT_EQ(d, ref.distance32);
    EXPECT_EQ(f, ref.features);
    EXPECT_EQ(l, ref.labels);
  }
  EdtOptions bad = o;
  std::vector<float> d(5);
  bad.into.distance32 = {d.data(), 5};
  try {
    distance_transform(g, SiteRule::NonZero, bad);
    ADD_FAILURE() << "a short array was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(ErrorCode::InvalidArgument));
    EXPECT_NE(std::string(e.what()).find("into.distance32 holds 5 elements"), std::string::npos)
        << e.what();
  }
  bad = o;
  std::vector<double> d64(std::size_t(g.count()));
  bad.into.distance64 = {d64.data(), g.count()};  // distance is 32
  EXPECT_THROW(distance_transform(g, SiteRule::NonZero, bad), Error);
}

// The device entry point on the CPU executor ("device" memory is host memory): the same outputs
// as the host entry, into the library's arrays or the caller's.
TEST(Edt, DeviceEntryOnCpuExecutor) {
  const std::vector<std::int64_t> shape{21, 17, 19};
  const io::Grid g = random_grid(shape, 0.03, 8);
  EdtOptions o = all_outputs();
  const auto ref = distance_transform(g, SiteRule::NonZero, o);
  const std::int64_t n = ref.count();
  GridView v;
  v.data = g.data.data();
  v.shape = shape;
  const auto r = distance_transform_device(v, SiteRule::NonZero, o);
  EXPECT_EQ(r.backend, Backend::Cpu);
  EXPECT_EQ(r.shape, ref.shape);
  ASSERT_TRUE(r.sqdist_int && r.distance64 && r.features && r.labels);
  EXPECT_EQ(std::vector<std::int64_t>(r.sqdist_int.get(), r.sqdist_int.get() + n), ref.sqdist_int);
  EXPECT_EQ(std::vector<double>(r.distance64.get(), r.distance64.get() + n), ref.distance64);
  EXPECT_EQ(std::vector<std::int32_t>(r.features.get(), r.features.get() + 3 * n), ref.features);
  EXPECT_EQ(std::vector<std::int32_t>(r.labels.get(), r.labels.get() + n), ref.labels);
  std::vector<std::int32_t> l(n);
  o.into.labels = {l.data(), n};
  o.slices = {};
  const auto r2 = distance_transform_device(v, SiteRule::NonZero, o);
  EXPECT_FALSE(r2.labels);
  EXPECT_EQ(l, ref.labels);
  o.into = {};
  o.slices = {3, 18};
  const auto s = distance_transform_device(v, SiteRule::NonZero, o);
  const auto sref = distance_transform(g, SiteRule::NonZero, o);
  EXPECT_EQ(std::vector<std::int32_t>(s.labels.get(), s.labels.get() + s.count()), sref.labels);
}

namespace {
void expect_same(const EdtResult& a, const EdtResult& b, const std::string& what) {
  EXPECT_EQ(a.shape, b.shape) << what;
  EXPECT_EQ(a.sqdist_int, b.sqdist_int) << what;
  EXPECT_EQ(a.sqdist_real, b.sqdist_real) << what;
  EXPECT_EQ(a.distance64, b.distance64) << what;
  EXPECT_EQ(a.features, b.features) << what;
  EXPECT_EQ(a.labels, b.labels) << what;
}
}  // namespace

// Grids whose coordinates need more than 32 bits of bit fields (1600^3) pack a site as its
// raster index. Forced on small grids, that packing gives the bit fields' results exactly, on
// every path: 2D and 3D, every density, anisotropic metrics, band counts, windowed or not,
// slices, site lists, the zero rule, JFA; and the exact reference where it is cheap.
TEST(Edt, RasterIndexPackingSameResults) {
  struct Case {
    std::vector<std::int64_t> shape;
    double density;
    std::vector<double> sampling;
    int reach;
  };
  const std::vector<Case> cases{
      {{1, 1}, 1.0, {}, -1},       {{7, 13}, 0.1, {}, -1},
      {{33, 65}, 0.02, {}, -1},    {{64, 17}, 0.5, {1.5, 0.5}, -1},
      {{90, 1}, 0.05, {}, 3},      {{1, 90}, 0.002, {}, 0},
      {{30, 41}, 0.6, {}, 16},     {{3, 7, 5}, 0.3, {}, -1},
      {{9, 8, 17}, 0.05, {}, 1},   {{13, 17, 19}, 0.002, {}, 1000},
      {{16, 16, 16}, 0.9, {}, -1}, {{9, 14, 11}, 0.05, {0.7, 1.3, 2.0}, -1},
      {{21, 18, 25}, 0.02, {}, 0}};
  unsigned seed = 500;
  for (const auto& c : cases) {
    const io::Grid g = random_grid(c.shape, c.density, seed++);
    EdtOptions o = all_outputs();
    o.sampling = c.sampling;
    o.window_reach = c.reach;
    const std::string what = "shape " + std::to_string(c.shape.size()) + "D density " +
                             std::to_string(c.density) + " reach " + std::to_string(c.reach);
    const auto bits = distance_transform(g, SiteRule::NonZero, o);
    const bool zeros = std::count(g.data.begin(), g.data.end(), 0) > 0;
    const auto zero_bits = zeros ? distance_transform(g, SiteRule::Zero, o) : EdtResult{};
    EdtOptions jo;
    jo.backend = Backend::Cpu;
    jo.squared = true;
    jo.method = EdtMethod::Jfa;
    const auto jfa_bits = distance_transform(g, SiteRule::NonZero, jo);
    std::vector<std::int64_t> list;  // the sites as coordinates, last first (labels differ)
    for (std::int64_t i = g.count() - 1; i >= 0; --i)
      if (g.data[i]) {
        std::int64_t r = i, cs[3];
        for (int j = int(c.shape.size()) - 1; j >= 0; --j) cs[j] = r % c.shape[j], r /= c.shape[j];
        for (std::size_t j = 0; j < c.shape.size(); ++j) list.push_back(cs[j]);
      }
    const auto list_bits = distance_transform_sites(c.shape, list, o);
    EdtOptions so = o;
    if (c.shape.size() == 3) so.slices = {c.shape[0] - 1, 0, c.shape[0] / 2};
    const auto slices_bits =
        c.shape.size() == 3 ? distance_transform(g, SiteRule::NonZero, so) : EdtResult{};
    o.tuning = jo.tuning = so.tuning = gg_edt::linear_packing();
    expect_same(distance_transform(g, SiteRule::NonZero, o), bits, what);
    if (zeros)
      expect_same(distance_transform(g, SiteRule::Zero, o), zero_bits, what + " zero rule");
    expect_same(distance_transform(g, SiteRule::NonZero, jo), jfa_bits, what + " jfa");
    expect_same(distance_transform_sites(c.shape, list, o), list_bits, what + " list");
    if (c.shape.size() == 3)
      expect_same(distance_transform(g, SiteRule::NonZero, so), slices_bits, what + " slices");
    if (g.count() <= 4096) expect_exact(g, o, what + " linear, exact");
  }
}

// The slice-by-slice mode computes blocks of slices, with the volume's own packing or packed by
// column (ColumnLayout: taken past 2^32 - 2 voxels, forced here): every block size and both
// packings give the whole volume's slices exactly, from a grid, a site list (repeated sites
// among them) and the zero rule, isotropic or not, slices in any order and repeated.
TEST(Edt, SliceBlocksAndColumnPackingSameResults) {
  struct Case {
    std::vector<std::int64_t> shape;
    double density;
    std::vector<double> sampling;
  };
  const std::vector<Case> cases{{{3, 7, 5}, 0.3, {}},
                                {{9, 8, 17}, 0.05, {}},
                                {{13, 17, 19}, 0.002, {}},
                                {{16, 16, 16}, 0.9, {}},
                                {{9, 14, 11}, 0.05, {0.7, 1.3, 2.0}},
                                {{40, 1, 23}, 0.03, {}},
                                {{30, 12, 1}, 0.01, {2.0, 1.0, 1.0}}};
  unsigned seed = 900;
  for (const auto& c : cases) {
    const io::Grid g = random_grid(c.shape, c.density, seed++);
    const std::int64_t nz = c.shape[0], plane = c.shape[1] * c.shape[2];
    EdtOptions o = all_outputs();
    o.sampling = c.sampling;
    std::vector<std::int64_t> list;  // the sites as coordinates, and the first one again
    for (std::int64_t i = 0; i < g.count(); ++i)
      if (g.data[i])
        list.insert(list.end(), {i / plane, (i / c.shape[2]) % c.shape[1], i % c.shape[2]});
    list.insert(list.end(), list.begin(), list.begin() + 3);
    const auto whole = distance_transform(g, SiteRule::NonZero, o);
    const auto whole_list = distance_transform_sites(c.shape, list, o);
    const bool zeros = std::count(g.data.begin(), g.data.end(), 0) > 0;
    const auto whole_zero = zeros ? distance_transform(g, SiteRule::Zero, o) : EdtResult{};
    EdtOptions so = o;
    so.slices = {nz - 1, 0, nz / 2, nz / 2, nz - 1};
    for (std::int64_t z = 1; z < nz; z += 3) so.slices.push_back(z);
    for (bool columns : {false, true}) {
      so.tuning = columns ? gg_edt::column_packing() : nullptr;
      for (std::int64_t block : {std::int64_t(0), std::int64_t(1), 2 * plane, 3 * plane + 1}) {
        so.slice_block = block;
        const std::string what = "shape " + std::to_string(c.shape[0]) + "x" +
                                 std::to_string(c.shape[1]) + "x" + std::to_string(c.shape[2]) +
                                 (columns ? " columns" : "") + " block " + std::to_string(block);
        const auto r = distance_transform(g, SiteRule::NonZero, so);
        expect_same(r, gg_edt::slices_of(whole, so.slices), what);
        const std::int64_t per = r.stats.slices_per_block;
        EXPECT_EQ(per, block == 0 ? std::int64_t(so.slices.size())
                                  : std::max<std::int64_t>(1, block / plane))
            << what;
        expect_same(distance_transform_sites(c.shape, list, so),
                    gg_edt::slices_of(whole_list, so.slices), what + " list");
        if (zeros)
          expect_same(distance_transform(g, SiteRule::Zero, so),
                      gg_edt::slices_of(whole_zero, so.slices), what + " zero rule");
      }
    }
  }
}

// The divisions that decode a raster index (Granlund-Montgomery multiply-high) are exact for
// every 32-bit numerator: divisors of every size, numerators at and around their multiples.
TEST(Edt, RasterIndexDivisionIsExact) {
  std::mt19937_64 r(3);
  std::vector<std::uint32_t> divisors{1,    2,       3,       5,     7,     10,    641,        1600,
                                      1625, 2560000, 2640625, 65535, 65536, 65537, 4294967295u};
  for (int k = 0; k < 200; ++k) divisors.push_back(std::uint32_t(r() >> (32 + r() % 32)) | 1u);
  for (std::uint32_t d : divisors) {
    const auto v = edt::Divider::of(d);
    std::vector<std::uint32_t> ns{0, 1, d - 1, d, 4294967295u, 4294967294u};
    for (int k = 0; k < 300; ++k) {
      const std::uint64_t m = (r() % (4294967295ull / d + 1)) * d;
      for (std::int64_t e = -1; e <= 1; ++e)
        if (std::int64_t(m) + e >= 0 && std::int64_t(m) + e <= 4294967295ll)
          ns.push_back(std::uint32_t(m + e));
      ns.push_back(std::uint32_t(r()));
    }
    for (std::uint32_t n : ns) ASSERT_EQ(v.div(n), n / d) << n << " / " << d;
  }
}

// The true limits, refused before any work with the numbers.
TEST(Edt, SizeLimitsAreStated) {
  auto message = [](const std::vector<std::int64_t>& shape) {
    try {
      distance_transform_sites(shape, std::vector<std::int64_t>(shape.size(), 0));
    } catch (const Error& e) {
      EXPECT_EQ(int(e.code()), int(ErrorCode::InvalidInput));
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({1700, 1700, 1700}).find("4913000000 voxels, at most 2^32-2"),
            std::string::npos);
  EXPECT_NE(message({65536, 65536}).find("at most 2^32-2"), std::string::npos);
  EXPECT_NE(message({2, 2, 70000}).find("at most 65536 along an axis of a 3D grid"),
            std::string::npos);
  EXPECT_NE(message({2, 140000}).find("at most 131072"), std::string::npos);
  // The largest shapes are taken (the layout only: no grid of that size is allocated here).
  EXPECT_TRUE(edt::make_layout({1600, 1600, 1600}).linear);
  EXPECT_TRUE(edt::make_layout({1625, 1625, 1625}).linear);
  EXPECT_FALSE(edt::make_layout({1024, 1024, 2048}).linear);
  EXPECT_FALSE(edt::make_layout({1025, 1024, 2048}).linear);  // 11 + 10 + 11 bits
  EXPECT_TRUE(edt::make_layout({1025, 1025, 2048}).linear);
  EXPECT_THROW(edt::make_layout({1600, 1600, 1600}, false, edt::Packing::Bits), Error);
  // By slices only a slice must fit: any voxel count, slices below 2^31 - 1 voxels.
  EXPECT_NO_THROW(edt::make_layout({65536, 46340, 46340}, true));
  try {
    edt::make_layout({2, 46341, 46341}, true);
    ADD_FAILURE() << "a slice of 2^31 voxels or more was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2147488281 voxels is too large: at most 2^31-2"),
              std::string::npos)
        << e.what();
  }
}

// Slice by slice, a volume of more than 2^32 voxels (4.4e9) known by its listed sites: every
// output of every computed slice is the brute force's, ties across columns included, with and
// without sampling; a whole transform of it is refused with the way out.
TEST(Edt, SlicesOfVolumesPastTwoToThe32Voxels) {
  const gg_edt::TallVolume t = gg_edt::tall_volume(7);
  const std::int64_t plane = t.shape[1] * t.shape[2];
  for (bool aniso : {false, true}) {
    EdtOptions o = all_outputs();
    o.slices = t.slices;
    std::int64_t w[3] = {1, 1, 1};
    if (aniso) o.sampling = {3, 1, 2}, w[0] = 9, w[2] = 4;
    const auto r = distance_transform_sites(t.shape, t.sites, o);
    const auto ref = gg_edt::slice_reference(t, w);
    const std::int64_t n = std::int64_t(t.slices.size()) * plane;
    ASSERT_EQ(r.count(), n);
    for (std::int64_t i = 0; i < n; ++i) {
      const std::string at = std::string(aniso ? "sampled" : "isotropic") + ", slice " +
                             std::to_string(t.slices[i / plane]) + " voxel " +
                             std::to_string(i % plane);
      if (aniso)
        ASSERT_EQ(r.sqdist_real[i], double(ref.sq[i])) << at;  // integers: exact in doubles
      else
        ASSERT_EQ(r.sqdist_int[i], ref.sq[i]) << at;
      for (int a = 0; a < 3; ++a)
        ASSERT_EQ(r.features[a * n + i], ref.coords[3 * i + a]) << at << " axis " << a;
      ASSERT_EQ(r.labels[i], ref.label[i]) << at;
    }
  }
  try {
    distance_transform_sites(t.shape, t.sites, all_outputs());
    ADD_FAILURE() << "a whole transform of 2^32 voxels or more was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("compute it by slices"), std::string::npos) << e.what();
  }
}
