#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>

#include "gpugeom/generate.hpp"

using namespace gpugeom;

TEST(Generate, DeterministicAndSeeded) {
  for (auto& d : distributions3d()) {
    auto a = generate3d(d, 5000, 42), b = generate3d(d, 5000, 42), c = generate3d(d, 5000, 43);
    ASSERT_EQ(a.size(), 5000u);
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(Point3))) << d;
    EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(Point3))) << d;
    for (auto& p : a)
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << d;
  }
  for (auto& d : distributions2d()) {
    auto a = generate2d(d, 5000, 42), b = generate2d(d, 5000, 42);
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(Point2))) << d;
  }
}

TEST(Generate, ShapesOfDistributions) {
  for (auto& p : generate3d("ball", 20000, 1)) {
    double r =
        std::sqrt((p.x - .5) * (p.x - .5) + (p.y - .5) * (p.y - .5) + (p.z - .5) * (p.z - .5));
    ASSERT_LE(r, 0.45 * (1 + 1e-12));
  }
  for (auto& p : generate3d("thin_sphere", 20000, 1)) {
    double r =
        std::sqrt((p.x - .5) * (p.x - .5) + (p.y - .5) * (p.y - .5) + (p.z - .5) * (p.z - .5));
    ASSERT_GE(r, 0.45 * (1 - 1e-12));
    ASSERT_LE(r, 0.4501 * (1 + 1e-12));
  }
  for (auto& p : generate2d("circle", 20000, 1))
    ASSERT_NEAR(std::hypot(p.x - .5, p.y - .5), 0.45, 1e-15);
  for (auto& p : generate3d("thin_box", 20000, 1)) {
    double m = std::max({std::fabs(p.x - .5), std::fabs(p.y - .5), std::fabs(p.z - .5)});
    ASSERT_GE(m, 0.45 - 1e-12);
    ASSERT_LE(m, 0.4501 + 1e-12);
  }
  auto g = generate3d("grid", 30000, 7);
  std::set<std::tuple<double, double, double>> s;
  for (auto& p : g) {
    ASSERT_EQ(p.x, std::floor(p.x));
    s.insert({p.x, p.y, p.z});
  }
  EXPECT_EQ(s.size(), g.size()) << "grid points must be distinct";
  for (auto& p : generate3d("two_lines", 1000, 1))
    ASSERT_TRUE((p.y == 0 && p.z == 0) || (p.x == 0.5 && p.z == 1));
}

TEST(Generate, BadArguments) {
  EXPECT_THROW(generate3d("cube", 10), Error);
  EXPECT_THROW(generate2d("uniform", -1), Error);
  EXPECT_TRUE(generate2d("uniform", 0).empty());
}
