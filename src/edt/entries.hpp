// What the module's public entries in edt.cpp lend the others (devices.cpp), internal.
#pragma once
#include <cstdint>
#include <vector>

#include "gpugeom/edt.hpp"

namespace gpugeom::edt {

// The outputs `opt` asks for on a grid of `shape`, checked as the entries check them (sampling,
// distance bits, the caller's arrays: asked for and of the grid's size; Error(InvalidArgument)
// otherwise), for any size of grid; returns whether the metric is isotropic (squared distances
// then int64, into.sqdist_int; else float64, into.sqdist_real).
bool checked_outputs(const std::vector<std::int64_t>& shape, const EdtOptions& opt);

}  // namespace gpugeom::edt
