// Weighted centroidal Voronoi diagrams on the CPU executor: every Lloyd step equals a brute-force
// step (cells, masses, energy, moves), the energy never increases, uniform densities converge to
// cells of near-equal mass, and bad input gets typed errors.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <numeric>

#include "cvd_cases.hpp"

using namespace gpugeom;

namespace {

CvdOptions cpu_options(const std::vector<double>& sites, int iterations) {
  CvdOptions o;
  o.backend = Backend::Cpu;
  o.initial_sites = sites;
  o.max_iterations = iterations;
  o.move_tolerance = 0;
  return o;
}

// Number of 4-connected (6-connected in 3D) components of every site's cell.
int split_cells(const io::Grid& g, const std::vector<std::int32_t>& owner, std::int64_t ns) {
  const int nd = int(g.shape.size());
  std::int64_t ext[3] = {1, 1, 1};
  for (int a = 0; a < nd; ++a) ext[a] = g.shape[nd - 1 - a];
  const std::int64_t n = g.count();
  std::vector<int> comp(std::size_t(ns), 0);
  std::vector<char> seen(std::size_t(n), 0);
  for (std::int64_t s = 0; s < n; ++s) {
    if (seen[s]) continue;
    ++comp[owner[s]];
    std::vector<std::int64_t> stack{s};
    seen[s] = 1;
    while (!stack.empty()) {
      const std::int64_t i = stack.back();
      stack.pop_back();
      const std::int64_t c[3] = {i % ext[0], (i / ext[0]) % ext[1], i / (ext[0] * ext[1])};
      for (int a = 0; a < nd; ++a)
        for (int d = -1; d <= 1; d += 2) {
          std::int64_t e[3] = {c[0], c[1], c[2]};
          e[a] += d;
          if (e[a] < 0 || e[a] >= ext[a]) continue;
          const std::int64_t j = e[0] + ext[0] * (e[1] + ext[1] * e[2]);
          if (!seen[j] && owner[j] == owner[i]) seen[j] = 1, stack.push_back(j);
        }
    }
  }
  int split = 0;
  for (int c : comp) split += c > 1;
  return split;
}

}  // namespace

TEST(Cvd, EveryStepEqualsBruteForce) {
  struct Case {
    std::vector<std::int64_t> shape;
    double zero_frac;
    int sites;
  };
  // Many sites on small grids (thin cells, cells in several pieces), few sites on large ones
  // (elongated cells reaching across empty regions and the border), zero-density regions, and
  // uniform densities (the unweighted diagram).
  const std::vector<Case> cases{{{40, 40}, 0.0, 150},   {{23, 61}, 0.3, 40}, {{64, 48}, 0.0, 3},
                                {{1, 50}, 0.0, 5},      {{50, 1}, 0.2, 4},   {{9, 10, 11}, 0.0, 60},
                                {{17, 5, 30}, 0.5, 12}, {{30, 30}, 0.9, 6},  {{37, 29}, -1, 25},
                                {{12, 13, 14}, -1, 30}};
  unsigned seed = 10;
  int split = 0;
  for (const auto& c : cases) {
    const io::Grid g = gg_cvd::random_density(c.shape, c.zero_frac, seed);
    std::vector<double> sites = gg_cvd::random_sites(g, c.sites, seed++);
    for (int it = 0; it < 4; ++it) {
      const auto ref = gg_cvd::brute_step(g, sites);
      const auto r = centroidal_voronoi(g, cpu_options(sites, 1));
      SCOPED_TRACE("case seed " + std::to_string(seed - 1) + " step " + std::to_string(it));
      ASSERT_EQ(r.sites, ref.sites);
      ASSERT_EQ(r.mass, ref.mass);
      ASSERT_EQ(r.energy.size(), 1u);
      ASSERT_EQ(r.energy[0], ref.energy);
      split += split_cells(g, ref.owner, c.sites);
      sites = ref.sites;
    }
  }
  EXPECT_GT(split, 0) << "no case had a cell in several pieces";
}

TEST(Cvd, RepeatedSitesKeepTheFirst) {
  const io::Grid g = gg_cvd::random_density({20, 30}, 0.0, 3);
  const std::vector<double> sites{4, 4, 10, 12, 4, 4, 25, 3};
  const auto r = centroidal_voronoi(g, cpu_options(sites, 1));
  const auto ref = gg_cvd::brute_step(g, sites);
  EXPECT_EQ(r.mass[2], 0.0);
  EXPECT_GT(r.mass[0], 0.0);
  EXPECT_EQ(r.sites, ref.sites);
}

TEST(Cvd, EnergyNeverIncreases) {
  for (auto shape : {std::vector<std::int64_t>{80, 120}, std::vector<std::int64_t>{20, 24, 28}}) {
    const io::Grid g = gg_cvd::random_density(shape, 0.2, 5);
    CvdOptions o;
    o.backend = Backend::Cpu;
    o.num_sites = shape.size() == 2 ? 300 : 200;
    o.max_iterations = 60;
    o.move_tolerance = 0;
    const auto r = centroidal_voronoi(g, o);
    ASSERT_GE(r.energy.size(), 2u);
    for (std::size_t i = 1; i < r.energy.size(); ++i) EXPECT_LE(r.energy[i], r.energy[i - 1]) << i;
    EXPECT_LT(r.energy.back(), r.energy.front());
  }
}

// Lloyd on a uniform density converges (no site moves any more), and the cells end near-equal
// in mass. The random start's cells are Poisson-Voronoi-like (mass coefficient of variation
// about 0.5 in 2D); a centroidal tessellation's are near-regular hexagons, unequal only through
// the border, defects of the hexagonal packing and whole-grid-point boundaries. The digital
// iteration stops once every centroid is within half a grid step of its site, before
// continuous Lloyd would; on this 640^2 grid (4 points per pixel) that leaves a CV near 0.1,
// hence the bound: 0.13, and at least 3 times below the start's.
TEST(Cvd, UniformDensityConvergesToEqualMasses) {
  io::Grid g;
  g.shape = {160, 160};
  g.type = io::ScalarType::U8;
  g.data.assign(160 * 160, 255);
  CvdOptions o;
  o.backend = Backend::Cpu;
  o.num_sites = 80;
  o.max_iterations = 1000;
  o.move_tolerance = 0;
  o.supersample = 4;
  o.seed = 3;
  auto cv = [](const auto& mass) {
    const double mean = std::accumulate(mass.begin(), mass.end(), 0.0) / mass.size();
    double var = 0;
    for (double m : mass) var += (m - mean) * (m - mean);
    return std::sqrt(var / mass.size()) / mean;
  };
  const auto r = centroidal_voronoi(g, o);
  EXPECT_TRUE(r.converged);
  o.max_iterations = 1;
  const double start = cv(centroidal_voronoi(g, o).mass);
  EXPECT_GT(start, 0.3);
  EXPECT_LT(cv(r.mass), 0.13) << "after " << r.iterations << " iterations";
  EXPECT_LT(cv(r.mass) * 3, start);
  const double total = std::accumulate(r.mass.begin(), r.mass.end(), 0.0);
  EXPECT_NEAR(total, 160.0 * 160.0 * 255, 1e-6 * total);  // the density is 255 everywhere
  // The statistics' counters are fields, printed under their names.
  EXPECT_EQ(r.stats.sites, 80);
  EXPECT_EQ(r.stats.iterations, r.iterations);
  EXPECT_EQ(r.stats.grid_points, 640 * 640);  // (supersampled 4 times a side)
  EXPECT_EQ(r.stats.counter_map(),
            (std::map<std::string, std::int64_t>{
                {"grid_points", 640 * 640}, {"sites", 80}, {"iterations", r.iterations}}));
}

TEST(Cvd, SupersampleIsTheUpsampledDensity) {
  const io::Grid g = gg_cvd::random_density({12, 17}, 0.2, 8);
  io::Grid up;  // each pixel as 3 x 3 grid points
  up.shape = {36, 51};
  up.type = g.type;
  up.data.resize(36 * 51 * 2);
  for (std::int64_t y = 0; y < 36; ++y)
    for (std::int64_t x = 0; x < 51; ++x)
      std::memcpy(&up.data[(y * 51 + x) * 2], &g.data[((y / 3) * 17 + x / 3) * 2], 2);
  // The same start on both: fine pixel f is coarse pixel (f - 1) / 3 (pixel centres).
  const std::vector<double> fine_sites = gg_cvd::random_sites(up, 20, 9);
  CvdOptions fine = cpu_options(fine_sites, 5), coarse = fine;
  coarse.supersample = 3;
  coarse.initial_sites.clear();
  for (double v : fine_sites) coarse.initial_sites.push_back((v - 1) / 3);
  const auto a = centroidal_voronoi(up, fine);
  const auto b = centroidal_voronoi(g, coarse);
  ASSERT_EQ(a.sites.size(), b.sites.size());
  for (std::size_t i = 0; i < a.sites.size(); ++i)
    EXPECT_NEAR(b.sites[i], (a.sites[i] - 1) / 3, 1e-12);
  for (std::size_t i = 0; i < a.mass.size(); ++i)
    EXPECT_NEAR(b.mass[i] * 9, a.mass[i], 1e-9 * (1 + a.mass[i]));
  ASSERT_EQ(a.energy.size(), b.energy.size());
  for (std::size_t i = 0; i < a.energy.size(); ++i)
    EXPECT_NEAR(b.energy[i] * 81, a.energy[i], 1e-9 * a.energy[i]);
}

TEST(Cvd, ProgressSeesEveryIterationAndCanStop) {
  const io::Grid g = gg_cvd::random_density({50, 50}, 0.0, 2);
  CvdOptions o;
  o.backend = Backend::Cpu;
  o.num_sites = 30;
  o.max_iterations = 100;
  o.move_tolerance = 0;
  int calls = 0;
  o.progress = [&](const CvdProgress& p) {
    EXPECT_EQ(p.iteration, ++calls);
    EXPECT_GT(p.energy, 0);
    return p.iteration < 3;
  };
  const auto r = centroidal_voronoi(g, o);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(r.iterations, 3);
  EXPECT_FALSE(r.converged);
}

TEST(Cvd, DrawnSitesAreDistinctAndOnPositiveDensity) {
  const io::Grid g = gg_cvd::random_density({30, 40}, 0.7, 4);
  std::int64_t positive = 0;
  for (std::int64_t i = 0; i < g.count(); ++i) positive += g.value(i) > 0;
  for (int s : {1, 3}) {  // with supersampling, pixels are drawn, then one of their points
    CvdOptions o;
    o.backend = Backend::Cpu;
    o.supersample = s;
    o.num_sites = positive * s * s;  // every positive grid point: the draw must find them all
    o.max_iterations = 1;
    const auto r = centroidal_voronoi(g, o);
    EXPECT_EQ(r.num_sites, o.num_sites);
    for (double m : r.mass) EXPECT_GT(m, 0);          // a repeated point would have no cell
    for (std::int64_t i = 0; i < r.num_sites; ++i) {  // on positive density
      const std::int64_t x = std::lround(r.sites[2 * i]), y = std::lround(r.sites[2 * i + 1]);
      EXPECT_GT(g.value(y * 40 + x), 0);
    }
    o.num_sites = positive * s * s + 1;
    EXPECT_THROW(centroidal_voronoi(g, o), Error);
  }
}

TEST(Cvd, BadInputIsATypedError) {
  auto code = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::Cuda;  // "no error" stands out in the expectations below
  };
  io::Grid g = gg_cvd::random_density({10, 10}, 0.0, 1);
  CvdOptions o;
  o.backend = Backend::Cpu;
  o.num_sites = 5;
  io::Grid f;
  f.shape = {4, 4};
  f.type = io::ScalarType::F64;
  f.data.assign(16 * 8, 0);
  EXPECT_EQ(code([&] { centroidal_voronoi(f, o); }), ErrorCode::InvalidInput);  // all zero
  double nan = std::nan("");
  std::memcpy(&f.data[8], &nan, 8);
  EXPECT_EQ(code([&] { centroidal_voronoi(f, o); }), ErrorCode::InvalidInput);
  double neg = -1;
  std::memcpy(&f.data[8], &neg, 8);
  EXPECT_EQ(code([&] { centroidal_voronoi(f, o); }), ErrorCode::InvalidInput);
  io::Grid line;
  line.shape = {10};
  line.type = io::ScalarType::U8;
  line.data.assign(10, 1);
  EXPECT_EQ(code([&] { centroidal_voronoi(line, o); }), ErrorCode::InvalidInput);
  CvdOptions bad = o;
  bad.supersample = 0;
  EXPECT_EQ(code([&] { centroidal_voronoi(g, bad); }), ErrorCode::InvalidArgument);
  bad = o;
  bad.max_iterations = 0;
  EXPECT_EQ(code([&] { centroidal_voronoi(g, bad); }), ErrorCode::InvalidArgument);
  bad = o;
  bad.move_tolerance = -1;
  EXPECT_EQ(code([&] { centroidal_voronoi(g, bad); }), ErrorCode::InvalidArgument);
  bad = o;
  bad.initial_sites = {1, 2, 3};
  EXPECT_EQ(code([&] { centroidal_voronoi(g, bad); }), ErrorCode::InvalidInput);
  bad.initial_sites = {1, 2, 10, 3};  // x = 10 is outside a 10-column density
  EXPECT_EQ(code([&] { centroidal_voronoi(g, bad); }), ErrorCode::InvalidInput);
  bad.initial_sites = {1, std::nan("")};
  EXPECT_EQ(code([&] { centroidal_voronoi(g, bad); }), ErrorCode::InvalidInput);
  bad = o;
  bad.num_sites = 101;
  EXPECT_EQ(code([&] { centroidal_voronoi(g, bad); }), ErrorCode::InvalidInput);
}

// A density of any element type, read where it is, gives the same diagram as the same values in
// another type; the device entry on the CPU executor (its "device" memory is host memory) gives
// the host entry's result; a bad density is refused the same way through both.
TEST(Cvd, TypedDensitiesAndDeviceEntry) {
  const io::Grid g16 = gg_cvd::random_density({60, 45}, 0.3, 9);  // uint16, values kept exactly
  const std::int64_t n = g16.count();
  std::vector<float> f(static_cast<std::size_t>(n));
  std::vector<double> d(static_cast<std::size_t>(n));
  for (std::int64_t i = 0; i < n; ++i) f[i] = float(g16.value(i)), d[i] = g16.value(i);
  CvdOptions o;
  o.backend = Backend::Cpu;
  o.num_sites = 70;
  o.max_iterations = 15;
  o.seed = 5;
  const auto ref = centroidal_voronoi(g16, o);
  ASSERT_EQ(ref.num_sites, 70);
  for (auto [data, type] : {std::pair<const void*, io::ScalarType>{f.data(), io::ScalarType::F32},
                            {d.data(), io::ScalarType::F64}}) {
    GridView v;
    v.data = data;
    v.type = type;
    v.shape = g16.shape;
    const auto r = centroidal_voronoi(v, o);
    EXPECT_EQ(r.sites, ref.sites);
    EXPECT_EQ(r.mass, ref.mass);
    EXPECT_EQ(r.energy, ref.energy);
    const auto dv = centroidal_voronoi_device(v, o);
    EXPECT_EQ(dv.backend, Backend::Cpu);
    ASSERT_EQ(dv.num_sites, ref.num_sites);
    EXPECT_EQ(dv.dim, 2);
    EXPECT_EQ(std::vector<double>(dv.sites.get(), dv.sites.get() + 2 * dv.num_sites),
              std::vector<double>(ref.sites.begin(), ref.sites.end()));
    EXPECT_EQ(std::vector<double>(dv.mass.get(), dv.mass.get() + dv.num_sites),
              std::vector<double>(ref.mass.begin(), ref.mass.end()));
    EXPECT_EQ(dv.energy, ref.energy);
    EXPECT_EQ(dv.iterations, ref.iterations);
    EXPECT_EQ(dv.converged, ref.converged);
  }
  // NaN and negative values: refused, counted, on both entries.
  f[7] = std::numeric_limits<float>::quiet_NaN();
  f[9] = -1;
  GridView v;
  v.data = f.data();
  v.type = io::ScalarType::F32;
  v.shape = g16.shape;
  for (bool device : {false, true}) {
    try {
      device ? (void)centroidal_voronoi_device(v, o) : (void)centroidal_voronoi(v, o);
      ADD_FAILURE() << "a density with NaN was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::InvalidInput);
      EXPECT_NE(std::string(e.what()).find("2 values"), std::string::npos) << e.what();
    }
  }
  v.data = nullptr;
  EXPECT_THROW(centroidal_voronoi(v, o), Error);
}

// The caller's arrays take the sites and masses on both entries; short ones are refused before
// anything is written.
TEST(Cvd, CallerArrays) {
  const io::Grid g = gg_cvd::random_density({40, 50}, 0.2, 3);
  CvdOptions o;
  o.backend = Backend::Cpu;
  o.num_sites = 25;
  o.max_iterations = 8;
  const auto ref = centroidal_voronoi(g, o);
  for (bool device : {false, true}) {
    std::vector<double> s(50, -7), m(25, -7);
    o.into = {{s.data(), 50}, {m.data(), 25}};
    if (device) {
      const auto r = centroidal_voronoi_device(view_of(g), o);
      EXPECT_FALSE(r.sites || r.mass);
      EXPECT_EQ(r.num_sites, 25);
    } else {
      const auto r = centroidal_voronoi(g, o);
      EXPECT_TRUE(r.sites.empty() && r.mass.empty());
      EXPECT_EQ(r.num_sites, 25);
    }
    EXPECT_EQ(s, std::vector<double>(ref.sites.begin(), ref.sites.end()));
    EXPECT_EQ(m, std::vector<double>(ref.mass.begin(), ref.mass.end()));
    std::vector<double> s2(49, -7);
    o.into = {{s2.data(), 49}, {}};
    try {
      device ? (void)centroidal_voronoi_device(view_of(g), o) : (void)centroidal_voronoi(g, o);
      ADD_FAILURE() << "a short array was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
      EXPECT_NE(std::string(e.what()).find("into.sites holds 49"), std::string::npos) << e.what();
    }
    EXPECT_EQ(s2, std::vector<double>(49, -7));
    o.into = {};
  }
}
