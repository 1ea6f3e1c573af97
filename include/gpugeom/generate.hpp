/// @file
/// Seeded point generators for the thesis' distributions (chapter 2.3) and the pathological
/// ones. Output depends only on (distribution, n, seed), not on the number of threads.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"

namespace gpugeom {

/// 2D: uniform (unit square), gaussian (sigma 1), thin_circle (annulus of radii 0.45..0.4501
/// around (0.5, 0.5)), circle (on the circle of radius 0.45, rounded to doubles, so nearly but
/// not exactly cocircular), grid (distinct points of an integer grid, exactly degenerate),
/// two_segments (on two disjoint segments).
std::vector<Point2> generate2d(const std::string& distribution, std::int64_t n,
                               std::uint64_t seed = 1);
/// 3D: uniform (unit cube), ball, gaussian, thin_sphere (shell of radii 0.45..0.4501), sphere
/// (on the sphere, rounded), grid (distinct integer grid points), thin_box (between two cubes of
/// half-widths 0.45 and 0.4501), two_lines (on two skew segments).
std::vector<Point3> generate3d(const std::string& distribution, std::int64_t n,
                               std::uint64_t seed = 1);

/// The names generate2d takes.
const std::vector<std::string>& distributions2d();
/// The names generate3d takes.
const std::vector<std::string>& distributions3d();

}  // namespace gpugeom
