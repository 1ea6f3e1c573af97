// Counter-based generators: point i draws from hash(seed, i, k), so any thread can make any
// point and the result is the same for every thread count.
#include "gpugeom/generate.hpp"

#include <cmath>
#include <limits>
#include <numeric>

namespace gpugeom {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kR1 = 0.45, kR2 = 0.4501;

std::uint64_t mix(std::uint64_t z) {  // splitmix64 finaliser
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

struct Rng {
  std::uint64_t seed, i;
  int k = 0;
  // Uniform in [0, 1) with 53 random bits.
  double u() {
    return double(mix(mix(seed ^ (i * 0x632be59bd9b4e019ull)) + std::uint64_t(k++)) >> 11) *
           0x1p-53;
  }
  double gauss() {
    double a = u(), b = u();
    return std::sqrt(-2.0 * std::log(1.0 - a)) * std::cos(2 * kPi * b);
  }
};

void check_n(std::int64_t n) {
  if (n < 0 || n > std::int64_t(std::numeric_limits<std::int32_t>::max()))
    throw Error(ErrorCode::InvalidArgument,
                "point count " + std::to_string(n) + " is out of range [0, 2147483647]");
}

// Distinct grid cells: i -> (a*i + c) mod cells is a bijection when gcd(a, cells) = 1.
struct GridPick {
  std::uint64_t side, cells, a, c;
  GridPick(std::int64_t n, int dim, std::uint64_t seed) {
    side = std::uint64_t(std::ceil(std::pow(double(std::max<std::int64_t>(n, 1)), 1.0 / dim)));
    while (std::pow(double(side), dim) < double(n)) ++side;
    cells = 1;
    for (int d = 0; d < dim; ++d) cells *= side;
    a = (mix(seed) % cells) | 1;
    while (std::gcd(a, cells) != 1) a += 2;
    c = mix(seed + 1) % cells;
  }
  std::uint64_t cell(std::uint64_t i) const {
    return std::uint64_t((unsigned __int128)(a)*i % cells + c) % cells;
  }
};

// Index of d in names; an unknown name is an error listing the known ones.
int find_distribution(const std::string& d, const std::vector<std::string>& names) {
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == d) return int(k);
  std::string all;
  for (auto& s : names) all += (all.empty() ? "" : ", ") + s;
  throw Error(ErrorCode::InvalidArgument, "unknown distribution '" + d + "': expected " + all);
}

// n points of distribution d (one of names; the grid's is number grid_which) in `dim`
// dimensions: point(which, i, rng, grid) makes point i, on all host threads.
template <class P, class F>
std::vector<P> generate(const std::string& d, std::int64_t n, std::uint64_t seed,
                        const std::vector<std::string>& names, int dim, int grid_which, F point) {
  check_n(n);
  const int which = find_distribution(d, names);
  std::vector<P> p(static_cast<std::size_t>(n));
  const GridPick grid(which == grid_which ? n : 1, dim, seed);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    Rng r{seed, std::uint64_t(i)};
    p[std::size_t(i)] = point(which, i, r, grid);
  }
  return p;
}

}  // namespace

const std::vector<std::string>& distributions2d() {
  static const std::vector<std::string> v{"uniform", "gaussian", "thin_circle",
                                          "circle",  "grid",     "two_segments"};
  return v;
}
const std::vector<std::string>& distributions3d() {
  static const std::vector<std::string> v{"uniform", "ball", "gaussian", "thin_sphere",
                                          "sphere",  "grid", "thin_box", "two_lines"};
  return v;
}

std::vector<Point2> generate2d(const std::string& d, std::int64_t n, std::uint64_t seed) {
  return generate<Point2>(
      d, n, seed, distributions2d(), 2, 4,
      [](int which, std::int64_t i, Rng& r, const GridPick& grid) -> Point2 {
        switch (which) {
          case 0:
            return {r.u(), r.u()};
          case 1:
            return {r.gauss(), r.gauss()};
          case 2:
          case 3: {
            double t = 2 * kPi * r.u();
            // Uniform in the annulus: radius with density proportional to r.
            double rad = which == 3 ? kR1 : std::sqrt(kR1 * kR1 + r.u() * (kR2 * kR2 - kR1 * kR1));
            return {0.5 + rad * std::cos(t), 0.5 + rad * std::sin(t)};
          }
          case 4: {
            std::uint64_t c = grid.cell(std::uint64_t(i));
            return {double(c % grid.side), double(c / grid.side)};
          }
          default: {
            double t = r.u();
            return (i & 1) ? Point2{t, 0.0} : Point2{0.5 + 0.25 * t, 0.5 + 0.5 * t};
          }
        }
      });
}

std::vector<Point3> generate3d(const std::string& d, std::int64_t n, std::uint64_t seed) {
  return generate<Point3>(
      d, n, seed, distributions3d(), 3, 5,
      [](int which, std::int64_t i, Rng& r, const GridPick& grid) -> Point3 {
        auto direction = [&r]() {
          double x, y, z, l;
          do {
            x = r.gauss(), y = r.gauss(), z = r.gauss();
            l = std::sqrt(x * x + y * y + z * z);
          } while (l == 0.0);
          return Point3{x / l, y / l, z / l};
        };
        switch (which) {
          case 0:
            return {r.u(), r.u(), r.u()};
          case 1:
          case 3:
          case 4: {
            Point3 v = direction();
            double rad =
                which == 4 ? kR1
                : which == 1
                    ? kR1 * std::cbrt(r.u())
                    : std::cbrt(kR1 * kR1 * kR1 + r.u() * (kR2 * kR2 * kR2 - kR1 * kR1 * kR1));
            return {0.5 + rad * v.x, 0.5 + rad * v.y, 0.5 + rad * v.z};
          }
          case 2:
            return {r.gauss(), r.gauss(), r.gauss()};
          case 5: {
            std::uint64_t c = grid.cell(std::uint64_t(i));
            return {double(c % grid.side), double(c / grid.side % grid.side),
                    double(c / grid.side / grid.side)};
          }
          case 6: {
            // Between two concentric cubes: pick a face, a point on it, a depth in the shell.
            double s = kR1 + r.u() * (kR2 - kR1);
            int face = int(r.u() * 6) % 6;
            double a = (2 * r.u() - 1) * s, b = (2 * r.u() - 1) * s;
            double f = (face & 1) ? s : -s;
            Point3 v = face < 2 ? Point3{f, a, b} : face < 4 ? Point3{a, f, b} : Point3{a, b, f};
            return {0.5 + v.x, 0.5 + v.y, 0.5 + v.z};
          }
          default: {
            double t = r.u();
            return (i & 1) ? Point3{t, 0.0, 0.0} : Point3{0.5, t, 1.0};
          }
        }
      });
}

}  // namespace gpugeom
