// The digital Voronoi diagram of a point set on an executor, in 2D or 3D (thesis 4.2: Phase 1a
// of the digital methods), shared by the digital 2D and 3D Delaunay methods. Included inside an
// executor's namespace with Exec and edt_impl defined.
//
// Each point goes to the grid cell holding it; the lowest-indexed point of a cell is its site
// (atomic minimum), the others are "missing". The feature transform (PBA) then gives every cell
// its nearest site's point (ties: the site first in raster order). Every step depends only on
// the points and the frame, so every executor gives the same arrays.

namespace point_voronoi_impl {

// A grid of n[0] x n[1] (x n[2]) cells of side h from the origin o; cell index x + n0 (y + n1 z).
struct CellFrame {
  int nd = 2;
  std::int64_t n[3] = {1, 1, 1};
  double o[3] = {0, 0, 0};
  double h = 1;
  std::int64_t count() const { return n[0] * n[1] * n[2]; }
  // The cell of point p (coordinates nd apart), clamped to the grid. (A subtraction and a
  // division, which no compiler fuses: the same cell on every executor.)
  GG_INLINE std::int64_t cell_of(const double* p) const {
    std::int64_t c = 0, stride = 1;
    for (int a = 0; a < nd; ++a) {
      std::int64_t k = std::int64_t(floor((p[a] - o[a]) / h));
      k = k < 0 ? 0 : (k > n[a] - 1 ? n[a] - 1 : k);
      c += k * stride;
      stride *= n[a];
    }
    return c;
  }
};

}  // namespace point_voronoi_impl

struct PointVoronoi {
  typename Exec::template Buffer<std::int32_t> cell;     // per point: its cell
  typename Exec::template Buffer<std::int32_t> colour;   // per cell: the nearest site's point
  typename Exec::template Buffer<std::int32_t> missing;  // points that are no site, ascending
  std::int64_t nmiss = 0, nsites = 0;
};

// Maps the n points P (nd coordinates each, executor memory) to F's cells and finds the sites.
// On return colour holds each site's point at its cell and INT32_MAX elsewhere.
inline PointVoronoi map_point_sites(Exec& ex, const double* P, std::int64_t n,
                                    const point_voronoi_impl::CellFrame& F) {
  PointVoronoi V;
  const std::int64_t nc = F.count();
  V.cell = ex.template alloc<std::int32_t>(std::size_t(n));
  V.colour = ex.template alloc<std::int32_t>(std::size_t(nc));
  std::int32_t* cell = V.cell.data();
  std::int32_t* colour = V.colour.data();
  ex.fill(colour, nc, std::numeric_limits<std::int32_t>::max());
  const int nd = F.nd;
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        const std::int64_t c = F.cell_of(P + nd * i);
        cell[i] = std::int32_t(c);
        atomic_min(&colour[c], std::int32_t(i));
      });
  V.missing = ex.template alloc<std::int32_t>(std::size_t(n));
  V.nmiss = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return colour[cell[i]] != std::int32_t(i); },
      V.missing.data());
  V.nsites = n - V.nmiss;
  return V;
}

// The layout the feature transform runs on for frame F (bit-field packing).
inline edt::Layout point_voronoi_layout(const point_voronoi_impl::CellFrame& F) {
  return F.nd == 2 ? edt::make_layout({F.n[1], F.n[0]}, false, edt::Packing::Bits)
                   : edt::make_layout({F.n[2], F.n[1], F.n[0]}, false, edt::Packing::Bits);
}

// The diagram: every cell takes its nearest site's point (V from map_point_sites).
inline void colour_cells(Exec& ex, std::int64_t n, const point_voronoi_impl::CellFrame& F,
                         PointVoronoi& V) {
  const edt::Layout L = point_voronoi_layout(F);
  const std::int64_t nc = F.count();
  std::int32_t* colour = V.colour.data();
  const std::int32_t* cell = V.cell.data();
  auto feat = ex.template alloc<std::uint32_t>(std::size_t(nc));
  std::uint32_t* Fe = feat.data();
  ex.fill(Fe, nc, edt::kNone);
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        const std::int64_t c = cell[i];
        if (colour[c] == std::int32_t(i)) Fe[c] = L.pack_voxel(c);
      });
  edt_impl::feature_transform_held(ex, L, edt::Metric{}, Fe, V.nsites);
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t c) {
        const std::int64_t site = L.voxel_of(Fe[c]);
        if (site != c) colour[c] = colour[site];
      });
}
