// Stipple drawings (include/gpugeom/cvd.hpp): the darkness map and the dot sizes around one
// centroidal Voronoi iteration. Shared by the CLI's `stipple` and the Python package.
#include <algorithm>
#include <cmath>
#include <string>

#include "exec/grid_input.hpp"
#include "gpugeom/cvd.hpp"

namespace gpugeom {

namespace {
std::int64_t count_of(const GridView& g) {
  std::int64_t c = 1;
  for (auto e : g.shape) c *= e;
  return c;
}
}  // namespace

HostVector<double> stipple_darkness(const GridView& image, bool invert, double contrast,
                                    double gamma) {
  if (image.shape.size() != 2)
    throw Error(ErrorCode::InvalidArgument, "stipple takes a 2D image (rows, cols); this one has " +
                                                std::to_string(image.shape.size()) + " axes");
  if (!(contrast > 0) || !(gamma > 0) || !std::isfinite(contrast) || !std::isfinite(gamma))
    throw Error(ErrorCode::InvalidArgument, "stipple: contrast and gamma must be finite and > 0");
  for (auto e : image.shape)
    if (e < 1) throw Error(ErrorCode::InvalidInput, "stipple: the image is empty");
  if (!image.data) throw Error(ErrorCode::InvalidArgument, "stipple: the image has no data");
  const std::int64_t n = count_of(image);
  HostVector<double> d(static_cast<std::size_t>(n));
  grid_input::visit(image.type, [&](auto zero) {
    using T = decltype(zero);
    const T* v = static_cast<const T*>(image.data);
    double range = 1;
    if (image.type == io::ScalarType::U8)
      range = 255;
    else if (image.type == io::ScalarType::U16)
      range = 65535;
    else if (image.type != io::ScalarType::Bool) {
#pragma omp parallel for reduction(max : range)
      for (std::int64_t i = 0; i < n; ++i) range = std::max(range, double(v[i]));
    }
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      const double x = std::clamp(double(v[i]) / range, 0.0, 1.0);  // NaN stays NaN
      double k = invert ? x : 1 - x;
      k = std::clamp((k - 0.5) * contrast + 0.5, 0.0, 1.0);
      d[std::size_t(i)] = std::pow(k, gamma);
    }
  });
  return d;
}

Stipple stipple(const GridView& image, const StippleOptions& opt) {
  if (!(opt.ink > 0) || !std::isfinite(opt.ink))
    throw Error(ErrorCode::InvalidArgument, "stipple: ink must be finite and > 0");
  HostVector<double> dark = stipple_darkness(image, opt.invert, opt.contrast, opt.gamma);
  GridView dv{dark.data(), io::ScalarType::F64, image.shape};
  Stipple s;
  s.rows = image.shape[0];
  s.cols = image.shape[1];
  s.cvd = centroidal_voronoi(dv, static_cast<const CvdOptions&>(opt));
  s.radius.resize(std::size_t(s.cvd.num_sites));
  const double* mass = s.cvd.mass.data();
  if (s.cvd.mass.empty() && opt.into.mass) mass = opt.into.mass.data;
  for (std::int64_t i = 0; i < s.cvd.num_sites; ++i)
    s.radius[std::size_t(i)] = std::sqrt(opt.ink * mass[i] / M_PI);
  return s;
}

}  // namespace gpugeom
