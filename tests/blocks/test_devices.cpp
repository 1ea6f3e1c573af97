// delaunay{2,3}d_devices on the CPU executor (every entry a block): a single call's arrays.
#include "devices_cases.hpp"

namespace gg_devices {
namespace {

Triangulation3d single3(const double* p, std::int64_t n, const Delaunay3dOptions& o) {
  return delaunay3d(p, n, o);
}
Triangulation3d blocks3(const double* p, std::int64_t n, const std::vector<int>& d,
                        const Delaunay3dOptions& o) {
  return delaunay3d_devices(p, n, d, o);
}
Triangulation2d single2(const double* p, std::int64_t n, const Delaunay2dOptions& o) {
  return delaunay2d(p, n, o);
}
Triangulation2d blocks2(const double* p, std::int64_t n, const std::vector<int>& d,
                        const Delaunay2dOptions& o) {
  return delaunay2d_devices(p, n, d, o);
}

// The points in 4 blocks on the CPU executor, checked against the single call; the blocks' result.
template <class Pts, class Opt, class Single, class Blocks>
auto in_four_blocks(const Pts& pts, Opt opt, Single single, Blocks blocks,
                    const std::string& what) {
  opt.backend = Backend::Cpu;
  const double* p = &pts[0].x;
  const std::int64_t n = std::int64_t(pts.size());
  auto got = blocks(p, n, std::vector<int>{0, 0, 0, 0}, opt);
  expect_same(got, single(p, n, opt), what);
  return got;
}

// The code of the error f throws (Internal where it throws none).
template <class F>
ErrorCode code_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  return ErrorCode::Internal;
}

TEST(DelaunayDevices, Blocks3dEqualOneCall) {
  const auto second =
      check_all<Point3, Delaunay3dOptions>(inputs3d(6000), Backend::Cpu, 0, single3, blocks3);
  RecordProperty("second_rounds", int(second));
}

TEST(DelaunayDevices, Blocks2dEqualOneCall) {
  const auto second =
      check_all<Point2, Delaunay2dOptions>(inputs2d(20000), Backend::Cpu, 0, single2, blocks2);
  RecordProperty("second_rounds", int(second));
}

// A Gaussian's tail leaves empty space round the points, and the balls that span it end on
// points a ghost layer does not hold: without the bins beside empty space every block took a
// second round; with them none does, and the arrays are still the single call's.
TEST(DelaunayDevices, BeyondEmptySpaceInOneRound) {
  auto check = [](const auto& pts, auto opt, auto single, auto blocks, const std::string& what) {
    EXPECT_EQ(in_four_blocks(pts, opt, single, blocks, what).stats.blocks_second_round, 0) << what;
  };
  check(generate3d("gaussian", 100000, 5), Delaunay3dOptions{}, single3, blocks3,
        "3D gaussian in 4 blocks");
  check(generate2d("gaussian", 200000, 5), Delaunay2dOptions{}, single2, blocks2,
        "2D gaussian in 4 blocks");
}

// Points on a circle or a sphere, or on a shell thinner than a sample's spacing, lie on a convex
// surface: they go to the single call on the first device (every block would hold most of them),
// and the arrays are the single call's. A shell thick enough to hold points inside its hull is
// split; so is a ball. A sample with a NaN is refused as the single call refuses it.
TEST(DelaunayDevices, ConvexSurfaceInOneBlock) {
  auto blocks_of = [](const auto& pts, auto opt, auto single, auto blocks,
                      const std::string& what) {
    return in_four_blocks(pts, opt, single, blocks, what).stats.blocks;
  };
  EXPECT_EQ(blocks_of(generate3d("sphere", 20000, 5), Delaunay3dOptions{}, single3, blocks3,
                      "3D sphere in 4 blocks"),
            1);
  EXPECT_EQ(blocks_of(generate2d("circle", 50000, 5), Delaunay2dOptions{}, single2, blocks2,
                      "2D circle in 4 blocks"),
            1);
  // (radii 0.45 to 0.4501: most of the points are inside the hull, few of the sample's are)
  EXPECT_EQ(blocks_of(generate3d("thin_sphere", 20000, 5), Delaunay3dOptions{}, single3, blocks3,
                      "3D thin shell in 4 blocks"),
            1);
  std::vector<Point3> shell = generate3d("sphere", 20000, 6);
  for (std::size_t i = 0; i < shell.size(); ++i) {
    // (radii 0.7 to 1 of the sphere's 0.45 round (0.5, 0.5, 0.5))
    const double r = 0.7 + 0.3 * double(i % 97) / 97.0;
    shell[i] = {0.5 + (shell[i].x - 0.5) * r, 0.5 + (shell[i].y - 0.5) * r,
                0.5 + (shell[i].z - 0.5) * r};
  }
  EXPECT_EQ(blocks_of(shell, Delaunay3dOptions{}, single3, blocks3, "3D thick shell in 4 blocks"),
            4);
  EXPECT_EQ(blocks_of(generate3d("ball", 20000, 5), Delaunay3dOptions{}, single3, blocks3,
                      "3D ball in 4 blocks"),
            4);
  // (every sample point on the sphere but one NaN: the single call's error, not the sample's)
  auto bad = generate3d("sphere", 20000, 5);
  bad[0].x = std::nan("");
  Delaunay3dOptions o;
  o.backend = Backend::Cpu;
  const std::int64_t n = std::int64_t(bad.size());
  const ErrorCode want = code_of([&] { delaunay3d(&bad[0].x, n, o); });
  EXPECT_NE(want, ErrorCode::Internal);
  EXPECT_EQ(code_of([&] { delaunay3d_devices(&bad[0].x, n, {0, 0, 0, 0}, o); }), want);
}

// Bad input is refused before any block runs, with the single call's errors where it has them.
TEST(DelaunayDevices, BadInputIsRefused) {
  auto pts = generate3d("uniform", 500, 3);
  Delaunay3dOptions o;
  o.backend = Backend::Cpu;
  const double* p = &pts[0].x;
  const std::int64_t n = std::int64_t(pts.size());
  EXPECT_EQ(code_of([&] { delaunay3d_devices(p, n, {0, -1}, o); }), ErrorCode::InvalidArgument);
  Delaunay3dOptions dig = o;
  dig.method = Method::Digital;
  EXPECT_EQ(code_of([&] { delaunay3d_devices(p, n, {0, 0}, dig); }), ErrorCode::InvalidArgument);
  Delaunay3dOptions neg = o;
  neg.threads = -2;
  EXPECT_EQ(code_of([&] { delaunay3d_devices(p, n, {0, 0}, neg); }), ErrorCode::InvalidArgument);
  auto bad = pts;
  bad[17].y = std::nan("");
  const ErrorCode nan_code = code_of([&] { delaunay3d(&bad[0].x, n, o); });
  EXPECT_NE(nan_code, ErrorCode::Internal);
  EXPECT_EQ(code_of([&] { delaunay3d_devices(&bad[0].x, n, {0, 0}, o); }), nan_code);
  std::vector<Point2> few{{0, 0}, {1, 0}};
  Delaunay2dOptions o2;
  o2.backend = Backend::Cpu;
  EXPECT_EQ(code_of([&] {
              delaunay2d_devices(&few[0].x, 2, {0, 0}, o2);
            }),
            code_of([&] { delaunay2d(&few[0].x, 2, o2); }));
}

}  // namespace
}  // namespace gg_devices
