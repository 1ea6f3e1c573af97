// The caller's memory resource (issue 48): every device array of a CUDA call, the device results
// it hands back included, comes from RunOptions::memory and goes back to it, on the call's
// stream; results are the same as from the library's pool; a resource that refuses gives a
// typed error and nothing leaks.
#include <cuda_runtime.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <set>
#include <string>
#include <vector>

#include "../common/device_arrays.hpp"
#include "gpugeom/gpugeom.hpp"

using namespace gpugeom;

namespace {

// The library's resource, with every block it hands out and takes back checked and counted.
class Counting final : public DeviceMemoryResource {
 public:
  // Throws at the allocation numbered fail_at (0-based), -1: never; with a library Error when
  // typed, else std::bad_alloc.
  std::int64_t fail_at = -1;
  bool typed = false;

  void* allocate(std::size_t bytes, std::size_t alignment, void* stream) override {
    std::lock_guard<std::mutex> lk(m_);
    if (fail_at >= 0 && allocs_ == fail_at) {
      if (typed) throw Error(ErrorCode::OutOfMemory, "the test's resource is full");
      throw std::bad_alloc();
    }
    void* p = base_->allocate(bytes, alignment, stream);
    if (reinterpret_cast<std::uintptr_t>(p) % alignment) ++misaligned_;
    blocks_[p] = bytes;
    streams_.insert(stream);
    ++allocs_;
    live_ += std::int64_t(bytes);
    high_ = std::max(high_, live_);
    return p;
  }
  void deallocate(void* p, std::size_t bytes, std::size_t alignment,
                  void* stream) noexcept override {
    {
      std::lock_guard<std::mutex> lk(m_);
      auto it = blocks_.find(p);
      if (it == blocks_.end() || it->second != bytes) ++bad_frees_;
      if (it != blocks_.end()) blocks_.erase(it);
      streams_.insert(stream);
      live_ -= std::int64_t(bytes);
    }
    base_->deallocate(p, bytes, alignment, stream);
  }
  std::uint64_t cached_bytes(int device) const noexcept override {
    return base_->cached_bytes(device);
  }

  std::int64_t allocs() const { return allocs_; }
  std::int64_t live() const { return live_; }
  std::int64_t high() const { return high_; }
  std::size_t open_blocks() const { return blocks_.size(); }
  int bad_frees() const { return bad_frees_; }
  int misaligned() const { return misaligned_; }
  std::set<void*> streams() const { return streams_; }

 private:
  std::shared_ptr<DeviceMemoryResource> base_ = library_memory_resource();
  mutable std::mutex m_;
  std::map<void*, std::size_t> blocks_;
  std::set<void*> streams_;
  std::int64_t allocs_ = 0, live_ = 0, high_ = 0;
  int bad_frees_ = 0, misaligned_ = 0;
};

class Memory : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!query_device().available) GTEST_SKIP() << "no usable CUDA device";
    GG_CK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking));
  }
  void TearDown() override {
    if (stream_) cudaStreamDestroy(stream_);
  }
  // Options on the test's stream taking memory from r.
  template <class Opt>
  Opt with(std::shared_ptr<Counting> r) const {
    Opt o;
    o.backend = Backend::Cuda;
    o.stream = stream_;
    o.memory = std::move(r);
    return o;
  }
  // Everything the resource handed out came back, each block once with its size, and every
  // block was taken and given back on the call's stream.
  void all_returned(const Counting& c, const char* what) {
    ASSERT_EQ(cudaStreamSynchronize(stream_), cudaSuccess);
    EXPECT_GT(c.allocs(), 0) << what << ": the call took nothing from the caller's resource";
    EXPECT_EQ(c.live(), 0) << what;
    EXPECT_EQ(c.open_blocks(), 0u) << what;
    EXPECT_EQ(c.bad_frees(), 0) << what << ": a block freed twice, or with another size";
    EXPECT_EQ(c.misaligned(), 0) << what;
    EXPECT_EQ(c.streams(), std::set<void*>{stream_}) << what << ": memory on another stream";
  }
  cudaStream_t stream_ = nullptr;
};

std::vector<double> coords3(const std::vector<Point3>& p) {
  return std::vector<double>(&p.data()->x, &p.data()->x + 3 * p.size());
}

}  // namespace

// A device result's arrays are the caller's resource's blocks, held until the result is dropped;
// the result equals the library pool's; the call's peak is what it held of the resource.
TEST_F(Memory, DeviceDelaunay3dTakesAndReturnsTheCallersMemory) {
  const auto pts = generate3d("uniform", 20000, 7);
  const gg_test::DeviceCopy d(coords3(pts));
  Delaunay3dOptions plain;
  plain.backend = Backend::Cuda;
  const auto want = delaunay3d_device(d.doubles(), std::int64_t(pts.size()), plain);
  auto c = std::make_shared<Counting>();
  {
    const auto got =
        delaunay3d_device(d.doubles(), std::int64_t(pts.size()), with<Delaunay3dOptions>(c));
    ASSERT_EQ(got.num_tetrahedra, want.num_tetrahedra);
    EXPECT_EQ(gg_test::from_device(got.tetrahedra, 4 * got.num_tetrahedra),
              gg_test::from_device(want.tetrahedra, 4 * want.num_tetrahedra));
    EXPECT_EQ(gg_test::from_device(got.neighbors, 4 * got.num_tetrahedra),
              gg_test::from_device(want.neighbors, 4 * want.num_tetrahedra));
    // The result's arrays are still the resource's.
    const std::int64_t held = 4 * (8 * got.num_tetrahedra + 2 * got.num_points);
    EXPECT_GE(c->live(), held);
    const std::int64_t peak = got.stats.device_peak_bytes;
    EXPECT_GE(peak, c->live());
    EXPECT_LE(peak, c->high());
  }
  all_returned(*c, "delaunay3d_device");
}

// Host entries on the CUDA executor: every temporary comes from the resource and is back by the
// time the call returns.
TEST_F(Memory, HostEntriesReturnEverything) {
  {
    const auto pts = generate2d("uniform", 50000, 3);
    Delaunay2dOptions plain;
    plain.backend = Backend::Cuda;
    const auto want = delaunay2d(pts, plain);
    auto c = std::make_shared<Counting>();
    const auto got = delaunay2d(pts, with<Delaunay2dOptions>(c));
    EXPECT_EQ(c->live(), 0) << "delaunay2d returned holding device memory";
    EXPECT_EQ(got.triangles, want.triangles);
    EXPECT_EQ(got.neighbors, want.neighbors);
    all_returned(*c, "delaunay2d");
  }
  {
    const auto pts = generate3d("sphere", 30000, 5);
    Hull3dOptions plain;
    plain.backend = Backend::Cuda;
    const auto want = convex_hull3d(pts, plain);
    auto c = std::make_shared<Counting>();
    const auto got = convex_hull3d(pts, with<Hull3dOptions>(c));
    EXPECT_EQ(c->live(), 0) << "convex_hull3d returned holding device memory";
    EXPECT_EQ(got.triangles, want.triangles);
    all_returned(*c, "convex_hull3d");
  }
}

// The EDT's device outputs, likewise.
TEST_F(Memory, DeviceEdtOutputsAreTheCallersMemory) {
  const std::vector<std::int64_t> shape{32, 48, 64};
  std::vector<std::uint8_t> grid(std::size_t(32 * 48 * 64), 1);
  for (std::size_t i = 0; i < grid.size(); i += 997) grid[i] = 0;
  const gg_test::DeviceCopy d(grid);
  GridView v;
  v.data = d.data();
  v.shape = shape;
  v.type = ScalarType::U8;
  EdtOptions plain;
  plain.distance = 32;
  plain.labels = true;
  const auto want = distance_transform_device(v, SiteRule::Zero, plain);
  auto c = std::make_shared<Counting>();
  {
    EdtOptions o = with<EdtOptions>(c);
    o.distance = 32;
    o.labels = true;
    const auto got = distance_transform_device(v, SiteRule::Zero, o);
    EXPECT_GE(c->live(), std::int64_t(8 * grid.size()));
    EXPECT_EQ(gg_test::from_device(got.labels, got.count()),
              gg_test::from_device(want.labels, want.count()));
    EXPECT_EQ(gg_test::from_device(got.distance32, got.count()),
              gg_test::from_device(want.distance32, want.count()));
  }
  all_returned(*c, "distance_transform_device");
}

// A capability that runs another inside its call (the CDT its Delaunay triangulation, the 3D
// Voronoi diagram its tetrahedralisation) runs it on the call's executor: the same stream and
// resource, and one count of the call's memory, so that the call's peak includes the points it
// uploaded while the inner triangulation ran (an inner executor of its own reported the inner
// run's peak alone, which is the device entry's on the same points).
TEST_F(Memory, NestedCapabilitiesShareTheCall) {
  const std::int64_t n2 = 30000, k = 256;
  std::vector<double> xy;
  for (const Point2& p : generate2d("uniform", n2 - k, 9)) xy.insert(xy.end(), {p.x, p.y});
  std::vector<std::int32_t> segs;
  for (std::int64_t i = 0; i < k; ++i) {  // a convex polygon around the middle: no crossings
    const double a = 6.283185307179586 * double(i) / double(k);
    xy.insert(xy.end(), {0.5 + 0.3 * std::cos(a), 0.5 + 0.3 * std::sin(a)});
    segs.insert(segs.end(), {std::int32_t(n2 - k + i), std::int32_t(n2 - k + (i + 1) % k)});
  }
  const gg_test::DeviceCopy dxy(xy);
  auto c0 = std::make_shared<Counting>();
  std::int64_t dt_peak = 0;
  {
    const auto dt = delaunay2d_device(dxy.doubles(), n2, with<Delaunay2dOptions>(c0));
    dt_peak = dt.stats.device_peak_bytes;
  }
  auto c = std::make_shared<Counting>();
  {
    const auto got = cdt2d(xy.data(), n2, segs.data(), k, with<Cdt2dOptions>(c));
    const std::int64_t peak = got.stats.device_peak_bytes;
    EXPECT_GE(peak, dt_peak + 16 * n2) << "the CDT's peak leaves out its upload of the points";
    EXPECT_LE(peak, c->high());
  }
  all_returned(*c, "cdt2d");

  const std::int64_t n3 = 20000;
  const auto pts = generate3d("uniform", n3, 11);
  const gg_test::DeviceCopy dxyz(coords3(pts));
  std::int64_t tet_peak = 0;
  {
    const auto dt = delaunay3d_device(dxyz.doubles(), n3, with<Delaunay3dOptions>(c0));
    tet_peak = dt.stats.device_peak_bytes;
  }
  auto c3 = std::make_shared<Counting>();
  {
    Triangulation3d tri;
    const auto v = voronoi3d(&pts.data()->x, n3, with<Delaunay3dOptions>(c3), &tri);
    const std::int64_t peak = v.stats.device_peak_bytes;
    EXPECT_GE(peak, tet_peak + 24 * n3) << "the diagram's peak leaves out the tetrahedralisation's";
    EXPECT_LE(peak, c3->high());
    EXPECT_EQ(tri.stats.backend, Backend::Cuda);
    const auto want = delaunay3d(pts, with<Delaunay3dOptions>(c0));
    EXPECT_EQ(tri.tetrahedra, want.tetrahedra);
  }
  all_returned(*c3, "voronoi3d");
}

// A resource that refuses: the call fails with OutOfMemory, naming the resource and the
// resource's own message; every block taken before the refusal is given back. At each of the
// first allocations, so that the refusal lands in different phases.
TEST_F(Memory, RefusalIsTypedAndLeaksNothing) {
  const auto pts = generate3d("uniform", 5000, 11);
  const gg_test::DeviceCopy d(coords3(pts));
  for (std::int64_t at : {0, 1, 7, 40}) {
    for (bool typed : {false, true}) {
      auto c = std::make_shared<Counting>();
      c->fail_at = at;
      c->typed = typed;
      try {
        (void)delaunay3d_device(d.doubles(), std::int64_t(pts.size()), with<Delaunay3dOptions>(c));
        ADD_FAILURE() << "a refused allocation (number " << at << ") was not reported";
      } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::OutOfMemory) << e.what();
        const std::string msg = e.what();
        EXPECT_NE(msg.find(typed ? "the test's resource is full" : "RunOptions::memory"),
                  std::string::npos)
            << msg;
      }
      ASSERT_EQ(cudaStreamSynchronize(stream_), cudaSuccess);
      EXPECT_EQ(c->live(), 0) << "blocks leaked after a refusal at allocation " << at;
      EXPECT_EQ(c->open_blocks(), 0u);
      EXPECT_EQ(c->bad_frees(), 0);
    }
  }
}
