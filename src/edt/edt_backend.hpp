// What the public EDT entry hands to a backend, and what it gets back (internal).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "edt/edt_common.hpp"
#include "edt/nd_layout.hpp"
#include "exec/dispatch.hpp"
#include "exec/tuning.hpp"
#include "gpugeom/edt.hpp"

namespace gpugeom::edt {

struct Request {
  Layout layout;
  Metric metric;
  // Grids of 4 to 8 axes (nd.nd != 0) take these instead of layout and metric, and a site list
  // as raster indices (nd_sites).
  NdShape nd;
  NdMetric nd_metric;
  std::vector<std::uint64_t> nd_sites;
  EdtMethod method = EdtMethod::Pba;
  Tuning tune;
  RunOptions run;
  // Sites: a grid whose values say which voxels are sites (rule), where the executor can read
  // it (grid_on_device) or on the host, or else a list: packed sites for a whole grid, column
  // keys (column_key) in slice-by-slice mode.
  const void* grid = nullptr;
  io::ScalarType type = io::ScalarType::U8;
  SiteRule rule = SiteRule::NonZero;
  bool grid_on_device = false;
  std::vector<std::uint32_t> sites;
  std::vector<std::uint64_t> column_sites;
  std::int64_t site_count = 0;  // sites in the list (a grid's are counted by the executor)
  // Slice-by-slice: the z values to compute (3D only); empty = the whole volume.
  std::vector<std::int64_t> slices;
  // A grid on the executor that is a slab of the layout (EdtOptions::slab): it holds the
  // slab_planes planes from slab_first; column_sites then holds the slab's bounds as column keys,
  // listed with the grid's sites.
  std::int64_t slab_first = 0, slab_planes = 0;
  bool want_sqdist = false, want_features = false, want_labels = false;
  int want_distance = 0;  // 0 none, 32 float32, 64 float64
  // Outputs: into the caller's arrays where given, else the library's; device_out leaves them
  // on the executor (Output's shared pointers), else they come to the host arrays.
  EdtBuffers into;
  bool device_out = false;
};

struct Output {
  HostVector<std::int64_t> sqdist_int;  // isotropic
  HostVector<double> sqdist_real;       // anisotropic
  HostVector<float> dist32;
  HostVector<double> dist64;
  HostVector<std::int32_t> features;  // nd arrays of voxel count, C axis order
  HostVector<std::int32_t> labels;
  // device_out: the library's arrays on the executor (null where the caller's were used).
  std::shared_ptr<std::int64_t> dev_sqdist_int;
  std::shared_ptr<double> dev_sqdist_real;
  std::shared_ptr<float> dev_dist32;
  std::shared_ptr<double> dev_dist64;
  std::shared_ptr<std::int32_t> dev_features;
  std::shared_ptr<std::int32_t> dev_labels;
  double transform_ms = 0;       // device-resident feature transform only
  double device_outputs_at = 0;  // clock when the distance / label arrays were on the device
};

// The packing of a C-order shape (2D/3D); throws Error(InvalidInput) for shapes the transform
// cannot hold (sliced: only one z slice must fit int32 indexing). Packing::Bits: bit fields
// only (modules that decode the sites themselves, cvd/); Any: raster indices where the bit
// fields need more than 32 bits.
// tuning.edt may ask for raster indices (Any only) or column packing (sliced only) where the
// rule would not take them; the passes give identical results on every packing.
enum class Packing { Any, Bits };
Layout make_layout(const std::vector<std::int64_t>& shape, bool sliced = false,
                   Packing packing = Packing::Any,
                   const detail::Tuning& tuning = detail::kDefaultTuning);

// Every column's first and last site of a grid in the executor's memory (column_site_bounds_
// device), to host arrays of `plane` each; true where the grid holds a NaN.
struct BoundsRequest {
  RunOptions run;
  const void* grid = nullptr;
  io::ScalarType type = io::ScalarType::U8;
  SiteRule rule = SiteRule::NonZero;
  std::int64_t planes = 0, plane = 0, offset = 0;
};

// The banded pass's bands along axis a (0..2) into its field.
inline void set_bands(EdtStats& s, int a, std::int64_t bands) {
  (a == 0 ? s.bands_x : a == 1 ? s.bands_y : s.bands_z) = bands;
}

// One executor's entries (exec/dispatch.hpp): impl/entry.inl defines them for each executor.
struct Entries {
  void (*run)(const Request& req, Output& out, EdtStats& stats);
  // True where the grid holds a NaN.
  bool (*column_bounds)(const BoundsRequest& rq, std::int64_t* first, std::int64_t* last);
};
GG_DECLARE_TABLE(Entries, entries)

}  // namespace gpugeom::edt
