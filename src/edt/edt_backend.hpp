// What the public EDT entry hands to a backend, and what it gets back (internal).
#pragma once
#include <cstdint>
#include <vector>

#include "edt/edt_common.hpp"
#include "gpugeom/edt.hpp"

namespace gpugeom::edt {

struct Request {
  Layout layout;
  Metric metric;
  EdtMethod method = EdtMethod::Pba;
  Tuning tune;
  RunOptions run;
  // Sites: a mask with one byte per voxel (nonzero = site), or a list of packed sites.
  const std::uint8_t* mask = nullptr;
  std::vector<std::uint32_t> sites;
  std::int64_t site_count = 0;  // sites in the mask or the list (chooses the windowed passes)
  // Slice-by-slice: the z values to compute (3D only); empty = the whole volume.
  std::vector<std::int64_t> slices;
  bool want_sqdist = false, want_features = false, want_labels = false;
  int want_distance = 0;  // 0 none, 32 float32, 64 float64
};

struct Output {
  std::vector<std::int64_t> sqdist_int;  // isotropic
  std::vector<double> sqdist_real;       // anisotropic
  std::vector<float> dist32;
  std::vector<double> dist64;
  std::vector<std::int32_t> features;  // nd arrays of voxel count, C axis order
  std::vector<std::int32_t> labels;
  double transform_ms = 0;       // device-resident feature transform only
  double device_outputs_at = 0;  // clock when the distance / label arrays were on the device
};

// The packing of a C-order shape (2D/3D); throws Error(InvalidInput) for shapes the transform
// cannot hold (sliced: only one z slice must fit int32 indexing).
Layout make_layout(const std::vector<std::int64_t>& shape, bool sliced = false);

namespace cpu_impl {
void run(const Request& req, Output& out, Stats& stats);
}
namespace cuda_impl {
void run(const Request& req, Output& out, Stats& stats);
}

}  // namespace gpugeom::edt
