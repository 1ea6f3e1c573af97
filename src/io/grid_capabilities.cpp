// The grid capabilities' overloads for grids read from files (io::Grid): here in gpugeom_io,
// so that the core needs nothing of the readers; each is the GridView entry on a view.
#include "gpugeom/cvd.hpp"
#include "gpugeom/edt.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom {

EdtResult distance_transform(const io::Grid& g, SiteRule rule, const EdtOptions& opt) {
  return distance_transform(io::view_of(g), rule, opt);
}

CvdResult centroidal_voronoi(const io::Grid& g, const CvdOptions& opt) {
  return centroidal_voronoi(io::view_of(g), opt);
}

}  // namespace gpugeom
