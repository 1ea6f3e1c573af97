// Near-degenerate and degenerate inputs for the predicate tests: points a few ulps off a line,
// circle, plane or sphere, at tiny and huge scales, and exactly degenerate integer configurations.
#pragma once
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace gg_test {

// k-point tuples of dim D (plus an optional 4th coordinate), flattened: tuple t, point j,
// coordinate c at [(t * k + j) * stride + c].
struct Tuples {
  int k, stride;
  std::vector<double> v;
  std::size_t size() const { return v.size() / (k * stride); }
  const double* at(std::size_t t, int j) const { return v.data() + (t * k + j) * stride; }
};

inline double wiggle(std::mt19937_64& g, double x) {
  int steps = int(g() % 7) - 3;
  for (; steps > 0; --steps) x = std::nextafter(x, INFINITY);
  for (; steps < 0; ++steps) x = std::nextafter(x, -INFINITY);
  return x;
}

// Kinds: 0 nearly degenerate (on the manifold, then a few ulps off), 1 exactly degenerate on an
// integer grid, 2 random. Scale multiplies everything (exact powers of two keep degeneracy).
inline Tuples make_tuples(int dim, int k, int count, std::uint64_t seed, double scale,
                          bool lifted_sphere, int stride = 0) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  Tuples t{k, stride ? stride : dim, {}};
  t.v.resize(std::size_t(count) * k * t.stride);
  for (int c = 0; c < count; ++c) {
    const int kind = c % 3;
    double base[3] = {U(g), U(g), U(g)}, e1[3] = {U(g), U(g), U(g)}, e2[3] = {U(g), U(g), U(g)};
    for (int j = 0; j < k; ++j) {
      double* p = t.v.data() + (std::size_t(c) * k + j) * t.stride;
      double q[4] = {0, 0, 0, 0};
      if (kind == 2) {
        for (int d = 0; d < t.stride; ++d) q[d] = U(g);
      } else if (kind == 1) {
        // integer points on a small lattice line/plane or a circle/sphere of radius 5
        static const int circ[12][2] = {{5, 0},  {4, 3},   {3, 4},   {0, 5},  {-3, 4}, {-4, 3},
                                        {-5, 0}, {-4, -3}, {-3, -4}, {0, -5}, {3, -4}, {4, -3}};
        static const int sph[10][3] = {{5, 0, 0}, {0, 5, 0},   {0, 0, 5},  {3, 4, 0},  {0, 3, 4},
                                       {4, 0, 3}, {-3, -4, 0}, {0, -4, 3}, {-5, 0, 0}, {4, 0, -3}};
        if (lifted_sphere && dim == 2) {
          const int* s = circ[(j * 5 + c) % 12];
          q[0] = s[0], q[1] = s[1];
        } else if (lifted_sphere && dim == 3) {
          const int* s = sph[(j * 3 + c) % 10];
          q[0] = s[0], q[1] = s[1], q[2] = s[2];
        } else {
          const double s = double(int(g() % 9) - 4), u = double(int(g() % 9) - 4);
          for (int d = 0; d < dim; ++d)
            q[d] = std::floor(base[d] * 8) + s * std::floor(e1[d] * 4) +
                   (dim == 3 ? u * std::floor(e2[d] * 4) : 0);
        }
        if (t.stride == 4) q[3] = double(int(g() % 5));
      } else {
        const double s = U(g), u = U(g);
        if (lifted_sphere) {
          // on the unit circle/sphere around base
          double dir[3] = {U(g), U(g), dim == 3 ? U(g) : 0.0};
          double l = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
          for (int d = 0; d < dim; ++d) q[d] = wiggle(g, base[d] + dir[d] / l);
        } else {
          for (int d = 0; d < dim; ++d)
            q[d] = wiggle(g, base[d] + s * e1[d] + (dim == 3 ? u * e2[d] : 0.0));
        }
        if (t.stride == 4)
          q[3] = wiggle(g, q[0] + 2 * q[1] - q[2] + 0.5);  // nearly affine w: near-degenerate
      }
      for (int d = 0; d < t.stride; ++d) p[d] = q[d] * (d < dim ? scale : scale);
    }
  }
  return t;
}

}  // namespace gg_test
