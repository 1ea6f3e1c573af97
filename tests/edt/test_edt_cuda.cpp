// The CUDA executor returns exactly what the CPU executor returns (every output, bit for bit),
// on grids large enough to use many bands, in 2D and 3D, whole and slice by slice.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <cstdlib>
#include <thread>

#include <cuda_runtime.h>
#include <string>

#include "edt/edt_backend.hpp"
#include "exec/cuda_device.hpp"
#include "../common/device_arrays.hpp"
#include "edt_cases.hpp"
#include "gpugeom/multi_gpu.hpp"

using namespace gpugeom;

namespace {
// Every output the bit-for-bit comparisons look at: squared distances, float32 distances,
// features and labels.
EdtOptions every_output(const std::vector<double>& sampling, Backend b) {
  EdtOptions o;
  o.squared = true;
  o.distance = 32;
  o.features = true;
  o.labels = true;
  o.sampling = sampling;
  o.backend = b;
  return o;
}
}  // namespace

TEST(CudaEdt, SameAsCpuBitForBit) {
  struct Case {
    std::vector<std::int64_t> shape;
    double density;
    std::vector<double> sampling;
  };
  const std::vector<Case> cases{{{1000, 1000}, 0.001, {}},
                                {{1023, 777}, 0.1, {}},
                                {{513, 2049}, 0.5, {}},
                                {{600, 500}, 0.01, {0.5, 1.25}},
                                {{64, 70, 90}, 0.01, {}},
                                {{100, 60, 40}, 0.2, {}},
                                {{33, 65, 17}, 0.05, {2.0, 1.0, 0.5}},
                                // rows of every register-tile width: 10, 17, 22, 20 and 24 steps
                                {{33, 300}, 0.02, {}},
                                {{40, 530}, 0.01, {}},
                                {{30, 700}, 0.1, {}},
                                {{25, 20, 600}, 0.003, {}},
                                {{9, 11, 768}, 0.001, {1.0, 2.0, 1.0}}};
  unsigned seed = 1;
  for (auto& c : cases) {
    io::Grid g = gg_edt::random_grid(c.shape, c.density, seed++);
    EdtOptions o = every_output(c.sampling, Backend::Cpu);
    const auto cpu = distance_transform(g, SiteRule::NonZero, o);
    o.backend = Backend::Cuda;
    const auto gpu = distance_transform(g, SiteRule::NonZero, o);
    EXPECT_EQ(gpu.labels, cpu.labels);
    EXPECT_EQ(gpu.features, cpu.features);
    EXPECT_EQ(gpu.sqdist_int, cpu.sqdist_int);
    EXPECT_EQ(gpu.sqdist_real, cpu.sqdist_real);
    EXPECT_EQ(gpu.distance32, cpu.distance32);
    if (c.shape.size() == 3) {
      o.slices = {0, c.shape[0] / 2, c.shape[0] - 1};
      const auto sl = distance_transform(g, SiteRule::NonZero, o);
      const std::int64_t plane = c.shape[1] * c.shape[2];
      for (std::size_t k = 0; k < o.slices.size(); ++k)
        for (std::int64_t i = 0; i < plane; ++i)
          ASSERT_EQ(sl.labels[k * plane + i], cpu.labels[o.slices[k] * plane + i]);
    }
  }
}

// A slab of a grid with its columns' bounds (EdtOptions::slab) on the GPU: the CPU's whole-grid
// outputs for its indices, on grids large enough for many bands, isotropic or not, with the
// column packing (volumes past 2^32 voxels take it) as well.
TEST(CudaEdt, SlabsSameAsCpuWholeGrid) {
  unsigned seed = 90;
  for (auto shape : {std::vector<std::int64_t>{96, 130, 150}, std::vector<std::int64_t>{40, 9, 300},
                     std::vector<std::int64_t>{20, 6, 7, 80}})
    for (double d : {0.0005, 0.05})
      for (bool aniso : {false, true})
        for (bool columns : {false, true}) {
          const io::Grid g = gg_edt::random_grid(shape, d, seed++);
          std::vector<double> samp;
          if (aniso)
            for (std::size_t a = 0; a < shape.size(); ++a) samp.push_back(1.0 + 0.5 * a);
          EdtOptions o = every_output(samp, Backend::Cpu);
          o.labels = false;
          const auto whole = distance_transform(g, SiteRule::Zero, o);
          if (columns) o.tuning = gg_edt::column_packing();
          const std::int64_t n0 = shape[0];
          for (std::int64_t first : {std::int64_t(0), n0 / 3, n0 - n0 / 4}) {
            const std::int64_t count = first == 0 ? n0 / 3 : std::min(n0 / 3, n0 - first);
            const auto sl = gg_edt::slab_of(g, first, count, SiteRule::Zero);
            EdtOptions so = o;
            so.backend = Backend::Cuda;
            so.slab = sl.bounds;
            std::vector<std::int64_t> zs;
            for (std::int64_t z = first; z < first + count; ++z) zs.push_back(z);
            const auto want = gg_edt::slices_of(whole, zs);
            const auto got = distance_transform(sl.grid, SiteRule::Zero, so);
            EXPECT_EQ(got.features, want.features) << shape.size() << "D slab " << first;
            EXPECT_EQ(got.sqdist_int, want.sqdist_int) << shape.size() << "D slab " << first;
            EXPECT_EQ(got.sqdist_real, want.sqdist_real) << shape.size() << "D slab " << first;
            EXPECT_EQ(got.distance32, want.distance32) << shape.size() << "D slab " << first;
            // The slab on the device (its sites listed there, with its bounds).
            gg_test::DeviceCopy dg(sl.grid.data);
            GridView v;
            v.data = dg.data();
            v.type = sl.grid.type;
            v.shape = sl.grid.shape;
            const auto dev = distance_transform_device(v, SiteRule::Zero, so);
            const std::int64_t m = got.count();
            EXPECT_EQ(gg_test::from_device(dev.features, m * std::int64_t(shape.size())),
                      std::vector<std::int32_t>(want.features.begin(), want.features.end()))
                << shape.size() << "D device slab " << first;
            EXPECT_EQ(gg_test::from_device(dev.distance32, m),
                      std::vector<float>(want.distance32.begin(), want.distance32.end()))
                << shape.size() << "D device slab " << first;
          }
        }
}

// Every column's first and last site of a grid on the device: the host sweep's, for every
// element type read; NaN refused.
TEST(CudaEdt, ColumnSiteBoundsOnTheDevice) {
  unsigned seed = 60;
  for (auto shape : {std::vector<std::int64_t>{70, 33, 41}, std::vector<std::int64_t>{9, 5000},
                     std::vector<std::int64_t>{5, 4, 6, 7}})
    for (SiteRule rule : {SiteRule::NonZero, SiteRule::Zero}) {
      const io::Grid g = gg_edt::random_grid(shape, 0.02, seed++);
      std::vector<float> f(g.data.begin(), g.data.end());
      for (bool as_float : {false, true}) {
        GridView h;
        h.data = as_float ? static_cast<const void*>(f.data()) : g.data.data();
        h.type = as_float ? io::ScalarType::F32 : g.type;
        h.shape = shape;
        const auto want = column_site_bounds(h, rule, 11);
        gg_test::DeviceCopy dg(g.data), df(f);
        GridView d = h;
        d.data = as_float ? df.data() : dg.data();
        RunOptions run;
        run.backend = Backend::Cuda;
        const auto got = column_site_bounds_device(d, rule, 11, run);
        EXPECT_EQ(got.first, want.first);
        EXPECT_EQ(got.last, want.last);
        EXPECT_EQ(got.columns_with_sites, want.columns_with_sites);
      }
    }
  std::vector<double> nan{1, 0, std::nan(""), 2};
  gg_test::DeviceCopy dn(nan);
  GridView d;
  d.data = dn.data();
  d.type = io::ScalarType::F64;
  d.shape = {2, 2};
  RunOptions run;
  run.backend = Backend::Cuda;
  EXPECT_THROW(column_site_bounds_device(d, SiteRule::Zero, 0, run), Error);
}

// Several devices of the host (every one, and device 0 named twice: two slabs at once on one
// device from two host threads) give the CPU's whole-grid outputs.
TEST(CudaEdt, SeveralDevicesSameAsCpu) {
  const io::Grid g = gg_edt::random_grid({150, 120, 140}, 0.002, 97);
  EdtOptions o = every_output({}, Backend::Cpu);
  o.labels = false;
  const auto want = distance_transform(g, SiteRule::Zero, o);
  o.backend = Backend::Cuda;
  for (const auto& devices : {std::vector<int>{}, std::vector<int>{0, 0}, std::vector<int>{0}}) {
    const auto got = distance_transform_devices(view_of(g), SiteRule::Zero, devices, o);
    EXPECT_EQ(got.stats.backend, Backend::Cuda);
    EXPECT_EQ(got.features, want.features) << devices.size() << " devices";
    EXPECT_EQ(got.sqdist_int, want.sqdist_int) << devices.size() << " devices";
    EXPECT_EQ(got.distance32, want.distance32) << devices.size() << " devices";
  }
}

// The y and z passes on shared-memory tiles (forced here: by default they take grids with blocks
// enough for every SM), on shapes whose x extent is not a multiple of the 32-line tile.
TEST(CudaEdt, TiledPassesSameAsCpu) {
  struct Case {
    std::vector<std::int64_t> shape;
    double density;
    std::vector<double> sampling;
    std::int64_t bands;
  };
  const std::vector<Case> cases{{{70, 40, 50}, 0.001, {}, 0},
                                {{100, 60, 40}, 0.2, {}, 0},
                                {{33, 65, 17}, 0.05, {2.0, 1.0, 0.5}, 0},
                                {{50, 200, 45}, 0.1, {}, 8},
                                {{40, 130, 7}, 0.6, {}, 32},
                                {{777, 300}, 0.01, {}, 0},
                                {{5, 7, 300}, 0.05, {}, 4}};
  unsigned seed = 200;
  for (auto& c : cases) {
    io::Grid g = gg_edt::random_grid(c.shape, c.density, seed++);
    EdtOptions o;
    o.squared = true;
    o.labels = true;
    o.sampling = c.sampling;
    for (int k = 0; k < 3; ++k) o.bands[k] = c.bands;
    o.tiles = 1;
    o.backend = Backend::Cpu;
    const auto cpu = distance_transform(g, SiteRule::NonZero, o);
    o.backend = Backend::Cuda;
    const auto gpu = distance_transform(g, SiteRule::NonZero, o);
    EXPECT_EQ(gpu.labels, cpu.labels);
    EXPECT_EQ(gpu.sqdist_int, cpu.sqdist_int);
    EXPECT_EQ(gpu.sqdist_real, cpu.sqdist_real);
  }
}

namespace {
// Squared distances and labels of g on the CUDA executor equal the CPU executor's.
void expect_same_as_cpu(const io::Grid& g, const std::string& what, std::int64_t reach = -1,
                        int tiles = -1) {
  EdtOptions o;
  o.window_reach = reach;
  o.tiles = tiles;
  o.squared = true;
  o.labels = true;
  o.backend = Backend::Cpu;
  const auto cpu = distance_transform(g, SiteRule::NonZero, o);
  o.backend = Backend::Cuda;
  const auto gpu = distance_transform(g, SiteRule::NonZero, o);
  EXPECT_EQ(gpu.labels, cpu.labels) << what;
  EXPECT_EQ(gpu.sqdist_int, cpu.sqdist_int) << what;
}
}  // namespace

// The windowed passes with short reaches (most lines handed to the banded pass, on tiles or
// not) and long ones, sparse and dense, against the CPU executor.
TEST(CudaEdt, WindowReachesSameAsCpu) {
  unsigned seed = 400;
  for (auto shape : {std::vector<std::int64_t>{700, 900}, std::vector<std::int64_t>{64, 70, 90},
                     std::vector<std::int64_t>{20, 300, 40}})
    for (double d : {0.001, 0.1})
      for (int reach : {1, 4, 16, 32})
        for (int tiles : {0, 1}) {
          const io::Grid g = gg_edt::random_grid(shape, d, seed++);
          expect_same_as_cpu(g,
                             "reach " + std::to_string(reach) + " tiles " + std::to_string(tiles),
                             reach, tiles);
        }
}

// Rows longer than 2^16: the windowed pass's costs no longer fit 32 bits (a site 70 000
// columns away). Short columns take wide keys, long ones clamped narrow keys (lines with a
// far best go to the banded pass). One lone site (costs past 2^32) and dense sites, with
// windows forced on.
TEST(CudaEdt, WideRowsSameAsCpu) {
  unsigned seed = 900;
  for (std::int64_t rows : {5, 80})
    for (double d : {0.0, 0.2})
      for (int reach : {4, 32}) {
        io::Grid g = gg_edt::random_grid({rows, 70001}, d, seed++);
        if (d == 0) {  // the lone site at x = 0: the far end of its row is 70 000 away
          std::fill(g.data.begin(), g.data.end(), 0);
          g.data[0] = 1;
        }
        expect_same_as_cpu(g,
                           std::to_string(rows) + " rows, density " + std::to_string(d) +
                               " reach " + std::to_string(reach),
                           reach);
      }
}

TEST(CudaEdt, BruteForceOnSmallGrids) {
  unsigned seed = 50;
  for (auto shape : {std::vector<std::int64_t>{1, 300}, std::vector<std::int64_t>{45, 38},
                     std::vector<std::int64_t>{12, 13, 14}})
    for (double d : {0.002, 0.1, 0.9}) {
      io::Grid g = gg_edt::random_grid(shape, d, seed++);
      const auto ref = gg_edt::brute_force(g, {});
      EdtOptions o;
      o.backend = Backend::Cuda;
      o.labels = true;
      o.squared = true;
      const auto r = distance_transform(g, SiteRule::NonZero, o);
      std::vector<std::int64_t> rank(g.count(), -1);
      for (std::int64_t i = 0, k = 0; i < g.count(); ++i)
        if (g.data[i]) rank[i] = k++;
      for (std::int64_t i = 0; i < g.count(); ++i) {
        ASSERT_EQ(r.labels[i], rank[ref.nearest[i]]);
        ASSERT_EQ(mpq_class((long)r.sqdist_int[i]), ref.sq[i]);
      }
    }
}

// Sites given as a list reach the x pass as packed features (not a mask): the x pass then runs
// in place and the windowed passes end in the other array. Dense lists (windowed) and sparse
// ones, 2D and 3D, with duplicates, against the CPU executor.
TEST(CudaEdt, SiteListsSameAsCpu) {
  unsigned seed = 700;
  for (auto shape : {std::vector<std::int64_t>{300, 257}, std::vector<std::int64_t>{40, 50, 66}})
    for (double d : {0.002, 0.2}) {
      const io::Grid g = gg_edt::random_grid(shape, d, seed++);
      std::vector<std::int64_t> sites;
      for (std::int64_t i = g.count() - 1; i >= 0; --i)  // reverse raster order
        if (g.data[i]) {
          std::int64_t rest = i;
          std::vector<std::int64_t> c(shape.size());
          for (std::size_t k = shape.size(); k-- > 0;) c[k] = rest % shape[k], rest /= shape[k];
          sites.insert(sites.end(), c.begin(), c.end());
          if (i % 7 == 0) sites.insert(sites.end(), c.begin(), c.end());  // a duplicate
        }
      EdtOptions o;
      o.squared = true;
      o.labels = true;
      o.backend = Backend::Cpu;
      const auto cpu = distance_transform_sites(shape, sites, o);
      o.backend = Backend::Cuda;
      const auto gpu = distance_transform_sites(shape, sites, o);
      EXPECT_EQ(gpu.labels, cpu.labels);
      EXPECT_EQ(gpu.sqdist_int, cpu.sqdist_int);
    }
}

using gg_test::back;

// The device entry point: a float32 grid on the device (SciPy's zero rule) on a stream of the
// caller's, outputs in the library's device arrays and in the caller's; the same values as the
// host entry on the CPU executor, whole and slice by slice.
TEST(CudaEdt, DeviceEntrySameAsHost) {
  for (auto shape : {std::vector<std::int64_t>{300, 257}, std::vector<std::int64_t>{40, 50, 66}}) {
    const io::Grid g = gg_edt::random_grid(shape, 0.03, 77);
    std::vector<float> f(g.data.size());
    for (std::size_t i = 0; i < f.size(); ++i) f[i] = g.data[i] ? 0.f : 1.5f;  // zeros are sites
    EdtOptions o;
    o.squared = true;
    o.distance = 32;
    o.features = true;
    o.labels = true;
    o.backend = Backend::Cpu;
    const auto ref = distance_transform(g, SiteRule::NonZero, o);
    const std::int64_t n = ref.count(), nd = std::int64_t(shape.size());
    const gg_test::Stream s;  // (outlives the results below)
    float* dg = nullptr;
    GG_CK(cudaMalloc(&dg, f.size() * sizeof(float)));
    GG_CK(cudaMemcpyAsync(dg, f.data(), f.size() * sizeof(float), cudaMemcpyHostToDevice, s));
    GridView v;
    v.data = dg;
    v.type = io::ScalarType::F32;
    v.shape = shape;
    o.backend = Backend::Cuda;
    o.stream = s;
    const auto r = distance_transform_device(v, SiteRule::Zero, o);
    EXPECT_EQ(r.backend, Backend::Cuda);
    EXPECT_EQ(back(r.sqdist_int.get(), n), ref.sqdist_int);
    EXPECT_EQ(back(r.distance32.get(), n), ref.distance32);
    EXPECT_EQ(back(r.features.get(), nd * n), ref.features);
    EXPECT_EQ(back(r.labels.get(), n), ref.labels);
    // Into the caller's device arrays.
    std::int32_t* dl = nullptr;
    GG_CK(cudaMalloc(&dl, sizeof(std::int32_t) * n));
    EdtOptions w = o;
    w.into.labels = {dl, n};
    const auto r2 = distance_transform_device(v, SiteRule::Zero, w);
    EXPECT_FALSE(r2.labels);
    EXPECT_EQ(back(dl, n), ref.labels);
    if (nd == 3) {
      o.slices = {1, 39};
      const auto sl = distance_transform_device(v, SiteRule::Zero, o);
      o.backend = Backend::Cpu;
      o.stream = nullptr;
      const auto sref = distance_transform(g, SiteRule::NonZero, o);
      EXPECT_EQ(back(sl.labels.get(), sl.count()), sref.labels);
      EXPECT_EQ(back(sl.distance32.get(), sl.count()), sref.distance32);
    }
    // Host entry with the caller's pinned array: written there by the copy itself.
    float* pinned = nullptr;
    GG_CK(cudaMallocHost(&pinned, sizeof(float) * n));
    EdtOptions h;
    h.distance = 32;
    h.backend = Backend::Cuda;
    h.into.distance32 = {pinned, n};
    const auto r3 = distance_transform(g, SiteRule::NonZero, h);
    EXPECT_TRUE(r3.distance32.empty());
    EXPECT_EQ(std::vector<float>(pinned, pinned + n), ref.distance32);
    GG_CK(cudaFreeHost(pinned));
    GG_CK(cudaFree(dl));
    GG_CK(cudaFree(dg));
  }
}

namespace {
std::atomic<int> g_release{0};
// Holds its stream until the test releases it (or 20 s pass, so a failure cannot hang).
void CUDART_CB hold(void*) {
  for (int i = 0; i < 20000 && !g_release.load(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}
}  // namespace

// The caller's stream is honoured: work held on another stream is not waited for (no device-wide
// synchronisation inside the call).
TEST(CudaEdt, DeviceEntryWaitsForItsStreamOnly) {
  // compute-sanitizer runs device work one item at a time, across streams: no overlap to see.
  if (std::getenv("GG_UNDER_SANITIZER") || std::getenv("CUDA_INJECTION64_PATH"))
    GTEST_SKIP() << "under compute-sanitizer (it serialises streams)";
  const io::Grid g = gg_edt::random_grid({512, 512}, 0.01, 5);
  std::uint8_t* dg = nullptr;
  GG_CK(cudaMalloc(&dg, g.data.size()));
  GG_CK(cudaMemcpy(dg, g.data.data(), g.data.size(), cudaMemcpyHostToDevice));
  const gg_test::Stream mine, other;  // (outlive the results below)
  EdtOptions o;
  o.distance = 32;
  o.backend = Backend::Cuda;
  o.stream = mine;
  GridView v;
  v.data = dg;
  v.shape = g.shape;
  (void)distance_transform_device(v, SiteRule::NonZero, o);  // warm: pools, staging
  g_release = 0;
  GG_CK(cudaLaunchHostFunc(other, hold, nullptr));
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = distance_transform_device(v, SiteRule::NonZero, o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const bool other_pending = cudaStreamQuery(other) == cudaErrorNotReady;
  g_release = 1;
  GG_CK(cudaStreamSynchronize(other));
  EXPECT_TRUE(other_pending) << "the call waited for another stream's work";
  EXPECT_LT(s, 10.0);
  ASSERT_TRUE(r.distance32);
  GG_CK(cudaFree(dg));
}

// Raster-index packing (grids past 32 bits of bit fields, 1600^3) forced on small grids: the
// CUDA executor's linear passes (x pass over ballots, windowed, tiled and banded passes, slices,
// site lists, a device grid by slices) give the CPU executor's bit-field results exactly.
TEST(CudaEdt, RasterIndexPackingSameAsCpu) {
  struct Case {
    std::vector<std::int64_t> shape;
    double density;
    std::vector<double> sampling;
    int reach, tiles;
  };
  const std::vector<Case> cases{
      {{1000, 1000}, 0.001, {}, -1, -1},       {{1023, 777}, 0.1, {}, -1, -1},
      {{600, 500}, 0.01, {0.5, 1.25}, -1, -1}, {{40, 530}, 0.01, {}, 4, 0},
      {{80, 70001}, 0.2, {}, 32, -1},          {{64, 70, 90}, 0.01, {}, -1, 1},
      {{100, 60, 40}, 0.2, {}, -1, -1},        {{33, 65, 17}, 0.05, {2.0, 1.0, 0.5}, -1, 1},
      {{20, 300, 40}, 0.001, {}, 1, 0},        {{25, 20, 600}, 0.003, {}, 16, 1}};
  unsigned seed = 1200;
  for (const auto& c : cases) {
    const io::Grid g = gg_edt::random_grid(c.shape, c.density, seed++);
    const std::string what = std::to_string(c.shape[0]) + "x" + std::to_string(c.shape[1]) +
                             (c.shape.size() == 3 ? "x" + std::to_string(c.shape[2]) : "");
    EdtOptions o = every_output(c.sampling, Backend::Cpu);
    o.window_reach = c.reach;
    o.tiles = c.tiles;
    const auto cpu = distance_transform(g, SiteRule::NonZero, o);
    EdtOptions so = o;
    if (c.shape.size() == 3) so.slices = {0, c.shape[0] / 2, c.shape[0] - 1};
    const auto cpu_sl = c.shape.size() == 3 ? distance_transform(g, SiteRule::NonZero, so) : cpu;
    std::vector<std::int64_t> list;  // every third site, as coordinates
    for (std::int64_t i = 0, k = 0; i < g.count(); ++i)
      if (g.data[i] && k++ % 3 == 0) {
        std::int64_t rest = i;
        std::vector<std::int64_t> p(c.shape.size());
        for (std::size_t j = c.shape.size(); j-- > 0;) p[j] = rest % c.shape[j], rest /= c.shape[j];
        list.insert(list.end(), p.begin(), p.end());
      }
    const auto cpu_list = distance_transform_sites(c.shape, list, o);
    o.tuning = so.tuning = gg_edt::linear_packing();
    o.backend = so.backend = Backend::Cuda;
    const auto gpu = distance_transform(g, SiteRule::NonZero, o);
    EXPECT_EQ(gpu.labels, cpu.labels) << what;
    EXPECT_EQ(gpu.features, cpu.features) << what;
    EXPECT_EQ(gpu.sqdist_int, cpu.sqdist_int) << what;
    EXPECT_EQ(gpu.sqdist_real, cpu.sqdist_real) << what;
    EXPECT_EQ(gpu.distance32, cpu.distance32) << what;
    const auto gpu_list = distance_transform_sites(c.shape, list, o);
    EXPECT_EQ(gpu_list.labels, cpu_list.labels) << what << " list";
    EXPECT_EQ(gpu_list.sqdist_int, cpu_list.sqdist_int) << what << " list";
    if (c.shape.size() != 3) continue;
    const auto gpu_sl = distance_transform(g, SiteRule::NonZero, so);
    EXPECT_EQ(gpu_sl.labels, cpu_sl.labels) << what << " slices";
    EXPECT_EQ(gpu_sl.features, cpu_sl.features) << what << " slices";
    // The grid on the device, by slices: its sites are listed there.
    void* dg = nullptr;
    ASSERT_EQ(cudaMalloc(&dg, g.data.size()), cudaSuccess);
    ASSERT_EQ(cudaMemcpy(dg, g.data.data(), g.data.size(), cudaMemcpyHostToDevice), cudaSuccess);
    GridView v;
    v.data = dg;
    v.shape = c.shape;
    const auto dev = distance_transform_device(v, SiteRule::NonZero, so);
    std::vector<std::int32_t> dl(std::size_t(dev.count()));
    ASSERT_EQ(cudaMemcpy(dl.data(), dev.labels.get(), dl.size() * 4, cudaMemcpyDeviceToHost),
              cudaSuccess);
    EXPECT_EQ(dl, cpu_sl.labels) << what << " device grid, slices";
    cudaFree(dg);
  }
}

// Blocks of slices on the CUDA executor, with the volume's packing, raster indices or columns,
// tiled y passes or not, every block size: the CPU executor's whole volume, slice for slice;
// also from a device grid (its sites listed there).
TEST(CudaEdt, SliceBlocksSameAsCpu) {
  struct Case {
    std::vector<std::int64_t> shape;
    double density;
    std::vector<double> sampling;
  };
  const std::vector<Case> cases{{{64, 70, 90}, 0.01, {}},
                                {{100, 60, 40}, 0.2, {}},
                                {{33, 65, 17}, 0.05, {2.0, 1.0, 0.5}},
                                {{20, 300, 40}, 0.001, {}},
                                {{50, 33, 700}, 0.003, {}}};
  unsigned seed = 2400;
  for (const auto& c : cases) {
    const io::Grid g = gg_edt::random_grid(c.shape, c.density, seed++);
    const std::int64_t nz = c.shape[0], plane = c.shape[1] * c.shape[2];
    EdtOptions o = every_output(c.sampling, Backend::Cpu);
    const auto whole = distance_transform(g, SiteRule::NonZero, o);
    EdtOptions so = o;
    so.backend = Backend::Cuda;
    so.slices = {nz - 1, 0, nz / 2, nz / 2};
    for (std::int64_t z = 1; z < nz; z += 2) so.slices.push_back(z);
    const auto want = gg_edt::slices_of(whole, so.slices);
    for (int packing = 0; packing < 3; ++packing) {
      so.tuning = packing == 1   ? gg_edt::linear_packing()
                  : packing == 2 ? gg_edt::column_packing()
                                 : nullptr;
      for (int tiles : {-1, 1})
        for (std::int64_t block : {std::int64_t(0), plane, 5 * plane}) {
          so.tiles = tiles;
          so.slice_block = block;
          const std::string what = std::to_string(c.shape[0]) + "x" + std::to_string(c.shape[1]) +
                                   "x" + std::to_string(c.shape[2]) + " packing " +
                                   std::to_string(packing) + " tiles " + std::to_string(tiles) +
                                   " block " + std::to_string(block);
          const auto r = distance_transform(g, SiteRule::NonZero, so);
          EXPECT_EQ(r.labels, want.labels) << what;
          EXPECT_EQ(r.features, want.features) << what;
          EXPECT_EQ(r.sqdist_int, want.sqdist_int) << what;
          EXPECT_EQ(r.sqdist_real, want.sqdist_real) << what;
          EXPECT_EQ(r.distance32, want.distance32) << what;
        }
      so.tiles = -1;
      so.slice_block = 0;
      const gg_test::DeviceCopy dg(g.data);
      GridView v;
      v.data = dg.data();
      v.shape = c.shape;
      const auto dev = distance_transform_device(v, SiteRule::NonZero, so);
      EXPECT_EQ(gg_test::from_device(dev.labels, dev.count()), want.labels)
          << "device grid, packing " << packing;
    }
  }
}

// A device result dropped by the caller gives its memory back to the library's pool, ordered on
// the call's stream (here the per-thread default stream), so the next call's memory check and
// allocations can use it (a 1600^3 transform needs most of
// an 80 GB device, and one dropped result must not make the next one refused).
TEST(CudaEdt, DroppedDeviceResultsAreFreed) {
  const std::vector<std::int64_t> shape{64, 128, 256};
  const io::Grid g = gg_edt::random_grid(shape, 0.01, 77);
  void* dg = nullptr;
  ASSERT_EQ(cudaMalloc(&dg, g.data.size()), cudaSuccess);
  ASSERT_EQ(cudaMemcpy(dg, g.data.data(), g.data.size(), cudaMemcpyHostToDevice), cudaSuccess);
  GridView v;
  v.data = dg;
  v.shape = shape;
  EdtOptions o;
  o.distance = 32;
  o.labels = true;
  auto used = [] {
    unsigned long long u = 0;
    EXPECT_EQ(cudaMemPoolGetAttribute(cuda_device::pool(0), cudaMemPoolAttrUsedMemCurrent, &u),
              cudaSuccess);
    return u;
  };
  const auto before = used();
  {
    const auto r = distance_transform_device(v, SiteRule::NonZero, o);
    EXPECT_GE(used() - before, 2ull * 4 * std::uint64_t(g.count()));
  }
  ASSERT_EQ(cudaStreamSynchronize(cudaStreamPerThread), cudaSuccess);  // the free has run
  EXPECT_EQ(used(), before);
  cudaFree(dg);
}

// Slice by slice, a volume of more than 2^32 voxels (4.4e9) known by its listed sites, on the
// device: every output the brute force's (ties across columns included), with and without
// sampling, with the tiled pass forced and not; then the same volume as a 4.4 GB grid on the
// device (its sites listed there): the same distances and sites, labels as raster ranks.
TEST(CudaEdt, SlicesOfVolumesPastTwoToThe32Voxels) {
  const gg_edt::TallVolume t = gg_edt::tall_volume(7);
  const std::int64_t plane = t.shape[1] * t.shape[2];
  const std::int64_t n = std::int64_t(t.slices.size()) * plane;
  for (bool aniso : {false, true})
    for (int tiles : {-1, 1}) {
      EdtOptions o =
          every_output(aniso ? std::vector<double>{3, 1, 2} : std::vector<double>{}, Backend::Cuda);
      o.slices = t.slices;
      o.tiles = tiles;
      std::int64_t w[3] = {1, 1, 1};
      if (aniso) w[0] = 9, w[2] = 4;
      const auto r = distance_transform_sites(t.shape, t.sites, o);
      const auto ref = gg_edt::slice_reference(t, w);
      ASSERT_EQ(r.count(), n);
      for (std::int64_t i = 0; i < n; ++i) {
        const std::string at = std::string(aniso ? "sampled" : "isotropic") + ", tiles " +
                               std::to_string(tiles) + ", slice " +
                               std::to_string(t.slices[i / plane]) + " voxel " +
                               std::to_string(i % plane);
        ASSERT_EQ(aniso ? r.sqdist_real[i] : double(r.sqdist_int[i]), double(ref.sq[i])) << at;
        for (int a = 0; a < 3; ++a)
          ASSERT_EQ(r.features[a * n + i], ref.coords[3 * i + a]) << at << " axis " << a;
        ASSERT_EQ(r.labels[i], ref.label[i]) << at;
      }
    }
  if (std::getenv("GG_UNDER_SANITIZER")) return;  // (4.4 GB scanned under the sanitizer: slow)
  const std::int64_t nvox = t.shape[0] * plane;
  std::vector<std::int64_t> raster;  // the sites' voxels, increasing: a grid's labels are ranks
  for (std::size_t j = 0; j < t.sites.size(); j += 3)
    raster.push_back((t.sites[j] * t.shape[1] + t.sites[j + 1]) * t.shape[2] + t.sites[j + 2]);
  std::sort(raster.begin(), raster.end());
  raster.erase(std::unique(raster.begin(), raster.end()), raster.end());
  void* dg = nullptr;
  ASSERT_EQ(cudaMalloc(&dg, std::size_t(nvox)), cudaSuccess);
  ASSERT_EQ(cudaMemset(dg, 0, std::size_t(nvox)), cudaSuccess);
  const unsigned char one = 1;
  for (std::int64_t v : raster)
    ASSERT_EQ(cudaMemcpy(static_cast<unsigned char*>(dg) + v, &one, 1, cudaMemcpyHostToDevice),
              cudaSuccess);
  GridView g;
  g.data = dg;
  g.shape = t.shape;
  EdtOptions o = every_output({}, Backend::Cuda);
  o.slices = t.slices;
  const auto d = distance_transform_device(g, SiteRule::NonZero, o);
  ASSERT_EQ(cudaFree(dg), cudaSuccess);
  std::vector<std::int64_t> sq(static_cast<std::size_t>(n));
  std::vector<std::int32_t> feat(static_cast<std::size_t>(3 * n)), lab(static_cast<std::size_t>(n));
  ASSERT_EQ(cudaMemcpy(sq.data(), d.sqdist_int.get(), sq.size() * 8, cudaMemcpyDeviceToHost),
            cudaSuccess);
  ASSERT_EQ(cudaMemcpy(feat.data(), d.features.get(), feat.size() * 4, cudaMemcpyDeviceToHost),
            cudaSuccess);
  ASSERT_EQ(cudaMemcpy(lab.data(), d.labels.get(), lab.size() * 4, cudaMemcpyDeviceToHost),
            cudaSuccess);
  const std::int64_t w[3] = {1, 1, 1};
  const auto ref = gg_edt::slice_reference(t, w);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::string at = "device grid, voxel " + std::to_string(i);
    ASSERT_EQ(sq[i], ref.sq[i]) << at;
    for (int a = 0; a < 3; ++a) ASSERT_EQ(feat[a * n + i], ref.coords[3 * i + a]) << at;
    const std::int64_t v = (ref.coords[3 * i] * t.shape[1] + ref.coords[3 * i + 1]) * t.shape[2] +
                           ref.coords[3 * i + 2];
    ASSERT_EQ(lab[i], std::lower_bound(raster.begin(), raster.end(), v) - raster.begin()) << at;
  }
}
